// Contact pieces alone: the Hermite-smoothed master surface (thesis §3.6.3) is C¹ across
// segment junctions, the node-to-surface gap varies continuously as a node slides over a
// junction, the contact force is the gradient of the penalty energy, and a ring mesh reports
// no initial overlaps.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fe/contact/ring_contact.hpp"
#include "fe/contact/smoothed_surface.hpp"
#include "fe/mesh/ring_mesh.hpp"

using namespace ringcrush::fe;

namespace {
// Three quadratic segments on a circle arc of radius 1 (counter-clockwise), node coords.
std::vector<Eigen::Vector2d> arc_nodes() {
  std::vector<Eigen::Vector2d> x;
  for (int i = 0; i <= 6; ++i) {
    const double a = 0.2 + 0.25 * i;
    x.emplace_back(std::cos(a), std::sin(a));
  }
  return x;
}
std::vector<SurfaceSegment> arc_chain() {
  return {{{0, 1, 2}, 0}, {{2, 3, 4}, 1}, {{4, 5, 6}, 2}};
}
void eval(const CurvePiece& p, const std::vector<Eigen::Vector2d>& x, double f, Eigen::Vector2d& pos,
          Eigen::Vector2d& tan) {
  double c[5], dc[5], ddc[5];
  p.coefficients(f, c, dc, ddc);
  pos.setZero();
  tan.setZero();
  for (int k = 0; k < p.count; ++k) {
    pos += c[k] * x[p.nodes[k]];
    tan += dc[k] * x[p.nodes[k]];
  }
}
}  // namespace

TEST(SmoothedSurface, PiecesJoinWithContinuousPositionAndTangent) {
  const auto x = arc_nodes();
  for (double alpha : {0.1, 0.25, 0.4}) {
    const auto pieces = smoothed_chain(arc_chain(), alpha);
    ASSERT_EQ(pieces.size(), 5u);  // 3 quadratic parts + 2 Hermite junctions
    for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
      Eigen::Vector2d pa, ta, pb, tb;
      eval(pieces[i], x, pieces[i].hi, pa, ta);
      eval(pieces[i + 1], x, pieces[i + 1].lo, pb, tb);
      EXPECT_LT((pa - pb).norm(), 1e-14) << "alpha " << alpha << " joint " << i;
      // Tangent direction continuous (parameter speeds differ by the 2α scaling).
      EXPECT_LT(std::abs(ta.normalized().dot(tb.normalized()) - 1.0), 1e-12) << "alpha " << alpha;
    }
  }
}

TEST(SmoothedSurface, GapIsContinuousAcrossAJunction) {
  const auto x = arc_nodes();
  const auto pieces = smoothed_chain(arc_chain(), 0.25);
  // A slave node just outside the arc (toward the centre = the void side of a CCW inner
  // wall) slides over the junction at node 2; the gap follows the distance to the curve.
  double prev = NAN;
  for (int k = 0; k <= 200; ++k) {
    const double a = 0.55 + 0.3 * k / 200.0;
    const Eigen::Vector2d xs = 0.999 * Eigen::Vector2d(std::cos(a), std::sin(a));
    double best = 1e300, gap_best = 0;
    for (const auto& p : pieces) {
      double coords[12];
      coords[0] = xs.x();
      coords[1] = xs.y();
      for (int n = 0; n < p.count; ++n) {
        coords[2 + 2 * n] = x[p.nodes[n]].x();
        coords[3 + 2 * n] = x[p.nodes[n]].y();
      }
      double force[12], gap = NAN, f = -10;
      // The gap is set whenever the node projects inside the piece (whatever its sign).
      self_contact_force(p, coords, 1.0, 1.0, force, gap, f);
      if (!std::isnan(gap) && std::abs(gap) < best) {
        best = std::abs(gap);
        gap_best = gap;
      }
    }
    EXPECT_GT(gap_best, 0.0);  // in the void: no contact
    EXPECT_NEAR(gap_best, 1e-3, 3e-4);
    if (!std::isnan(prev)) {
      EXPECT_LT(std::abs(gap_best - prev), 2e-5);
    }
    prev = gap_best;
  }
}

TEST(SelfContact, ForceIsTheGradientOfThePenaltyEnergy) {
  const auto x = arc_nodes();
  const auto pieces = smoothed_chain(arc_chain(), 0.25);
  // A node penetrating the wall (outside the unit circle) near the Hermite junction.
  int checked = 0;
  for (const auto& p : pieces) {
    double coords[12];
    const double a = 0.7;
    coords[0] = 1.002 * std::cos(a);
    coords[1] = 1.002 * std::sin(a);
    for (int n = 0; n < p.count; ++n) {
      coords[2 + 2 * n] = x[p.nodes[n]].x();
      coords[3 + 2 * n] = x[p.nodes[n]].y();
    }
    double force[12], gap = 0, f = -10;
    const double k = 1e6;
    if (!self_contact_force(p, coords, k, 0.1, force, gap, f)) continue;
    ASSERT_LT(gap, 0.0);
    ++checked;
    auto energy = [&](double* c) {
      double fo[12], g = 0, ff = -10;
      self_contact_force(p, c, k, 0.1, fo, g, ff, false);
      return g < 0 ? 0.5 * k * g * g : 0.0;
    };
    const double h = 1e-8;
    for (int j = 0; j < 2 + 2 * p.count; ++j) {
      const double keep = coords[j];
      coords[j] = keep + h;
      const double ep = energy(coords);
      coords[j] = keep - h;
      const double em = energy(coords);
      coords[j] = keep;
      EXPECT_NEAR(force[j], (ep - em) / (2 * h), 1e-5 * std::abs(k * gap)) << "component " << j;
    }
  }
  EXPECT_GE(checked, 1);
}

TEST(RingContact, UnloadedRingHasNoOverlapsAndTouchesBothPlates) {
  RingInput ring;
  for (bool half : {true, false}) {
    MeshInput mi;
    mi.elements_around = 24;
    mi.elements_through = 2;
    mi.grading = 2.0;
    mi.half_ring = half;
    const RingMesh m = make_ring_mesh(ring, mi);
    ContactInput ci;
    RingContact contact(m, ci, 202e9, 0.0125);
    std::vector<ContactContribution> out;
    ContactState st;
    contact.evaluate(m.nodes, ring.outer_radius_m, -ring.outer_radius_m, true, true, out, st);
    EXPECT_EQ(st.plate_contacts, 0);
    EXPECT_EQ(st.self_contacts, 0);
    EXPECT_EQ(st.max_plate_penetration, 0.0);
    EXPECT_EQ(out.size(), 2u);  // the two touching points carry stiffness, no force
    // Graded mesh: elements finest at contact and side, `grading` times coarser between.
    const auto a = graded_angles(24, std::numbers::pi, 2.0);
    EXPECT_NEAR((a[6] - a[5]) / (a[1] - a[0]), 2.0, 0.1);
  }
}
