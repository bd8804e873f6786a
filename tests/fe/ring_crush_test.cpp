// Verification of the whole ring model (issue 3 d, e, g, h): elastic stiffness against the
// closed form, global equilibrium, the thesis static crush against DeRuntz–Hodge and
// Redwood, lock-up, and the failure diagnosis. Runs in a few seconds (Release).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "compare/fe_static.hpp"
#include "compare/formula.hpp"
#include "fe/time/static_driver.hpp"
#include "hinge/ring_laws.hpp"

using namespace ringcrush;

namespace {

compare::Scene thesis_scene() {
  return compare::load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_static.toml");
}

fe::FeInput thesis_input() {
  fe::FeInput in = compare::fe_static_input(thesis_scene());
  in.solver.frames = 0;
  return in;
}

using fe::load_at;

// The thesis ring crushed to 0.72 d on 44×2 (two elements through the wall: the fully plastic
// moment is integrated exactly), as (deflection, load) for the Redwood fits of (g).
struct LoadCurve {
  std::vector<double> deflection_m, force_n;
};
LoadCurve crush_44x2(const compare::Scene& scene, double d) {
  fe::FeInput in = compare::fe_static_input(scene);
  in.solver.frames = 0;
  in.mesh.elements_around = 44;
  in.mesh.elements_through = 2;
  in.solver.crush_m = 0.72 * d;
  LoadCurve c;
  for (const auto& h : fe::run_static(in).history) {
    c.deflection_m.push_back(h.deflection_m);
    c.force_n.push_back(h.force_n);
  }
  return c;
}

struct Reference {
  double d, p0, m0;
};
Reference reference(const compare::Scene& s) {
  const auto fin = compare::formula_input(s);
  Reference r;
  r.d = fin.section.mean_diameter();
  r.m0 = hinge::plastic_moment(fin.section, fin.yield_stress_pa, fin.state);
  r.p0 = hinge::collapse_load(r.m0, r.d);
  return r;
}

}  // namespace

// (d) Elastic diametral stiffness against THEORY §1.1 (389.1 N/mm plane stress), on a
// converged mesh; the half and the full ring agree.
TEST(RingCrush, ElasticStiffnessMatchesClosedForm) {
  const auto scene = thesis_scene();
  const auto fin = compare::formula_input(scene);
  const double k_theory = hinge::elastic_stiffness(fin.section, fin.youngs_modulus_pa, fin.poisson_ratio,
                                                   hinge::SectionState::PlaneStress);
  EXPECT_NEAR(k_theory / 1e3, 389.1, 0.1);
  double k_half = 0;
  for (bool half : {true, false}) {
    fe::FeInput in = thesis_input();
    in.material.hardening = {{1e12, 0.0}};  // elastic
    in.mesh = {48, 2, 1.0, half};
    in.solver.crush_m = 0.1e-3;
    in.solver.initial_increment = in.solver.max_increment = 0.5;
    in.solver.force_tolerance_n = 1e-6;
    const auto r = fe::run_static(in);
    const double k = r.history.back().force_n / r.history.back().deflection_m;
    EXPECT_NEAR(k / k_theory, 1.0, 0.03) << (half ? "half" : "full") << " ring: k = " << k / 1e3 << " N/mm";
    if (half) k_half = k;
    else EXPECT_NEAR(k / k_half, 1.0, 1e-4);
  }
}

// (e) At every converged increment the driven plate's force equals the fixed plate's
// (no inertia) to 1e-6 relative.
TEST(RingCrush, GlobalEquilibriumAtEveryIncrement) {
  fe::FeInput in = thesis_input();
  const auto ref = reference(thesis_scene());
  in.solver.crush_m = 0.3 * ref.d;
  in.solver.force_tolerance_n = 1e-5;
  const auto r = fe::run_static(in);
  ASSERT_GT(r.history.size(), 20u);
  for (const auto& h : r.history) {
    if (h.force_n <= 0) continue;
    EXPECT_LT(std::abs(h.force_n - h.fixed_force_n) / h.force_n, 1e-6) << "at " << h.deflection_m;
  }
  EXPECT_LT(r.max_equilibrium_error, 1e-6);
}

// (g) The thesis static crush on its own mesh (22 × 1, selective): completes to 46 mm,
// collapses near P0, rises steeply toward full crush, energy balanced.
TEST(RingCrush, ThesisCrushOnThesisMesh) {
  const auto scene = thesis_scene();
  const auto ref = reference(scene);
  const auto r = fe::run_static(thesis_input());
  EXPECT_NEAR(r.history.back().deflection_m, 0.046, 1e-12);
  // Knee: first load where the secant stiffness over an increment falls below 10 % of the
  // initial one.
  const double k0 = r.history[1].force_n / r.history[1].deflection_m;
  double knee = 0;
  for (std::size_t i = 2; i < r.history.size(); ++i) {
    const auto &a = r.history[i - 1], &b = r.history[i];
    if ((b.force_n - a.force_n) / (b.deflection_m - a.deflection_m) < 0.1 * k0) {
      knee = a.force_n;
      break;
    }
  }
  EXPECT_NEAR(knee / ref.p0, 1.0, 0.10) << "knee " << knee << " N, P0 " << ref.p0 << " N";
  // Steep rise toward full crush: the load at δ/d = 0.9 is more than twice that at 0.7.
  EXPECT_GT(load_at(r, 0.9 * ref.d), 2.0 * load_at(r, 0.7 * ref.d));
  const auto& last = r.history.back();
  EXPECT_LT(std::abs(last.external_work_j - last.elastic_j - last.plastic_j - last.contact_j) / last.external_work_j,
            0.01);
  EXPECT_LT(r.max_equilibrium_error, 1e-3);
}

