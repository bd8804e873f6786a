// The node–segment search with its box shrinking to the closest segment found
// (closest_segment, hinge/polygon_closest_segment.hpp) against the same search without the
// shrink (margin ∞): the same segment, distance and s to the bit, for slave nodes scattered
// within the reach of a distorted ring (many segments in reach, in the list's order and in
// reverse), on vertices' bisectors (two segments at one distance: the first of equals), and on
// the full ring's wrapping segment; and the first of two equally distant segments is chosen,
// in either order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "hinge/polygon_closest_segment.hpp"

using namespace ringcrush::hinge;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

constexpr double kT = 1.5e-3;  // the wall, as Test 30's

// A ring of n nodes (radius 25 mm, centre 0.1 m off the origin), every node moved by up to
// 0.2 ℓ0, in the chain's state layout (x, y of node k at 6 k).
std::vector<double> distorted_ring(int n, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double R = 0.025, l0 = 2.0 * std::numbers::pi * R / n;
  std::vector<double> m(6 * static_cast<std::size_t>(n), 0.0);
  for (int k = 0; k < n; ++k) {
    const double phi = 2.0 * std::numbers::pi * k / n;
    m[6 * static_cast<std::size_t>(k)] = 0.1 + R * std::cos(phi) + 0.2 * l0 * u(gen);
    m[6 * static_cast<std::size_t>(k) + 1] = 0.3 + R * std::sin(phi) + 0.2 * l0 * u(gen);
  }
  return m;
}

constexpr double kNoShrink = std::numeric_limits<double>::infinity();

struct Found {
  double best, s;
  int a;
};

// The closest of the listed segments within 2t (the landing's reach), the box shrinking by
// `margin` past the closest found (kNoShrink: the reference search).
template <bool FullRing>
Found search(lanes::Pair slave, const std::vector<double>& m, int wrap, const std::vector<int>& list, double margin) {
  Found f{2.0 * kT, 0.0, -1};
  closest_segment<FullRing>(slave, m.data(), wrap, list.data(), list.data() + list.size(), 2.0 * kT, margin, f.best,
                            f.a, f.s);
  return f;
}

template <bool FullRing>
void expect_same_choice(int n, unsigned seed) {
  std::mt19937 gen(seed);
  const auto m = distorted_ring(n, gen);
  const int segments = FullRing ? n : n - 1, wrap = n - 1;
  std::vector<int> list(static_cast<std::size_t>(segments));
  for (int a = 0; a < segments; ++a) list[static_cast<std::size_t>(a)] = a;
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.0, 1.0);
  int found = 0, compared = 0;
  auto check = [&](lanes::Pair p) {
    const Found ref = search<FullRing>(p, m, wrap, list, kNoShrink);
    const Found shrunk = search<FullRing>(p, m, wrap, list, 1e-6 * kT);
    EXPECT_EQ(shrunk.a, ref.a);
    EXPECT_TRUE(same_bits(shrunk.best, ref.best) && same_bits(shrunk.s, ref.s)) << p[0] << ", " << p[1];
    found += ref.a >= 0;
    ++compared;
  };
  // Points near every segment, at up to 2.5 t from it (beyond the reach too).
  for (int a = 0; a < segments; ++a)
    for (int i = 0; i < 40; ++i) {
      const double* pa = m.data() + 6 * a;
      const double* pb = FullRing && a == wrap ? m.data() : pa + 6;
      const double s = 1.2 * w(gen) - 0.1;
      check(lanes::Pair{pa[0] + s * (pb[0] - pa[0]) + 2.5 * kT * u(gen), pa[1] + s * (pb[1] - pa[1]) + 2.5 * kT * u(gen)});
    }
  // On each vertex's bisector, outside the ring: the vertex is the closest point of both its
  // segments (ties, or near-ties by the rounding of a + s e at s = 1).
  for (int k = 1; k < n - 1; ++k) {
    const double* p = m.data() + 6 * k;
    const double* prev = p - 6;
    const double* next = p + 6;
    double bx = (p[0] - prev[0]) / std::hypot(p[0] - prev[0], p[1] - prev[1]) -
                (next[0] - p[0]) / std::hypot(next[0] - p[0], next[1] - p[1]);
    double by = (p[1] - prev[1]) / std::hypot(p[0] - prev[0], p[1] - prev[1]) -
                (next[1] - p[1]) / std::hypot(next[0] - p[0], next[1] - p[1]);
    const double l = std::hypot(bx, by);
    for (const double r : {0.3 * kT, 0.9 * kT, 1.7 * kT}) check(lanes::Pair{p[0] + r * bx / l, p[1] + r * by / l});
  }
  EXPECT_GT(found, compared / 2);  // most points have a segment within the reach
}

}  // namespace

TEST(PolygonClosestSegment, ShrinkingBoxChoosesAsTheFullSearchHalfModel) { expect_same_choice<false>(25, 3u); }

TEST(PolygonClosestSegment, ShrinkingBoxChoosesAsTheFullSearchFullRing) { expect_same_choice<true>(48, 4u); }

// Two segments at exactly the same distance (mirror images about the slave's x): the first
// listed wins, in either order, with and without the shrink; a closer one listed between them
// wins.
TEST(PolygonClosestSegment, FirstOfEqualsAndStrictlyCloser) {
  std::vector<double> m(6 * 4, 0.0);
  const double xs[4] = {-2e-3, -1e-3, 1e-3, 2e-3}, ys[4] = {0.0, 0.0, 0.0, 0.0};
  for (int k = 0; k < 4; ++k) {
    m[6 * k] = xs[k];
    m[6 * k + 1] = ys[k];
  }
  const lanes::Pair slave = {0.0, 1e-3};
  // Segments 0 (−2…−1 mm) and 2 (1…2 mm) are both 1.414 mm away; segment 1 (−1…1 mm) 1 mm.
  for (const double margin : {kNoShrink, 1e-6 * kT}) {
    const Found f02 = search<false>(slave, m, 3, {0, 2}, margin);
    const Found f20 = search<false>(slave, m, 3, {2, 0}, margin);
    EXPECT_EQ(f02.a, 0);
    EXPECT_EQ(f20.a, 2);
    EXPECT_TRUE(same_bits(f02.best, f20.best));
    EXPECT_EQ(search<false>(slave, m, 3, {0, 1, 2}, margin).a, 1);
  }
}

// A segment listed after the first found and closer than it by 10⁻⁴ of the distance, straight
// above the node (its box as near as the segment itself): it is projected and wins — the box
// shrinks to the distance found, not below it.
TEST(PolygonClosestSegment, ACloserSegmentListedLaterWins) {
  // Segment 0 below the node at 1 mm, segment 1 beside it at 1 mm, segment 2 above it at
  // 0.9999 mm.
  const double xs[4] = {-1e-3, 1e-3, 1e-3, -1e-3}, ys[4] = {0.0, 0.0, 1.9999e-3, 1.9999e-3};
  std::vector<double> m(6 * 4, 0.0);
  for (int k = 0; k < 4; ++k) {
    m[6 * k] = xs[k];
    m[6 * k + 1] = ys[k];
  }
  const lanes::Pair slave = {0.0, 1e-3};
  const Found ref = search<false>(slave, m, 3, {0, 1, 2}, kNoShrink);
  const Found shrunk = search<false>(slave, m, 3, {0, 1, 2}, 1e-6 * kT);
  EXPECT_EQ(ref.a, 2);
  EXPECT_EQ(shrunk.a, 2);
  EXPECT_TRUE(same_bits(shrunk.best, ref.best));
  EXPECT_NEAR(shrunk.best, 0.9999e-3, 1e-15);
}
