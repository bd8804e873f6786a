// Master surface for node-to-surface contact: a chain of quadratic element edges whose
// junctions are smoothed by Hermite cubics (thesis §3.6.3, Fig. 3.6.3-2, ABAQUS SMOOTH).
//
// With smoothing α ∈ [0, 0.5), each junction between segments (x2, x3, x4) and (x4, x5, x6)
// is replaced, between x_a (segment parameter g = 1 − 2α) and x_b (g = −1 + 2α on the next
// segment), by the Hermite cubic in f ∈ [−1, 1]
//   x(f) = H1 x_a + H2 x_b + H3 x_a' + H4 x_b',   x_a' = 2α dx/dg|a,  x_b' = 2α dx/dg|b,
// H1 = (2 − 3f + f³)/4, H2 = (2 + 3f − f³)/4, H3 = (1 − f − f² + f³)/4, H4 = (−1 − f + f² + f³)/4.
// The surface is then C¹: position and normal are continuous, so the gap and the contact
// force vary continuously as a node slides over a junction.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "fe/mesh/ring_mesh.hpp"

namespace ringcrush::fe {

// A polynomial piece x(f) = Σ_k c_k(f) x_k of the smoothed surface, f ∈ [lo, hi].
struct CurvePiece {
  int count = 3;                 // 3 nodes (quadratic part) or 5 (Hermite junction)
  std::array<int, 5> nodes{};
  double lo = -1, hi = 1;
  double alpha = 0;              // smoothing (Hermite pieces)
  // c_k(f), c_k'(f), c_k''(f).
  void coefficients(double f, double* c, double* dc, double* ddc) const;
};

// Parameter speed of a piece relative to the segment parameter g: 1 on a quadratic part,
// 2α on a Hermite junction (x'(±1) = 2α dx/dg); Σ (hi − lo) · speed is then a surface
// coordinate with a continuous dx/dS along a chain (the friction stick points use it).
inline double surface_speed(const CurvePiece& p) { return p.count == 5 ? 2 * p.alpha : 1.0; }

// Pieces of one counter-clockwise chain of consecutive segments (shared end nodes).
std::vector<CurvePiece> smoothed_chain(const std::vector<SurfaceSegment>& chain, double alpha);

// Maximal runs of consecutive inner-wall segments of `ring` whose middle node's reference
// angle φ satisfies `in_set` (the master surfaces of a self-contact pass on part of the wall).
// A full ring's wall is a loop, so the runs start at a segment whose predecessor is out of the
// set and one run may cross the segment list's start.
std::vector<std::vector<SurfaceSegment>> inner_wall_runs(const RingMesh& ring, const std::function<bool(double)>& in_set);

}  // namespace ringcrush::fe