// (g) On a mesh with two elements through the wall (the fully plastic moment is then
// integrated exactly), the load lies above DeRuntz–Hodge over δ/d ∈ [0.1, 0.7] and within
// ±15 % of Redwood's curve for the best α. The thesis material stops hardening at 2.1 %
// plastic strain while Redwood's formula hardens without limit, so the best α lies above
// the issue's [0.5, 4] (README reports both fits); the search range here is [0.5, 16].
TEST(RingCrush, ThesisCrushAgainstDeRuntzHodgeAndRedwood) {
  const auto scene = thesis_scene();
  const auto [x, p] = crush_44x2(scene, reference(scene).d);
  const auto fit = compare::fit_redwood(scene, x, p, 0.1, 0.7, 0.5, 16.0);
  EXPECT_GT(fit.min_ratio_to_deruntz_hodge, 1.0);
  EXPECT_LT(fit.max_relative_deviation, 0.15) << "best alpha " << fit.alpha;
  const auto narrow = compare::fit_redwood(scene, x, p, 0.1, 0.7, 0.5, 4.0);
  RecordProperty("redwood_alpha", std::to_string(fit.alpha));
  RecordProperty("redwood_max_deviation", std::to_string(fit.max_relative_deviation));
  RecordProperty("redwood_max_deviation_alpha_le_4", std::to_string(narrow.max_relative_deviation));
  std::printf("Redwood best alpha %.3f (max dev %.3f); alpha <= 4: %.3f (max dev %.3f); min P/P_DH %.3f\n",
              fit.alpha, fit.max_relative_deviation, narrow.alpha, narrow.max_relative_deviation,
              fit.min_ratio_to_deruntz_hodge);
}

// (g) as the issue words it, on the material Redwood's formula assumes. Redwood's curve is
// the power balance of side hinges hardening linearly without limit (THEORY §1.4); the
// thesis table stops hardening at 2.1 % plastic strain, so the thesis crush cannot be
// within 15 % of it for α ≤ 4 (test above). Here the same ring and mesh with the table's
// first slope E′ carried on (rigid-linear hardening, σ0 and E′ unchanged, so Redwood's curve
// is the same function): the FE then lies within ±15 % of Redwood's curve for the best α in
// the issue's [0.5, 4] — the deviation above is the material, not the element.
TEST(RingCrush, LinearHardeningRingFollowsRedwoodWithAlphaInIssueRange) {
  auto scene = thesis_scene();
  auto& table = scene.rings.material.hardening;
  const double e_t = scene.rings.material.hardening_modulus();
  ASSERT_GT(e_t, 0.0);
  table = {table.front(), {table.front().yield_stress_pa + e_t * 1.0, 1.0}};
  ASSERT_NEAR(scene.rings.material.hardening_modulus(), e_t, 1e-6 * e_t);
  const auto [x, p] = crush_44x2(scene, reference(scene).d);
  const auto fit = compare::fit_redwood(scene, x, p, 0.1, 0.7, 0.5, 4.0);
  std::printf("linear hardening: Redwood best alpha in [0.5, 4] %.3f (max dev %.3f, rms %.3f); min P/P_DH %.3f\n",
              fit.alpha, fit.max_relative_deviation, fit.rms_relative_deviation, fit.min_ratio_to_deruntz_hodge);
  RecordProperty("linear_hardening_redwood_alpha", std::to_string(fit.alpha));
  RecordProperty("linear_hardening_redwood_max_deviation", std::to_string(fit.max_relative_deviation));
  EXPECT_GT(fit.min_ratio_to_deruntz_hodge, 1.0);
  EXPECT_LT(fit.max_relative_deviation, 0.15) << "best alpha " << fit.alpha;
}

