// cps8_force_lanes_on_coords() (cps8_force_lanes.hpp) forms the geometry on x_n inside the lane
// kernel instead of reading it from each element's Cps8Geometry: its results must be bitwise
// those of Cps8GeometryUpdater::update() on x_n followed by cps8_force() on each element alone
// (the path ChainModel takes without the lanes) — force, bulk-viscous force, energies and
// every trial-state value, every rule, with and without bulk viscosity, elastic and yielding
// points in the same group. Any change of an operation's order in the lane geometry
// (the Jacobian's dot-product tree, the gradients, the weights) changes the last bits of
// some of these values on random elements and fails the test. The lanes' own Cps8Geometry is
// neither read (it holds the geometry of another configuration) nor written. The same for
// eight elements a group (the AVX-512 copy, where the CPU has it).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "cps8_random_elements.hpp"
#include "fe/chain/geometry_update.hpp"
#include "fe/element/cps8_force_lanes.hpp"

using namespace ringcrush::fe;

namespace {

constexpr double kWidth = 0.0125;

using kernel_test::ElementResult;

// x_n: the element rotated by a large angle and moved, as a crushed ring's element; its
// increment rotated with it (the same strain increment, seen in the rotated frame).
void move(kernel_test::RandomElement& el, double angle, ElementCoords& x) {
  const double c = std::cos(angle), s = std::sin(angle);
  for (int k = 0; k < 8; ++k) {
    x(k, 0) = c * el.x(k, 0) - s * el.x(k, 1) + 0.031;
    x(k, 1) = s * el.x(k, 0) + c * el.x(k, 1) - 0.017;
    const double ux = el.du[2 * k], uy = el.du[2 * k + 1];
    el.du[2 * k] = c * ux - s * uy;
    el.du[2 * k + 1] = s * ux + c * uy;
  }
}

// Groups of W; returns {points that yielded, points that stayed elastic}.
template <int W>
std::array<int, 2> compare_with_update_then_scalar(Integration rule, bool viscous, int groups, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  const J2PlaneStress material(kernel_test::thesis_steel());
  const Cps8GeometryUpdater updater(rule);
  const int count = groups * W;
  std::vector<kernel_test::RandomElement> el;
  std::vector<ElementCoords> x_n;
  std::vector<Cps8Geometry> stale, updated;
  for (int k = 0; k < count; ++k) {
    el.push_back(kernel_test::random_element(rng, k % 2 ? 1e-2 : 1e-4, k % 3 == 0));
    stale.push_back(cps8_geometry(el.back().x, rule, kWidth));  // the last increment's geometry
    x_n.emplace_back();
    move(el.back(), angle(rng), x_n.back());
    updated.push_back(stale.back());
    updater.update(x_n.back(), kWidth, updated.back());
  }
  const double dt = 5e-8;
  std::vector<ElementResult> ref(count), lanes(count);
  std::vector<BulkViscousLoad> ref_load(count), lane_load(count);
  for (int k = 0; k < count; ++k) {
    const double coefficient = 3.7e3 * (1.0 + 0.1 * k);
    ref_load[k] = BulkViscousLoad{coefficient, dt, &ref[k].viscous};
    lane_load[k] = BulkViscousLoad{coefficient, dt, &lanes[k].viscous};
    cps8_force(updated[k], el[k].du, el[k].committed.data(), ref[k].trial.data(), material, ref[k].out,
               viscous ? &ref_load[k] : nullptr);
  }
  const std::vector<Cps8Geometry> stale_before = stale;
  for (int k = 0; k < count; k += W) {
    Cps8LaneGroupOf<W> group;
    std::array<const ElementCoords*, W> x;
    for (int l = 0; l < W; ++l) {
      const int e = k + l;
      group[l] = Cps8Lane{&stale[e], el[e].du, el[e].committed.data(), lanes[e].trial.data(), &lanes[e].out,
                          viscous ? &lane_load[e] : nullptr};
      x[l] = &x_n[e];
    }
    EXPECT_TRUE(cps8_force_lanes_on_coords(group, updater.tables(), x, kWidth, material));
  }
  std::array<int, 2> branches{0, 0};
  for (int e = 0; e < count; ++e) {
    SCOPED_TRACE(::testing::Message() << "element " << e);
    kernel_test::expect_bitwise_equal(lanes[e], ref[e], updated[e].points);
    for (int i = 0; i < updated[e].points; ++i) {
      ++branches[ref[e].trial[i].peeq > el[e].committed[i].peeq ? 0 : 1];
      EXPECT_EQ(stale[e].dndx[i], stale_before[e].dndx[i]);  // not stored
      EXPECT_EQ(stale[e].weight[i], stale_before[e].weight[i]);
    }
    // The geometry did matter: the stale one gives another force.
    EXPECT_NE(updated[e].dndx[0], stale[e].dndx[0]);
  }
  if (viscous) {
    for (int e = 0; e < count; ++e) EXPECT_GT(ref[e].viscous.norm(), 0.0);
  }
  return branches;
}

}  // namespace

