// The inner wall's self contact at the edge of its exclusion (fe/contact/self_contact_taper.hpp;
// README "FE dynamics", stability matrix): a node pressed into its own wall must lose its
// contact force continuously as its closest point approaches it along the wall, not all at
// once where the excluded arc begins (the HHT half-step residual cannot shrink across such a
// jump: free chain, 50 m/s, ×4 mass, t/D 0.03, 7.5e5 N at 6.30 ms).
//
// Geometry as tests/fe/fold_contact_test.cpp: one 16-element half ring (Test 30), y → s·y, a
// flattened ring whose open side fold at C (φ = π/2) gives no contact. Then the lower-wall
// node nearest C (reference arc a from C) is placed a fixed depth p inside the upper leg's
// material, above the upper leg's point at arc b past C, and b is swept from well outside the
// exclusion (arc a + b ≫ 0.2 rad) into it: the only contact is that node's.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fe/chain/chain_mesh.hpp"
#include "fe/contact/ring_pair_contact.hpp"
#include "fe/contact/self_contact_taper.hpp"
#include "flattened_ring.hpp"

using namespace ringcrush::fe;

namespace {

constexpr double kS = fixture::kFlattening;

struct Fold {
  ChainTopology t;
  std::vector<Eigen::Vector2d> x;  // the flattened ring
  int slave = -1;                  // lower inner node nearest C
  double a = 0;                    // its reference arc from C
  double r = 0;                    // inner radius
  double k = 0;                    // its penalty stiffness
  std::vector<ContactPass> passes;
};

Fold make_fold(double taper_band) {
  // One pass (lower nodes on the upper wall): the moved node is then only a slave.
  fixture::FlattenedRing f = fixture::make_flattened_ring(taper_band, false);
  Fold fo{std::move(f.t), std::move(f.x), -1, 0, f.r, 0, std::move(f.passes)};
  const ChainTopology& t = fo.t;
  const double half_pi = 0.5 * std::numbers::pi;
  for (std::size_t i = 0; i < t.ring.inner_nodes.size(); ++i) {
    const int node = t.ring.inner_nodes[i];
    const double phi = t.ring.node_angle[node];
    if (phi < half_pi - 1e-9 && (fo.slave < 0 || phi > half_pi - fo.a)) {
      fo.slave = node;
      fo.a = half_pi - phi;
    }
  }
  const ContactPass& pass = fo.passes.front();
  for (std::size_t s = 0; s < pass.slaves.size(); ++s)
    if (pass.slaves[s] == t.ring_node[0][fo.slave]) fo.k = pass.slave_k[s];
  return fo;
}

// The slave p inside the upper leg at arc b past C: the flattened leg (r cos b, s r sin b)
// and its normal into the leg's material.
Eigen::Vector2d slave_position(const Fold& fo, double b, double p) { return fixture::inside_flattened_wall(fo.r, b, p); }

struct Contact {
  Eigen::Vector2d slave_force = Eigen::Vector2d::Zero();
  double energy = 0;
  int active = 0;
  std::vector<ContactContribution> out;
};

Contact evaluate(const Fold& fo, const std::vector<Eigen::Vector2d>& x) {
  SurfaceContact contact(fo.passes, fo.t.ring.element_depth);
  Contact c;
  SurfaceContactState st;
  contact.evaluate(x, false, c.out, nullptr, st);
  c.energy = st.energy;
  c.active = st.active;
  const int g = fo.t.ring_node[0][fo.slave];
  for (const auto& k : c.out)
    for (int i = 0; i < k.count; ++i)
      if (k.nodes[i] == g) c.slave_force += Eigen::Vector2d(k.force(2 * i), k.force(2 * i + 1));
  return c;
}

}  // namespace

TEST(SelfContactTaper, WeightIsAC1RampFromTheExclusion) {
  const ArcTaper taper(0.2, 0.1);
  double slope = -1;
  EXPECT_EQ(taper.weight(0.1, &slope), 0.0);
  EXPECT_EQ(slope, 0.0);
  EXPECT_EQ(taper.weight(0.2), 0.0);
  EXPECT_EQ(taper.weight(0.35, &slope), 1.0);
  EXPECT_EQ(slope, 0.0);
  EXPECT_NEAR(taper.weight(0.25, &slope), 0.5, 1e-12);
  EXPECT_NEAR(slope, 15.0, 1e-9);  // 6 t (1 − t) / band at t = ½
  // Slope vs finite differences, and C¹ at the band's ends (slope → 0).
  for (double d : {0.201, 0.23, 0.27, 0.299}) {
    const double h = 1e-7;
    taper.weight(d, &slope);
    EXPECT_NEAR(slope, (taper.weight(d + h) - taper.weight(d - h)) / (2 * h), 1e-6) << d;
  }
  taper.weight(0.2 + 1e-6, &slope);
  EXPECT_LT(slope, 1e-3);
  taper.weight(0.3 - 1e-6, &slope);
  EXPECT_LT(slope, 1e-3);
  // Bare cut.
  const ArcTaper cut(0.2, 0.0);
  EXPECT_EQ(cut.weight(0.1999), 0.0);
  EXPECT_EQ(cut.weight(0.2001), 1.0);
}

