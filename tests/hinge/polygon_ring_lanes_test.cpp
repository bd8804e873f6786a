// The central difference's ring pass over all rings at once (hinge/polygon_ring_lanes.cpp,
// two rings to an SSE2 vector) against the per-ring pass it replaces: the same evaluation,
// flow update and plastic work to the bit, on distorted, yielding chains — odd and even ring
// counts (the spare lane), the half model and the full ring, the series and atan2 branches of
// the hinge rotation, two successive calls (the work's ½(M_n + M_{n+1}) reads the first).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "hinge/polygon_chain.hpp"

using namespace ringcrush::hinge;

namespace {

PolygonChainInput chain_input(int rings, bool half, int nodes) {
  PolygonChainInput in;
  in.rings = rings;
  in.half_symmetry = half;
  in.nodes_per_ring = nodes;
  in.joint = PolygonJoint::Welded;
  in.impactor_velocity_m_s = 20.0;
  in.redwood_alpha = 2.0;
  in.hardening_modulus_pa = 2.2e9;
  in.yield_cap_ratio = 320.0 / 273.0;
  in.membrane_damping_ratio = 1.0;  // the Kelvin–Voigt dampers implicit, as the driver sets them
  in.hinge_damping_ratio = 1.0;
  return in;
}

// The rest state moved at random: every node by up to 2 % of R, a few by 25 % (hinges beyond
// the series, some past a right angle), velocities, θp up to ±0.05 rad (most hinges above
// their yield moment, 0.008 rad of elastic rotation), ā up to 0.3.
std::vector<double> distorted_state(const PolygonChain& chain, std::mt19937& rng) {
  std::vector<double> y = chain.initial_state();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double R = chain.mean_radius();
  const int n_ind = chain.independent_nodes();
  const bool half = chain.input().half_symmetry;
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < n_ind; ++j) {
      const auto o = chain.node_offset(r, j);
      const double move = (j % 7 == 3) ? 0.25 : 0.02;
      if (!(half && (j == 0 || j == n_ind - 1))) y[o] += move * R * u(rng);
      y[o + 1] += move * R * u(rng);
      y[o + 2] = 5.0 * u(rng);
      y[o + 3] = 5.0 * u(rng);
      if (half && (j == 0 || j == n_ind - 1)) y[o + 2] = 0.0;
      y[o + 4] = 0.05 * u(rng);
      y[o + 5] = 0.15 * (1.0 + u(rng));
    }
  return y;
}

struct Evaluation {
  std::vector<double> y, dydt;
  double work = 0.0, relaxation = 1.0;
};

// Two calls of rhs_with_flow_update (dt = 0, as the driver's first, then dt), the second on
// the first's updated state moved a little.
std::vector<Evaluation> evaluate(bool lanes, const PolygonChainInput& in, const std::vector<double>& y0) {
  PolygonChain chain(in);
  chain.set_implicit_ring_dampers(true);
  chain.set_ring_lanes(lanes);
  std::vector<Evaluation> out;
  Evaluation e{y0, std::vector<double>(y0.size(), 0.0)};
  chain.rhs_with_flow_update(0.0, e.y.data(), 0.0, e.dydt.data(), e.work, e.relaxation);
  out.push_back(e);
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) e.y[chain.node_offset(r, j) + 1] += 1e-5 * (j % 5);
  chain.rhs_with_flow_update(1e-7, e.y.data(), 2e-7, e.dydt.data(), e.work, e.relaxation);
  out.push_back(e);
#ifndef __FMA__  // a build with FMA keeps the per-ring pass (polygon_ring_lanes.cpp)
  EXPECT_EQ(chain.ring_lane_passes(), lanes ? 2 : 0);  // the pass compared is the one taken
#endif
  return out;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

int first_difference(const std::vector<double>& a, const std::vector<double>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(double)) != 0) return static_cast<int>(i);
  return -1;
}

void expect_lanes_equal_rings(int rings, bool half, int nodes, unsigned seed) {
  const PolygonChainInput in = chain_input(rings, half, nodes);
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 3; ++trial) {
    const std::vector<double> y0 = distorted_state(PolygonChain(in), rng);
    const auto ref = evaluate(false, in, y0);
    const auto lanes = evaluate(true, in, y0);
    for (std::size_t c = 0; c < ref.size(); ++c) {
      SCOPED_TRACE(testing::Message() << rings << " rings, half " << half << ", N " << nodes << ", trial "
                                      << trial << ", call " << c);
      EXPECT_TRUE(same_bits(ref[c].dydt, lanes[c].dydt)) << "first row " << first_difference(ref[c].dydt, lanes[c].dydt);
      EXPECT_TRUE(same_bits(ref[c].y, lanes[c].y)) << "first row " << first_difference(ref[c].y, lanes[c].y);
      EXPECT_EQ(std::memcmp(&ref[c].work, &lanes[c].work, sizeof(double)), 0) << ref[c].work << " " << lanes[c].work;
      EXPECT_EQ(ref[c].relaxation, lanes[c].relaxation);
    }
    // The state is one that tests what it should: hinges flowed (θp moved, work done).
    EXPECT_FALSE(same_bits(y0, ref[1].y));
    EXPECT_NE(ref[1].work, 0.0);
  }
}

}  // namespace

TEST(PolygonRingLanes, HalfModelEvenRingsEqualThePerRingPass) { expect_lanes_equal_rings(6, true, 48, 1u); }
TEST(PolygonRingLanes, HalfModelOddRingsUseTheSpareLane) {
  expect_lanes_equal_rings(1, true, 48, 2u);
  expect_lanes_equal_rings(3, true, 16, 3u);
}
TEST(PolygonRingLanes, FullRingsEqualThePerRingPass) {
  expect_lanes_equal_rings(2, false, 48, 4u);
  expect_lanes_equal_rings(5, false, 12, 5u);
}

// The hinges beyond the series take atan2 in both passes: the distorted states have them.
TEST(PolygonRingLanes, DistortedStatesReachTheAtan2Branch) {
  const PolygonChainInput in = chain_input(3, true, 48);
  std::mt19937 rng(7u);
  PolygonChain chain(in);
  const auto y = distorted_state(chain, rng);
  const auto shape = chain.shape(y.data());
  int beyond = 0;
  for (const auto& ring : shape.turning)
    for (const double tau : ring)
      if (std::abs(tau - 2.0 * 3.141592653589793 / 48) > 0.4) ++beyond;
  EXPECT_GT(beyond, 5);
}
