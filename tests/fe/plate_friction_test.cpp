// Coulomb friction at the rigid plates (issue 3 item 4 "Coulomb friction as an option",
// fe/contact/plate_friction.hpp): the point law alone (stick/slip, reversal, dissipation,
// tangent, bad input), then the ring contact that carries the history (a ring pressed on the
// bottom plate and slid: total friction force μ N, consistent tangent, committed/trial
// history kept apart).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "fe/contact/plate_friction.hpp"
#include "fe/contact/ring_contact.hpp"
#include "fe/fe_input.hpp"
#include "fe/mesh/ring_mesh.hpp"

using namespace ringcrush::fe;

namespace {

constexpr double kN = 1e7;    // normal penalty (N/m)
constexpr double kT = 2e7;    // tangential penalty (N/m)
constexpr double kMu = 0.3;

// A node at height y over the bottom plate y = 0 (y < 0: penetration), f_n = k (0 − y).
PlateFriction at(double x, double y, double anchor_n) { return plate_friction(x, -kN * y, -kN, kT, kMu, anchor_n); }

}  // namespace

// (a) Pressed with N, slid forward: the friction force is −k_t x while |k_t x| < μN (stick)
// and exactly −μN once slipping; reversed: elastic unloading through zero to +μN, then slip
// backward at +μN.
TEST(PlateFriction, StickThenSlipThenReverse) {
  const double y = -1e-5, n = -kN * y, limit = kMu * n;  // N = 100 N, μN = 30 N
  double anchor = 0;
  int stick = 0, slip = 0;
  auto step = [&](double x, int direction) {
    const PlateFriction f = at(x, y, anchor);
    const double elastic = -kT * (x - anchor);
    if (std::abs(elastic) < limit * (1 - 1e-12)) {
      EXPECT_FALSE(f.slipping) << "x " << x;
      EXPECT_NEAR(f.traction, elastic, 1e-12 * limit);
      EXPECT_EQ(f.dissipation, 0.0);
      ++stick;
    } else if (std::abs(elastic) > limit * (1 + 1e-12)) {
      EXPECT_TRUE(f.slipping) << "x " << x;
      EXPECT_NEAR(f.traction, -direction * limit, 1e-8 * limit) << "x " << x;
      ++slip;
    }
    anchor = f.anchor;  // commit
    return f;
  };
  const double stick_travel = limit / kT;  // 1.5 µm
  for (int i = 1; i <= 100; ++i) step(10 * stick_travel * i / 100.0, +1);
  const double top = 10 * stick_travel;
  EXPECT_NEAR(anchor, top - stick_travel, 1e-15);
  for (int i = 1; i <= 200; ++i) step(top - 20 * stick_travel * i / 200.0, -1);
  EXPECT_NEAR(anchor, -10 * stick_travel + stick_travel, 1e-15);
  EXPECT_GT(stick, 20);  // 10 steps forward, 20 back through the elastic band
  EXPECT_GT(slip, 200);
}

// (c) The work dissipated is μ N × (slip distance), the slip distance being the travel less
// the elastic (stick) part μN/k_t taken up at each start and reversal.
TEST(PlateFriction, DissipationIsMuNTimesSlipDistance) {
  const double y = -2e-5, n = -kN * y, limit = kMu * n, elastic = limit / kT;
  double anchor = 0, dissipated = 0, stored = 0;
  const double travel = 40 * elastic;
  for (int i = 1; i <= 400; ++i) {
    const PlateFriction f = at(travel * i / 400.0, y, anchor);
    anchor = f.anchor;
    dissipated += f.dissipation;
    stored = f.stored_energy;
  }
  EXPECT_NEAR(dissipated, limit * (travel - elastic), 1e-10 * limit * travel);
  EXPECT_NEAR(stored, 0.5 * limit * elastic, 1e-10 * limit * elastic);
  // Back by twice the travel: the stored energy is released, then μN (2L − 2 μN/k_t) more.
  for (int i = 1; i <= 800; ++i) {
    const PlateFriction f = at(travel - 2 * travel * i / 800.0, y, anchor);
    anchor = f.anchor;
    dissipated += f.dissipation;
  }
  EXPECT_NEAR(dissipated, limit * (travel - elastic) + limit * (2 * travel - 2 * elastic), 1e-10 * limit * travel);
}

