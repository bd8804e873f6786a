// The one interface the dynamic drivers step (STYLE.md practice 5; thesis §3.5): a
// semi-discrete system  M ü + f(u) = 0  with a lumped (diagonal) mass, internal + contact
// force f that depends on the path only through committed states, and its tangent ∂f/∂u.
// The explicit central-difference and the HHT-α drivers know nothing else about rings, so
// they are verified on small closed-form systems and then run on the ChainModel unchanged.
//
// Contract:
//  - u is the total displacement from the reference configuration; evaluate(u) writes only
//    trial (path) states relative to the last commit, so a rejected step leaves no trace;
//  - commit(u) makes the trial states of the last evaluate(u) the committed ones; when the
//    last evaluate() was at another displacement (the HHT half-step residual, thesis §3.5,
//    evaluates at u_{n+½} after Newton converged at u_{n+1}) commit(u) re-evaluates at u
//    first, so the committed path is always that of the committed displacements;
//  - fixed dofs stay at zero displacement; `force` carries their reactions;
//  - the energies are those of the model (a half model's, not doubled).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fe/assembly/sparse_system.hpp"

namespace ringcrush::fe {

struct ExplicitStepEnd;  // explicit_step_end.hpp

struct SystemEvaluation {
  Eigen::VectorXd force;          // f(u): internal + contact, all dofs
  double elastic_energy = 0;      // recoverable strain energy (J)
  double plastic_work = 0;        // plastic dissipation since t = 0 (J)
  double contact_energy = 0;      // penalty energy stored in the active contacts (J)
  double contact_time_s = 0;      // wall time spent in contact search and forces
  // The part of `force` that is bulk viscosity (rate-dependent, explicit only; empty when the
  // system has none): the drivers book its work as its own dissipation, not as stored energy.
  Eigen::VectorXd viscous_force;
};

struct StableStep {
  double step_s = 0;              // 2/ω_max (without the driver's safety factor)
  std::string limited_by;         // e.g. "element 17 (ring 1)", "contact penalty, node 230"
};

class DynamicSystem {
 public:
  virtual ~DynamicSystem() = default;

  virtual int dofs() const = 0;
  virtual const std::vector<int>& fixed_dofs() const = 0;
  // Diagonal (lumped) mass per dof, > 0 on every free dof.
  virtual const Eigen::VectorXd& lumped_mass() const = 0;
  virtual Eigen::VectorXd initial_velocity() const = 0;

  // evaluate() sizes and writes all of out.force (and sizes out.viscous_force): the explicit
  // driver hands it the buffers of an earlier evaluation instead of fresh ones.
  // want_tangent: also assemble ∂f/∂u into tangent_system().matrix() (free dofs only; the
  // pattern holds the diagonal of every free dof, so a driver may add M/(βΔt²) there).
  // out.force and out.viscous_force are written whole, whatever they held on entry (the
  // explicit driver hands back its previous step's buffers).
  virtual void evaluate(const Eigen::VectorXd& u, bool want_tangent, SystemEvaluation& out) = 0;
  virtual void commit(const Eigen::VectorXd& u) = 0;

  // The explicit driver's evaluation: evaluate(u, false, out), then the step's end
  // (explicit_step_end.hpp: a = −M⁻¹f, v += ½Δt a, the finiteness test, the energy sums) over
  // every dof with its final force. A system may instead run `end` inside its own final force
  // sum, on each dof once its force is final, in any order of the dofs (ChainModel does: one
  // pass over the vectors instead of several, on the serial tail of the two-thread step).
  virtual void evaluate_explicit(const Eigen::VectorXd& u, SystemEvaluation& out, ExplicitStepEnd& end);
  // commit(u) where the caller guarantees that the last evaluate() was at u, and u has not
  // changed since (the explicit driver commits the u it has just evaluated): a system may skip
  // its own test of that (ChainModel: the whole-vector comparison). Default: commit(u).
  virtual void commit_evaluated(const Eigen::VectorXd& u) { commit(u); }
  virtual SparseSystem& tangent_system() = 0;

  // Bound on the highest frequency at displacement u (element eigenvalue inequality plus
  // the active contact stiffness over the node mass); the explicit driver multiplies the
  // step by its safety factor.
  virtual StableStep stable_step(const Eigen::VectorXd& u) const = 0;
  // The re-bound after the contact activity changed, between two full stable_step() calls
  // of the driver: a system may reuse the element part of its last stable_step() (at most
  // the driver's re-bound interval old) and update only the contact springs. Default: the
  // full bound.
  virtual StableStep contact_stable_step(const Eigen::VectorXd& u) const { return stable_step(u); }

  // Explicit driver: the step Δt over which the next evaluate()'s increment u − u_n is taken,
  // so that a rate-dependent force (bulk viscosity, ε̇ = Δε/Δt) can be formed. 0 (the
  // default, and HHT, which never calls it): no rate-dependent force.
  virtual void set_increment_time(double /*dt*/) {}
};

}  // namespace ringcrush::fe
