// The central-difference driver's update of the hinges' first-order states θp, ā
// (PolygonChain::advance_plastic_flow, polygon_chain.hpp). The explicit step (~0.1–0.3 µs,
// polygon_stable_step.cpp) is longer than the relaxation time of the default Perzyna flow:
// with λ̇ = C (|M|/M_y − 1), C = 2 l_h D / t = 4e4 s⁻¹ (α = 2, D = 1e4 s⁻¹) and
// ∂M/∂θp = −k_θ, 1/τ = C k_θ / M_y = 4e4 × E t / (3 ℓ0 σ0) ≈ 4.9e6 s⁻¹, τ ≈ 0.2 µs; forward
// Euler on θp diverges for dt > 2τ. Backward Euler at the step's end positions is stable for
// any dt (the discrete map contracts: g(Δλ) below is increasing) and, for dt ≫ τ, returns the
// hinge to the rate-dependent yield surface as a return mapping does (THEORY §4.3).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "hinge/polygon_chain.hpp"

namespace ringcrush::hinge {

// Rotation θ = τ − 2π/N of hinge j of `ring`, with τ the turning of the polygon at node j
// (clockwise order, as in ring_forces): θ = wrap(β_{j−1} − β_j) − 2π/N.
double PolygonChain::hinge_rotation(int ring, int j, const double* y) const {
  auto node = [&](int k, double& x, double& yy) {
    k = (k + n_full_) % n_full_;
    const bool mirrored = half_ && k >= n_ind_;
    const auto o = node_offset(ring, mirrored ? n_full_ - k : k);
    x = mirrored ? -y[o] : y[o];
    yy = y[o + 1];
  };
  double xm = 0, ym = 0, x0 = 0, y0 = 0, xp = 0, yp = 0;
  node(j - 1, xm, ym);
  node(j, x0, y0);
  node(j + 1, xp, yp);
  const double b0 = std::atan2(y0 - ym, x0 - xm), b1 = std::atan2(yp - y0, xp - x0);
  return wrap_angle(b0 - b1) - 2.0 * std::numbers::pi / n_full_;
}

double PolygonChain::advance_plastic_flow(double dt, double* y, double& min_relaxation_time) {
  double work = 0.0;
  for (int r = 0; r < n_rings_; ++r)
    for (int j = 0; j < n_ind_; ++j) {
      const auto o = node_offset(r, j);
      const double trial = k_theta_ * (hinge_rotation(r, j, y) - y[o + 4]);
      const double a0 = y[o + 5];
      if (!(flow(trial, a0).rate > 0.0)) continue;
      const double mt = std::abs(trial);
      // g(Δ) = Δ − dt λ̇(|M_trial| − k_θ Δ, ā + Δ): g(0) < 0, g(|M_trial|/k_θ) > 0 (M = 0
      // there), g increasing; Newton kept inside the bracket, bisection when it leaves it.
      double lo = 0.0, hi = mt / k_theta_, d = 0.0;
      double slope_rate = 0.0;  // ∂λ̇/∂θp at the solution, for the relaxation time
      for (int it = 0; it < 60; ++it) {
        const double m = mt - k_theta_ * d;
        const Flow fl = flow(m, a0 + d);
        const double g = d - dt * fl.rate;
        if (g < 0.0) lo = d; else hi = d;
        double dl_dm = 0.0, dl_da = 0.0;
        if (fl.over > 0.0) {
          const double c = C_vp_ * q_ * std::pow(fl.over, q_ - 1.0) / fl.yield_moment;
          dl_dm = c;
          dl_da = M0_ + H_ * (a0 + d) < cap_ ? -c * m * H_ / fl.yield_moment : 0.0;
        }
        slope_rate = dl_dm * k_theta_;
        const double dg = 1.0 + dt * (dl_dm * k_theta_ - dl_da);
        double next = d - g / dg;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const bool done = std::abs(next - d) <= 1e-14 * std::max(hi, 1e-300);
        d = next;
        if (done) break;
      }
      const double sg = trial > 0 ? 1.0 : -1.0;
      y[o + 4] += sg * d;
      y[o + 5] = a0 + d;
      // The elastic energy the step releases at fixed θ, ½(|M_trial| + |M_end|) Δλ, is booked
      // as plastic work: backward Euler's |M_end| Δλ would leave ½ k_θ Δλ² per step out of
      // the energy balance.
      work += node_weight(j) * 0.5 * (mt + (mt - k_theta_ * d)) * d;
      if (slope_rate > 0.0) min_relaxation_time = std::min(min_relaxation_time, 1.0 / slope_rate);
    }
  return work;
}

}  // namespace ringcrush::hinge
