// The half model's damper + membrane solve (μ + h C) v = μ v* (PolygonChain::half_band_step and
// ring_damper_membrane_kick, polygon_implicit_dampers.cpp) on the interleaved band that
// polygon_band_lanes.hpp assembles: L D Lᵀ without square roots, the forward substitution fused
// into the factorisation, then the backward one, the rings in lockstep. Ring by ring (one lane
// at a time: the reference), two rings to an SSE2 vector, or four to an AVX one (then a pair
// for the rest) where the CPU has AVX2: the rings' bands are independent blocks and every lane
// does its ring's operations in the same order (IEEE add, multiply and divide; no contraction:
// the AVX copy is compiled for "avx2", which does not imply FMA), so all three give the same
// bits.
#pragma once

#include <cstddef>
#include <vector>

#include "hinge/polygon_band_lanes.hpp"

namespace ringcrush::hinge {

// The solve's operands: the interleaved band C (ring r's C(i, i − q) at (6 i + q) S + r, S =
// band_lane_count), the factor L, the right-hand side b and 1/D interleaved alike, each at its
// first band row (band_factor_rows sets the pad rows before it), the masses μ and the
// state-length v and d (ring r's node j at 6 (r n_ind + j), its velocity rows at + 2, + 3).
struct BandSolve {
  const double* C;
  double *L, *b, *inv;
  const double* mu;
  int n_ind, rings;
  double h;
  double *v, *d;
};

// The pad rows ahead of the band in L, b and 1/D (the fixed-width rows then need no bounds).
constexpr int kBandPadRows = 5;

// Sizes L, 1/D and b for `rings` rings of n_ind independent nodes (2 n_ind band rows) and sets
// what no solve writes: L's leading pad rows identity and trailing ones 0, a spare lane
// identity throughout, 1/D 1 and b 0.
void band_factor_rows(int n_ind, int rings, std::vector<double>& L, std::vector<double>& inv, std::vector<double>& b);

// Whether the CPU runs the four-ring (AVX2) lanes of the solve and of assemble_ring_bands.
bool band_lanes_avx2();

// With v's node rows holding v*: v ← the solution (the axis nodes' x 0) and d = C v; `width`
// rings to a vector: 1 (ring by ring), 2 (SSE2) or 4 (AVX2, two where band_lanes_avx2 is
// false). Returns whether every pivot was positive. h > 0.
bool solve_ring_bands(const BandSolve& p, int width);

}  // namespace ringcrush::hinge
