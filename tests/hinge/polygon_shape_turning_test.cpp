// PolygonChain::shape's turning angles come from one atan2 per bar (each bar's direction shared
// by its two end nodes): the same bits as the reference form, τ_k = wrap(β(k−1 → k) − β(k → k+1))
// with both directions formed at node k, on distorted rings (half model mirrored, and full).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "hinge/polygon_chain.hpp"

using namespace ringcrush::hinge;

namespace {

double wrap(double a) {  // PolygonChain::wrap_angle's range (−π, π]
  while (a > std::numbers::pi) a -= 2.0 * std::numbers::pi;
  while (a <= -std::numbers::pi) a += 2.0 * std::numbers::pi;
  return a;
}

void check(bool half, unsigned seed) {
  PolygonChainInput in;
  in.rings = 3;
  in.half_symmetry = half;
  in.nodes_per_ring = 48;
  PolygonChain chain(in);
  std::vector<double> y = chain.initial_state();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double reach = 0.25 * 0.5 * in.outer_diameter_m;  // up to 25 % of R: sharp folds too
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) {
      const auto o = chain.node_offset(r, j);
      if (!(half && (j == 0 || j == chain.independent_nodes() - 1))) y[o] += reach * u(rng);
      y[o + 1] += reach * u(rng);
    }
  const PolygonShape s = chain.shape(y.data());
  int folds = 0;
  for (std::size_t r = 0; r < s.nodes.size(); ++r) {
    const auto& p = s.nodes[r];
    const std::size_t n = p.size();
    ASSERT_EQ(s.turning[r].size(), n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t km = (k + n - 1) % n, kp = (k + 1) % n;
      const double b0 = std::atan2(p[k][1] - p[km][1], p[k][0] - p[km][0]);
      const double b1 = std::atan2(p[kp][1] - p[k][1], p[kp][0] - p[k][0]);
      const double reference = wrap(b0 - b1);
      EXPECT_EQ(s.turning[r][k], reference) << "ring " << r << " node " << k;
      if (std::abs(reference) > 0.5) ++folds;
    }
  }
  EXPECT_GT(folds, 10);  // the distortion reaches well past the round ring's 2π/N turns
}

}  // namespace

TEST(PolygonShapeTurning, OneDirectionPerBarEqualsTheReferenceHalfModel) { check(true, 31u); }
TEST(PolygonShapeTurning, OneDirectionPerBarEqualsTheReferenceFullRings) { check(false, 32u); }
