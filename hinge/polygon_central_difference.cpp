#include "polygon_central_difference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

PolygonCentralDifference::PolygonCentralDifference(PolygonChain& chain, double t0, std::vector<double> y0,
                                                   const CentralDifferenceOptions& options)
    : chain_(chain), options_(options), t_(t0), y_(std::move(y0)) {
  if (!(options.safety > 0.0 && options.safety <= 1.0))
    throw std::invalid_argument("PolygonCentralDifference: safety must lie in (0, 1], got " +
                                std::to_string(options.safety));
  if (!(options.max_step_s >= 0.0))
    throw std::invalid_argument("PolygonCentralDifference: max_step_s must be ≥ 0, got " +
                                std::to_string(options.max_step_s));
  if (!(options.fixed_step_s >= 0.0 && std::isfinite(options.fixed_step_s)))
    throw std::invalid_argument("PolygonCentralDifference: fixed_step_s must be ≥ 0 and finite, got " +
                                std::to_string(options.fixed_step_s));
  if (options.implicit_membrane && !options.implicit_ring_dampers)
    throw std::invalid_argument(
        "PolygonCentralDifference: implicit_membrane needs implicit_ring_dampers (the membrane joins the "
        "dampers' banded solve)");
  if (y_.size() != chain.size())
    throw std::invalid_argument("PolygonCentralDifference: state size " + std::to_string(y_.size()) +
                                " is not the chain's " + std::to_string(chain.size()));
  // The kinematic pairs x′ = v: node (x, y) and free bodies' y. Axis nodes' x stays 0 (its
  // force row is 0); the driven impactor's position follows the prescribed speed. The nodes'
  // rows [x, y, vx, vy, θp, ā] follow each other from row 0 (node_offset), so the node pairs
  // are walked as one strided range, not through index lists.
  nodes_end_ = chain.node_offset(chain.ring_count() - 1, chain.independent_nodes() - 1) + 6;
  for (int b = 0; b < chain.body_count(); ++b) {
    if (b == 0 && chain.input().driven_impactor) continue;
    position_rows_.push_back(chain.body_offset(b));
    velocity_rows_.push_back(chain.body_offset(b) + 1);
  }
  a_.resize(y_.size());
  a_next_.resize(y_.size());
  // Elastic-rate hinge dampers: the explicit damper term, p = Σ c_θ θ̇p g, joins the implicit
  // dampers' kicks (or, with explicit dampers, the chain's own evaluation takes θ̇p from its
  // flow update: polygon_flow_update.cpp). θ̇p = 0 at t0 (no flow before the first step).
  elastic_rate_dampers_ = chain.hinge_damper_on_elastic_rate() && options.implicit_ring_dampers;
  if (elastic_rate_dampers_) {
    theta_p_start_.assign(y_.size(), 0.0);
    inverse_mass_.assign(y_.size(), 0.0);
    for (std::size_t o = 2; o < nodes_end_; o += 6)
      for (std::size_t i = o; i < o + 2; ++i) inverse_mass_[i] = 1.0 / chain_.mass_row(i);
    plastic_rate_.assign(y_.size(), 0.0);
    plastic_force_.assign(y_.size(), 0.0);
  }
  chain_.set_implicit_ring_dampers(options.implicit_ring_dampers);
  chain_.set_implicit_membrane(options.implicit_membrane);
  chain_.set_contact_landing(options.contact_landing_depth, options.contact_landing_speed);
  // dt = 0: no flow, but the chain notes the hinge moments the first step's work starts from.
  double no_work = 0.0;
  chain_.rhs_with_flow_update(t_, y_.data(), 0.0, a_.data(), no_work, stats_.min_flow_relaxation_s);
  ++stats_.rhs_evaluations;
  if (options.implicit_ring_dampers) {
    damper_.assign(y_.size(), 0.0);
    damper_next_.assign(y_.size(), 0.0);
    v_start_.assign(y_.size(), 0.0);
    v_half_.assign(y_.size(), 0.0);
    chain_.ring_damper_forces(y_.data(), y_.data(), damper_.data());
    for (std::size_t o = 2; o < nodes_end_; o += 6)
      for (std::size_t i = o; i < o + 2; ++i) a_[i] -= damper_[i] / chain_.mass_row(i);
  }
  // The power estimate is of the undamped stiffness: it bounds the implicit dampers' step
  // only (CentralDifferenceOptions::power_iteration_bound).
  if (options.power_iteration_bound && options.implicit_ring_dampers) {
    if (!(options.power_margin >= 1.0) || !(options.power_refresh_steps >= 1) ||
        !(options.power_min_refresh_steps >= 1) || !(options.power_refresh_change > 0.0))
      throw std::invalid_argument(
          "PolygonCentralDifference: power_margin must be ≥ 1, the refresh intervals ≥ 1 and "
          "power_refresh_change > 0");
    spectrum_.emplace(chain);
  }
  update_stable_step();
  if (options.implicit_membrane) filter_initial_acceleration();
}

