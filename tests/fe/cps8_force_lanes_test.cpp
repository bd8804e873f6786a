// The force-only CPS8 kernel on four elements at once (cps8_force_lanes.hpp) is bitwise
// cps8_force() on each element alone — itself bitwise its point-by-point form
// (explicit_speed_test.cpp) — on deformed element sets with elastic and yielding points in
// the same group, every rule, with and without bulk viscosity, in both compiled copies
// (portable and AVX2), and the same for eight elements a group (AVX-512): 23 elements, two
// groups of eight, a group of four and three one by one, as ChainModel deals them there — and
// the eight-lane results are bitwise the four-lane ones on the same elements.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <stdexcept>
#include <vector>

#include "cps8_random_elements.hpp"
#include "fe/element/cps8_force_lanes.hpp"

using namespace ringcrush::fe;

namespace {

template <int W>
using LaneKernelOf = void (*)(const Cps8LaneGroupOf<W>&, const J2PlaneStress&);
using LaneKernel = LaneKernelOf<kCps8Lanes>;
using WideLaneKernel = LaneKernelOf<kCps8WideLanes>;

using kernel_test::ElementResult;

// Groups of W elements [k, k + W) of the set into `kernel`, from k, while a whole group is
// left; returns the first element not done.
template <int W>
int run_groups(LaneKernelOf<W> kernel, int k, int count, std::vector<Cps8Geometry>& geo,
               std::vector<kernel_test::RandomElement>& el, std::vector<ElementResult>& lanes,
               std::vector<BulkViscousLoad>& lane_load, bool viscous, const J2PlaneStress& material) {
  for (; k + W <= count; k += W) {
    Cps8LaneGroupOf<W> group;
    for (int l = 0; l < W; ++l) {
      const int e = k + l;
      group[l] = Cps8Lane{&geo[e], el[e].du, el[e].committed.data(), lanes[e].trial.data(), &lanes[e].out,
                          viscous ? &lane_load[e] : nullptr};
    }
    kernel(group, material);
  }
  return k;
}

// Compares `kernel` with cps8_force() on `count` random elements (groups of W; for W = 8 then
// a group of four through the dispatched 4-lane kernel; the remainder through cps8_force());
// returns {points that yielded, points that stayed elastic}. The lane results into *results.
template <int W>
std::array<int, 2> compare_with_scalar(LaneKernelOf<W> kernel, Integration rule, bool viscous, int count,
                                       unsigned seed, const MaterialInput& steel = kernel_test::thesis_steel(),
                                       std::vector<ElementResult>* results = nullptr) {
  std::mt19937 rng(seed);
  const J2PlaneStress material(steel);
  std::vector<kernel_test::RandomElement> el;
  std::vector<Cps8Geometry> geo;
  for (int k = 0; k < count; ++k) {
    // Large increments on every other element, committed stress near yield on every third:
    // each group holds yielding and elastic points.
    el.push_back(kernel_test::random_element(rng, k % 2 ? 1e-2 : 1e-4, k % 3 == 0));
    geo.push_back(cps8_geometry(el.back().x, rule, 0.0125));
  }
  const double dt = 5e-8;
  std::vector<ElementResult> ref(count), lanes(count);
  std::vector<BulkViscousLoad> ref_load(count), lane_load(count);
  for (int k = 0; k < count; ++k) {
    const double coefficient = 3.7e3 * (1.0 + 0.1 * k);  // each element its own
    ref_load[k] = BulkViscousLoad{coefficient, dt, &ref[k].viscous};
    lane_load[k] = BulkViscousLoad{coefficient, dt, &lanes[k].viscous};
    cps8_force(geo[k], el[k].du, el[k].committed.data(), ref[k].trial.data(), material, ref[k].out,
               viscous ? &ref_load[k] : nullptr);
  }
  int k = run_groups<W>(kernel, 0, count, geo, el, lanes, lane_load, viscous, material);
  if constexpr (W == kCps8WideLanes) {
    const LaneKernel four = &cps8_force_lanes;
    k = run_groups<kCps8Lanes>(four, k, count, geo, el, lanes, lane_load, viscous, material);
  }
  for (; k < count; ++k)
    cps8_force(geo[k], el[k].du, el[k].committed.data(), lanes[k].trial.data(), material, lanes[k].out,
               viscous ? &lane_load[k] : nullptr);

  std::array<int, 2> branches{0, 0};
  for (int e = 0; e < count; ++e) {
    SCOPED_TRACE(::testing::Message() << "element " << e);
    kernel_test::expect_bitwise_equal(lanes[e], ref[e], geo[e].points);
    for (int i = 0; i < geo[e].points; ++i) {
      ++branches[ref[e].trial[i].peeq > el[e].committed[i].peeq ? 0 : 1];
    }
  }
  if (viscous) {
    for (int e = 0; e < count; ++e) EXPECT_GT(ref[e].viscous.norm(), 0.0);
  }
  if (results) *results = std::move(lanes);
  return branches;
}

template <int W>
void check_kernel(LaneKernelOf<W> kernel, const MaterialInput& steel = kernel_test::thesis_steel()) {
  unsigned seed = 3;
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective})
    for (bool viscous : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "rule " << static_cast<int>(rule) << ", viscous " << viscous);
      const auto branches = compare_with_scalar<W>(kernel, rule, viscous, W == 4 ? 11 : 23, seed++, steel);
      EXPECT_GT(branches[0], 0);  // both material branches compared
      EXPECT_GT(branches[1], 0);
    }
}

}  // namespace

TEST(Cps8ForceLanes, PortableCopyIsBitwiseTheScalarKernel) {
  if (!cps8_lanes_bitwise_build()) GTEST_SKIP() << "FMA build: the lanes are not used";
  check_kernel<4>(&cps8_force_lanes_portable);
}

