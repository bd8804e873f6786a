// The contact landing's reach for ring–ring pairs (hinge/polygon_segment_contact.cpp): a pair
// closing within a gap of t is noted, (gap + depth)/ṗ, before it touches — not only once inside
// the segment's t-box, where a ring's bottom node 1.5 t above the next ring's top segment is
// never. Two free rings, the upper one moving down onto the lower at 10 m/s: gaps 0.5 t and
// 0.9 t are noted with that closing time, 1.2 t is beyond the reach; without the landing the
// forces are those of the lists with the t-box (no pair touches either way).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "hinge/polygon_chain.hpp"

using namespace ringcrush::hinge;

namespace {

struct Approach {
  double landing = 0.0;
  std::vector<double> dydt;
};

Approach approach(bool half, double gap_over_t, double depth) {
  PolygonChainInput in;
  in.rings = 2;
  in.half_symmetry = half;
  in.nodes_per_ring = 48;
  in.joint = PolygonJoint::Free;
  // The mean lines 1.5 t apart at the axis is a gap of 0.5 t (gap = distance − t).
  in.pitch_m = in.outer_diameter_m + gap_over_t * in.wall_thickness_m;
  in.impactor_velocity_m_s = 0.0;
  PolygonChain chain(in);
  chain.set_contact_landing(depth, 1.0);
  std::vector<double> y = chain.initial_state();
  for (int j = 0; j < chain.independent_nodes(); ++j) y[chain.node_offset(0, j) + 3] = -10.0;  // ring 0 (upper) down
  Approach out;
  out.dydt.assign(y.size(), 0.0);
  chain.rhs(0.0, y.data(), out.dydt.data());
  out.landing = chain.contact_landing_step();
  return out;
}

}  // namespace

TEST(PolygonLandingReach, ClosingRingPairIsNotedBeforeItTouches) {
  const double t = PolygonChainInput{}.wall_thickness_m, depth = 1e-3 * t;
  for (const bool half : {true, false})
    for (const double gap : {0.5, 0.9}) {
      const auto a = approach(half, gap, depth);
      // The closest points are the rings' axis nodes; the closing speed 10 m/s.
      EXPECT_NEAR(a.landing, (gap * t + depth) / 10.0, 1e-9 * a.landing) << "half " << half << ", gap " << gap << " t";
    }
}

TEST(PolygonLandingReach, PairBeyondAGapOfTIsNotNoted) {
  const double t = PolygonChainInput{}.wall_thickness_m;
  for (const bool half : {true, false})
    EXPECT_EQ(approach(half, 1.2, 1e-3 * t).landing, std::numeric_limits<double>::infinity()) << "half " << half;
}

TEST(PolygonLandingReach, ForcesAreThoseWithoutTheLanding) {
  const double t = PolygonChainInput{}.wall_thickness_m;
  for (const bool half : {true, false}) {
    const auto with = approach(half, 0.5, 1e-3 * t), without = approach(half, 0.5, 0.0);
    EXPECT_EQ(without.landing, std::numeric_limits<double>::infinity());
    ASSERT_EQ(with.dydt.size(), without.dydt.size());
    for (std::size_t i = 0; i < with.dydt.size(); ++i) EXPECT_EQ(with.dydt[i], without.dydt[i]) << "row " << i;
  }
}
