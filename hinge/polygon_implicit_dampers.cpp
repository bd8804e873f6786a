// Implicit Kelvin–Voigt ring dampers for the central-difference driver
// (PolygonChain::ring_damper_step, polygon_chain.hpp; polygon_central_difference.hpp).
//
// The bar damper of bar k and the hinge damper of hinge k (PolygonChainInput: c_b ℓ̇ and
// c_θ θ̇, THEORY §4.3) are linear in the node velocities: their forces are −C(x) v with
//   C = Σ_bars c_b g gᵀ (g = ∂ℓ/∂p = (−e, e) on nodes k, k+1)
//     + Σ_hinges c_θ g gᵀ (g = ∂θ/∂p = (−a, a + b, −b) on k−1, k, k+1, a = n_{k−1}/ℓ_{k−1},
//       b = n_k/ℓ_k, the gradients polygon_ring_forces.cpp uses),
// symmetric positive semi-definite and coupling only nodes two apart on one ring. The half
// model's rows are those of the independent nodes weighted as φ (axis nodes ½): with the
// mirror expansion E of the independent velocities this is ½ EᵀC_full E (the full ring's
// dissipation function halved), symmetric as well; the axis nodes' x rows are left out
// (their velocity stays 0 as in φ). Ties and contacts couple rings; they stay explicit.
//
// Each ring's matrix is stored as a profile (skyline) lower triangle: a row spans from its
// first coupled column to the diagonal, and Cholesky keeps the profile. Open rows (the half
// model) have bandwidth 5; the full ring's wrap-around gives the last node's rows a full
// profile, but the inner products along them stay short (they run from the later of the two
// rows' first columns), so one factorisation costs O(N) either way. The half model, which
// the Test 30 runs use, has its own path with the fixed band (half_band_step, below),
// factorised as L D Lᵀ without square roots.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "hinge/polygon_band_lanes.hpp"
#include "hinge/polygon_band_solve.hpp"
#include "hinge/polygon_chain.hpp"
#include "hinge/polygon_hinge_angle.hpp"
#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

namespace {

// d = C v for a symmetric C stored as a profile lower triangle; row(i) maps the ring's row i
// to its place in the state-length arrays v and d.
template <class Row>
void profile_multiply(const std::vector<int>& first, const std::vector<int>& start, const std::vector<double>& c,
                      int n, Row row, const double* v, double* d) {
  for (int i = 0; i < n; ++i) d[row(i)] = 0.0;
  for (int i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const double* ci = c.data() + start[u] - first[u];
    double di = ci[i] * v[row(i)];
    for (int j = first[u]; j < i; ++j) {
      di += ci[j] * v[row(j)];
      d[row(j)] += ci[j] * v[row(i)];
    }
    d[row(i)] += di;
  }
}

}  // namespace

// Calls sink(I, J, value) for every lower-triangle (I ≥ J) contribution of the current ring
// geometry (px_, py_) to C, rows 2j + (0: x, 1: y) of independent node j.
template <class Sink>
void PolygonChain::for_each_damper_entry(Sink&& sink) const {
  const double share = half_ ? 0.5 : 1.0;  // ½ EᵀC_full E in the half model
  auto axis_x = [&](int j, int d) { return half_ && d == 0 && (j == 0 || j == n_ind_ - 1); };
  auto scatter = [&](const int* nodes, const double (*g)[2], int count, double c) {
    for (int p = 0; p < count; ++p) {
      const auto [jp, sp] = independent(nodes[p]);
      for (int dp = 0; dp < 2; ++dp) {
        if (axis_x(jp, dp)) continue;
        const double gp = g[p][dp] * (dp == 0 ? sp : 1.0);
        const int I = 2 * jp + dp;
        for (int q = 0; q < count; ++q) {
          const auto [jq, sq] = independent(nodes[q]);
          for (int dq = 0; dq < 2; ++dq) {
            const int J = 2 * jq + dq;
            if (J > I || axis_x(jq, dq)) continue;
            sink(I, J, share * c * gp * g[q][dq] * (dq == 0 ? sq : 1.0));
          }
        }
      }
    }
  };
  const double c_bar = bar_matrix_coefficient();  // c_b, plus h k_m for the implicit membrane
  for (int k = 0; k < n_full_; ++k) {
    const int k1 = (k + 1) % n_full_;
    const double bx = px_[k1] - px_[k], by = py_[k1] - py_[k];
    const double l = std::sqrt(bx * bx + by * by);
    if (c_bar > 0 || implicit_membrane_) {  // the implicit membrane's bars: laid out even at c_b = 0
      const int nodes[2] = {k, k1};
      const double g[2][2] = {{-bx / l, -by / l}, {bx / l, by / l}};
      scatter(nodes, g, 2, c_bar);
    }
  }
  if (!(c_hinge_ > 0)) return;
  for (int k = 0; k < n_full_; ++k) {
    const int km = (k + n_full_ - 1) % n_full_, kp = (k + 1) % n_full_;
    const int nodes[3] = {km, k, kp};
    const auto grad = hinge_angle_gradient(px_[k] - px_[km], py_[k] - py_[km], px_[kp] - px_[k], py_[kp] - py_[k]);
    scatter(nodes, grad.g, 3, c_hinge_);
  }
}

