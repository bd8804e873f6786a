// Cps8GeometryUpdater::update() on four elements at once (geometry_update.hpp): the Jacobian
// J = ∂x/∂ξ, det J and ∂N/∂x = ∂N/∂ξ J⁻ᵀ at every point, one vector lane per element, written
// into each element's Cps8Geometry. The lane arithmetic (bitwise update(), Eigen's dot-product
// tree included) is in fe/element/geometry_lanes.hpp, shared with the force kernel that forms
// the geometry without storing it (cps8_force_lanes_on_coords()).
#include "fe/chain/geometry_update.hpp"
#include "fe/element/geometry_lanes.hpp"

namespace ringcrush::fe {

namespace {

using namespace lanes;

// Returns false (nothing written) if a stress point of a lane has det J ≤ 0 or NaN.
template <bool kShuffle>
[[gnu::always_inline]] inline bool update_lanes_body(const Cps8RuleTables& t,
                                                     const std::array<const ElementCoords*, 4>& x,
                                                     double thickness, const std::array<Cps8Geometry*, 4>& geo) {
  Lanes xs[2][8];
  gather_coords<kShuffle>(x, xs);
  PointJacobian<Lanes> jac[13];
  if (!jacobians_lanes(t, xs, jac)) return false;
  const int n = t.points + t.reduced;
  double* out[4];
  for (int i = 0; i < n; ++i) {
    Lanes g[8][2];
    gradients_lanes(t, i, jac[i], g);
    for (int l = 0; l < 4; ++l) out[l] = (i < t.points ? geo[l]->dndx[i] : geo[l]->dndx_reduced[i - t.points]).data();
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 8; k += 4) {
        const Lanes col[4] = {g[k][c], g[k + 1][c], g[k + 2][c], g[k + 3][c]};
        scatter_transposed<kShuffle>(col, 8 * c + k, out);
      }
  }
  for (int i = 0; i < t.points; ++i) {
    Lanes w;
    weight_lanes(t, i, jac[i], thickness, w);
    for (int l = 0; l < 4; ++l) geo[l]->weight[i] = w[l];
  }
  return true;
}

#if defined(__x86_64__) || defined(__i386__)
[[gnu::target("avx2")]] bool update_lanes_avx2(const Cps8RuleTables& t, const std::array<const ElementCoords*, 4>& x,
                                               double thickness, const std::array<Cps8Geometry*, 4>& geo) {
  return update_lanes_body<true>(t, x, thickness, geo);
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
    for (const Cps8Geometry* g : geo) same_rule = same_rule && g->rule == t_.rule && g->points == t_.points;
    if (same_rule && update_lanes_avx2(t_, x, thickness, geo)) return;
  }
#endif
  for (int l = 0; l < 4; ++l) update(*x[l], thickness, *geo[l]);
}

}  // namespace ringcrush::fe
