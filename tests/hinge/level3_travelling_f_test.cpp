// Hinge Level 3 with a travelling F placed by the shear-free condition (THEORY §4.5; issue 7
// item 2; hinge/level3_travelling_f.cpp for the derivation: dP/dθ_F = 0 ⇔ Q = 0 at F).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "compare/hinge_run_level3.hpp"
#include "compare/measures.hpp"
#include "compare/run_output.hpp"
#include "hinge/level3_mechanism.hpp"
#include "test_files.hpp"

using namespace ringcrush;
using namespace ringcrush::hinge;
using std::numbers::pi;

namespace {

const Level3Ring kRing{0.0508, 0.0016, 2.184, 1.358};  // Test 30: D, t, M0, Redwood k

compare::Scene scene(const char* name, double velocity, bool shear_free) {
  auto s = compare::load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/" + name + ".toml");
  s.impactor->velocity_m_s = velocity;
  s.hinge.level3_hinge_f = shear_free ? compare::HingeSettings::Level3HingeF::ShearFree
                                      : compare::HingeSettings::Level3HingeF::LeastOnsetLoad;
  return s;
}

compare::HingeRunOptions options() {
  compare::HingeRunOptions o;
  o.level = "3";
  o.relative_tolerance = 1e-10;
  o.absolute_tolerance = 1e-12;
  return o;
}

// θ_F of least onset load of the FIXED-F family, from a fine table (first κ step 1/2000 of the
// wrap, so the one-sided onset load is the onset value to O(1e-3)): the closed-form chord
// geometry of level3_wrap_mechanism, independent of the cell sums of the travelling code.
double fine_least_onset_theta_f(const Level3Ring& r) {
  auto onset = [&](double th) { return level3_wrap_mechanism(r, th, 2000).load.front(); };
  double a = 110.0 * pi / 180.0, b = 160.0 * pi / 180.0;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 40; ++it) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (onset(c) < onset(d)) b = d;
    else a = c;
  }
  return 0.5 * (a + b);
}

}  // namespace

// (1) Upper-bound limit check. On the undeformed ring the shear-free F (stationary point of
// the instantaneous load, closed-form integrals of the circle) must coincide with the θ_F of
// least onset load of the fixed-hinge family (closed-form chord geometry of
// level3_wrap_mechanism, fine table): the same minimum reached through two independent
// kinematic descriptions. Tolerance 0.1°: the fine table's onset load is its one-sided first
// step (an average over 1/2000 of the wrap), which shifts the load by 3e-4 (measured 1777.44
// vs 1776.93 N) and the flat minimum (curvature ≈ 1.5e3 N/rad²) by a few hundredths of a
// degree. The loads agree to 1e-3; the load is stationary there (P(θ* ± 2°) above P(θ*), a
// central difference of dP/dθ_F below 1e-3 P per radian), and the cell-sum version used
// along the wrap converges to it (720 cells: within one cell, 0.125°).
TEST(Level3TravellingF, ShearFreeFAtOnsetIsTheLeastOnsetLoadF) {
  const WrapRate sf = level3_onset_shear_free_rate(kRing);
  const double fixed = fine_least_onset_theta_f(kRing);
  EXPECT_NEAR(sf.theta_f * 180.0 / pi, fixed * 180.0 / pi, 0.1);
  const double table_onset = level3_wrap_mechanism(kRing, fixed, 2000).load.front();
  EXPECT_NEAR(sf.load, table_onset, 1e-3 * table_onset);
  const auto beta = level3_undeformed_tangent(kRing, 720);
  const double d = 2.0 * pi / 180.0;
  EXPECT_GT(level3_wrap_rate(kRing, beta, sf.theta_f - d).load, sf.load * (1.0 + 1e-4));
  EXPECT_GT(level3_wrap_rate(kRing, beta, sf.theta_f + d).load, sf.load * (1.0 + 1e-4));
  const double e = 0.5 * pi / 180.0;
  const double slope = (level3_wrap_rate(kRing, beta, sf.theta_f + e).load -
                        level3_wrap_rate(kRing, beta, sf.theta_f - e).load) / (2.0 * e);
  EXPECT_LT(std::abs(slope), 1e-3 * sf.load);
  // The fixed mode's own least-onset search (40-sample table, Richardson onset) agrees too.
  EXPECT_NEAR(level3_optimal_theta_f(kRing) * 180.0 / pi, sf.theta_f * 180.0 / pi, 0.1);
  const WrapRate cells = level3_shear_free_rate(kRing, beta);
  EXPECT_NEAR(cells.theta_f, sf.theta_f, 0.125 * pi / 180.0);
  EXPECT_NEAR(cells.load, sf.load, 1e-4 * sf.load);
  // Symmetry at B with unit curvature rate: ω_C + ω_F + arc = 0.
  EXPECT_NEAR(sf.omega_c + sf.omega_f + kRing.mean_radius() * (pi - sf.theta_f), 0.0, 1e-12);
}

