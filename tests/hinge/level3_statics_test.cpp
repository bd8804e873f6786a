// Level 3 statics check (hinge/level3_statics.hpp): the least max |M|/M0 of a field in
// equilibrium with the contact loads, against the closed form of the ring between plates
// (THEORY §1.2–1.3: four-hinge onset and the DeRuntz–Hodge mechanism).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "hinge/level3_mechanism.hpp"
#include "hinge/level3_statics.hpp"
#include "level3_ring_fixtures.hpp"

using namespace ringcrush::hinge;
using std::numbers::pi;

namespace {

const Level3Ring& kRing = ringcrush::hinge::testing::kLevel3Ring;
using ringcrush::hinge::testing::uniform_shape;

}  // namespace

// Onset between plates (φ = 0, P = P0 = 4 M0/R): the field is M = ±M0 (1 − 2 sin θ) with
// H = 0 — at yield at A, C, B and below it between them; the four-hinge mechanism is the
// collapse mechanism (ratio exactly 1).
TEST(Level3Statics, RingBetweenPlatesAtOnsetIsTheFourHingeField) {
  const auto s = uniform_shape(0.0);
  const double M0 = kRing.plastic_moment_nm, P0 = kRing.collapse_load();
  const auto st = level3_statics_check(s, P0, M0);
  EXPECT_NEAR(st.peak_ratio, 1.0, 1e-9);
  EXPECT_NEAR(st.horizontal_force_n, 0.0, 1e-6 * P0);
  double off_hinge = 0.0;
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    const double th = s.theta[k];
    EXPECT_NEAR(std::abs(st.moment_nm[k]), M0 * std::abs(1.0 - 2.0 * std::sin(th)), 1e-9 * M0) << "θ = " << th;
    const double from_hinge = std::min({th, std::abs(th - 0.5 * pi), pi - th});
    if (from_hinge > 10.0 * pi / 180.0) off_hinge = std::max(off_hinge, std::abs(st.moment_nm[k]) / M0);
  }
  EXPECT_LT(off_hinge, 0.98);  // |1 − 2 sin 80°| = 0.970 is the largest 10° off a hinge
  ASSERT_EQ(st.peak_angles_deg.size(), 3u);  // the field touches M0 at A, C and B only
  EXPECT_NEAR(st.peak_angles_deg[0], 0.0, 1e-9);
  EXPECT_NEAR(st.peak_angles_deg[1], 90.0, 1e-9);
  EXPECT_NEAR(st.peak_angles_deg[2], 180.0, 1e-9);
  EXPECT_GT(off_hinge, 0.96);
}

// Under the DeRuntz–Hodge load P0/cos φ of the flattened ring the arcs carry M linear in x
// from +M0 at the flat's edge to −M0 at C: ratio 1 (the mechanism is exact); a load below it
// scales the ratio (P R cos φ / 4 M0), a load above it exceeds M0 — the ring would need
// another hinge, and no field can help. Tolerance 5e-5: the drawn flat ends between two shape
// points and its edge is found by a parabola fit of the circular arc (1.1e-5 off at 48 points
// a quadrant; taking the last flat point instead, the lever arm is 2e-3–9e-3 off).
TEST(Level3Statics, DeRuntzHodgeLoadIsExactlyAtYieldOnTheFlattenedRing) {
  const double M0 = kRing.plastic_moment_nm, P0 = kRing.collapse_load();
  for (double phi : {0.2, 0.6, 1.0}) {
    const auto s = uniform_shape(phi);
    const auto at = level3_statics_check(s, P0 / std::cos(phi), M0);
    EXPECT_NEAR(at.peak_ratio, 1.0, 5e-5) << "φ = " << phi;
    const auto below = level3_statics_check(s, P0, M0);
    EXPECT_NEAR(below.peak_ratio, std::cos(phi), 5e-5) << "φ = " << phi;
    const auto above = level3_statics_check(s, 1.2 * P0 / std::cos(phi), M0);
    EXPECT_NEAR(above.peak_ratio, 1.2, 6e-5) << "φ = " << phi;
  }
}

// The contact edges: the outermost points of the flats (the travelling hinges' sites).
TEST(Level3Statics, ContactEdgesAreTheEndsOfTheFlats) {
  const double phi = 0.5;
  const auto s = uniform_shape(phi, 24);
  const auto c = level3_contact_edges(s);
  const double edge = kRing.mean_radius() * (1.0 - std::cos(phi));  // tangent point of the arc
  EXPECT_NEAR(c.top_edge[0], edge, 1e-3 * edge);
  EXPECT_NEAR(c.bottom_edge[0], edge, 1e-3 * edge);
  EXPECT_LT(s.points[c.top][0], edge);  // the last drawn flat point falls short of it
  EXPECT_LT(s.points[c.bottom][0], edge);
  const auto round = uniform_shape(0.0, 24);
  const auto r = level3_contact_edges(round);
  EXPECT_EQ(r.top, 0u);
  EXPECT_EQ(r.bottom, round.points.size() - 1);
}

TEST(Level3Statics, BadInputIsRejected) {
  const auto s = uniform_shape(0.0, 8);
  EXPECT_THROW(level3_statics_check(s, -1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(level3_statics_check(s, std::nan(""), 1.0), std::invalid_argument);
  EXPECT_THROW(level3_statics_check(s, 1.0, 0.0), std::invalid_argument);
  Level3Shape bad = s;
  bad.theta[3] = bad.theta[2];
  EXPECT_THROW(level3_statics_check(bad, 1.0, 1.0), std::invalid_argument);
  Level3Shape tiny;
  tiny.points = {{0.0, 0.0}, {1.0, 0.0}};
  tiny.theta = {0.0, 1.0};
  EXPECT_THROW(level3_statics_check(tiny, 1.0, 1.0), std::invalid_argument);
}

// In the chain: a plated rigid-perfectly-plastic chain flows DeRuntz–Hodge in every ring at
// the common force, so every ring's statics ratio over the run is 1 (at yield, never above);
// 5e-4: the flat-edge fit on the chain's 48-point shapes over φ up to 1.3 rad.
TEST(Level3Statics, PlatedChainRingsStayAtYield) {
  Level3Input in = ringcrush::hinge::testing::plated_three_rings();
  HybridOptions o;
  o.relative_tolerance = 1e-10;
  o.absolute_tolerance = 1e-12;
  o.end_time = 0.05;
  const auto r = simulate_level3(in, o);
  ASSERT_EQ(r.rings.size(), 3u);
  for (const auto& rr : r.rings) EXPECT_NEAR(rr.peak_moment_ratio, 1.0, 5e-4);
}
