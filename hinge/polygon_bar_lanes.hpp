// The central difference's bar pass over the ring lanes (PolygonChain::ring_lanes_bars,
// polygon_ring_lanes.cpp): for every bar k of every ring, value k of ring r at k·lanes + r,
//   w = p_{k+1} − p_k,  ℓ = √(w·w),  e = w (1/ℓ),  n/ℓ = (−e_y, e_x) (1/ℓ),  N = k_m (ℓ − ℓ0),
// the operations of the per-ring pass (PolygonChain::ring_bars) in its order. A bar's value of
// every ring only reads the nodes' values at the same place and the next node's (one lane row
// on), so a range of bars is one flat run of independent values: 8, 4 or 2 of them to a vector
// (hinge/ring_lanes_wide.hpp), the run's end in smaller vectors. One square root and one
// division per vector: on the test machine's divider a quarter (AVX-512) of the pairs' count.
#pragma once

#include <cstddef>

namespace ringcrush::hinge {

struct BarLanes {
  const double *px, *py;           // node k's values at k·lanes (node N after the last)
  double *ex, *ey, *gx, *gy, *n;   // bar k's at k·lanes
  std::size_t lanes;               // the lane stride, even
  double k_m, l0;
};

// Bars first … last − 1 of every lane, `width` values to a vector: 2 (SSE2), 4 (AVX2) or 8
// (AVX-512); a width the CPU lacks (lanes::wide_lanes_available) is not to be asked for.
void bar_lanes(const BarLanes& b, int first, int last, int width);

}  // namespace ringcrush::hinge
