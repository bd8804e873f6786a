#include "polygon_chain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "hinge/redwood_hinge_length.hpp"

namespace ringcrush::hinge {

namespace {

constexpr double pi = std::numbers::pi;

double wrap_angle(double a) {
  while (a > pi) a -= 2.0 * pi;
  while (a <= -pi) a += 2.0 * pi;
  return a;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("PolygonChainInput: " + what);
}

}  // namespace

PolygonChain::PolygonChain(const PolygonChainInput& input) : in_(input) {
  require(in_.rings >= 1, "rings must be at least 1");
  require(in_.nodes_per_ring >= 8 && in_.nodes_per_ring % 2 == 0, "nodes_per_ring must be even and ≥ 8");
  require(!in_.half_symmetry || in_.nodes_per_ring % 4 == 0,
          "nodes_per_ring must be a multiple of 4 for the half model");
  require(in_.outer_diameter_m > 0 && in_.wall_thickness_m > 0 &&
              in_.wall_thickness_m < 0.5 * in_.outer_diameter_m && in_.width_m > 0,
          "ring dimensions must be positive with t < D/2");
  require(in_.youngs_modulus_pa > 0 && in_.yield_stress_pa > 0 && in_.density_kg_m3 > 0,
          "E, σ0 and ρ must be positive");
  require(in_.cowper_symonds_d_per_s > 0 && in_.cowper_symonds_q >= 1,
          "Cowper–Symonds D > 0 and q ≥ 1");
  require(in_.joint != PolygonJoint::Plates || in_.plate_thickness_m > 0,
          "plates need a thickness");
  require(in_.driven_impactor || in_.impactor_mass_kg > 0, "impactor mass must be positive");

  half_ = in_.half_symmetry;
  n_full_ = in_.nodes_per_ring;
  n_ind_ = half_ ? n_full_ / 2 + 1 : n_full_;
  n_rings_ = in_.rings;
  t_ = in_.wall_thickness_m;
  R_ = 0.5 * (in_.outer_diameter_m - t_);
  l0_ = 2.0 * R_ * std::sin(pi / n_full_);
  const double I = in_.width_m * t_ * t_ * t_ / 12.0;
  k_theta_ = in_.youngs_modulus_pa * I / l0_;
  k_m_ = in_.youngs_modulus_pa * t_ * in_.width_m / l0_;
  M0_ = in_.yield_stress_pa * t_ * t_ * in_.width_m / 4.0;
  const double lh = in_.redwood_alpha > 0 ? in_.redwood_alpha * t_ : l0_;
  H_ = in_.hardening_modulus_pa * I /
       (in_.redwood_fitted_hardening ? redwood_hinge_length(in_.redwood_alpha, l0_) : lh);
  cap_ = in_.yield_cap_ratio > 0 ? in_.yield_cap_ratio * M0_ : std::numeric_limits<double>::infinity();
  C_vp_ = 2.0 * lh / t_ * in_.cowper_symonds_d_per_s;
  q_ = in_.cowper_symonds_q;
  m_node_ = in_.density_kg_m3 * t_ * in_.width_m * (2.0 * pi * R_ / n_full_);
  k_n_ = in_.contact_stiffness_scale * k_m_;
  chi_ = in_.contact_damping_s_per_m;
  k_tie_ = in_.tie_stiffness_scale * k_m_;
  c_bar_ = in_.membrane_damping_ratio * 2.0 * std::sqrt(k_m_ * m_node_ / 2.0);
  c_hinge_ = in_.hinge_damping_ratio * 2.0 * std::sqrt(k_theta_ * m_node_ * l0_ * l0_ / 2.0);

  const double D = in_.outer_diameter_m;
  const bool plates = in_.joint == PolygonJoint::Plates;
  const double pitch = in_.pitch_m > 0 ? in_.pitch_m : (plates ? D + in_.plate_thickness_m : D);
  ring_centre_.resize(n_rings_);
  for (int r = 0; r < n_rings_; ++r) ring_centre_[r] = -r * pitch;
  target_y_ = ring_centre_.back() - 0.5 * D;

  const double share = half_ ? 0.5 : 1.0;
  bodies_.push_back({0.0, share * in_.impactor_mass_kg, false, 0.0});
  if (plates)
    for (int r = 0; r + 1 < n_rings_; ++r) {
      require(in_.plate_mass_kg > 0, "plates need a mass");
      bodies_.push_back({0.5 * in_.plate_thickness_m, share * in_.plate_mass_kg, false, 0.0});
    }
  n_bodies_ = static_cast<int>(bodies_.size());
  body_base_ = static_cast<std::size_t>(n_rings_ * n_ind_ * 6);
  acc_base_ = body_base_ + 2 * static_cast<std::size_t>(n_bodies_);
  size_ = acc_base_ + 4;

  // Diagonal of F = μ y′ − φ.
  mu_.assign(size_, 1.0);
  for (int r = 0; r < n_rings_; ++r)
    for (int j = 0; j < n_ind_; ++j) {
      const auto o = node_offset(r, j);
      mu_[o + 2] = mu_[o + 3] = node_weight(j) * m_node_;
    }
  for (int b = 0; b < n_bodies_; ++b)
    if (!(b == 0 && in_.driven_impactor)) mu_[body_offset(b) + 1] = bodies_[b].mass;

  // Rigid stack from top to bottom for plate–plate contact: impactor, plates, target.
  for (int b = 0; b + 1 < n_bodies_; ++b) body_body_.push_back({b, b + 1});
  if (in_.fixed_target) body_body_.push_back({n_bodies_ - 1, -1});

  px_.resize(n_full_);
  py_.resize(n_full_);
  vx_.resize(n_full_);
  vy_.resize(n_full_);
  theta_p_.resize(n_full_);
  fx_.resize(n_full_);
  fy_.resize(n_full_);
  moment_.resize(n_full_);
  bar_l_.resize(n_full_);
  bar_nx_.resize(n_full_);
  bar_ny_.resize(n_full_);
  bar_ex_.resize(n_full_);
  bar_ey_.resize(n_full_);
  bar_beta_.resize(n_full_);
  phi_.resize(size_);
  hinge_gx_.resize(n_full_);
  hinge_gy_.resize(n_full_);
  axis_force_row_.assign(size_, 0);
  if (half_)
    for (int r = 0; r < n_rings_; ++r) {
      axis_force_row_[node_offset(r, 0) + 2] = 1;
      axis_force_row_[node_offset(r, n_ind_ - 1) + 2] = 1;
    }
  ring_box_.resize(n_rings_);
  seg_box_.resize(static_cast<std::size_t>(n_rings_ * n_ind_));
  block_box_.resize(static_cast<std::size_t>(n_rings_ * (n_ind_ / seg_block + 1)));
}

std::vector<double> PolygonChain::component_scales() const {
  const double v = std::max(1.0, in_.impactor_velocity_m_s + in_.drive_speed_m_s);
  std::vector<double> s(size_, 1.0);
  for (int g = 0; g < n_rings_ * n_ind_; ++g) {
    const auto o = static_cast<std::size_t>(g) * 6;
    s[o] = s[o + 1] = R_;
    s[o + 2] = s[o + 3] = v;
    s[o + 4] = s[o + 5] = 1.0;
  }
  for (int b = 0; b < n_bodies_; ++b) {
    s[body_offset(b)] = R_;
    s[body_offset(b) + 1] = v;
  }
  const double e0 = std::max(1.0, 0.5 * bodies_[0].mass * v * v);
  for (int k = 0; k < 4; ++k) s[acc_base_ + k] = e0;
  return s;
}

std::vector<PolygonChain::Component> PolygonChain::component_kinds() const {
  std::vector<Component> k(size_, Component::Energy);
  for (int g = 0; g < n_rings_ * n_ind_; ++g) {
    const auto o = static_cast<std::size_t>(g) * 6;
    k[o] = k[o + 1] = Component::Position;
    k[o + 2] = k[o + 3] = Component::Velocity;
    k[o + 4] = k[o + 5] = Component::Plastic;
  }
  for (int b = 0; b < n_bodies_; ++b) {
    k[body_offset(b)] = Component::Position;
    k[body_offset(b) + 1] = Component::Velocity;
  }
  return k;
}

std::vector<double> PolygonChain::initial_state() const {
  std::vector<double> y(size_, 0.0);
  for (int r = 0; r < n_rings_; ++r)
    for (int j = 0; j < n_ind_; ++j) {
      const double a = 2.0 * pi * j / n_full_;
      const auto o = node_offset(r, j);
      y[o] = R_ * std::sin(a);
      if (half_ && (j == 0 || j == n_ind_ - 1)) y[o] = 0.0;
      y[o + 1] = ring_centre_[r] + R_ * std::cos(a);
    }
  const double D = in_.outer_diameter_m;
  y[body_offset(0)] = ring_centre_[0] + 0.5 * D;
  y[body_offset(0) + 1] = in_.driven_impactor ? 0.0 : -in_.impactor_velocity_m_s;
  for (int b = 1; b < n_bodies_; ++b)
    y[body_offset(b)] = 0.5 * (ring_centre_[b - 1] - 0.5 * D + ring_centre_[b] + 0.5 * D);
  return y;
}

double PolygonChain::prescribed_speed(double t) const {
  if (in_.drive_ramp_s <= 0 || t >= in_.drive_ramp_s) return in_.drive_speed_m_s;
  return in_.drive_speed_m_s * 0.5 * (1.0 - std::cos(pi * t / in_.drive_ramp_s));
}

double PolygonChain::body_y(int body, const double* y) const {
  return body < 0 ? target_y_ : y[body_offset(body)];
}

double PolygonChain::body_v(int body, double t, const double* y) const {
  if (body < 0) return 0.0;
  if (body == 0 && in_.driven_impactor) return -prescribed_speed(t);
  return y[body_offset(body) + 1];
}

void PolygonChain::expand_ring(int ring, const double* y) {
  // Full-ring positions from the unknowns; the half model mirrors nodes N/2+1…N−1.
  for (int k = 0; k < n_full_; ++k) {
    const bool mirrored = half_ && k >= n_ind_;
    const int j = mirrored ? n_full_ - k : k;
    const auto o = node_offset(ring, j);
    px_[k] = mirrored ? -y[o] : y[o];
    py_[k] = y[o + 1];
    vx_[k] = mirrored ? -y[o + 2] : y[o + 2];
    vy_[k] = y[o + 3];
    theta_p_[k] = y[o + 4];
  }
}

// Hunt–Crossley-type normal force f = k p (1 + χ ṗ) ≥ 0 on penetration p; returns f and the
// rate of energy lost to the damping part, (f − k p) ṗ (THEORY §4.3 "Contact").
double PolygonChain::contact_force(double penetration, double rate, double& dissipation) const {
  double f = k_n_ * penetration * (1.0 + chi_ * rate);
  if (f < 0.0) f = 0.0;
  dissipation += (f - k_n_ * penetration) * rate;
  return f;
}

// Partials of the contact dissipation rate (f − k p) ṗ: k p χ ṗ² while f > 0, −k p ṗ where the
// clip at zero force acts.
void PolygonChain::diss_partials(double penetration, double rate, double& d_pen, double& d_rate) const {
  if (1.0 + chi_ * rate > 0.0) {
    d_pen = k_n_ * chi_ * rate * rate;
    d_rate = 2.0 * k_n_ * penetration * chi_ * rate;
  } else {
    d_pen = -k_n_ * rate;
    d_rate = -k_n_ * penetration;
  }
}

void PolygonChain::evaluate(double t, const double* y, double* phi, bool record) {
  std::fill(phi, phi + size_, 0.0);
  const double turn0 = 2.0 * pi / n_full_;
  double plastic_power = 0.0, dissipation = 0.0, damping = 0.0, elastic = 0.0, contact_energy = 0.0;
  const bool plates = in_.joint == PolygonJoint::Plates;
  if (record) {
    pairs_.clear();
    body_contacts_.clear();
  }

  // --- Ring internal forces: bending hinges and membrane bars (THEORY §4.3) -------------
  for (int r = 0; r < n_rings_; ++r) {
    expand_ring(r, y);
    for (int k = 0; k < n_full_; ++k) {
      const int k1 = (k + 1) % n_full_;
      const double bx = px_[k1] - px_[k], by = py_[k1] - py_[k];
      const double l = std::sqrt(bx * bx + by * by);
      bar_l_[k] = l;
      bar_ex_[k] = bx / l;
      bar_ey_[k] = by / l;
      bar_nx_[k] = -bar_ey_[k];
      bar_ny_[k] = bar_ex_[k];
      bar_beta_[k] = std::atan2(by, bx);
      fx_[k] = fy_[k] = 0.0;
    }
    for (int k = 0; k < n_full_; ++k) {
      const int km = (k + n_full_ - 1) % n_full_, kp = (k + 1) % n_full_;
      // Hinge k: turning τ = β_{k−1} − β_k (clockwise node order), rotation θ = τ − 2π/N,
      // moment M = k_θ (θ − θp); forces −M ∂θ/∂p with ∂β/∂p_end = n/ℓ.
      const double theta = wrap_angle(bar_beta_[km] - bar_beta_[k]) - turn0;
      const double ax = bar_nx_[km] / bar_l_[km], ay = bar_ny_[km] / bar_l_[km];
      const double bx = bar_nx_[k] / bar_l_[k], by = bar_ny_[k] / bar_l_[k];
      moment_[k] = k_theta_ * (theta - theta_p_[k]);
      double M = moment_[k];
      double hinge_rate = 0.0;
      if (c_hinge_ > 0) {  // Kelvin–Voigt hinge damper on θ̇ = ∂θ/∂p · v
        const double rate = -(ax * vx_[km] + ay * vy_[km]) + (ax + bx) * vx_[k] +
                            (ay + by) * vy_[k] - (bx * vx_[kp] + by * vy_[kp]);
        M += c_hinge_ * rate;
        if (k < n_ind_) damping += node_weight(k) * c_hinge_ * rate * rate;
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
          if (k < n_ind_) {  // damper power w c_θ θ̇²
            const double d = 2.0 * node_weight(k) * c_hinge_ * hinge_rate;
            for (int i = 0; i < 3; ++i) {
              ring_state_entry(r, acc_base_ + 2, nodes[i], 2, -d * gx[i], -d * gy[i]);
              ring_state_entry(r, acc_base_ + 2, nodes[i], 0, -d * rx[i], -d * ry[i]);
            }
          }
        }
      }
      // Membrane bar k: N = k_m (ℓ − ℓ0) along e.
      double N = k_m_ * (bar_l_[k] - l0_);
      double bar_rate = 0.0;
      if (c_bar_ > 0) {  // Kelvin–Voigt bar damper on ℓ̇ = e · (v_{k+1} − v_k)
        const double rate = bar_ex_[k] * (vx_[kp] - vx_[k]) + bar_ey_[k] * (vy_[kp] - vy_[k]);
        N += c_bar_ * rate;
        if (!half_ || k < n_full_ / 2) damping += c_bar_ * rate * rate;
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
      for (int k = 0; k < bars; ++k) elastic += 0.5 * k_m_ * (bar_l_[k] - l0_) * (bar_l_[k] - l0_);
    }
    for (int j = 0; j < n_ind_; ++j) {
      const auto o = node_offset(r, j);
      const double w = node_weight(j);
      const bool on_axis = half_ && (j == 0 || j == n_ind_ - 1);
      phi[o] = on_axis ? 0.0 : y[o + 2];
      phi[o + 1] = y[o + 3];
      phi[o + 2] = on_axis ? 0.0 : w * fx_[j];
      phi[o + 3] = w * fy_[j];
      if (in_.mass_damping_per_s > 0) {
        const double c = in_.mass_damping_per_s * w * m_node_;
        if (!on_axis) phi[o + 2] -= c * y[o + 2];
        phi[o + 3] -= c * y[o + 3];
        if (jac_) {
          if (!on_axis) jac(o + 2, o + 2, c);
          jac(o + 3, o + 3, c);
          if (!on_axis) jac(acc_base_ + 2, o + 2, -2.0 * c * y[o + 2]);
          jac(acc_base_ + 2, o + 3, -2.0 * c * y[o + 3]);
        }
        damping += c * ((on_axis ? 0.0 : y[o + 2] * y[o + 2]) + y[o + 3] * y[o + 3]);
      }
      // Viscoplastic hinge (Cowper–Symonds): λ̇ = C ⟨|M|/M_y(ā) − 1⟩^q,
      // θp′ = λ̇ sign M, ā′ = λ̇; the plastic power is |M| λ̇.
      const double M = moment_[j];
      const double My = std::min(M0_ + H_ * y[o + 5], cap_);
      const double over = std::abs(M) / My - 1.0;
      const double rate = over > 0.0 ? C_vp_ * std::pow(over, q_) : 0.0;
      if (over > 0.0) {
        phi[o + 4] = M > 0 ? rate : -rate;
        phi[o + 5] = rate;
        plastic_power += w * std::abs(M) * rate;
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
      if (record) elastic += w * 0.5 * M * M / k_theta_;
    }
  }

  // --- Ties: welded point B(r) — A(r+1), c = p_B − p_A − (0, t), energy ½ w k |c|² ------
  if (in_.joint == PolygonJoint::Welded) {
    if (record) tie_pairs_.clear();
    const int jb = half_ ? n_ind_ - 1 : n_full_ / 2;
    const double w = half_ ? 0.5 : 1.0;
    for (int r = 0; r + 1 < n_rings_; ++r) {
      const auto ob = node_offset(r, jb), oa = node_offset(r + 1, 0);
      const double cx = y[ob] - y[oa], cy = y[ob + 1] - y[oa + 1] - t_;
      const double fx = w * k_tie_ * cx, fy = w * k_tie_ * cy;
      if (!half_) {
        phi[ob + 2] -= fx;
        phi[oa + 2] += fx;
      }
      phi[ob + 3] -= fy;
      phi[oa + 3] += fy;
      if (jac_) {  // −∂φ/∂y of the tie spring, both components (x only in the full model)
        const double kk = w * k_tie_;
        for (int c = half_ ? 1 : 0; c < 2; ++c) {
          const auto rb = ob + 2 + static_cast<std::size_t>(c), ra = oa + 2 + static_cast<std::size_t>(c);
          const auto cb = ob + static_cast<std::size_t>(c), ca = oa + static_cast<std::size_t>(c);
          jac(rb, cb, kk);
          jac(rb, ca, -kk);
          jac(ra, cb, -kk);
          jac(ra, ca, kk);
        }
      }
      if (record) {
        elastic += 0.5 * w * k_tie_ * (cx * cx + cy * cy);
        tie_pairs_.push_back({r * n_ind_ + jb, (r + 1) * n_ind_});
      }
    }
  }

  // --- Node–plate contact (gap = distance of the node to the face − t/2) ----------------
  double impactor_force = 0.0, target_force = 0.0;
  auto plate_contact = [&](int r, int body, bool above) {
    const double h = body < 0 ? 0.0 : bodies_[body].half_thickness;
    const double face = body_y(body, y) + (above ? -h : h);
    const double vface = body_v(body, t, y);
    for (int j = 0; j < n_ind_; ++j) {
      const auto o = node_offset(r, j);
      const double pen = above ? y[o + 1] + 0.5 * t_ - face : face - (y[o + 1] - 0.5 * t_);
      if (pen <= -t_) continue;
      if (record) body_contacts_.push_back({r * n_ind_ + j, body});
      // Near pairs (within t) keep their Jacobian entries, as zeros while apart, so that the
      // sparse pattern, and the direct solver's symbolic analysis, survive contact chatter.
      if (pen <= 0.0 && !jac_) continue;
      const bool touching = pen > 0.0;
      const double rate = above ? y[o + 3] - vface : vface - y[o + 3];
      const double w = node_weight(j);
      double diss = 0.0;
      const double f = touching ? w * contact_force(pen, rate, diss) : 0.0;
      if (touching) {
        dissipation += w * diss;
        contact_energy += w * 0.5 * k_n_ * pen * pen;
      }
      const double fy = above ? -f : f;  // on the node
      phi[o + 3] += fy;
      const bool body_free = body >= 0 && !(body == 0 && in_.driven_impactor);
      if (body_free) phi[body_offset(body) + 1] -= fy;
      if (jac_) {  // contact dissipation rate w (f − k p) ṗ, s = ±1 as below
        const double sg = above ? 1.0 : -1.0;
        double dp = 0.0, dr = 0.0;
        if (touching) diss_partials(pen, rate, dp, dr);
        jac(acc_base_ + 1, o + 1, -w * sg * dp);
        jac(acc_base_ + 1, o + 3, -w * sg * dr);
        if (body >= 0) jac(acc_base_ + 1, body_offset(body), w * sg * dp);
        if (body_free) jac(acc_base_ + 1, body_offset(body) + 1, w * sg * dr);
      }
      if (jac_) {
        // p = s (y_node − y_body) + const, ṗ = s (v_node − v_body), s = ±1 (above/below);
        // node force −s f, body force s f.
        const double fp = f > 0.0 ? w * k_n_ * (1.0 + chi_ * rate) : 0.0;
        const double fr = f > 0.0 ? w * k_n_ * pen * chi_ : 0.0;
        if (body == 0 && in_.driven_impactor) {  // external power f · V of the driven plate
          const double v = prescribed_speed(t);
          jac(acc_base_ + 3, o + 1, -v * fp);
          jac(acc_base_ + 3, o + 3, -v * fr);
          jac(acc_base_ + 3, body_offset(0), v * fp);
        }
        jac(o + 3, o + 1, fp);
        jac(o + 3, o + 3, fr);
        if (body >= 0) {
          const auto ob = body_offset(body);
          jac(o + 3, ob, -fp);
          if (body_free) jac(o + 3, ob + 1, -fr);
          if (body_free) {
            jac(ob + 1, o + 1, -fp);
            jac(ob + 1, o + 3, -fr);
            jac(ob + 1, ob, fp);
            jac(ob + 1, ob + 1, fr);
          }
        }
      }
      if (body == 0) impactor_force -= fy;
      if (body < 0) target_force += f;
    }
  };
  for (int r = 0; r < n_rings_; ++r) {
    const int above = r == 0 ? 0 : (plates ? r : -2);
    const int below = r == n_rings_ - 1 ? (in_.fixed_target ? -1 : -2) : (plates ? r + 1 : -2);
    if (above != -2) plate_contact(r, above, true);
    if (below != -2) plate_contact(r, below, false);
  }

  // --- Plate–plate contact (backstop once the rings between are flat) --------------------
  for (const auto& bb : body_body_) {
    const int upper = bb[0], lower = bb[1];
    const double hu = bodies_[upper].half_thickness;
    const double hl = lower < 0 ? 0.0 : bodies_[lower].half_thickness;
    const int between = plates ? 1 : n_rings_;
    const double pen = (body_y(lower, y) + hl) - (body_y(upper, y) - hu) + between * t_;
    if (pen <= 0.0) continue;
    const double rate = body_v(lower, t, y) - body_v(upper, t, y);
    double diss = 0.0;
    const double f = contact_force(pen, rate, diss);
    dissipation += diss;
    contact_energy += 0.5 * k_n_ * pen * pen;
    const bool upper_free = !(upper == 0 && in_.driven_impactor);
    if (upper_free) phi[body_offset(upper) + 1] += f;
    if (upper == 0) impactor_force += f;
    if (lower >= 0) phi[body_offset(lower) + 1] -= f;
    else target_force += f;
    if (jac_) {  // dissipation (f − k p) ṗ with p, ṗ rising with the lower body
      double dp = 0.0, dr = 0.0;
      diss_partials(pen, rate, dp, dr);
      jac(acc_base_ + 1, body_offset(upper), dp);
      if (upper_free) jac(acc_base_ + 1, body_offset(upper) + 1, dr);
      if (lower >= 0) {
        jac(acc_base_ + 1, body_offset(lower), -dp);
        jac(acc_base_ + 1, body_offset(lower) + 1, -dr);
      }
    }
    if (jac_ && f > 0.0) {
      // ∂f/∂y_lower = −∂f/∂y_upper = k(1 + χ ṗ); ∂f/∂v_lower = −∂f/∂v_upper = k p χ.
      const double fp = k_n_ * (1.0 + chi_ * rate), fr = k_n_ * pen * chi_;
      const auto ou = body_offset(upper);
      if (upper == 0 && in_.driven_impactor) {
        const double v = prescribed_speed(t);
        jac(acc_base_ + 3, ou, v * fp);
        if (lower >= 0) jac(acc_base_ + 3, body_offset(lower), -v * fp);
        if (lower >= 0) jac(acc_base_ + 3, body_offset(lower) + 1, -v * fr);
      }
      auto row = [&](std::size_t rrow, double sign) {
        jac(rrow, ou, sign * fp);
        if (upper_free) jac(rrow, ou + 1, sign * fr);
        if (lower >= 0) {
          jac(rrow, body_offset(lower), -sign * fp);
          jac(rrow, body_offset(lower) + 1, -sign * fr);
        }
      };
      if (upper_free) row(ou + 1, 1.0);    // −∂(+f)/∂y
      if (lower >= 0) row(body_offset(lower) + 1, -1.0);
    }
  }

  // --- Node–segment contact: ring–ring and inner wall (gap = distance − t) ---------------
  // Each slave node meets the closest master segment of the other ring (or of its own ring,
  // skipping the bars within two nodes); the reaction goes to the segment ends with weights
  // (1 − s, s). Both rings of a pair act as slave in turn.
  const int segs = half_ ? n_ind_ - 1 : n_ind_;
  // Broad phase: per ring a bounding box, per block of `seg_block` consecutive segments a
  // box, per segment a box grown by t. A node tests a block's segments only inside the
  // block's box (the segments are still visited in order: the same closest segment).
  const int blocks = (segs + seg_block - 1) / seg_block;
  auto unite = [](std::array<double, 4>& into, const std::array<double, 4>& b) {
    into = {std::min(into[0], b[0]), std::max(into[1], b[1]), std::min(into[2], b[2]),
            std::max(into[3], b[3])};
  };
  for (int r = 0; r < n_rings_; ++r) {
    auto& box = ring_box_[r];
    box = {1e300, -1e300, 1e300, -1e300};
    for (int blk = 0; blk < blocks; ++blk) {
      auto& bb = block_box_[static_cast<std::size_t>(r * blocks + blk)];
      bb = {1e300, -1e300, 1e300, -1e300};
      for (int a = blk * seg_block; a < std::min(segs, (blk + 1) * seg_block); ++a) {
        const auto oa = node_offset(r, a), ob = node_offset(r, (a + 1) % n_ind_);
        auto& sb = seg_box_[static_cast<std::size_t>(r * n_ind_ + a)];
        sb = {std::min(y[oa], y[ob]) - t_, std::max(y[oa], y[ob]) + t_,
              std::min(y[oa + 1], y[ob + 1]) - t_, std::max(y[oa + 1], y[ob + 1]) + t_};
        unite(bb, sb);
      }
      unite(box, bb);
    }
  }
  auto node_segment = [&](int rs, int rm, bool self) {
    const auto& box = ring_box_[rm];
    for (int j = 0; j < n_ind_; ++j) {
      const auto os = node_offset(rs, j);
      const double sx = y[os], sy = y[os + 1];
      if (sx < box[0] || sx > box[1] || sy < box[2] || sy > box[3]) continue;
      double best = t_ * 2.0;
      int best_a = -1;
      double best_s = 0.0;
      for (int a = 0; a < segs; ++a) {
        if (a % seg_block == 0) {
          const auto& bb = block_box_[static_cast<std::size_t>(rm * blocks + a / seg_block)];
          if (sx < bb[0] || sx > bb[1] || sy < bb[2] || sy > bb[3]) {
            a += seg_block - 1;
            continue;
          }
        }
        const auto& sb = seg_box_[static_cast<std::size_t>(rm * n_ind_ + a)];
        if (sx < sb[0] || sx > sb[1] || sy < sb[2] || sy > sb[3]) continue;
        const int b = (a + 1) % n_ind_;
        if (self) {
          const int da = std::abs(j - a), db = std::abs(j - b);
          const int dista = half_ ? da : std::min(da, n_ind_ - da);
          const int distb = half_ ? db : std::min(db, n_ind_ - db);
          if (dista <= 2 || distb <= 2) continue;
        }
        const auto oa = node_offset(rm, a), ob = node_offset(rm, b);
        const double ax = y[oa], ay = y[oa + 1], bx = y[ob], by = y[ob + 1];
        const double ex = bx - ax, ey = by - ay;
        const double ll = ex * ex + ey * ey;
        double s = ((sx - ax) * ex + (sy - ay) * ey) / ll;
        s = std::clamp(s, 0.0, 1.0);
        const double qx = ax + s * ex, qy = ay + s * ey;
        const double d = std::sqrt((sx - qx) * (sx - qx) + (sy - qy) * (sy - qy));
        if (d < best) {
          best = d;
          best_a = a;
          best_s = s;
        }
      }
      if (best_a < 0) continue;
      const int a = best_a, b = (a + 1) % n_ind_;
      if (record) pairs_.push_back({rs * n_ind_ + j, rm * n_ind_ + a, rm * n_ind_ + b});
      const double pen = t_ - best;
      if (pen <= 0.0 && !jac_) continue;  // near pairs keep their (zero) Jacobian entries
      const bool touching = pen > 0.0;
      const auto oa = node_offset(rm, a), ob = node_offset(rm, b);
      const double s = best_s;
      const double qx = (1 - s) * y[oa] + s * y[ob], qy = (1 - s) * y[oa + 1] + s * y[ob + 1];
      const double nx = (sx - qx) / best, ny = (sy - qy) / best;
      const double vqx = (1 - s) * y[oa + 2] + s * y[ob + 2];
      const double vqy = (1 - s) * y[oa + 3] + s * y[ob + 3];
      const double rate = -((y[os + 2] - vqx) * nx + (y[os + 3] - vqy) * ny);
      const double w = node_weight(j);
      double diss = 0.0;
      const double f = touching ? w * contact_force(pen, rate, diss) : 0.0;
      if (touching) {
        dissipation += w * diss;
        contact_energy += w * 0.5 * k_n_ * pen * pen;
      }
      phi[os + 2] += f * nx;
      phi[os + 3] += f * ny;
      phi[oa + 2] -= (1 - s) * f * nx;
      phi[oa + 3] -= (1 - s) * f * ny;
      phi[ob + 2] -= s * f * nx;
      phi[ob + 3] -= s * f * ny;
      if (jac_) {  // dissipation w (f − k p) ṗ; ∂p/∂p_m = ∂ṗ/∂v_m = −c_m n (c as below)
        double dp = 0.0, dr = 0.0;
        if (touching) diss_partials(pen, rate, dp, dr);
        const std::array<std::size_t, 3> off{os, oa, ob};
        const std::array<double, 3> cw{1.0, -(1.0 - s), -s};
        for (int i = 0; i < 3; ++i) {
          jac(acc_base_ + 1, off[i], w * cw[i] * nx * dp);
          jac(acc_base_ + 1, off[i] + 1, w * cw[i] * ny * dp);
          jac(acc_base_ + 1, off[i] + 2, w * cw[i] * nx * dr);
          jac(acc_base_ + 1, off[i] + 3, w * cw[i] * ny * dr);
        }
      }
      if (jac_) {
        // Forces (f n, −(1 − s) f n, −s f n) on (slave, a, b) with the gap d = |p − q| and
        // ṗ = −n·(v − v_q): ∂F_i/∂p_m = −c_i c_m f_p n nᵀ, ∂F_i/∂v_m = −c_i c_m f_v n nᵀ,
        // c = (1, −(1 − s), −s). s and n are held: their rates (the slide along the segment)
        // move the force sideways, a small term next to the normal stiffness.
        const double fp = f > 0.0 ? w * k_n_ * (1.0 + chi_ * rate) : 0.0;
        const double fr = f > 0.0 ? w * k_n_ * pen * chi_ : 0.0;
        const std::array<std::size_t, 3> off{os, oa, ob};
        const std::array<double, 3> cw{1.0, -(1.0 - s), -s};
        const double nn[2][2] = {{nx * nx, nx * ny}, {ny * nx, ny * ny}};
        for (int i = 0; i < 3; ++i)
          for (int m = 0; m < 3; ++m) {
            const double c = cw[i] * cw[m];
            for (int a1 = 0; a1 < 2; ++a1)
              for (int b1 = 0; b1 < 2; ++b1) {
                jac(off[i] + 2 + static_cast<std::size_t>(a1), off[m] + static_cast<std::size_t>(b1), c * fp * nn[a1][b1]);
                jac(off[i] + 2 + static_cast<std::size_t>(a1), off[m] + 2 + static_cast<std::size_t>(b1),
                    c * fr * nn[a1][b1]);
              }
          }
      }
    }
  };
  for (int r = 0; r < n_rings_; ++r) {
    node_segment(r, r, true);
    if (!plates && r + 1 < n_rings_) {
      node_segment(r, r + 1, false);
      node_segment(r + 1, r, false);
    }
  }
  // The symmetry plane carries no x force on axis nodes.
  if (half_)
    for (int r = 0; r < n_rings_; ++r) {
      phi[node_offset(r, 0) + 2] = 0.0;
      phi[node_offset(r, n_ind_ - 1) + 2] = 0.0;
    }

  // --- Bodies ---------------------------------------------------------------------------
  for (int b = 0; b < n_bodies_; ++b) {
    const auto o = body_offset(b);
    if (b == 0 && in_.driven_impactor) {
      phi[o] = -prescribed_speed(t);
      phi[o + 1] = 0.0;
    } else {
      phi[o] = y[o + 1];
    }
  }
  phi[acc_base_] = plastic_power;
  phi[acc_base_ + 1] = dissipation;
  phi[acc_base_ + 2] = damping;
  phi[acc_base_ + 3] = in_.driven_impactor ? impactor_force * prescribed_speed(t) : 0.0;

  last_impactor_force_ = impactor_force;
  last_target_force_ = target_force;
  if (record) last_contact_energy_ = contact_energy;
  last_elastic_ = elastic;
}

void PolygonChain::rhs(double t, const double* y, double* dydt) {
  evaluate(t, y, dydt, false);
  for (std::size_t i = 0; i < size_; ++i) dydt[i] /= mu_[i];
}

void PolygonChain::residual(double t, const double* y, const double* yp, double* r) {
  evaluate(t, y, r, false);
  for (std::size_t i = 0; i < size_; ++i) r[i] = mu_[i] * yp[i] - r[i];
}

void PolygonChain::generalised_forces(double t, const double* y, double* phi) {
  evaluate(t, y, phi, false);
}

void PolygonChain::jac(std::size_t row, std::size_t col, double value) {
  if (axis_force_row_[row]) return;  // the symmetry plane: no x force on axis nodes
  jac_->push_back({static_cast<int>(row), static_cast<int>(col), value});
}

// Full-ring node m → (independent node, sign of its x): the half model mirrors m ≥ N/2 + 1.
std::pair<int, double> PolygonChain::independent(int m) const {
  if (half_ && m >= n_ind_) return {n_full_ - m, -1.0};
  return {m, 1.0};
}

void PolygonChain::ring_block(int ring, int i, int m, int slot, double dxx, double dxy, double dyx,
                              double dyy) {
  if (i >= n_ind_) return;  // forces on mirrored nodes are not equations of the half model
  const double w = node_weight(i);
  const auto row = node_offset(ring, i) + 2;
  const auto [j, sx] = independent(m);
  const auto col = node_offset(ring, j) + static_cast<std::size_t>(slot);
  jac(row, col, -w * sx * dxx);
  jac(row, col + 1, -w * dxy);
  jac(row + 1, col, -w * sx * dyx);
  jac(row + 1, col + 1, -w * dyy);
}

void PolygonChain::ring_force_entry(int ring, int i, std::size_t col, double dfx, double dfy) {
  if (i >= n_ind_) return;
  const double w = node_weight(i);
  const auto row = node_offset(ring, i) + 2;
  jac(row, col, -w * dfx);
  jac(row + 1, col, -w * dfy);
}

void PolygonChain::ring_state_entry(int ring, std::size_t row, int m, int slot, double jx, double jy) {
  const auto [j, sx] = independent(m);
  const auto col = node_offset(ring, j) + static_cast<std::size_t>(slot);
  jac(row, col, sx * jx);
  jac(row, col + 1, jy);
}

void PolygonChain::analytic_jacobian(double t, double cj, const double* y, std::vector<Triplet>& out) {
  out.clear();
  jac_ = &out;
  try {
    evaluate(t, y, phi_.data(), true);
  } catch (...) {
    jac_ = nullptr;
    throw;
  }
  jac_ = nullptr;
  // Kinematic rows x′ = v (none for the x of axis nodes, held at 0) and bodies' y′ = v.
  for (int r = 0; r < n_rings_; ++r)
    for (int j = 0; j < n_ind_; ++j) {
      const auto o = node_offset(r, j);
      if (!(half_ && (j == 0 || j == n_ind_ - 1)))
        out.push_back({static_cast<int>(o), static_cast<int>(o + 2), -1.0});
      out.push_back({static_cast<int>(o + 1), static_cast<int>(o + 3), -1.0});
    }
  for (int b = 0; b < n_bodies_; ++b)
    if (!(b == 0 && in_.driven_impactor)) {
      const auto o = body_offset(b);
      out.push_back({static_cast<int>(o), static_cast<int>(o + 1), -1.0});
    }
  for (std::size_t i = 0; i < size_; ++i)
    out.push_back({static_cast<int>(i), static_cast<int>(i), cj * mu_[i]});
}

void PolygonChain::sparse_jacobian(double t, double cj, const double* y, const double* yp,
                                   const double* r0, std::vector<Triplet>& out) {
  out.clear();
  const int n_nodes = n_rings_ * n_ind_;
  const int n_ent = n_nodes + n_bodies_;
  // Contact graph at the current state (pairs within one wall thickness of touching).
  base_r_.resize(size_);
  evaluate(t, y, base_r_.data(), true);
  std::vector<std::vector<int>> adj(n_ent);
  auto link = [&](int a, int b) {
    adj[a].push_back(b);
    adj[b].push_back(a);
  };
  for (int e = 0; e < n_ent; ++e) adj[e].push_back(e);
  for (int r = 0; r < n_rings_; ++r)
    for (int j = 0; j < n_ind_; ++j)
      for (int d = 1; d <= 2; ++d) {
        int k = j + d;
        if (half_) {
          if (k >= n_ind_) continue;
        } else {
          k %= n_ind_;
        }
        link(r * n_ind_ + j, r * n_ind_ + k);
      }
  if (in_.joint == PolygonJoint::Welded)
    for (const auto& tp : tie_pairs_) link(tp[0], tp[1]);
  for (const auto& p : pairs_) {
    link(p.slave, p.master_a);
    link(p.slave, p.master_b);
  }
  for (const auto& bc : body_contacts_)
    if (bc.body >= 0) link(bc.node, n_nodes + bc.body);
  for (const auto& bb : body_body_)
    if (bb[1] >= 0) link(n_nodes + bb[0], n_nodes + bb[1]);
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  // Distance-2 greedy colouring: entities of one colour touch disjoint residual rows.
  std::vector<int> colour(n_ent, -1);
  std::vector<int> mark;
  int n_colours = 0;
  for (int e = 0; e < n_ent; ++e) {
    mark.assign(static_cast<std::size_t>(n_colours) + 1, 0);
    for (int rrow : adj[e])
      for (int f : adj[rrow])
        if (colour[f] >= 0) mark[colour[f]] = 1;
    int c = 0;
    while (mark[c]) ++c;
    colour[e] = c;
    n_colours = std::max(n_colours, c + 1);
  }
  std::vector<std::vector<int>> groups(n_colours);
  for (int e = 0; e < n_ent; ++e) groups[colour[e]].push_back(e);

  auto ent_offset = [&](int e) {
    return e < n_nodes ? static_cast<std::size_t>(e) * 6 : body_offset(e - n_nodes);
  };
  auto ent_slots = [&](int e) { return e < n_nodes ? 6 : 2; };
  pert_y_.assign(y, y + size_);
  pert_r_.resize(size_);
  const double sqrt_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  const auto scales = component_scales();
  std::vector<double> h(size_);
  for (int slot = 0; slot < 6; ++slot)
    for (const auto& group : groups) {
      bool any = false;
      for (int e : group)
        if (slot < ent_slots(e)) {
          const auto col = ent_offset(e) + slot;
          h[col] = sqrt_eps * std::max(std::abs(y[col]), 1e-3 * scales[col]);
          pert_y_[col] = y[col] + h[col];
          h[col] = pert_y_[col] - y[col];
          any = true;
        }
      if (!any) continue;
      residual(t, pert_y_.data(), yp, pert_r_.data());
      for (int e : group) {
        if (slot >= ent_slots(e)) continue;
        const auto col = ent_offset(e) + slot;
        for (int re : adj[e]) {
          const auto ro = ent_offset(re);
          for (int rs = 0; rs < ent_slots(re); ++rs) {
            const auto row = ro + rs;
            const double v = (pert_r_[row] - r0[row]) / h[col];
            if (v != 0.0) out.push_back({static_cast<int>(row), static_cast<int>(col), v});
          }
        }
        pert_y_[col] = y[col];
      }
    }
  for (std::size_t i = 0; i < size_; ++i) out.push_back({static_cast<int>(i), static_cast<int>(i), cj * mu_[i]});
}

PolygonShape PolygonChain::shape(const double* y) const {
  PolygonShape s;
  s.nodes.resize(n_rings_);
  s.turning.resize(n_rings_);
  s.plastic_rotation.resize(n_rings_);
  for (int r = 0; r < n_rings_; ++r) {
    auto& nodes = s.nodes[r];
    nodes.resize(n_full_);
    s.plastic_rotation[r].resize(n_full_);
    for (int k = 0; k < n_full_; ++k) {
      const bool mirrored = half_ && k >= n_ind_;
      const int j = mirrored ? n_full_ - k : k;
      const auto o = node_offset(r, j);
      nodes[k] = {mirrored ? -y[o] : y[o], y[o + 1]};
      s.plastic_rotation[r][k] = y[o + 5];
    }
    auto& turning = s.turning[r];
    turning.resize(n_full_);
    for (int k = 0; k < n_full_; ++k) {
      const int km = (k + n_full_ - 1) % n_full_, kp = (k + 1) % n_full_;
      const double b0 = std::atan2(nodes[k][1] - nodes[km][1], nodes[k][0] - nodes[km][0]);
      const double b1 = std::atan2(nodes[kp][1] - nodes[k][1], nodes[kp][0] - nodes[k][0]);
      turning[k] = wrap_angle(b0 - b1);
    }
  }
  s.body_faces.push_back(y[body_offset(0)]);
  for (int b = 1; b < n_bodies_; ++b) s.body_faces.push_back(y[body_offset(b)]);
  if (in_.fixed_target) s.body_faces.push_back(target_y_);
  return s;
}

PolygonEnergies PolygonChain::energies(double t, const double* y) {
  evaluate(t, y, phi_.data(), true);
  PolygonEnergies e;
  for (int r = 0; r < n_rings_; ++r)
    for (int j = 0; j < n_ind_; ++j) {
      const auto o = node_offset(r, j);
      e.kinetic += 0.5 * mu_[o + 2] * (y[o + 2] * y[o + 2] + y[o + 3] * y[o + 3]);
    }
  for (int b = 0; b < n_bodies_; ++b)
    if (!(b == 0 && in_.driven_impactor)) {
      const double v = y[body_offset(b) + 1];
      e.kinetic += 0.5 * bodies_[b].mass * v * v;
    }
  e.elastic = last_elastic_;
  e.contact = last_contact_energy_;
  e.plastic = y[acc_base_];
  e.contact_damping = y[acc_base_ + 1];
  e.damping = y[acc_base_ + 2];
  e.external = y[acc_base_ + 3];
  return e;
}

double PolygonChain::impactor_force(double t, const double* y) {
  evaluate(t, y, phi_.data(), false);
  return structure_factor() * last_impactor_force_;
}

double PolygonChain::target_force(double t, const double* y) {
  evaluate(t, y, phi_.data(), false);
  return structure_factor() * last_target_force_;
}

double PolygonChain::impactor_position(double, const double* y) const {
  return ring_centre_[0] + 0.5 * in_.outer_diameter_m - y[body_offset(0)];
}

double PolygonChain::impactor_velocity(double t, const double* y) const {
  return -body_v(0, t, y);
}

}  // namespace ringcrush::hinge
