// The membrane bars' tangent for the central-difference driver's implicit membrane
// (CentralDifferenceOptions::implicit_membrane, polygon_central_difference.hpp).
//
// Bar k's force N = k_m (ℓ − ℓ0) along e (THEORY §4.3) has the tangent
//   ∂(N g)/∂p = k_m g gᵀ + (N/ℓ)(I − e eᵀ) blocks,  g = ∂ℓ/∂p = (−e, e) on nodes k, k + 1;
// the material part K_m = Σ_bars k_m g gᵀ is the bar damper's c_b g gᵀ with k_m for c_b, so
// the driver's matrix μ + h C + h² K_m is the damper matrix with c_b + h k_m
// (PolygonChain::bar_matrix_coefficient, polygon_implicit_dampers.cpp) and fits its band. The
// geometric part, N/ℓ ≤ k_m |ε| (ε ≲ 1e-3 in a crushed Test 30 ring), is left out of the
// matrix; the force itself stays exact in φ.
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "hinge/polygon_chain.hpp"

namespace ringcrush::hinge {

// Bar by bar: ℓ̇ = g·v = e·(v_{k+1} − v_k), and k_m ℓ̇ g into the two ends. The half model
// takes bars 0…N/2 − 1, which join independent nodes only, once each — the fold of a bar and
// its mirror image that assemble_half_band makes for the bar dampers —, and clears the axis
// nodes' x rows (held on the symmetry plane); the full ring all N bars.
void PolygonChain::membrane_stiffness_product(const double* y, const double* v, double* out) {
  const int bars = half_ ? n_ind_ - 1 : n_full_;
  membrane_e_.resize(2 * static_cast<std::size_t>(bars * n_rings_));
  for (int r = 0; r < n_rings_; ++r) {
    double* e = membrane_e_.data() + 2 * static_cast<std::ptrdiff_t>(r * bars);
    for (int k = 0; k < bars; ++k) {
      const std::size_t a = node_offset(r, k), b = node_offset(r, (k + 1) % n_ind_);
      const double bx = y[b] - y[a], by = y[b + 1] - y[a + 1];
      const double inv = 1.0 / std::sqrt(bx * bx + by * by);
      e[2 * k] = bx * inv;
      e[2 * k + 1] = by * inv;
    }
  }
  membrane_stiffness_product_again(v, out);
}

void PolygonChain::membrane_stiffness_product_again(const double* v, double* out) const {
  const int bars = half_ ? n_ind_ - 1 : n_full_;
  for (int r = 0; r < n_rings_; ++r) {
    const double* e = membrane_e_.data() + 2 * static_cast<std::ptrdiff_t>(r * bars);
    for (int j = 0; j < n_ind_; ++j) {
      const std::size_t o = node_offset(r, j) + 2;
      out[o] = out[o + 1] = 0.0;
    }
    for (int k = 0; k < bars; ++k) {
      const std::size_t a = node_offset(r, k) + 2, b = node_offset(r, (k + 1) % n_ind_) + 2;
      const double ex = e[2 * k], ey = e[2 * k + 1];
      const double s = k_m_ * (ex * (v[b] - v[a]) + ey * (v[b + 1] - v[a + 1]));
      out[a] -= s * ex;
      out[a + 1] -= s * ey;
      out[b] += s * ex;
      out[b + 1] += s * ey;
    }
    if (half_) {
      out[node_offset(r, 0) + 2] = 0.0;
      out[node_offset(r, n_ind_ - 1) + 2] = 0.0;
    }
  }
}

void PolygonChain::ring_damper_membrane_step(const double* y, double h, double* v, double* d) {
  if (!(h > 0.0 && std::isfinite(h)))
    throw std::invalid_argument("PolygonChain::ring_damper_membrane_step: h must be positive and finite, got " +
                                std::to_string(h));
  if (!implicit_membrane_)
    throw std::logic_error("PolygonChain::ring_damper_membrane_step: set_implicit_membrane(true) first");
  membrane_h_ = h;
  try {
    ring_damper_step(y, h, v, d);
  } catch (...) {
    membrane_h_ = 0.0;
    throw;
  }
  membrane_h_ = 0.0;
}

}  // namespace ringcrush::hinge
