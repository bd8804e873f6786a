// The wide elementwise kernels (hinge/ring_lanes_wide.hpp): the ring lanes' bar pass
// (bar_lanes, hinge/polygon_bar_lanes.cpp) and the contact nodes' stable-step limits
// (min_node_step_limit, hinge/polygon_node_step_lanes.cpp), 2, 4 and 8 values to a vector,
// against the scalar formulas value by value: to the bit, on runs whose lengths leave every
// tail (8 + 4 + 2, 4 + 2, 2 alone) and for the limits every padding of the last group, with
// the limits' special cases (K ≤ 0, K = 0 with C > 0, ξ past 1e8, the minimum in the padded
// group, a NaN row). The chain's use of both is covered by polygon_ring_lanes_test (the lanes
// against the per-ring pass) and polygon_stable_step_nodes_test (the contact nodes against
// the every-node scan).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "hinge/polygon_bar_lanes.hpp"
#include "hinge/polygon_node_step_lanes.hpp"
#include "hinge/ring_lanes.hpp"

using namespace ringcrush::hinge;

namespace {

#ifndef __FMA__  // a build with FMA runs the pairs only (and may fuse the scalar reference)

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The widths this CPU runs: always 2; 4 and 8 where lanes::wide_lanes_available allows.
std::vector<int> widths() {
  std::vector<int> w{2};
  for (const int x : {4, 8})
    if (lanes::wide_lanes_available() >= x) w.push_back(x);
  return w;
}

struct BarArrays {
  std::vector<double> px, py, ex, ey, gx, gy, n;
};

// Nodes 0 … nodes of `lanes` lanes on a distorted circle of radius ≈ 25 mm, lane by lane a
// different ring; the outputs preset to a sentinel (a bar outside the run must keep it).
BarArrays ring_nodes(int nodes, std::size_t lanes, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto values = static_cast<std::size_t>(nodes + 1) * lanes;
  BarArrays a{std::vector<double>(values), std::vector<double>(values), {}, {}, {}, {}, {}};
  for (int k = 0; k <= nodes; ++k)
    for (std::size_t l = 0; l < lanes; ++l) {
      const double phi = 2.0 * std::numbers::pi * k / 48 + 0.01 * u(gen), r = 0.025 * (1.0 + 0.05 * u(gen));
      a.px[static_cast<std::size_t>(k) * lanes + l] = r * std::cos(phi) + 0.05 * static_cast<double>(l);
      a.py[static_cast<std::size_t>(k) * lanes + l] = r * std::sin(phi);
    }
  for (auto* v : {&a.ex, &a.ey, &a.gx, &a.gy, &a.n}) v->assign(values, -7.25);
  return a;
}

BarLanes view(BarArrays& a, std::size_t lanes, double k_m, double l0) {
  return {a.px.data(), a.py.data(), a.ex.data(), a.ey.data(), a.gx.data(), a.gy.data(), a.n.data(), lanes, k_m, l0};
}

// Every lane's bar values from `width` against the scalar pass (PolygonChain::ring_bars, the
// central difference's form) on the runs [first, last) of 4, 6, 8 and 10 lanes (3 to 10 rings,
// one spare lane for an odd count): runs of 1 to 26 bars give 6 to 260 values, so the widest
// vector's run ends in every mix of 4 and 2.
TEST(WideLanes, BarPassIsTheScalarPassToTheBit) {
  std::mt19937 gen(63);
  const double k_m = 4.1e6, l0 = 3.3e-3;
  for (const int width : widths())
    for (const std::size_t lanes : {4u, 6u, 8u, 10u})
      for (const auto& run : std::vector<std::array<int, 2>>{{0, 26}, {46, 48}, {3, 4}, {5, 8}, {7, 12}, {1, 24}}) {
        BarArrays a = ring_nodes(48, lanes, gen);
        bar_lanes(view(a, lanes, k_m, l0), run[0], run[1], width);
        int wrong = 0, outside = 0;
        for (int k = 0; k < 48; ++k)
          for (std::size_t l = 0; l < lanes; ++l) {
            const std::size_t at = static_cast<std::size_t>(k) * lanes + l;
            if (k < run[0] || k >= run[1]) {
              outside += !(a.ex[at] == -7.25 && a.ey[at] == -7.25 && a.gx[at] == -7.25 && a.gy[at] == -7.25 &&
                           a.n[at] == -7.25);
              continue;
            }
            const double bx = a.px[at + lanes] - a.px[at], by = a.py[at + lanes] - a.py[at];
            const double len = std::sqrt(bx * bx + by * by), inv = 1.0 / len;
            const double ex = bx * inv, ey = by * inv;
            wrong += !same_bits(a.ex[at], ex) + !same_bits(a.ey[at], ey) + !same_bits(a.gx[at], -ey * inv) +
                     !same_bits(a.gy[at], ex * inv) + !same_bits(a.n[at], k_m * (len - l0));
          }
        EXPECT_EQ(wrong, 0) << "width " << width << ", " << lanes << " lanes, bars " << run[0] << "–" << run[1];
        EXPECT_EQ(outside, 0) << "width " << width << ": a bar outside the run was written";
      }
}

// A one-ulp change of one node in one lane changes that lane's two bars only, on every width
// (the lanes are not mixed up).
TEST(WideLanes, BarPassKeepsTheLanesApart) {
  std::mt19937 gen(7);
  const std::size_t lanes = 6;
  for (const int width : widths()) {
    BarArrays a = ring_nodes(48, lanes, gen), b = a;
    const std::size_t moved = 10 * lanes + 3;  // node 10 of lane 3
    b.px[moved] = std::nextafter(b.px[moved], 1.0);
    bar_lanes(view(a, lanes, 1.0, 0.0), 0, 26, width);
    bar_lanes(view(b, lanes, 1.0, 0.0), 0, 26, width);
    for (int k = 0; k < 26; ++k)
      for (std::size_t l = 0; l < lanes; ++l) {
        const std::size_t at = static_cast<std::size_t>(k) * lanes + l;
        const bool touched = l == 3 && (k == 9 || k == 10);
        EXPECT_EQ(!same_bits(a.n[at], b.n[at]) || !same_bits(a.ex[at], b.ex[at]), touched)
            << "width " << width << ", bar " << k << ", lane " << l;
      }
  }
}

// The minimum of the limits of `count` nodes one by one (the scalar scan's order).
double scalar_min(double dt, const std::vector<double>& K, const std::vector<double>& C,
                  const std::vector<double>& mass) {
  for (std::size_t i = 0; i < K.size(); ++i) dt = std::min(dt, node_step_limit(K[i], C[i], mass[i]));
  return dt;
}

// Node rows as the Test 30 chain has them: K of a hinge-bound node and its contact rows
// (1e5–1e9 N/m), C up to a few ξ, masses of a node, half and full weight.
void random_rows(int count, std::mt19937& gen, std::vector<double>& K, std::vector<double>& C,
                 std::vector<double>& mass) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  K.resize(static_cast<std::size_t>(count));
  C.resize(K.size());
  mass.resize(K.size());
  for (std::size_t i = 0; i < K.size(); ++i) {
    K[i] = std::pow(10.0, 5.0 + 4.0 * u(gen));
    mass[i] = (u(gen) < 0.2 ? 0.5 : 1.0) * 3.9e-4;
    C[i] = 2.0 * std::sqrt(K[i] * mass[i]) * 3.0 * u(gen);
  }
}

