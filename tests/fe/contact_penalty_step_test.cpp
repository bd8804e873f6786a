// The contact penalty that does not shorten the explicit step (fe/contact/penalty_step_cap.hpp,
// ChainInput::contact_penalty_step_fraction): its closed form, the element + contact bound
// of a pressed chain kept within the set fraction of the element step (the element
// eigenvalues formed here, independently of the model), the default penalty shown to cost
// more than that fraction (so the test can fail), a cap that does not bind changing nothing
// bitwise, and the bad values refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "fe/chain/chain_model.hpp"
#include "fe/contact/penalty_step_cap.hpp"
#include "fe/dynamics/element_eigenvalue.hpp"

using namespace ringcrush::fe;

namespace {
constexpr double kR = 25.4e-3, kDepth = 1.6e-3;

ChainInput pressed_chain(double fraction) {
  ChainInput in;
  in.rings = 3;
  in.mesh.elements_around = 8;
  in.joints = JointKind::Welded;
  in.pitch_m = 2 * kR;
  in.fixed_target = true;
  in.threads = 1;
  in.contact_penalty_step_fraction = fraction;
  return in;
}

// The impactor 0.1 of the wall depth into ring 1: its springs, the welded neighbours' outer
// nodes and the target's all lie within one depth of contact.
Eigen::VectorXd pressed(const ChainModel& m) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m.dofs());
  u(m.impactor_dof()) = -0.1 * kDepth;
  return u;
}

// max_e λ_max(K_e, M_e) of the undeformed chain, from the element routines themselves.
double largest_element_omega2(const ChainModel& m) {
  const J2PlaneStress material(m.input().material);
  double out = 0;
  for (std::size_t e = 0; e < m.mesh().elements.size(); ++e) {
    ElementCoords x;
    for (int a = 0; a < 8; ++a) x.row(a) = m.mesh().nodes[m.mesh().elements[e][a]].transpose();
    out = std::max(out, element_max_eigenvalue(x, m.element_mass(static_cast<int>(e)), m.input().integration,
                                               m.input().ring.width_m, material));
  }
  return out;
}

double stable_step_at_press(ChainModel& m) {
  SystemEvaluation ev;
  const Eigen::VectorXd u = pressed(m);
  m.evaluate(u, false, ev);
  return m.stable_step(u).step_s;
}
}  // namespace

TEST(ContactPenaltyStep, ClosedForm) {
  EXPECT_NEAR(spring_to_element_omega2_limit(0.1), 1 / 0.81 - 1, 1e-15);
  EXPECT_NEAR(spring_to_element_omega2_limit(0.5), 3.0, 1e-15);
  // 2/√(ω_e² + ω_c²) = (1 − φ) 2/ω_e at the limit.
  for (double phi : {0.01, 0.05, 0.2}) {
    const double we2 = 4e16, limit = spring_to_element_omega2_limit(phi);
    EXPECT_NEAR((2 / std::sqrt(we2 + limit * we2)) / (2 / std::sqrt(we2)), 1 - phi, 1e-14);
  }
  EXPECT_NEAR(penalty_step_factor(0.1, 1.0, 10.0), (1 / 0.81 - 1) / 10, 1e-15);
  EXPECT_EQ(penalty_step_factor(0.1, 1.0, 0.1), 1.0);  // already soft enough: unchanged
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double bad : {0.0, -0.1, 0.51, nan}) EXPECT_THROW(spring_to_element_omega2_limit(bad), std::invalid_argument) << bad;
  EXPECT_THROW(penalty_step_factor(0.1, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(penalty_step_factor(0.1, 1.0, nan), std::invalid_argument);
}

TEST(ContactPenaltyStep, ContactSpringsCostAtMostTheFractionOfTheElementStep) {
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    ChainInput plain_in = pressed_chain(0);
    plain_in.integration = rule;
    ChainModel plain(plain_in);
    const double element_step = 2 / std::sqrt(largest_element_omega2(plain));
    // The default penalty costs more than 10 % of the element step on a pressed chain.
    EXPECT_LT(stable_step_at_press(plain), 0.9 * element_step);
    EXPECT_EQ(plain.contact_penalty_scale(), 1.0);
    for (double phi : {0.05, 0.1, 0.2}) {
      ChainInput in = plain_in;
      in.contact_penalty_step_fraction = phi;
      ChainModel capped(in);
      const double step = stable_step_at_press(capped);
      EXPECT_GE(step, (1 - phi) * element_step * (1 - 1e-12)) << "phi " << phi;
      // The default springs cost 10–20 % here: the cap binds at 5 and 10 %, not at 20 %.
      if (phi < 0.15) EXPECT_LT(capped.contact_penalty_scale(), 1.0) << phi;
      else EXPECT_EQ(capped.contact_penalty_scale(), 1.0) << phi;
      // The parts the bound reports: the springs near contact within the limit of the
      // largest element's ω².
      const auto& parts = capped.step_parts();
      EXPECT_LE(parts.contact_omega2, spring_to_element_omega2_limit(phi) * parts.element_omega2 * (1 + 1e-12));
      EXPECT_GT(parts.contact_omega2, 0.0);
    }
  }
}

