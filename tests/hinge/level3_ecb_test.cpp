// Level 3 E–C–B as a flowing mechanism of the ring underneath a wrap (hinge/level3_ecb.hpp;
// issue 7 item 2): its onset against h16's closed form, its work against ∫ P dδ, its drawn
// geometry (rigid E–C and C–B′, cap untouched, B′ on its line), and the chain's least-load
// choice between it and the bottom mechanism.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "compare/hinge_run_level3.hpp"
#include "compare/scene.hpp"
#include "hinge/level3_ecb.hpp"
#include "hinge/level3_mechanism.hpp"
#include "hinge/level3_travelling_e.hpp"
#include "test_files.hpp"

using namespace ringcrush::hinge;
using std::numbers::pi;

namespace {

const Level3Ring kRing{0.0508, 0.0016, 2.184, 1.358};  // Test 30 ring
const Level3Ring kRigidPlastic{0.0508, 0.0016, 2.184, 0.0};

// h16's onset closed form on the circle (level3_travelling_e.hpp), no hardening.
double onset_closed_form(double th) {
  return 4.0 * kRing.plastic_moment_nm / kRing.mean_radius() * (1.0 + std::cos(th)) /
         (1.0 + std::cos(th) - std::sin(th));
}

Level3Input chain(double velocity, int rings = 6) {
  Level3Input in;
  in.rings = rings;
  in.ring = kRing;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = velocity;
  return in;
}

HybridOptions options() {
  HybridOptions o;
  o.relative_tolerance = 1e-10;
  o.absolute_tolerance = 1e-12;
  o.end_time = 0.05;
  return o;
}

bool has_switch(const Level3Result& r, int ring) {
  for (const auto& e : r.events)
    if (e.kind == "mode_selected" && e.ring == ring && e.detail.find("E-C-B") != std::string::npos) return true;
  return false;
}

}  // namespace

// Onset on the undeformed circle: the finite-rotation trace starts at h16's virtual-work
// load, P = (4M0/R)(1 + cos θ_E)/(1 + cos θ_E − sin θ_E), and at level3_e_rate's on a drawn
// crushed shape (hardening 1 + kψ at C and B′).
TEST(Level3Ecb, OnsetMatchesTheClosedFormAndTheDrawnShapeRate) {
  for (double deg : {0.0, 15.0, 30.0, 45.0, 70.0}) {
    const double th = deg * pi / 180.0;
    EXPECT_NEAR(level3_ecb_onset_load(kRigidPlastic, 0.0, 0.0, th) / onset_closed_form(th), 1.0, 1e-12) << deg;
    const auto m = level3_ecb_mechanism(kRigidPlastic, 0.0, 0.0, th);
    EXPECT_NEAR(m.load.front() / onset_closed_form(th), 1.0, 1e-12) << deg;
  }
  const double phi = 0.6, psi = 0.4, th = 0.7;
  Level3RingResult st;
  st.uniform_angle = phi;
  st.reinforced = true;
  st.bottom_angle = psi;
  const auto shape = level3_ring_shape(kRing, WrapMechanism{}, st, 0.0, 400);
  const auto e = level3_e_rate(shape, kRing.plastic_moment_nm, th, 1.0 + kRing.hardening_k * psi);
  EXPECT_NEAR(level3_ecb_onset_load(kRing, phi, psi, th) / e.load, 1.0, 1e-3);
  EXPECT_THROW(level3_ecb_onset_load(kRing, phi, psi, 1.6), std::invalid_argument);
  // From the top flat's edge of a DeRuntz–Hodge state (θ_E = φ = ψ) without hardening the
  // E–C–B starts at the bottom mechanism's load P0/cos ψ exactly (the two are the same
  // instantaneous motion of a symmetric ring); once the bottom has flowed on (ψ > φ) E–C–B
  // is the cheaper by geometry alone.
  for (double a : {0.2, 0.6, 1.0}) {
    const double bottom = kRigidPlastic.collapse_load() / std::cos(a);
    EXPECT_NEAR(level3_ecb_onset_load(kRigidPlastic, a, a, a) / bottom, 1.0, 1e-12) << a;
    EXPECT_LT(level3_ecb_onset_load(kRigidPlastic, a, a + 0.15, a), kRigidPlastic.collapse_load() / std::cos(a + 0.15)) << a;
  }
  // With Redwood hardening: E on the flat's edge carries the uniform mechanism's 1 + kφ, so
  // from ψ = φ the two loads are equal again (an E counted as a fresh hinge would be cheaper
  // by hardening bookkeeping alone: the test fails with e_start = 0); E out on the rigid
  // quadrant is a fresh hinge.
  for (double a : {0.2, 0.6, 1.0}) {
    const double bottom = kRing.collapse_load() * (1.0 + kRing.hardening_k * a) / std::cos(a);
    EXPECT_NEAR(level3_ecb_onset_load(kRing, a, a, a) / bottom, 1.0, 1e-12) << a;
    EXPECT_DOUBLE_EQ(level3_ecb_points(kRing, a, a, a).e_start, a);
    EXPECT_DOUBLE_EQ(level3_ecb_points(kRing, a, a, a + 0.1).e_start, 0.0);
  }
  EXPECT_THROW(level3_ecb_mechanism(kRing, -0.1, psi, th), std::invalid_argument);
}

