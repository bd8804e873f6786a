// Level 3 travelling E of the ring underneath a wrap (hinge/level3_travelling_e.hpp): the
// E–C–B mechanism against its closed form on the circle, E at the symmetry point A when
// nothing holds the cap, pinned to the held cap's edge otherwise, the held cap against the
// geometry of two stacked circles, and the chain with E shear-free.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "compare/hinge_run_level3.hpp"
#include "compare/scene.hpp"
#include "hinge/level3_mechanism.hpp"
#include "hinge/level3_travelling_e.hpp"
#include "test_files.hpp"

using namespace ringcrush::hinge;
using std::numbers::pi;

namespace {

const Level3Ring kRing{0.0508, 0.0016, 2.184, 1.358};  // Test 30 ring

Level3Shape circle(double top_y = 0.0, int n = 96) {
  return level3_ring_shape(kRing, WrapMechanism{}, Level3RingResult{}, top_y, n);
}

// The onset closed form (header): P(θ_E) = (4 M0/R)(1 + cos θ)/(1 + cos θ − sin θ).
double onset_load(double th) {
  return 4.0 * kRing.plastic_moment_nm / kRing.mean_radius() * (1.0 + std::cos(th)) /
         (1.0 + std::cos(th) - std::sin(th));
}

}  // namespace

TEST(Level3TravellingE, EMechanismOnTheCircleMatchesTheClosedForm) {
  const auto s = circle();
  for (double deg : {0.0, 20.0, 45.0, 70.0}) {
    const double th = deg * pi / 180.0;
    const auto e = level3_e_rate(s, kRing.plastic_moment_nm, th);
    EXPECT_NEAR(e.load / onset_load(th), 1.0, 2e-4) << deg << "°";
  }
  // E = A: the four-hinge onset P0, with E–C and C–B turning equal and opposite.
  const auto a = level3_e_rate(s, kRing.plastic_moment_nm, 0.0);
  EXPECT_NEAR(a.load / kRing.collapse_load(), 1.0, 1e-9);
  EXPECT_NEAR(a.omega_ec, -a.omega_cb, 1e-9 * std::abs(a.omega_ec));
}

// Shear-free E: with nothing held the least load sits at the symmetry point A (P = P0); with
// a held cap the load rises monotonically with θ_E on the circle, so E sits on the cap edge.
TEST(Level3TravellingE, ShearFreeEIsAtTheSymmetryPointOrTheHeldCapEdge) {
  const auto s = circle();
  const double M0 = kRing.plastic_moment_nm;
  const auto free = level3_shear_free_e(s, M0, 0.0);
  EXPECT_LT(free.theta_e, 0.5 * pi / 180.0);
  EXPECT_NEAR(free.load / kRing.collapse_load(), 1.0, 1e-3);
  for (double deg : {15.0, 30.0, 50.0}) {
    const double cap = deg * pi / 180.0;
    const auto e = level3_shear_free_e(s, M0, cap);
    EXPECT_NEAR(e.theta_e, cap, 1e-9) << deg << "°";
    EXPECT_NEAR(e.load / onset_load(cap), 1.0, 2e-4) << deg << "°";
  }
}

// On a crushed ring the least-load E is either the cap edge or an interior stationary point
// (dP/dθ_E = 0 there, the shear-free condition): both checked by central differences.
TEST(Level3TravellingE, ShearFreeEOnACrushedRingIsStationaryOrOnTheCap) {
  const double M0 = kRing.plastic_moment_nm;
  for (double phi : {0.3, 0.7}) {
    for (double psi : {0.2, 0.6}) {
      Level3RingResult st;
      st.uniform_angle = phi;
      st.reinforced = true;
      st.bottom_angle = psi;
      const auto s = level3_ring_shape(kRing, WrapMechanism{}, st, 0.0, 96);
      const double cap = 10.0 * pi / 180.0;
      const auto e = level3_shear_free_e(s, M0, cap);
      ASSERT_TRUE(std::isfinite(e.load));
      EXPECT_GE(e.theta_e, cap);
      EXPECT_LT(e.theta_e, 0.5 * pi);
      const double h = 0.2 * pi / 180.0;
      const double up = level3_e_rate(s, M0, std::min(e.theta_e + h, 89.0 * pi / 180.0)).load;
      EXPECT_LE(e.load, up * (1.0 + 1e-9)) << "φ " << phi << " ψ " << psi;
      if (e.theta_e > cap + h) {
        const double dn = level3_e_rate(s, M0, e.theta_e - h).load;
        EXPECT_LE(e.load, dn * (1.0 + 1e-9));
      }
    }
  }
}

