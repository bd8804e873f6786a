// The stable step's per-node limit (PolygonChain::stable_step, polygon_stable_step.cpp) for
// many nodes at once: with K the node's Gershgorin stiffness row, C its damping row and μ its
// mass,
//   ω = √(K/μ),  ξ = C/(2√(K μ)),  Δt = (2/ω)(√(1 + ξ²) − ξ)   (∞ where K ≤ 0),
// three divisions and three square roots per node, each lane the scalar formula's operations
// in its order, 8, 4 or 2 nodes to a vector (hinge/ring_lanes_wide.hpp). The minimum over the
// nodes is exact and independent of the order (a NaN is passed over, as std::min(dt, NaN)
// keeps dt), so it is the scalar scan's to the bit.
#pragma once

namespace ringcrush::hinge {

// The central-difference limit of one node, the scalar reference.
double node_step_limit(double K, double C, double mass);

// min(dt, the limits of nodes 0 … count − 1), `width` nodes to a vector: 2 (SSE2), 4 (AVX2)
// or 8 (AVX-512); a width the CPU lacks (lanes::wide_lanes_available) is not to be asked for.
double min_node_step_limit(double dt, const double* K, const double* C, const double* mass, int count, int width);

}  // namespace ringcrush::hinge
