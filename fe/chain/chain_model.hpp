// ChainModel: a chain of CPS8 rings with its impactor, target, interleaved plates and
// welded ties, as a DynamicSystem (dynamic_system.hpp). Built from a ChainInput.
//
// Degrees of freedom are nodal (2 per node, SparseSystem): the rings' nodes (with welded
// neighbours sharing their touching node), then one node per rigid body — the impactor and,
// for `plates` joints, each plate — whose x dof is fixed and whose y dof carries the body.
// Contact (all penalty, frictionless, energy-conserving potentials):
//  - impactor's lower face against ring 1's outer surface; the target plane (fixed) against
//    the last ring; each plate's two faces against the rings above and below it;
//  - ring i's outer surface against ring j's for every pair whose padded bounding boxes
//    overlap (broad phase), two passes (i's nodes on j's surface and j's on i's), so
//    neither ring is master;
//  - every ring's inner wall against itself (lock-up), as RingContact does for one ring.
// Implementation notes for the drivers:
//  - commit(u) takes the trial states of u: if the last evaluate() was at another u (e.g. a
//    half-step residual evaluated after the step), it evaluates u again first;
//  - stable_step(u) bounds the elements at u (exact 16×16 element eigenvalues with the
//    committed thickness λ3 of their points, re-solved when an element's shape or λ3 has
//    changed by 5 %) and the contact springs of the LAST evaluate() within one element depth
//    of contact; call it between evaluate() calls, on the driver's thread; contact_stable_step()
//    keeps the element part of the last stable_step() and updates the contact springs; with
//    ChainInput::step_bound = Assembled both estimate the assembled system's ω_max² (elements
//    and active penalty springs) by warm-started power iteration, times a margin, never above
//    the element + contact bound (fe/dynamics/assembled_eigenvalue.hpp);
//  - commit(u) only marks the element geometry stale: it is re-derived on x_n element by
//    element in the next evaluate()'s element pass (with the bulk viscosity, over the threads);
//  - bulk viscosity (ChainInput::bulk_viscosity, explicit only): a pressure at each stress
//    point proportional to its volumetric strain rate over the step the driver announces through
//    set_increment_time(), with L_e = 2 c_d / ω_e from the element eigenvalue; the force is
//    in SystemEvaluation::force and, separately, viscous_force; stable_step() is reduced by
//    √(1 + b1²) − b1 (the central-difference limit with damping ξ = b1 in the highest mode);
//  - with two threads (ChainInput::threads) the element loop is split over a persistent
//    helper thread (force only: dealt in chunks, fe/dynamics/work_dealer.hpp), and so are the
//    searches of the ring↔ring and inner-wall contact passes (force only: the caller forms the
//    rigid faces' contact and keeps the candidate list, then both threads deal the passes —
//    the caller passes first, the helper elements first — and the caller sums the passes in
//    their serial order, SurfaceContact::finish); the results are bitwise those of one thread.
//    SystemEvaluation::contact_time_s is then the caller's part of the contact only;
//  - the last sums of the force (the helper's half, the contact, the bulk viscosity) are one
//    pass over the dofs on the caller, bitwise the separate sums (chain_force_sum.hpp), and
//    evaluate_explicit() runs the explicit driver's step end in it (explicit_step_end.hpp);
//    commit_evaluated() is commit() without the comparison of u with the evaluated one.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "fe/chain/chain_input.hpp"
#include "fe/contact/contact_arrival.hpp"
#include "fe/dynamics/dynamic_system.hpp"
#include "fe/element/cps8_element.hpp"
#include "fe/mesh/ring_mesh.hpp"

namespace ringcrush::fe {

// The assembled mesh of the chain (global node numbering).
struct ChainMesh {
  std::vector<Eigen::Vector2d> nodes;        // reference coordinates; rigid-body nodes last
  std::vector<std::array<int, 8>> elements;  // CPS8 connectivity, all rings
  std::vector<int> element_ring;             // ring (0-based) of each element
  // Per ring: global ids of its outer-surface nodes ordered by material angle θ from the top
  // apex (θ = 0) through the side (π/2) to the bottom (π) — and on to 2π for a full ring —
  // and θ of each (reference). Feeds compare/measures (RingShape).
  std::vector<std::vector<int>> ring_outer_nodes;
  std::vector<std::vector<double>> ring_outer_theta;
  std::vector<double> ring_centre_y;         // reference centre of each ring
  int impactor_node = -1;
  std::vector<int> plate_nodes;              // plates joints: plate k between rings k and k+1
  bool half_ring = true;
};

struct ChainContactForces {
  double impactor_n = 0;       // contact force on the impactor (model, ≥ 0, pushing it up)
  double target_n = 0;         // force of the target on the last ring (model, ≥ 0)
  double ring_ring_n = 0;      // Σ |normal force| of ring↔ring contact (model)
  double self_n = 0;           // Σ |normal force| of inner-wall contact (model)
  double max_penetration_m = 0;
  // The deepest contact point: slave node (global id) and what it penetrates (for the
  // diagnosis of a failed step: penalty contact acts only up to one through-wall element
  // depth). deepest_ring: the master ring of a ring↔ring contact.
  enum class Surface { None, RingOuter, OwnInnerWall, Impactor, Target, Plate };
  int deepest_node = -1;
  Surface deepest_into = Surface::None;
  int deepest_ring = -1;
  int active = 0;              // active contact points
  // Hash of the sequence of active slave nodes: it changes when the SET of active contacts
  // changes, also at the same count (the explicit driver re-bounds its step on it).
  std::uint64_t active_set = 0;
  int pairs_checked = 0;       // ring pairs that passed the broad phase
  long candidate_pairs = 0;    // (node, surface piece) pairs in the contact candidate list
  long list_rebuilds = 0;      // candidate-list builds so far (ring_pair_contact.hpp)
};

class ChainModel final : public DynamicSystem {
 public:
  explicit ChainModel(const ChainInput& input);
  ~ChainModel() override;

