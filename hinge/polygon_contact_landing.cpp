// Contact landing for the central-difference driver (PolygonChain::set_contact_landing,
// polygon_chain.hpp; CentralDifferenceOptions::contact_landing_depth).
//
// Why: a penalty contact that closes during an explicit step is first seen at a penetration δ
// anywhere in [0, ṗ Δt], and while it closes fast the penetration grows by ṗ Δt per step; the
// leapfrog applies each step's force k p over the whole step, and the energy balance takes an
// error of the order of ½ k (ṗ Δt)² per closing step. At the impactor's 27.7 m/s on Test 30
// (Δt ≈ 0.35 µs: ṗ Δt ≈ 10 µm, ½ k (ṗ Δt)² ≈ 0.06 J against KE0 = 98.6 J) that one impact
// is nearly the run's whole balance error (4.7–7.3e-4 of KE0, incurred in the first 20 µs and
// flat after; README). Landing the step on the contact — the step shortened so that a closing
// pair is first seen at most `depth` deep, and goes at most `depth` deeper per step while it
// closes fast — cuts it to ≈ 2e-4 with 5–9 shortened steps per run: the other steps keep
// their length.
#include <stdexcept>
#include <string>

#include "hinge/polygon_chain.hpp"

namespace ringcrush::hinge {

void PolygonChain::set_contact_landing(double depth, double min_speed) {
  if (!(depth >= 0.0) || !(min_speed >= 0.0))
    throw std::invalid_argument("PolygonChain::set_contact_landing: depth and speed must be ≥ 0, got " +
                                std::to_string(depth) + ", " + std::to_string(min_speed));
  landing_depth_ = depth;
  landing_speed_ = min_speed;
  candidates_built_ = false;  // the lists' reach follows the landing (build_candidates)
}

}  // namespace ringcrush::hinge
