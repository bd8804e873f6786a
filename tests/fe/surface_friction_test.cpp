// Coulomb friction of the inner wall against itself (issue 3 item 4): a slave node pressed
// into a master curve piece and slid. On a flat piece: stick, then μ f_n in slip, reversal,
// action = reaction. On a circular arc of three quadratic segments with the thesis's Hermite
// junction smoothing (§3.6.3): the slip is measured along the smoothed surface, so the work
// dissipated is μ f_n × (arc length slid − the elastic stick part), across the junctions.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "fe/contact/ring_contact.hpp"
#include "fe/contact/smoothed_surface.hpp"

using namespace ringcrush::fe;

namespace {
constexpr double kN = 1e6, kT = 5e5, kMu = 0.25;
const double kNone = std::numeric_limits<double>::quiet_NaN();
}  // namespace

// Flat piece y = 0 along +x (its left normal +y points into the void): a slave at y = −p
// penetrates by p. Slid along x it sticks (t = −k_t x) until |t| = μ k p, then slips at
// exactly μ k p; reversed, it unloads elastically and slips back. Forces sum to zero.
TEST(SurfaceFriction, FlatPieceStickSlipReverse) {
  CurvePiece piece;  // nodes only matter through the coordinates passed in
  piece.count = 3;
  const double p = 1e-5, fn = kN * p, limit = kMu * fn;
  double anchor = kNone;
  auto slide = [&](double x, double& t, bool& slipping) {
    double xy[8] = {x, -p, -1, 0, 0, 0, 1, 0}, force[8], gap, f = 0;
    SurfaceFriction fr;
    EXPECT_TRUE(self_contact_friction_force(piece, xy, kN, kT, kMu, anchor, 1.0, force, gap, f, fr));
    EXPECT_NEAR(gap, -p, 1e-15);
    double sx = 0, sy = 0;
    for (int i = 0; i < 4; ++i) { sx += force[2 * i]; sy += force[2 * i + 1]; }
    EXPECT_NEAR(sx, 0, 1e-12 * fn);
    EXPECT_NEAR(sy, 0, 1e-12 * fn);
    EXPECT_NEAR(force[0], -fr.traction, 1e-12 * fn);  // residual = −(force on the slave)
    anchor = fr.anchor;                                  // commit
    t = fr.traction;
    slipping = fr.slipping;
  };
  double t;
  bool slipping;
  slide(0.0, t, slipping);  // touch-down: sticks where it is, no force yet
  EXPECT_EQ(t, 0.0);
  const double elastic = limit / kT;
  slide(0.5 * elastic, t, slipping);
  EXPECT_FALSE(slipping);
  EXPECT_NEAR(t, -0.5 * limit, 1e-10 * limit);
  for (int i = 1; i <= 20; ++i) slide(0.5 * elastic + 5 * elastic * i / 20.0, t, slipping);
  EXPECT_TRUE(slipping);
  EXPECT_NEAR(t, -limit, 1e-8 * limit);
  const double top = 5.5 * elastic;
  slide(top - elastic, t, slipping);  // back by one elastic length: through zero to +μN/..
  EXPECT_FALSE(slipping);
  EXPECT_NEAR(t, 0.0, 1e-8 * limit);
  for (int i = 1; i <= 20; ++i) slide(top - elastic - 5 * elastic * i / 20.0, t, slipping);
  EXPECT_TRUE(slipping);
  EXPECT_NEAR(t, limit, 1e-8 * limit);
}