// (f) Mesh convergence of the thesis crush (the suite's version of `ringcrush
// bench-fe-static`): the thesis mesh refined 2× and 3× in both directions; the loads at
// δ/d = 0.3 and 0.6 of the two finest differ by less than 2 %, and the coarse thesis mesh
// (one element through the wall: plastic moment under-integrated) lies below them.
TEST(RingCrush, MeshConvergence) {
  const auto ref = reference(thesis_scene());
  std::vector<std::pair<double, double>> loads;
  for (int k = 1; k <= 3; ++k) {
    fe::FeInput in = thesis_input();
    in.mesh.elements_around *= k;
    in.mesh.elements_through *= k;
    in.solver.crush_m = 0.61 * ref.d;
    const auto r = fe::run_static(in);
    loads.emplace_back(load_at(r, 0.3 * ref.d), load_at(r, 0.6 * ref.d));
    std::printf("mesh %dx%d: P(0.3) = %.2f N, P(0.6) = %.2f N\n", in.mesh.elements_around,
                in.mesh.elements_through, loads.back().first, loads.back().second);
  }
  EXPECT_LT(std::abs(loads[2].first - loads[1].first) / loads[2].first, 0.02);
  EXPECT_LT(std::abs(loads[2].second - loads[1].second) / loads[2].second, 0.02);
  EXPECT_LT(loads[0].first, loads[2].first);
}

// (h) Lock-up: crushed until the plate gap is 2t + 0.2 mm, the inner wall touches itself
// and carries load, with no interpenetration beyond the contact tolerance (1 % of the
// element depth through the wall).
TEST(RingCrush, LockUpActivatesInnerWallContact) {
  const auto scene = thesis_scene();
  fe::FeInput in = thesis_input();
  const double t = scene.rings.wall_thickness_m;
  in.solver.crush_m = scene.rings.outer_diameter_m - (2 * t + 0.2e-3);
  const auto r = fe::run_static(in);
  const auto& last = r.history.back();
  EXPECT_GT(last.self_contacts, 0);
  EXPECT_GT(last.self_contact_force_n, 0.05 * last.force_n);
  double max_pen = 0;
  for (const auto& h : r.history) max_pen = std::max(max_pen, h.max_self_penetration_m);
  EXPECT_LT(max_pen, 0.01 * t);
  // The self-contact starts before the end and the load rises steeply once it does.
  double first = -1;
  for (const auto& h : r.history)
    if (h.self_contacts > 0) {
      first = h.deflection_m;
      break;
    }
  ASSERT_GT(first, 0);
  EXPECT_LT(first, in.solver.crush_m);
}

// A failing solve ends with a diagnosis naming the increment, deflection, residual and node.
TEST(RingCrush, FailureDiagnosisNamesWhereAndWhen) {
  fe::FeInput in = thesis_input();
  in.solver.crush_m = 0.01;
  in.solver.max_iterations = 2;  // cannot converge once plasticity starts
  in.solver.force_tolerance_n = 1e-9;
  in.solver.min_increment = 1e-3;
  in.solver.initial_increment = 0.05;
  in.solver.max_increment = 0.05;
  try {
    fe::run_static(in);
    FAIL() << "expected a SolveFailure";
  } catch (const fe::SolveFailure& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("increment"), std::string::npos) << m;
    EXPECT_NE(m.find("deflection"), std::string::npos) << m;
    EXPECT_NE(m.find("residual"), std::string::npos) << m;
    EXPECT_NE(m.find("node"), std::string::npos) << m;
  }
}

// One CPS8 through the wall integrates the section's plastic moment on its Gauss points across
// it: 2 (reduced) at ±t/(2√3) give 2/√3 M0 = 1.155 M0, 3 (selective, full) at 0, ±0.775 t/2 give
// 0.861 M0 (the middle point sits on the neutral axis). The dynamic scenes use one element
// through the wall (Test 30: reduced; the thesis scene: selective), so their FE rings are too
// strong or too weak in bending and yield across the section at once (README "FE against the
// hinge model", session 15: with two elements through the wall the FE's wrap flags and
// alternation move onto Level 2's). Two elements through (4 and 6 points) carry the load within
// a few per cent of the converged mesh (RingCrush.MeshConvergence); one element errs by the
// rule's sign, by up to its factor (the elastic and hardened parts of the ring dilute it).
TEST(RingCrush, OneElementThroughTheWallMissesThePlasticMomentByItsGaussRule) {
  const auto ref = reference(thesis_scene());
  auto load = [&](fe::Integration rule, int through) {
    fe::FeInput in = thesis_input();
    in.integration = rule;
    in.mesh.elements_around = 44;
    in.mesh.elements_through = through;
    in.solver.crush_m = 0.31 * ref.d;
    return load_at(fe::run_static(in), 0.3 * ref.d);
  };
  const double reduced = load(fe::Integration::Reduced, 1) / load(fe::Integration::Reduced, 2);
  const double selective = load(fe::Integration::Selective, 1) / load(fe::Integration::Selective, 2);
  std::printf("P(one element through) / P(two), delta/d = 0.3: reduced %.4f, selective %.4f\n", reduced, selective);
  EXPECT_GT(reduced, 1.08);  // measured 1.120 at 44 around
  EXPECT_LT(reduced, 2.0 / std::sqrt(3.0) + 0.01);
  EXPECT_LT(selective, 0.92);  // measured 0.885
  EXPECT_GT(selective, 0.861 - 0.01);
}
