// The fully plastic moment of the FE section through the wall, relative to M0 = σ0 t²/4
// (fe/element/through_wall_plastic_moment.hpp): the closed forms of each Gauss rule, the even
// counts that are exact, an odd count by hand, the selective rule's points across the wall
// read from the element itself, and the section moment the CPS8 elements carry in bending
// against the rule sum.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>
#include <stdexcept>

#include "fe/element/cps8_element.hpp"
#include "fe/element/cps8_rule_tables.hpp"
#include "fe/element/through_wall_plastic_moment.hpp"
#include "fe/material/j2_plane_stress.hpp"

using namespace ringcrush::fe;

namespace {

// The moment the CPS8 elements themselves carry across a straight wall of depth t, n elements
// through it, in a bending field u_x = κ x y, u_y = −κ x²/2 (ε_xx = κ y, ε_yy = γ = 0) far past
// yield: the work conjugate of κ, Σ_a f_a · ∂u_a/∂κ = Σ_points w σ_xx ∂E_xx/∂κ, which is the
// Gauss sum of σ_xx y over the section (per unit length of wall). Perfectly plastic material
// with a tiny yield strain (σ0/E = 1e-6), so that every point off the mid-surface is fully
// plastic (the innermost at 34 yield strains) while the geometry stays linear (outer fibre
// strain 0.03 %).
double element_section_moment(int through, Integration rule) {
  MaterialInput m;
  m.youngs_modulus_pa = 200e9;
  m.poisson_ratio = 0.3;
  m.hardening = {{0.2e6, 0.0}};
  const J2PlaneStress material(m);
  const double t = 1.6e-3, length = 2e-3, kappa = 2 * 3e-4 / t;
  double work = 0;
  for (int k = 0; k < through; ++k) {
    ElementCoords x;
    double du[16];
    for (int a = 0; a < 8; ++a) {
      const double xa = 0.5 * length * cps8_node_coords[a][0];
      const double ya = -0.5 * t + (k + 0.5 + 0.5 * cps8_node_coords[a][1]) * t / through;
      x(a, 0) = xa;
      x(a, 1) = ya;
      du[2 * a] = kappa * xa * ya;
      du[2 * a + 1] = -0.5 * kappa * xa * xa;
    }
    const Cps8Geometry geo = cps8_geometry(x, rule, 1.0);
    std::vector<PointState> committed(9), trial(9);
    Cps8Output out;
    cps8_evaluate(geo, du, committed.data(), trial.data(), material, true, out);
    for (int a = 0; a < 8; ++a) {
      const double xa = x(a, 0), ya = x(a, 1);
      work += out.force(2 * a) * xa * ya - out.force(2 * a + 1) * 0.5 * xa * xa;
    }
  }
  return work / length;
}

const double two_point = 2 / std::sqrt(3.0);                    // 2 · 1 · (1/√3)
const double three_point = 2 * (5.0 / 9.0) * std::sqrt(0.6);    // 2 · (5/9) · √0.6; the middle point has no arm
}  // namespace

TEST(ThroughWallPlasticMoment, OneElementMissesM0ByItsGaussRule) {
  EXPECT_NEAR(through_wall_plastic_moment(1, Integration::Reduced), 1.1547005383792517, 1e-14);
  EXPECT_NEAR(through_wall_plastic_moment(1, Integration::Reduced), two_point, 1e-15);
  EXPECT_NEAR(through_wall_plastic_moment(1, Integration::Full), 0.8606629658238705, 1e-14);
  EXPECT_NEAR(through_wall_plastic_moment(1, Integration::Full), three_point, 1e-15);
  EXPECT_NEAR(through_wall_plastic_moment(1, Integration::Selective), three_point, 1e-15);
}

// |ξ| is linear on an element that does not straddle the mid-surface: any even count is exact.
TEST(ThroughWallPlasticMoment, EvenCountsCarryM0Exactly) {
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective})
    for (int n : {2, 4, 6, 16}) EXPECT_NEAR(through_wall_plastic_moment(n, rule), 1.0, 1e-14) << n;
}

