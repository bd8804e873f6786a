// The half model's damper + membrane band (PolygonChain::half_band_step and
// ring_damper_membrane_kick, polygon_implicit_dampers.cpp) assembled from y: ring by ring
// (assemble_ring_band, the reference) or with the rings side by side, two to an SSE2 vector or
// four to an AVX one (assemble_ring_bands). The rings have the same N and the same element
// order, so every lane does the per-ring assembly's operations on its ring in the same order
// (IEEE add, multiply, divide and square root, no contraction on the default x86-64 target nor
// on "avx2"): the same bits. What changes is the count of instructions: each element's
// gradients, divisions and square roots are issued for two or four rings at once, and the band
// rows, whose ring index is innermost in the interleaved band, go out as one store for them.
//
// The band: C(i, i − q) of ring r at band[(6 i + q) S + r], S the ring count rounded up to even
// (a spare lane, left 0 here, when it is odd), i over the ring's 2 n_ind velocity rows; the
// entries written are those of the bandwidth-5 band (the x rows' q = 5 slot is never written).
// y holds ring r's node j at y[r ring_stride + 6 j] (x, y first). bar_e, unless null, gets
// every bar's e = w/ℓ (ring r's bar k at bar_e[2 (r (n_ind − 1) + k)]) for the membrane's K_m.
#pragma once

#include <cstddef>
#include <vector>

namespace ringcrush::hinge {

// The lane stride S of the interleaved band for `rings` rings.
inline int band_lane_count(int rings) { return rings + rings % 2; }

// Scratch (doubles) the two assemblies need for rings of n_ind independent nodes.
std::size_t ring_band_scratch_size(int n_ind);

// One ring (its band entries at band[(6 i + q) S], band at the ring's lane; y at its node 0).
// `scratch` of ring_band_scratch_size, zero on the first call (slots no element writes must
// stay 0); reused in any order of coefficients (with one at 0 the elements are cleared first).
void assemble_ring_band(const double* y, int n_ind, double c_bar, double c_hinge, double* band, std::ptrdiff_t S,
                        double* scratch, double* bar_e);

// All rings, `width` to a vector: two (SSE2), four (AVX2, then a pair for the rest) where
// band_lanes_avx2 (polygon_band_solve.hpp) says the CPU has it, or eight (AVX-512, the last
// vector's spare lanes masked off) where lanes::wide_lanes_available() is 8; the widest the CPU
// has up to `width`, two at least. Bitwise the rings' assemble_ring_band (a spare lane untouched).
void assemble_ring_bands(const double* y, std::size_t ring_stride, int rings, int n_ind, double c_bar,
                         double c_hinge, double* band, double* scratch, double* bar_e, int width);

}  // namespace ringcrush::hinge
