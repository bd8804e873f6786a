// The arrival rule of the surface contact (fe/contact/contact_arrival.hpp; issue 4,
// verification g): a pair first seen deep is refused and adds no force or energy (the back-to-
// back crease: a node one wall depth behind its own leg's piece); a pair that arrived shallow
// keeps acting, from its side, past the old reach of one element depth (a node pushed deep is
// pushed back, not pulled through), across pieces of the C¹ surface and candidate-list
// rebuilds; only commit() changes the memory (a rejected HHT step or a Newton iterate leaves
// none); the tangent stays the derivative of the force; bad arrival depths are named errors.
//
// Geometry: a flat master surface y = 0 from x = −3 to 3 (six quadratic segments, Hermite
// junctions), its left normal +y (the slaves' side), and one slave node; element depth 1.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "fe/chain/chain_input.hpp"
#include "fe/contact/contact_arrival.hpp"
#include "fe/contact/ring_pair_contact.hpp"

using namespace ringcrush::fe;

namespace {

constexpr double kDepth = 1.0, kK = 1000.0, kArrival = 0.5;
constexpr int kSegments = 6;

// Nodes 1 … 2·kSegments + 1 on y = 0, x from −3 to 3; node 0 is the slave.
struct Flat {
  std::vector<ContactPass> passes;
  std::vector<Eigen::Vector2d> x;
};
Flat flat(double smoothing = 0.25) {
  Flat f;
  f.x.emplace_back(0.0, 1.0);
  for (int i = 0; i <= 2 * kSegments; ++i) f.x.emplace_back(-3.0 + 6.0 * i / (2 * kSegments), 0.0);
  ContactPass p;
  p.slave_ring = 0;
  p.master_ring = 1;
  p.slaves = {0};
  p.slave_k = {kK};
  p.slave_area = {1.0};
  std::vector<SurfaceSegment> chain;
  for (int s = 0; s < kSegments; ++s) chain.push_back({{1 + 2 * s, 2 + 2 * s, 3 + 2 * s}, -1});
  p.pieces = smoothed_chain(chain, smoothing);
  p.symmetric_end.assign(p.pieces.size(), 0);
  f.passes.push_back(p);
  return f;
}

struct Seen {
  int active = 0;
  double fy = 0, energy = 0;  // force on the slave (+y: pushed out), penalty energy
  ContactContribution c;
};
Seen at(SurfaceContact& contact, std::vector<Eigen::Vector2d>& x, double sx, double sy, bool tangent = false) {
  x[0] = {sx, sy};
  std::vector<ContactContribution> out;
  SurfaceContactState st;
  contact.evaluate(x, tangent, out, nullptr, st);
  Seen s;
  s.active = st.active;
  s.energy = st.energy;
  if (!out.empty()) {
    s.c = out.front();
    s.fy = -s.c.force(1);  // force(·) is the internal force ∂E/∂x; the node is pushed by −∂E/∂x
  }
  return s;
}

}  // namespace

TEST(ContactArrival, DeepFirstSightIsRefusedAndAddsNothing) {
  // A back-to-back crease: the node first seen 0.95 of the depth behind a piece (inside the
  // reach, which would act on it with k·0.95 and ½ k 0.95² of energy from nothing).
  Flat f = flat();
  SurfaceContact contact(f.passes, kDepth, kArrival);
  Seen s = at(contact, f.x, 0.1, -0.95);
  EXPECT_EQ(s.active, 0);
  EXPECT_EQ(s.energy, 0.0);
  contact.commit();
  EXPECT_EQ(contact.arrival().refused(), 1);
  EXPECT_NEAR(contact.arrival().deepest_refused().depth, 0.95, 1e-12);
  EXPECT_EQ(contact.arrival().deepest_refused().node, 0);
  EXPECT_EQ(contact.arrival().deepest_refused().master_ring, 1);
  // The crease opening toward the surface: still the same refused pair, still no force (it
  // would otherwise "arrive" at the arrival depth), and counted once.
  for (double y : {-0.8, -0.6, -0.4, -0.2, -0.05}) {
    s = at(contact, f.x, 0.1, y);
    EXPECT_EQ(s.active, 0) << y;
    contact.commit();
  }
  EXPECT_EQ(contact.arrival().refused(), 1);
  // Once the gap opens the pair is forgotten: a later approach from outside acts.
  at(contact, f.x, 0.1, 0.05);
  contact.commit();
  s = at(contact, f.x, 0.1, -0.05);
  EXPECT_EQ(s.active, 1);
  EXPECT_NEAR(s.fy, kK * 0.05, 1e-9);
  // Without the rule (arrival depth = the reach) the same first sight acts: the test can fail.
  Flat g = flat();
  SurfaceContact old_rule(g.passes, kDepth, kDepth);
  EXPECT_EQ(at(old_rule, g.x, 0.1, -0.95).active, 1);
}

