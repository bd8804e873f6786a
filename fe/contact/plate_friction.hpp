// Penalty-regularised Coulomb friction of one node on a flat rigid plate (DESIGN.md
// "Contact": Coulomb friction optional; THEORY §4 "Coulomb friction with smoothing"). The
// plates are the planes y = const and do not move sideways, so the slip is the node's x.
//
// Elasto-plastic analogy (Wriggers, Computational Contact Mechanics, §5.2): the node is tied
// to a stick point (the "anchor" a on the plate) by a tangential penalty spring k_t, so the
// tangential force of the plate on the node is t = −k_t (x − a), and the slip condition
// |t| ≤ μ f_n plays the yield function. One backward-Euler step from the committed anchor
// a_n (the return mapping):
//   trial  t* = −k_t (x − a_n);
//   stick  |t*| ≤ μ f_n:  t = t*,                a = a_n;
//   slip   |t*| > μ f_n:  t = μ f_n sign(t*),    a = x + t / k_t   (the anchor is dragged);
// the dissipation of the step is μ f_n |a − a_n| (exact for the backward-Euler step) and the
// stored (elastic) part ½ k_t (x − a)² joins the penalty energy.
//
// The residual of the model is internal − external force, so the friction term added to the
// residual is r_x = −t; its consistent tangent is
//   stick  ∂r_x/∂x = k_t,  ∂r_x/∂y = 0;
//   slip   ∂r_x/∂x = 0,    ∂r_x/∂y = −μ sign(t*) ∂f_n/∂y   (not symmetric: f_n couples in).
#pragma once

namespace ringcrush::fe {

struct PlateFriction {
  double traction = 0;       // t: tangential (x) force of the plate on the node
  double anchor = 0;         // a: trial stick point
  bool slipping = false;
  double dr_dx = 0, dr_dy = 0;  // tangent of r_x = −t
  double stored_energy = 0;  // ½ k_t (x − a)²
  double dissipation = 0;    // μ f_n |a − a_n| of this step
};

// x: current node x; normal_force f_n ≥ 0 (the penalty force, 0 out of contact) and its
// derivative with respect to the node's y; k_t > 0; mu ≥ 0; anchor_n: committed stick point.
// Throws std::invalid_argument for μ < 0, k_t ≤ 0 or a non-finite argument.
PlateFriction plate_friction(double x, double normal_force, double dnormal_dy, double k_t, double mu,
                             double anchor_n);

}  // namespace ringcrush::fe
