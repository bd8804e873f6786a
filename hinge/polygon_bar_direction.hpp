// A bar's direction for the implicit kicks' matrices (polygon_implicit_dampers.cpp,
// polygon_implicit_membrane.cpp): with w = p_{k+1} − p_k and r = 1/ℓ² = 1/|w|²,
//   e = w/ℓ = w √r,   n/ℓ = (−w_y, w_x)/ℓ² = (−w_y, w_x) r
// (the gradients ∂ℓ/∂p = (−e, e) and ∂θ/∂p of THEORY §4.3) from one division and one square
// root, where w/√(ℓ²) and (−w_y, w_x)/ℓ² took three divisions, and the membrane's product a
// fourth with another square root. The divider bounds these loops (README, h42): the
// division and the square root are the long latencies. e and n/ℓ are each within ≈ 2 ulp of
// the quotients. The damper band (one ring, or two or four rings on the lanes of a vector:
// polygon_band_lanes.cpp) and K_m take e from here, so the membrane's part of the band and its
// products use the same bits.
#pragma once

#include <cmath>

#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

struct BarDirection {
  double nx, ny;  // n/ℓ
  double ex, ey;  // e
};

inline BarDirection bar_direction(double wx, double wy) {
  const double r = 1.0 / (wx * wx + wy * wy);
  const double s = std::sqrt(r);
  return {-wy * r, wx * r, wx * s, wy * s};
}

// Bars k of several rings on the lanes of a vector V (two rings on a Pair; four on an AVX
// vector in polygon_band_lanes.cpp, whose Sqrt takes each half's sqrtpd): one division and one
// square root for all, each lane the scalar form's operations, so the same bits. Sqrt::of is
// the lanes' correctly rounded square root.
template <class V>
struct BarDirectionLanes {
  V nx, ny, ex, ey;
};

template <class Sqrt, class V>
[[gnu::always_inline]] inline BarDirectionLanes<V> bar_direction_lanes(V wx, V wy) {
  const V r = 1.0 / (wx * wx + wy * wy);
  const V s = Sqrt::of(r);
  return {-wy * r, wx * r, wx * s, wy * s};
}

struct PairSqrt {
  [[gnu::always_inline]] static lanes::Pair of(lanes::Pair x) { return lanes::sqrt(x); }
};

inline BarDirectionLanes<lanes::Pair> bar_direction(lanes::Pair wx, lanes::Pair wy) {
  return bar_direction_lanes<PairSqrt>(wx, wy);
}

}  // namespace ringcrush::hinge
