// The force-only CPS8 kernel on four elements at once (cps8_force_lanes.hpp) is bitwise
// cps8_force() on each element alone — itself bitwise its point-by-point form
// (explicit_speed_test.cpp) — on deformed element sets with elastic and yielding points in
// the same group, every rule, with and without bulk viscosity, in both compiled copies
// (portable and AVX2). The set has 11 elements: two lane groups and a remainder of three that
// the chain evaluates element by element, as ChainModel does.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <stdexcept>
#include <vector>

#include "cps8_random_elements.hpp"
#include "fe/element/cps8_force_lanes.hpp"

using namespace ringcrush::fe;

namespace {

using LaneKernel = void (*)(const Cps8LaneGroup&, const J2PlaneStress&);

using kernel_test::ElementResult;

// Compares `kernel` with cps8_force() on `count` random elements (groups of 4, then the
// remainder through cps8_force()); returns {points that yielded, points that stayed elastic}.
std::array<int, 2> compare_with_scalar(LaneKernel kernel, Integration rule, bool viscous, int count,
                                       unsigned seed, const MaterialInput& steel = kernel_test::thesis_steel()) {
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
  int k = 0;
  for (; k + kCps8Lanes <= count; k += kCps8Lanes) {
    Cps8LaneGroup group;
    for (int l = 0; l < kCps8Lanes; ++l) {
      const int e = k + l;
      group[l] = Cps8Lane{&geo[e], el[e].du, el[e].committed.data(), lanes[e].trial.data(), &lanes[e].out,
                          viscous ? &lane_load[e] : nullptr};
    }
    kernel(group, material);
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
  return branches;
}

void check_kernel(LaneKernel kernel, const MaterialInput& steel = kernel_test::thesis_steel()) {
  unsigned seed = 3;
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective})
    for (bool viscous : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "rule " << static_cast<int>(rule) << ", viscous " << viscous);
      const auto branches = compare_with_scalar(kernel, rule, viscous, 11, seed++, steel);
      EXPECT_GT(branches[0], 0);  // both material branches compared
      EXPECT_GT(branches[1], 0);
    }
}

}  // namespace

TEST(Cps8ForceLanes, PortableCopyIsBitwiseTheScalarKernel) {
  if (!cps8_lanes_bitwise_build()) GTEST_SKIP() << "FMA build: the lanes are not used";
  check_kernel(&cps8_force_lanes_portable);
}

TEST(Cps8ForceLanes, Avx2CopyIsBitwiseTheScalarKernel) {
  if (!cps8_lanes_bitwise_build()) GTEST_SKIP() << "FMA build: the lanes are not used";
  if (!cps8_lanes_avx2_available()) GTEST_SKIP() << "this CPU has no AVX2";
  check_kernel(&cps8_force_lanes_avx2);
}

TEST(Cps8ForceLanes, DispatchedKernelIsBitwiseTheScalarKernel) { check_kernel(&cps8_force_lanes); }

// The lanes look σy(ᾱ_n) up on the vector (yield_stress_lanes, cps8_force_lanes.cpp): a table
// of four points, softening at the end, with committed ᾱ (0 … 0.04) on every segment, at 0 and
// beyond the last point, in both copies.
TEST(Cps8ForceLanes, MultiSegmentHardeningIsBitwiseTheScalarKernel) {
  if (!cps8_lanes_bitwise_build()) GTEST_SKIP() << "FMA build: the lanes are not used";
  MaterialInput steel = kernel_test::thesis_steel();
  steel.hardening = {{273e6, 0.0}, {290e6, 0.005}, {315e6, 0.015}, {300e6, 0.03}};
  check_kernel(&cps8_force_lanes_portable, steel);
  if (cps8_lanes_avx2_available()) check_kernel(&cps8_force_lanes_avx2, steel);
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
