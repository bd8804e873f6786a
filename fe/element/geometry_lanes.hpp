// The per-increment CPS8 geometry of four or eight elements on vector lanes, one lane per element:
// J = ∂x/∂ξ, det J, ∂N/∂x = ∂N/∂ξ J⁻ᵀ and the point weights, each lane bitwise
// Cps8GeometryUpdater::update() (geometry_update.cpp) on its element. Internal to the lane
// kernels: Cps8GeometryUpdater::update_lanes() stores the result into each element's
// Cps8Geometry; cps8_force_lanes_on_coords() (cps8_force_lanes.hpp) keeps it in the
// kernel's own arrays and never stores it — the element's 2.6 kB geometry is then neither
// written nor read back (README, session 9). Always inlined, for the same reason as
// element_lanes.hpp.
//
// Bitwise update(): ∂N/∂ξ is the same for every element (the rule's tables,
// cps8_rule_tables.hpp), so each lane does update()'s operations on its own coordinates —
// including the order of Eigen's dot products J_ij = ∂N/∂ξ_i · x_j, whose summation tree
// depends on Eigen's vector width (reproduced for SSE2 and AVX; other widths are not
// reproduced, kDotTreeKnown is then false and the callers go element by element).
#pragma once

#include <array>
#include <cstddef>

#include <Eigen/Core>

#include "fe/element/cps8_element.hpp"
#include "fe/element/cps8_rule_tables.hpp"
#include "fe/element/element_lanes.hpp"

namespace ringcrush::fe::lanes {

// The packet width of Eigen's dot product of two 8-vectors, with the flags of the library
// (the same for geometry_update.cpp, whose update() the lanes reproduce).
constexpr int kDotPacket = Eigen::internal::packet_traits<double>::size;
constexpr bool kDotTreeKnown = kDotPacket == 2 || kDotPacket == 4;

// Σ_k a_k x_k for a = one column of ∂N/∂ξ (the same for all lanes), x = one coordinate of the
// 8 nodes, in the order of Eigen's fully unrolled vectorised redux: products in packets of P,
// the packets summed as a halving tree, then the P lanes of the result summed (predux).
//   P = 2: ((p0 + p2) + (p4 + p6)) + ((p1 + p3) + (p5 + p7))
//   P = 4: ((p0 + p4) + (p2 + p6)) + ((p1 + p5) + (p3 + p7))
// (Results through a reference: a vector returned by value from a function not itself compiled
// for AVX changes the ABI, -Wpsabi.)
template <class V>
[[gnu::always_inline]] inline void dot8(const double* a, const V* x, V& out) {
  V p[8];
  for (int k = 0; k < 8; ++k) p[k] = a[k] * x[k];
  if constexpr (kDotPacket == 2)
    out = ((p[0] + p[2]) + (p[4] + p[6])) + ((p[1] + p[3]) + (p[5] + p[7]));
  else
    out = ((p[0] + p[4]) + (p[2] + p[6])) + ((p[1] + p[5]) + (p[3] + p[7]));
}

// Node coordinates as lanes: xs[j][a] = x_j of node a of each element (ElementCoords is
// column-major 8 × 2), by 4 × 4 transposes.
template <bool kShuffle, class V, std::size_t W>
[[gnu::always_inline]] inline void gather_coords(const std::array<const ElementCoords*, W>& x, V (&xs)[2][8]) {
  static_assert(kWidthOf<V> == static_cast<int>(W));
  const double* c[W];
  for (std::size_t l = 0; l < W; ++l) c[l] = x[l]->data();
  for (int j = 0; j < 2; ++j)
    for (int k = 0; k < 8; k += 4) gather_transposed<kShuffle>(c, 8 * j + k, &xs[j][k]);
}

template <class V>
struct PointJacobian {
  V j00, j01, j10, j11, det;
};

// J and det J at the t.points stress points, then the t.reduced Barlow points (jac[13]).
// Returns false if det J ≤ 0 (or NaN) at a stress point of some lane: update() throws there.
template <class V>
[[gnu::always_inline]] inline bool jacobians_lanes(const Cps8RuleTables& t, const V (&xs)[2][8],
                                                   PointJacobian<V>* jac) {
  const int n = t.points + t.reduced;
  for (int i = 0; i < n; ++i) {
    const ShapeGrad& d = i < t.points ? t.dn[i] : t.dn_reduced[i - t.points];
    PointJacobian<V>& j = jac[i];
    dot8(d.col(0).data(), xs[0], j.j00);
    dot8(d.col(0).data(), xs[1], j.j01);
    dot8(d.col(1).data(), xs[0], j.j10);
    dot8(d.col(1).data(), xs[1], j.j11);
    j.det = j.j00 * j.j11 - j.j01 * j.j10;
  }
  for (int i = 0; i < t.points; ++i) {
    if (!all_lanes(jac[i].det > 0.0)) return false;
  }
  return true;
}

// ∂N/∂x at point i (stress points first, then Barlow points) into g[a][c] = ∂N_a/∂x_c:
// (∂N/∂ξ₁ j11 − ∂N/∂ξ₂ j01) / det, (∂N/∂ξ₂ j00 − ∂N/∂ξ₁ j10) / det, as update()'s
// gradients(), 1/det formed once per point as there.
template <class V>
[[gnu::always_inline]] inline void gradients_lanes(const Cps8RuleTables& t, int i, const PointJacobian<V>& j,
                                                   V (&g)[8][2]) {
  const ShapeGrad& d = i < t.points ? t.dn[i] : t.dn_reduced[i - t.points];
  const V inv = 1.0 / j.det;
  for (int k = 0; k < 8; ++k) {
    g[k][0] = (d(k, 0) * j.j11 - d(k, 1) * j.j01) * inv;
    g[k][1] = (d(k, 1) * j.j00 - d(k, 0) * j.j10) * inv;
  }
}

// The weight of stress point i: Gauss weight · det J · thickness, in update()'s order.
template <class V>
[[gnu::always_inline]] inline void weight_lanes(const Cps8RuleTables& t, int i, const PointJacobian<V>& j,
                                                double thickness, V& w) {
  w = t.weight[i] * j.det * thickness;
}

}  // namespace ringcrush::fe::lanes
