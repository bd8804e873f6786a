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
  ring_box_.resize(n_rings_);
  seg_box_.resize(static_cast<std::size_t>(n_rings_ * n_ind_));
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
      if (c_hinge_ > 0) {  // Kelvin–Voigt hinge damper on θ̇ = ∂θ/∂p · v
        const double rate = -(ax * vx_[km] + ay * vy_[km]) + (ax + bx) * vx_[k] +
                            (ay + by) * vy_[k] - (bx * vx_[kp] + by * vy_[kp]);
        M += c_hinge_ * rate;
        if (k < n_ind_) damping += node_weight(k) * c_hinge_ * rate * rate;
      }
      fx_[km] += M * ax;
      fy_[km] += M * ay;
      fx_[k] -= M * (ax + bx);
      fy_[k] -= M * (ay + by);
      fx_[kp] += M * bx;
      fy_[kp] += M * by;
      // Membrane bar k: N = k_m (ℓ − ℓ0) along e.
      double N = k_m_ * (bar_l_[k] - l0_);
      if (c_bar_ > 0) {  // Kelvin–Voigt bar damper on ℓ̇ = e · (v_{k+1} − v_k)
        const double rate = bar_ex_[k] * (vx_[kp] - vx_[k]) + bar_ey_[k] * (vy_[kp] - vy_[k]);
        N += c_bar_ * rate;
        if (!half_ || k < n_full_ / 2) damping += c_bar_ * rate * rate;
      }
      fx_[k] += N * bar_ex_[k];
      fy_[k] += N * bar_ey_[k];
      fx_[kp] -= N * bar_ex_[k];
      fy_[kp] -= N * bar_ey_[k];
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
        damping += c * ((on_axis ? 0.0 : y[o + 2] * y[o + 2]) + y[o + 3] * y[o + 3]);
      }
      // Viscoplastic hinge (Cowper–Symonds): λ̇ = C ⟨|M|/M_y(ā) − 1⟩^q,
      // θp′ = λ̇ sign M, ā′ = λ̇; the plastic power is |M| λ̇.
      const double M = moment_[j];
      const double My = std::min(M0_ + H_ * y[o + 5], cap_);
      const double over = std::abs(M) / My - 1.0;
      if (over > 0.0) {
        const double rate = C_vp_ * std::pow(over, q_);
        phi[o + 4] = M > 0 ? rate : -rate;
        phi[o + 5] = rate;
        plastic_power += w * std::abs(M) * rate;
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
      if (pen <= 0.0) continue;
      const double rate = above ? y[o + 3] - vface : vface - y[o + 3];
      const double w = node_weight(j);
      double diss = 0.0;
      const double f = w * contact_force(pen, rate, diss);
      dissipation += w * diss;
      contact_energy += w * 0.5 * k_n_ * pen * pen;
      const double fy = above ? -f : f;  // on the node
      phi[o + 3] += fy;
      if (body >= 0 && !(body == 0 && in_.driven_impactor)) phi[body_offset(body) + 1] -= fy;
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
    if (!(upper == 0 && in_.driven_impactor)) phi[body_offset(upper) + 1] += f;
    if (upper == 0) impactor_force += f;
    if (lower >= 0) phi[body_offset(lower) + 1] -= f;
    else target_force += f;
  }

  // --- Node–segment contact: ring–ring and inner wall (gap = distance − t) ---------------
  // Each slave node meets the closest master segment of the other ring (or of its own ring,
  // skipping the bars within two nodes); the reaction goes to the segment ends with weights
  // (1 − s, s). Both rings of a pair act as slave in turn.
  const int segs = half_ ? n_ind_ - 1 : n_ind_;
  // Broad phase: per ring a bounding box, per segment a box grown by t.
  for (int r = 0; r < n_rings_; ++r) {
    auto& box = ring_box_[r];
    box = {1e300, -1e300, 1e300, -1e300};
    for (int a = 0; a < segs; ++a) {
      const auto oa = node_offset(r, a), ob = node_offset(r, (a + 1) % n_ind_);
      auto& sb = seg_box_[static_cast<std::size_t>(r * n_ind_ + a)];
      sb = {std::min(y[oa], y[ob]) - t_, std::max(y[oa], y[ob]) + t_,
            std::min(y[oa + 1], y[ob + 1]) - t_, std::max(y[oa + 1], y[ob + 1]) + t_};
      box = {std::min(box[0], sb[0]), std::max(box[1], sb[1]), std::min(box[2], sb[2]),
             std::max(box[3], sb[3])};
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
      if (pen <= 0.0) continue;
      const auto oa = node_offset(rm, a), ob = node_offset(rm, b);
      const double s = best_s;
      const double qx = (1 - s) * y[oa] + s * y[ob], qy = (1 - s) * y[oa + 1] + s * y[ob + 1];
      const double nx = (sx - qx) / best, ny = (sy - qy) / best;
      const double vqx = (1 - s) * y[oa + 2] + s * y[ob + 2];
      const double vqy = (1 - s) * y[oa + 3] + s * y[ob + 3];
      const double rate = -((y[os + 2] - vqx) * nx + (y[os + 3] - vqy) * ny);
      const double w = node_weight(j);
      double diss = 0.0;
      const double f = w * contact_force(pen, rate, diss);
      dissipation += w * diss;
      contact_energy += w * 0.5 * k_n_ * pen * pen;
      phi[os + 2] += f * nx;
      phi[os + 3] += f * ny;
      phi[oa + 2] -= (1 - s) * f * nx;
      phi[oa + 3] -= (1 - s) * f * ny;
      phi[ob + 2] -= s * f * nx;
      phi[ob + 3] -= s * f * ny;
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
