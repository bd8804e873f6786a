// Linear bulk viscosity of the CPS8 element for the explicit driver (ABAQUS/Explicit's
// default damping of the highest element frequency; ABAQUS Theory Manual "Bulk viscosity",
// and the thesis's remark (§3.5) that explicit integration keeps every mode undamped).
//
// A pressure proportional to the in-plane volumetric strain rate acts on top of the material
// stress at every stress point i,
//   q_i = b1 ρ c_d L_e ε̇_vol,i,   ε̇_vol,i = tr ΔE_i / Δt,
// with c_d = √(E / (ρ (1 − ν²))) the plane-stress dilatational wave speed and L_e the
// element's characteristic length. Point by point, not on the element mean as a one-point
// element would: the highest modes of the 8-node element change the volume with alternating
// sign inside the element (zero mean), and those are the modes to damp. Its nodal force is the
// variation of Σ_i w_i q_i tr ΔE_i with q frozen (δ tr ΔE = f : δf, kinematics.hpp):
//   r_a = Σ_i q_i w_i f_i ∇N_a.
// Linear in the rate, it damps a purely dilatational highest mode at ξ = b1 when
// L_e = 2 c_d / ω_e (ω_e the element's highest frequency, the choice ChainModel makes), and
// dissipates Σ q_i ε̇_vol,i w_i ≥ 0. Rigid motions give tr ΔE = 0, hence no force; Σ_a r_a = 0
// (Σ_a ∇N_a = 0), so momentum is kept.
#pragma once

#include "fe/element/cps8_element.hpp"

namespace ringcrush::fe {

// Adds the bulk-viscous force of one element to `force` (16 values) and returns its
// volume-weighted mean pressure (Pa). geo: the element on x_n (its stress points and weights); du: the 16 displacement
// increments of the step; dt: the step (s, > 0); coefficient = b1 ρ c_d L_e (Pa·s).
double add_bulk_viscous_force(const Cps8Geometry& geo, const double* du, double dt, double coefficient,
                              ElementVector& force);

}  // namespace ringcrush::fe
