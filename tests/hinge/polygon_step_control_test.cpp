// The central-difference step controls beyond the Gershgorin bound
// (hinge/polygon_central_difference.hpp): the contact landing (polygon_contact_landing.cpp) and
// the power-iteration step bound (polygon_stiffness_spectrum.hpp), on the two-ring Test 30
// chain struck at 27.7 m/s.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "hinge/polygon_central_difference.hpp"
#include "hinge/polygon_simulation.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

namespace {

PolygonRunOutput run_cd(const PolygonChainInput& in, double landing_depth, bool power, double end) {
  PolygonRunOptions o;
  o.integrator = PolygonIntegrator::CentralDifference;
  o.end_time_s = end;
  o.output_interval_s = 1e-5;
  o.central_difference_landing_depth_m = landing_depth;
  o.central_difference_power_bound = power;
  return run_polygon_chain(in, o);
}

double crush(const PolygonRunOutput& out, const PolygonChainInput& in, int ring) {
  PolygonChain chain(in);
  return two_ring_chain::crush(chain.shape(out.final_state.data()), ring, in);
}

}  // namespace

// The impactor 0.3 t above ring 1's top node, closing at V with the rings at rest: the one
// pair that closes is the top node's, and the landing step is (gap + depth)/V; once the
// impactor is 0.1 t in, depth/V.
TEST(PolygonStepControl, LandingStepIsTheTimeToTheLandingDepth) {
  const PolygonChainInput in = two_ring_chain::input(PolygonJoint::Free);
  PolygonChain chain(in);
  std::vector<double> y = chain.initial_state(), phi(y.size());
  const double t = in.wall_thickness_m, depth = 0.002 * t;
  // Top node (axis node 0 of ring 0) at y_top; the impactor's face at y_top + t/2 + gap.
  const double top = y[chain.node_offset(0, 0) + 1];
  const double face = chain.shape(y.data()).body_faces[0];
  y[chain.body_offset(0)] += (top + 0.5 * t + 0.3 * t) - face;
  const double V = -y[chain.body_offset(0) + 1];
  ASSERT_NEAR(V, in.impactor_velocity_m_s, 1e-12);
  chain.generalised_forces(0.0, y.data(), phi.data());
  EXPECT_EQ(chain.contact_landing_step(), std::numeric_limits<double>::infinity());  // off by default
  chain.set_contact_landing(depth, 1.0);
  chain.generalised_forces(0.0, y.data(), phi.data());
  EXPECT_NEAR(chain.contact_landing_step(), (0.3 * t + depth) / V, 1e-12 * (0.3 * t + depth) / V);
  // Slower than min_speed: not noted.
  chain.set_contact_landing(depth, 1.5 * V);
  chain.generalised_forces(0.0, y.data(), phi.data());
  EXPECT_EQ(chain.contact_landing_step(), std::numeric_limits<double>::infinity());
  // Pressed 0.1 t in and still closing: at most `depth` deeper per step.
  y[chain.body_offset(0)] -= 0.4 * t;
  chain.set_contact_landing(depth, 1.0);
  chain.generalised_forces(0.0, y.data(), phi.data());
  EXPECT_NEAR(chain.contact_landing_step(), depth / V, 1e-12 * depth / V);
  EXPECT_THROW(chain.set_contact_landing(-1e-6, 1.0), std::invalid_argument);
  EXPECT_THROW(chain.set_contact_landing(1e-6, -1.0), std::invalid_argument);
}

// The impact's energy-balance error is the penalty contact's closing (½ k δ² per step, δ the
// penetration gained in a step, up to V Δt): landing the steps on the contact cuts it; the
// power-iteration bound takes fewer, longer steps, and with the landing keeps the balance
// below 1e-3 of KE0 and the crush of the Gershgorin run. 0.2 ms of two welded rings (~500
// steps each run).
TEST(PolygonStepControl, LandingCutsTheImpactErrorAndThePowerBoundKeepsTheRun) {
  const PolygonChainInput in = two_ring_chain::input(PolygonJoint::Welded);
  const double end = 2e-4, depth = 0.002 * in.wall_thickness_m;
  const auto base = run_cd(in, 0.0, false, end);
  const auto landed = run_cd(in, depth, false, end);
  const auto power = run_cd(in, depth, true, end);
  const auto power_alone = run_cd(in, 0.0, true, end);
  EXPECT_GE(landed.landing_steps, 1);
  EXPECT_EQ(base.landing_steps, 0);
  // Measured: 4.68e-4 → 1.96e-4 (Gershgorin, 5 shortened steps of 572), 7.25e-4 → 1.92e-4
  // (power bound).
  EXPECT_LT(landed.energy_balance_error, 0.6 * base.energy_balance_error);
  EXPECT_LT(power.energy_balance_error, 0.6 * power_alone.energy_balance_error);
  EXPECT_LT(static_cast<double>(landed.steps), 1.02 * static_cast<double>(base.steps));
  EXPECT_LT(power.energy_balance_error, 1e-3);
  EXPECT_GE(power.power_refreshes, 2);
  EXPECT_LT(static_cast<double>(power.steps), 0.85 * static_cast<double>(landed.steps));
  EXPECT_GT(power.max_step_s, 1.15 * landed.max_step_s);
  for (int ring = 0; ring < 2; ++ring) {
    EXPECT_NEAR(crush(power, in, ring), crush(base, in, ring), 2e-3 * in.outer_diameter_m) << ring;
    EXPECT_NEAR(crush(landed, in, ring), crush(base, in, ring), 2e-3 * in.outer_diameter_m) << ring;
  }
}

TEST(PolygonStepControl, BadPowerBoundOptionsAreErrors) {
  PolygonChain chain(two_ring_chain::input(PolygonJoint::Free));
  CentralDifferenceOptions o;
  o.power_iteration_bound = true;
  o.power_margin = 0.9;
  EXPECT_THROW(PolygonCentralDifference(chain, 0.0, chain.initial_state(), o), std::invalid_argument);
  o.power_margin = 1.1;
  o.power_refresh_steps = 0;
  EXPECT_THROW(PolygonCentralDifference(chain, 0.0, chain.initial_state(), o), std::invalid_argument);
  o.power_refresh_steps = 100;
  o.power_refresh_change = 0.0;
  EXPECT_THROW(PolygonCentralDifference(chain, 0.0, chain.initial_state(), o), std::invalid_argument);
}
