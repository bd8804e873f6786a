// The element eigenvalue inequality of the explicit stable step (issue 4 item 5): the highest
// frequency of the assembled system with a lumped mass M = Σ M_e is bounded by the largest
// element eigenvalue, ω_max² ≤ max_e λ_max(K_e, M_e) (Rayleigh quotient; Hughes, The Finite
// Element Method, §9.3), so Δt ≤ 2/√(max_e λ_max) is stable for central difference.
//
// K_e is the elastic tangent (which bounds the elastic-plastic one) of the element on its
// current coordinates and with its current thickness: the plane-stress wall thickens where
// it is crushed plastically (out-of-plane stretch λ3 up to ≈ 1.4 at the hinges of the thesis
// chain), and K_e grows in proportion while M_e stays. The committed stress is left out: its
// geometric stiffness is O(σ/E) ≈ 1e-3 of the elastic one, and a point on the yield surface
// would return the softer elastic-plastic tangent.
#pragma once

#include <array>

#include "fe/element/cps8_element.hpp"
#include "fe/material/j2_plane_stress.hpp"

namespace ringcrush::fe {

// λ_max(K_e, M_e) (1/s²) of a CPS8 element with coordinates x, integration rule, reference
// thickness `width`, HRZ nodal masses `mass`, and the out-of-plane stretches λ3 of its
// `points` committed states (states null: λ3 = 1). Throws std::invalid_argument if the
// element is inverted or degenerate.
double element_max_eigenvalue(const ElementCoords& x, const std::array<double, 8>& mass, Integration rule,
                              double width, const J2PlaneStress& material, const PointState* states = nullptr,
                              int points = 0);
// The two halves of it: K_e, the elastic tangent on x with the λ3 of the states, and
// λ_max(K_e, M_e) of a given K_e (the assembled estimate keeps the K_e).
ElementMatrix element_elastic_stiffness(const ElementCoords& x, Integration rule, double width,
                                        const J2PlaneStress& material, const PointState* states = nullptr,
                                        int points = 0);
double element_max_eigenvalue(const ElementMatrix& k, const std::array<double, 8>& mass);

}  // namespace ringcrush::fe