// (b) Consistent tangent of r_x = −t against central differences, in stick and in slip (the
// slip tangent couples to the normal displacement: ∂r_x/∂y = −μ sign ∂f_n/∂y).
TEST(PlateFriction, TangentMatchesFiniteDifferences) {
  const double y = -1e-5, h = 1e-12;
  for (double x : {0.5e-6, -0.8e-6, 4e-6, -7e-6}) {  // |k_t x| vs μN = 30 N: stick, stick, slip, slip
    const PlateFriction f = at(x, y, 0.0);
    EXPECT_EQ(f.slipping, std::abs(x) > 1.5e-6);
    const double dx = (-at(x + h, y, 0.0).traction + at(x - h, y, 0.0).traction) / (2 * h);
    const double dy = (-at(x, y + h, 0.0).traction + at(x, y - h, 0.0).traction) / (2 * h);
    EXPECT_NEAR(f.dr_dx, dx, 1e-6 * kT) << "x " << x;
    EXPECT_NEAR(f.dr_dy, dy, 1e-6 * kT) << "x " << x;
  }
}

// (g) Bad input is refused, naming the value.
TEST(PlateFriction, BadInputIsRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(plate_friction(0, 1, -1, kT, -0.1, 0), std::invalid_argument);
  EXPECT_THROW(plate_friction(0, 1, -1, kT, nan, 0), std::invalid_argument);
  EXPECT_THROW(plate_friction(0, 1, -1, 0.0, 0.2, 0), std::invalid_argument);
  EXPECT_THROW(plate_friction(nan, 1, -1, kT, 0.2, 0), std::invalid_argument);
  for (double mu : {-0.2, nan, std::numeric_limits<double>::infinity()}) {
    FeInput in;
    in.contact.friction_coefficient = mu;
    try {
      validate(in);
      FAIL() << "friction coefficient " << mu << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("friction coefficient"), std::string::npos) << e.what();
    }
  }
  FeInput in;
  in.contact.tangential_penalty_scale = -1;
  EXPECT_THROW(validate(in), std::invalid_argument);
}

namespace {

// A full ring (no symmetry) resting on the bottom plate, top plate far away; the ring is
// moved rigidly by (dx, −press) and its outer nodes slide on the bottom plate.
struct SlidingRing {
  RingInput ring;
  MeshInput mesh_in{16, 1, 1.0, false};
  RingMesh mesh = make_ring_mesh(ring, mesh_in);
  ContactInput ci = [] {
    ContactInput c;
    c.self_contact = false;
    c.friction_coefficient = kMu;
    return c;
  }();
  RingContact contact{mesh, ci, 202e9, 0.0125};
  double y_top = 1.0, y_bottom = -0.0254;
  std::vector<Eigen::Vector2d> place(double dx, double press) const {
    std::vector<Eigen::Vector2d> x = mesh.nodes;
    for (auto& p : x) p += Eigen::Vector2d(dx, -press);
    return x;
  }
  // Contact residual scattered over all dofs.
  Eigen::VectorXd residual(const std::vector<Eigen::Vector2d>& x, ContactState& st,
                           std::vector<ContactContribution>* keep = nullptr, bool tangent = false) {
    std::vector<ContactContribution> out;
    contact.evaluate(x, y_top, y_bottom, tangent, false, out, st);
    Eigen::VectorXd r = Eigen::VectorXd::Zero(2 * static_cast<int>(x.size()));
    for (const auto& c : out)
      for (int a = 0; a < c.count; ++a) {
        r(2 * c.nodes[a]) += c.force(2 * a);
        r(2 * c.nodes[a] + 1) += c.force(2 * a + 1);
      }
    if (keep) *keep = out;
    return r;
  }
};

}  // namespace

