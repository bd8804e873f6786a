#include "fe/chain/geometry_update.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace ringcrush::fe {

namespace {
// J_ij = ∂x_j/∂ξ_i at one point and its determinant.
struct Jacobian {
  double j00, j01, j10, j11, det;
};
inline Jacobian jacobian(const ShapeGrad& dn, const ElementCoords& x) {
  Jacobian j;
  j.j00 = dn.col(0).dot(x.col(0));
  j.j01 = dn.col(0).dot(x.col(1));
  j.j10 = dn.col(1).dot(x.col(0));
  j.j11 = dn.col(1).dot(x.col(1));
  j.det = j.j00 * j.j11 - j.j01 * j.j10;
  return j;
}
// ∂N/∂x = ∂N/∂ξ J⁻ᵀ, J⁻ᵀ = (1/det) [[j11, −j10], [−j01, j00]], all 8 nodes at once.
inline void gradients(const ShapeGrad& dn, const Jacobian& j, double inv, ShapeGrad& dndx) {
  dndx.col(0) = (dn.col(0) * j.j11 - dn.col(1) * j.j01) * inv;
  dndx.col(1) = (dn.col(1) * j.j00 - dn.col(0) * j.j10) * inv;
}
}  // namespace

Cps8GeometryUpdater::Cps8GeometryUpdater(Integration rule) : t_(cps8_rule_tables(rule)) {}

// In three passes over the points — Jacobians, the reciprocals of their determinants,
// gradients — rather than point by point: the 13 divisions are then independent and overlap
// in the CPU instead of each holding up its point's gradients (perf: that wait was a fifth
// of the update). Per point the operations are those of the point-by-point form.
void Cps8GeometryUpdater::update(const ElementCoords& x, double thickness, Cps8Geometry& geo) const {
  if (geo.rule != t_.rule || geo.points != t_.points)
    throw std::logic_error("Cps8GeometryUpdater: geometry built for another integration rule");
  const int points = t_.points, reduced = t_.rule == Integration::Selective ? 4 : 0, n = points + reduced;
  const auto dn = [&](int i) -> const ShapeGrad& { return i < points ? t_.dn[i] : t_.dn_reduced[i - points]; };
  std::array<Jacobian, 13> j;
  std::array<double, 13> inv;
  for (int i = 0; i < n; ++i) j[i] = jacobian(dn(i), x);
  for (int i = 0; i < points; ++i)
    if (!(j[i].det > 0))
      throw std::invalid_argument(fmt::format("CPS8 element inverted or degenerate (det J = {:g})", j[i].det));
  for (int i = 0; i < n; ++i) inv[i] = 1.0 / j[i].det;
  for (int i = 0; i < points; ++i) {
    gradients(t_.dn[i], j[i], inv[i], geo.dndx[i]);
    geo.weight[i] = t_.weight[i] * j[i].det * thickness;
  }
  for (int r = 0; r < reduced; ++r) gradients(t_.dn_reduced[r], j[points + r], inv[points + r], geo.dndx_reduced[r]);
}

}  // namespace ringcrush::fe
