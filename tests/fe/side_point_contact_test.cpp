// The inner wall's self contact at the side point C (φ = π/2; README "FE dynamics", stability
// matrix; issue 4 verification g): the inner node at C and the wall on both sides of it must be
// treated like every other point of the wall. The old split of the wall into a lower (y < 0)
// and an upper (y > 0) half left the node at C, y = 0, a slave of neither half, and ended both
// master surfaces at C, so a node pressed into the other leg of a closed side fold lost its
// whole force k·g when its closest point ran past C (HHT, welded and free chains, 100 m/s,
// ×4 impactor: half-step residuals of 6e5–3e6 N at ring 6's node C).
//
// Geometry as tests/fe/self_contact_taper_test.cpp: one 16-element half ring (Test 30, the
// matrix mesh), y → s·y, a flattened ring whose open side fold at C gives no contact; then one
// inner node is placed a depth p inside the wall at the point of parameter b of the flattened
// inner surface (r cos b, s r sin b): b > 0 on the upper leg, b < 0 on the lower one, so the
// node runs continuously around the fold. The default passes (both directions) throughout.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fe/chain/chain_mesh.hpp"
#include "fe/contact/ring_pair_contact.hpp"
#include "fe/contact/self_contact_taper.hpp"
#include "flattened_ring.hpp"

using namespace ringcrush::fe;

namespace {

using Fold = fixture::FlattenedRing;

// The default passes (both directions), the chain model's.
Fold make_fold() { return fixture::make_flattened_ring(kSelfContactTaperBandRad, ChainInput{}.contact.self_contact_two_pass); }

// The inner node nearest the reference angle φ (local id) and its penalty k = k_scale · w.
struct InnerNode {
  int local = -1;
  double arc_from_c = 0;  // φ − π/2
  double k = 0;
};
InnerNode inner_node_at(const Fold& fo, double phi) {
  const RingMesh& ring = fo.t.ring;
  InnerNode best;
  for (std::size_t i = 0; i < ring.inner_nodes.size(); ++i) {
    const int n = ring.inner_nodes[i];
    if (best.local < 0 || std::abs(ring.node_angle[n] - phi) < std::abs(best.arc_from_c + 0.5 * std::numbers::pi - phi)) {
      best.local = n;
      best.arc_from_c = ring.node_angle[n] - 0.5 * std::numbers::pi;
      best.k = fo.k_scale * ring.inner_weight[i];
    }
  }
  return best;
}

// A point a depth p inside the wall at parameter b of the flattened inner surface: b > 0 on
// the upper leg (arc b past C), b < 0 on the lower leg; the ellipse's outward normal points
// into the wall's material.
Eigen::Vector2d inside_wall(const Fold& fo, double b, double p) { return fixture::inside_flattened_wall(fo.r, b, p); }

struct Contact {
  // Contact force on the moved node as a slave, −∂E/∂x_s (ContactContribution::force is the
  // energy gradient). Moved, the node also drags the master pieces it belongs to through the
  // wall; what other nodes do against those is not the point here.
  Eigen::Vector2d node_force = Eigen::Vector2d::Zero();
  int as_slave = 0;
  double energy = 0;
  int active = 0;
  std::vector<ContactContribution> out;
};

Contact evaluate(const Fold& fo, const std::vector<Eigen::Vector2d>& x, int global) {
  SurfaceContact contact(fo.passes, fo.t.ring.element_depth);
  Contact c;
  SurfaceContactState st;
  contact.evaluate(x, false, c.out, nullptr, st);
  c.energy = st.energy;
  c.active = st.active;
  for (const auto& k : c.out)
    if (k.nodes[0] == global) {
      c.node_force -= Eigen::Vector2d(k.force(0), k.force(1));
      ++c.as_slave;
    }
  return c;
}

}  // namespace

TEST(SidePointContact, TheNodeAtCIsASlaveOfTheWall) {
  // The node at C pushed a quarter of the wall depth into the upper leg, then into the lower
  // leg, at 0.5 rad of arc from C (well beyond the exclusion and its taper): the full
  // penalty force k·p pushes it out, the same on both legs (no master/slave bias). The old
  // split gave it no force at all.
  const Fold fo = make_fold();
  const InnerNode c = inner_node_at(fo, 0.5 * std::numbers::pi);
  ASSERT_NEAR(c.arc_from_c, 0.0, 1e-12);
  ASSERT_GT(c.k, 0);
  const int g = fo.t.ring_node[0][c.local];
  ASSERT_EQ(evaluate(fo, fo.x, g).active, 0);  // the open fold alone: no contact
  const double p = 0.25 * fo.t.ring.element_depth;
  double magnitude[2] = {0, 0};
  for (int leg = 0; leg < 2; ++leg) {
    const double b = leg == 0 ? 0.5 : -0.5;
    std::vector<Eigen::Vector2d> x = fo.x;
    x[g] = inside_wall(fo, b, p);
    const Contact r = evaluate(fo, x, g);
    ASSERT_TRUE(std::isfinite(r.node_force.x()) && std::isfinite(r.node_force.y()));
    EXPECT_NEAR(r.node_force.norm(), c.k * p, 0.1 * c.k * p) << "leg " << leg;
    // Out of the leg's material, toward the hollow: down on the upper leg, up on the lower.
    EXPECT_LT(r.node_force.y() * b, 0.0) << "leg " << leg;
    magnitude[leg] = r.node_force.norm();
  }
  EXPECT_NEAR(magnitude[0], magnitude[1], 1e-6 * magnitude[0]);
}