TEST(ContactArrival, ShallowArrivalIsPushedBackPastTheReach) {
  Flat f = flat();
  SurfaceContact contact(f.passes, kDepth, kArrival);
  Seen s = at(contact, f.x, 0.1, 0.02);
  EXPECT_EQ(s.active, 0);
  contact.commit();
  // Driven in 0.1 at a time (each step committed) to 2.5 depths: the candidate list is
  // rebuilt on the way (the slave moves more than its skin) and the pair is beyond the
  // list's padding at the end.
  const long builds = contact.rebuilds();
  double previous = 0;
  for (int i = 1; i <= 25; ++i) {
    const double y = -0.1 * i;
    s = at(contact, f.x, 0.1, y);
    ASSERT_EQ(s.active, 1) << y;
    EXPECT_NEAR(s.fy, -kK * y, 1e-9 * kK) << y;          // from its side (+y) and k·|g|
    EXPECT_NEAR(s.energy, 0.5 * kK * y * y, 1e-9 * kK) << y;  // kept in the books
    EXPECT_GT(s.fy, previous) << y;                        // monotone in depth
    previous = s.fy;
    contact.commit();
  }
  EXPECT_GT(contact.rebuilds(), builds);
  EXPECT_EQ(contact.arrival().refused(), 0);
  // The old rule at the same place: beyond the reach, no force (the node would pass through).
  Flat g = flat();
  SurfaceContact fresh(g.passes, kDepth, kArrival);
  EXPECT_EQ(at(fresh, g.x, 0.1, -2.5).active, 0);
  // Coming back out: the force falls with the gap and the pair ends when it opens.
  s = at(contact, f.x, 0.1, -0.3);
  EXPECT_NEAR(s.fy, 0.3 * kK, 1e-9 * kK);
  contact.commit();
  EXPECT_EQ(at(contact, f.x, 0.1, 0.01).active, 0);
  contact.commit();
  EXPECT_EQ(at(contact, f.x, 0.1, -0.8).active, 0);  // a new, deep first sight
}

TEST(ContactArrival, PairFollowsItsClosestPointAcrossPieces) {
  // Arrived shallow, then held 0.8 deep (beyond the arrival depth, within the reach) while
  // sliding along the whole surface: the closest point crosses quadratic parts and Hermite
  // junctions, the pair stays the same and acts with k·0.8 throughout.
  Flat f = flat();
  SurfaceContact contact(f.passes, kDepth, kArrival);
  at(contact, f.x, -2.6, -0.1);
  contact.commit();
  for (double y = -0.2; y >= -0.8 - 1e-12; y -= 0.1) {
    ASSERT_EQ(at(contact, f.x, -2.6, y).active, 1);
    contact.commit();
  }
  for (double x = -2.6; x <= 2.6 + 1e-12; x += 0.05) {
    const Seen s = at(contact, f.x, x, -0.8);
    ASSERT_EQ(s.active, 1) << x;
    EXPECT_NEAR(s.fy, 0.8 * kK, 1e-9 * kK) << x;
    contact.commit();
  }
  EXPECT_EQ(contact.arrival().refused(), 0);
}

TEST(ContactArrival, OnlyCommitChangesTheMemory) {
  // An HHT step: Newton iterates (evaluations) then accepted (commit) or rejected (none).
  Flat f = flat();
  SurfaceContact contact(f.passes, kDepth, kArrival);
  at(contact, f.x, 0.1, 0.05);
  contact.commit();
  // Rejected: the iterates saw the node arrive at 0.1 but nothing was committed; the retry's
  // first iterate lands 0.8 deep: a first sight, refused, and no refusal counted either
  // until it is committed.
  EXPECT_EQ(at(contact, f.x, 0.1, -0.1).active, 1);
  EXPECT_EQ(at(contact, f.x, 0.1, -0.8).active, 0);
  EXPECT_EQ(contact.arrival().refused(), 0);
  at(contact, f.x, 0.1, 0.05);  // the retry's converged configuration: open
  contact.commit();
  EXPECT_EQ(contact.arrival().refused(), 0);
  // Accepted: the arrival at 0.1 is committed, so 0.55 deep is the same pair and acts.
  EXPECT_EQ(at(contact, f.x, 0.1, -0.1).active, 1);
  contact.commit();
  EXPECT_EQ(at(contact, f.x, 0.1, -0.55).active, 1);
  contact.commit();
  EXPECT_EQ(at(contact, f.x, 0.1, -0.8).active, 1);
  // Evaluating twice at the same place gives the same result (a function of x and the
  // committed memory only).
  const Seen a = at(contact, f.x, 0.3, -0.7), b = at(contact, f.x, 0.3, -0.7);
  EXPECT_EQ(a.fy, b.fy);
}

