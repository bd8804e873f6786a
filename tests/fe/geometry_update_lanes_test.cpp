// Cps8GeometryUpdater::update_lanes (geometry_update_lanes.cpp) is bitwise update() on each of
// its four elements — ∂N/∂x at the stress and reduced points and the point weights — on
// distorted, rotated elements of every rule; a group with an inverted element throws as
// update() does.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <stdexcept>

#include "cps8_random_elements.hpp"
#include "fe/chain/geometry_update.hpp"

using namespace ringcrush::fe;

TEST(GeometryUpdateLanes, IsBitwiseTheElementByElementUpdate) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective}) {
    const Cps8GeometryUpdater updater(rule);
    for (int group = 0; group < 5; ++group) {
      std::array<ElementCoords, 4> x;
      std::array<Cps8Geometry, 4> initial, one, lanes;
      for (int l = 0; l < 4; ++l) {
        const auto el = kernel_test::random_element(rng, 1e-3, false);
        // Rotated by a large angle and moved: a current configuration of a crushed ring.
        const double a = angle(rng), c = std::cos(a), s = std::sin(a);
        for (int k = 0; k < 8; ++k) {
          x[l](k, 0) = c * el.x(k, 0) - s * el.x(k, 1) + el.du[2 * k] + 0.031;
          x[l](k, 1) = s * el.x(k, 0) + c * el.x(k, 1) + el.du[2 * k + 1] - 0.017;
        }
        initial[l] = one[l] = lanes[l] = cps8_geometry(el.x, rule, 0.0125);
        updater.update(x[l], 0.0125, one[l]);
      }
      updater.update_lanes({&x[0], &x[1], &x[2], &x[3]}, 0.0125, {&lanes[0], &lanes[1], &lanes[2], &lanes[3]});
      for (int l = 0; l < 4; ++l) {
        for (int i = 0; i < one[l].points; ++i) {
          EXPECT_EQ(lanes[l].dndx[i], one[l].dndx[i]);
          EXPECT_EQ(lanes[l].weight[i], one[l].weight[i]);
        }
        if (rule == Integration::Selective) {
          for (int r = 0; r < 4; ++r) EXPECT_EQ(lanes[l].dndx_reduced[r], one[l].dndx_reduced[r]);
        }
        EXPECT_NE(lanes[l].dndx[0], initial[l].dndx[0]);  // the update did move the geometry
      }
    }
  }
  std::printf("update_lanes on vector lanes here: %s\n", Cps8GeometryUpdater::lanes_vectorised() ? "yes" : "no");
}

TEST(GeometryUpdateLanes, InvertedElementThrows) {
  std::mt19937 rng(2);
  const Cps8GeometryUpdater updater(Integration::Selective);
  std::array<ElementCoords, 4> x;
  std::array<Cps8Geometry, 4> geo;
  for (int l = 0; l < 4; ++l) {
    x[l] = kernel_test::random_element(rng, 1e-4, false).x;
    geo[l] = cps8_geometry(x[l], Integration::Selective, 0.0125);
  }
  x[2].col(0) *= -1.0;  // mirrored: det J < 0
  EXPECT_THROW(
      updater.update_lanes({&x[0], &x[1], &x[2], &x[3]}, 0.0125, {&geo[0], &geo[1], &geo[2], &geo[3]}),
      std::invalid_argument);
}
