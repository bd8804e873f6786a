// The node–segment contact's broad phase in the central difference's evaluation
// (hinge/polygon_segment_contact.cpp): candidate lists carried over from an earlier state,
// with each listed segment's t-box tested from its end points (SSE2), give the same forces,
// contact rows and landing step, to the bit, as lists built afresh at the state itself — the
// pairs are those of an all-segments search either way. Rings pushed into each other and one
// flattened (its inner walls in contact), moved at random within and beyond the lists' reach.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "hinge/polygon_chain.hpp"

using namespace ringcrush::hinge;

namespace {

PolygonChainInput overlapping_rings(bool half) {
  PolygonChainInput in;
  in.rings = 3;
  in.half_symmetry = half;
  in.nodes_per_ring = 48;
  in.joint = PolygonJoint::Free;
  in.pitch_m = in.outer_diameter_m - 0.6 * in.wall_thickness_m;  // neighbours overlap by 0.6 t
  in.impactor_velocity_m_s = 20.0;
  in.redwood_alpha = 2.0;
  return in;
}

// Ring 1 flattened to 3 % of its height (the inner walls 1.5 mm apart, closer than 2t), the
// others round; velocities at random.
std::vector<double> contact_state(const PolygonChain& chain, std::mt19937& rng) {
  std::vector<double> y = chain.initial_state();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double c1 = 0.5 * (y[chain.node_offset(1, 0) + 1] + y[chain.node_offset(1, chain.independent_nodes() - 1) + 1]);
  const bool half = chain.input().half_symmetry;
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) {
      const auto o = chain.node_offset(r, j);
      if (r == 1) y[o + 1] = c1 + 0.03 * (y[o + 1] - c1);
      const bool axis = half && (j == 0 || j == chain.independent_nodes() - 1);
      y[o + 2] = axis ? 0.0 : 3.0 * u(rng);
      y[o + 3] = 3.0 * u(rng);
    }
  return y;
}

// Every node moved by up to `reach` per coordinate (the axis nodes' x kept at 0).
std::vector<double> moved(const PolygonChain& chain, std::vector<double> y, double reach, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const bool half = chain.input().half_symmetry;
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) {
      const auto o = chain.node_offset(r, j);
      if (!(half && (j == 0 || j == chain.independent_nodes() - 1))) y[o] += reach * u(rng);
      y[o + 1] += reach * u(rng);
    }
  return y;
}

struct Outcome {
  std::vector<double> dydt;
  double landing = 0.0, stable = 0.0;
};

// rhs_with_flow_update (dt = 0) at each state in turn on one chain; the last one's results.
Outcome evaluate(const PolygonChainInput& in, const std::vector<std::vector<double>>& states) {
  PolygonChain chain(in);
  chain.set_implicit_ring_dampers(true);
  chain.set_contact_landing(1e-3 * in.wall_thickness_m, 1e-3);
  Outcome out;
  for (auto y : states) {
    out.dydt.assign(y.size(), 0.0);
    double work = 0.0, relaxation = 1.0;
    chain.rhs_with_flow_update(0.0, y.data(), 0.0, out.dydt.data(), work, relaxation);
  }
  out.landing = chain.contact_landing_step();
  out.stable = chain.stable_step();
  return out;
}

void expect_carried_lists_equal_fresh(bool half, unsigned seed) {
  const PolygonChainInput in = overlapping_rings(half);
  const PolygonChain probe(in);
  std::mt19937 rng(seed);
  const double t = in.wall_thickness_m;
  for (int trial = 0; trial < 4; ++trial) {
    const auto y1 = contact_state(probe, rng);
    // Within the lists' reach (half the margin t per coordinate: no rebuild), then beyond it.
    for (const double reach : {0.45 * t, 2.0 * t}) {
      const auto y2 = moved(probe, y1, reach, rng);
      SCOPED_TRACE(testing::Message() << "half " << half << ", trial " << trial << ", reach " << reach / t << " t");
      const Outcome carried = evaluate(in, {y1, y2});
      const Outcome fresh = evaluate(in, {y2});
      ASSERT_EQ(carried.dydt.size(), fresh.dydt.size());
      EXPECT_EQ(std::memcmp(carried.dydt.data(), fresh.dydt.data(), fresh.dydt.size() * sizeof(double)), 0);
      EXPECT_EQ(carried.landing, fresh.landing);
      EXPECT_EQ(carried.stable, fresh.stable);
      // The state has the contacts it should: ring–ring and inner-wall pairs, some of them
      // penetrating (a recorded evaluation lists them).
      PolygonChain check(in);
      check.energies(0.0, y2.data());
      EXPECT_GT(check.contact_pairs_last(), 10);
      EXPECT_GT(check.max_penetration_last(), 0.1 * t);
    }
  }
}

}  // namespace

TEST(PolygonContactLists, CarriedListsEqualAFreshSearchHalfModel) { expect_carried_lists_equal_fresh(true, 11u); }
TEST(PolygonContactLists, CarriedListsEqualAFreshSearchFullRings) { expect_carried_lists_equal_fresh(false, 12u); }
