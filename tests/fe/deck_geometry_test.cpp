// Node generation geometry of the deck reader (fe/deck/deck_geometry.hpp) against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fe/deck/deck_geometry.hpp"

namespace fd = ringcrush::fe::deck;

TEST(DeckGeometry, ArcTurnsCounterClockwiseAboutTheNormal) {
  // From the bottom (0, −1) to the top (0, 1) about +z: the half circle through +x — the
  // dynamic deck's half ring (NGEN, LINE=C 101,197).
  const fd::Point a{0, -1, 0}, b{0, 1, 0}, c{0, 0, 0};
  const fd::Point mid = fd::arc_point(a, b, c, {0, 0, 1}, 0.5);
  EXPECT_NEAR(mid[0], 1.0, 1e-15);
  EXPECT_NEAR(mid[1], 0.0, 1e-15);
  // About −z the same ends give the half circle through −x.
  EXPECT_NEAR(fd::arc_point(a, b, c, {0, 0, -1}, 0.5)[0], -1.0, 1e-15);
  // A quarter: 1/3 of the way from −90° to 0° is −60°, on the circle.
  const fd::Point q = fd::arc_point({0, -2, 0}, {2, 0, 0}, c, {0, 0, 1}, 1.0 / 3.0);
  EXPECT_NEAR(q[0], 2 * std::cos(-std::numbers::pi / 3), 1e-15);
  EXPECT_NEAR(q[1], 2 * std::sin(-std::numbers::pi / 3), 1e-15);
  // Off-origin centre, ends at different radii: radius interpolated linearly.
  const fd::Point r = fd::arc_point({2, 1, 0}, {1, 3, 0}, {1, 1, 0}, {0, 0, 1}, 0.5);
  EXPECT_NEAR(std::hypot(r[0] - 1, r[1] - 1), 1.5, 1e-14);
  EXPECT_NEAR(std::atan2(r[1] - 1, r[0] - 1), std::numbers::pi / 4, 1e-14);
  EXPECT_THROW(fd::arc_point(c, b, c, {0, 0, 1}, 0.5), std::invalid_argument);
  EXPECT_THROW(fd::arc_point(a, b, c, {0, 0, 0}, 0.5), std::invalid_argument);
}

TEST(DeckGeometry, ShiftThenRotate) {
  // Translate (1, 0), then rotate 90° about the z axis through (0, 0): (1,0) → (2,0) → (0,2).
  const fd::Point p = fd::shift_rotate({1, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 0, 1}, 90.0);
  EXPECT_NEAR(p[0], 0.0, 1e-15);
  EXPECT_NEAR(p[1], 2.0, 1e-15);
  // The dynamic deck's copies: shift (0, −50.8 mm), rotation 0 about a z axis at y = 25.4 mm.
  const fd::Point q = fd::shift_rotate({0, 0.0254, 0}, {0, -0.0508, 0}, {0, 0.0254, 0}, {0, 0.0254, 1}, 0.0);
  EXPECT_EQ(q[1], 0.0254 - 0.0508);
  EXPECT_THROW(fd::shift_rotate({1, 0, 0}, {0, 0, 0}, {1, 1, 1}, {1, 1, 1}, 30.0), std::invalid_argument);
}

TEST(DeckGeometry, ReflectInALine) {
  // The static deck's REFLECT=LINE through (50 mm, 0) and (0, 0): the x axis.
  const fd::Point p = fd::reflect_line({0.01, -0.02, 0}, {0.05, 0, 0}, {0, 0, 0});
  EXPECT_NEAR(p[0], 0.01, 1e-17);
  EXPECT_NEAR(p[1], 0.02, 1e-17);
  // The line y = x swaps the coordinates.
  const fd::Point s = fd::reflect_line({3, 1, 0}, {0, 0, 0}, {1, 1, 0});
  EXPECT_NEAR(s[0], 1.0, 1e-15);
  EXPECT_NEAR(s[1], 3.0, 1e-15);
  EXPECT_THROW(fd::reflect_line(p, {1, 1, 0}, {1, 1, 0}), std::invalid_argument);
}
