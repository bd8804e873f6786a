// The node–segment contact's narrow phase (PolygonChain::node_segment_contact,
// polygon_segment_contact.cpp): of a slave node's listed segments of a master ring, the closest
// one within the reach — the first of equals in the list's (ascending) order —, its distance
// and the closest point's parameter s along it.
//
// Each listed segment's box, grown by the reach, is tested first (the node outside it is too
// far); the ones that hold the node are projected. Once a segment is found at d, only a closer
// one can take its place (d' < d strictly), and a segment whose box grown by d misses the node
// is at least d away: so the box shrinks to d + `shrink_margin` (never beyond the reach). The
// margin — the caller's 10⁻⁶ t, ≈ 10⁻⁹ m, against the rounding of the box's corners and of the
// projection, ≈ 10⁻¹⁶ m on coordinates of 0.1 m — keeps every segment whose projection could
// come out at d or closer: the segments skipped could not have been chosen, so the choice and
// its bits are those of the search without the shrink (shrink_margin = ∞, the tests'
// reference), with fewer projections (each a division and a square root).
#pragma once

#include <algorithm>
#include <cstddef>

#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

// The master ring's node k at master[6 k] (x, y); segment a from node a to a + 1, the full
// ring's last (a = wrap) to node 0 (FullRing; the half model's segments never wrap). `best`
// on entry the bound (only closer segments count), on exit the closest one's distance, `best_a`
// its index (unchanged, −1 from the caller, when none is closer), `best_s` its s.
template <bool FullRing>
[[gnu::always_inline]] inline void closest_segment(lanes::Pair slave, const double* master, int wrap, const int* first,
                                                   const int* last, double reach, double shrink_margin, double& best,
                                                   int& best_a, double& best_s) {
  const double sx = slave[0], sy = slave[1];
  lanes::Pair grow = {reach, reach};
  for (const int* it = first; it != last; ++it) {
    const int a = *it;
    const double* pa = master + 6 * static_cast<std::size_t>(a);
    const double* pb = FullRing && a == wrap ? master : pa + 6;
    const lanes::Pair end_a = lanes::load(pa), end_b = lanes::load(pb);
    if (lanes::any_less(slave, lanes::min(end_a, end_b) - grow, lanes::max(end_a, end_b) + grow, slave)) continue;
    const double ax = end_a[0], ay = end_a[1], bx = end_b[0], by = end_b[1];
    const double ex = bx - ax, ey = by - ay;
    const double ll = ex * ex + ey * ey;
    double s = ((sx - ax) * ex + (sy - ay) * ey) / ll;
    s = std::clamp(s, 0.0, 1.0);
    const double qx = ax + s * ex, qy = ay + s * ey;
    const double d = lanes::sqrt_nonnegative((sx - qx) * (sx - qx) + (sy - qy) * (sy - qy));
    if (d < best) {
      best = d;
      best_a = a;
      best_s = s;
      const double g = std::min(reach, d + shrink_margin);
      grow = lanes::Pair{g, g};
    }
  }
}

}  // namespace ringcrush::hinge