// Once F has rotated it does not travel: the finite rotation leaves a corner at F, across
// which the tangent, and with it dP/dθ_F (equivalently the shear at F), jumps; the load is
// least AT the corner (left slope < 0 < right slope: zero lies in the shear jump, the
// shear-free condition of a hinge at a corner), so the global search keeps F there through
// the whole wrap — the thesis's "hinges oscillate about fixed positions without travelling
// far" (§4.2.3). Consequence checked: θ_F constant along the trace, and the traced wrap
// equals the fixed-F wrap at that θ_F (crush at equal κ_B and load at equal crush to 1e-3,
// the fixed table 10× finer since its loads are differences of its work; its first node is
// a one-sided difference and is left out).
TEST(Level3TravellingF, FOncePlasticIsPinnedByItsOwnCorner) {
  const auto w = level3_travelling_wrap_mechanism(kRing);
  const double th = w.hinge_f.front();
  for (double t : w.hinge_f) EXPECT_NEAR(t, th, 1e-9);
  EXPECT_NEAR(th, level3_onset_shear_free_rate(kRing).theta_f, 1e-9);
  const int per = 10;  // fixed table 10× finer in κ: node per·j has the trace's κ_B of node j
  const auto fixed = level3_wrap_mechanism(kRing, th, per * (static_cast<int>(w.crush.size()) - 1));
  ASSERT_EQ(fixed.crush.size(), static_cast<std::size_t>(per) * (w.crush.size() - 1) + 1);
  for (std::size_t j = 1; j < w.crush.size(); ++j) {
    EXPECT_NEAR(w.crush[j], fixed.crush[per * j], 1e-3 * fixed.crush[per * j]) << j;
    EXPECT_NEAR(w.load[j], fixed.load_at(w.crush[j]), 1e-3 * w.load[j]) << j;
  }
  const std::size_t j = w.crush.size() / 2;
  const double e = 0.2 * pi / 180.0, p = level3_wrap_rate(kRing, w.tangent[j], th, w.cell_edges).load;
  const double left = (p - level3_wrap_rate(kRing, w.tangent[j], th - e, w.cell_edges).load) / e;
  const double right = (level3_wrap_rate(kRing, w.tangent[j], th + e, w.cell_edges).load - p) / e;
  EXPECT_LT(left, -0.1 * p);
  EXPECT_GT(right, 0.1 * p);
  // Not a property of the cells: four times finer, F stays put too and the trace converges.
  const auto fine = level3_travelling_wrap_mechanism(kRing, 60, 360);
  for (double t : fine.hinge_f) EXPECT_NEAR(t, th, 1e-9);
  EXPECT_NEAR(fine.capacity(), w.capacity(), 1e-3 * w.capacity());
  EXPECT_NEAR(fine.load.back(), w.load.back(), 1e-3 * w.load.back());
  // (3) θ_F over the wrap against the thesis's F range (THEORY §4.5: 120–150°).
  EXPECT_GE(th * 180.0 / pi, 120.0);
  EXPECT_LE(th * 180.0 / pi, 150.0);
}

