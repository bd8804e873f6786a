// The hardening table's σy(ᾱ) on the lanes of the element kernels (element_lanes.hpp), each
// lane bitwise HardeningTable::yield_stress() (j2_plane_stress.cpp) on its own ᾱ: the kernel's
// yield check reads σy(ᾱ_n) at every stress point of four (or eight) elements. Always inlined, for the
// same reason as element_lanes.hpp.
#pragma once

#include <cstddef>
#include <vector>

#include "fe/element/element_lanes.hpp"
#include "fe/material/j2_plane_stress.hpp"

namespace ringcrush::fe::lanes {

// σy(ᾱ) of HardeningTable::yield_stress() on the lanes, bitwise: its formula on the tabulated
// segment differences, each lane taking the first segment with ᾱ < ᾱ_{i+1} (segments visited
// from the last, so the first one found last wins), the last point's σy beyond the table, the
// first point's at ᾱ ≤ 0 (virgin points: then no segment is formed at all). One vector
// formula per segment in place of an out-of-line call per lane.
template <class V>
[[gnu::always_inline]] inline void yield_stress_lanes(const HardeningTable& table, const V& a, V& sy) {
  const std::vector<HardeningPoint>& p = table.points();
  const auto virgin = a <= 0.0;
  const V first = V{} + p.front().yield_stress_pa;
  if (all_lanes(virgin)) {
    sy = first;
    return;
  }
  V r = V{} + p.back().yield_stress_pa;
  for (std::size_t i = p.size() - 1; i >= 1; --i) {
    const V v = p[i - 1].yield_stress_pa + table.rise(i - 1) * (a - p[i - 1].plastic_strain) / table.run(i - 1);
    r = a < p[i].plastic_strain ? v : r;
  }
  sy = virgin ? first : r;
}

}  // namespace ringcrush::fe::lanes
