// Contact of one ring (DESIGN.md "Contact", thesis §3.6.2–3.6.3), penalty (friction below):
//  - rigid plates: the outer-surface nodes against the planes y = y_bottom (fixed target)
//    and y = y_top (driven); gap g = (y − y_bottom) or (y_top − y);
//  - the inner wall against itself (lock-up): nodes of one inner half against the
//    Hermite-smoothed quadratic surface of the other half (two passes by default).
// Penalty energy ½ k g² for g < 0 with k = penalty_scale · E · L · w / h (fe_input.hpp), so
// the force is the gradient of a potential and the tangent is symmetric.
// Optional Coulomb friction (friction_coefficient > 0), penalty-regularised: at the plates
// (plate_friction.hpp) each outer node keeps a stick point per plate; on the inner wall each
// slave keeps a stick point on the smoothed master surface, the slip being measured along
// that surface (self_contact_friction_force below). Committed and trial stick points are kept
// apart like the J2 point states (evaluate() writes trial only, commit() promotes it, a
// rejected increment leaves no trace); the tangent is then not symmetric.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "fe/contact/contact_element.hpp"
#include "fe/contact/smoothed_surface.hpp"
#include "fe/fe_input.hpp"
#include "fe/mesh/ring_mesh.hpp"

namespace ringcrush::fe {

struct ContactState {
  double top_force = 0;         // force the driven plate exerts on the model (≥ 0, downward)
  double bottom_force = 0;      // force the fixed plate exerts on the model (≥ 0, upward)
  double self_force = 0;        // Σ |normal force| of inner-wall contact (per pass pair)
  double energy = 0;            // penalty energy (normal, and tangential stick springs)
  double friction_dissipation = 0;  // plate friction work since the start (trial, model)
  double top_friction_force = 0, bottom_friction_force = 0;  // Σ |t| per plate
  double self_friction_force = 0;  // Σ |t| of inner-wall contact
  int slipping_contacts = 0;
  double max_plate_penetration = 0;
  double max_self_penetration = 0;
  int plate_contacts = 0, self_contacts = 0;
  std::vector<double> node_pressure;  // contact pressure per node (filled on request)
};

class RingContact {
 public:
  RingContact(const RingMesh& mesh, const ContactInput& input, double youngs_modulus, double width);

  // x: current coordinates of all nodes. Appends the active contributions.
  // Writes the trial friction state (stick points) only.
  void evaluate(const std::vector<Eigen::Vector2d>& x, double y_top, double y_bottom, bool want_tangent,
                bool want_pressure, std::vector<ContactContribution>& out, ContactState& state);
  // Makes the trial friction state of the last evaluate() the committed one (call it after
  // evaluating the converged configuration). Out-of-contact nodes are re-anchored where they
  // are, so a node that touches down starts sticking at its touch-down point.
  void commit();
  bool frictional() const { return in_.friction_coefficient > 0; }
  // Committed stick point (x) of outer node i on the top (plate 0) or bottom (plate 1) plate.
  double committed_anchor(std::size_t i, int plate) const { return anchor_n_[2 * i + static_cast<std::size_t>(plate)]; }
  double committed_friction_dissipation() const { return dissipation_n_; }

  double penalty_of_outer(std::size_t i) const { return k_outer_[i]; }

 private:
  struct Pass {
    std::vector<int> slaves;        // node ids
    std::vector<double> slave_k;    // penalty per slave
    std::vector<double> slave_area; // tributary area (w L) per slave
    std::vector<CurvePiece> pieces; // master surface
    // Friction: tangential penalty per slave and its stick point as a surface coordinate
    // S = piece_start[q] + (f − lo) · w_q (NaN: not in contact at the last commit), committed
    // and trial. w_q = 1 on a quadratic part (its parameter is the segment's g) and 2α on a
    // Hermite junction (x'(±1) = 2α dx/dg), so that dx/dS is continuous along a chain and a
    // stick point carries over from one piece to the next; chains are 10 apart in S.
    std::vector<double> slave_kt, anchor_n, anchor_trial, piece_start;
  };
  bool self_pair(const Pass& p, const Eigen::Vector2d& xs, int slave, const CurvePiece& piece,
                 const std::vector<Eigen::Vector2d>& x, double& f, double& gap, double& dist) const;

  const RingMesh& mesh_;
  ContactInput in_;
  double width_;
  std::vector<double> k_outer_, area_outer_, kt_outer_;
  // Plate friction history, two slots (top, bottom) per outer node.
  std::vector<double> anchor_n_, anchor_trial_;
  double dissipation_n_ = 0, dissipation_trial_ = 0;
  std::vector<Pass> passes_;
  // Plate contacts that just touch (gap below this round-off band, e.g. the two contact
  // points of the unloaded ring) carry stiffness but no force: this keeps the vertical
  // rigid-body motion restrained at the start without disturbing Newton later.
  double band_;
};

// Local force of a slave node against a curve piece as a function of the coordinates of the
// slave and the piece nodes (12 values max): k g [n; −c_k n] for g < 0 (used by the
// assembler through finite differences for the tangent and tested alone).
bool self_contact_force(const CurvePiece& piece, const double* coords, double k, double max_depth,
                        double* force, double& gap, double& f_hint, bool strict = true);

// Coulomb friction on the smoothed surface, same penalty regularisation and return mapping as
// at the plates (plate_friction.hpp), added to the normal force of self_contact_force (same
// arguments; the friction force is added into `force`). The stick point is a parameter
// `anchor_n` of this piece's polynomial (a little outside [lo, hi] when it lies on a
// neighbouring piece: the polynomial continues the C¹ surface to second order); NaN when the
// node was not in contact at the last commit: it then sticks at its current closest point.
// Elastic slip g_T = (x_s − x(anchor))·τ along the unit tangent τ at the closest point;
// trial t* = −k_t g_T; slip when |t*| > μ f_n, the stick point then moves along the surface to
// f + t/(k_t |x'(f)|). The slave receives t τ, the piece nodes −c_a(f) t τ.
struct SurfaceFriction {
  double traction = 0;       // along τ, on the slave
  double anchor = 0;         // trial stick point (piece parameter)
  bool slipping = false;
  double stored_energy = 0;  // ½ t² / k_t
  double dissipation = 0;    // μ f_n |t* − t| / k_t
};
bool self_contact_friction_force(const CurvePiece& piece, const double* coords, double k, double kt, double mu,
                                 double anchor_n, double max_depth, double* force, double& gap, double& f_hint,
                                 SurfaceFriction& friction, bool strict = true);

}  // namespace ringcrush::fe