TEST(ContactArrival, AJumpOfTheGapIsAFirstSight) {
  // An acting pair whose gap moves by more than the arrival depth in one step has had its
  // closest point jump (a node past its partner's centre of curvature): judged as a first
  // sight, so it cannot bring ½ k (g² − g_n²) of energy from nothing (free 30 m/s ×4 t/D
  // 0.02: a node behind its ring's apex crease, its gap −1.02 → −2.43 depths in one step).
  Flat f = flat();
  SurfaceContact contact(f.passes, kDepth, kArrival);
  at(contact, f.x, 0.1, -0.1);
  contact.commit();
  at(contact, f.x, 0.1, -0.2);
  contact.commit();
  EXPECT_EQ(at(contact, f.x, 0.1, -0.65).active, 1);  // moved 0.45: the same pair
  const Seen s = at(contact, f.x, 0.1, -0.75);        // moved 0.55: refused
  EXPECT_EQ(s.active, 0);
  EXPECT_EQ(s.energy, 0.0);
  contact.commit();
  EXPECT_EQ(contact.arrival().refused(), 1);
  EXPECT_NEAR(contact.arrival().deepest_refused().depth, 0.75, 1e-12);
  // and stays refused while closed, also when it comes back within the arrival depth.
  EXPECT_EQ(at(contact, f.x, 0.1, -0.1).active, 0);
}

TEST(ContactArrival, TangentOfAPairPastTheReachIsTheForceDerivative) {
  Flat f = flat();
  SurfaceContact contact(f.passes, kDepth, kArrival);
  at(contact, f.x, 0.37, 0.01);
  contact.commit();
  for (double y = -0.1; y >= -1.5 - 1e-12; y -= 0.1) {
    ASSERT_EQ(at(contact, f.x, 0.37, y).active, 1);
    contact.commit();
  }
  // Bend the surface a little so the derivative is not trivial.
  f.x[7].y() += 0.05;
  const Seen s = at(contact, f.x, 0.37, -1.5, true);
  ASSERT_EQ(s.active, 1);
  const ContactContribution c = s.c;
  const double h = 1e-6;
  for (int j = 0; j < 2 * c.count; ++j) {
    const int node = c.nodes[j / 2], d = j % 2;
    std::vector<Eigen::Vector2d> x = f.x;
    x[0] = {0.37, -1.5};
    auto force_at = [&](double delta) {
      std::vector<Eigen::Vector2d> y = x;
      y[node][d] += delta;
      std::vector<ContactContribution> out;
      SurfaceContactState st;
      contact.evaluate(y, false, out, nullptr, st);
      EXPECT_EQ(out.size(), 1u);
      return out.front();
    };
    const ContactContribution p = force_at(h), m = force_at(-h);
    ASSERT_EQ(p.count, c.count);
    for (int i = 0; i < 2 * c.count; ++i)
      EXPECT_NEAR(c.tangent(i, j), (p.force(i) - m.force(i)) / (2 * h), 1e-4 * kK) << i << ' ' << j;
  }
}

TEST(ContactArrival, BadArrivalDepthsAreNamedErrors) {
  Flat f = flat();
  for (double bad : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    try {
      SurfaceContact contact(f.passes, kDepth, bad);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("arrival depth"), std::string::npos) << e.what();
    }
  }
  ChainInput in;
  for (double bad : {0.0, 1.5, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    in.contact.arrival_depth = bad;
    try {
      validate(in);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("contact arrival depth"), std::string::npos) << e.what();
    }
  }
  in.contact.arrival_depth = 1.0;
  EXPECT_NO_THROW(validate(in));
}
