// HHT-α (thesis §3.5, eqs. 3.5-2a/b; issue 4 item 4) on closed-form systems: the driver's
// states follow the closed-form amplification matrix, the spectral radius tends to
// (1 + α)/(1 − α) at large ωΔt, the error is O(Δt²), α = 0 conserves energy to round-off,
// momentum is exact through a penalty collision, and the half-step residual control halves,
// keeps and grows the step exactly as §3.5 says on a step whose residual is predicted here.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "fe/dynamics/hht_driver.hpp"
#include "fe/time/static_driver.hpp"
#include "dynamic_toy_systems.hpp"

namespace ringcrush::fe {
namespace {

using testing::SpringMassSystem;

constexpr double kPi = 3.14159265358979323846;

SpringMassSystem oscillator(double omega) {
  SpringMassSystem s({1.0}, {0.0});
  s.add_spring(0, -1, omega * omega);
  return s;
}

HhtOptions fixed_step(double alpha, double dt) {
  HhtOptions o;
  o.alpha = alpha;
  o.initial_step_s = o.min_step_s = o.max_step_s = dt;
  o.half_step_control = false;
  o.ptol_n = 1e-10;
  return o;
}

// Closed-form HHT amplification matrix of the unit-mass oscillator, x = (u, v, a):
// L x_{n+1} = R x_n from (3.5-2a) and the two Newmark formulas (3.5-2b).
Eigen::Matrix3d amplification(double alpha, double omega, double dt) {
  const double b = 0.25 * (1 - alpha) * (1 - alpha), g = 0.5 - alpha, w2 = omega * omega;
  Eigen::Matrix3d l, r;
  l << (1 + alpha) * w2, 0, 1, 1, 0, -b * dt * dt, 0, 1, -g * dt;
  r << alpha * w2, 0, 0, 1, dt, (0.5 - b) * dt * dt, 0, 1, (1 - g) * dt;
  return l.fullPivLu().solve(r);
}

double spectral_radius(const Eigen::Matrix3d& a) { return a.eigenvalues().cwiseAbs().maxCoeff(); }

TEST(HhtDriver, StatesFollowTheClosedFormAmplificationMatrix) {
  for (double alpha : {0.0, -0.105, -1.0 / 3.0})
    for (double wdt : {0.3, 2.0, 1000.0}) {
      const double omega = 1.0, dt = wdt / omega;
      auto s = oscillator(omega);
      HhtDriver d(s, fixed_step(alpha, dt), Eigen::Vector2d(1.0, 0.0));
      const Eigen::Matrix3d a = amplification(alpha, omega, dt);
      Eigen::Vector3d x(1.0, 0.0, -omega * omega);
      for (int n = 0; n < 30; ++n) {
        d.step();
        x = a * x;
        const double scale = std::max(1.0, x.cwiseAbs().maxCoeff());
        ASSERT_NEAR(d.displacement()(0), x(0), 1e-9 * scale) << "α " << alpha << " ωΔt " << wdt << " step " << n;
        ASSERT_NEAR(d.velocity()(0), x(1), 1e-9 * scale) << "α " << alpha << " ωΔt " << wdt << " step " << n;
        ASSERT_NEAR(d.acceleration()(0), x(2), 1e-9 * scale) << "α " << alpha << " ωΔt " << wdt << " step " << n;
      }
    }
}

TEST(HhtDriver, SpectralRadiusAtLargeStepIsTheAlgorithmicDamping) {
  for (double alpha : {0.0, -0.105, -0.2, -1.0 / 3.0}) {
    EXPECT_NEAR(spectral_radius(amplification(alpha, 1.0, 1e6)), (1 + alpha) / (1 - alpha), 1e-4) << alpha;
    // ... and no damping of the resolved modes: ρ → 1 as ωΔt → 0.
    EXPECT_NEAR(spectral_radius(amplification(alpha, 1.0, 1e-3)), 1.0, 1e-6) << alpha;
  }
  // The driver damps an unresolved mode as the closed form does: its energy after 10 and 20
  // steps at ωΔt = 1e4 matches the recursion x_{n+1} = A x_n (at ωΔt → ∞ the principal roots
  // coincide at −ρ∞, so the amplitude goes as n ρ∞ⁿ rather than ρ∞ⁿ).
  const double alpha = -0.105, dt = 1e4;
  auto s = oscillator(1.0);
  HhtDriver d(s, fixed_step(alpha, dt), Eigen::Vector2d(1.0, 0.0));
  const Eigen::Matrix3d a = amplification(alpha, 1.0, dt);
  Eigen::Vector3d x(1.0, 0.0, -1.0);
  for (int n = 1; n <= 20; ++n) {
    d.step();
    x = a * x;
    if (n % 10 == 0) {
      const double closed = 0.5 * x(1) * x(1) + 0.5 * x(0) * x(0);
      EXPECT_NEAR(d.energy().kinetic + d.energy().elastic, closed, 1e-9 * closed + 1e-14) << n;
    }
  }
}

double phase_error(double alpha, double dt) {
  auto s = oscillator(2 * kPi);
  HhtDriver d(s, fixed_step(alpha, dt), Eigen::Vector2d(1.0, 0.0));
  while (d.time() < 1.25 - 1e-12) d.step(1.25);
  return std::abs(d.displacement()(0));
}

TEST(HhtDriver, ErrorIsSecondOrder) {
  for (double alpha : {0.0, -0.105, -0.3}) {
    const double e1 = phase_error(alpha, 1.0 / 40), e2 = phase_error(alpha, 1.0 / 80), e3 = phase_error(alpha, 1.0 / 160);
    EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.15) << alpha;
    EXPECT_NEAR(std::log2(e2 / e3), 2.0, 0.15) << alpha;
  }
}

TEST(HhtDriver, TrapezoidalRuleConservesEnergyOfLinearSystems) {
  // α = 0: the average-acceleration rule conserves ½ m v² + ½ k u² exactly on a linear system,
  // and the trapezoidal force work equals the elastic energy, so the numerical dissipation is
  // zero to round-off. A two-mass chain with a coarse step (ω_max Δt > 2).
  SpringMassSystem s({1.0, 2.0}, {0.0, 1.0});
  s.add_spring(0, -1, 100.0);
  s.add_spring(0, 1, 400.0);
  HhtDriver d(s, fixed_step(0.0, 0.1), Eigen::Vector4d(0.3, 0.0, -0.2, 0.0));
  const double e0 = d.energy().kinetic + d.energy().elastic;
  for (int n = 0; n < 1000; ++n) {
    d.step();
    ASSERT_NEAR(d.energy().kinetic + d.energy().elastic, e0, 1e-11 * e0) << n;
  }
  EXPECT_LT(std::abs(d.energy().relative_numerical()), 1e-11);
  EXPECT_LT(d.energy().relative_balance_error(), 1e-11);
}

SpringMassSystem collision() {
  SpringMassSystem s({1.0, 3.0}, {0.0, 0.5});
  s.add_contact(0, 1, 1e5);
  s.set_velocity(0, 1.0);
  s.set_velocity(1, -0.5);
  return s;
}

TEST(HhtDriver, CollisionConservesMomentumAndDissipatesLittle) {
  auto s = collision();
  HhtOptions o;
  o.initial_step_s = 1e-4;
  o.max_step_s = 1e-2;
  o.min_step_s = 1e-9;
  o.haftol_n = 2.0;  // 1 % of the peak contact force (≈ 190 N)
  o.ptol_n = 1e-8;
  HhtDriver d(s, o);
  const double p0 = testing::momentum(s, d.velocity());
  double worst = 0;
  while (d.time() < 0.8 - 1e-12) {
    d.step(0.8);
    worst = std::max(worst, std::abs(testing::momentum(s, d.velocity()) - p0));
  }
  EXPECT_LT(worst, 1e-10);
  EXPECT_NEAR(d.velocity()(0), -1.25, 0.02);
  EXPECT_NEAR(d.velocity()(2), 0.25, 0.01);
  // α < 0 removes energy only from what the step does not resolve: little here.
  EXPECT_GE(d.energy().relative_numerical(), -1e-6);
  EXPECT_LT(d.energy().relative_numerical(), 0.03);
  EXPECT_GT(d.rejected_steps(), 0);  // the contact onset forced at least one halving
}

// First step of the oscillator from u = 0, v = 1 (a_0 = 0): the HHT step and its half-step
// residual in closed form, independently of the driver.
double predicted_half_step_residual(double alpha, double k, double dt) {
  const double b = 0.25 * (1 - alpha) * (1 - alpha);
  const double a1 = -(1 + alpha) * k * dt / (1 + (1 + alpha) * k * b * dt * dt);
  const double h = 0.5 * dt, ah = 0.5 * a1, uh = h + h * h * b * ah;
  return std::abs(ah + (1 + alpha) * k * uh);
}

struct HalfStepCase {
  SpringMassSystem system = oscillator(100.0);
  HhtOptions options;
  HalfStepCase() {
    system.set_velocity(0, 1.0);
    options.initial_step_s = 2e-3;
    options.min_step_s = 1e-8;
    options.max_step_s = 1.0;
    options.ptol_n = 1e-9;
  }
};

TEST(HhtDriver, HalfStepResidualAboveHaftolHalvesTheStep) {
  HalfStepCase c;
  const double r0 = predicted_half_step_residual(c.options.alpha, 1e4, 2e-3);
  const double r1 = predicted_half_step_residual(c.options.alpha, 1e4, 1e-3);
  ASSERT_GT(r0, 2 * r1);
  c.options.haftol_n = std::sqrt(r0 * r1);  // r1 < HAFTOL < r0
  HhtDriver d(c.system, c.options);
  d.step();
  ASSERT_EQ(d.attempts().size(), 2u);
  EXPECT_FALSE(d.attempts()[0].accepted);
  EXPECT_STREQ(d.attempts()[0].outcome, "halved");
  EXPECT_NEAR(d.attempts()[0].half_step_residual_n, r0, 1e-9 * r0);
  EXPECT_TRUE(d.attempts()[1].accepted);
  EXPECT_DOUBLE_EQ(d.attempts()[1].step_s, 1e-3);
  EXPECT_NEAR(d.attempts()[1].half_step_residual_n, r1, 1e-9 * r0);
  EXPECT_DOUBLE_EQ(d.time(), 1e-3);
  EXPECT_EQ(d.rejected_steps(), 1);
}

TEST(HhtDriver, HalfStepResidualBetweenHalfAndFullHaftolKeepsTheStep) {
  HalfStepCase c;
  const double r0 = predicted_half_step_residual(c.options.alpha, 1e4, 2e-3);
  c.options.haftol_n = r0 / 0.75;  // HAFTOL/2 < r0 ≤ HAFTOL
  HhtDriver d(c.system, c.options);
  d.step();
  ASSERT_EQ(d.attempts().size(), 1u);
  EXPECT_STREQ(d.attempts()[0].outcome, "kept");
  EXPECT_DOUBLE_EQ(d.next_step(), 2e-3);
}

TEST(HhtDriver, TwoStepsBelowHalfHaftolGrowTheStepByAQuarter) {
  HalfStepCase c;
  c.options.haftol_n = 1e12;  // every half-step residual is far below HAFTOL/2
  HhtDriver d(c.system, c.options);
  const double expected[] = {2e-3, 2e-3, 2.5e-3, 2.5e-3, 3.125e-3, 3.125e-3};
  for (double dt : expected) {
    d.step();
    EXPECT_DOUBLE_EQ(d.step_size(), dt);
  }
  EXPECT_STREQ(d.attempts()[0].outcome, "small");
  EXPECT_STREQ(d.attempts()[1].outcome, "grown");
  EXPECT_EQ(d.rejected_steps(), 0);
}

TEST(HhtDriver, MinimumStepEndsWithADiagnosis) {
  HalfStepCase c;
  c.options.haftol_n = 1e-30;  // unattainable: halves down to the minimum
  c.options.min_step_s = 1e-6;
  HhtDriver d(c.system, c.options);
  try {
    d.step();
    FAIL() << "no SolveFailure";
  } catch (const SolveFailure& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("HAFTOL"), std::string::npos) << m;
    EXPECT_NE(m.find("minimum"), std::string::npos) << m;
    EXPECT_NE(m.find("dof 0"), std::string::npos) << m;
    EXPECT_NE(m.find("t = 0"), std::string::npos) << m;
  }
  EXPECT_EQ(d.steps(), 0);
  EXPECT_TRUE(d.displacement().allFinite());
}

