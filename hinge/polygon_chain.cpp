#include "polygon_chain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "hinge/redwood_hinge_length.hpp"
#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

namespace {

constexpr double pi = std::numbers::pi;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("PolygonChainInput: " + what);
}

}  // namespace

double PolygonChain::wrap_angle(double a) {
  while (a > pi) a -= 2.0 * pi;
  while (a <= -pi) a += 2.0 * pi;
  return a;
}

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
  const auto positive_scale = [](double s) { return s > 0 && std::isfinite(s); };
  require(positive_scale(in_.membrane_stiffness_scale), "membrane_stiffness_scale must be positive and finite");
  require(positive_scale(in_.contact_stiffness_scale), "contact_stiffness_scale must be positive and finite");
  require(positive_scale(in_.tie_stiffness_scale), "tie_stiffness_scale must be positive and finite");

  half_ = in_.half_symmetry;
  n_full_ = in_.nodes_per_ring;
  n_ind_ = half_ ? n_full_ / 2 + 1 : n_full_;
  n_rings_ = in_.rings;
  t_ = in_.wall_thickness_m;
  R_ = 0.5 * (in_.outer_diameter_m - t_);
  l0_ = 2.0 * R_ * std::sin(pi / n_full_);
  const double I = in_.width_m * t_ * t_ * t_ / 12.0;
  k_theta_ = in_.youngs_modulus_pa * I / l0_;
  const double k_section = in_.youngs_modulus_pa * t_ * in_.width_m / l0_;  // E t L / ℓ0
  k_m_ = in_.membrane_stiffness_scale * k_section;
  M0_ = in_.yield_stress_pa * t_ * t_ * in_.width_m / 4.0;
  const double lh = in_.redwood_alpha > 0 ? in_.redwood_alpha * t_ : l0_;
  H_ = in_.hardening_modulus_pa * I /
       (in_.redwood_fitted_hardening ? redwood_hinge_length(in_.redwood_alpha, l0_) : lh);
  cap_ = in_.yield_cap_ratio > 0 ? in_.yield_cap_ratio * M0_ : std::numeric_limits<double>::infinity();
  C_vp_ = 2.0 * lh / t_ * in_.cowper_symonds_d_per_s;
  q_ = in_.cowper_symonds_q;
  m_node_ = in_.density_kg_m3 * t_ * in_.width_m * (2.0 * pi * R_ / n_full_);
  k_n_ = in_.contact_stiffness_scale * k_section;
  chi_ = in_.contact_damping_s_per_m;
  k_tie_ = in_.tie_stiffness_scale * k_section;
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
  bar_gx_.resize(n_full_);
  bar_gy_.resize(n_full_);
  plan_ring_pass();
  for (std::size_t i = 0; i < size_; ++i)
    if (mu_[i] != 1.0) {
      inertia_rows_.push_back(i);
      inverse_mu_.push_back(1.0 / mu_[i]);
    }
  // A node row with μ = 1 (not in the list) multiplied by 1/1 keeps its bits.
  for (int j = 0; j < n_ind_; ++j) node_inverse_mass_.push_back(1.0 / mu_[node_offset(0, j) + 2]);
  while (inertia_body_first_ < inertia_rows_.size() && inertia_rows_[inertia_body_first_] < body_base_)
    ++inertia_body_first_;
  phi_.resize(size_);
  hinge_gx_.resize(n_full_);
  hinge_gy_.resize(n_full_);
  axis_force_row_.assign(size_, 0);
  if (half_)
    for (int r = 0; r < n_rings_; ++r) {
      axis_force_row_[node_offset(r, 0) + 2] = 1;
      axis_force_row_[node_offset(r, n_ind_ - 1) + 2] = 1;
    }
  contact_k_row_.assign(static_cast<std::size_t>(n_rings_ * n_ind_ + n_bodies_), 0.0);
  contact_c_row_.assign(contact_k_row_.size(), 0.0);
  seg_box_.resize(static_cast<std::size_t>(n_rings_ * n_ind_));
  plan_ring_lanes();  // and flow_moment_, in the lanes' order
  candidate_reference_.resize(static_cast<std::size_t>(2 * n_rings_ * n_ind_));
  candidate_start_.resize(static_cast<std::size_t>((3 * n_rings_) * (n_ind_ + 1)));
  candidate_node_start_.assign(static_cast<std::size_t>(2 * 3 * n_rings_), 0);
  candidate_margin_ = t_;
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
double PolygonChain::contact_load(double w, double penetration, double rate, Tally& tally) const {
  double diss = 0.0;
  const double f = w * contact_force(penetration, rate, diss);
  tally.dissipation += w * diss;
  tally.contact_energy += w * 0.5 * k_n_ * penetration * penetration;
  tally.max_penetration = std::max(tally.max_penetration, penetration);
  return f;
}

void PolygonChain::diss_partials(double penetration, double rate, double& d_pen, double& d_rate) const {
  if (1.0 + chi_ * rate > 0.0) {
    d_pen = k_n_ * chi_ * rate * rate;
    d_rate = 2.0 * k_n_ * penetration * chi_ * rate;
  } else {
    d_pen = -k_n_ * rate;
    d_rate = -k_n_ * penetration;
  }
}

void PolygonChain::add_contact_rows(std::size_t entity, double w, double penetration, double rate) {
  contact_k_row_[entity] += w * k_n_ * std::max(0.0, 1.0 + chi_ * rate);
  contact_c_row_[entity] += w * k_n_ * penetration * chi_;
  if (entity < static_cast<std::size_t>(n_rings_ * n_ind_)) contact_row_nodes_.push_back(static_cast<int>(entity));
}

