// Level 2 polygon ring (THEORY §4.3) against the closed forms of §1: the elastic diametral
// stiffness (§1.1, verification b, N = 48 and 96) and the quasi-static crush load of
// DeRuntz–Hodge (§1.3, verification a, N = 48 and 96).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "hinge/polygon_simulation.hpp"
#include "hinge/ring_laws.hpp"
#include "polygon_diametral_stiffness.hpp"
#include "quasi_static_ring.hpp"

using namespace ringcrush::hinge;

namespace {

PolygonChainInput test30_ring(int nodes) {
  PolygonChainInput in;  // defaults: the Test 30 ring, plane stress
  in.rings = 1;
  in.nodes_per_ring = nodes;
  return in;
}

const RingSection& section = plates_crush::test30_section;

double polygon_stiffness(int nodes) { return ringcrush::hinge::testing::polygon_diametral_stiffness(test30_ring(nodes)); }

struct QuasiStatic {
  double mean_ratio;  // mean of P / P_DH over δ/d ∈ [0.2, 0.5]
  double min_ratio, max_ratio;
};

// The load is averaged over δ/d ∈ [0.2, 0.5] (quasi_static_ring.hpp), rigid–perfectly-plastic
// hinges.
QuasiStatic quasi_static(int nodes, double rtol) {
  auto in = test30_ring(nodes);
  in.hardening_modulus_pa = 0.0;
  const auto out = plates_crush::crush_between_plates(in, rtol);
  const double d = section.mean_diameter();
  const double M0 = plastic_moment(section, in.yield_stress_pa, SectionState::PlaneStress);
  const double P0 = collapse_load(M0, d);
  const auto b = plates_crush::load_band(out, [&](double delta) { return deruntz_hodge_load(P0, delta, d); });
  EXPECT_GT(b.samples, 100);
  return {b.mean, b.low, b.high};
}

}  // namespace

TEST(PolygonRing, ElasticStiffnessWithinTwoPercentN48) {
  const double k = polygon_stiffness(48);
  const double ref = elastic_stiffness(section, 202e9, 0.3, SectionState::PlaneStress);
  EXPECT_NEAR(k / ref, 1.0, 0.02) << "k = " << k << " N/m, THEORY §1.1 " << ref;
}

TEST(PolygonRing, ElasticStiffnessWithinTwoPercentN96) {
  const double k = polygon_stiffness(96);
  const double ref = elastic_stiffness(section, 202e9, 0.3, SectionState::PlaneStress);
  EXPECT_NEAR(k / ref, 1.0, 0.02) << "k = " << k << " N/m, THEORY §1.1 " << ref;
}

TEST(PolygonRing, QuasiStaticDeRuntzHodgeN48) {
  const auto q = quasi_static(48, 1e-4);
  EXPECT_NEAR(q.mean_ratio, 1.0, 0.03) << "min " << q.min_ratio << " max " << q.max_ratio;
}

TEST(PolygonRing, QuasiStaticDeRuntzHodgeN96) {
  const auto q = quasi_static(96, 1e-4);  // the saw-tooth halves with the node spacing
  EXPECT_NEAR(q.mean_ratio, 1.0, 0.03) << "min " << q.min_ratio << " max " << q.max_ratio;
}