// The traced wrap with travelling F is a closed, inextensible lower quadrant at every node
// (B on the axis, length πR/2, no gap), its tabulated work is the integral of its load, and
// B rises monotonically (the table is in increasing crush).
TEST(Level3TravellingF, TracedWrapIsClosedAndItsWorkIsTheIntegralOfItsLoad) {
  const double R = kRing.mean_radius();
  const auto w = level3_travelling_wrap_mechanism(kRing);
  ASSERT_TRUE(w.travelling());
  ASSERT_GE(w.crush.size(), 10u);
  EXPECT_NEAR(w.energy_at(w.capacity()), w.dissipation.back(), 2e-3 * w.dissipation.back());
  for (std::size_t j = 1; j < w.crush.size(); ++j) EXPECT_GT(w.crush[j], w.crush[j - 1]);
  for (std::size_t j : {std::size_t{0}, w.curvature.size() / 2, w.curvature.size() - 1}) {
    Level3RingResult s;
    s.wrap_started = true;
    s.wrap_curvature = w.curvature[j];
    const auto sh = level3_ring_shape(kRing, w, s, 0.0, 200);
    double len = 0.0, gap = 0.0;
    for (std::size_t k = 1; k < sh.points.size(); ++k) {
      if (sh.theta[k - 1] < 0.5 * pi - 1e-12) continue;
      const double seg = std::hypot(sh.points[k][0] - sh.points[k - 1][0], sh.points[k][1] - sh.points[k - 1][1]);
      len += seg;
      gap = std::max(gap, seg);
    }
    EXPECT_NEAR(len, 0.5 * pi * R, 1e-3 * R) << "node " << j;
    EXPECT_LT(gap, 0.02 * R);
    EXPECT_NEAR(sh.points.back()[0], 0.0, 1e-12);
  }
}

// (2) Energy balance of a Level 3 chain run with travelling F, to the existing Level 3 bar:
// KE + plastic work = ½MV² to 1e-7 along the run, and the integrated plastic work equals the
// mechanisms' work of the final state (1e-6 of KE0). At 50 m/s the wrap is selected.
TEST(Level3TravellingF, EnergyBalanceTest30WeldedShearFree) {
  for (double v : {27.7, 50.0}) {
    const auto sc = scene("test30_welded", v, true);
    const auto r = compare::run_hinge_level3(sc, options());
    EXPECT_LT(compare::energy_balance_error(r, sc), 1e-7) << v;
    EXPECT_EQ(r.extra["hinge_F"], "shear_free");
    const auto in = compare::level3_input(sc);
    HybridOptions o;
    o.relative_tolerance = 1e-10;
    o.absolute_tolerance = 1e-12;
    o.end_time = 0.05;
    const auto res = simulate_level3(in, o);
    EXPECT_LT(res.energy_balance_error(), 1e-7);
    EXPECT_NEAR(res.history.plastic_j.back(), res.plastic_work_closed_form_j, 1e-6 * res.initial_kinetic_energy_j);
    if (v > 40.0) {
      EXPECT_TRUE(res.rings[0].wrap_started);
    }
  }
}

// A fixed θ_F and the travelling F cannot both be asked for.
TEST(Level3TravellingF, FixedThetaAndShearFreeConflict) {
  Level3Input in;
  in.ring = kRing;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = 50.0;
  in.theta_f = 2.3;
  in.hinge_f = Level3HingeF::ShearFree;
  EXPECT_THROW(in.validate(), std::invalid_argument);
}

// The scene keys ([hinge] level3_hinge_f, level3_theta_f_deg) reach the run, and a fixed θ_F
// with the shear-free placement, or a θ_F outside (90°, 180°), is refused naming the key.
TEST(Level3TravellingF, SceneKeysSelectHowFIsPlaced) {
  auto with_hinge = [](const std::string& keys) {
    return compare::parse_scene(test_files::scene_text_with("data/scenes/test30_welded.toml", "hinge", keys),
                                "level3.toml");
  };
  const auto sf = with_hinge("level3_hinge_f = \"shear_free\"\n");
  EXPECT_EQ(compare::level3_input(sf).hinge_f, Level3HingeF::ShearFree);
  const auto fixed = with_hinge("level3_theta_f_deg = 140.0   # F fixed\n");
  EXPECT_NEAR(compare::level3_input(fixed).theta_f * 180.0 / pi, 140.0, 1e-12);
  EXPECT_NEAR(compare::level3_input(fixed, {125.0, true}).theta_f * 180.0 / pi, 125.0, 1e-12);  // run option wins
  for (const char* bad : {"level3_hinge_f = \"shear_free\"\nlevel3_theta_f_deg = 140.0\n", "level3_theta_f_deg = 80.0\n",
                          "level3_hinge_f = \"travelling\"\n"}) {
    try {
      with_hinge(bad);
      ADD_FAILURE() << bad;
    } catch (const compare::SceneError& e) {
      EXPECT_NE(e.key().find("level3_"), std::string::npos) << e.what();
    }
  }
}