TEST(Cps8ForceOnCoords, IsBitwiseUpdateThenScalarKernel) {
  if (!cps8_force_lanes_forms_geometry()) GTEST_SKIP() << "no bitwise lanes here (no AVX2, or an FMA build)";
  unsigned seed = 5;
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective})
    for (bool viscous : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "rule " << static_cast<int>(rule) << ", viscous " << viscous);
      const auto branches = compare_with_update_then_scalar<kCps8Lanes>(rule, viscous, 3, seed++);
      EXPECT_GT(branches[0], 0);  // both material branches compared
      EXPECT_GT(branches[1], 0);
    }
}

TEST(Cps8ForceOnCoords, WideGroupIsBitwiseUpdateThenScalarKernel) {
  if (!cps8_force_wide_lanes_available()) GTEST_SKIP() << "no eight-lane kernel here (no AVX-512F, or an FMA build)";
  unsigned seed = 25;
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective})
    for (bool viscous : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "rule " << static_cast<int>(rule) << ", viscous " << viscous);
      const auto branches = compare_with_update_then_scalar<kCps8WideLanes>(rule, viscous, 2, seed++);
      EXPECT_GT(branches[0], 0);
      EXPECT_GT(branches[1], 0);
    }
}

// Without the eight-lane kernel the wide entry point forms nothing and says so.
TEST(Cps8ForceOnCoords, WideGroupDeclinesWithoutAvx512) {
  if (cps8_force_wide_lanes_available()) GTEST_SKIP() << "this CPU and build run the eight-lane kernel";
  std::mt19937 rng(3);
  const J2PlaneStress material(kernel_test::thesis_steel());
  const Cps8GeometryUpdater updater(Integration::Full);
  const auto el = kernel_test::random_element(rng, 1e-4, false);
  Cps8Geometry geo = cps8_geometry(el.x, Integration::Full, kWidth);
  std::array<ElementResult, kCps8WideLanes> out;
  Cps8WideLaneGroup group;
  std::array<const ElementCoords*, kCps8WideLanes> x;
  for (int l = 0; l < kCps8WideLanes; ++l) {
    out[l].out.force.setConstant(-7.0);
    group[l] = Cps8Lane{&geo, el.du, el.committed.data(), out[l].trial.data(), &out[l].out, nullptr};
    x[l] = &el.x;
  }
  EXPECT_FALSE(cps8_force_lanes_on_coords(group, updater.tables(), x, kWidth, material));
  for (const auto& o : out) EXPECT_EQ(o.out.force, ElementVector::Constant(-7.0));
}

