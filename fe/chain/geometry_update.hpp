// Re-deriving the CPS8 element geometry on a new configuration without allocation
// (performance: the incremental element is re-referenced at every commit, i.e. every
// explicit step, DESIGN.md "Performance"). The natural shape derivatives at the Gauss points
// depend only on the rule and are tabulated once; per commit only J = ∂x/∂ξ, det J and
// ∂N/∂x are recomputed. The result equals cps8_geometry() (tested to round-off).
#pragma once

#include <array>

#include "fe/element/cps8_element.hpp"
#include "fe/element/cps8_rule_tables.hpp"

namespace ringcrush::fe {

class Cps8GeometryUpdater {
 public:
  explicit Cps8GeometryUpdater(Integration rule);

  // geo: built by cps8_geometry() with the same rule (its shape values and Barlow matrix
  // are kept). Throws std::invalid_argument if the element is inverted or degenerate at x.
  void update(const ElementCoords& x, double thickness, Cps8Geometry& geo) const;
  // update() on four elements at once, one vector lane per element (geometry_update_lanes.cpp),
  // bitwise update() on each. Where the lanes cannot repeat update()'s sums exactly (no AVX2,
  // or a vector width other than Eigen's SSE2 / AVX dot products) and for a group with an
  // inverted or degenerate element (update() then throws), the elements go one by one.
  void update_lanes(const std::array<const ElementCoords*, 4>& x, double thickness,
                    const std::array<Cps8Geometry*, 4>& geo) const;
  // Whether update_lanes() runs on vector lanes on this CPU and build.
  static bool lanes_vectorised();
  // The rule's tables the geometry is formed from (also used by cps8_force_lanes_on_coords()).
  const Cps8RuleTables& tables() const { return t_; }

 private:
  Cps8RuleTables t_;
};

}  // namespace ringcrush::fe