void PolygonChain::assemble_ring_dampers(int ring, const double* y) {
  expand_ring(ring, y);
  const int n = 2 * n_ind_;
  if (kv_first_.empty()) {  // the profile depends on the topology only: found once
    kv_first_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) kv_first_[static_cast<std::size_t>(i)] = i;
    for_each_damper_entry([&](int I, int J, double) {
      auto& f = kv_first_[static_cast<std::size_t>(I)];
      f = std::min(f, J);
    });
    kv_start_.resize(static_cast<std::size_t>(n) + 1);
    kv_start_[0] = 0;
    for (int i = 0; i < n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      kv_start_[u + 1] = kv_start_[u] + (i - kv_first_[u] + 1);
    }
    kv_c_.resize(static_cast<std::size_t>(kv_start_.back()));
    kv_factor_.resize(kv_c_.size());
    kv_b_.resize(static_cast<std::size_t>(n));
  }
  std::fill(kv_c_.begin(), kv_c_.end(), 0.0);
  for_each_damper_entry([&](int I, int J, double value) {
    const auto u = static_cast<std::size_t>(I);
    kv_c_[static_cast<std::size_t>(kv_start_[u] + J - kv_first_[u])] += value;
  });
}

// --- The half model: an open band, assembled from y without the mirror expansion ---------
//
// polygon_band_lanes.cpp assembles it (the element order and the sums there) and
// polygon_band_solve.cpp solves it, all rings two or four to a vector where the ring lanes are
// on (set_ring_lanes), ring by ring otherwise (the reference).
namespace {

// The rings' lanes in the interleaved band arrays (half_band_step): an even count, two rings
// to a Pair, with a spare lane (identity, b = 0) when the ring count is odd.
inline int lane_count(int rings) { return band_lane_count(rings); }

// How many rings to a vector in the band's assembly and solve: 1 with the ring lanes off (the
// reference), else 4 (AVX2 where the CPU has it, 2 otherwise) — the assembly 8 where the CPU
// has AVX-512 (hinge/ring_lanes_wide.hpp; the solve's chain is its latency, not its width). In a build with FMA
// (RINGCRUSH_NATIVE) the assembly stays ring by ring and the solve two to a vector, as before
// the lanes: GCC may fuse a product into a sum there, on the lanes differently from the
// ring-by-ring form (as ring_lanes_apply).
inline int lane_width(bool ring_lanes, bool assembly) {
#ifdef __FMA__
  (void)ring_lanes;
  return assembly ? 1 : 2;
#else
  if (!ring_lanes) return 1;
  return assembly && lanes::wide_lanes_available() == 8 ? 8 : 4;
#endif
}

}  // namespace

void PolygonChain::assemble_half_band(int ring, const double* y, double* band) {
  // The element scratch is the tail of kv_band_c_ (prepare_half_band), its unused slots 0.
  double* scratch = kv_band_c_.data() + kv_band_c_.size() - ring_band_scratch_size(n_ind_);
  // The membrane's bar directions for its K_m products (ring_damper_membrane_kick).
  double* bar_e = implicit_membrane_ ? membrane_e_.data() + 2 * static_cast<std::ptrdiff_t>(ring * (n_ind_ - 1)) : nullptr;
  assemble_ring_band(y + node_offset(ring, 0), n_ind_, bar_matrix_coefficient(), c_hinge_, band, lane_count(n_rings_),
                     scratch, bar_e);
}

// All rings at once: the factorisation and the two substitutions are chains of dependent
// operations (each row waits for the previous ones), so the rings' bands are interleaved
// (ring index innermost) and the rings advance in lockstep, two or four to a vector —
// independent work for the processor's pipelines and SIMD lanes (polygon_band_solve.cpp). The
// pad rows (identity before the band, zero after it) stay from the first call, so each call
// writes only the band.
void PolygonChain::half_band_step(const double* y, double h, double* v, double* d) {
  prepare_half_band();
  assemble_half_bands(y);
  half_band_solve(h, v, d);
}

