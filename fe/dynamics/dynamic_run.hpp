// Dynamic impact of a ring chain (issue 4; thesis §3.5, §4.2): the ChainModel stepped by the
// explicit central-difference or the HHT-α driver until the impactor stops or rebounds and
// the rings are at rest (or the end time), recording the history DESIGN.md asks for.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "fe/chain/chain_input.hpp"
#include "fe/chain/chain_model.hpp"

namespace ringcrush::fe {

enum class DynamicScheme { Explicit, Hht };

struct DynamicSolverInput {
  DynamicScheme scheme = DynamicScheme::Explicit;
  double end_time_s = 0.05;
  // End when the impactor moves away from the chain (or has stopped) and the kinetic
  // energy of everything left is below rest_kinetic_fraction × the initial one.
  bool stop_at_rest = true;
  double rest_kinetic_fraction = 0.01;
  // Stop with a named reason when |energy balance error| / KE0 exceeds this.
  double energy_error_limit = 0.05;
  // Explicit: Δt = safety · 2/ω_max, ω_max re-bounded every `stable_step_every` steps.
  double safety = 0.8;
  int stable_step_every = 100;
  // HHT-α (thesis §3.5): α ∈ [−1/3, 0], β = (1 − α)²/4, γ = 1/2 − α.
  double alpha = -0.105;
  double initial_step_s = 5e-7;
  double min_step_s = 1e-10;
  double max_step_s = 1e-4;
  double haftol_n = 1e4;       // half-step residual tolerance (model forces)
  double ptol_n = 3.0;         // Newton: largest residual force (model)
  int max_iterations = 10;
  // History rows: at most one per output_interval_s (and first, last, and events).
  double output_interval_s = 2e-5;
  int frames = 20;             // field frames over the run (0: none)
};

struct DynamicRow {
  double time_s = 0;
  double impactor_displacement_m = 0;  // travel toward the chain (> 0)
  double impactor_velocity_m_s = 0;    // positive toward the chain
  double impactor_force_n = 0;         // contact force on the impactor (whole chain)
  std::vector<double> ring_crush_m;    // δ_i = H0 − H_i
  // Whole-chain energies (J), definitions in energy_balance.hpp: numerical = KE0 + external −
  // kinetic − W_f, with W_f the trapezoidal work of the internal + contact forces over the
  // steps; it equals KE0 + external − (kinetic + elastic + plastic + contact) up to the
  // energy balance error (elastic + plastic + contact − W_f).
  double kinetic_j = 0, elastic_j = 0, plastic_j = 0, contact_j = 0, numerical_j = 0, external_work_j = 0;
  double bulk_viscous_j = 0;  // explicit with bulk viscosity: W_v, its dissipation (energy_balance.hpp)
  double step_s = 0;
};

struct DynamicFrame {
  double time_s = 0;
  Eigen::VectorXd displacement;              // 2 per node
  std::vector<double> mises_pa, peeq;        // per element
  std::vector<double> stress_pa;             // per element: xx, yy, xy (point average, global axes)
  std::vector<double> contact_pressure_pa;   // per node
};

struct DynamicStatistics {
  long steps = 0, rejected_steps = 0, newton_iterations = 0, factorizations = 0;
  double wall_time_s = 0, contact_time_s = 0;
  double min_step_s = 0, max_step_s = 0;
  std::string step_limited_by;   // explicit: what limited the stable step (last bound)
  // Explicit: full stable-step bounds, contact-only re-bounds, and with the assembled bound
  // its power iterations and the bounds that fell back to the element bound.
  long full_bounds = 0, contact_bounds = 0, bound_iterations = 0, bound_fallbacks = 0;
  // Explicit with a mass-scaling target: steps whose stable step stayed below it.
  long steps_below_mass_scaling_target = 0;
  // The surface contact's arrival rule (fe/contact/contact_arrival.hpp): pairs refused at a
  // deep first sight, the deepest of them (fraction of the through-wall element depth) and
  // where; new pairs admitted, and their deepest first sight (fraction).
  long refused_contact_arrivals = 0;
  double deepest_refused_arrival = 0;
  std::string deepest_refused_arrival_at;
  long admitted_contact_arrivals = 0;
  double deepest_admitted_arrival = 0;
  // The deepest contact penetration over the accepted steps (m) and the penalty scale the
  // contact springs used (ChainModel::contact_penalty_scale).
  double max_penetration_m = 0;
  double contact_penalty_scale = 0;
};

struct DynamicResult {
  ChainMesh mesh;
  std::vector<DynamicRow> history;       // first row: t = 0
  std::vector<DynamicFrame> frames;
  Eigen::VectorXd final_displacement;
  std::vector<double> max_peeq_per_ring;
  double initial_kinetic_j = 0;          // whole chain
  double energy_balance_error = 0;       // max over the run of |elastic + plastic + contact − W_f| / KE0
  double numerical_dissipation = 0;      // final numerical_j / KE0 (HHT > 0; explicit ≈ 0)
  std::string end_reason;                // "arrest", "end_time", ...
  DynamicStatistics statistics;
  // Explicit mass scaling (ChainInput::mass_scaling): the model's report with the masses
  // (element_mass_kg, added_mass_kg) converted to the whole chain (× symmetry factor).
  MassScalingReport mass_scaling;
};

struct DynamicProgress {
  double time_s = 0, end_time_s = 0, step_s = 0, impactor_velocity_m_s = 0, kinetic_fraction = 0;
  long step = 0;
};

struct DynamicCallbacks {
  std::function<void(const DynamicProgress&)> progress;
  std::function<void(const std::string&)> log;
};

// Mass scaling (chain.mass_scaling) with HHT: std::invalid_argument (its step is not set by
// the stable step; scaling would only change the physics). Its safety is solver.safety.
// Throws SolveFailure (static_driver.hpp) with a diagnosis (time, step, residual, where)
// when the HHT step falls below its minimum, and when the energy limit or a non-finite value
// stops the run.
DynamicResult run_dynamic(const ChainInput& chain, const DynamicSolverInput& solver,
                          const DynamicCallbacks& callbacks = {});

}  // namespace ringcrush::fe