// (a) at the ring level: pressed, then slid far enough to slip everywhere, the total
// tangential force on the ring is μ × (total normal force) to 1e-8; a small slide sticks.
TEST(RingPlateFriction, SlidingRingCarriesMuTimesNormalForce) {
  SlidingRing s;
  const double press = 2e-6;
  ContactState st;
  s.residual(s.place(0, press), st);
  s.contact.commit();
  ASSERT_GE(st.plate_contacts, 1);
  const double normal = st.bottom_force;
  // A slide of 1 nm sticks: force below μ N, no dissipation.
  Eigen::VectorXd r = s.residual(s.place(1e-9, press), st);
  double fx = 0;
  for (int i = 0; i < r.size(); i += 2) fx += r(i);
  EXPECT_EQ(st.slipping_contacts, 0);
  EXPECT_GT(fx, 0);
  EXPECT_LT(fx, kMu * normal);
  EXPECT_EQ(st.friction_dissipation, 0.0);
  // A slide of 0.1 mm slips: the residual (−force on the ring) is +μN along x.
  r = s.residual(s.place(1e-4, press), st);
  fx = 0;
  for (int i = 0; i < r.size(); i += 2) fx += r(i);
  EXPECT_EQ(st.slipping_contacts, st.plate_contacts);
  EXPECT_NEAR(fx, kMu * st.bottom_force, 1e-8 * kMu * st.bottom_force);
  EXPECT_NEAR(st.bottom_friction_force, kMu * st.bottom_force, 1e-8 * kMu * st.bottom_force);
  EXPECT_NEAR(st.bottom_force, normal, 1e-12 * normal);  // a rigid slide keeps the normal force
}

// (b) The assembled contact tangent (stick and slip, with its non-symmetric normal coupling)
// against central differences of the assembled contact force, 1e-6 relative.
TEST(RingPlateFriction, TangentMatchesFiniteDifferencesInStickAndSlip) {
  for (double slide : {2e-10, 1e-5}) {  // stick, slip
    SlidingRing s;
    const double press = 2e-6;
    ContactState st;
    s.residual(s.place(0, press), st);
    s.contact.commit();
    auto x = s.place(slide, press);
    std::vector<ContactContribution> cs;
    s.residual(x, st, &cs, true);
    EXPECT_EQ(st.slipping_contacts > 0, slide > 1e-8);
    double scale = 0;
    for (const auto& c : cs) scale = std::max(scale, c.tangent.cwiseAbs().maxCoeff());
    for (const auto& c : cs) {
      const int node = c.nodes[0];
      for (int j = 0; j < 2; ++j) {
        // Steps well inside the stick band and the penetration keep the state unchanged.
        const double h = 1e-9;
        auto xp = x, xm = x;
        xp[node](j) += h;
        xm[node](j) -= h;
        ContactState sp, sm;
        const Eigen::VectorXd rp = s.residual(xp, sp), rm = s.residual(xm, sm);
        for (int i = 0; i < 2; ++i) {
          const double fd = (rp(2 * node + i) - rm(2 * node + i)) / (2 * h);
          EXPECT_NEAR(c.tangent(i, j), fd, 1e-6 * scale) << "node " << node << " slide " << slide << " (" << i << "," << j << ")";
        }
      }
    }
  }
}

// (d) A rejected increment leaves no trace: after evaluating a far slide without committing,
// the committed stick points are unchanged and the committed slide evaluates bit for bit as
// before; committing it then moves them.
TEST(RingPlateFriction, RejectedIncrementLeavesCommittedSlipUnchanged) {
  SlidingRing s;
  const double press = 2e-6;
  ContactState st;
  s.residual(s.place(0, press), st);
  s.contact.commit();
  const auto committed_slide = s.place(3e-5, press);
  const Eigen::VectorXd r1 = s.residual(committed_slide, st);
  s.contact.commit();
  const double dissipated = s.contact.committed_friction_dissipation();
  EXPECT_GT(dissipated, 0);
  std::vector<double> anchors;
  for (std::size_t i = 0; i < s.mesh.outer_nodes.size(); ++i) anchors.push_back(s.contact.committed_anchor(i, 1));
  ContactState rejected;
  s.residual(s.place(-5e-4, 3 * press), rejected);  // a trial that slips far the other way
  EXPECT_GT(rejected.friction_dissipation, dissipated);
  for (std::size_t i = 0; i < anchors.size(); ++i) EXPECT_EQ(s.contact.committed_anchor(i, 1), anchors[i]);
  EXPECT_EQ(s.contact.committed_friction_dissipation(), dissipated);
  ContactState again;
  const Eigen::VectorXd r2 = s.residual(committed_slide, again);
  EXPECT_EQ((r2 - r1).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(again.friction_dissipation, dissipated);
  // Committing a further slide does move the stick points of the slipping nodes.
  s.residual(s.place(6e-5, press), st);
  s.contact.commit();
  int moved = 0;
  for (std::size_t i = 0; i < anchors.size(); ++i) moved += s.contact.committed_anchor(i, 1) != anchors[i];
  EXPECT_GE(moved, st.slipping_contacts);
  EXPECT_GT(st.slipping_contacts, 0);
}
