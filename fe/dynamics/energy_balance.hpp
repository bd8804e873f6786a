// Energy bookkeeping of a dynamic run (issue 4 item 6; STYLE.md practice 6: energy is a
// result). Both drivers keep one EnergyBalance, updated every accepted step.
//
// Definitions (all for the model the DynamicSystem describes; run_dynamic scales by the
// symmetry factor). The system is M ü + f(u) = p with f the internal + contact force and p
// the external load (zero for the chains: the impactor is a mass, the target is fixed):
//
//   KE            = ½ vᵀ M v                                  (kinetic, at the step end)
//   S             = elastic + plastic + contact               (state energies of the model)
//   W_f           = Σ_steps ½ (f_n + f_{n+1}) · (u_{n+1} − u_n) (work of the internal and
//                   contact forces, trapezoidal in the step — the energy the body stored
//                   or dissipated according to the integrator's own path)
//   W_ext         = Σ_steps ½ (p_n + p_{n+1}) · (u_{n+1} − u_n) (zero here, kept for clarity)
//   W_v           = Σ_steps ½ (q_n + q_{n+1}) · (u_{n+1} − u_n) with q the bulk-viscous part of
//                   f (explicit only, bulk_viscosity.hpp): the energy the bulk viscosity
//                   dissipated. It has no stored part, so it is not in S nor in W_f.
//
// Two checks, each compared with E_ref = KE0 + S0 + |W_ext| (= KE0 for a chain that starts
// unstressed; the initial energy of a toy oscillator started from a displaced state):
//
//   balance error        = (S − S0) − W_f
//       the state energies must equal the work the forces did on the path. A wrong tangent
//       of the energy, a plastic work that is not the stress power, a contact force that is
//       not the gradient of its potential, or a step too coarse for the contact onset all show
//       here. This is `energy_balance_error` (< 1 % for explicit, issue 4 b).
//   numerical dissipation = KE0 + W_ext − KE − W_f − W_v
//       the energy the time integrator itself removed: O(Δt²) and bounded (not accumulating)
//       for central difference, ≥ 0 for HHT-α with α < 0 (its algorithmic damping of the high
//       modes, thesis §3.5), zero to round-off for α = 0 on linear systems (trapezoidal rule).
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "fe/dynamics/dynamic_system.hpp"

namespace ringcrush::fe {

struct EnergyBalance {
  double initial_kinetic = 0;   // KE0
  double initial_stored = 0;    // S0
  double kinetic = 0, elastic = 0, plastic = 0, contact = 0;
  double force_work = 0;        // W_f
  double external_work = 0;     // W_ext
  double viscous_work = 0;      // W_v: bulk-viscous dissipation

  double stored() const { return elastic + plastic + contact; }
  double reference() const {
    const double e = initial_kinetic + initial_stored + std::abs(external_work);
    return e > 0 ? e : 1.0;  // a system at rest with no load: report absolute values
  }
  double balance_error() const { return (stored() - initial_stored) - force_work; }
  double numerical() const { return initial_kinetic + external_work - kinetic - force_work - viscous_work; }
  double relative_balance_error() const { return std::abs(balance_error()) / reference(); }
  double relative_numerical() const { return numerical() / reference(); }

  static double kinetic_energy(const Eigen::VectorXd& mass, const Eigen::VectorXd& v) {
    return 0.5 * v.cwiseAbs2().dot(mass);
  }
  void set_state(double ke, const SystemEvaluation& ev) {
    kinetic = ke;
    elastic = ev.elastic_energy;
    plastic = ev.plastic_work;
    contact = ev.contact_energy;
  }
  void start(double ke, const SystemEvaluation& ev) {
    set_state(ke, ev);
    initial_kinetic = ke;
    initial_stored = stored();
    force_work = 0;
    external_work = 0;
    viscous_work = 0;
  }
  // Trapezoidal work of the forces over one step (fixed dofs do not move, so their
  // reactions do no work).
  void add_step(const Eigen::VectorXd& f_old, const Eigen::VectorXd& f_new, const Eigen::VectorXd& du) {
    force_work += 0.5 * (f_old + f_new).dot(du);
  }
  // The same with the bulk-viscous parts q of f split off into W_v (empty q: none).
  void add_step(const Eigen::VectorXd& f_old, const Eigen::VectorXd& f_new, const Eigen::VectorXd& q_old,
                const Eigen::VectorXd& q_new, const Eigen::VectorXd& du) {
    add_step(f_old, f_new, du);
    double w = 0;
    if (q_old.size() == du.size()) w += 0.5 * q_old.dot(du);
    if (q_new.size() == du.size()) w += 0.5 * q_new.dot(du);
    force_work -= w;
    viscous_work += w;
  }
  // The same from the sums Σ (f_n + f_{n+1})·Δu and Σ (q_n + q_{n+1})·Δu formed elsewhere (the
  // explicit step's end, explicit_step_end.hpp: in another order than the dot products above,
  // so the two differ in round-off only).
  void add_step_sums(double force_du, double viscous_du) {
    force_work += 0.5 * force_du;
    const double w = 0.5 * viscous_du;
    force_work -= w;
    viscous_work += w;
  }
};

}  // namespace ringcrush::fe
