// Linear bulk viscosity of the CPS8 element for the explicit driver (ABAQUS/Explicit's
// default damping of the highest element frequency; ABAQUS Theory Manual "Bulk viscosity",
// and the thesis's remark (§3.5) that explicit integration keeps every mode undamped).
//
// A pressure proportional to the in-plane volumetric strain rate of the element,
//   q = b1 ρ c_d L_e ε̇_vol,   ε̇_vol = (Σ_points w tr ΔE) / (Σ_points w) / Δt,
// acts on top of the material stress, with c_d = √(E / (ρ (1 − ν²))) the plane-stress
// dilatational wave speed and L_e the element's characteristic length. Its nodal force is
// the variation of q Σ w tr ΔE (δ tr ΔE = f : δf, kinematics.hpp):
//   r_a = q Σ_points w f ∇N_a.
// It is linear in the rate, so it damps each element's dilatational mode at the fraction of
// critical ξ = b1 when L_e = 2 c_d / ω_e (ω_e the element's highest frequency, the choice
// ChainModel makes), and dissipates q ε̇_vol V ≥ 0. Rigid motions give tr ΔE = 0, hence no
// force; Σ_a r_a = 0 (Σ_a ∇N_a = 0), so momentum is kept.
#pragma once

#include "fe/element/cps8_element.hpp"

namespace ringcrush::fe {

// Adds the bulk-viscous force of one element to `force` (16 values) and returns the pressure
// q (Pa). geo: the element on x_n (its stress points and weights); du: the 16 displacement
// increments of the step; dt: the step (s, > 0); coefficient = b1 ρ c_d L_e (Pa·s).
double add_bulk_viscous_force(const Cps8Geometry& geo, const double* du, double dt, double coefficient,
                              ElementVector& force);

}  // namespace ringcrush::fe
