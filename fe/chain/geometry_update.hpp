// Re-deriving the CPS8 element geometry on a new configuration without allocation
// (performance: the incremental element is re-referenced at every commit, i.e. every
// explicit step, DESIGN.md "Performance"). The natural shape derivatives at the Gauss points
// depend only on the rule and are tabulated once; per commit only J = ∂x/∂ξ, det J and
// ∂N/∂x are recomputed. The result equals cps8_geometry() (tested to round-off).
#pragma once

#include <array>

#include "fe/element/cps8_element.hpp"

namespace ringcrush::fe {

class Cps8GeometryUpdater {
 public:
  explicit Cps8GeometryUpdater(Integration rule);

  // geo: built by cps8_geometry() with the same rule (its shape values and Barlow matrix
  // are kept). Throws std::invalid_argument if the element is inverted or degenerate at x.
  void update(const ElementCoords& x, double thickness, Cps8Geometry& geo) const;

 private:
  Integration rule_;
  int points_;
  std::array<ShapeGrad, 9> dn_{};          // ∂N/∂ξ at the stress points
  std::array<double, 9> weight_{};         // Gauss weights
  std::array<ShapeGrad, 4> dn_reduced_{};  // Selective: ∂N/∂ξ at the 2×2 points
};

}  // namespace ringcrush::fe