TEST(SidePointContact, ForceIsContinuousAroundTheFold) {
  // The lower-leg node 0.295 rad below C (the corner node of the second element, as node
  // 446/450 of the failing cases) pressed a quarter depth into the other leg of the fold,
  // then carried round the fold tip onto its own leg: b from 0.5 (arc to its closest point
  // ≈ 0.8 rad, full force) through C (b = 0) down to −0.2 (arc ≈ 0.1, its own wall: no force).
  // The force must fall continuously through the taper (self_contact_taper.hpp), not drop
  // where the upper half's master surface used to end at C.
  const Fold fo = make_fold();
  const InnerNode s = inner_node_at(fo, 0.5 * std::numbers::pi - 0.295);
  ASSERT_NEAR(s.arc_from_c, -0.295, 0.01);
  const int g = fo.t.ring_node[0][s.local];
  const double sep = ContactInput{}.self_contact_min_separation_rad;
  const double p = 0.25 * fo.t.ring.element_depth;
  const double full = s.k * p;
  const int n = 350;
  const double b_hi = 0.5, b_lo = -0.2;
  Eigen::Vector2d previous = Eigen::Vector2d::Zero();
  double largest_jump = 0, jump_at = 0;
  for (int i = 0; i <= n; ++i) {
    const double b = b_hi - (b_hi - b_lo) * i / n;
    std::vector<Eigen::Vector2d> x = fo.x;
    x[g] = inside_wall(fo, b, p);
    const Contact c = evaluate(fo, x, g);
    ASSERT_TRUE(std::isfinite(c.node_force.x()) && std::isfinite(c.node_force.y())) << b;
    if (i == 0) {
      EXPECT_NEAR(c.node_force.norm(), full, 0.1 * full);
    } else if ((c.node_force - previous).norm() > largest_jump) {
      largest_jump = (c.node_force - previous).norm();
      jump_at = b;
    }
    // Its closest point on its own leg inside the exclusion: no force.
    if (-s.arc_from_c + b < sep - 0.02) {
      EXPECT_EQ(c.node_force.norm(), 0.0) << "b = " << b;
    }
    // Across C itself (arc ≈ 0.3 from the node, weight ≈ 1): still in contact.
    if (std::abs(b) < 0.01) {
      EXPECT_GT(c.node_force.norm(), 0.5 * full) << "b = " << b;
    }
    previous = c.node_force;
  }
  // 350 steps of 0.002 rad: the taper (slope ≤ 15 per rad) changes the force by at most
  // 0.03 k·p per step; the master surface ending at C dropped about k·p at once.
  EXPECT_LT(largest_jump, 0.08 * full) << "largest change per step at b = " << jump_at;
}

TEST(SidePointContact, PointsOfOneHalfArePaired) {
  // A side fold need not sit at C (the failing cases folded 0.15 rad below it): the lower-leg
  // node 0.59 rad below C pressed into the wall 0.1 rad below C (0.49 rad of arc away, both
  // points in the lower half y < 0) gets the full penalty force; the split paired no two
  // points of one half.
  const Fold fo = make_fold();
  const InnerNode s = inner_node_at(fo, 0.5 * std::numbers::pi - 0.59);
  ASSERT_NEAR(s.arc_from_c, -0.59, 0.01);
  const int g = fo.t.ring_node[0][s.local];
  const double p = 0.25 * fo.t.ring.element_depth;
  std::vector<Eigen::Vector2d> x = fo.x;
  x[g] = inside_wall(fo, -0.1, p);
  const Contact c = evaluate(fo, x, g);
  EXPECT_EQ(c.as_slave, 1);
  EXPECT_NEAR(c.node_force.norm(), s.k * p, 0.1 * s.k * p);
  EXPECT_GT(c.node_force.y(), 0.0);  // out of the lower leg's material, up into the hollow
}

TEST(SidePointContact, ForceAcrossCIsTheGradientOfTheEnergy) {
  // The wall is one C¹ surface through C now (a Hermite junction piece spans C): the contact
  // forces with the closest point on it, in the taper band or not, must stay the exact
  // gradient of the penalty energy (the HHT tangent is its central difference). Checked on
  // every node of the moved node's contact element, with all the contacts it makes (its own
  // pieces, dragged along, may touch other nodes).
  const Fold fo = make_fold();
  const InnerNode s = inner_node_at(fo, 0.5 * std::numbers::pi - 0.295);
  const int g = fo.t.ring_node[0][s.local];
  const double p = 0.25 * fo.t.ring.element_depth;
  for (double b : {0.05, 0.01, -0.03, -0.07}) {
    std::vector<Eigen::Vector2d> x = fo.x;
    x[g] = inside_wall(fo, b, p);
    const Contact c = evaluate(fo, x, g);
    ASSERT_EQ(c.as_slave, 1) << b;
    const ContactContribution* e = nullptr;
    for (const auto& k : c.out)
      if (k.nodes[0] == g) e = &k;
    // Σ over the contributions of the gradient at one dof of one node.
    auto gradient = [&](int node, int d) {
      double sum = 0;
      for (const auto& k : c.out)
        for (int i = 0; i < k.count; ++i)
          if (k.nodes[i] == node) sum += k.force(2 * i + d);
      return sum;
    };
    double scale = 0;
    for (int i = 0; i < 2 * e->count; ++i) scale = std::max(scale, std::abs(e->force(i)));
    ASSERT_GT(scale, 0.0);
    const double h = 1e-8;
    for (int i = 0; i < e->count; ++i)
      for (int d = 0; d < 2; ++d) {
        std::vector<Eigen::Vector2d> xp = x, xm = x;
        xp[e->nodes[i]][d] += h;
        xm[e->nodes[i]][d] -= h;
        const double de = (evaluate(fo, xp, g).energy - evaluate(fo, xm, g).energy) / (2 * h);
        EXPECT_NEAR(gradient(e->nodes[i], d), de, 1e-4 * scale) << "b " << b << " node " << i << " dof " << d;
      }
  }
}
