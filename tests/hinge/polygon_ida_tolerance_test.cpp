// Level 2 on IDA: what sets the step count (README, Level 2 speed). The step log
// (PolygonIdaOptions::step_log) records every accepted BDF step with the component whose
// weighted local error was largest; on the first millisecond of two Test 30 rings at the
// Level 2 tolerance (rtol 1e-3, absolute 1e-6 × scale) the node velocities limit most steps.
// Looser absolute tolerances on velocities and on θp, ā (the Level 2 defaults, ×30 and ×3)
// take far fewer steps for the same crush and an energy balance inside the Test 30 bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "two_ring_chain.hpp"
#include "hinge/polygon_simulation.hpp"

using namespace ringcrush::hinge;

namespace {

struct LoggedRun {
  PolygonRunOutput out;
  std::vector<PolygonIdaStep> steps;
};

LoggedRun run(const PolygonChainInput& in, double velocity_factor, double plastic_factor) {
  LoggedRun r;
  PolygonRunOptions o;
  o.relative_tolerance = 1e-3;  // Level 2's run tolerance (compare/hinge_run_2d.hpp)
  o.absolute_scale = 1e-6;
  o.velocity_tolerance_factor = velocity_factor;
  o.plastic_tolerance_factor = plastic_factor;
  o.end_time_s = 1e-3;
  o.output_interval_s = 5e-5;
  o.ida_step_log = &r.steps;
  r.out = run_polygon_chain(in, o);
  return r;
}

using two_ring_chain::crush;

}  // namespace

TEST(PolygonIdaTolerance, StepLogHoldsEveryAcceptedStep) {
  const auto in = two_ring_chain::input(PolygonJoint::Welded);
  const auto r = run(in, 1.0, 1.0);
  ASSERT_EQ(static_cast<long>(r.steps.size()), r.out.steps);
  const PolygonChain chain(in);
  double t = 0.0;
  for (const auto& s : r.steps) {
    EXPECT_GT(s.t, t);
    EXPECT_GT(s.h, 0.0);
    EXPECT_NEAR(s.t - t, s.h, 1e-12 + 1e-9 * s.t);  // consecutive steps: t_n − t_{n−1} = h_n
    EXPECT_GE(s.order, 1);
    EXPECT_LE(s.order, 5);
    EXPECT_GE(s.worst_component, 0);
    EXPECT_LT(s.worst_component, static_cast<long>(chain.size()));
    t = s.t;
  }
  EXPECT_GE(t, 1e-3);
}

TEST(PolygonIdaTolerance, NodeVelocitiesLimitMostStepsAtTheLevel2Tolerance) {
  const auto in = two_ring_chain::input(PolygonJoint::Welded);
  const auto r = run(in, 1.0, 1.0);
  const auto kinds = PolygonChain(in).component_kinds();
  long velocity = 0;
  for (const auto& s : r.steps)
    if (kinds[static_cast<std::size_t>(s.worst_component)] == PolygonChain::Component::Velocity) ++velocity;
  // Measured 999 of 1211.
  EXPECT_GT(static_cast<double>(velocity), 0.5 * static_cast<double>(r.steps.size()))
      << velocity << " of " << r.steps.size() << " steps";
}

TEST(PolygonIdaTolerance, LooserVelocityAndPlasticToleranceKeepCrushAndEnergy) {
  const auto in = two_ring_chain::input(PolygonJoint::Welded);
  const auto tight = run(in, 1.0, 1.0);
  const auto loose = run(in, 30.0, 3.0);
  // Measured 770 against 1211 steps (the whole Test 30 chain: 3293 against 8887).
  EXPECT_LT(static_cast<double>(loose.out.steps), 0.7 * static_cast<double>(tight.out.steps))
      << loose.out.steps << " against " << tight.out.steps;
  EXPECT_LT(loose.out.energy_balance_error, 1e-3);
  for (int ring = 0; ring < 2; ++ring) {
    const double a = crush(tight.out.history.shapes.back(), ring, in);
    const double b = crush(loose.out.history.shapes.back(), ring, in);
    // 0.01 mm on a ring of 50.8 mm (crush ratio 2e-4); measured 1 µm.
    EXPECT_NEAR(a, b, 1e-5) << "ring " << ring + 1;
  }
  EXPECT_GT(crush(loose.out.history.shapes.back(), 0, in), 5e-3);
}

TEST(PolygonIdaTolerance, NonPositiveFactorIsABadInput) {
  const auto in = two_ring_chain::input(PolygonJoint::Free);
  PolygonRunOptions o;
  o.velocity_tolerance_factor = 0.0;
  o.end_time_s = 1e-4;
  try {
    run_polygon_chain(in, o);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("velocity_tolerance_factor 0"), std::string::npos) << e.what();
  }
}