void PolygonChain::prepare_half_band() {
  const int n = 2 * n_ind_, R = n_rings_, S = lane_count(R);
  const std::size_t band_size = 6 * static_cast<std::size_t>(n) * static_cast<std::size_t>(S);
  if (implicit_membrane_) membrane_e_.resize(2 * static_cast<std::size_t>((n_ind_ - 1) * R));
  if (kv_band_c_.size() != band_size + ring_band_scratch_size(n_ind_)) {
    // C(i, i − q) of ring r at (6 i + q) S + r (a spare lane 0), then the element scratch of
    // assemble_half_band.
    kv_band_c_.assign(band_size + ring_band_scratch_size(n_ind_), 0.0);
    // The factors, L(i, i − q) of ring r at (6 i + q) S + r, with their pad rows.
    band_factor_rows(n_ind_, R, kv_band_l_, kv_inv_diag_, kv_b_);
    kv_inverse_mu_.resize(mu_.size());
    for (std::size_t i = 0; i < mu_.size(); ++i) kv_inverse_mu_[i] = 1.0 / mu_[i];
  }
}

void PolygonChain::assemble_half_bands(const double* y) {
  const int width = lane_width(ring_lanes_, true);
  if (width == 1) {  // the reference: ring by ring
    for (int r = 0; r < n_rings_; ++r) assemble_half_band(r, y, kv_band_c_.data() + r);
    return;
  }
  double* scratch = kv_band_c_.data() + kv_band_c_.size() - ring_band_scratch_size(n_ind_);
  assemble_ring_bands(y, 6 * static_cast<std::size_t>(n_ind_), n_rings_, n_ind_, bar_matrix_coefficient(), c_hinge_,
                      kv_band_c_.data(), scratch, implicit_membrane_ ? membrane_e_.data() : nullptr, width);
}

void PolygonChain::half_band_solve(double h, double* v, double* d) {
  const auto lanes = static_cast<std::size_t>(lane_count(n_rings_));
  const BandSolve p{kv_band_c_.data(),
                    kv_band_l_.data() + 6 * kBandPadRows * lanes,
                    kv_b_.data() + kBandPadRows * lanes,
                    kv_inv_diag_.data() + kBandPadRows * lanes,
                    mu_.data(),
                    n_ind_,
                    n_rings_,
                    h,
                    v,
                    d};
  if (!solve_ring_bands(p, lane_width(ring_lanes_, false)))
    throw std::runtime_error("PolygonChain::ring_damper_step: μ + h C is not positive definite");
}

void PolygonChain::ring_damper_forces(const double* y, const double* v, double* d) {
  const int n = 2 * n_ind_;
  for (int r = 0; r < n_rings_; ++r) {
    assemble_ring_dampers(r, y);
    const std::size_t o = node_offset(r, 0) + 2;  // row 2j + c ↦ state o + 6j + c
    auto row = [&](int i) { return o + 6 * static_cast<std::size_t>(i / 2) + static_cast<std::size_t>(i % 2); };
    profile_multiply(kv_first_, kv_start_, kv_c_, n, row, v, d);
  }
}

// The damper moments' plastic part (PolygonChain::hinge_plastic_rate_forces, polygon_chain.hpp):
// hinge k's moment −c_θ θ̇p_k puts −M g = c_θ θ̇p_k g on its nodes (k − 1, k, k + 1), g the
// hinge-angle gradient of for_each_damper_entry, weighted and mirrored as there, so that with C
// of the same geometry the hinge dampers' force is −Σ c_θ g (g·v − θ̇p) = −(C v − out).
double PolygonChain::hinge_plastic_rate_forces(const double* y, const double* rate, double* out) {
  const double share = half_ ? 0.5 : 1.0;
  double square_sum = 0.0;
  for (int r = 0; r < n_rings_; ++r) {
    const std::size_t o = node_offset(r, 0);
    auto row = [&](int j) { return o + 6 * static_cast<std::size_t>(j); };
    for (int j = 0; j < n_ind_; ++j) out[row(j) + 2] = out[row(j) + 3] = 0.0;
    if (!(c_hinge_ > 0)) continue;
    // Full-ring node k's position (the half model mirrors k ≥ n_ind).
    auto position = [&](int k, double& px, double& py) {
      const bool mirrored = half_ && k >= n_ind_;
      const std::size_t q = row(mirrored ? n_full_ - k : k);
      px = mirrored ? -y[q] : y[q];
      py = y[q + 1];
    };
    auto hinge = [&](int k, double f) {
      const int km = (k + n_full_ - 1) % n_full_, kp = (k + 1) % n_full_;
      double xm, ym, x, yk, xp, yp;
      position(km, xm, ym);
      position(k, x, yk);
      position(kp, xp, yp);
      const int nodes[3] = {km, k, kp};
      const auto grad = hinge_angle_gradient(x - xm, yk - ym, xp - x, yp - yk);
      const auto& g = grad.g;
      for (int p = 0; p < 3; ++p) {
        const auto [jp, sp] = independent(nodes[p]);
        const std::size_t q = row(jp) + 2;
        if (!(half_ && (jp == 0 || jp == n_ind_ - 1))) out[q] += f * g[p][0] * sp;  // axis x rows stay 0
        out[q + 1] += f * g[p][1];
      }
    };
    // Only the flowing hinges (θ̇p ≠ 0; most hinges in most steps have none); in the half
    // model an off-axis hinge j and its image N − j, which has the same θp.
    for (int j = 0; j < n_ind_; ++j) {
      const double tp = rate[row(j) + 4];
      if (tp == 0.0) continue;
      const double f = share * c_hinge_ * tp;
      const bool pair = half_ && j > 0 && j < n_ind_ - 1;
      square_sum += (pair ? 2.0 : 1.0) * f * tp;
      hinge(j, f);
      if (pair) hinge(n_full_ - j, f);
    }
  }
  return square_sum;
}

