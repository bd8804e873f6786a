// Explicit central-difference (leapfrog) integration of the Level 2 polygon chain
// (polygon_chain.hpp), as an explicit FE code integrates a lumped-mass model: the chain's
// mass is diagonal, so one force evaluation per step advances it.
//
// One step of size Δt from the synchronised state (x_n, v_n) with a_n = φ(x_n, v_{n−½})/μ:
//   v_{n+½} = v_n + ½Δt a_n,   x_{n+1} = x_n + Δt v_{n+½},
//   θp, ā at x_{n+1} by backward Euler (PolygonChain::advance_plastic_flow: the flow relaxes
//     faster than the step),
//   a_{n+1} = φ(x_{n+1}, v_{n+½})/μ — the velocity-dependent forces (Hunt–Crossley,
//     Kelvin–Voigt, mass damping) from the half-step velocity, as explicit FE codes do —,
//   v_{n+1} = v_{n+½} + ½Δt a_{n+1};
// the dissipated energies (contact damping, Kelvin–Voigt and mass damping, external work)
// accumulate by the trapezoidal rule on the powers of the two evaluations, the plastic work
// as ½(M_n + M_{n+1}) Δθp per hinge, with the moments the two evaluations' forces used
// (polygon_flow_update.cpp: that closes the hinges' share of the balance). With equal steps this is the classical central difference
// (v_{n+½} = v_{n−½} + Δt a_n); the synchronised v_n serve the outputs.
//
// The step: safety × PolygonChain::stable_step() of the current state (contacts included),
// re-computed after every step, and shortened so that every `advance` target is met exactly.
//
// Implicit ring dampers (CentralDifferenceOptions::implicit_ring_dampers, the default): the
// Kelvin–Voigt bar and hinge dampers, forces −C(x) v (polygon_implicit_dampers.cpp), leave
// φ and enter the two half-kicks at the step's ends — the trapezoidal rule on the damping:
//   v_{n+½} = v_n + ½Δt μ⁻¹(f(x_n, v_{n−½}…) − C_n v_n),
//   (μ + ½Δt C_{n+1}) v_{n+1} = μ v_{n+½} + ½Δt f(x_{n+1}, v_{n+½})
// (f the other forces, explicit as above; one banded solve per ring). For one mode
// (ω, ξ) the amplification matrix has spectral radius ≤ 1 for ωΔt ≤ 2 whatever ξ, so the
// stable step is that of the undamped stiffness (PolygonChain::stable_step leaves the
// dampers out): ≈ 3× the explicit dampers' at ζ = 1. The damper work is booked as the work
// of the damper forces in the two kicks, Δt/4 [d_n·(v_n + v_{n+½}) + d_{n+1}·(v_{n+½} + v_{n+1})]
// with d = C v: exactly their share of the kinetic-energy change of the step, so the
// balance closes as with the explicit dampers (to the leapfrog's O(Δt²) on the stiffness).
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include "polygon_chain.hpp"
#include "polygon_stiffness_spectrum.hpp"