// A slave pressed 2e-3 into a unit circular arc made of three quadratic segments (Hermite
// junctions, α = 0.3) and carried around at constant radius over both junctions. The stick
// point is carried as the surface coordinate S = start_q + (f − lo) · surface_speed, as
// RingContact does. Dissipation against μ Σ f_n Δs, Δs the distance its closest point on the smoothed
// surface moved in the step, less μ f_n × the elastic stick length at the start.
TEST(SurfaceFriction, SlipIsMeasuredAlongTheSmoothedSurface) {
  std::vector<Eigen::Vector2d> x;
  for (int i = 0; i <= 6; ++i) x.emplace_back(std::cos(0.2 + 0.25 * i), std::sin(0.2 + 0.25 * i));
  const auto pieces = smoothed_chain({{{0, 1, 2}, 0}, {{2, 3, 4}, 1}, {{4, 5, 6}, 2}}, 0.3);
  std::vector<double> start{0.0};
  for (const auto& q : pieces) start.push_back(start.back() + (q.hi - q.lo) * surface_speed(q));
  const double radius = 1.002;  // outside the CCW arc = penetrating (the void is inside)
  double anchor_s = kNone, dissipated = 0, fn_sum = 0, last_t = 0, last_fn = 0, expected = 0, first_fn = 0;
  Eigen::Vector2d last_closest = Eigen::Vector2d::Zero();
  int steps = 0, used_junctions = 0;
  const double from = 0.4, to = 1.55;
  const int n = 2000;
  for (int i = 0; i <= n; ++i) {
    const double a = from + (to - from) * i / n;
    const Eigen::Vector2d xs = radius * Eigen::Vector2d(std::cos(a), std::sin(a));
    int best = -1;
    double best_gap = 0, best_f = 0;
    for (std::size_t q = 0; q < pieces.size(); ++q) {
      double xy[12] = {xs.x(), xs.y()}, force[12], gap = 0, f = -10;
      for (int k = 0; k < pieces[q].count; ++k) {
        xy[2 + 2 * k] = x[pieces[q].nodes[k]].x();
        xy[3 + 2 * k] = x[pieces[q].nodes[k]].y();
      }
      if (self_contact_force(pieces[q], xy, kN, 1.0, force, gap, f) && (best < 0 || std::abs(gap) < std::abs(best_gap))) {
        best = static_cast<int>(q);
        best_gap = gap;
        best_f = f;
      }
    }
    ASSERT_GE(best, 0) << "angle " << a;
    const CurvePiece& pc = pieces[best];
    used_junctions += pc.count == 5;
    double xy[12] = {xs.x(), xs.y()}, force[12], gap, f = best_f;
    for (int k = 0; k < pc.count; ++k) {
      xy[2 + 2 * k] = x[pc.nodes[k]].x();
      xy[3 + 2 * k] = x[pc.nodes[k]].y();
    }
    const double w = surface_speed(pc), s0 = start[static_cast<std::size_t>(best)];
    const double anchor_f = std::isnan(anchor_s) ? kNone : pc.lo + (anchor_s - s0) / w;
    SurfaceFriction fr;
    ASSERT_TRUE(self_contact_friction_force(pc, xy, kN, kT, kMu, anchor_f, 1.0, force, gap, f, fr));
    anchor_s = s0 + (fr.anchor - pc.lo) * w;
    dissipated += fr.dissipation;
    double c[5], dc[5], ddc[5];
    pc.coefficients(f, c, dc, ddc);
    Eigen::Vector2d closest = Eigen::Vector2d::Zero();
    for (int k = 0; k < pc.count; ++k) closest += c[k] * x[pc.nodes[k]];
    if (i > 0) {
      fn_sum += -kN * gap;
      expected += kMu * (-kN * gap) * (closest - last_closest).norm();
      ++steps;
    } else {
      first_fn = -kN * gap;
    }
    last_closest = closest;
    last_t = fr.traction;
    last_fn = -kN * gap;
  }
  EXPECT_GT(used_junctions, 100);
  const double fn_mean = fn_sum / steps;
  // The slave moves along the circle of radius 1.002; its projection on the (nearly unit)
  // surface moves by Δθ × 1.
  const double slid = to - from;
  const double elastic = kMu * fn_mean / kT;
  EXPECT_NEAR(last_t, -kMu * last_fn, 1e-8 * kMu * last_fn);  // slipping backward-forward: −μ f_n
  // f_n varies by a few % along the smoothed fit of the circle, hence the looser check here.
  EXPECT_NEAR(dissipated, kMu * fn_mean * (slid - elastic), 3e-2 * kMu * fn_mean * slid);
  // Step by step along the smoothed surface: exact but for the stick length at the start.
  expected -= kMu * first_fn * (kMu * first_fn / kT);
  EXPECT_NEAR(dissipated, expected, 1e-4 * expected);
}
