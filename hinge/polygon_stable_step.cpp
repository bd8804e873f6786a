// The stable step of the central-difference driver (PolygonChain::stable_step,
// polygon_chain.hpp). Per node i with mass μ_i (half on the symmetry axis, the forces
// weighted alike), a Gershgorin bound of M⁻¹K and of M⁻¹C:
//   K_i = w (4 k_m + 16 k_θ/ℓ0²) + 2 w k_tie (tied nodes) + contact rows,
//   C_i = w (4 c_b + 16 c_θ/ℓ0² + c_mass m) + contact rows,
// where a membrane bar adds k_m e eᵀ blocks of norm k_m to its two ends and their coupling
// (2 bars × 2 = 4 k_m), a hinge k_θ g gᵀ with |g| = (1, 2, 1)/ℓ (centre 2·4, ends 1·4 twice:
// 16 k_θ/ℓ²); the contact rows are those the last evaluation summed (k(1 + χṗ) and k p χ
// per touching pair, polygon_segment_contact.cpp and polygon_body_contact.cpp). Then
// ω_i² = K_i/μ_i, ξ_i = C_i/(2√(K_i μ_i)) and dt_i = (2/ω_i)(√(1 + ξ_i²) − ξ_i), the
// central-difference limit with damping taken at the half-step velocity (Belytschko, Liu &
// Moran, Nonlinear Finite Elements, §6.3). The Kelvin–Voigt dampers (ratios ζ_m, ζ_b of the
// shortest modes, PolygonChainInput, whose own default is 0; the ringcrush tool's defaults are
// Level2Settings', compare/hinge_run_2d.hpp: ζ_m = 1 and, since session 18, ζ_b = 0.15) put
// ξ ≳ 1 into every node, mostly through the membrane bars, and so shorten the step by the
// factor √(1 + ξ²) − ξ above — unless the driver applies them implicitly
// (set_implicit_ring_dampers): then C_i holds the contact and mass damping only, and the
// Kelvin–Voigt dampers do not shorten the step.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "hinge/polygon_chain.hpp"
#include "hinge/polygon_node_step_lanes.hpp"
#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

double PolygonChain::stable_step(unsigned terms) const { return stable_step_scan(terms, false); }

double PolygonChain::stable_step_all_nodes(unsigned terms) const { return stable_step_scan(terms, true); }