// The first kick is Newmark's first step: the membrane at the midpoint x_0 + h v_{½}, i.e.
// (μ + h C + h² K_m) u = h μ a_0 − h² K_m v_0 for u = v_{½} − v_0 (a_0 holding f − C v_0), with
// h = ½ × the first step's bound (an `advance` target may shorten that step: O(Δt³) in u).
// Without the −h² K_m v_0 term an initial velocity in a membrane mode past 2/Δt would enter
// v_{½} unfiltered and start that mode at (ωΔt/2)× its amplitude (the energy ×(ωΔt/2)²: ×25 at
// 10× the explicit step, tests/hinge/polygon_implicit_membrane_test.cpp). What the filter takes
// off, μ (a_0 − u/h), is the first kick's implicit force.
void PolygonCentralDifference::filter_initial_acceleration() {
  const double h = 0.5 * dt_stable_;
  stiff_half_.assign(y_.size(), 0.0);
  stiff_end_.assign(y_.size(), 0.0);
  correction_.assign(y_.size(), 0.0);
  correction_next_.assign(y_.size(), 0.0);
  chain_.membrane_stiffness_product(y_.data(), y_.data(), stiff_end_.data());  // K_m v_0
  std::vector<double>& u = stiff_half_;  // scratch: the solve's v rows
  for (std::size_t o = 2; o < nodes_end_; o += 6)
    for (std::size_t i = o; i < o + 2; ++i) u[i] = h * a_[i] - h * h * stiff_end_[i] / chain_.mass_row(i);
  chain_.ring_damper_membrane_step(y_.data(), h, u.data(), stiff_end_.data());
  for (std::size_t o = 2; o < nodes_end_; o += 6)
    for (std::size_t i = o; i < o + 2; ++i) {
      const double filtered = u[i] / h;
      correction_[i] = chain_.mass_row(i) * (a_[i] - filtered);
      damper_[i] += correction_[i];
      a_[i] = filtered;
    }
}

void PolygonCentralDifference::update_stable_step() {
  // Both from the step's evaluation (the estimate below evaluates the chain anew).
  const double bound = chain_.stable_step(), landing = chain_.contact_landing_step();
  if (spectrum_) {
    ++power_age_;
    const bool due = power_age_ >= options_.power_refresh_steps ||
                     (power_age_ >= options_.power_min_refresh_steps &&
                      std::abs(bound - power_reference_) > options_.power_refresh_change * power_reference_);
    if (power_reference_ == 0.0 || due) {
      const auto e = spectrum_->estimate(t_, y_.data(), 5, 30, 1e-3);
      power_ratio_ = std::max(1.0, 2.0 / std::sqrt(options_.power_margin * e.lambda) / bound);
      power_reference_ = bound;
      power_age_ = 0;
      ++stats_.power_refreshes;
    }
  }
  dt_stable_ = options_.safety * power_ratio_ * bound;
  if (options_.max_step_s > 0) dt_stable_ = std::min(dt_stable_, options_.max_step_s);
  if (options_.contact_landing_depth > 0.0 && landing < dt_stable_) {
    dt_stable_ = landing;
    ++stats_.landing_steps;
  }
  if (options_.fixed_step_s > 0.0) dt_stable_ = options_.fixed_step_s;
}