TEST(HhtDriver, NewtonFailureCutsTheStepToAQuarter) {
  HalfStepCase c;
  c.options.haftol_n = 1e12;
  c.options.ptol_n = 1e-300;  // unattainable: every Newton solve fails
  c.options.max_iterations = 3;
  HhtDriver d(c.system, c.options);
  try {
    d.step();
    FAIL() << "no SolveFailure";
  } catch (const SolveFailure& e) {
    EXPECT_NE(std::string(e.what()).find("Newton failed"), std::string::npos) << e.what();
  }
  const auto& at = d.attempts();
  ASSERT_GE(at.size(), 5u);
  for (std::size_t i = 0; i < at.size(); ++i) {
    EXPECT_STREQ(at[i].outcome, "newton cut-back");
    if (i > 0) {
      EXPECT_DOUBLE_EQ(at[i].step_s, 0.25 * at[i - 1].step_s);
    }
  }
  EXPECT_GE(at.back().step_s, c.options.min_step_s);
  EXPECT_LT(0.25 * at.back().step_s, c.options.min_step_s);
}

TEST(HhtDriver, RejectsAlphaOutsideTheHilberRange) {
  auto s = oscillator(1.0);
  HhtOptions o;
  o.alpha = 0.1;
  EXPECT_THROW(HhtDriver(s, o), std::invalid_argument);
  o.alpha = -0.4;
  EXPECT_THROW(HhtDriver(s, o), std::invalid_argument);
}

}  // namespace
}  // namespace ringcrush::fe