void PolygonChain::evaluate(double t, const double* y, double* phi, bool record) {
  // ring_forces comes first and sets every node row; the bodies' rows are sums.
  std::fill(phi + body_base_, phi + size_, 0.0);
  std::fill(contact_k_row_.begin(), contact_k_row_.end(), 0.0);
  std::fill(contact_c_row_.begin(), contact_c_row_.end(), 0.0);
  contact_row_nodes_.clear();
  landing_step_ = std::numeric_limits<double>::infinity();
  Tally tally;
  const bool plates = in_.joint == PolygonJoint::Plates;
  if (record) {
    pairs_.clear();
    body_contacts_.clear();
  }
  ring_forces(y, phi, record, tally);
  if (in_.joint == PolygonJoint::Welded) tie_forces(y, phi, record, tally);
  for (int r = 0; r < n_rings_; ++r) {
    const int above = r == 0 ? 0 : (plates ? r : -2);
    const int below = r == n_rings_ - 1 ? (in_.fixed_target ? -1 : -2) : (plates ? r + 1 : -2);
    if (above != -2) plate_contact(r, above, true, t, y, phi, record, tally);
    if (below != -2) plate_contact(r, below, false, t, y, phi, record, tally);
  }
  body_body_contact(t, y, phi, tally);
  update_contact_boxes(y);
  for (int r = 0; r < n_rings_; ++r) {
    node_segment_contact(r, r, true, y, phi, record, tally);
    if (!plates && r + 1 < n_rings_) {
      node_segment_contact(r, r + 1, false, y, phi, record, tally);
      node_segment_contact(r + 1, r, false, y, phi, record, tally);
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
  phi[acc_base_] = tally.plastic_power;
  phi[acc_base_ + 1] = tally.dissipation;
  phi[acc_base_ + 2] = tally.damping;
  phi[acc_base_ + 3] = in_.driven_impactor ? tally.impactor_force * prescribed_speed(t) : 0.0;

  last_impactor_force_ = tally.impactor_force;
  last_target_force_ = tally.target_force;
  if (record) {
    last_contact_energy_ = tally.contact_energy;
    last_max_penetration_ = tally.max_penetration;
    last_max_strain_ = tally.max_bar_strain;
  }
  last_elastic_ = tally.elastic;
}

void PolygonChain::rhs(double t, const double* y, double* dydt) {
  evaluate(t, y, dydt, false);
  if (flow_y_) {  // the central difference's evaluation: round-off as its other cheaper forms
    double* row = dydt + 2;  // a node's (v_x′, v_y′) rows are a pair
    for (int r = 0; r < n_rings_; ++r)
      for (int j = 0; j < n_ind_; ++j, row += 6)
        lanes::store(row, lanes::load(row) * node_inverse_mass_[static_cast<std::size_t>(j)]);
    for (std::size_t k = inertia_body_first_; k < inertia_rows_.size(); ++k) dydt[inertia_rows_[k]] *= inverse_mu_[k];
    return;
  }
  for (const std::size_t i : inertia_rows_) dydt[i] /= mu_[i];
}

void PolygonChain::residual(double t, const double* y, const double* yp, double* r) {
  evaluate(t, y, r, false);
  for (std::size_t i = 0; i < size_; ++i) r[i] = mu_[i] * yp[i] - r[i];
}

void PolygonChain::generalised_forces(double t, const double* y, double* phi) {
  evaluate(t, y, phi, false);
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
  emit_kinematic_and_diagonal(cj);
  jac_ = nullptr;
}

bool PolygonChain::analytic_jacobian_scatter(double t, double cj, const double* y, JacobianScatter& into) {
  into.cursor = 0;
  into.matched = true;
  scatter_unused_.clear();
  jac_ = &scatter_unused_;  // the force laws test jac_ to form their derivatives
  scatter_ = &into;
  try {
    evaluate(t, y, phi_.data(), true);
  } catch (...) {
    jac_ = nullptr;
    scatter_ = nullptr;
    throw;
  }
  emit_kinematic_and_diagonal(cj);
  jac_ = nullptr;
  scatter_ = nullptr;
  return into.matched && into.cursor == into.count;
}

// Kinematic rows x′ = v (none for the x of axis nodes, held at 0) and bodies' y′ = v, then
// the diagonal cj μ (last, so that a caller can find its slots).
void PolygonChain::emit_kinematic_and_diagonal(double cj) {
  for (int r = 0; r < n_rings_; ++r)
    for (int j = 0; j < n_ind_; ++j) {
      const auto o = node_offset(r, j);
      if (!(half_ && (j == 0 || j == n_ind_ - 1))) emit(o, o + 2, -1.0);
      emit(o + 1, o + 3, -1.0);
    }
  for (int b = 0; b < n_bodies_; ++b)
    if (!(b == 0 && in_.driven_impactor)) {
      const auto o = body_offset(b);
      emit(o, o + 1, -1.0);
    }
  for (std::size_t i = 0; i < size_; ++i) emit(i, i, cj * mu_[i]);
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
  std::vector<double> bar_angle(static_cast<std::size_t>(n_full_));
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
    // Each bar's direction once (bar k from node k to k + 1): node k turns from bar k − 1 to
    // bar k. The same operands as one atan2 per bar end, so the same bits at half the calls
    // (the samples' shapes were ≈ 4 % of a central-difference run, README "reference forms").
    for (int k = 0; k < n_full_; ++k) {
      const int kp = (k + 1) % n_full_;
      bar_angle[static_cast<std::size_t>(k)] = std::atan2(nodes[kp][1] - nodes[k][1], nodes[kp][0] - nodes[k][0]);
    }
    for (int k = 0; k < n_full_; ++k) {
      const int km = (k + n_full_ - 1) % n_full_;
      turning[k] = wrap_angle(bar_angle[static_cast<std::size_t>(km)] - bar_angle[static_cast<std::size_t>(k)]);
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
