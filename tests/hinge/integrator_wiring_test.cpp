// The IDA and Boost.Odeint wiring proved on problems with closed-form answers.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "hinge/ida_solver.hpp"
#include "hinge/odeint_integrator.hpp"

using namespace ringcrush::hinge;

namespace {

// Index-1 DAE: x′ = −k x + z, 0 = z − sin t. Closed form with x(0) = 1:
// x = C e^{−kt} + (k sin t − cos t)/(1 + k²), C = 1 + 1/(1 + k²).
class ForcedDecay : public DaeSystem {
 public:
  explicit ForcedDecay(double k) : k_(k) {}
  std::size_t size() const override { return 2; }
  void residual(double t, const double* y, const double* yp, double* r) override {
    r[0] = yp[0] + k_ * y[0] - y[1];
    r[1] = y[1] - std::sin(t);
  }
  std::vector<double> differential_mask() const override { return {1.0, 0.0}; }
  bool has_jacobian() const override { return true; }
  void jacobian(double, double cj, const double*, const double*, JacobianSink& j) override {
    j.set(0, 0, cj + k_);
    j.set(0, 1, -1.0);
    j.set(1, 1, 1.0);
  }
  double exact(double t) const {
    const double a = 1.0 + k_ * k_;
    return (1.0 + 1.0 / a) * std::exp(-k_ * t) + (k_ * std::sin(t) - std::cos(t)) / a;
  }

 private:
  double k_;
};

// Harmonic oscillator x″ = −ω² x as a first-order DAE with an event at x = 0.
class Oscillator : public DaeSystem, public OdeSystem {
 public:
  explicit Oscillator(double w) : w_(w) {}
  std::size_t size() const override { return 2; }
  void residual(double, const double* y, const double* yp, double* r) override {
    r[0] = yp[0] - y[1];
    r[1] = yp[1] + w_ * w_ * y[0];
  }
  std::size_t root_count() const override { return 1; }
  void roots(double, const double* y, const double*, double* g) override { g[0] = y[0]; }
  void rhs(double, const double* y, double* dydt) override {
    dydt[0] = y[1];
    dydt[1] = -w_ * w_ * y[0];
  }
  double w_;
};

}  // namespace

TEST(IdaWiring, IndexOneDaeMatchesClosedForm) {
  ForcedDecay dae(3.0);
  // Inconsistent guesses for z and x′: IDACalcIC must repair them.
  IdaSolver ida(dae, 0.0, {1.0, 0.7}, {0.0, 0.0}, {.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12});
  ida.calc_initial_conditions(0.1);
  EXPECT_NEAR(ida.y()[1], 0.0, 1e-12);
  EXPECT_NEAR(ida.yp()[0], -3.0, 1e-9);
  for (double t : {0.5, 1.0, 2.0, 5.0}) {
    ida.advance(t);
    EXPECT_NEAR(ida.time(), t, 1e-12);
    EXPECT_NEAR(ida.y()[0], dae.exact(t), 1e-6);
    EXPECT_NEAR(ida.y()[1], std::sin(t), 1e-6);
  }
  const auto stats = ida.statistics();
  EXPECT_GT(stats.steps, 10);
  EXPECT_GT(stats.jacobian_evaluations, 0);  // the analytic Jacobian was used
}

TEST(IdaWiring, BandSolverGivesTheSameAnswer) {
  ForcedDecay dae(3.0);
  IdaOptions o{.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12};
  o.linear_solver = IdaOptions::LinearSolver::Band;
  o.upper_bandwidth = 1;
  o.lower_bandwidth = 1;
  IdaSolver ida(dae, 0.0, {1.0, 0.0}, {-3.0, 0.0}, o);
  ida.calc_initial_conditions(0.1);
  ida.advance(2.0);
  EXPECT_NEAR(ida.y()[0], dae.exact(2.0), 1e-6);
}

TEST(IdaWiring, RootFindingLocatesZeroCrossings) {
  const double w = 2.0;
  Oscillator osc(w);
  IdaSolver ida(osc, 0.0, {1.0, 0.0}, {0.0, -w * w}, {.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12});
  // x = cos(ωt) crosses zero at π/(2ω) (falling) and 3π/(2ω) (rising).
  auto s = ida.advance(10.0);
  ASSERT_TRUE(s.root_found);
  EXPECT_NEAR(s.t, std::numbers::pi / (2 * w), 1e-7);
  EXPECT_EQ(s.roots_found[0], -1);
  s = ida.advance(10.0);
  ASSERT_TRUE(s.root_found);
  EXPECT_NEAR(s.t, 3 * std::numbers::pi / (2 * w), 1e-7);
  EXPECT_EQ(s.roots_found[0], +1);
}

TEST(IdaWiring, FailuresThrowWithTheFunctionName) {
  ForcedDecay dae(3.0);
  IdaSolver ida(dae, 0.0, {1.0, 0.0}, {-3.0, 0.0}, {.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12, .max_steps = 3});
  try {
    ida.advance(100.0);
    FAIL() << "expected IDA_TOO_MUCH_WORK";
  } catch (const IdaError& e) {
    EXPECT_NE(std::string(e.what()).find("IDASolve"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("IDA_TOO_MUCH_WORK"), std::string::npos) << e.what();
  }
}

TEST(OdeintWiring, OscillatorMatchesClosedForm) {
  const double w = 2.0;
  Oscillator osc(w);
  std::vector<double> y{1.0, 0.0};
  OdeintStatistics stats;
  double max_error = 0.0;
  integrate_dense(osc, y, 0.0, 5.0, {.relative_tolerance = 1e-11, .absolute_tolerance = 1e-12},
                  [&](double t0, double t1, const auto& at) {
                    std::vector<double> s;
                    at(0.5 * (t0 + t1), s);  // the dense output between steps
                    max_error = std::max(max_error, std::abs(s[0] - std::cos(w * 0.5 * (t0 + t1))));
                    return true;
                  },
                  &stats);
  EXPECT_NEAR(y[0], std::cos(w * 5.0), 1e-6);
  EXPECT_NEAR(y[1], -w * std::sin(w * 5.0), 1e-6);
  EXPECT_LT(max_error, 1e-6);
  EXPECT_GT(stats.steps, 10);
}