namespace ringcrush::hinge {

struct CentralDifferenceOptions {
  double safety = 0.8;     // × the stable-step bound; in (0, 1] (the FE explicit driver's 0.8)
  double max_step_s = 0.0;  // 0: none
  // true: the Kelvin–Voigt ring dampers by the trapezoidal rule (above); false: explicit
  // from the half-step velocity with the rest of φ (the step then carries their ξ).
  bool implicit_ring_dampers = true;
  // true: the step is safety × ρ × the Gershgorin bound, ρ = (2/√(margin θ)) / bound ≥ 1 with
  // θ the power-iteration estimate of λ_max of M⁻¹K (PolygonStiffnessSpectrum, warm-started),
  // refreshed every `power_refresh_steps` steps and whenever the bound moved by more than
  // `power_refresh_change` since (a contact closed or opened), at most every
  // `power_min_refresh_steps`. Between refreshes ρ scales the current bound, so a new contact
  // still shortens the step at once. Gershgorin is 1.28–1.45× pessimistic on Test 30
  // (bench-hinge2 --step-breakdown): 17–26 % fewer steps. Alone it takes the impact's
  // energy-balance error over 1e-3 (free, plated); with the contact landing below the balance
  // stays ≈ 2e-4 (README). Off by default. Implicit dampers only: θ is of the undamped
  // stiffness, and with explicit dampers the bound is the damped (2/ω)(√(1 + ξ²) − ξ) with
  // ξ ≈ 1 — ρ from the undamped 2/ω_max would lift that step back to ≈ 2/ω_max, 2.4× past
  // the damped limit (issue 7: the explicit-damper run diverged to a balance of 1e11). With
  // explicit dampers the option is ignored and the damped Gershgorin bound sets the step.
  bool power_iteration_bound = false;
  double power_margin = 1.1;  // on θ, ≥ 1 (θ approaches λ_max from below)
  int power_refresh_steps = 200, power_min_refresh_steps = 10;
  double power_refresh_change = 0.05;
  // > 0: contact landing (PolygonChain::set_contact_landing, polygon_contact_landing.cpp) —
  // each step is also at most the time in which a pair closing faster than
  // `contact_landing_speed` reaches this penetration (m) or, touching, goes this much deeper:
  // a closing contact is first seen at a penetration ≤ depth instead of anywhere up to ṗ Δt,
  // and the fast part of an impact is stepped at ≤ depth per step. 0: off.
  double contact_landing_depth = 0.0;
  double contact_landing_speed = 1.0;  // m/s
  // > 0: every step is this (s) whatever the bound and the landing (advance still meets its
  // targets exactly): step-convergence studies, and a step above the bound to show that the
  // divergence is caught (the run's energy limit, polygon_simulation.hpp). 0: the bound.
  double fixed_step_s = 0.0;
};

struct CentralDifferenceStatistics {
  long steps = 0, rhs_evaluations = 0;
  double min_step_s = std::numeric_limits<double>::infinity(), max_step_s = 0.0;
  // Shortest relaxation time 1/(∂λ̇/∂θp) of a flowing hinge met in the run.
  double min_flow_relaxation_s = std::numeric_limits<double>::infinity();
  long power_refreshes = 0;  // power-iteration estimates made (power_iteration_bound)
  long landing_steps = 0;    // steps shortened by the contact landing
};

class PolygonCentralDifference {
 public:
  PolygonCentralDifference(PolygonChain& chain, double t0, std::vector<double> y0,
                           const CentralDifferenceOptions& options);
  // Steps to t_end (> time()) and returns it.
  double advance(double t_end);
  double time() const { return t_; }
  const std::vector<double>& y() const { return y_; }  // synchronised state at time()
  const CentralDifferenceStatistics& statistics() const { return stats_; }
  double stable_step() const { return dt_stable_; }  // safety × bound at the current state

 private:
  void step(double dt);

  PolygonChain& chain_;
  CentralDifferenceOptions options_;
  double t_;
  std::vector<double> y_, a_, a_next_;
  // Implicit dampers: C v at the step's start and end, v_n and v_{n+½} on the node rows.
  std::vector<double> damper_, damper_next_, v_start_, v_half_;
  std::size_t nodes_end_ = 0;  // the node rows: 6 per node from row 0
  std::vector<std::size_t> velocity_rows_, position_rows_;  // the free bodies' pairs x′ = v
  double dt_stable_ = 0.0;
  CentralDifferenceStatistics stats_;
  // power_iteration_bound: the estimator, ρ, the bound at its last refresh and the steps since.
  void update_stable_step();
  std::optional<PolygonStiffnessSpectrum> spectrum_;
  double power_ratio_ = 1.0, power_reference_ = 0.0;
  long power_age_ = 0;
};

}  // namespace ringcrush::hinge
