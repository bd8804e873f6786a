// The fully plastic moment a CPS8 ring section carries, relative to M0 = σ0 t²/4 (per unit
// width; THEORY §1.2), as the element's Gauss rule integrates it through the wall.
//
// In the fully plastic state the hoop stress is σ0 sign(y) across the wall (y from the
// mid-surface). Exactly, ∫ σ0 |y| dy = σ0 t²/4 = M0. The FE integrates it on the stress points
// of each element through the wall: with n elements, element k spans ξ ∈ [−1 + 2k/n,
// −1 + 2(k+1)/n] of the wall (ξ = 2y/t), and the factor is Σ_k Σ_j (w_j/n) |c_k + x_j/n|
// (c_k its centre, x_j, w_j the 1-D Gauss points and weights). |ξ| is linear on every element
// that does not straddle the mid-surface, and any Gauss rule integrates that exactly; so an
// even count is exact (1), and an odd count errs on its middle element only, by 1/n² of the
// one-element error. One element: 2 points at ±1/√3 give 2/√3 = 1.155 (too strong), 3 points
// at 0, ±√0.6 give 2·(5/9)·√0.6 = 0.861 (too weak; the middle point sits on the neutral axis)
// — the FE's rings then yield across the section at once (README "FE against the hinge
// model", test RingCrush.OneElementThroughTheWallMissesThePlasticMomentByItsGaussRule).
//
// Points through the wall per rule (cps8_element.hpp, thesis §3.6.1.4): reduced 2; full 3;
// selective 3 — its stress points are the 3×3 ones, and its volumetric part, carried by the
// 2×2 (Barlow) points, reaches them through the bilinear interpolant M_r, which reproduces a
// field linear through the wall exactly (Σ_r M_r(ξ_i) ξ_r = ξ_i), so the moment arm of every
// part is the 3-point rule's (checked on the element's own bending moment, test
// ThroughWallPlasticMoment.TheElementsCarryTheFactor: within 2e-5 for all three rules).
#pragma once

#include "fe/fe_input.hpp"

namespace ringcrush::fe {

// Gauss points across one element in the through-wall direction for this rule: 2 or 3.
int gauss_points_through(Integration rule);

// M_p(FE) / M0 for elements_through ≥ 1 elements through the wall (std::invalid_argument
// otherwise).
double through_wall_plastic_moment(int elements_through, Integration rule);

}  // namespace ringcrush::fe
