// A bar's direction for the implicit kicks' matrices (polygon_implicit_dampers.cpp,
// polygon_implicit_membrane.cpp): with w = p_{k+1} − p_k and r = 1/ℓ² = 1/|w|²,
//   e = w/ℓ = w √r,   n/ℓ = (−w_y, w_x)/ℓ² = (−w_y, w_x) r
// (the gradients ∂ℓ/∂p = (−e, e) and ∂θ/∂p of THEORY §4.3) from one division and one square
// root, where w/√(ℓ²) and (−w_y, w_x)/ℓ² took three divisions, and the membrane's product a
// fourth with another square root. The divider bounds these loops (README, h42): the
// division and the square root are the long latencies. e and n/ℓ are each within ≈ 2 ulp of
// the quotients. The damper band (one ring, or two rings on the lanes of a Pair:
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

// Two bars (two rings' bars k) on the lanes of a Pair (one divpd and one sqrtpd for both):
// each lane the scalar form's operations, so the same bits.
struct BarDirectionPair {
  lanes::Pair nx, ny, ex, ey;
};

inline BarDirectionPair bar_direction(lanes::Pair wx, lanes::Pair wy) {
  const lanes::Pair r = 1.0 / (wx * wx + wy * wy);
  const lanes::Pair s = lanes::sqrt(r);
  return {-wy * r, wx * r, wx * s, wy * s};
}

}  // namespace ringcrush::hinge
