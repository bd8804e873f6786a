// What the per-increment CPS8 geometry is formed from (geometry_update.hpp, and the lane
// kernel that forms it in registers, cps8_force_lanes.hpp): for one integration rule
// (thesis §3.6.1.4) the natural shape derivatives ∂N/∂ξ at the stress points and, for the
// selective rule, at the 2×2 (Barlow) points, and the Gauss weights. They depend on the rule
// only, so they are tabulated once; every consumer reads the same table, hence the same bits.
#pragma once

#include <array>

#include "fe/element/cps8_shape.hpp"
#include "fe/fe_input.hpp"

namespace ringcrush::fe {

struct Cps8RuleTables {
  Integration rule = Integration::Full;
  int points = 0;                        // stress points: 9 (Full, Selective) or 4 (Reduced)
  int reduced = 0;                       // Barlow points: 4 (Selective) or 0
  std::array<ShapeGrad, 9> dn{};         // ∂N/∂ξ at the stress points
  std::array<double, 9> weight{};        // Gauss weights
  std::array<ShapeGrad, 4> dn_reduced{};  // Selective: ∂N/∂ξ at the 2×2 points
};

Cps8RuleTables cps8_rule_tables(Integration rule);

}  // namespace ringcrush::fe
