// A contact penalty that does not shorten the explicit step (issue 4 performance).
//
// The explicit stable step bounds ω_max² by the largest element eigenvalue ω_e² plus the
// largest contact-spring frequency² ω_c² of the springs near contact (chain_model.hpp,
// stable_step): Δt = 2/√(ω_e² + ω_c²). With the default penalty (ContactInput::penalty_scale
// 1, the stiffness of the material column under the node) ω_c² ≈ 0.4 ω_e² on the thesis chain,
// i.e. the springs take 15–20 % off the element step (README "Performance"). ABAQUS/Explicit
// chooses its default penalty so that "the effect on the time increment is minimal yet the
// allowed penetration is not significant" (Analysis User's Guide, contact constraint
// enforcement in Abaqus/Explicit); its rule is not published. Here it is made explicit: the
// penalty scale is lowered, uniformly over every contact spring of the model, until the
// stiffest spring costs at most a set fraction φ of the element step,
//
//   2/√(ω_e² + ω_c²) ≥ (1 − φ) · 2/ω_e   ⇔   ω_c² ≤ ((1 − φ)^−2 − 1) ω_e²,
//
// with ω_e² the largest element eigenvalue of the undeformed model and ω_c² the spring
// frequency² as the bound counts it (k (1/m_s + 1.25 max 1/m_master) on a deformable master,
// k (1/m_s + 1/m_body) on a rigid face). A uniform factor keeps the penalty's distribution
// over the nodes (tributary length / wall element depth), so the contact law is the same
// law, only softer; a penalty already soft enough is left as it is.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "fe/contact/ring_pair_contact.hpp"

namespace ringcrush::fe {

// ((1 − φ)^−2 − 1): the largest ω_c²/ω_e² that costs at most the fraction φ of the step.
// Throws std::invalid_argument unless φ ∈ (0, 0.5].
double spring_to_element_omega2_limit(double fraction);

// The factor s ∈ (0, 1] for every penalty stiffness so that s · spring_omega2 ≤
// spring_to_element_omega2_limit(fraction) · element_omega2 (1 when it already holds).
// Throws std::invalid_argument on a bad fraction or non-positive / non-finite ω².
double penalty_step_factor(double fraction, double element_omega2, double spring_omega2);

// The largest spring frequency² of the surface passes, k (1/m_s + 1.25 max_master 1/m), as
// SurfaceContact::set_mass forms it for the step bound (mass: lumped, per dof).
double surface_spring_omega2(const std::vector<ContactPass>& passes, const Eigen::VectorXd& mass);

}  // namespace ringcrush::fe