TEST(ContactPenaltyStep, ACapThatDoesNotBindChangesNothing) {
  // φ = 0.5 allows ω_c² up to 3 ω_e²: the default penalty is below it, so the model is the
  // default one bit for bit.
  ChainModel plain(pressed_chain(0)), loose(pressed_chain(0.5));
  EXPECT_EQ(loose.contact_penalty_scale(), 1.0);
  SystemEvaluation a, b;
  const Eigen::VectorXd u = pressed(plain);
  plain.evaluate(u, false, a);
  loose.evaluate(u, false, b);
  EXPECT_TRUE(a.force == b.force);
  EXPECT_EQ(a.contact_energy, b.contact_energy);
  EXPECT_GT(a.contact_energy, 0.0);
  EXPECT_EQ(plain.stable_step(u).step_s, loose.stable_step(u).step_s);
}

TEST(ContactPenaltyStep, TheCapLowersThePenaltyUniformly) {
  // The contact energy ½ k g² of the same penetration scales with the penalty factor.
  ChainModel plain(pressed_chain(0)), capped(pressed_chain(0.1));
  SystemEvaluation a, b;
  const Eigen::VectorXd u = pressed(plain);
  plain.evaluate(u, false, a);
  capped.evaluate(u, false, b);
  ASSERT_GT(a.contact_energy, 0.0);
  EXPECT_NEAR(b.contact_energy / a.contact_energy, capped.contact_penalty_scale(), 1e-12);
  EXPECT_NEAR(capped.contact_forces().impactor_n / plain.contact_forces().impactor_n, capped.contact_penalty_scale(),
              1e-12);
}

TEST(ContactPenaltyStep, BadFractionsAreNamed) {
  for (double bad : {-0.1, 0.6, std::numeric_limits<double>::quiet_NaN()}) {
    try {
      validate(pressed_chain(bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("contact_penalty_step_fraction"), std::string::npos) << e.what();
    }
  }
}

TEST(StepParts, ElementsOnlyEstimateLeavesTheRunUntouched) {
  // The diagnosis's own estimator (elements_only_assembled_omega2) must not move the run's
  // warm-started estimate: two models, one asked for the diagnosis between its bounds, give
  // the same steps bit for bit; the elements-only value lies under the element bound × the
  // margin (the element eigenvalue inequality) and is not above the estimate with springs by
  // more than the iteration's tolerance.
  ChainInput in = pressed_chain(0);
  in.step_bound = StepBound::Assembled;
  ChainModel plain(in), asked(in);
  const Eigen::VectorXd u = pressed(plain);
  SystemEvaluation a, b;
  plain.evaluate(u, false, a);
  asked.evaluate(u, false, b);
  for (int k = 0; k < 3; ++k) {
    const double s_plain = plain.stable_step(u).step_s;
    const double s_asked = asked.stable_step(u).step_s;
    EXPECT_EQ(s_plain, s_asked) << k;
    const double only = asked.elements_only_assembled_omega2();
    const auto& parts = asked.step_parts();
    EXPECT_GT(only, 0.0);
    EXPECT_LE(only, in.step_bound_margin * parts.element_omega2 * (1 + 1e-12));
    EXPECT_LE(only, parts.assembled_omega2 * (1 + 1e-3));
    EXPECT_EQ(parts.bulk_factor, 1.0);
  }
  ChainModel element_bound(pressed_chain(0));
  EXPECT_THROW(element_bound.elements_only_assembled_omega2(), std::logic_error);
}