// Two undeformed circles stacked a wall apart (mean lines t apart at the contact): the cap
// within 1.1 t of the ring above ends where R sin²… the gap |p − c_upper| − R reaches 1.1 t;
// the polyline answer is the last shape point before it.
TEST(Level3TravellingE, HeldCapOfTwoStackedCirclesMatchesTheGeometry) {
  const double R = kRing.mean_radius(), t = kRing.wall_thickness_m;
  const auto upper = circle(0.0);
  const auto lower = circle(upper.bottom_y - t);
  auto gap = [&](double th) {  // centres 2R + t apart
    return std::hypot(R * std::sin(th), 2.0 * R + t - R * std::cos(th)) - R;
  };
  double a = 0.0, b = 0.5;
  for (int it = 0; it < 100; ++it) (gap(0.5 * (a + b)) < 1.1 * t ? a : b) = 0.5 * (a + b);
  const double cap = level3_held_cap(upper, lower, 1.1 * t);
  const double spacing = 0.5 * pi / 96;
  EXPECT_LE(cap, a + 1e-12);
  EXPECT_GT(cap, a - spacing);
  EXPECT_GT(cap, 0.0);
  EXPECT_THROW(level3_held_cap(upper, lower, 0.0), std::invalid_argument);
}

TEST(Level3TravellingE, BadInputIsRejected) {
  const auto s = circle(0.0, 24);
  EXPECT_THROW(level3_e_rate(s, kRing.plastic_moment_nm, -0.1), std::invalid_argument);
  EXPECT_THROW(level3_e_rate(s, kRing.plastic_moment_nm, 0.5 * pi), std::invalid_argument);
  EXPECT_THROW(level3_e_rate(s, 0.0, 0.3), std::invalid_argument);
  EXPECT_THROW(level3_shear_free_e(s, kRing.plastic_moment_nm, 1.6), std::invalid_argument);
  Level3Input in;
  in.ring = kRing;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = 27.7;
  in.theta_e = 1.6;
  EXPECT_THROW(in.validate(), std::invalid_argument);
}

// The chain: E shear-free is reported, not flowed — the run itself is unchanged (crush,
// wrap flags, energy balance), E sits at or beyond the held cap and short of C, and the
// shear-free E–C–B load is the least of the candidates (never above the fixed E's).
TEST(Level3TravellingE, ChainWithShearFreeEIsUnchangedAndPlacesE) {
  Level3Input in;
  in.rings = 6;
  in.ring = kRing;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = 45.0;  // Level 3 alternates wrap / bottom from 40 m/s (README)
  in.ring_under = Level3RingUnder::Bottom;  // E reported, not flowed (level3_ecb_test: flowed)
  HybridOptions o;
  o.relative_tolerance = 1e-8;
  o.absolute_tolerance = 1e-10;
  o.end_time = 0.05;
  const auto fixed = simulate_level3(in, o);
  in.hinge_e = Level3HingeE::ShearFree;
  const auto sf = simulate_level3(in, o);
  ASSERT_EQ(fixed.rings.size(), sf.rings.size());
  EXPECT_LT(sf.energy_balance_error(), 1e-4);
  int under = 0;
  for (std::size_t i = 0; i < sf.rings.size(); ++i) {
    const auto& a = fixed.rings[i];
    const auto& b = sf.rings[i];
    EXPECT_EQ(a.crush_m, b.crush_m);
    EXPECT_EQ(a.wrap_started, b.wrap_started);
    EXPECT_EQ(a.peak_moment_ratio, b.peak_moment_ratio);
    if (!b.reinforced) continue;
    ++under;
    EXPECT_NEAR(a.theta_e, in.theta_e, 1e-12);
    EXPECT_GE(b.theta_e, b.held_cap);
    EXPECT_LT(b.theta_e, 0.5 * pi);
    EXPECT_TRUE(std::isfinite(b.e_mechanism_load_n));
    EXPECT_GT(b.e_mechanism_load_n, 0.0);
    if (b.held_cap <= in.theta_e) {  // the fixed E is then a candidate: the least load is below
      EXPECT_LE(b.e_mechanism_load_n, a.e_mechanism_load_n * (1.0 + 1e-9));
    }
    bool reported = false;
    for (const auto& h : b.hinges)
      if (h.name == "E") {
        reported = true;
        EXPECT_NEAR(h.angle_deg, b.theta_e * 180.0 / pi, 1e-9);
      }
    EXPECT_TRUE(reported);
  }
  EXPECT_GE(under, 2);  // rings 2, 4 under the wraps of rings 1, 3
}

// The scene option: [hinge] level3_hinge_e = "fixed" (default) | "shear_free" reaches the
// Level 3 input; any other value is a scene error naming the key.
TEST(Level3TravellingE, SceneOptionReachesTheRunAndBadValuesAreRejected) {
  const std::string text = test_files::read_text(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test30_welded.toml");
  auto with = [](const std::string& line) {
    return test_files::scene_text_with("data/scenes/test30_welded.toml", "hinge", line);
  };
  const auto plain = ringcrush::compare::parse_scene(text, "t30.toml");
  EXPECT_EQ(ringcrush::compare::level3_input(plain, {}).hinge_e, Level3HingeE::Fixed);
  const auto sf = ringcrush::compare::parse_scene(with("level3_hinge_e = \"shear_free\""), "t30.toml");
  EXPECT_EQ(ringcrush::compare::level3_input(sf, {}).hinge_e, Level3HingeE::ShearFree);
  try {
    ringcrush::compare::parse_scene(with("level3_hinge_e = \"sideways\""), "bad.toml");
    ADD_FAILURE() << "accepted level3_hinge_e = sideways";
  } catch (const ringcrush::compare::SceneError& e) {
    EXPECT_NE(e.key().find("level3_hinge_e"), std::string::npos) << e.key();
  }
}