// The second half-kick with the membrane implicit (polygon_central_difference.hpp): the node
// rows hold v* and v_half_ v_{n+½}; solves (μ + h C + h² K_m) v = μ v* + h² K_m v_{n+½}, forms
// the implicit force d = C v + h K_m u and books its work and the correction's.
void PolygonCentralDifference::membrane_step(double h) {
  const std::size_t acc = chain_.accumulator_offset();
  double* y = y_.data();
  // K_m v_{n+½}, the solve, d = (C + h K_m) v_{n+1} and K_m v_{n+1} on one assembly.
  chain_.ring_damper_membrane_kick(y, h, v_half_.data(), y, damper_next_.data(), stiff_half_.data(),
                                   stiff_end_.data());
  if (elastic_rate_dampers_) finish_plastic_rate_step(2.0 * h);
  // Each node's (x, y) rows as one Pair, u/h by one reciprocal (a division per row was the
  // loop's longest latency), and the two works summed per lane — x rows and y rows apart, then
  // added: the sums' order is not the rows', so their last bits are not the row-by-row sums'
  // (the serial sum was this loop's other latency chain).
  const double inv_h = 1.0 / h;
  using lanes::Pair;
  Pair work2 = {0.0, 0.0}, correction2 = {0.0, 0.0};
  for (std::size_t o = 2; o < nodes_end_; o += 6) {
    const Pair k_half = lanes::load(&stiff_half_[o]);
    const Pair correction = h * (lanes::load(&stiff_end_[o]) - k_half);
    const Pair d = lanes::load(&damper_next_[o]) - h * k_half;
    const Pair v = lanes::load(y + o), v_half = lanes::load(&v_half_[o]);
    lanes::store(&correction_next_[o], correction);
    lanes::store(&damper_next_[o], d);
    lanes::store(&a_next_[o], (v - v_half) * inv_h);
    const Pair start = lanes::load(&v_start_[o]) + v_half, end = v_half + v;
    work2 += lanes::load(&damper_[o]) * start + d * end;
    correction2 += lanes::load(&correction_[o]) * start + correction * end;
  }
  const double work = work2[0] + work2[1], correction_work = correction2[0] + correction2[1];
  // ¼Δt = ½h.
  y[acc + 2] += 0.5 * h * work;
  stats_.membrane_correction_work_j += 0.5 * h * correction_work;
  damper_.swap(damper_next_);
  correction_.swap(correction_next_);
}

// Elastic-rate hinge dampers, after the step's evaluation at x_{n+1}: θ̇p of the step from its
// flow update, p = Σ c_θ θ̇p g (PolygonChain::hinge_plastic_rate_forces) into the acceleration
// of the second half-kick (a_next = f/μ; the solve then reads v* = v_{n+½} + ½Δt (f + p)/μ).
void PolygonCentralDifference::add_plastic_rate_forces(double dt) {
  double* y = y_.data();
  const double inv_dt = 1.0 / dt;
  for (std::size_t o = 4; o < nodes_end_; o += 6) plastic_rate_[o] = (y[o] - theta_p_start_[o]) * inv_dt;
  plastic_square_sum_ = chain_.hinge_plastic_rate_forces(y, plastic_rate_.data(), plastic_force_.data());
  for (std::size_t o = 2; o < nodes_end_; o += 6)
    for (std::size_t i = o; i < o + 2; ++i) a_next_[i] += plastic_force_[i] * inverse_mass_[i];
}

// ... and after the solve: the damper force at n+1 is −(C v_{n+1} − p), so d_{n+1} = C v − p is
// what the kicks' work books (and the next step's first kick reads as d_n); the damper
// moments' work on the plastic rate over the step, Δt (p·v_{n+1} − Σ w c_θ θ̇p²), is noted.
void PolygonCentralDifference::finish_plastic_rate_step(double dt) {
  const double* y = y_.data();
  double pv = 0.0;
  for (std::size_t o = 2; o < nodes_end_; o += 6)
    for (std::size_t i = o; i < o + 2; ++i) {
      damper_next_[i] -= plastic_force_[i];
      pv += plastic_force_[i] * y[i];
    }
  stats_.hinge_damper_plastic_work_j += dt * (pv - plastic_square_sum_);
}

double PolygonCentralDifference::advance(double t_end) {
  while (t_ < t_end) {
    // Equal steps to the target, none above the stable one.
    const double remaining = t_end - t_;
    const double n = std::max(1.0, std::ceil(remaining / dt_stable_ * (1.0 - 1e-12)));
    step(n == 1.0 ? remaining : remaining / n);
    if (n == 1.0) t_ = t_end;  // no round-off left over
  }
  return t_;
}