// An inverted element at x_n: nothing is written and false is returned, so that the caller
// updates the stored geometry, which reports the element (Cps8GeometryUpdater::update throws).
TEST(Cps8ForceOnCoords, InvertedElementWritesNothing) {
  if (!cps8_force_lanes_forms_geometry()) GTEST_SKIP() << "no bitwise lanes here (no AVX2, or an FMA build)";
  std::mt19937 rng(7);
  const J2PlaneStress material(kernel_test::thesis_steel());
  const Cps8GeometryUpdater updater(Integration::Selective);
  std::array<kernel_test::RandomElement, kCps8Lanes> el;
  std::array<ElementCoords, kCps8Lanes> x;
  std::array<Cps8Geometry, kCps8Lanes> geo;
  std::array<ElementResult, kCps8Lanes> out;
  Cps8LaneGroup group;
  for (int l = 0; l < kCps8Lanes; ++l) {
    el[l] = kernel_test::random_element(rng, 1e-4, false);
    x[l] = el[l].x;
    geo[l] = cps8_geometry(el[l].x, Integration::Selective, kWidth);
    out[l].out.force.setConstant(-7.0);
    for (auto& p : out[l].trial) p.peeq = -3.0;
    group[l] = Cps8Lane{&geo[l], el[l].du, el[l].committed.data(), out[l].trial.data(), &out[l].out, nullptr};
  }
  x[1].col(0) *= -1.0;  // mirrored: det J < 0
  EXPECT_FALSE(cps8_force_lanes_on_coords(group, updater.tables(), {&x[0], &x[1], &x[2], &x[3]}, kWidth, material));
  for (int l = 0; l < kCps8Lanes; ++l) {
    EXPECT_EQ(out[l].out.force, ElementVector::Constant(-7.0));
    for (const auto& p : out[l].trial) EXPECT_EQ(p.peeq, -3.0);
  }
  EXPECT_THROW(updater.update(x[1], kWidth, geo[1]), std::invalid_argument);
}

// The same in a group of eight, the inverted element in the upper half (lane 6).
TEST(Cps8ForceOnCoords, WideGroupInvertedElementWritesNothing) {
  if (!cps8_force_wide_lanes_available()) GTEST_SKIP() << "no eight-lane kernel here (no AVX-512F, or an FMA build)";
  std::mt19937 rng(7);
  const J2PlaneStress material(kernel_test::thesis_steel());
  const Cps8GeometryUpdater updater(Integration::Selective);
  std::array<kernel_test::RandomElement, kCps8WideLanes> el;
  std::array<ElementCoords, kCps8WideLanes> x;
  std::array<const ElementCoords*, kCps8WideLanes> x_n;
  std::array<Cps8Geometry, kCps8WideLanes> geo;
  std::array<ElementResult, kCps8WideLanes> out;
  Cps8WideLaneGroup group;
  for (int l = 0; l < kCps8WideLanes; ++l) {
    el[l] = kernel_test::random_element(rng, 1e-4, false);
    x[l] = el[l].x;
    x_n[l] = &x[l];
    geo[l] = cps8_geometry(el[l].x, Integration::Selective, kWidth);
    out[l].out.force.setConstant(-7.0);
    for (auto& p : out[l].trial) p.peeq = -3.0;
    group[l] = Cps8Lane{&geo[l], el[l].du, el[l].committed.data(), out[l].trial.data(), &out[l].out, nullptr};
  }
  x[6].col(0) *= -1.0;  // mirrored: det J < 0
  EXPECT_FALSE(cps8_force_lanes_on_coords(group, updater.tables(), x_n, kWidth, material));
  for (int l = 0; l < kCps8WideLanes; ++l) {
    EXPECT_EQ(out[l].out.force, ElementVector::Constant(-7.0));
    for (const auto& p : out[l].trial) EXPECT_EQ(p.peeq, -3.0);
  }
}

TEST(Cps8ForceOnCoords, RejectsTablesOfAnotherRule) {
  if (!cps8_force_lanes_forms_geometry()) GTEST_SKIP() << "no bitwise lanes here (no AVX2, or an FMA build)";
  std::mt19937 rng(9);
  const J2PlaneStress material(kernel_test::thesis_steel());
  const auto el = kernel_test::random_element(rng, 1e-4, false);
  const Cps8Geometry full = cps8_geometry(el.x, Integration::Full, kWidth);
  std::array<Cps8Output, kCps8Lanes> out;
  std::array<std::array<PointState, 9>, kCps8Lanes> trial{};
  Cps8LaneGroup group;
  for (int l = 0; l < kCps8Lanes; ++l)
    group[l] = Cps8Lane{&full, el.du, el.committed.data(), trial[l].data(), &out[l], nullptr};
  const Cps8RuleTables reduced = cps8_rule_tables(Integration::Reduced);
  EXPECT_THROW(cps8_force_lanes_on_coords(group, reduced, {&el.x, &el.x, &el.x, &el.x}, kWidth, material),
               std::invalid_argument);
}
