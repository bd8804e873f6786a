// The thesis static crush with Coulomb friction (issue 3 item 4): μ = 0 is the
// frictionless path bit for bit, a vanishing μ converges to it, and μ = 0.2 raises the load
// (friction at the plates restrains the spreading of the flattened contact zones) while the
// energy balance, now with the friction work, and the plate equilibrium still close. Thesis
// mesh (22 × 1 per half ring), a few seconds in Release.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "compare/fe_static.hpp"
#include "compare/formula.hpp"
#include "fe/time/static_driver.hpp"

using namespace ringcrush;

namespace {

compare::Scene thesis_scene() {
  return compare::load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_static.toml");
}

fe::FeInput thesis_input(double crush_over_d) {
  const auto scene = thesis_scene();
  fe::FeInput in = compare::fe_static_input(scene);
  in.solver.frames = 0;
  in.solver.crush_m = crush_over_d * compare::formula_input(scene).section.mean_diameter();
  return in;
}

using fe::load_at;

}  // namespace

// (e) μ = 0 is the frictionless path: a different tangential penalty changes nothing, bit for
// bit; a vanishing μ (1e-9, through the friction code and the LU solver) agrees to 1e-6.
TEST(FrictionCrush, ZeroFrictionIsTheFrictionlessPath) {
  const fe::FeInput base = thesis_input(0.2);
  fe::FeInput zero = base;
  zero.contact.friction_coefficient = 0.0;
  zero.contact.tangential_penalty_scale = 7.0;
  fe::FeInput tiny = base;
  tiny.contact.friction_coefficient = 1e-9;
  const auto a = fe::run_static(base), b = fe::run_static(zero), c = fe::run_static(tiny);
  ASSERT_EQ(a.history.size(), b.history.size());
  for (std::size_t i = 0; i < a.history.size(); ++i) {
    EXPECT_EQ(a.history[i].force_n, b.history[i].force_n) << "increment " << i;
    EXPECT_EQ(a.history[i].plastic_j, b.history[i].plastic_j) << "increment " << i;
    EXPECT_EQ(b.history[i].friction_j, 0.0);
  }
  const double d = a.history.back().deflection_m;
  for (double f : {0.25, 0.5, 1.0})
    EXPECT_NEAR(load_at(c, f * d), load_at(a, f * d), 1e-6 * load_at(a, f * d)) << "at " << f << " of the crush";
  EXPECT_LT(c.history.back().friction_j, 1e-6 * c.history.back().external_work_j);
}

// (f) μ = 0.2 against 0 on the thesis crush to δ/d = 0.6. The load rises: the friction force
// at a plate, at most μ P, opposes the outward slide of the flattened zone and so adds a
// horizontal force H ≤ μ P whose moment about the side hinges (lever ≲ the mean radius, the
// same as that of P/2 about them) is at most that of μ P: the rise is positive and below
// μ = 20 %. Energy: W_ext = elastic + plastic + contact + friction within 1 %, equilibrium
// of the two plates to 1e-3 as in the frictionless verification (issue 3 e).
TEST(FrictionCrush, FrictionRaisesTheLoadByLessThanMu) {
  const double mu = 0.2;
  const fe::FeInput base = thesis_input(0.6);
  fe::FeInput rough = base;
  rough.contact.friction_coefficient = mu;
  const auto a = fe::run_static(base), b = fe::run_static(rough);
  const double d = compare::formula_input(thesis_scene()).section.mean_diameter();
  for (double f : {0.3, 0.6}) {
    const double p0 = load_at(a, f * d), p1 = load_at(b, f * d);
    std::printf("delta/d = %.1f: P(mu = 0) = %.2f N, P(mu = %.1f) = %.2f N, rise %.2f %%\n", f, p0, mu, p1,
                100 * (p1 / p0 - 1));
    EXPECT_GT(p1, p0 * 1.001) << "at delta/d " << f;
    EXPECT_LT(p1, p0 * (1 + mu)) << "at delta/d " << f;
  }
  const auto& last = b.history.back();
  EXPECT_GT(last.friction_j, 0.0);
  EXPECT_GT(last.friction_force_n, 0.0);
  EXPECT_LT(std::abs(last.external_work_j - last.elastic_j - last.plastic_j - last.contact_j - last.friction_j) /
                last.external_work_j,
            0.01);
  EXPECT_LT(b.max_equilibrium_error, 1e-3);
  // The friction work is a small part of the input: it is bounded by μ P × (slip), and the
  // contact zones slide by a fraction of the crush.
  EXPECT_LT(last.friction_j, mu * last.external_work_j);
}

// (g) The scene maps μ and the tangential penalty, and refuses a bad one.
TEST(FrictionCrush, SceneCarriesFrictionAndRefusesBadValues) {
  auto s = thesis_scene();
  s.fe.friction_coefficient = 0.3;
  s.fe.friction_penalty_scale = 2.0;  // not the default 0.1
  const fe::FeInput in = compare::fe_static_input(s);
  EXPECT_EQ(in.contact.friction_coefficient, 0.3);
  EXPECT_EQ(in.contact.tangential_penalty_scale, 2.0);
  s.fe.friction_coefficient = std::nan("");
  EXPECT_THROW(compare::fe_static_input(s), std::invalid_argument);
  s.fe.friction_coefficient = 0.3;
  s.fe.friction_penalty_scale = 0.0;
  EXPECT_THROW(compare::fe_static_input(s), std::invalid_argument);
}

// Lock-up with friction (μ = 0.2 at the plates and on the inner wall): crushed until the plate
// gap is 2t + 0.2 mm, the inner wall carries load and slips on itself (slipping contacts
// beyond the plate ones), the run closes its energy balance with the friction work within 1 %
// and the plates stay in equilibrium.
TEST(FrictionCrush, LockUpWithFrictionOnTheInnerWall) {
  const auto scene = thesis_scene();
  fe::FeInput in = thesis_input(0.6);
  const double t = scene.rings.wall_thickness_m;
  in.solver.crush_m = scene.rings.outer_diameter_m - (2 * t + 0.2e-3);
  in.contact.friction_coefficient = 0.2;
  const auto r = fe::run_static(in);
  const auto& last = r.history.back();
  EXPECT_NEAR(last.deflection_m, in.solver.crush_m, 1e-12);
  EXPECT_GT(last.self_contacts, 0);
  EXPECT_GT(last.self_contact_force_n, 0.05 * last.force_n);
  int most_slipping = 0;
  for (const auto& h : r.history) most_slipping = std::max(most_slipping, h.slipping_contacts);
  EXPECT_GT(most_slipping, 0);
  EXPECT_GT(last.friction_j, 0.0);
  EXPECT_LT(std::abs(last.external_work_j - last.elastic_j - last.plastic_j - last.contact_j - last.friction_j) /
                last.external_work_j,
            0.01);
  EXPECT_LT(r.max_equilibrium_error, 1e-3);
}