void PolygonCentralDifference::step(double dt) {
  const std::size_t acc = chain_.accumulator_offset();
  const std::size_t nb = velocity_rows_.size();
  const bool implicit = options_.implicit_ring_dampers;
  double* y = y_.data();
  const double* a = a_.data();
  double* a_next = a_next_.data();
  // The node rows' (x, y) and (v_x, v_y) as Pairs, v_n kept for the implicit dampers' work.
  using lanes::Pair;
  const double half_dt = 0.5 * dt;
  for (std::size_t o = 0; o < nodes_end_; o += 6) {
    Pair v = lanes::load(y + o + 2);
    if (implicit) lanes::store(&v_start_[o + 2], v);
    v += half_dt * lanes::load(a + o + 2);
    lanes::store(y + o + 2, v);
    lanes::store(y + o, lanes::load(y + o) + dt * v);
  }
  for (std::size_t i = 0; i < nb; ++i) {
    double& v = y[velocity_rows_[i]];
    v += 0.5 * dt * a[velocity_rows_[i]];
    y[position_rows_[i]] += dt * v;
  }
  if (chain_.input().driven_impactor)  // y′ = −V(t) at the step's midpoint
    y[chain_.body_offset(0)] -= dt * chain_.impactor_velocity(t_ + 0.5 * dt, y);
  for (std::size_t k = 1; k < 4; ++k) y[acc + k] += 0.5 * dt * a[acc + k];

  if (elastic_rate_dampers_)
    for (std::size_t o = 4; o < nodes_end_; o += 6) theta_p_start_[o] = y[o];

  t_ += dt;
  chain_.rhs_with_flow_update(t_, y, dt, a_next, y[acc], stats_.min_flow_relaxation_s);
  ++stats_.rhs_evaluations;
  if (elastic_rate_dampers_) add_plastic_rate_forces(dt);
  for (std::size_t o = 2; o < nodes_end_; o += 6) {
    const Pair v = lanes::load(y + o);
    if (implicit) lanes::store(&v_half_[o], v);
    lanes::store(y + o, v + half_dt * lanes::load(a_next + o));
  }
  for (std::size_t i = 0; i < nb; ++i) y[velocity_rows_[i]] += 0.5 * dt * a_next[velocity_rows_[i]];
  for (std::size_t k = 1; k < 4; ++k) y[acc + k] += 0.5 * dt * a_next[acc + k];
  if (implicit && options_.implicit_membrane) {
    membrane_step(0.5 * dt);
  } else if (implicit) {
    // The node rows now hold the explicit prediction v*; (μ + ½Δt C) v = μ v*, and the
    // acceleration of the second half-kick (the next step's first) is (v_{n+1} − v_{n+½})/(½Δt).
    chain_.ring_damper_step(y, 0.5 * dt, y, damper_next_.data());
    if (elastic_rate_dampers_) finish_plastic_rate_step(dt);
    const double* d = damper_.data();
    const double* d_next = damper_next_.data();
    double work = 0.0;
    for (std::size_t o = 2; o < nodes_end_; o += 6)
      for (std::size_t i = o; i < o + 2; ++i) {
        a_next[i] = (y[i] - v_half_[i]) / (0.5 * dt);
        work += d[i] * (v_start_[i] + v_half_[i]) + d_next[i] * (v_half_[i] + y[i]);
      }
    y[acc + 2] += 0.25 * dt * work;
    damper_.swap(damper_next_);
  }
  a_.swap(a_next_);

  ++stats_.steps;
  stats_.min_step_s = std::min(stats_.min_step_s, dt);
  stats_.max_step_s = std::max(stats_.max_step_s, dt);
  update_stable_step();
  if (!std::isfinite(y_[acc]))
    throw std::runtime_error("PolygonCentralDifference: non-finite plastic work at t = " + std::to_string(t_) +
                             " (the integration diverged)");
  if (!(dt_stable_ > 0.0))
    throw std::runtime_error("PolygonCentralDifference: no stable step at t = " + std::to_string(t_));
}

}  // namespace ringcrush::hinge