double PolygonChain::stable_step_scan(unsigned terms, bool every_node) const {
  // The implicit membrane (polygon_implicit_membrane.cpp) does not bound the step.
  const double k_membrane = (terms & kMembrane) && !implicit_membrane_ ? 4.0 * k_m_ : 0.0;
  const double k_ring = k_membrane + ((terms & kHinges) ? 16.0 * k_theta_ / (l0_ * l0_) : 0.0);
  const bool contacts = (terms & kContacts) != 0;
  // Implicit ring dampers (trapezoidal in the driver, polygon_implicit_dampers.cpp) leave the
  // step: the leapfrog with the damping at the step's ends is stable up to ω Δt = 2 for any ξ.
  const double c_kv = implicit_dampers_ ? 0.0 : 4.0 * c_bar_ + 16.0 * c_hinge_ / (l0_ * l0_);
  const double c_ring = c_kv + in_.mass_damping_per_s * m_node_;
  const bool welded = in_.joint == PolygonJoint::Welded && (terms & kTies);
  const int jb = half_ ? n_ind_ - 1 : n_full_ / 2;
  const double w_tie = half_ ? 0.5 : 1.0;
  const double none = std::numeric_limits<double>::infinity();
  auto limit = [&](double K, double C, double mass) { return node_step_limit(K, C, mass); };
  // A node's stiffness, damping and mass rows.
  auto node_rows = [&](double w, bool tied, double k_contact, double c_contact, double& K, double& C, double& mass) {
    K = w * k_ring + k_contact;
    if (tied) K += 2.0 * w_tie * k_tie_;
    C = w * c_ring + c_contact;
    mass = w * m_node_;
  };
  auto node_step = [&](double w, bool tied, double k_contact, double c_contact) {
    double K, C, mass;
    node_rows(w, tied, k_contact, c_contact, K, C, mass);
    return limit(K, C, mass);
  };
  // A node without contact rows has the step of every such node of its weight and tie: the
  // same operands, so the same bits. Each such class's step is computed once (the square
  // roots and divisions were 7.7 % of a welded central-difference run). Only the axis nodes
  // (half weight) and the tied ones (0 and jb) differ from an interior node.
  auto special = [&](int j) { return j == 0 || j == jb || j == n_ind_ - 1; };
  auto tied_node = [&](int r, int j) {
    return special(j) && welded && ((j == jb && r + 1 < n_rings_) || (j == 0 && r > 0));
  };
  auto weight = [&](int j) { return special(j) ? node_weight(j) : 1.0; };
  // [axis node][tied]: nodes of the class in the chain, and those with contact rows.
  int members[2][2] = {{0, 0}, {0, 0}}, with_rows[2][2] = {{0, 0}, {0, 0}};
  double dt = none;
  // A node with contact rows: its own step; returns false for one without (both rows 0).
  // The contact nodes' rows are gathered and their limits taken several to a vector
  // (polygon_node_step_lanes.hpp: the divisions and square roots were the scan's cost).
  constexpr int kBatch = 64;
  double batch_k[kBatch], batch_c[kBatch], batch_mass[kBatch];
  int batched = 0;
  const int width = lanes::wide_lanes_available();
  auto flush = [&] {
    dt = min_node_step_limit(dt, batch_k, batch_c, batch_mass, batched, width);
    batched = 0;
  };
  // The every-node scan (the reference) takes each node's limit at once, one by one.
  auto contact_node = [&](int r, int j) {
    const auto g = static_cast<std::size_t>(r * n_ind_ + j);
    const double k_contact = contacts ? contact_k_row_[g] : 0.0, c_contact = contact_c_row_[g];
    if (k_contact == 0.0 && c_contact == 0.0) return false;
    if (every_node) {
      dt = std::min(dt, node_step(weight(j), tied_node(r, j), k_contact, c_contact));
      return true;
    }
    node_rows(weight(j), tied_node(r, j), k_contact, c_contact, batch_k[batched], batch_c[batched],
              batch_mass[batched]);
    if (++batched == kBatch) flush();
    return true;
  };
  auto class_of = [&](int r, int j, int& axis, int& tie) {
    axis = weight(j) == 1.0 ? 0 : 1;
    tie = tied_node(r, j) ? 1 : 0;
  };
  if (every_node) {  // the reference: every node in turn
    for (int r = 0; r < n_rings_; ++r)
      for (int j = 0; j < n_ind_; ++j) {
        int a = 0, t = 0;
        class_of(r, j, a, t);
        ++members[a][t];
        if (contact_node(r, j)) ++with_rows[a][t];
      }
  } else {
    // Only the nodes the last evaluation gave contact rows (≈ 12 touching pairs on Test 30
    // against 150 nodes); the classes' sizes from the few special nodes. min is exact and
    // order-free, so the bound is the scan's to the bit. A class whose members all have
    // contact rows is left out, as the scan leaves it: in exact arithmetic a node's step with
    // its rows is never above its class's, but √(1 + ξ²) − ξ need not be monotone to the last
    // bit, so the distinct nodes are counted (the marks) rather than the class assumed.
    int specials[3], n_special = 0;  // 0, jb, n_ind − 1, each once (jb = n_ind − 1 in the half model)
    for (const int j : {0, jb, n_ind_ - 1})
      if (std::find(specials, specials + n_special, j) == specials + n_special) specials[n_special++] = j;
    for (int r = 0; r < n_rings_; ++r) {
      members[0][0] += n_ind_ - n_special;
      for (int i = 0; i < n_special; ++i) {
        int a = 0, t = 0;
        class_of(r, specials[i], a, t);
        ++members[a][t];
      }
    }
    contact_row_mark_.resize(static_cast<std::size_t>(n_rings_ * n_ind_), 0);
    const std::uint64_t epoch = ++contact_row_epoch_;
    for (const int g : contact_row_nodes_) {
      auto& mark = contact_row_mark_[static_cast<std::size_t>(g)];
      if (mark == epoch) continue;  // a node listed twice
      mark = epoch;
      const int r = g / n_ind_, j = g % n_ind_;
      int a = 0, t = 0;
      class_of(r, j, a, t);
      if (contact_node(r, j)) ++with_rows[a][t];
    }
  }
  if (batched > 0) flush();
  for (int a = 0; a < 2; ++a)
    for (int t = 0; t < 2; ++t)
      if (members[a][t] > with_rows[a][t]) dt = std::min(dt, node_step(a == 0 ? 1.0 : 0.5, t == 1, 0.0, 0.0));
  for (int b = 0; b < n_bodies_; ++b) {
    if (b == 0 && in_.driven_impactor) continue;
    const auto g = static_cast<std::size_t>(n_rings_ * n_ind_ + b);
    dt = std::min(dt, limit(contacts ? contact_k_row_[g] : 0.0, contact_c_row_[g], bodies_[b].mass));
  }
  return dt;
}

}  // namespace ringcrush::hinge