// Along the trace: the nodal loads are dD/dδ of the closed-form dissipation (central
// differences), the work the chain integrates (the Hermite load's integral) equals ∫ P dδ by
// quadrature and the closed-form dissipation D(δ).
TEST(Level3Ecb, WorkIsTheIntegralOfTheLoad) {
  for (const auto& ring : {kRigidPlastic, kRing}) {
    const auto m = level3_ecb_mechanism(ring, 0.6, 0.4, 0.7);
    ASSERT_GT(m.crush.size(), 50u);
    for (std::size_t j = 1; j + 1 < m.crush.size(); j += 10) {
      const double fd = (m.dissipation[j + 1] - m.dissipation[j - 1]) / (m.crush[j + 1] - m.crush[j - 1]);
      EXPECT_NEAR(fd / m.load[j], 1.0, 1e-3) << j;
    }
    const double cap = m.capacity();
    const int n = 20000;  // composite Simpson
    double simpson = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double w = k == 0 || k == n ? 1.0 : k % 2 ? 4.0 : 2.0;
      simpson += w * m.load_at(cap * k / n);
    }
    simpson *= cap / (3.0 * n);
    EXPECT_NEAR(m.energy_at(cap) / simpson, 1.0, 1e-6);
    EXPECT_NEAR(m.energy_at(cap) / m.dissipation.back(), 1.0, 1e-4);
    const std::size_t mid = m.crush.size() / 2;
    EXPECT_NEAR(m.energy_at(m.crush[mid]) / m.dissipation[mid], 1.0, 1e-4);
  }
}

// The drawn E–C–B state: the cap A–E as before, E–C and C–B′ rigid (every point at its
// distance from E, resp. from the turned C), B′ on its vertical line, and the ring's height
// shortened by the E–C–B crush.
TEST(Level3Ecb, ShapeTurnsRigidSegmentsAndKeepsTheCap) {
  const double phi = 0.6, psi = 0.4, th = 0.7;
  const auto m = level3_ecb_mechanism(kRing, phi, psi, th);
  Level3RingResult st;
  st.uniform_angle = phi;
  st.reinforced = true;
  st.bottom_angle = psi;
  const auto before = level3_ring_shape(kRing, WrapMechanism{}, st, 0.0, 48);
  const double d = 0.6 * m.capacity();
  st.ecb_started = true;
  st.mode = Level3Mode::Ecb;
  st.ecb_crush_m = d;
  st.ecb_theta_e = th;
  st.ecb_psi = psi;
  st.ecb_rotation_cb = m.q_at(d);
  st.ecb_rotation_e = m.beta_at(d);
  const auto after = level3_ring_shape(kRing, WrapMechanism{}, st, 0.0, 48);
  ASSERT_EQ(after.points.size(), before.points.size() + 1);  // E inserted
  EXPECT_NEAR(after.bottom_y - before.bottom_y, d, 1e-3 * d);
  const auto p = level3_ecb_points(kRing, phi, psi, th);
  std::size_t ke = 0, kc = 0;
  for (std::size_t k = 0; k < after.theta.size(); ++k) {
    if (std::abs(after.theta[k] - th) < 1e-12) ke = k;
    if (std::abs(after.theta[k] - 0.5 * pi) < 1e-12) kc = k;
  }
  ASSERT_GT(ke, 0u);
  ASSERT_GT(kc, ke);
  const double R = kRing.mean_radius(), tol = 1e-9 * R;
  const double off = before.points[0][1] - (R - R * std::sin(phi));  // shape frame − ring frame
  const std::array<double, 2> e{p.e[0], p.e[1] + off}, c0{p.c[0], p.c[1] + off};
  EXPECT_NEAR(after.points[ke][0], e[0], tol);
  EXPECT_NEAR(after.points[ke][1], e[1], tol);
  for (std::size_t k = 0; k < ke; ++k) {  // the cap is held
    EXPECT_NEAR(after.points[k][0], before.points[k][0], tol);
    EXPECT_NEAR(after.points[k][1], before.points[k][1], tol);
  }
  auto dist = [](const std::array<double, 2>& a, const std::array<double, 2>& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); };
  for (std::size_t k = ke + 1; k <= kc; ++k)  // E–C rigid about E (after's k is before's k − 1)
    EXPECT_NEAR(dist(after.points[k], e), dist(before.points[k - 1], e), tol) << k;
  EXPECT_NEAR(dist(before.points[kc - 1], c0), 0.0, tol);
  const double turned = std::atan2(after.points[kc][1] - e[1], after.points[kc][0] - e[0]) -
                        std::atan2(c0[1] - e[1], c0[0] - e[0]);
  EXPECT_NEAR(turned, st.ecb_rotation_e, 1e-3);
  const double flat_from = pi - psi;
  for (std::size_t k = kc; k < after.points.size(); ++k) {
    if (after.theta[k] >= flat_from - 1e-12) {  // the flat: level at B′
      EXPECT_NEAR(after.points[k][1], after.bottom_y, tol);
      EXPECT_NEAR(after.points[k][0], before.points[k - 1][0], tol);
    } else {  // C–B′ rigid: distances to the turned C kept
      EXPECT_NEAR(dist(after.points[k], after.points[kc]), dist(before.points[k - 1], before.points[kc - 1]), tol) << k;
    }
  }
}

