// The central-difference driver's update of the hinges' first-order states θp, ā
// (PolygonChain::rhs_with_flow_update, polygon_chain.hpp). The flow is stiff: with
// λ̇ = C (|M|/M_y − 1), C = 2 l_h D / t = 4e4 s⁻¹ (α = 2, D = 1e4 s⁻¹, the default Perzyna law)
// and ∂M/∂θp = −k_θ, 1/τ = C k_θ / M_y = 4e4 × E t / (3 ℓ0 σ0) ≈ 4.9e6 s⁻¹, τ ≈ 0.2 µs —
// shorter than the undamped explicit step (0.6 µs at N = 48) and within a factor 2 of the
// damped one (~0.1 µs, polygon_stable_step.cpp); forward Euler on θp diverges for dt > 2τ.
// Backward Euler at the step's end positions is stable for any dt (g(Δλ) below is increasing,
// one root) and, for dt ≫ τ, returns the hinge to the rate-dependent yield surface as a
// return mapping does (THEORY §4.3).
#include <algorithm>
#include <cmath>
#include <limits>

#include "hinge/polygon_chain.hpp"

namespace ringcrush::hinge {

// Δλ ≥ 0 of one hinge from its trial moment k_θ(θ_{n+1} − θp_n) and ā_n.
double PolygonChain::return_map(double trial, double a0, double dt, double& min_relaxation_time) const {
  if (!(flow(trial, a0).rate > 0.0)) return 0.0;
  const double mt = std::abs(trial);
  if (q_ == 1.0) {
    // The default Perzyna law in closed form: with M_y = M0 + H(ā + Δ) below the cap,
    // g(Δ) = 0 is H Δ² + (M_y0 + dt C (k_θ + H)) Δ − dt C (|M_t| − M_y0) = 0 (its positive
    // root, written without cancellation); at the cap, M_y = cap and g is linear. g is
    // increasing, so the branch whose M_y agrees with the root's is the one root.
    const double cdt = C_vp_ * dt, my0 = M0_ + H_ * a0;
    double d = 0.0, my = cap_;
    if (my0 < cap_) {
      const double b = my0 + cdt * (k_theta_ + H_), c = cdt * (mt - my0);
      d = 2.0 * c / (b + std::sqrt(b * b + 4.0 * H_ * c));
      my = my0 + H_ * d;
    }
    if (!(my < cap_)) {
      my = cap_;
      d = cdt * (mt - cap_) / (cap_ + cdt * k_theta_);
    }
    min_relaxation_time = std::min(min_relaxation_time, my / (C_vp_ * k_theta_));
    return d;
  }
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
      const double c = C_vp_ * q_ * (q_ == 1.0 ? 1.0 : std::pow(fl.over, q_ - 1.0)) / fl.yield_moment;
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
  if (slope_rate > 0.0) min_relaxation_time = std::min(min_relaxation_time, 1.0 / slope_rate);
  return d;
}

// Hinge k (independent) of ring r at rotation θ, trial moment k_θ(θ − θp_n): θp, ā in the
// state, the work; returns the moment after the update.
double PolygonChain::flow_hinge(int r, int k, double theta, double trial) {
  const auto o = node_offset(r, k);
  const auto h = flow_index(r, k);
  double moment = trial;
  const double d = flow_dt_ > 0.0 ? return_map(trial, flow_y_[o + 5], flow_dt_, flow_relaxation_) : 0.0;
  if (d > 0.0) {
    const double dtheta_p = trial > 0 ? d : -d;
    flow_y_[o + 4] += dtheta_p;
    flow_y_[o + 5] += d;
    moment = k_theta_ * (theta - flow_y_[o + 4]);
    // Plastic work ½(M_n + M_{n+1}) Δθp, with the moments the leapfrog's forces used at the
    // two ends of the step: the hinge's elastic energy then changes by exactly
    // ½(M_n + M_{n+1})(Δθ − Δθp) against the forces' work ½(M_n + M_{n+1}) Δθ, and the
    // balance closes (booking ½(|M_trial| + |M_{n+1}|) Δλ instead leaves ½ k_θ Δλ Δθ per step
    // out: ~1e-3 of the impact energy on Test 30).
    flow_work_ += node_weight(k) * 0.5 * (flow_moment_[h] + moment) * dtheta_p;
  }
  flow_moment_[h] = moment;
  return moment;
}

// The per-ring pass's scratch: the hinge's θp and that of its mirror image, and its moment.
void PolygonChain::update_hinge_flow(int r, int k, double theta) {
  moment_[k] = flow_hinge(r, k, theta, moment_[k]);
  theta_p_[k] = flow_y_[node_offset(r, k) + 4];
  if (half_ && k > 0 && k < n_ind_ - 1) theta_p_[n_full_ - k] = theta_p_[k];
}

// The ring laws of the central difference's evaluation (ring_forces, reference = false), ring
// r: hinge moments M = k_θ (θ − θp) with the flow update, and bar forces N = k_m (ℓ − ℓ0),
// each with its Kelvin–Voigt damper when explicit, into hinge_m_ and bar_n_.
void PolygonChain::central_difference_ring_laws(int r, Tally& tally) {
  // Explicit elastic-rate hinge dampers (PolygonChainInput::hinge_damper_on_elastic_rate):
  // the step's θ̇p = Δθp/Δt of the update below, a mirrored hinge's that of its image (updated
  // before it: ring_hinges_ ascends).
  const bool elastic_rate = c_hinge_ > 0 && in_.hinge_damper_on_elastic_rate && flow_dt_ > 0.0;
  if (elastic_rate) plastic_step_.assign(static_cast<std::size_t>(n_ind_), 0.0);
  for (const int k : ring_hinges_) {
    const double theta = hinge_theta_[k];
    moment_[k] = k_theta_ * (theta - theta_p_[k]);
    if (k < n_ind_) {
      // |M| ≤ M_y (flow's yield moment): no flow, so no update, and the flow rows stay zero
      // (ring_forces); the moment is noted for the next step's work.
      const double yield = std::min(M0_ + H_ * flow_y_[node_offset(r, k) + 5], cap_);
      const bool elastic = !(std::abs(moment_[k]) > yield);
      hinge_elastic_[static_cast<std::size_t>(k)] = elastic;
      if (elastic) {
        flow_moment_[flow_index(r, k)] = moment_[k];
      } else {
        const double before = theta_p_[k];
        update_hinge_flow(r, k, theta);
        if (elastic_rate) plastic_step_[static_cast<std::size_t>(k)] = theta_p_[k] - before;
      }
    }
    double M = moment_[k];
    if (c_hinge_ > 0) {
      const int km = k == 0 ? n_full_ - 1 : k - 1, kp = k + 1 == n_full_ ? 0 : k + 1;
      const double rate = hinge_damper_rate(km, k, kp);
      // The damper's rate: θ̇, or θ̇ − θ̇p; its power M_damp θ̇ either way.
      const double damper_rate =
          elastic_rate ? rate - plastic_step_[static_cast<std::size_t>(k < n_ind_ ? k : n_full_ - k)] / flow_dt_ : rate;
      M += c_hinge_ * damper_rate;
      if (k < n_ind_) tally.damping += node_weight(k) * c_hinge_ * damper_rate * rate;
    }
    hinge_m_[k] = M;
  }
  for (const int k : ring_bars_) {
    double N = k_m_ * (bar_l_[k] - l0_);
    if (c_bar_ > 0) {
      const double rate = bar_damper_rate(k, k + 1 == n_full_ ? 0 : k + 1);
      N += c_bar_ * rate;
      if (!half_ || k < n_full_ / 2) tally.damping += c_bar_ * rate * rate;
    }
    bar_n_[k] = N;
  }
}

void PolygonChain::rhs_with_flow_update(double t, double* y, double dt, double* dydt, double& plastic_work,
                                        double& min_relaxation_time) {
  flow_y_ = y;
  flow_dt_ = dt;
  flow_work_ = 0.0;
  flow_relaxation_ = min_relaxation_time;
  // Implicit ring dampers (polygon_implicit_dampers.cpp): the evaluation runs with the
  // Kelvin–Voigt coefficients at zero, so φ and the damping power hold the other forces only.
  const double c_bar = c_bar_, c_hinge = c_hinge_;
  if (implicit_dampers_) c_bar_ = c_hinge_ = 0.0;
  auto restore = [&] {
    flow_y_ = nullptr;
    c_bar_ = c_bar;
    c_hinge_ = c_hinge;
  };
  try {
    rhs(t, y, dydt);
  } catch (...) {
    restore();
    throw;
  }
  restore();
  plastic_work += flow_work_;
  min_relaxation_time = flow_relaxation_;
}

}  // namespace ringcrush::hinge
