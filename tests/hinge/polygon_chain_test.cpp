// Level 2 polygon chain in time (THEORY §4.3–4.4), verification c of issue 7: the energy
// balance closes to 1e-4 of the impact energy on IDA, and IDA and Odeint (the DAE and the
// ODE form of the same equations) agree on the crush to 1e-3. Short runs of two Test 30
// rings (the first 1 ms of the impact: ring 1 is well into its plastic collapse by then).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "two_ring_chain.hpp"
#include "hinge/polygon_simulation.hpp"

using namespace ringcrush::hinge;

namespace {

PolygonChainInput two_rings(PolygonJoint joint) { return two_ring_chain::input(joint); }

using two_ring_chain::crush;

PolygonRunOutput run(const PolygonChainInput& in, PolygonIntegrator integ, double rtol, double end) {
  PolygonRunOptions o;
  o.integrator = integ;
  o.relative_tolerance = rtol;
  o.absolute_scale = rtol;
  o.end_time_s = end;
  o.output_interval_s = 5e-5;
  return run_polygon_chain(in, o);
}

}  // namespace

TEST(PolygonChain, EnergyBalanceOnIdaWelded) {
  const auto in = two_rings(PolygonJoint::Welded);
  const auto out = run(in, PolygonIntegrator::Ida, 1e-5, 1e-3);
  EXPECT_NEAR(out.initial_energy_j, 0.5 * 0.257 * 27.7 * 27.7, 1e-9);
  EXPECT_LT(out.energy_balance_error, 1e-4);
  // Something happened: ring 1 dissipated a good part of the impact energy.
  EXPECT_GT(out.history.plastic_j.back(), 0.1 * out.initial_energy_j);
}

TEST(PolygonChain, IdaAndOdeintAgreeOnCrush) {
  const auto in = two_rings(PolygonJoint::Free);
  const auto ida = run(in, PolygonIntegrator::Ida, 1e-6, 1e-3);
  const auto ode = run(in, PolygonIntegrator::Odeint, 1e-7, 1e-3);
  ASSERT_EQ(ida.history.time_s.size(), ode.history.time_s.size());
  EXPECT_LT(ode.energy_balance_error, 1e-4);
  for (int ring = 0; ring < 2; ++ring) {
    const double a = crush(ida.history.shapes.back(), ring, in);
    const double b = crush(ode.history.shapes.back(), ring, in);
    EXPECT_NEAR(a, b, 1e-3 * std::max(std::abs(b), 1e-3)) << "ring " << ring + 1;
  }
  EXPECT_GT(crush(ida.history.shapes.back(), 0, in), 5e-3);
}

TEST(PolygonChain, HalfModelMatchesFullRingWhileSymmetric) {
  // The x = 0 symmetry model and the full ring solve the same symmetric problem.
  auto half = two_rings(PolygonJoint::Welded);
  half.rings = 1;
  auto full = half;
  full.half_symmetry = false;
  const auto a = run(half, PolygonIntegrator::Ida, 1e-6, 4e-4);
  const auto b = run(full, PolygonIntegrator::Ida, 1e-6, 4e-4);
  const double ca = crush(a.history.shapes.back(), 0, half);
  const double cb = crush(b.history.shapes.back(), 0, full);
  EXPECT_NEAR(ca, cb, 1e-3 * cb);
  EXPECT_NEAR(a.history.plastic_j.back(), b.history.plastic_j.back(), 1e-3 * b.history.plastic_j.back());
}

TEST(PolygonChain, RejectsBadInput) {
  auto in = two_rings(PolygonJoint::Free);
  in.nodes_per_ring = 50;  // not a multiple of 4 for the half model
  EXPECT_THROW(PolygonChain{in}, std::invalid_argument);
  in = two_rings(PolygonJoint::Plates);
  in.plate_thickness_m = 0.0;
  EXPECT_THROW(PolygonChain{in}, std::invalid_argument);
}

// The run's samples read the impactor and target forces off energies()'s evaluation instead of
// evaluating twice more (polygon_simulation.cpp): the forces must be those of an evaluation
// that records nothing, to the bit, on states in contact with the impactor and the target.
TEST(PolygonChain, SampledForcesAreThoseOfAFreshEvaluation) {
  for (auto joint : {PolygonJoint::Free, PolygonJoint::Welded, PolygonJoint::Plates}) {
    const auto in = two_ring_chain::input(joint);
    PolygonChain chain(in);
    std::vector<double> y = chain.initial_state();
    y[chain.body_offset(0)] -= 0.2 * in.wall_thickness_m;  // impactor pressed into ring 1
    y[chain.node_offset(1, in.nodes_per_ring / 2) + 1] -= 0.1 * in.wall_thickness_m;  // ring 2 into the target
    chain.energies(1e-4, y.data());
    const double impactor = chain.impactor_force_last(), target = chain.target_force_last();
    EXPECT_GT(impactor, 0.0);
    EXPECT_GT(target, 0.0);
    EXPECT_EQ(impactor, chain.impactor_force(1e-4, y.data())) << static_cast<int>(joint);
    EXPECT_EQ(target, chain.target_force(1e-4, y.data())) << static_cast<int>(joint);
  }
}