// The chain's choice for the ring underneath (2 rings, ring 1 wraps over ring 2): with E at
// the held cap's edge E–C–B is cheaper than the bottom mechanism and is selected — the switch
// is an event with both loads, the hinge map lists E turning; with E fixed far down the
// quadrant (80°) it is dearer and ring 2 keeps the bottom mechanism.
TEST(Level3Ecb, ChainPicksTheCheaperMechanismOfTheRingUnderneath) {
  auto in = chain(45.0, 2);
  in.hinge_e = Level3HingeE::ShearFree;
  const auto cheap = simulate_level3(in, options());
  ASSERT_TRUE(cheap.rings[0].wrap_started);
  EXPECT_EQ(cheap.rings[1].mode, Level3Mode::Ecb);
  // The held cap's edge lies on ring 2's top flat: E moved out to the flat's edge φ.
  EXPECT_NEAR(cheap.rings[1].ecb_theta_e, cheap.rings[1].uniform_angle, 1e-12);
  EXPECT_TRUE(has_switch(cheap, 1));
  bool turned = false;
  for (const auto& h : cheap.rings[1].hinges)
    if (h.name == "E" && h.first_yield_s > 0.0) {
      turned = true;
      EXPECT_GT(h.rotation_rad, 0.0);
      EXPECT_NEAR(h.angle_deg, cheap.rings[1].ecb_theta_e * 180.0 / pi, 1e-9);
    }
  EXPECT_TRUE(turned);
  EXPECT_LT(cheap.energy_balance_error(), 1e-6);

  in.hinge_e = Level3HingeE::Fixed;
  in.theta_e = 80.0 * pi / 180.0;
  const auto dear = simulate_level3(in, options());
  ASSERT_TRUE(dear.rings[0].wrap_started);
  // At the reinforcement E–C–B with E at 80° needs more than the bottom mechanism…
  const auto& h = dear.history;
  std::size_t k0 = 0;
  while (k0 < h.time_s.size() && !h.ring_state[k0][1].reinforced) ++k0;
  ASSERT_LT(k0, h.time_s.size());
  const auto& s = h.ring_state[k0][1];
  const double bottom = kRing.collapse_load() * (1.0 + kRing.hardening_k * s.bottom_angle) / std::cos(s.bottom_angle);
  EXPECT_GT(level3_ecb_onset_load(kRing, s.uniform_angle, s.bottom_angle, in.theta_e), 1.2 * bottom);
  // …so ring 2 flows in the bottom mechanism (once ring 1's wrap has run), and turns E only
  // later, if at all,
  // where E–C–B has become the cheaper (its switch event then lists both loads).
  double bottom_from = -1.0, switch_at = -1.0;
  for (const auto& e : dear.events) {
    if (e.ring != 1) continue;
    if (e.kind == "hinge_formed" && e.detail.find("bottom") != std::string::npos) bottom_from = e.time_s;
    if (e.kind == "mode_selected" && e.detail.find("E-C-B") != std::string::npos) switch_at = e.time_s;
  }
  EXPECT_GE(bottom_from, h.time_s[k0]);  // when ring 1's softening wrap has locked
  if (switch_at >= 0.0) {
    EXPECT_GT(switch_at, bottom_from);
    EXPECT_GT(dear.rings[1].bottom_crush_m, 0.0);
  } else {
    EXPECT_EQ(dear.rings[1].mode, Level3Mode::Bottom);
  }
  EXPECT_LT(dear.energy_balance_error(), 1e-6);
}

