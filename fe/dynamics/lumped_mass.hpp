// Lumped (diagonal) mass of the CPS8 element for the explicit central-difference driver
// (issue 4 item 5). The row-sum lumping of the serendipity element is not usable: its corner
// rows sum to a negative mass (−1/12 of the element mass each on a rectangle). The HRZ
// scheme (Hinton, Rock & Zienkiewicz 1976) keeps the diagonal of the consistent mass
// ρ t ∫ N_a² dA, which is positive, and scales it so that the nodal masses add up to the
// element mass ρ t A exactly (on a parallelogram: 3/76 of the mass at each corner, 16/76 at
// each mid-side node, from ∫N_corner² : ∫N_mid² = 2/15 : 32/45).
#pragma once

#include <array>

#include "fe/element/cps8_element.hpp"

namespace ringcrush::fe {

// Nodal masses (kg, one per node; the same for its x and y dof) of a CPS8 element with
// reference coordinates x, density rho and thickness (ring width). 3×3 Gauss: exact for
// N_a² on a parallelogram. Throws std::invalid_argument if the element is degenerate.
std::array<double, 8> hrz_lumped_mass(const ElementCoords& x, double density, double thickness);

}  // namespace ringcrush::fe
