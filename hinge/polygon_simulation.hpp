// Runs the Level 2 polygon chain (polygon_chain.hpp) in time on IDA (polygon_ida.hpp), on
// Boost.Odeint (dopri5, dense output) or by explicit central difference
// (polygon_central_difference.hpp), sampling the histories, the ring shapes and the
// first yield of every hinge. Plain structs in and out: no scene, no TOML (DESIGN.md).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "polygon_chain.hpp"
#include "polygon_ida.hpp"
#include "polygon_stiffness_spectrum.hpp"

namespace ringcrush::hinge {

enum class PolygonIntegrator { Ida, Odeint, CentralDifference };

struct PolygonRunOptions {
  PolygonIntegrator integrator = PolygonIntegrator::Ida;
  double relative_tolerance = 1e-6;
  double absolute_scale = 1e-6;   // absolute tolerance per component = scale × component scale
  // IDA only: factors on that absolute tolerance for velocities and for θp, ā
  // (PolygonIdaOptions).
  double velocity_tolerance_factor = 1.0;
  double plastic_tolerance_factor = 1.0;
  double end_time_s = 0.05;       // latest end
  bool stop_at_arrest = true;     // end `settle_time_s` after the impactor first stops
  double settle_time_s = 1e-3;
  double output_interval_s = 2e-5;
  double yield_threshold_rad = 1e-4;  // ā above this marks a hinge as having yielded
  double max_step_s = 0.0;        // 0: unbounded
  int ida_max_order = 5;          // IDA BDF order limit (PolygonIdaOptions::max_order)
  PolygonLinearSolver ida_linear_solver = PolygonLinearSolver::Direct;  // PolygonIdaOptions
  PolygonJacobian ida_jacobian = PolygonJacobian::Analytic;             // PolygonIdaOptions
  std::vector<PolygonIdaStep>* ida_step_log = nullptr;                  // PolygonIdaOptions
  int ida_jacobian_reuse_steps = 0;  // PolygonIdaOptions::jacobian_reuse_steps
  int ida_klu_ordering = 1;          // PolygonIdaOptions::klu_ordering
  double ida_pattern_slack = 0.0;    // PolygonIdaOptions::pattern_slack
  // Central difference: × the stable-step bound (CentralDifferenceOptions::safety); the
  // tolerances above do not apply to it.
  double central_difference_safety = 0.8;
  bool central_difference_implicit_dampers = true;  // CentralDifferenceOptions::implicit_ring_dampers
  bool central_difference_power_bound = false;      // CentralDifferenceOptions::power_iteration_bound
  double central_difference_landing_depth_m = 0.0;  // CentralDifferenceOptions::contact_landing_depth
  double central_difference_fixed_step_s = 0.0;     // CentralDifferenceOptions::fixed_step_s
  bool central_difference_implicit_membrane = false;  // CentralDifferenceOptions::implicit_membrane
  // > 0: the run stops with PolygonEnergyLimitError at the first output sample whose
  // |energy balance| / KE0 exceeds this (impact runs: a driven run starts with KE0 = 0 and is
  // not checked). The explicit central difference diverges past its stable step into a
  // bounded garbage state (issue 7: 1.8 M steps to a balance of 1e11, no NaN); the limit is the
  // FE drivers' energy_error_limit. 0: no limit.
  double energy_error_limit = 0.0;
  // Any integrator: at every output sample, the Gershgorin step with each stiffness term left
  // out and the power-iteration estimate of 2/ω_max (stable_step_breakdown,
  // polygon_stiffness_spectrum.hpp) into PolygonRunOutput::step_breakdown. A diagnostic: the
  // run itself is unchanged (the breakdown re-evaluates the chain after the sample).
  bool step_breakdown = false;
};

// The run's energy balance exceeded PolygonRunOptions::energy_error_limit: the integration
// diverged (or the step is too long for the balance asked for).
class PolygonEnergyLimitError : public std::runtime_error {
 public:
  PolygonEnergyLimitError(const std::string& what, double time_s, double relative_error)
      : std::runtime_error(what), time_s_(time_s), relative_error_(relative_error) {}
  double time_s() const { return time_s_; }                  // of the sample that exceeded it
  double relative_error() const { return relative_error_; }  // |balance| / KE0 there
 private:
  double time_s_, relative_error_;
};

struct PolygonHistory {  // full structure (both halves), SI
  std::vector<double> time_s, impactor_displacement_m, impactor_velocity_m_s, impactor_force_n,
      target_force_n;
  std::vector<double> kinetic_j, elastic_j, contact_j, plastic_j, contact_damping_j, damping_j,
      external_j;
  std::vector<PolygonShape> shapes;  // one per sample
};

struct PolygonRunOutput {
  PolygonHistory history;
  std::vector<std::vector<double>> first_yield_time_s;  // [ring][full node], −1 if never
  double initial_energy_j = 0.0;       // kinetic energy at t = 0 (full structure)
  double energy_balance_error = 0.0;   // max over samples of |balance| / max(KE0, external work)
  double arrest_time_s = -1.0;         // first time the impactor speed toward the chain ≤ 0
  double end_time_s = 0.0;
  long steps = 0, rejected_steps = 0, nonlinear_iterations = 0, rhs_evaluations = 0,
       jacobian_setups = 0, linear_iterations = 0, symbolic_factorisations = 0,
       jacobian_formations = 0,  // IDA direct: setups that formed ∂φ/∂y anew
       pattern_rebuilds = 0, pattern_remaps = 0;  // PolygonIdaStatistics
  // Central difference: the smallest and largest step taken and the shortest flow
  // relaxation time met (CentralDifferenceStatistics); 0 for the other integrators.
  double min_step_s = 0.0, max_step_s = 0.0, min_flow_relaxation_s = 0.0;
  long power_refreshes = 0, landing_steps = 0;  // CentralDifferenceStatistics
  // Central difference, implicit membrane: the work of the membrane's implicit correction
  // (CentralDifferenceStatistics::membrane_correction_work_j), full structure, J; in damping_j.
  double membrane_correction_work_j = 0.0;
  // Central difference, elastic-rate hinge dampers (PolygonChainInput::
  // hinge_damper_on_elastic_rate, implicit dampers): the damper moments' work on the plastic
  // rate, ∫ c_θ (θ̇ − θ̇p) θ̇p dt (CentralDifferenceStatistics::hinge_damper_plastic_work_j), full
  // structure, J; in damping_j.
  double hinge_damper_plastic_work_j = 0.0;
  // Largest contact penetration (m) and membrane strain |ℓ/ℓ0 − 1| over the output samples
  // (PolygonChain::max_penetration_last, max_membrane_strain_last): what softened membrane
  // and penalty stiffness cost in geometry.
  double max_penetration_m = 0.0, max_membrane_strain = 0.0;
  double wall_time_s = 0.0;
  std::vector<double> final_state;
  std::vector<std::pair<double, StableStepBreakdown>> step_breakdown;  // (t, breakdown) per sample
};

PolygonRunOutput run_polygon_chain(const PolygonChainInput& input, const PolygonRunOptions& options);

}  // namespace ringcrush::hinge