// The 45 m/s Test 30 chain with the least-load ring underneath: energy balance, the switch
// in the event list, finite histories; with level3_ring_under = bottom the old chain.
TEST(Level3Ecb, WeldedChainAt45MetresPerSecondSwitchesAndBalances) {
  auto in = chain(45.0);
  const auto r = simulate_level3(in, options());
  EXPECT_LT(r.energy_balance_error(), 1e-6);
  EXPECT_NEAR(r.history.plastic_j.back() + r.lock_loss_j, r.plastic_work_closed_form_j + r.lock_loss_j,
              1e-6 * r.initial_kinetic_energy_j);
  int switched = 0;
  for (int i = 0; i < in.rings; ++i) switched += has_switch(r, i);
  EXPECT_GE(switched, 1);
  for (std::size_t k = 0; k < r.history.time_s.size(); ++k) {
    ASSERT_TRUE(std::isfinite(r.history.force_n[k])) << k;
    for (const auto& c : r.history.ring_crush_m) ASSERT_TRUE(std::isfinite(c[k])) << k;
  }
  for (const auto& rr : r.rings) EXPECT_TRUE(std::isfinite(rr.crush_m) && std::isfinite(rr.peak_moment_ratio));
  in.ring_under = Level3RingUnder::Bottom;
  const auto old = simulate_level3(in, options());
  for (int i = 0; i < in.rings; ++i) EXPECT_FALSE(has_switch(old, i));
  for (const auto& rr : old.rings) EXPECT_NE(rr.mode, Level3Mode::Ecb);
}

// Test 30 at its own 27.7 m/s has no wrap, hence no ring underneath: the choice changes
// nothing (bit for bit).
TEST(Level3Ecb, Test30At27MetresPerSecondIsUnchanged) {
  auto in = chain(27.7);
  const auto a = simulate_level3(in, options());
  in.ring_under = Level3RingUnder::Bottom;
  const auto b = simulate_level3(in, options());
  ASSERT_EQ(a.rings.size(), b.rings.size());
  for (std::size_t i = 0; i < a.rings.size(); ++i) {
    EXPECT_EQ(a.rings[i].crush_m, b.rings[i].crush_m);
    EXPECT_EQ(a.rings[i].mode, Level3Mode::Uniform);
  }
}

// [hinge] level3_ring_under = "bottom" | "least_load" (default) reaches the run; other values
// are scene errors naming the key.
TEST(Level3Ecb, SceneOptionReachesTheRun) {
  const std::string text = test_files::read_text(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test30_welded.toml");
  auto with = [](const std::string& line) {
    return test_files::scene_text_with("data/scenes/test30_welded.toml", "hinge", line);
  };
  using ringcrush::compare::level3_input;
  using ringcrush::compare::parse_scene;
  EXPECT_EQ(level3_input(parse_scene(text, "t30.toml"), {}).ring_under, Level3RingUnder::LeastLoad);
  EXPECT_EQ(level3_input(parse_scene(with("level3_ring_under = \"bottom\""), "t30.toml"), {}).ring_under,
            Level3RingUnder::Bottom);
  try {
    parse_scene(with("level3_ring_under = \"sideways\""), "bad.toml");
    ADD_FAILURE() << "accepted level3_ring_under = sideways";
  } catch (const ringcrush::compare::SceneError& e) {
    EXPECT_NE(e.key().find("level3_ring_under"), std::string::npos) << e.key();
  }
}
