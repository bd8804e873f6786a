// Cps8GeometryUpdater::update() on four elements at once (geometry_update.hpp): the Jacobian
// J = ∂x/∂ξ, det J and ∂N/∂x = ∂N/∂ξ J⁻ᵀ at every point, one vector lane per element, written
// into each element's Cps8Geometry. Bitwise update(): the natural derivatives ∂N/∂ξ are the
// same for every element (the rule's tables), so each lane does update()'s operations on its
// own coordinates — including the order of Eigen's dot products J_ij = ∂N/∂ξ_i · x_j, whose
// summation tree depends on Eigen's vector width (reproduced below for SSE2 and AVX; other
// widths take update() one element at a time).
#include <Eigen/Core>

#include "fe/chain/geometry_update.hpp"
#include "fe/element/element_lanes.hpp"

namespace ringcrush::fe {

namespace {

using namespace lanes;

// The packet width of Eigen's dot product of two 8-vectors in this translation unit (the
// same flags as geometry_update.cpp).
constexpr int kDotPacket = Eigen::internal::packet_traits<double>::size;
constexpr bool kDotTreeKnown = kDotPacket == 2 || kDotPacket == 4;

// Σ_k a_k x_k for a = one column of ∂N/∂ξ (the same for all lanes), x = one coordinate of the
// 8 nodes, in the order of Eigen's fully unrolled vectorised redux: products in packets of P,
// the packets summed as a halving tree, then the P lanes of the result summed (predux).
//   P = 2: ((p0 + p2) + (p4 + p6)) + ((p1 + p3) + (p5 + p7))
//   P = 4: ((p0 + p4) + (p2 + p6)) + ((p1 + p5) + (p3 + p7))
[[gnu::always_inline]] inline void dot8(const double* a, const Lanes* x, Lanes& out) {
  Lanes p[8];
  for (int k = 0; k < 8; ++k) p[k] = a[k] * x[k];
  if constexpr (kDotPacket == 2)
    out = ((p[0] + p[2]) + (p[4] + p[6])) + ((p[1] + p[3]) + (p[5] + p[7]));
  else
    out = ((p[0] + p[4]) + (p[2] + p[6])) + ((p[1] + p[5]) + (p[3] + p[7]));
}

struct PointJacobian {
  Lanes j00, j01, j10, j11, det;
};

// Returns false (nothing written) if a stress point of a lane has det J ≤ 0 or NaN.
template <bool kShuffle>
[[gnu::always_inline]] inline bool update_lanes_body(const std::array<ShapeGrad, 9>& dn_stress,
                                                     const std::array<double, 9>& gauss_weight,
                                                     const std::array<ShapeGrad, 4>& dn_reduced, int points,
                                                     int reduced, const std::array<const ElementCoords*, 4>& x,
                                                     double thickness, const std::array<Cps8Geometry*, 4>& geo) {
  const int n = points + reduced;
  // Node coordinates as lanes: xs[j][a] = x_j of node a (ElementCoords is column-major 8 × 2).
  Lanes xs[2][8];
  {
    const double* c[4] = {x[0]->data(), x[1]->data(), x[2]->data(), x[3]->data()};
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 8; k += 4) gather_transposed<kShuffle>(c, 8 * j + k, &xs[j][k]);
  }
  const auto dn = [&](int i) -> const ShapeGrad& { return i < points ? dn_stress[i] : dn_reduced[i - points]; };
  PointJacobian jac[13];
  for (int i = 0; i < n; ++i) {
    const ShapeGrad& d = dn(i);
    PointJacobian& j = jac[i];
    dot8(d.col(0).data(), xs[0], j.j00);
    dot8(d.col(0).data(), xs[1], j.j01);
    dot8(d.col(1).data(), xs[0], j.j10);
    dot8(d.col(1).data(), xs[1], j.j11);
    j.det = j.j00 * j.j11 - j.j01 * j.j10;
  }
  for (int i = 0; i < points; ++i) {
    const LaneMask positive = jac[i].det > 0.0;
    if (!(positive[0] && positive[1] && positive[2] && positive[3])) return false;
  }
  double* out[4];
  for (int i = 0; i < n; ++i) {
    const ShapeGrad& d = dn(i);
    const PointJacobian& j = jac[i];
    const Lanes inv = 1.0 / j.det;
    // ∂N/∂x = (∂N/∂ξ₁ j11 − ∂N/∂ξ₂ j01) / det, (∂N/∂ξ₂ j00 − ∂N/∂ξ₁ j10) / det, as update().
    Lanes g[2][8];
    for (int k = 0; k < 8; ++k) {
      g[0][k] = (d(k, 0) * j.j11 - d(k, 1) * j.j01) * inv;
      g[1][k] = (d(k, 1) * j.j00 - d(k, 0) * j.j10) * inv;
    }
    for (int l = 0; l < 4; ++l) out[l] = (i < points ? geo[l]->dndx[i] : geo[l]->dndx_reduced[i - points]).data();
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 8; k += 4) scatter_transposed<kShuffle>(&g[c][k], 8 * c + k, out);
  }
  for (int i = 0; i < points; ++i) {
    const Lanes w = gauss_weight[i] * jac[i].det * thickness;
    for (int l = 0; l < 4; ++l) geo[l]->weight[i] = w[l];
  }
  return true;
}

#if defined(__x86_64__) || defined(__i386__)
[[gnu::target("avx2")]] bool update_lanes_avx2(const std::array<ShapeGrad, 9>& dn_stress,
                                               const std::array<double, 9>& gauss_weight,
                                               const std::array<ShapeGrad, 4>& dn_reduced, int points, int reduced,
                                               const std::array<const ElementCoords*, 4>& x, double thickness,
                                               const std::array<Cps8Geometry*, 4>& geo) {
  return update_lanes_body<true>(dn_stress, gauss_weight, dn_reduced, points, reduced, x, thickness, geo);
}
#endif

}  // namespace

bool Cps8GeometryUpdater::lanes_vectorised() {
#if defined(__x86_64__) || defined(__i386__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
#ifdef __FMA__
  return false;  // as cps8_lanes_bitwise_build(): an FMA build keeps update() element by element
#else
  return kDotTreeKnown && avx2;
#endif
#else
  return false;
#endif
}

void Cps8GeometryUpdater::update_lanes(const std::array<const ElementCoords*, 4>& x, double thickness,
                                       const std::array<Cps8Geometry*, 4>& geo) const {
#if defined(__x86_64__) || defined(__i386__)
  if (lanes_vectorised()) {
    bool same_rule = true;
    for (const Cps8Geometry* g : geo) same_rule = same_rule && g->rule == rule_ && g->points == points_;
    const int reduced = rule_ == Integration::Selective ? 4 : 0;
    if (same_rule && update_lanes_avx2(dn_, weight_, dn_reduced_, points_, reduced, x, thickness, geo)) return;
  }
#endif
  for (int l = 0; l < 4; ++l) update(*x[l], thickness, *geo[l]);
}

}  // namespace ringcrush::fe
