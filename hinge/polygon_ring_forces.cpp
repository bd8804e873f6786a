// The ring's own forces in the polygon chain's residual (THEORY §4.3): bending hinges as
// elastic–viscoplastic rotational springs with Kelvin–Voigt dampers, membrane bars, and the
// Cowper–Symonds (Perzyna) flow rule of every hinge — with, while analytic_jacobian runs, the
// derivatives of each law (PolygonChain::analytic_jacobian).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "hinge/polygon_chain.hpp"
#include "hinge/polygon_hinge_angle.hpp"

namespace ringcrush::hinge {

PolygonChain::Flow PolygonChain::flow(double moment, double plastic_sum) const {
  const double My = std::min(M0_ + H_ * plastic_sum, cap_);
  const double over = std::abs(moment) / My - 1.0;
  // q = 1 (the default Perzyna law) skips pow: pow(x, 1) is x exactly.
  return {My, over, over > 0.0 ? C_vp_ * (q_ == 1.0 ? over : std::pow(over, q_)) : 0.0};
}

// The half model's equations are those of nodes 0…N/2: a hinge k acts on k − 1, k, k + 1
// and a bar k on k, k + 1, so hinges N/2 + 2…N − 2 and bars N/2 + 2…N − 3 reach only
// mirrored nodes and are skipped, and nodes N/2 + 3…N − 3 are never read (their forces would
// be dropped; the sums on the independent nodes keep their order). The lists are fixed by
// the topology; the bars also as at most two index ranges, so that their loop vectorises.
void PolygonChain::plan_ring_pass() {
  const int h = n_full_ / 2;
  ring_nodes_.clear();
  ring_bars_.clear();
  ring_hinges_.clear();
  bar_ranges_.clear();
  ring_hinge_.assign(static_cast<std::size_t>(n_full_), 0);
  for (int k = 0; k < n_full_; ++k) {
    if (!half_ || k <= h + 2 || k >= n_full_ - 2) ring_nodes_.push_back(k);
    if (!half_ || k <= h + 1 || k >= n_full_ - 2) {
      ring_bars_.push_back(k);
      if (bar_ranges_.empty() || bar_ranges_.back()[1] != k) bar_ranges_.push_back({k, k + 1});
      else bar_ranges_.back()[1] = k + 1;
    }
    if (!half_ || k <= h + 1 || k == n_full_ - 1) {
      ring_hinge_[static_cast<std::size_t>(k)] = 1;
      ring_hinges_.push_back(k);
    }
  }
  hinge_theta_.assign(static_cast<std::size_t>(n_full_), 0.0);
  hinge_m_.assign(static_cast<std::size_t>(n_full_), 0.0);
  bar_n_.assign(static_cast<std::size_t>(n_full_), 0.0);
  // Node N is node 0 again (gather_ring), so bar k always ends at node k + 1.
  px_.resize(static_cast<std::size_t>(n_full_) + 1);
  py_.resize(static_cast<std::size_t>(n_full_) + 1);
  const double turn0 = 2.0 * std::numbers::pi / n_full_;
  turn_cos_ = std::cos(turn0);
  turn_sin_ = std::sin(turn0);
  hinge_elastic_.assign(static_cast<std::size_t>(n_full_), 0);
}

// Positions and θp (velocities only for the Kelvin–Voigt dampers, the one reader) of the
// nodes the ring's bars reach; the half model mirrors nodes N/2 + 1…N − 1.
void PolygonChain::gather_ring(int ring, const double* y, bool velocities) {
  for (const int k : ring_nodes_) {
    const bool mirrored = half_ && k >= n_ind_;
    const auto o = node_offset(ring, mirrored ? n_full_ - k : k);
    px_[k] = mirrored ? -y[o] : y[o];
    py_[k] = y[o + 1];
    theta_p_[k] = y[o + 4];
    if (velocities) {
      vx_[k] = mirrored ? -y[o + 2] : y[o + 2];
      vy_[k] = y[o + 3];
    }
  }
  px_[n_full_] = px_[0];
  py_[n_full_] = py_[0];
}

// Length, direction e and n/ℓ (∂β/∂p of the far end, n = e turned by +90°, read by the two
// hinges the bar joins) of bars k ∈ [first, last), ending at node k + 1. The reference forms
// (`reference`) divide by ℓ and take each bar's angle β by atan2; the central difference's
// multiply by 1/ℓ and need no β (ring_forces).
void PolygonChain::ring_bars(int first, int last, bool reference) {
  const double* __restrict px = px_.data();
  const double* __restrict py = py_.data();
  double* __restrict bl = bar_l_.data();
  double* __restrict ex = bar_ex_.data();
  double* __restrict ey = bar_ey_.data();
  double* __restrict gx = bar_gx_.data();
  double* __restrict gy = bar_gy_.data();
  if (reference) {
    for (int k = first; k < last; ++k) {
      const double bx = px[k + 1] - px[k], by = py[k + 1] - py[k];
      const double l = std::sqrt(bx * bx + by * by);
      bl[k] = l;
      ex[k] = bx / l;
      ey[k] = by / l;
      gx[k] = -ey[k] / l;
      gy[k] = ex[k] / l;
      bar_beta_[k] = std::atan2(by, bx);
    }
    return;
  }
  for (int k = first; k < last; ++k) {
    const double bx = px[k + 1] - px[k], by = py[k + 1] - py[k];
    const double l = std::sqrt(bx * bx + by * by), inv = 1.0 / l;
    bl[k] = l;
    ex[k] = bx * inv;
    ey[k] = by * inv;
    gx[k] = -ey[k] * inv;
    gy[k] = ex[k] * inv;
  }
}

// Rates of the Kelvin–Voigt dampers: θ̇ = ∂θ/∂p · v of hinge k (a, b the n/ℓ of bars k − 1,
// k) and ℓ̇ = e · (v_{k+1} − v_k) of bar k.
double PolygonChain::hinge_damper_rate(int km, int k, int kp) const {
  const double ax = bar_gx_[km], ay = bar_gy_[km], bx = bar_gx_[k], by = bar_gy_[k];
  return -(ax * vx_[km] + ay * vy_[km]) + (ax + bx) * vx_[k] + (ay + by) * vy_[k] - (bx * vx_[kp] + by * vy_[kp]);
}

double PolygonChain::bar_damper_rate(int k, int kp) const {
  return bar_ex_[k] * (vx_[kp] - vx_[k]) + bar_ey_[k] * (vy_[kp] - vy_[k]);
}

// The node forces of the hinge moments M and bar forces N, node by node: hinge k puts
// M a, −M (a + b), M b on nodes k − 1, k, k + 1 (a, b the n/ℓ of bars k − 1, k) and bar k
// puts N e, −N e on nodes k, k + 1, so node j carries
//   (M_{j−1} − M_j) g_{j−1} + (M_{j+1} − M_j) g_j + N_j e_j − N_{j−1} e_{j−1}.
// Gathered per node rather than scattered per hinge, the nodes are independent.
void PolygonChain::ring_node_forces() {
  const double* __restrict m = hinge_m_.data();
  const double* __restrict n = bar_n_.data();
  const double* __restrict gx = bar_gx_.data();
  const double* __restrict gy = bar_gy_.data();
  const double* __restrict ex = bar_ex_.data();
  const double* __restrict ey = bar_ey_.data();
  double* __restrict fx = fx_.data();
  double* __restrict fy = fy_.data();
  const auto node = [&](int j, int jm, int jp) {
    const double before = m[jm] - m[j], after = m[jp] - m[j];
    fx[j] = before * gx[jm] + after * gx[j] + n[j] * ex[j] - n[jm] * ex[jm];
    fy[j] = before * gy[jm] + after * gy[j] + n[j] * ey[j] - n[jm] * ey[jm];
  };
  // The ends wrap round the ring; the nodes between run without index tests.
  const int last = n_ind_ - 1;
  node(0, n_full_ - 1, 1);
  for (int j = 1; j < last; ++j) node(j, j - 1, j + 1);
  node(last, last - 1, last + 1 == n_full_ ? 0 : last + 1);
}

void PolygonChain::ring_forces(const double* y, double* phi, bool record, Tally& tally) {
  const double turn0 = 2.0 * std::numbers::pi / n_full_;
  const bool velocities = c_bar_ > 0 || c_hinge_ > 0;
  // The central difference's evaluation (flow_y_ set) takes the cheaper forms: 1/ℓ, the
  // hinge rotation from the hinge's own bars by a series (polygon_hinge_angle.hpp), the node
  // forces gathered per node (ring_node_forces). They change the round-off only, and the
  // explicit run keeps Test 30's crush to three digits; IDA's step control carries round-off
  // further (Test 30 free: 0.002 D, its energy balance 4× worse, README), so its residual,
  // the Jacobians and Odeint keep the reference forms, to the bit as before.
  const bool reference = flow_y_ == nullptr;
  if (!record && ring_lanes_apply()) {  // all rings at once, the same bits (polygon_ring_lanes.cpp)
    central_difference_ring_lanes(y, phi, tally);
    return;
  }
  for (int r = 0; r < n_rings_; ++r) {
    gather_ring(r, y, velocities);
    if (reference)
      for (const int k : ring_nodes_) fx_[k] = fy_[k] = 0.0;
    for (const auto& range : bar_ranges_) ring_bars(range[0], range[1], reference);
    // Hinge k: turning τ = β_{k−1} − β_k (clockwise node order), rotation θ = τ − 2π/N, the
    // angle from bar k to bar k − 1 turned back by 2π/N. The hinges apart, so that their
    // latencies overlap.
    for (const int k : ring_hinges_) {
      const int km = k == 0 ? n_full_ - 1 : k - 1;
      if (reference) {
        hinge_theta_[k] = wrap_angle(bar_beta_[km] - bar_beta_[k]) - turn0;
        continue;
      }
      const double tx = bar_ex_[km] * turn_cos_ + bar_ey_[km] * turn_sin_;
      const double ty = bar_ey_[km] * turn_cos_ - bar_ex_[km] * turn_sin_;
      hinge_theta_[k] = hinge_rotation(bar_ex_[k] * ty - bar_ey_[k] * tx, bar_ex_[k] * tx + bar_ey_[k] * ty, turn0);
    }
    // The central difference: moments with the flow update and bar forces in two short
    // loops (polygon_flow_update.cpp), node forces gathered; the reference forms below.
    if (!reference) central_difference_ring_laws(r, tally);
    if (reference)
    for (const int k : ring_bars_) {
      const int km = k == 0 ? n_full_ - 1 : k - 1, kp = k + 1 == n_full_ ? 0 : k + 1;
      if (ring_hinge_[static_cast<std::size_t>(k)]) {
        // Moment M = k_θ (θ − θp); forces −M ∂θ/∂p with ∂β/∂p_end = n/ℓ.
        const double ax = bar_gx_[km], ay = bar_gy_[km];
        const double bx = bar_gx_[k], by = bar_gy_[k];
        moment_[k] = k_theta_ * (hinge_theta_[k] - theta_p_[k]);
        double M = moment_[k];
        double hinge_rate = 0.0;
        // The damper on the elastic rate (PolygonChainInput::hinge_damper_on_elastic_rate):
        // θ̇p = λ̇(M, ā) sign M of the flow law at this state (the θp row's φ below, so θp′ on
        // IDA's solution), with ∂λ̇/∂|M| = dl_dm, ∂λ̇/∂ā = dl_da for the Jacobian.
        double plastic_rate = 0.0, dl_dm = 0.0, dl_da = 0.0, sg = 1.0;
        const std::size_t hinge_row = node_offset(r, k < n_ind_ ? k : n_full_ - k);  // its θp, ā
        if (c_hinge_ > 0) {  // Kelvin–Voigt hinge damper on θ̇ = ∂θ/∂p · v (or θ̇ − θ̇p)
          const double rate = hinge_damper_rate(km, k, kp);
          double damper_rate = rate;
          if (in_.hinge_damper_on_elastic_rate) {
            const Flow fl = flow(moment_[k], y[hinge_row + 5]);
            if (fl.over > 0.0) {
              sg = moment_[k] > 0 ? 1.0 : -1.0;
              plastic_rate = sg * fl.rate;
              dl_dm = C_vp_ * q_ * (q_ == 1.0 ? 1.0 : std::pow(fl.over, q_ - 1.0)) / fl.yield_moment;
              dl_da = M0_ + H_ * y[hinge_row + 5] < cap_ ? -dl_dm * std::abs(moment_[k]) * H_ / fl.yield_moment : 0.0;
            }
            damper_rate = rate - plastic_rate;
          }
          M += c_hinge_ * damper_rate;
          // The damper moment's power c_θ θ̇_d θ̇ (θ̇_d its rate: θ̇ or θ̇ − θ̇p).
          if (k < n_ind_) tally.damping += node_weight(k) * c_hinge_ * damper_rate * rate;
          hinge_rate = rate;
        }
        fx_[km] += M * ax;
        fy_[km] += M * ay;
        fx_[k] -= M * (ax + bx);
        fy_[k] -= M * (ay + by);
        fx_[kp] += M * bx;
        fy_[kp] += M * by;
        if (jac_) {
          // F_i = −M g_i with g = ∂θ/∂p = (−a, a + b, −b) on (k−1, k, k+1):
          // ∂F_i/∂p_m ≈ −k_θ g_i g_mᵀ, ∂F_i/∂v_m = −c_θ g_i g_mᵀ, ∂F_i/∂θp_k = k_θ g_i.
          // The curvature terms −M ∂g/∂p (≈ M/ℓ², 1 % of k_θ/ℓ² at full plastic moment)
          // are left out: the matrix only drives Newton, the residual stays exact.
          const std::array<int, 3> nodes{km, k, kp};
          const std::array<double, 3> gx{-ax, ax + bx, -bx}, gy{-ay, ay + by, -by};
          hinge_gx_[k] = gx;
          hinge_gy_[k] = gy;
          for (int i = 0; i < 3; ++i)
            for (int m = 0; m < 3; ++m) {
              const double xx = gx[i] * gx[m], xy = gx[i] * gy[m], yx = gy[i] * gx[m],
                           yy = gy[i] * gy[m];
              ring_block(r, nodes[i], nodes[m], 0, -k_theta_ * xx, -k_theta_ * xy, -k_theta_ * yx,
                         -k_theta_ * yy);
              if (c_hinge_ > 0)
                ring_block(r, nodes[i], nodes[m], 2, -c_hinge_ * xx, -c_hinge_ * xy, -c_hinge_ * yx,
                           -c_hinge_ * yy);
            }
          if (k < n_ind_)  // θp of hinge k is an unknown only for the independent nodes
            for (int i = 0; i < 3; ++i)
              ring_force_entry(r, nodes[i], node_offset(r, k) + 4, k_theta_ * gx[i], k_theta_ * gy[i]);
          else  // mirrored hinge: its θp is that of node N − k
            for (int i = 0; i < 3; ++i)
              ring_force_entry(r, nodes[i], node_offset(r, n_full_ - k) + 4, k_theta_ * gx[i],
                               k_theta_ * gy[i]);
          if (c_hinge_ > 0) {
            // θ̇ = a·(v_k − v_{k−1}) + b·(v_k − v_{k+1}) with a = ∇β(u_{k−1}), b = ∇β(u_k) of the
            // bar vectors u: ∂θ̇/∂u = H_β(u) Δv, H_β = [[2uxuy, uy²−ux²], [uy²−ux², −2uxuy]]/|u|⁴.
            auto hess = [](double ux, double uy, double dvx, double dvy, double& hx, double& hy) {
              const double l2 = ux * ux + uy * uy, l4 = l2 * l2;
              const double hxx = 2 * ux * uy / l4, hxy = (uy * uy - ux * ux) / l4;
              hx = hxx * dvx + hxy * dvy;
              hy = hxy * dvx - hxx * dvy;
            };
            double hax = 0, hay = 0, hbx = 0, hby = 0;
            hess(px_[k] - px_[km], py_[k] - py_[km], vx_[k] - vx_[km], vy_[k] - vy_[km], hax, hay);
            hess(px_[kp] - px_[k], py_[kp] - py_[k], vx_[k] - vx_[kp], vy_[k] - vy_[kp], hbx, hby);
            const std::array<double, 3> rx{-hax, hax - hbx, hbx}, ry{-hay, hay - hby, hby};  // ∂θ̇/∂p
            for (int i = 0; i < 3; ++i)
              for (int m = 0; m < 3; ++m)
                ring_block(r, nodes[i], nodes[m], 0, -c_hinge_ * gx[i] * rx[m], -c_hinge_ * gx[i] * ry[m],
                           -c_hinge_ * gy[i] * rx[m], -c_hinge_ * gy[i] * ry[m]);
            if (k < n_ind_) {  // damper power w c_θ (θ̇ − θ̇p) θ̇ (θ̇p = 0 on the total rate)
              const double d = node_weight(k) * c_hinge_ * (2.0 * hinge_rate - plastic_rate);
              for (int i = 0; i < 3; ++i) {
                ring_state_entry(r, acc_base_ + 2, nodes[i], 2, -d * gx[i], -d * gy[i]);
                ring_state_entry(r, acc_base_ + 2, nodes[i], 0, -d * rx[i], -d * ry[i]);
              }
            }
            if (in_.hinge_damper_on_elastic_rate) {
              // (Emitted for every hinge, zeros while it does not flow, so that the pattern does
              // not change with every yield, as the flow rows' below.)
              // The elastic-rate damper's moment −c_θ λ̇(|M|, ā) sign M of a flowing hinge, with
              // ∂(λ̇ sign M)/∂M = dl_dm, ∂M/∂p = k_θ g, ∂M/∂θp = −k_θ: ∂F_i/∂p_m = c_θ dl_dm k_θ
              // g_i g_m, ∂F_i/∂θp = −c_θ dl_dm k_θ g_i, ∂F_i/∂ā = c_θ sign M dl_da g_i; and in the
              // power, −w c_θ θ̇ λ̇ sign M.
              const double cm = c_hinge_ * dl_dm * k_theta_, ca = c_hinge_ * sg * dl_da;
              for (int i = 0; i < 3; ++i) {
                for (int m = 0; m < 3; ++m)
                  ring_block(r, nodes[i], nodes[m], 0, cm * gx[i] * gx[m], cm * gx[i] * gy[m], cm * gy[i] * gx[m],
                             cm * gy[i] * gy[m]);
                ring_force_entry(r, nodes[i], hinge_row + 4, -cm * gx[i], -cm * gy[i]);
                ring_force_entry(r, nodes[i], hinge_row + 5, ca * gx[i], ca * gy[i]);
              }
              if (k < n_ind_) {
                const double w = node_weight(k) * hinge_rate;
                for (int i = 0; i < 3; ++i) ring_state_entry(r, acc_base_ + 2, nodes[i], 0, w * cm * gx[i], w * cm * gy[i]);
                jac(acc_base_ + 2, hinge_row + 4, -w * cm);
                jac(acc_base_ + 2, hinge_row + 5, w * ca);
              }
            }
          }
        }
      }
      // Membrane bar k: N = k_m (ℓ − ℓ0) along e.
      double N = k_m_ * (bar_l_[k] - l0_);
      double bar_rate = 0.0;
      if (c_bar_ > 0) {  // Kelvin–Voigt bar damper on ℓ̇ = e · (v_{k+1} − v_k)
        const double rate = bar_damper_rate(k, kp);
        N += c_bar_ * rate;
        if (!half_ || k < n_full_ / 2) tally.damping += c_bar_ * rate * rate;
        bar_rate = rate;
      }
      fx_[k] += N * bar_ex_[k];
      fy_[k] += N * bar_ey_[k];
      fx_[kp] -= N * bar_ex_[k];
      fy_[kp] -= N * bar_ey_[k];
      if (jac_) {
        // F_k = N e = −F_{k+1}: ∂F_k/∂p_{k+1} = k_m e eᵀ + (N/ℓ)(I − e eᵀ),
        // ∂F_k/∂v_{k+1} = c_b e eᵀ (the rotation of e in the damper term left out).
        const double ex = bar_ex_[k], ey = bar_ey_[k], g = N / bar_l_[k];
        const double sxx = k_m_ * ex * ex + g * (1 - ex * ex), sxy = (k_m_ - g) * ex * ey,
                     syy = k_m_ * ey * ey + g * (1 - ey * ey);
        const std::array<int, 2> ends{k, kp};
        for (int i = 0; i < 2; ++i)
          for (int m = 0; m < 2; ++m) {
            const double sign = (i == m) ? -1.0 : 1.0;  // ∂F_k/∂p_k = −S, ∂F_k/∂p_{k+1} = S
            ring_block(r, ends[i], ends[m], 0, sign * sxx, sign * sxy, sign * sxy, sign * syy);
            if (c_bar_ > 0)
              ring_block(r, ends[i], ends[m], 2, sign * c_bar_ * ex * ex, sign * c_bar_ * ex * ey,
                         sign * c_bar_ * ex * ey, sign * c_bar_ * ey * ey);
          }
        if (c_bar_ > 0) {
          // ℓ̇ = e·Δv turns with e: ∂ℓ̇/∂p_{k+1} = −∂ℓ̇/∂p_k = (I − e eᵀ) Δv / ℓ.
          const double dvx = vx_[kp] - vx_[k], dvy = vy_[kp] - vy_[k];
          const double ed = ex * dvx + ey * dvy;
          const double hx = (dvx - ex * ed) / bar_l_[k], hy = (dvy - ey * ed) / bar_l_[k];
          // F_k = c_b ℓ̇ e + …: ∂F_k/∂p_{k+1} += c_b e hᵀ; F_{k+1} = −F_k.
          for (int i = 0; i < 2; ++i)
            for (int m = 0; m < 2; ++m) {
              const double sign = (i == m) ? -1.0 : 1.0;
              ring_block(r, ends[i], ends[m], 0, sign * c_bar_ * ex * hx, sign * c_bar_ * ex * hy,
                         sign * c_bar_ * ey * hx, sign * c_bar_ * ey * hy);
            }
          if (!half_ || k < n_full_ / 2) {  // damper power c_b ℓ̇²
            const double d = 2.0 * c_bar_ * bar_rate;
            ring_state_entry(r, acc_base_ + 2, kp, 2, -d * ex, -d * ey);
            ring_state_entry(r, acc_base_ + 2, k, 2, d * ex, d * ey);
            ring_state_entry(r, acc_base_ + 2, kp, 0, -d * hx, -d * hy);
            ring_state_entry(r, acc_base_ + 2, k, 0, d * hx, d * hy);
          }
        }
      }
    }
    if (record) {
      const int bars = half_ ? n_full_ / 2 : n_full_;
      for (int k = 0; k < bars; ++k) {
        tally.elastic += 0.5 * k_m_ * (bar_l_[k] - l0_) * (bar_l_[k] - l0_);
        tally.max_bar_strain = std::max(tally.max_bar_strain, std::abs(bar_l_[k] - l0_) / l0_);
      }
    }
    if (!reference) ring_node_forces();
    const bool mass_damping = in_.mass_damping_per_s > 0;
    for (int j = 0; j < n_ind_; ++j) {
      const auto o = node_offset(r, j);
      const bool on_axis = half_ && (j == 0 || j == n_ind_ - 1);
      const double w = on_axis ? 0.5 : 1.0;  // node_weight
      phi[o] = on_axis ? 0.0 : y[o + 2];
      phi[o + 1] = y[o + 3];
      phi[o + 2] = on_axis ? 0.0 : w * fx_[j];
      phi[o + 3] = w * fy_[j];
      phi[o + 4] = phi[o + 5] = 0.0;  // the flow rows, while the hinge does not flow
      if (mass_damping) {
        const double c = in_.mass_damping_per_s * w * m_node_;
        if (!on_axis) phi[o + 2] -= c * y[o + 2];
        phi[o + 3] -= c * y[o + 3];
        if (jac_) {
          if (!on_axis) jac(o + 2, o + 2, c);
          jac(o + 3, o + 3, c);
          if (!on_axis) jac(acc_base_ + 2, o + 2, -2.0 * c * y[o + 2]);
          jac(acc_base_ + 2, o + 3, -2.0 * c * y[o + 3]);
        }
        tally.damping += c * ((on_axis ? 0.0 : y[o + 2] * y[o + 2]) + y[o + 3] * y[o + 3]);
      }
      // Viscoplastic hinge (Cowper–Symonds): λ̇ = C ⟨|M|/M_y(ā) − 1⟩^q,
      // θp′ = λ̇ sign M, ā′ = λ̇; the plastic power is |M| λ̇.
      const double M = moment_[j];
      if (flow_y_ && hinge_elastic_[static_cast<std::size_t>(j)]) {  // no flow (above)
        if (record) tally.elastic += w * 0.5 * M * M / k_theta_;
        continue;
      }
      const Flow fl = flow(M, y[o + 5]);
      const double My = fl.yield_moment, over = fl.over, rate = fl.rate;
      if (over > 0.0) {
        phi[o + 4] = M > 0 ? rate : -rate;
        phi[o + 5] = rate;
        tally.plastic_power += w * std::abs(M) * rate;
      }
      if (jac_) {
        // ∂λ̇/∂M = C q over^(q−1) sign M / M_y with ∂M/∂p = k_θ g, ∂M/∂θp = −k_θ;
        // ∂λ̇/∂ā = −C q over^(q−1) |M| H / M_y² while the cap is not reached. Elastic hinges
        // keep these entries as zeros: the pattern then does not change with every yield.
        const double dm = over > 0.0 ? C_vp_ * q_ * std::pow(over, q_ - 1.0) / My : 0.0;
        const double sg = M > 0 ? 1.0 : -1.0;
        const int km = (j + n_full_ - 1) % n_full_, kp = (j + 1) % n_full_;
        const std::array<int, 3> nodes{km, j, kp};
        const double dp = w * sg * (rate + std::abs(M) * dm);  // ∂(w |M| λ̇)/∂M
        for (int i = 0; i < 3; ++i) {
          const double gx = k_theta_ * hinge_gx_[j][i], gy = k_theta_ * hinge_gy_[j][i];
          ring_state_entry(r, o + 4, nodes[i], 0, -dm * gx, -dm * gy);
          ring_state_entry(r, o + 5, nodes[i], 0, -dm * sg * gx, -dm * sg * gy);
          ring_state_entry(r, acc_base_, nodes[i], 0, -dp * gx, -dp * gy);
        }
        jac(o + 4, o + 4, dm * k_theta_);
        jac(o + 5, o + 4, dm * sg * k_theta_);
        jac(acc_base_, o + 4, dp * k_theta_);
        const double da = M0_ + H_ * y[o + 5] < cap_ ? -dm * std::abs(M) * H_ / My : 0.0;
        jac(o + 4, o + 5, -sg * da);
        jac(o + 5, o + 5, -da);
        jac(acc_base_, o + 5, -w * std::abs(M) * da);
      }
      if (record) tally.elastic += w * 0.5 * M * M / k_theta_;
    }
  }
}

}  // namespace ringcrush::hinge