  const ChainInput& input() const { return input_; }
  const ChainMesh& mesh() const { return mesh_; }
  // Forces, masses and energies of the whole chain = symmetry_factor × those of the model.
  double symmetry_factor() const { return mesh_.half_ring ? 2.0 : 1.0; }

  // DynamicSystem
  int dofs() const override;
  const std::vector<int>& fixed_dofs() const override;
  const Eigen::VectorXd& lumped_mass() const override;
  Eigen::VectorXd initial_velocity() const override;
  void evaluate(const Eigen::VectorXd& u, bool want_tangent, SystemEvaluation& out) override;
  void commit(const Eigen::VectorXd& u) override;
  // The step's end inside the final force sum (chain_force_sum.hpp), bitwise evaluate()'s force.
  void evaluate_explicit(const Eigen::VectorXd& u, SystemEvaluation& out, ExplicitStepEnd& end) override;
  // commit(u) without comparing u with the evaluated displacement (the caller guarantees it).
  void commit_evaluated(const Eigen::VectorXd& u) override;
  SparseSystem& tangent_system() override;
  StableStep stable_step(const Eigen::VectorXd& u) const override;
  StableStep contact_stable_step(const Eigen::VectorXd& u) const override;
  // Bulk viscosity (ChainInput::bulk_viscosity > 0): the next evaluate() forms the element
  // volumetric strain rates over this step; 0 switches it off.
  void set_increment_time(double dt) override;

  // Mass scaling (ChainInput::mass_scaling, explicit only; mass_scaling.hpp): what was scaled
  // and the added mass, in the model (a half model: half the chain's). Inactive: report.active false.
  const MassScalingReport& mass_scaling() const;
  // HRZ nodal masses of element e (0-based), scaled if mass scaling scaled it.
  const std::array<double, 8>& element_mass(int e) const;
  // Contact forces of the last evaluate().
  const ChainContactForces& contact_forces() const;
  // Reach of the penalty contact: one element through the wall (a deeper penetration gets
  // no force).
  double contact_depth() const;
  // The surface contact's arrival rule so far (committed; fe/contact/contact_arrival.hpp).
  const ContactArrival& contact_arrival() const;
  // Contact pressure per node of the last evaluate() (for field output).
  std::vector<double> contact_pressure() const;
  int impactor_dof() const { return 2 * mesh_.impactor_node + 1; }
  // Outer extent of ring i along the chain axis at displacement u (H_i of DESIGN.md).
  double ring_extent(int ring, const Eigen::VectorXd& u) const;
  // Point-averaged Mises and PEEQ per element, committed states.
  std::vector<Cps8Fields> element_fields() const;
  // StepBound::Assembled: stable_step() calls, power iterations, calls that fell back to
  // the element bound (iteration not settled).
  struct StepBoundStatistics { long calls = 0, iterations = 0, fallbacks = 0; };
  StepBoundStatistics step_bound_statistics() const;
  // The penalty scale the contact springs use: ChainInput::contact.penalty_scale, lowered by
  // contact_penalty_step_fraction when that is set (fe/contact/penalty_step_cap.hpp).
  double contact_penalty_scale() const;
  // What the last stable_step() / contact_stable_step() was made of (ω² in 1/s², without the
  // driver's safety): the largest element eigenvalue, the largest contact-spring frequency²
  // near contact, the assembled estimate × margin (StepBound::Assembled and converged; 0
  // otherwise; the bound takes it only where it undercuts the element + contact sum) and the bulk-viscosity factor on 2/ω.
  struct StepParts {
    double element_omega2 = 0, contact_omega2 = 0, assembled_omega2 = 0, bulk_factor = 1;
  };
  const StepParts& step_parts() const;
  // Diagnosis of the step (not used by the run): the assembled power-iteration estimate of
  // the element matrices of the last stable_step() WITHOUT the contact springs, times the
  // margin; its own warm-started iterate, so the run's estimates are untouched.
  // StepBound::Assembled only (throws std::logic_error otherwise or before stable_step()).
  double elements_only_assembled_omega2() const;
  // Largest committed point PEEQ of each ring.
  std::vector<double> max_peeq_per_ring() const;

 private:
  // evaluate(), with the explicit step's end run in the final force sum (null: none).
  void evaluate_ending(const Eigen::VectorXd& u, bool want_tangent, SystemEvaluation& out, ExplicitStepEnd* end);
  // commit() once the trial states are known to be those of u.
  void commit_trial();
  struct Impl;
  ChainInput input_;
  ChainMesh mesh_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ringcrush::fe
