// Explicit central difference (issue 4 item 5) on closed-form systems: second-order phase
// convergence on the linear oscillator, stability just below 2/ω and a diagnosed blow-up just
// above it, exact momentum through a penalty collision, and the energy balance.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "fe/dynamics/explicit_driver.hpp"
#include "fe/time/static_driver.hpp"
#include "dynamic_toy_systems.hpp"

namespace ringcrush::fe {
namespace {

using testing::SpringMassSystem;

constexpr double kPi = 3.14159265358979323846;

// Unit mass, ω = 2π (period 1 s), released from u = 1 at rest: u(t) = cos ωt.
SpringMassSystem oscillator() {
  SpringMassSystem s({1.0}, {0.0});
  s.add_spring(0, -1, 4 * kPi * kPi);
  return s;
}

// Error at t = 1.25 T, where cos ωt crosses zero with its largest slope, so the phase error
// shows at first order (at t = T it would hide in the peak).
double phase_error(double dt) {
  auto s = oscillator();
  ExplicitOptions o;
  o.fixed_step_s = dt;
  ExplicitDriver d(s, o, Eigen::Vector2d(1.0, 0.0));
  while (d.time() < 1.25 - 1e-12) d.step(1.25);
  return std::abs(d.displacement()(0));  // cos(2.5π) = 0
}

TEST(ExplicitDriver, OscillatorPhaseConvergesAtSecondOrder) {
  const double e1 = phase_error(1.0 / 40), e2 = phase_error(1.0 / 80), e3 = phase_error(1.0 / 160);
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.1);
  EXPECT_NEAR(std::log2(e2 / e3), 2.0, 0.1);
  EXPECT_LT(e3, 1e-3);
}

TEST(ExplicitDriver, OscillatorAmplitudeHasNoDrift) {
  // Central difference has no amplitude error on a linear oscillator: after 20 periods the
  // largest |u| of the last period is 1 to O((ωΔt)²), and the energy does not drift.
  auto s = oscillator();
  ExplicitOptions o;
  o.fixed_step_s = 1.0 / 100;
  ExplicitDriver d(s, o, Eigen::Vector2d(1.0, 0.0));
  double peak = 0;
  while (d.time() < 20.0 - 1e-9) {
    d.step(20.0);
    if (d.time() > 19.0) peak = std::max(peak, std::abs(d.displacement()(0)));
  }
  const double wdt = 2 * kPi / 100;
  EXPECT_NEAR(peak, 1.0, wdt * wdt / 4);
  EXPECT_LT(std::abs(d.energy().relative_numerical()), wdt * wdt / 4);
}

TEST(ExplicitDriver, StableStepFromSystemTimesSafety) {
  auto s = oscillator();
  ExplicitOptions o;
  o.safety = 0.8;
  ExplicitDriver d(s, o, Eigen::Vector2d(1.0, 0.0));
  d.step();
  EXPECT_NEAR(d.step_size(), 0.8 * 2.0 / (2 * kPi), 1e-12);
  EXPECT_NEAR(d.stable_step(), 2.0 / (2 * kPi), 1e-12);
  EXPECT_EQ(d.limited_by(), "mass 0");
}

TEST(ExplicitDriver, StableJustBelowCriticalStep) {
  auto s = oscillator();
  ExplicitOptions o;
  o.fixed_step_s = 0.99 * 2.0 / (2 * kPi);
  ExplicitDriver d(s, o, Eigen::Vector2d(1.0, 0.0));
  double peak = 0;
  for (int i = 0; i < 5000; ++i) {
    d.step();
    peak = std::max(peak, std::abs(d.displacement()(0)));
  }
  // Bounded: the central-difference invariant keeps |u| ≤ 1/√(1 − (ωΔt/2)²) ≈ 7.1 here.
  EXPECT_LT(peak, 1.0 / std::sqrt(1 - 0.99 * 0.99) + 1e-9);
}

TEST(ExplicitDriver, BlowUpJustAboveCriticalStepIsDiagnosed) {
  auto s = oscillator();
  ExplicitOptions o;
  o.fixed_step_s = 1.02 * 2.0 / (2 * kPi);
  ExplicitDriver d(s, o, Eigen::Vector2d(1.0, 0.0));
  bool thrown = false;
  try {
    for (int i = 0; i < 2000; ++i) {
      d.step();
      ASSERT_TRUE(d.displacement().allFinite());
    }
  } catch (const SolveFailure& e) {
    thrown = true;
    EXPECT_NE(std::string(e.what()).find("blow-up"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("stable step"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(thrown);
  EXPECT_LT(d.steps(), 2000);
}

// Mass 1 at x = 0 moving right at 1 m/s meets mass 3 at x = 0.5 moving left at 0.5 m/s
// through a stiff penalty contact: an elastic collision.
SpringMassSystem collision() {
  SpringMassSystem s({1.0, 3.0}, {0.0, 0.5});
  s.add_contact(0, 1, 1e5);
  s.set_velocity(0, 1.0);
  s.set_velocity(1, -0.5);
  return s;
}

TEST(ExplicitDriver, CollisionConservesMomentumAndEnergy) {
  auto s = collision();
  ExplicitOptions o;
  o.safety = 0.5;
  o.max_step_s = 1e-4;  // free flight has no stable-step bound; resolve the ~9 ms contact
  ExplicitDriver d(s, o);
  int last_active = 0, changes = 0;
  double worst_momentum = 0, worst_balance = 0;
  const double p0 = testing::momentum(s, d.velocity());
  while (d.time() < 0.8 - 1e-12) {
    d.step(0.8);
    if (s.active_contacts() != last_active) {
      d.request_stable_step();
      last_active = s.active_contacts();
      ++changes;
    }
    worst_momentum = std::max(worst_momentum, std::abs(testing::momentum(s, d.velocity()) - p0));
    worst_balance = std::max(worst_balance, d.energy().relative_balance_error());
  }
  EXPECT_EQ(changes, 2);  // contact made and released
  EXPECT_LT(worst_momentum, 1e-10);
  // Elastic collision: velocities exchanged as for rigid spheres, v1' = −1.25, v2' = 0.25.
  EXPECT_NEAR(d.velocity()(0), -1.25, 1e-3);
  EXPECT_NEAR(d.velocity()(2), 0.25, 1e-3);
  EXPECT_LT(worst_balance, 1e-2);
  EXPECT_LT(std::abs(d.energy().relative_numerical()), 1e-3);
}

TEST(ExplicitDriver, EnergyLimitStopsTheRunWithANamedReason) {
  auto s = collision();
  ExplicitOptions o;
  o.safety = 0.9;
  o.max_step_s = 1e-3;
  o.energy_error_limit = 1e-9;  // far below the O(Δt²) quadrature error of the contact onset
  ExplicitDriver d(s, o);
  try {
    while (d.time() < 0.8 - 1e-12) d.step(0.8);
    FAIL() << "the energy limit did not stop the run";
  } catch (const SolveFailure& e) {
    EXPECT_NE(std::string(e.what()).find("energy_error_limit"), std::string::npos) << e.what();
  }
}

// A system whose force turns non-finite at given dofs from its n-th evaluation on (a blown-up
// element): the step fails with a named reason at the first such dof, the driver's one
// vectorised test per step (allFinite) followed by the search for the dof.
class PoisonedForce final : public DynamicSystem {
 public:
  PoisonedForce(SpringMassSystem& s, int from, std::vector<std::pair<int, double>> poison)
      : s_(s), from_(from), poison_(std::move(poison)) {}
  int dofs() const override { return s_.dofs(); }
  const std::vector<int>& fixed_dofs() const override { return s_.fixed_dofs(); }
  const Eigen::VectorXd& lumped_mass() const override { return s_.lumped_mass(); }
  Eigen::VectorXd initial_velocity() const override { return s_.initial_velocity(); }
  SparseSystem& tangent_system() override { return s_.tangent_system(); }
  void commit(const Eigen::VectorXd& u) override { s_.commit(u); }
  StableStep stable_step(const Eigen::VectorXd& u) const override { return s_.stable_step(u); }
  void evaluate(const Eigen::VectorXd& u, bool t, SystemEvaluation& out) override {
    s_.evaluate(u, t, out);
    if (++calls_ >= from_)
      for (const auto& [dof, value] : poison_) out.force(dof) = value;
  }

 private:
  SpringMassSystem& s_;
  int from_, calls_ = 0;
  std::vector<std::pair<int, double>> poison_;
};

TEST(ExplicitDriver, NonFiniteForceNamesItsFirstDof) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  struct Case { std::vector<std::pair<int, double>> poison; std::string dof; };
  for (const Case& c : {Case{{{4, nan}}, "dof #4"}, Case{{{4, nan}, {2, -inf}}, "dof #2"}, Case{{{0, inf}}, "dof #0"}}) {
    SpringMassSystem base({1.0, 2.0, 3.0}, {0.0, 1.0, 2.0});
    base.add_spring(0, 1, 10.0);
    base.add_spring(1, 2, 10.0);
    base.set_velocity(0, 1.0);
    PoisonedForce s(base, 4, c.poison);
    ExplicitOptions o;
    o.fixed_step_s = 1e-3;
    ExplicitDriver d(s, o);
    d.describe_dof = [](int dof) { return "dof #" + std::to_string(dof); };
    try {
      for (int i = 0; i < 10; ++i) d.step();
      FAIL() << "a non-finite force did not stop the run";
    } catch (const SolveFailure& e) {
      EXPECT_NE(std::string(e.what()).find("non-finite internal force"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("largest at " + c.dof), std::string::npos) << e.what();
    }
    EXPECT_EQ(d.steps(), 2);  // evaluations 1 (start), 2, 3 pass; the 4th fails in step 3
  }
}

TEST(ExplicitDriver, RejectsBadOptions) {
  auto s = oscillator();
  ExplicitOptions o;
  o.safety = 1.5;
  EXPECT_THROW(ExplicitDriver(s, o), std::invalid_argument);
}

}  // namespace
}  // namespace ringcrush::fe
