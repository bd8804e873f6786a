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
// dampers out): ≈ 3× the explicit dampers' step at ζ_m = ζ_b = 1, the defaults when it was
// measured (the ringcrush tool's are Level2Settings', compare/hinge_run_2d.hpp: ζ_m = 1 and,
// since session 18, ζ_b = 0.15; PolygonChainInput's are 0). The damper work is booked as the work
// of the damper forces in the two kicks, Δt/4 [d_n·(v_n + v_{n+½}) + d_{n+1}·(v_{n+½} + v_{n+1})]
// with d = C v: exactly their share of the kinetic-energy change of the step, so the
// balance closes as with the explicit dampers (to the leapfrog's O(Δt²) on the stiffness).
//
// Elastic-rate hinge dampers (PolygonChainInput::hinge_damper_on_elastic_rate): the hinge
// damper moment is c_θ (θ̇ − θ̇p), i.e. its force −Σ c_θ g (g·v − θ̇p) = −(C v − p). The C v part
// stays implicit as above (same matrix, same stable step); p = Σ c_θ θ̇p g is an explicit force
// of x_{n+1} and of the step's plastic rate θ̇p = (θp_{n+1} − θp_n)/Δt from the backward-Euler
// flow update (the rate at n+1 of that update: Δλ = Δt λ̇_{n+1}), added to f(x_{n+1}, …) in both
// kicks that use it, as the other explicit forces are. The damper work booked is that of
// d = C v − p, so the balance closes as before. In a steady flow θ̇p ≈ g·v_{n+½} and the net
// damper force −c_θ g gᵀ(v_{n+1} − v_{n+½}) only adds μ-like inertia along g in the solve.
//
// Implicit membrane (CentralDifferenceOptions::implicit_membrane; implicit dampers only): the
// membrane bars, k_m = EA/ℓ0 unscaled, are the stiffest ring term (README "Which term binds");
// they leave the step bound. In the three-level form of the leapfrog, δ²x = x_{n+1} − 2x_n +
// x_{n−1} = Δt (v_{n+½} − v_{n−½}), the scheme is
//   (μ + ¼Δt² K_m(x_n)) δ²x = Δt² (f(x_n, …) − C v…),
// f all forces (the membrane's exact, nonlinear; hinges, ties, contacts explicit as above),
// K_m = Σ_bars k_m g gᵀ the membrane's material tangent at x_n (polygon_implicit_membrane.cpp;
// the geometric (N/ℓ)(I − e eᵀ) left out). For a linear K = K_m + K_E this is
//   μ δ²x + Δt² [K_E x_n + K_m (¼x_{n+1} + ½x_n + ¼x_{n−1})] = 0:
// Newmark's trapezoidal rule (β = ¼, γ = ½) on the membrane, the central difference on the
// rest — the implicit–explicit partition of Hughes & Liu (1978) in its linearised, one-solve
// form. Stability: with A = μ + ¼Δt² K_m the recurrence is stable iff Δt² (K_m + K_E) ≤ 4A,
// i.e. Δt² K_E ≤ 4μ — the explicit terms' limit ω_E Δt ≤ 2, whatever k_m (no commuting
// assumed). The trapezoidal rule is non-dissipative in the linear case; a membrane mode above
// 2/Δt is stepped with period elongation, not lost. Second order (the ¼Δt² K_m δ²x term is
// O(Δt⁴) per step against Δt² f).
//   In the driver's half-kicks, with h = ½Δt and u = v_{n+1} − v_{n+½} (= v_{n+½} − v_n of the
// next step's first half-kick, the leapfrog's shared acceleration u/h):
//   (μ + h C + h² K_m) u = h (f(x_{n+1}, v_{n+½}) − C v_{n+½}),
// the damper solve with c_b + h k_m for each bar's coefficient (same band). It is posed for v:
//   (μ + h C + h² K_m) v_{n+1} = μ v* + h² K_m v_{n+½},  v* = v_{n+½} + h f/μ,
// and the two kicks' implicit force d = C v + h K_m u (the dampers and the membrane's
// correction g = h K_m u, the force the explicit membrane would have added) is booked as the
// dampers' alone are, ¼Δt [d_n·(v_n + v_{n+½}) + d_{n+1}·(v_{n+½} + v_{n+1})], into the
// Kelvin–Voigt accumulator: exactly its share of the kinetic-energy change. The correction's
// part is the scheme's numerical work, reported (CentralDifferenceStatistics::
// membrane_correction_work_j); what remains of the balance is the leapfrog's own telescoping
// term (the kicks' work against the potential's change), now (Δt/4) f·u with the filtered u —
// never larger than the explicit leapfrog's (Δt²/8μ)|f|² at the same step. The first kick is
// Newmark's first step, the membrane at x_0 + h v_{½} (filter_initial_acceleration).
//   What this does not cover: a contact that closes during a step set by the hinges is as stiff
// as the membrane at penalty scale 1, and the leapfrog's margin is then too thin (Test 30 free
// diverges at safety 0.8, README): the implicit membrane pays with the penalties at 1/16.
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
  // true: the membrane bars implicit (above): they leave the step bound, the step is set by
  // hinges, ties and contacts. Needs implicit_ring_dampers. Off by default.
  bool implicit_membrane = false;
};