TEST(Cps8ForceLanes, Avx2CopyIsBitwiseTheScalarKernel) {
  if (!cps8_lanes_bitwise_build()) GTEST_SKIP() << "FMA build: the lanes are not used";
  if (!cps8_lanes_avx2_available()) GTEST_SKIP() << "this CPU has no AVX2";
  check_kernel<4>(&cps8_force_lanes_avx2);
}

TEST(Cps8ForceLanes, DispatchedKernelIsBitwiseTheScalarKernel) {
  const LaneKernel kernel = &cps8_force_lanes;
  check_kernel<4>(kernel);
}

TEST(Cps8ForceLanes, Avx512CopyIsBitwiseTheScalarKernel) {
  if (!cps8_lanes_bitwise_build()) GTEST_SKIP() << "FMA build: the lanes are not used";
  if (!cps8_lanes_avx512_available()) GTEST_SKIP() << "this CPU has no AVX-512F: the eight-lane copy cannot run";
  check_kernel<8>(&cps8_force_lanes_avx512);
}

// Eight a group through the dispatch: the AVX-512 copy, or two groups of four without it.
TEST(Cps8ForceLanes, DispatchedWideKernelIsBitwiseTheScalarKernel) {
  const WideLaneKernel kernel = &cps8_force_lanes;
  check_kernel<8>(kernel);
}

// Lane l of the eight-lane copy and lane l mod 4 of the four-lane copy (AVX2) give the same bits
// on the same 23 elements, every rule, with and without bulk viscosity.
TEST(Cps8ForceLanes, Avx512CopyIsBitwiseTheAvx2Copy) {
  if (!cps8_lanes_bitwise_build()) GTEST_SKIP() << "FMA build: the lanes are not used";
  if (!cps8_lanes_avx512_available()) GTEST_SKIP() << "this CPU has no AVX-512F: the eight-lane copy cannot run";
  unsigned seed = 11;
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective})
    for (bool viscous : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "rule " << static_cast<int>(rule) << ", viscous " << viscous);
      std::vector<ElementResult> four, eight;
      compare_with_scalar<4>(&cps8_force_lanes_avx2, rule, viscous, 23, seed, kernel_test::thesis_steel(), &four);
      compare_with_scalar<8>(&cps8_force_lanes_avx512, rule, viscous, 23, seed, kernel_test::thesis_steel(), &eight);
      ++seed;
      ASSERT_EQ(four.size(), eight.size());
      const int points = rule == Integration::Reduced ? 4 : 9;
      for (std::size_t e = 0; e < four.size(); ++e) {
        SCOPED_TRACE(::testing::Message() << "element " << e);
        kernel_test::expect_bitwise_equal(eight[e], four[e], points);
      }
    }
}

// The lanes look σy(ᾱ_n) up on the vector (yield_stress_lanes, cps8_force_lanes.cpp): a table
// of four points, softening at the end, with committed ᾱ (0 … 0.04) on every segment, at 0 and
// beyond the last point, in both copies.
TEST(Cps8ForceLanes, MultiSegmentHardeningIsBitwiseTheScalarKernel) {
  if (!cps8_lanes_bitwise_build()) GTEST_SKIP() << "FMA build: the lanes are not used";
  MaterialInput steel = kernel_test::thesis_steel();
  steel.hardening = {{273e6, 0.0}, {290e6, 0.005}, {315e6, 0.015}, {300e6, 0.03}};
  check_kernel<4>(&cps8_force_lanes_portable, steel);
  if (cps8_lanes_avx2_available()) check_kernel<4>(&cps8_force_lanes_avx2, steel);
  if (cps8_lanes_avx512_available()) check_kernel<8>(&cps8_force_lanes_avx512, steel);
}

TEST(Cps8ForceLanes, RejectsMixedRules) {
  std::mt19937 rng(1);
  const J2PlaneStress material(kernel_test::thesis_steel());
  const auto el = kernel_test::random_element(rng, 1e-4, false);
  const Cps8Geometry full = cps8_geometry(el.x, Integration::Full, 0.0125);
  const Cps8Geometry selective = cps8_geometry(el.x, Integration::Selective, 0.0125);
  std::array<Cps8Output, kCps8Lanes> out;
  std::array<std::array<PointState, 9>, kCps8Lanes> trial{};
  Cps8LaneGroup group;
  for (int l = 0; l < kCps8Lanes; ++l)
    group[l] = Cps8Lane{l == 2 ? &selective : &full, el.du, el.committed.data(), trial[l].data(), &out[l], nullptr};
  EXPECT_THROW(cps8_force_lanes(group, material), std::invalid_argument);
}

TEST(Cps8ForceLanes, WideGroupRejectsMixedRules) {
  std::mt19937 rng(1);
  const J2PlaneStress material(kernel_test::thesis_steel());
  const auto el = kernel_test::random_element(rng, 1e-4, false);
  const Cps8Geometry full = cps8_geometry(el.x, Integration::Full, 0.0125);
  const Cps8Geometry selective = cps8_geometry(el.x, Integration::Selective, 0.0125);
  std::array<Cps8Output, kCps8WideLanes> out;
  std::array<std::array<PointState, 9>, kCps8WideLanes> trial{};
  Cps8WideLaneGroup group;
  for (int l = 0; l < kCps8WideLanes; ++l)  // the odd one in the upper half
    group[l] = Cps8Lane{l == 6 ? &selective : &full, el.du, el.committed.data(), trial[l].data(), &out[l], nullptr};
  EXPECT_THROW(cps8_force_lanes(group, material), std::invalid_argument);
}
