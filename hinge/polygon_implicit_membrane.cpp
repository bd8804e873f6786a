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

#include "hinge/polygon_bar_direction.hpp"
#include "hinge/polygon_chain.hpp"
#include "hinge/ring_lanes.hpp"

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
      const std::size_t a = node_offset(r, k), b = node_offset(r, k + 1 < n_ind_ ? k + 1 : 0);
      // The band's e (polygon_bar_direction.hpp), so that K_m here is the band's to the bit.
      const BarDirection g = bar_direction(y[b] - y[a], y[b + 1] - y[a + 1]);
      e[2 * k] = g.ex;
      e[2 * k + 1] = g.ey;
    }
  }
  membrane_stiffness_product_again(v, out);
}

// Node by node: node j's rows take the force of bar j − 1 (at its end) and then bar j's (at
// its start), (0 + s_{j−1} e_{j−1}) − s_j e_j with s = k_m ℓ̇ — the sums, in their order, of a
// scatter bar by bar into cleared rows, without the clearing and the read-modify-write. The
// full ring's node 0 takes bar N − 1 last, as that scatter did.

void PolygonChain::membrane_stiffness_product_again(const double* v, double* out) const {
  const int bars = half_ ? n_ind_ - 1 : n_full_;
  for (int r = 0; r < n_rings_; ++r) {
    const double* e = membrane_e_.data() + 2 * static_cast<std::ptrdiff_t>(r * bars);
    double fx = 0.0, fy = 0.0;  // s e of the bar before
    for (int k = 0; k < bars; ++k) {
      // The next node without a modulo (an integer division per bar was this loop's latency).
      const std::size_t a = node_offset(r, k) + 2, b = k + 1 < n_ind_ ? a + 6 : node_offset(r, 0) + 2;
      const double ex = e[2 * k], ey = e[2 * k + 1];
      const double s = k_m_ * (ex * (v[b] - v[a]) + ey * (v[b + 1] - v[a + 1]));
      const double gx = s * ex, gy = s * ey;
      out[a] = (0.0 + fx) - gx;  // node 0: no bar before (the full ring's comes below)
      out[a + 1] = (0.0 + fy) - gy;
      fx = gx;
      fy = gy;
    }
    const std::size_t z = node_offset(r, bars < n_ind_ ? bars : 0) + 2;  // the last bar's end node
    if (half_) {
      out[z] = 0.0 + fx;
      out[z + 1] = 0.0 + fy;
    } else {
      out[z] += fx;
      out[z + 1] += fy;
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

// The half model: one assembly gives the band and K_m's bar directions (the membrane's own
// pass, a square root and a division per bar, is gone), the two products run on them.
void PolygonChain::ring_damper_membrane_kick(const double* y, double h, const double* w, double* v, double* d,
                                             double* kw, double* kv) {
  if (!(h > 0.0 && std::isfinite(h)))
    throw std::invalid_argument("PolygonChain::ring_damper_membrane_kick: h must be positive and finite, got " +
                                std::to_string(h));
  if (!implicit_membrane_)
    throw std::logic_error("PolygonChain::ring_damper_membrane_kick: set_implicit_membrane(true) first");
  if (kv_inverse_mu_.size() != mu_.size()) {
    kv_inverse_mu_.resize(mu_.size());
    for (std::size_t i = 0; i < mu_.size(); ++i) kv_inverse_mu_[i] = 1.0 / mu_[i];
  }
  if (half_) {
    prepare_half_band();
    membrane_h_ = h;  // c_b + h k_m in the bars' band entries
    assemble_half_bands(y);
    membrane_h_ = 0.0;
    membrane_stiffness_product_again(w, kw);
  } else {
    membrane_stiffness_product(y, w, kw);
  }
  // μ v* + h² K_m w as μ (v* + h² K_m w / μ): the right-hand side of the solve, and the v* its
  // d = μ (v* − v)/h is taken from. The nodes' rows follow each other from row 0
  // (node_offset), a node's two velocity rows one Pair.
  const double h2 = h * h;
  const double* inverse_mu = kv_inverse_mu_.data();
  const std::size_t nodes_end = node_offset(n_rings_ - 1, n_ind_ - 1) + 6;
  for (std::size_t o = 2; o < nodes_end; o += 6)
    lanes::store(v + o, lanes::load(v + o) + h2 * lanes::load(kw + o) * lanes::load(inverse_mu + o));
  if (half_)
    half_band_solve(h, v, d);
  else
    ring_damper_membrane_step(y, h, v, d);
  membrane_stiffness_product_again(v, kv);  // the positions are y's still
}

}  // namespace ringcrush::hinge
