// Explicit central-difference integration of M ü + f(u) = 0 (issue 4 item 5) over the
// DynamicSystem interface, with the system's lumped (diagonal) mass:
//
//   v_{n+½} = v_n + ½Δt a_n,   u_{n+1} = u_n + Δt v_{n+½},
//   a_{n+1} = −M⁻¹ f(u_{n+1}),  v_{n+1} = v_{n+½} + ½Δt a_{n+1}
//
// (the half-step velocity form, written with the full-step velocity kept for output and
// energies; with a variable Δt it is the usual Belytschko form). Conditionally stable:
// Δt ≤ 2/ω_max. The step is Δt = safety · stable_step(u), where stable_step bounds ω_max from
// the element eigenvalues and the active contact stiffness; it is re-bounded every
// `stable_step_every` steps (and on request_stable_step()), and its contact part whenever
// the caller says the contact activity changed (request_contact_bound(): contacts come and
// go every few steps, the element part changes slowly). What limited it is logged.
//
// A rate-dependent force of the system (bulk viscosity, SystemEvaluation::viscous_force) is
// formed from the step's increment over Δt (set_increment_time before each evaluate), i.e.
// at the half-step velocity v_{n+½}, as explicit codes do; its work is booked as W_v.
//
// Blow-up is detected, never output: a non-finite force or velocity, or a kinetic energy
// above blowup_energy_factor × the reference energy (a conservative system cannot gain
// energy), throws SolveFailure with the time, step, stable step and where it happened.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>

#include "fe/dynamics/dynamic_system.hpp"
#include "fe/dynamics/energy_balance.hpp"

namespace ringcrush::fe {

struct ExplicitOptions {
  double safety = 0.8;              // Δt = safety · 2/ω_max
  int stable_step_every = 100;      // steps between re-bounds of ω_max
  double max_step_s = std::numeric_limits<double>::infinity();
  // > 0: use exactly this step, ignoring the stable step (verification of the stability
  // limit only: the driver then reports blow-up rather than preventing it).
  double fixed_step_s = 0;
  // Kinetic energy above this × reference energy: the integration has blown up.
  double blowup_energy_factor = 10.0;
  // |balance error| / reference energy above this stops the run (0: no limit).
  double energy_error_limit = 0;
  // The mass-scaling target Δt* (mass_scaling.hpp; 0: none), for the log and the count of
  // steps whose stable step stayed below it (contact or crushed elements limiting).
  double mass_scaling_target_s = 0;
};

class ExplicitDriver {
 public:
  // u0: initial displacement (empty: zero); the initial velocity is the system's.
  ExplicitDriver(DynamicSystem& system, const ExplicitOptions& options, const Eigen::VectorXd& u0 = {});

  // One step, shortened so as not to pass t_limit.
  void step(double t_limit = std::numeric_limits<double>::infinity());
  // Re-bound the stable step before the next step.
  void request_stable_step() { rebound_ = true; }
  // The set of active contacts changed: re-bound the contact springs before the next step
  // (DynamicSystem::contact_stable_step; the element part is re-bounded on its schedule).
  void request_contact_bound() { contact_rebound_ = true; }

  double time() const { return t_; }
  double step_size() const { return dt_; }           // last step taken
  double stable_step() const { return dt_stable_; }  // last 2/ω_max bound (no safety)
  const std::string& limited_by() const { return limited_by_; }
  long steps() const { return steps_; }
  double min_step() const { return min_dt_; }
  double max_step() const { return max_dt_; }
  double contact_time() const { return contact_time_; }
  long evaluations() const { return evaluations_; }
  long full_bounds() const { return full_bounds_; }        // stable_step() calls
  long contact_bounds() const { return contact_bounds_; }  // contact_stable_step() calls
  // Steps whose safety × stable step was below the mass-scaling target (0 without one).
  long steps_below_target() const { return steps_below_target_; }

  const Eigen::VectorXd& displacement() const { return u_; }
  const Eigen::VectorXd& velocity() const { return v_; }
  const Eigen::VectorXd& acceleration() const { return a_; }
  const SystemEvaluation& evaluation() const { return ev_; }
  const EnergyBalance& energy() const { return energy_; }

  std::function<void(const std::string&)> log;
  // Names a dof in diagnoses (default "dof N").
  std::function<std::string(int)> describe_dof;

 private:
  void bound_step(bool contact_only);
  void fail(const std::string& what, int dof) const;

  DynamicSystem& sys_;
  ExplicitOptions opt_;
  Eigen::VectorXd inv_mass_;  // 1/M on free dofs, 0 on fixed ones
  Eigen::VectorXd u_, v_, a_, du_, f_old_, q_old_;
  Eigen::VectorXd zeros_;  // the missing q_n of the first step (ExplicitStepEnd::zeros)
  SystemEvaluation ev_;
  EnergyBalance energy_;
  double t_ = 0, dt_ = 0, dt_stable_ = 0, dt_target_ = 0;
  std::string limited_by_, logged_kind_;
  double logged_dt_ = 0;
  bool rebound_ = true, contact_rebound_ = false;
  long full_bounds_ = 0, contact_bounds_ = 0;
  long steps_ = 0, since_bound_ = 0, evaluations_ = 0, steps_below_target_ = 0;
  bool below_target_ = false;
  double min_dt_ = 0, max_dt_ = 0, contact_time_ = 0;
};

}  // namespace ringcrush::fe
