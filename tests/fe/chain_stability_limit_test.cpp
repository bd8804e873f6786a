// The explicit step against the TRUE stability limit of a ring chain (issue 4, safety factor;
// README "Explicit step: what sets it"): on a small welded chain at rest, ω_max of the
// assembled tangent (dense, tests/fe/chain_omega_max.hpp) sets 2/ω_max. A fixed step 25 %
// above it is caught as a named blow-up before any NaN is output; the same chain at 0.9 of it
// (a safety the driver's bound would give only if its estimate were exact) runs stably and
// keeps its energy balance; and the driver's own step (assembled estimate × margin × safety
// 0.8) lies at or below 0.8 × 2/ω_max, since the estimate is not below the true ω_max.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "chain_omega_max.hpp"
#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/explicit_driver.hpp"
#include "fe/time/static_driver.hpp"  // SolveFailure

using namespace ringcrush::fe;

namespace {
constexpr double kR = 25.4e-3;

// Two welded half rings, 6 around, free far end, nothing moving: the state whose ω_max the
// dense solve gives stays that of the run (no contact closes, no plasticity).
ChainInput resting_chain() {
  ChainInput in;
  in.rings = 2;
  in.mesh.elements_around = 6;
  in.joints = JointKind::Welded;
  in.pitch_m = 2 * kR;
  in.fixed_target = false;
  in.threads = 1;
  in.impactor_velocity_m_s = 0;
  in.step_bound = StepBound::Assembled;
  return in;
}

// A small elastic disturbance of every free dof, so every mode is excited.
Eigen::VectorXd disturbance(const ChainModel& m) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m.dofs());
  for (int d = 0; d < m.dofs(); ++d) u(d) = 1e-9 * std::sin(0.7 * d + 0.3);
  for (int d : m.fixed_dofs()) u(d) = 0;
  u(m.impactor_dof()) = 0;
  return u;
}

double true_limit(ChainModel& m) {
  SystemEvaluation ev;
  m.evaluate(Eigen::VectorXd::Zero(m.dofs()), true, ev);
  return 2 / test::chain_omega_max(m);
}
}  // namespace

TEST(ChainStabilityLimit, AStepAboveTheTrueLimitIsDiagnosed) {
  ChainModel m(resting_chain());
  const double limit = true_limit(m);
  ExplicitOptions o;
  o.fixed_step_s = 1.25 * limit;
  ExplicitDriver d(m, o, disturbance(m));
  bool thrown = false;
  try {
    for (int i = 0; i < 3000; ++i) d.step();
  } catch (const SolveFailure& e) {
    thrown = true;
    const std::string what = e.what();
    EXPECT_TRUE(what.find("blow-up") != std::string::npos || what.find("non-finite") != std::string::npos) << what;
  }
  EXPECT_TRUE(thrown);
}

TEST(ChainStabilityLimit, NinetyPercentOfTheTrueLimitIsStable) {
  ChainModel m(resting_chain());
  const double limit = true_limit(m);
  ExplicitOptions o;
  o.fixed_step_s = 0.9 * limit;
  ExplicitDriver d(m, o, disturbance(m));
  for (int i = 0; i < 3000; ++i) d.step();
  EXPECT_TRUE(d.displacement().allFinite());
  EXPECT_LT(d.displacement().cwiseAbs().maxCoeff(), 1e-7);  // the 1e-9 disturbance stays bounded
}

TEST(ChainStabilityLimit, DriverStepIsAtMostSafetyTimesTheTrueLimit) {
  ChainModel m(resting_chain());
  const double limit = true_limit(m);
  ExplicitOptions o;  // safety 0.8
  ExplicitDriver d(m, o);
  d.step();
  EXPECT_LE(d.step_size(), 0.8 * limit * (1 + 1e-9)) << d.limited_by();
  EXPECT_GE(d.step_size(), 0.6 * limit) << d.limited_by();
}
