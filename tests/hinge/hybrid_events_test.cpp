// The event machinery of the integrator layer: root masking in IDA, sign change + bisection
// on Odeint's dense output, and the hybrid driver's restarts with jumps — on problems with
// closed-form answers.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "hinge/hybrid_system.hpp"
#include "hinge/ida_solver.hpp"
#include "hinge/odeint_integrator.hpp"

using namespace ringcrush::hinge;

namespace {

// x″ = −4x from x = 1 (x = cos 2t) as a DAE, root g = x: falling at π/4, rising at 3π/4.
class Cosine : public DaeSystem {
 public:
  std::size_t size() const override { return 2; }
  void residual(double, const double* y, const double* yp, double* r) override {
    r[0] = yp[0] - y[1];
    r[1] = yp[1] + 4.0 * y[0];
  }
  std::size_t root_count() const override { return 1; }
  void roots(double, const double* y, const double*, double* g) override { g[0] = y[0]; }
};

const double quarter = std::numbers::pi / 4.0;

// Restart at the first root, a hair *before* it (g = +1e-13, as a located root may be left),
// with the given mask; returns the next event.
IdaSolver::Step restart_at_first_root(int mask) {
  Cosine c;
  IdaSolver ida(c, 0.0, {1.0, 0.0}, {0.0, -4.0}, {.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12});
  ida.set_stop_time(3.0);
  auto s = ida.advance(3.0);
  EXPECT_TRUE(s.root_found);
  EXPECT_NEAR(s.t, quarter, 1e-8);
  EXPECT_EQ(s.roots_found[0], -1);
  const double t = s.t;
  std::vector<double> y{1e-13, -2.0 * std::sin(2.0 * t)};
  ida.reinit(t, y, {y[1], -4.0 * y[0]}, {mask});
  ida.set_stop_time(3.0);
  s = ida.advance(3.0);
  EXPECT_EQ(ida.restarts(), 1);
  EXPECT_GT(ida.statistics().steps, 5);  // counters kept across the restart
  return s;
}

}  // namespace

TEST(RootMasking, UnmaskedRootAtZeroFiresAgainAtOnce) {
  // Control: the chattering that masking prevents.
  const auto s = restart_at_first_root(0);
  ASSERT_TRUE(s.root_found);
  EXPECT_LT(s.t - quarter, 1e-6);
  EXPECT_EQ(s.roots_found[0], -1);
}

TEST(RootMasking, MaskedRootIsQuietUntilItsNextGenuineCrossing) {
  const auto s = restart_at_first_root(-1);  // expected to leave zero downward: it does
  ASSERT_TRUE(s.root_found);
  EXPECT_NEAR(s.t, 3.0 * quarter, 1e-7);
  EXPECT_EQ(s.roots_found[0], +1);
}

TEST(RootMasking, MaskedRootLeavingTheWrongWayIsStillReported) {
  const auto s = restart_at_first_root(+1);  // expected upward, goes downward: an event
  ASSERT_TRUE(s.root_found);
  EXPECT_LT(s.t - quarter, 1e-6);
  EXPECT_EQ(s.roots_found[0], -1);
}

TEST(RootMasking, InactiveMaskIgnoresTheDepartureAltogether) {
  const auto s = restart_at_first_root(root_mask_inactive);
  ASSERT_TRUE(s.root_found);
  EXPECT_NEAR(s.t, 3.0 * quarter, 1e-7);
}

namespace {

// Bouncing ball: h″ = −g, bounce at h = 0 with restitution e. Closed-form bounce times:
// t_1 = √(2h0/g), then each flight lasts 2 e^k v_1/g.
class Ball : public HybridSystem {
 public:
  Ball(double e, int bounces) : e_(e), max_bounces_(bounces) {}
  std::size_t size() const override { return 2; }
  std::size_t root_count() const override { return 1; }
  void rhs(double, const double* y, double* f) override {
    f[0] = y[1];
    f[1] = -9.81;
  }
  void residual(double t, const double* y, const double* yp, double* r) override {
    rhs(t, y, r);
    r[0] = yp[0] - r[0];
    r[1] = yp[1] - r[1];
  }
  bool has_jacobian() const override { return true; }
  void jacobian(double, double cj, const double*, const double*, JacobianSink& j) override {
    j.set(0, 0, cj);
    j.set(0, 1, -1.0);
    j.set(1, 1, cj);
  }
  void event_roots(double, const double* y, double* g) override { g[0] = y[0]; }
  int root_departure(std::size_t, int) const override { return 1; }  // h rises after a bounce
  EventAction on_event(double t, std::vector<double>& y, const std::vector<int>& fired) override {
    if (fired[0] >= 0) return EventAction::Continue;
    bounce_times.push_back(t);
    y[0] = 0.0;
    y[1] = -e_ * y[1];
    return static_cast<int>(bounce_times.size()) >= max_bounces_ ? EventAction::Stop : EventAction::Continue;
  }
  std::vector<double> bounce_times;

 private:
  double e_;
  int max_bounces_;
};

}  // namespace

TEST(OdeintEvents, BisectionOnDenseOutputLocatesZeroCrossings) {
  // x″ = −ω² x from x = 1: zeros at (2k + 1)π/(2ω).
  struct Osc : OdeSystem {
    std::size_t size() const override { return 2; }
    void rhs(double, const double* y, double* f) override {
      f[0] = y[1];
      f[1] = -4.0 * y[0];
    }
  } osc;
  OdeintEventOptions ev;
  ev.root_count = 1;
  ev.roots = [](double, const std::vector<double>& y, double* g) { g[0] = y[0]; };
  std::vector<double> y{1.0, 0.0};
  double t = 0.0;
  OdeintStatistics stats;
  for (int k = 0; k < 3; ++k) {
    ev.masked = {k == 0 ? 0 : root_mask_inactive};
    const auto s = integrate_until_event(osc, y, t, 10.0, {.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12}, ev, nullptr, &stats);
    ASSERT_TRUE(s.root_found);
    EXPECT_NEAR(s.t, (2 * k + 1) * std::numbers::pi / 4.0, 1e-9);
    EXPECT_EQ(s.roots_found[0], k % 2 == 0 ? -1 : +1);
    t = s.t;
  }
  EXPECT_GT(stats.steps, 10);
}

class BouncingBall : public ::testing::TestWithParam<HybridIntegrator> {};

TEST_P(BouncingBall, BounceTimesMatchClosedForm) {
  const double h0 = 1.0, e = 0.8, g = 9.81;
  Ball ball(e, 5);
  std::vector<double> y{h0, 0.0};
  HybridOptions o;
  o.integrator = GetParam();
  o.relative_tolerance = 1e-10;
  o.absolute_tolerance = 1e-12;
  o.end_time = 20.0;
  long samples = 0;
  const auto out = run_hybrid(ball, 0.0, y, o, [&](double, const std::vector<double>&) { ++samples; });
  ASSERT_EQ(ball.bounce_times.size(), 5u);
  EXPECT_TRUE(out.stopped_by_model);
  double t = std::sqrt(2 * h0 / g), v = std::sqrt(2 * g * h0);
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(ball.bounce_times[k], t, 1e-7) << "bounce " << k + 1;
    v *= e;
    t += 2 * v / g;
  }
  EXPECT_EQ(out.statistics.events, 5);
  EXPECT_GT(out.statistics.steps, 5);
  EXPECT_GT(samples, out.statistics.steps);
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, BouncingBall,
                         ::testing::Values(HybridIntegrator::Ida, HybridIntegrator::Odeint),
                         [](const auto& param_info) { return to_string(param_info.param); });