// Every count from 0 to 27 (the welded run's ≈ 27 contact nodes a step), every width: the
// vector minimum is the scalar one to the bit, and the minimum node is moved through every
// lane of the last, padded group.
TEST(WideLanes, NodeStepLimitsAreTheScalarMinimumToTheBit) {
  std::mt19937 gen(1963);
  const double inf = std::numeric_limits<double>::infinity();
  for (const int width : widths())
    for (int count = 0; count <= 27; ++count)
      for (int repeat = 0; repeat < 4; ++repeat) {
        std::vector<double> K, C, mass;
        random_rows(count, gen, K, C, mass);
        if (count > 0 && repeat > 0) K[static_cast<std::size_t>(count - repeat % count - 1)] = 2.0e9;  // the stiffest
        const double expected = scalar_min(inf, K, C, mass);
        const double got = min_node_step_limit(inf, K.data(), C.data(), mass.data(), count, width);
        EXPECT_TRUE(same_bits(got, expected)) << "width " << width << ", " << count << " nodes: " << got << " vs "
                                              << expected;
        // A bound below every node's limit is kept.
        EXPECT_EQ(min_node_step_limit(1e-12, K.data(), C.data(), mass.data(), count, width), 1e-12);
      }
}

// The special rows: K ≤ 0 (no limit), K = 0 with damping, ξ so large that √(1 + ξ²) − ξ is
// round-off alone, and a NaN damping row (passed over, as std::min(dt, NaN) keeps dt).
TEST(WideLanes, NodeStepLimitsSpecialRows) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  for (const int width : widths()) {
    std::vector<double> K{-1.0, 0.0, 0.0, 3e6, 2e6, 5e6, -0.0, 1e7, 4e6}, C{0.0, 0.0, 5.0, nan, 1.0, 0.0, 1.0, 0.5, 2.0},
        mass(9, 3.9e-4);
    const double expected = scalar_min(inf, K, C, mass);
    EXPECT_TRUE(std::isfinite(expected));
    EXPECT_TRUE(same_bits(min_node_step_limit(inf, K.data(), C.data(), mass.data(), 9, width), expected))
        << "width " << width;
    // Only rows without a limit: the bound comes back.
    EXPECT_EQ(min_node_step_limit(inf, K.data(), C.data(), mass.data(), 3, width), inf) << "width " << width;
    // ξ ≈ 1e9: the same round-off on every width.
    std::vector<double> K2{1e6}, C2{1e9 * 2.0 * std::sqrt(1e6 * 3.9e-4)}, m2{3.9e-4};
    EXPECT_TRUE(same_bits(min_node_step_limit(inf, K2.data(), C2.data(), m2.data(), 1, width), scalar_min(inf, K2, C2, m2)))
        << "width " << width;
  }
}

#endif  // __FMA__

// The scalar limit is the central-difference formula (Belytschko, Liu & Moran §6.3):
// undamped 2/ω, and at ξ = 1 the factor √2 − 1.
TEST(WideLanes, NodeStepLimitFormula) {
  const double K = 4e6, m = 1e-3, omega = std::sqrt(K / m);
  EXPECT_NEAR(node_step_limit(K, 0.0, m), 2.0 / omega, 1e-15);
  EXPECT_NEAR(node_step_limit(K, 2.0 * std::sqrt(K * m), m), 2.0 / omega * (std::sqrt(2.0) - 1.0), 1e-15);
  EXPECT_EQ(node_step_limit(0.0, 1.0, m), std::numeric_limits<double>::infinity());
}

}  // namespace
