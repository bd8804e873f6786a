// yield_stress_lanes() (fe/element/hardening_lanes.hpp), the element kernels' σy(ᾱ_n) on four
// (and eight) lanes, is bitwise HardeningTable::yield_stress() on each lane: ᾱ at 0, −0, negative, inside
// every segment, exactly at the break points, beyond the last point and NaN, mixed in one
// vector, for tables of one, two and four points (one falling).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fe/element/hardening_lanes.hpp"

using namespace ringcrush::fe;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every window of W lanes of `alphas` (all lanes virgin, mixed, none virgin): the number of
// lanes that differ from the scalar table. (The eight-lane vector is here compiled for the
// baseline instruction set, the template's arithmetic the same as in the AVX-512 kernel, whose
// own code Cps8ForceLanes.MultiSegmentHardeningIsBitwiseTheScalarKernel checks.)
template <class V>
int lanes_differing(const HardeningTable& table, const std::vector<double>& alphas) {
  constexpr int W = lanes::kWidthOf<V>;
  int n = 0;
  for (std::size_t k = 0; k + W <= alphas.size(); ++k) {
    V a, sy;
    for (int l = 0; l < W; ++l) a[l] = alphas[k + static_cast<std::size_t>(l)];
    lanes::yield_stress_lanes(table, a, sy);
    for (int l = 0; l < W; ++l) n += !same_bits(sy[l], table.yield_stress(a[l]));
  }
  return n;
}

std::vector<double> alphas_over(const std::vector<HardeningPoint>& pts, unsigned seed) {
  std::vector<double> a{0.0, -0.0, 0.0, 0.0, -1e-3, 0.0};
  for (const HardeningPoint& p : pts) a.push_back(p.plastic_strain);  // the break points
  a.push_back(std::nan(""));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.5 * pts.back().plastic_strain + 0.01);
  for (int k = 0; k < 400; ++k) a.push_back(k % 9 == 0 ? 0.0 : u(rng));
  return a;
}

}  // namespace

TEST(HardeningLanes, YieldStressIsBitwiseTheTableOnEveryLane) {
  for (const std::vector<HardeningPoint>& pts :
       {std::vector<HardeningPoint>{{250e6, 0.0}}, std::vector<HardeningPoint>{{273e6, 0.0}, {320e6, 0.02113}},
        std::vector<HardeningPoint>{{273e6, 0.0}, {290e6, 0.005}, {315e6, 0.015}, {300e6, 0.03}}}) {
    SCOPED_TRACE(::testing::Message() << pts.size() << " points");
    const HardeningTable table(pts);
    EXPECT_EQ(lanes_differing<lanes::Lanes>(table, alphas_over(pts, 7)), 0);
    EXPECT_EQ(lanes_differing<lanes::Lanes8>(table, alphas_over(pts, 7)), 0);
  }
}

// The comparison is sharp: the same lanes on a table whose one interior point is moved by one
// ulp of its yield stress differ from the original table inside the two segments it bounds.
TEST(HardeningLanes, OneUlpOfATablePointIsDetected) {
  std::vector<HardeningPoint> pts{{273e6, 0.0}, {290e6, 0.005}, {315e6, 0.015}, {300e6, 0.03}};
  const HardeningTable table(pts);
  pts[2].yield_stress_pa = std::nextafter(pts[2].yield_stress_pa, 1e300);
  const HardeningTable nudged(pts);
  int n = 0;
  const std::vector<double> a = alphas_over(pts, 8);
  for (std::size_t k = 0; k + 4 <= a.size(); k += 4) {
    lanes::Lanes sy;
    lanes::yield_stress_lanes(nudged, lanes::Lanes{a[k], a[k + 1], a[k + 2], a[k + 3]}, sy);
    for (int l = 0; l < 4; ++l) n += !same_bits(sy[l], table.yield_stress(a[k + l]));
  }
  EXPECT_GT(n, 0);
}
