// Level 2 polygon ring (THEORY §4.3) against the closed forms of §1: the elastic diametral
// stiffness (§1.1, verification b, N = 48 and 96) and the quasi-static crush load of
// DeRuntz–Hodge (§1.3, verification a, N = 48).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "hinge/polygon_simulation.hpp"
#include "hinge/ring_laws.hpp"
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

// Diametral stiffness of the half model: the top node loaded, the bottom node held; K by
// finite differences of the generalised forces (perturbing away from the plates, which touch
// with zero gap), then K u = f.
double polygon_stiffness(int nodes) {
  PolygonChain chain(test30_ring(nodes));
  const auto y = chain.initial_state();
  const int n = chain.independent_nodes();
  std::vector<std::size_t> dofs;
  for (int j = 0; j < n - 1; ++j) dofs.push_back(chain.node_offset(0, j) + 1);  // y, bottom held
  for (int j = 1; j < n - 1; ++j) dofs.push_back(chain.node_offset(0, j));      // x, off the axis
  const auto m = static_cast<Eigen::Index>(dofs.size());
  Eigen::MatrixXd K(m, m);
  std::vector<double> f0(chain.size()), f1(chain.size());
  chain.generalised_forces(0.0, y.data(), f0.data());
  const double h = -1e-9;
  for (Eigen::Index a = 0; a < m; ++a) {
    auto yy = y;
    yy[dofs[a]] += h;
    chain.generalised_forces(0.0, yy.data(), f1.data());
    for (Eigen::Index b = 0; b < m; ++b) K(b, a) = -(f1[dofs[b] + 2] - f0[dofs[b] + 2]) / h;
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m);
  f(0) = -0.5;  // half of a unit load: the half model carries half of everything on the axis
  const Eigen::VectorXd u = K.partialPivLu().solve(f);
  return 1.0 / -u(0);
}

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
