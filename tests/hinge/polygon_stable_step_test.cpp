// The central-difference step bound (PolygonChain::stable_step, polygon_stable_step.cpp)
// against the true highest frequency of the chain: the generalised eigenvalues of the
// stiffness K = −∂φ/∂x (the analytic Jacobian's position columns, exact on an unloaded
// ring) over the node masses. Without dampers the bound's 2/ω must not exceed 2/ω_max (it is
// a Gershgorin bound), and it should not be loose by more than 1/0.65 (measured: 0.71 of
// 2/ω_max free, 0.77 welded; a looser bound wastes explicit steps). With Kelvin–Voigt dampers
// at ζ_m = ζ_b = 1 (set below, not the tool's defaults: compare/hinge_run_2d.hpp) the step must
// shrink by the damping factor √(1 + ξ²) − ξ, ξ ≥ ζ (measured 0.30 of the undamped step).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "hinge/polygon_chain.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

namespace {

// ω_max² of M⁻¹K over the node position unknowns (bodies held), at the initial state.
double highest_omega_squared(PolygonChain& chain) {
  const auto y = chain.initial_state();
  std::vector<PolygonChain::Triplet> jac;
  chain.analytic_jacobian(0.0, 0.0, y.data(), jac);
  const int nodes = chain.ring_count() * chain.independent_nodes();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * nodes, 2 * nodes);
  const auto mass = [&](int g) {
    const int j = g % chain.independent_nodes();
    const bool axis = chain.input().half_symmetry && (j == 0 || j == chain.independent_nodes() - 1);
    return (axis ? 0.5 : 1.0) * chain.node_mass();
  };
  for (const auto& e : jac) {
    if (e.row >= 6 * nodes || e.col >= 6 * nodes) continue;
    const int rs = e.row % 6, cs = e.col % 6;
    if ((rs != 2 && rs != 3) || (cs != 0 && cs != 1)) continue;  // force rows × position columns
    const int gr = e.row / 6, gc = e.col / 6;
    A(2 * gr + rs - 2, 2 * gc + cs) += e.value / mass(gr);
  }
  // Axis nodes' x are held (no x row): drop them by leaving their rows zero.
  const Eigen::VectorXcd ev = A.eigenvalues();
  double top = 0.0;
  for (Eigen::Index i = 0; i < ev.size(); ++i) top = std::max(top, ev[i].real());
  return top;
}

}  // namespace

TEST(PolygonStableStep, BoundsTheHighestFrequency) {
  for (bool half : {false, true})
    for (auto joint : {PolygonJoint::Free, PolygonJoint::Welded}) {
      PolygonChainInput in = two_ring_chain::input(joint);
      in.half_symmetry = half;
      in.membrane_damping_ratio = 0.0;
      in.hinge_damping_ratio = 0.0;
      PolygonChain chain(in);
      const double omega = std::sqrt(highest_omega_squared(chain));
      const double exact = 2.0 / omega;
      const double bound = chain.stable_step();  // contact rows of the Jacobian's evaluation
      EXPECT_LE(bound, exact * (1.0 + 1e-12)) << "half " << half << " joint " << static_cast<int>(joint);
      EXPECT_GE(bound, 0.65 * exact) << "half " << half << " joint " << static_cast<int>(joint);
      // The bar mode's 2c/ℓ0 (THEORY: c = √(E/ρ)) is the scale.
      const double c = std::sqrt(in.youngs_modulus_pa / in.density_kg_m3);
      EXPECT_NEAR(omega, 2.0 * c / chain.bar_length(), 0.5 * 2.0 * c / chain.bar_length());
    }
}

TEST(PolygonStableStep, DampersShortenTheStep) {
  PolygonChainInput in = two_ring_chain::input(PolygonJoint::Free);
  in.membrane_damping_ratio = 0.0;
  in.hinge_damping_ratio = 0.0;
  PolygonChain undamped(in);
  std::vector<double> y = undamped.initial_state(), phi(y.size());
  undamped.generalised_forces(0.0, y.data(), phi.data());
  const double dt0 = undamped.stable_step();
  in.membrane_damping_ratio = 1.0;
  in.hinge_damping_ratio = 1.0;
  PolygonChain damped(in);
  damped.generalised_forces(0.0, y.data(), phi.data());
  const double dt1 = damped.stable_step();
  EXPECT_LT(dt1, (std::sqrt(2.0) - 1.0) * dt0 * (1.0 + 1e-12));  // ξ ≥ 1
  EXPECT_GT(dt1, 0.2 * dt0);
}