// Three elements through (by hand): the outer two are exact and carry 1 − 1/9 of M0; the middle
// one (half-depth 1/3) carries (1/3)² of the one-element factor. Five: (1/5)².
TEST(ThroughWallPlasticMoment, OddCountsErrOnTheMiddleElementOnly) {
  EXPECT_NEAR(through_wall_plastic_moment(3, Integration::Reduced), 8.0 / 9 + two_point / 9, 1e-14);
  EXPECT_NEAR(through_wall_plastic_moment(3, Integration::Reduced), 1.0171889487088057, 1e-14);
  EXPECT_NEAR(through_wall_plastic_moment(3, Integration::Full), 8.0 / 9 + three_point / 9, 1e-14);
  EXPECT_NEAR(through_wall_plastic_moment(3, Integration::Selective), 0.9845181073137633, 1e-14);
  EXPECT_NEAR(through_wall_plastic_moment(5, Integration::Reduced), 24.0 / 25 + two_point / 25, 1e-14);
  EXPECT_GT(std::abs(through_wall_plastic_moment(3, Integration::Reduced) - 1), 0.01);  // not exact
}

TEST(ThroughWallPlasticMoment, NoElementThroughIsANamedError) {
  for (int n : {0, -1}) {
    try {
      (void)through_wall_plastic_moment(n, Integration::Reduced);
      ADD_FAILURE() << n << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("elements_through"), std::string::npos) << e.what();
    }
  }
}

// The points across the wall come from the element's own rule tables: √(stress points).
// Selective: the stress points are the 3×3 ones, and its volumetric part, carried by the 2×2
// (Barlow) points, reaches each stress point through the bilinear interpolant M_r, which
// reproduces a through-wall coordinate exactly (Σ_r M_r(ξ_i) h_r = h_i): every part of the
// selective stress acts on the 3-point rule's moment arms.
TEST(ThroughWallPlasticMoment, PointsAcrossTheWallAreTheElementsOwn) {
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective}) {
    const Cps8RuleTables t = cps8_rule_tables(rule);
    EXPECT_EQ(gauss_points_through(rule) * gauss_points_through(rule), t.points);
  }
  ElementCoords x;  // a rectangle: 4 around (X) × the wall 1.6 (Y)
  for (int a = 0; a < 8; ++a) {
    x(a, 0) = 2.0 * cps8_node_coords[a][0];
    x(a, 1) = 0.8 * cps8_node_coords[a][1];
  }
  const Cps8Geometry geo = cps8_geometry(x, Integration::Selective, 1.0);
  const auto stress_points = gauss_rule(3);
  const auto barlow_points = gauss_rule(2);
  ASSERT_EQ(geo.points, 9);
  for (int i = 0; i < 9; ++i) {
    double h = 0, g = 0, sum = 0;
    for (int r = 0; r < 4; ++r) {
      h += geo.barlow(i, r) * barlow_points[r].h;
      g += geo.barlow(i, r) * barlow_points[r].g;
      sum += geo.barlow(i, r);
    }
    EXPECT_NEAR(h, stress_points[i].h, 1e-15) << i;
    EXPECT_NEAR(g, stress_points[i].g, 1e-15) << i;
    EXPECT_NEAR(sum, 1.0, 1e-15) << i;
  }
}

// The elements carry the factor the rule sum predicts: with one element through the wall the
// section moment is the rule's factor times the two-element one (which is exact), for reduced,
// full and selective alike — so the selective rule's 2×2 volumetric part does not change the
// 3-point moment arms; three elements carry their middle-element correction too.
TEST(ThroughWallPlasticMoment, TheElementsCarryTheFactor) {
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective}) {
    const double exact = element_section_moment(2, rule);
    const double factor = through_wall_plastic_moment(1, rule);
    std::printf("%s: M(1)/M(2) = %.5f (sum %.5f), M(3)/M(2) = %.5f (sum %.5f), M(4)/M(2) = %.6f\n",
                rule == Integration::Reduced ? "reduced" : rule == Integration::Full ? "full" : "selective",
                element_section_moment(1, rule) / exact, factor,
                element_section_moment(3, rule) / exact, through_wall_plastic_moment(3, rule),
                element_section_moment(4, rule) / exact);
    EXPECT_NEAR(element_section_moment(1, rule) / exact, factor, 2e-4);  // measured within 2e-5
    EXPECT_NEAR(element_section_moment(3, rule) / exact, through_wall_plastic_moment(3, rule), 2e-4);
    EXPECT_NEAR(element_section_moment(4, rule) / exact, 1.0, 2e-4);
  }
}
