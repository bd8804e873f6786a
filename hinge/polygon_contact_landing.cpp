// Contact landing for the central-difference driver (PolygonChain::set_contact_landing,
// polygon_chain.hpp; CentralDifferenceOptions::contact_landing_depth).
//
// Why: a penalty contact that closes during an explicit step is first seen at a penetration δ
// anywhere in [0, ṗ Δt]; the leapfrog then applies k δ over a whole step, and the energy
// balance takes an error of the order of ½ k δ² per closing. At the impactor's 27.7 m/s on
// Test 30 (Δt ≈ 0.35 µs: δ up to 10 µm, ½ k δ² ≈ 0.06 J against KE0 = 98.6 J) that one event
// is the run's whole balance error (4.7–7.3e-4 of KE0, incurred in the first 20 µs and flat
// after; README). Landing the step on the contact — the step shortened so that the closing
// pair is first seen at a penetration of at most `depth` — removes it without shortening the
// other steps.
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
}

}  // namespace ringcrush::hinge