struct CentralDifferenceStatistics {
  long steps = 0, rhs_evaluations = 0;
  double min_step_s = std::numeric_limits<double>::infinity(), max_step_s = 0.0;
  // Shortest relaxation time 1/(∂λ̇/∂θp) of a flowing hinge met in the run.
  double min_flow_relaxation_s = std::numeric_limits<double>::infinity();
  long power_refreshes = 0;  // power-iteration estimates made (power_iteration_bound)
  long landing_steps = 0;    // steps shortened by the contact landing
  // implicit_membrane: the work of the membrane's implicit correction h K_m u in the kicks
  // (modelled structure, J; > 0 dissipated), booked in the Kelvin–Voigt accumulator.
  double membrane_correction_work_j = 0.0;
  // Elastic-rate hinge dampers (PolygonChainInput::hinge_damper_on_elastic_rate): the damper
  // moments' work on the plastic rate, Σ ∫ c_θ (θ̇ − θ̇p) θ̇p dt (modelled structure, J; part of
  // the Kelvin–Voigt accumulator, which books ∫ c_θ (θ̇ − θ̇p) θ̇ dt), summed per step at its end.
  double hinge_damper_plastic_work_j = 0.0;
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
  // Implicit membrane: K_m v_{n+½}, K_m v_{n+1}, and the correction h K_m u at the step's
  // start and end.
  std::vector<double> stiff_half_, stiff_end_, correction_, correction_next_;
  // Elastic-rate hinge dampers: θp at the step's start (node rows), the step's θ̇p (θp rows) and
  // the force of the dampers' plastic part (node velocity rows; PolygonChain::
  // hinge_plastic_rate_forces), and its Σ w c_θ θ̇p².
  bool elastic_rate_dampers_ = false;
  std::vector<double> theta_p_start_, plastic_rate_, plastic_force_, inverse_mass_;
  double plastic_square_sum_ = 0.0;
  void add_plastic_rate_forces(double dt);
  void finish_plastic_rate_step(double dt);
  std::size_t nodes_end_ = 0;  // the node rows: 6 per node from row 0
  std::vector<std::size_t> velocity_rows_, position_rows_;  // the free bodies' pairs x′ = v
  double dt_stable_ = 0.0;
  CentralDifferenceStatistics stats_;
  // power_iteration_bound: the estimator, ρ, the bound at its last refresh and the steps since.
  void update_stable_step();
  void filter_initial_acceleration();
  void membrane_step(double h);
  std::optional<PolygonStiffnessSpectrum> spectrum_;
  double power_ratio_ = 1.0, power_reference_ = 0.0;
  long power_age_ = 0;
};

}  // namespace ringcrush::hinge