void PolygonChain::ring_damper_step(const double* y, double h, double* v, double* d) {
  if (!(h >= 0.0))
    throw std::invalid_argument("PolygonChain::ring_damper_step: h must be ≥ 0, got " + std::to_string(h));
  if (h == 0.0) {  // μ v = μ v*
    ring_damper_forces(y, v, d);
    return;
  }
  if (half_) {
    half_band_step(y, h, v, d);
    return;
  }
  const int n = 2 * n_ind_;
  for (int r = 0; r < n_rings_; ++r) {
    assemble_ring_dampers(r, y);
    const std::size_t o = node_offset(r, 0) + 2;
    auto row = [&](int i) { return o + 6 * static_cast<std::size_t>(i / 2) + static_cast<std::size_t>(i % 2); };
    // μ + h C, and b = μ v* (0 on the axis x rows, whose C rows are empty: v stays 0).
    for (std::size_t e = 0; e < kv_c_.size(); ++e) kv_factor_[e] = h * kv_c_[e];
    for (int i = 0; i < n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      const bool axis_x = half_ && i % 2 == 0 && (i == 0 || i == n - 2);
      kv_factor_[static_cast<std::size_t>(kv_start_[u + 1] - 1)] += mu_[row(i)];
      kv_b_[u] = axis_x ? 0.0 : mu_[row(i)] * v[row(i)];
    }
    // Profile Cholesky μ + h C = L Lᵀ in place (row i: L_ij for j = first_i…i).
    for (int i = 0; i < n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      double* li = kv_factor_.data() + kv_start_[u] - kv_first_[u];
      for (int j = kv_first_[u]; j <= i; ++j) {
        const auto w = static_cast<std::size_t>(j);
        const double* lj = kv_factor_.data() + kv_start_[w] - kv_first_[w];
        double s = li[j];
        for (int k = std::max(kv_first_[u], kv_first_[w]); k < j; ++k) s -= li[k] * lj[k];
        if (j < i) {
          li[j] = s / lj[j];
        } else {
          if (!(s > 0.0))
            throw std::runtime_error("PolygonChain::ring_damper_step: μ + h C is not positive definite (ring " +
                                     std::to_string(r) + ", row " + std::to_string(i) + ")");
          li[i] = std::sqrt(s);
        }
      }
    }
    // L z = b, then Lᵀ v = z (column sweep over the rows of L).
    for (int i = 0; i < n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      const double* li = kv_factor_.data() + kv_start_[u] - kv_first_[u];
      double s = kv_b_[u];
      for (int k = kv_first_[u]; k < i; ++k) s -= li[k] * kv_b_[static_cast<std::size_t>(k)];
      kv_b_[u] = s / li[i];
    }
    for (int i = n - 1; i >= 0; --i) {
      const auto u = static_cast<std::size_t>(i);
      const double* li = kv_factor_.data() + kv_start_[u] - kv_first_[u];
      const double vi = kv_b_[u] / li[i];
      kv_b_[u] = vi;
      for (int k = kv_first_[u]; k < i; ++k) kv_b_[static_cast<std::size_t>(k)] -= li[k] * vi;
    }
    for (int i = 0; i < n; ++i) v[row(i)] = kv_b_[static_cast<std::size_t>(i)];
    // d = C v with this ring's C (still in kv_c_).
    profile_multiply(kv_first_, kv_start_, kv_c_, n, row, v, d);
  }
}

}  // namespace ringcrush::hinge
