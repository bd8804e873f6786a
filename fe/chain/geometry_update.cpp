#include "fe/chain/geometry_update.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace ringcrush::fe {

namespace {
// ∂N/∂x = ∂N/∂ξ J⁻ᵀ with J_ij = ∂x_j/∂ξ_i; returns det J.
inline double gradients(const ShapeGrad& dn, const ElementCoords& x, ShapeGrad& dndx) {
  const double j00 = dn.col(0).dot(x.col(0)), j01 = dn.col(0).dot(x.col(1));
  const double j10 = dn.col(1).dot(x.col(0)), j11 = dn.col(1).dot(x.col(1));
  const double det = j00 * j11 - j01 * j10;
  const double inv = 1.0 / det;
  // ∂N/∂x = ∂N/∂ξ J⁻ᵀ, J⁻ᵀ = (1/det) [[j11, −j10], [−j01, j00]].
  for (int k = 0; k < 8; ++k) {
    const double g = dn(k, 0), h = dn(k, 1);
    dndx(k, 0) = (g * j11 - h * j01) * inv;
    dndx(k, 1) = (h * j00 - g * j10) * inv;
  }
  return det;
}
}  // namespace

Cps8GeometryUpdater::Cps8GeometryUpdater(Integration rule) : rule_(rule) {
  const auto pts = gauss_rule(rule == Integration::Reduced ? 2 : 3);
  points_ = static_cast<int>(pts.size());
  ShapeVec n;
  for (int i = 0; i < points_; ++i) {
    cps8_shape(pts[i].g, pts[i].h, n, dn_[i]);
    weight_[i] = pts[i].weight;
  }
  const auto red = gauss_rule(2);
  for (int r = 0; r < 4; ++r) cps8_shape(red[r].g, red[r].h, n, dn_reduced_[r]);
}

void Cps8GeometryUpdater::update(const ElementCoords& x, double thickness, Cps8Geometry& geo) const {
  if (geo.rule != rule_ || geo.points != points_)
    throw std::logic_error("Cps8GeometryUpdater: geometry built for another integration rule");
  for (int i = 0; i < points_; ++i) {
    const double det = gradients(dn_[i], x, geo.dndx[i]);
    if (!(det > 0))
      throw std::invalid_argument(fmt::format("CPS8 element inverted or degenerate (det J = {:g})", det));
    geo.weight[i] = weight_[i] * det * thickness;
  }
  if (rule_ == Integration::Selective)
    for (int r = 0; r < 4; ++r) gradients(dn_reduced_[r], x, geo.dndx_reduced[r]);
}

}  // namespace ringcrush::fe