TEST(SelfContactTaper, RejectsBadArcs) {
  EXPECT_THROW(ArcTaper(-0.1, 0.1), std::invalid_argument);
  EXPECT_THROW(ArcTaper(0.2, -0.1), std::invalid_argument);
  EXPECT_THROW(ArcTaper(0.2, std::nan("")), std::invalid_argument);
  Fold fo = make_fold(0.1);
  fo.passes.front().taper_band = -1;
  EXPECT_THROW(SurfaceContact(fo.passes, fo.t.ring.element_depth), std::invalid_argument);
}

TEST(SelfContactTaper, ForceIsContinuousAcrossTheExclusionEdge) {
  const Fold fo = make_fold(kSelfContactTaperBandRad);
  const double sep = ContactInput{}.self_contact_min_separation_rad;
  ASSERT_GT(fo.slave, -1);
  ASSERT_GT(fo.k, 0);
  ASSERT_LT(fo.a, 0.5 * sep);  // the node's partner across C starts inside the exclusion
  // The open fold alone: no contact.
  EXPECT_EQ(evaluate(fo, fo.x).active, 0);
  const double p = 0.25 * fo.t.ring.element_depth;
  const double full = fo.k * p;
  // b from 0.6 rad (a + b ≈ 0.68, far outside) down to 0.02: the closest point crosses the
  // end of every piece the old rule dropped whole.
  const int n = 300;
  const double b_hi = 0.6, b_lo = 0.02;
  Eigen::Vector2d previous = Eigen::Vector2d::Zero();
  double largest_jump = 0, jump_at = 0;
  for (int i = 0; i <= n; ++i) {
    const double b = b_hi - (b_hi - b_lo) * i / n;
    std::vector<Eigen::Vector2d> x = fo.x;
    x[fo.t.ring_node[0][fo.slave]] = slave_position(fo, b, p);
    const Contact c = evaluate(fo, x);
    ASSERT_TRUE(std::isfinite(c.slave_force.x()) && std::isfinite(c.slave_force.y())) << b;
    if (i == 0) {
      // Well outside: the full penalty force k·p (the leg is the ellipse only to the
      // interpolation of its nodes).
      EXPECT_NEAR(c.slave_force.norm(), full, 0.1 * full);
    } else if ((c.slave_force - previous).norm() > largest_jump) {
      largest_jump = (c.slave_force - previous).norm();
      jump_at = b;
    }
    // Inside the exclusion (closest point within the excluded arc): no force.
    if (fo.a + b < sep - 0.02) {
      EXPECT_EQ(c.slave_force.norm(), 0.0) << "b = " << b;
    }
    previous = c.slave_force;
  }
  // 300 steps of 0.0019 rad: the ramp over 0.1 rad of arc changes the force by at most
  // 1.5 · full · 0.0019 / 0.1 ≈ 0.03 full per step; the bare cut dropped all of k·p at once.
  EXPECT_LT(largest_jump, 0.08 * full) << "largest change per step at b = " << jump_at;
}

TEST(SelfContactTaper, TaperedForceIsTheGradientOfTheTaperedEnergy) {
  // In the band the force has a tangential part through w(Δ(f)); the energy ½ k w g² must be
  // its potential (energy balance and symmetric tangent), checked by central differences of
  // the total contact energy in every coordinate of the contact element.
  const Fold fo = make_fold(kSelfContactTaperBandRad);
  const double sep = ContactInput{}.self_contact_min_separation_rad, band = kSelfContactTaperBandRad;
  const double p = 0.25 * fo.t.ring.element_depth;
  std::vector<Eigen::Vector2d> x = fo.x;
  for (double arc : {sep + 0.3 * band, sep + 0.5 * band, sep + 0.8 * band}) {
    x[fo.t.ring_node[0][fo.slave]] = slave_position(fo, arc - fo.a, p);
    const Contact c = evaluate(fo, x);
    ASSERT_EQ(c.out.size(), 1u) << arc;
    const ContactContribution& e = c.out.front();
    const double h = 1e-8;
    double scale = 0;
    for (int i = 0; i < 2 * e.count; ++i) scale = std::max(scale, std::abs(e.force(i)));
    ASSERT_GT(scale, 0.0);
    for (int i = 0; i < e.count; ++i)
      for (int d = 0; d < 2; ++d) {
        std::vector<Eigen::Vector2d> xp = x, xm = x;
        xp[e.nodes[i]][d] += h;
        xm[e.nodes[i]][d] -= h;
        const double de = (evaluate(fo, xp).energy - evaluate(fo, xm).energy) / (2 * h);
        EXPECT_NEAR(e.force(2 * i + d), de, 1e-4 * scale) << "arc " << arc << " node " << i << " dof " << d;
      }
    // The part through w' is not negligible: the slave's force has a component along the
    // leg (a normal force alone would have none), so leaving it out fails the check above.
    const double b = arc - fo.a;
    const Eigen::Vector2d along = Eigen::Vector2d(-std::sin(b), kS * std::cos(b)).normalized();
    const Eigen::Vector2d fs(e.force(0), e.force(1));
    EXPECT_GT(std::abs(fs.dot(along)), 0.05 * fs.norm()) << arc;
  }
}
