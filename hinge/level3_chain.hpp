// The massless Level 3 chain (THEORY §4.5; hinge/level3_mechanism.hpp describes it): the
// mechanism laws of each ring, their admissibility and the least-load selection with one
// common force F. Internal to hinge/: level3_mechanism.cpp runs it, and the chain with ring
// inertia (hinge/level3_inertia.cpp) derives from it to reuse the same laws, tables and
// mechanism bookkeeping with a force per ring.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "level3_ecb.hpp"
#include "level3_mechanism.hpp"
#include "level3_statics.hpp"
#include "level3_travelling_e.hpp"

namespace ringcrush::hinge::level3_detail {

using std::numbers::pi;
// Redwood-hardened flattening law in terms of the quadrant angle: P0 (1 + kφ)/cos φ.
inline double flat_load(double p0, double k, double phi) { return p0 * (1.0 + k * phi) / std::cos(phi); }
inline double flat_load_dphi(double p0, double k, double phi) {
  const double c = std::cos(phi);
  return p0 * (k / c + (1.0 + k * phi) * std::sin(phi) / (c * c));
}

// Table interval holding q (clamped to the first and last).
inline std::size_t segment(const std::vector<double>& x, double q) {
  const auto it = std::upper_bound(x.begin(), x.end(), q);
  std::size_t j = it == x.begin() ? 0 : static_cast<std::size_t>(it - x.begin()) - 1;
  return std::min(j, x.size() - 2);
}

// Mechanism slots of ring i: kM·i + {uniform, wrap, bottom, E–C–B} (the Level3Mode order) for
// the roots and the mode logic; state 4 + 3i + {uniform, wrap, bottom or E–C–B}: the bottom
// and the E–C–B of a ring never flow together (the switch is one-way), so they share one crush
// state (zero components would change IDA's error norm, and its steps: 151 against 101 at
// 27.7 m/s with a state of their own).
constexpr int kU = 0, kW = 1, kL = 2, kE = 3, kM = 4;

class Level3Chain : public HybridSystem {
 public:
  Level3Chain(const Level3Input& in, WrapMechanism wrap)
      : in_(in), r_(in.ring), w_(std::move(wrap)), n_(in.rings), m_(kM * in.rings) {
    p0_ = r_.collapse_load();
    d_ = r_.mean_diameter();
    R_ = r_.mean_radius();
    active_.assign(m_, false);
    locked_.assign(m_, false);
    first_.assign(m_, -1.0);
    psi0_.assign(n_, 0.0);
    theta_e_.assign(n_, in.theta_e);
    ecb_.resize(static_cast<std::size_t>(n_));
    ecb_started_.assign(n_, false);
    bottom_frozen_.assign(n_, 0.0);
    wrap_started_.assign(n_, false);
    reinforced_.assign(n_, false);
  }

  std::size_t size() const override { return static_cast<std::size_t>(4 + 3 * n_); }
  // State index of mechanism slot j, and the mechanism's own crush.
  static int state(int j) { return 4 + 3 * (j / kM) + std::min(j % kM, kL); }
  double crush_of(const double* y, int j) const {
    const int i = j / kM;
    switch (j % kM) {
      case kL: return ecb_started_[i] ? bottom_frozen_[i] : y[state(j)];
      case kE: return ecb_started_[i] ? y[state(j)] - bottom_frozen_[i] : 0.0;
      default: return y[state(j)];
    }
  }
  std::size_t root_count() const override { return m_ + 2; }

  // --- mechanism laws -------------------------------------------------------------
  double uniform_phi(const double* y, int i) const {
    return std::asin(std::clamp(crush_of(y, kM * i + kU) / d_, 0.0, 1.0));
  }
  double bottom_psi(const double* y, int i) const {
    return std::asin(std::clamp(std::sin(psi0_[i]) + crush_of(y, kM * i + kL) / R_, 0.0, 1.0));
  }
  double load(const double* y, int j) const {
    const int i = j / kM;
    switch (j % kM) {
      case kU: return flat_load(p0_, r_.hardening_k, uniform_phi(y, i));
      case kW: return w_.load_at(crush_of(y, j));
      case kL: return flat_load(p0_, r_.hardening_k, bottom_psi(y, i));
      default: return ecb_load(y, i);
    }
  }
  // E–C–B of ring i: its table once E has turned, else the onset load on the current bottom
  // state (the candidate held against the bottom mechanism while that one flows).
  double ecb_load(const double* y, int i) const {
    if (ecb_started_[i]) return ecb(i).load_at(crush_of(y, kM * i + kE));
    const double psi = bottom_psi(y, i);
    const auto s = level3_ecb_pose(r_, level3_ecb_points(r_, psi0_[i], psi, ecb_theta_e(i)), psi, 0.0);
    return s.valid ? s.load : std::numeric_limits<double>::infinity();  // no mechanism: never selected
  }
  const EcbMechanism& ecb(int i) const { return ecb_[static_cast<std::size_t>(i)]; }
  // E–C–B replaces a flowing bottom mechanism only when it is cheaper by a margin: at the
  // reinforcement the two loads are equal (E on the flat's edge carries the uniform
  // mechanism's hardening, level3_ecb.hpp), and a tie must not be decided by round-off. The
  // candidate's root fires at a full margin below F, the selection asks for half of it, so
  // the event that finds E–C–B cheaper also selects it.
  static constexpr double kEcbSwitchMargin = 1e-6;
  double switch_margin(int j) const { return j % kM == kE && !ecb_started_[j / kM] ? kEcbSwitchMargin : 0.0; }
  // E of ring i's E–C–B: the chosen θ_E, but not inside the top flat (material angles below
  // the uniform angle φ = psi0_): that flat is pressed flat-on-flat by the ring above over its
  // length, and an E inside it would lift its outer part into that ring at first order in β
  // (1.0 mm at the E–C–B limit for E = 45° on Test 30's φ = 60.6°); from the flat's edge the
  // arc beyond E rises only by ≈ Rβ²/2, like the arc beside B′ dips (level3_ecb.hpp).
  double ecb_theta_e(int i) const { return std::max(theta_e_[i], psi0_[i]); }
  double slope(const double* y, int j) const {
    const int i = j / kM;
    switch (j % kM) {
      case kU: {
        const double phi = uniform_phi(y, i);
        return flat_load_dphi(p0_, r_.hardening_k, phi) / (d_ * std::cos(phi));
      }
      case kW: return w_.slope_at(crush_of(y, j));
      case kL: {
        const double psi = bottom_psi(y, i);
        return flat_load_dphi(p0_, r_.hardening_k, psi) / (R_ * std::cos(psi));
      }
      default: return ecb_started_[i] ? ecb(i).slope_at(crush_of(y, j)) : 0.0;  // flows only from its table
    }
  }
  double energy(const double* y, int j) const {
    const int i = j / kM;
    const double M0 = r_.plastic_moment_nm, k = r_.hardening_k;
    switch (j % kM) {
      case kU: return level3_uniform_energy(r_, crush_of(y, j));
      case kW: return w_.energy_at(crush_of(y, j));
      case kL: {
        const double a = psi0_[i], b = bottom_psi(y, i);
        return 4.0 * M0 * ((b - a) + 0.5 * k * (b * b - a * a));
      }
      default: return ecb_started_[i] ? ecb(i).energy_at(crush_of(y, j)) : 0.0;
    }
  }
  double ring_crush(const double* y, int i) const {
    return y[state(kM * i + kU)] + y[state(kM * i + kW)] + y[state(kM * i + kL)];
  }
  // Remaining travel of mechanism j: its own geometric limit and the ring's lock-up d − t.
  double margin(const double* y, int j) const {
    const int i = j / kM;
    const double ring_left = (d_ - r_.wall_thickness_m) - ring_crush(y, i);
    double own;
    switch (j % kM) {
      case kU: own = ring_left; break;
      case kW: own = w_.capacity() - crush_of(y, j); break;
      case kL: own = (R_ - r_.wall_thickness_m) - R_ * std::sin(bottom_psi(y, i)); break;
      default: own = ecb_started_[i] ? ecb(i).capacity() - crush_of(y, j) : ring_left; break;
    }
    return std::min(own, ring_left);
  }
  bool available(int j) const {
    const int i = j / kM;
    if (locked_[j]) return false;
    switch (j % kM) {
      case kU: return !reinforced_[i];
      case kW: return !in_.plates && i + 1 < n_ && !reinforced_[i] && !wrap_started_[i + 1];
      // Once E has turned the bottom mechanism's DeRuntz–Hodge lower quadrant (its flat's
      // edge travelling on a round arc about a C that stays put) no longer describes the ring:
      // C has moved and B′ is a hinge, so the ring stays in E–C–B (one-way switch).
      case kL: return reinforced_[i] && !ecb_started_[i];
      default: return reinforced_[i] && in_.ring_under == Level3RingUnder::LeastLoad;
    }
  }

  // --- equations ---------------------------------------------------------------------
  void rhs(double, const double* y, double* f) override {
    std::fill(f, f + size(), 0.0);
    const double v = y[1], F = y[2];
    f[0] = v;
    f[1] = -F / in_.impactor_mass_kg;
    f[3] = F * v;
    if (soft_ >= 0) {
      f[state(soft_)] = v;
      f[2] = slope(y, soft_) * v;
      return;
    }
    double inv = 0.0;
    for (int j = 0; j < m_; ++j)
      if (active_[j]) inv += 1.0 / std::max(slope(y, j), 1e-12 * p0_ / d_);
    if (inv <= 0.0) return;
    const double Fdot = v / inv;
    f[2] = Fdot;
    for (int j = 0; j < m_; ++j)
      if (active_[j]) f[state(j)] = Fdot / std::max(slope(y, j), 1e-12 * p0_ / d_);
  }
  void residual(double t, const double* y, const double* yp, double* r) override {
    rhs(t, y, r);
    for (std::size_t k = 0; k < size(); ++k) r[k] = yp[k] - r[k];
  }

  void event_roots(double, const double* y, double* g) override {
    for (int j = 0; j < m_; ++j) {
      if (active_[j]) g[j] = margin(y, j) / d_;
      else if (available(j)) g[j] = std::max((y[2] * (1.0 - switch_margin(j)) - load(y, j)) / p0_, -1e3);  // E–C–B may be +∞
      else g[j] = 1.0;
    }
    // A softening mechanism turns hardening, or a hardening one starts to soften (E–C–B's
    // load peaks before its limit; the wrap softens from its onset, the others never do).
    if (soft_ >= 0) {
      g[m_] = slope(y, soft_) * d_ / p0_;
    } else {
      g[m_] = 1.0;
      for (int j = 0; j < m_; ++j)
        if (active_[j]) g[m_] = std::min(g[m_], slope(y, j) * d_ / p0_);
    }
    g[m_ + 1] = y[1] / in_.impactor_velocity_m_s;
  }

  int root_departure(std::size_t i, int fired) const override {
    if (static_cast<int>(i) < m_ && fired > 0) return -1;  // activated: now a margin (falls)
    return fired;
  }

  EventAction on_event(double t, std::vector<double>& y, const std::vector<int>& fired) override {
    if (fired[m_ + 1] < 0 || y[1] <= 0.0) {
      events_.push_back({t, "impactor_arrested", -1, fmt::format("F = {:.1f} N", y[2])});
      arrested_ = true;
      return EventAction::Stop;
    }
    for (int j = 0; j < m_; ++j)
      if (active_[j] && fired[j] != 0 && margin(y.data(), j) <= 1e-9 * d_) {
        locked_[j] = true;
        events_.push_back({t, "ring_locked", j / kM,
                           fmt::format("{} mechanism at its limit", to_string(static_cast<Level3Mode>(j % kM)))});
      }
    return select(t, y) ? EventAction::Continue : EventAction::Stop;
  }

  // Mode selection: the admissible mechanisms of least load flow (THEORY §4.5).
  // Returns false when every mechanism is exhausted (the chain is locked).
  bool select(double t, std::vector<double>& y) {
    for (int pass = 0; pass < 4; ++pass) {
      std::fill(active_.begin(), active_.end(), false);
      soft_ = -1;
      double pmin = std::numeric_limits<double>::infinity();
      for (int j = 0; j < m_; ++j) {
        if (available(j) && margin(y.data(), j) <= 1e-9 * d_) locked_[j] = true;
        if (available(j)) pmin = std::min(pmin, load(y.data(), j));
      }
      if (!std::isfinite(pmin)) {
        lock_loss_ += 0.5 * in_.impactor_mass_kg * y[1] * y[1];
        events_.push_back({t, "chain_locked", -1, "every mechanism at its limit: impactor stopped"});
        y[1] = 0.0;
        return false;
      }
      // The massless chain carries no more than its least load: F rises to it, or drops to it
      // when a mechanism made available by this event is cheaper (E–C–B of a ring just
      // reinforced); the drop is instantaneous and costs no work (∫ F dδ is continuous).
      if (y[2] < pmin || y[2] > pmin * (1.0 + 1e-6)) y[2] = pmin;
      const double F = y[2];
      for (int j = 0; j < m_; ++j)
        if (available(j) && load(y.data(), j) <= F * (1.0 + 1e-7)) active_[j] = true;
      for (int i = 0; i < n_; ++i) {  // one mechanism per ring underneath: the cheaper
        const int b = kM * i + kL, e = kM * i + kE;
        if (active_[b] && active_[e])
          active_[load(y.data(), e) < load(y.data(), b) * (1.0 - 0.5 * kEcbSwitchMargin) ? b : e] = false;
      }
      for (int j = 0; j < m_ && soft_ < 0; ++j)  // softening: the one nearest the impactor
        if (active_[j] && slope(y.data(), j) < 0.0) soft_ = j;
      if (soft_ >= 0) {
        std::fill(active_.begin(), active_.end(), false);
        active_[soft_] = true;
      }
      for (int i = 0; i < n_; ++i)
        if (active_[kM * i + kE] && !ecb_started_[i]) switch_to_ecb(t, y, i);
      bool changed = false;
      for (int j = 0; j < m_; ++j) {
        if (!active_[j] || first_[j] >= 0) continue;
        first_[j] = t;
        const int i = j / kM;
        events_.push_back({t, "hinge_formed", i,
                           fmt::format("{} mechanism at F = {:.1f} N", to_string(static_cast<Level3Mode>(j % kM)), F)});
        if (j % kM == kW && !wrap_started_[i]) {
          wrap_started_[i] = true;
          reinforced_[i + 1] = true;
          psi0_[i + 1] = uniform_phi(y.data(), i + 1);  // the bottom half's current angle
          if (in_.hinge_e == Level3HingeE::ShearFree) theta_e_[i + 1] = shear_free_e(y.data(), i);
          double pu = load(y.data(), kM * i + kU);
          events_.push_back({t, "mode_selected", i,
                             fmt::format("wrap over ring {} (wrap load {:.1f} N <= uniform {:.1f} N)", i + 2,
                                         load(y.data(), j), pu)});
          changed = true;
        }
      }
      if (!changed) break;
    }
    return true;
  }

  // Ring i turns E: its E–C–B traced from the current bottom state (hinge/level3_ecb.hpp).
  void switch_to_ecb(double t, const std::vector<double>& y, int i) {
    const double psi = bottom_psi(y.data(), i), pb = load(y.data(), kM * i + kL);
    const double pe = load(y.data(), kM * i + kE);
    ecb_[static_cast<std::size_t>(i)] = level3_ecb_mechanism(r_, psi0_[i], psi, ecb_theta_e(i));
    bottom_frozen_[i] = y[static_cast<std::size_t>(state(kM * i + kL))];
    ecb_started_[i] = true;
    events_.push_back({t, "mode_selected", i,
                       fmt::format("E-C-B under ring {} (E at {:.1f} deg, load {:.3f} N < bottom {:.3f} N, psi = {:.3f} deg)", i,
                                   ecb_theta_e(i) * 180.0 / pi, pe, pb, psi * 180.0 / pi)});
  }

  // The shear-free E of ring i + 1 just reinforced by ring i's wrap: the least-load E–C–B
  // hinge beyond the cap held by ring i (level3_travelling_e.hpp), on the drawn shapes.
  double shear_free_e(const double* y, int i) const {
    const double t = r_.wall_thickness_m;
    const auto up = level3_ring_shape(r_, w_, ring_state(y, i), 0.0, 48);
    const auto lo = level3_ring_shape(r_, w_, ring_state(y, i + 1), up.bottom_y - t, 48);
    const double cap = level3_held_cap(up, lo, 1.1 * t);
    const double hard = 1.0 + r_.hardening_k * bottom_psi(y, i + 1);
    return level3_shear_free_e(lo, r_.plastic_moment_nm, cap, hard).theta_e;
  }

  bool finished(double, const double* y) override { return y[1] <= 0.0; }

  // --- results -----------------------------------------------------------------------
  void record(double t, const std::vector<double>& y, Level3History& h) const {
    h.time_s.push_back(t);
    h.impactor_displacement_m.push_back(y[0]);
    h.impactor_velocity_m_s.push_back(y[1]);
    h.force_n.push_back(y[2]);
    h.ring_crush_m.resize(n_);
    for (int i = 0; i < n_; ++i) h.ring_crush_m[i].push_back(ring_crush(y.data(), i));
    h.kinetic_j.push_back(0.5 * in_.impactor_mass_kg * y[1] * y[1]);
    h.plastic_j.push_back(y[3]);
    std::vector<Level3RingResult> states;
    states.reserve(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) states.push_back(ring_state(y.data(), i));
    h.ring_state.push_back(std::move(states));
  }

  // The geometric state of ring i (what level3_ring_shape draws).
  Level3RingResult ring_state(const double* s, int i) const {
    Level3RingResult rr;
    rr.uniform_crush_m = crush_of(s, kM * i + kU);
    rr.wrap_crush_m = crush_of(s, kM * i + kW);
    rr.bottom_crush_m = crush_of(s, kM * i + kL);
    rr.ecb_crush_m = crush_of(s, kM * i + kE);
    rr.ecb_started = ecb_started_[i];
    if (ecb_started_[i]) {
      const auto& m = ecb(i);
      rr.ecb_theta_e = m.theta_e;
      rr.ecb_psi = m.psi;
      rr.ecb_rotation_cb = m.q_at(rr.ecb_crush_m);
      rr.ecb_rotation_e = m.beta_at(rr.ecb_crush_m);
    }
    rr.crush_m = ring_crush(s, i);
    rr.uniform_angle = uniform_phi(s, i);
    rr.bottom_angle = reinforced_[i] ? bottom_psi(s, i) : 0.0;
    rr.wrap_started = wrap_started_[i];
    rr.wrap_theta_f = wrap_started_[i] ? w_.theta_f_at(rr.wrap_crush_m) : 0.0;
    rr.reinforced = reinforced_[i];
    rr.mode = wrap_started_[i]  ? Level3Mode::Wrap
              : ecb_started_[i] ? Level3Mode::Ecb
              : reinforced_[i]  ? Level3Mode::Bottom
                                : Level3Mode::Uniform;
    if (wrap_started_[i]) {  // κ between the table's nodes, linear in the wrap crush
      const std::size_t j = segment(w_.crush, rr.wrap_crush_m);
      const std::size_t k = std::min(j + 1, w_.crush.size() - 1);
      const double span = w_.crush[k] - w_.crush[j];
      const double f = span > 0 ? std::clamp((rr.wrap_crush_m - w_.crush[j]) / span, 0.0, 1.0) : 0.0;
      rr.wrap_curvature = w_.curvature[j] + f * (w_.curvature[k] - w_.curvature[j]);
    }
    return rr;
  }

  void finish(const std::vector<double>& y, Level3Result& res) const {
    const double* s = y.data();
    double total = 0.0;
    for (int i = 0; i < n_; ++i) {
      Level3RingResult rr = ring_state(s, i);
      const double eu = energy(s, kM * i + kU), ew = energy(s, kM * i + kW), el = reinforced_[i] ? energy(s, kM * i + kL) : 0.0;
      const double ee = energy(s, kM * i + kE);
      rr.plastic_work_j = eu + ew + el + ee;
      total += rr.plastic_work_j;
      // Hinge map (material angles from the top apex).
      const double fu = first_[kM * i + kU], fw = first_[kM * i + kW], fl = first_[kM * i + kL];
      const double phi = rr.uniform_angle;
      if (fu >= 0) {
        rr.hinges.push_back({"A", 0.0, fu, 2.0 * phi});
        rr.hinges.push_back({"C", 90.0, fu, 2.0 * phi});
        rr.hinges.push_back({"B", 180.0, fu, 2.0 * phi});
      }
      if (fw >= 0 && w_.travelling()) {  // travelling F: rotations accumulated along the trace
        const std::size_t j = segment(w_.crush, crush_of(s, kM * i + kW));
        const double arc = w_.dissipation[j] / (2.0 * r_.plastic_moment_nm) - std::abs(w_.rotation_c[j]) - w_.rotation_f[j];
        rr.hinges.push_back({"C", 90.0, fw, std::abs(w_.rotation_c[j])});
        rr.hinges.push_back({"F", rr.wrap_theta_f * 180.0 / pi, fw, w_.rotation_f[j]});
        rr.hinges.push_back({"B", 180.0, fw, arc});
      } else if (fw >= 0) {
        const double q = crush_of(s, kM * i + kW);
        const std::size_t j = segment(w_.crush, q);
        const double kappa = w_.curvature[j], alpha = w_.chord_angle[j];
        const double S = R_ * (pi - w_.theta_f);
        rr.hinges.push_back({"C", 90.0, fw, std::abs(alpha - w_.chord_angle.front())});
        rr.hinges.push_back({"F", w_.theta_f * 180.0 / pi, fw,
                             std::abs((kappa - w_.curvature.front()) * S - (alpha - w_.chord_angle.front()))});
        rr.hinges.push_back({"B", 180.0, fw, S * std::abs(kappa - w_.curvature.front())});
      }
      const double fe = first_[kM * i + kE];
      if (fl >= 0 && fe < 0) {  // E reported (not turned): its angle from the statics check
        rr.hinges.push_back({"E", in_.theta_e * 180.0 / pi, -1.0, 0.0});
        rr.hinges.push_back({"C", 90.0, fl, rr.bottom_angle - psi0_[i]});
        rr.hinges.push_back({"B", 180.0, fl, rr.bottom_angle - psi0_[i]});
      }
      if (fe >= 0) {  // E–C–B flowed: E turned by β, C by β + q, B′ (the flat's edge) by q
        if (fl >= 0) {
          rr.hinges.push_back({"C", 90.0, fl, rr.bottom_angle - psi0_[i]});
          rr.hinges.push_back({"B", 180.0, fl, rr.bottom_angle - psi0_[i]});
        }
        rr.hinges.push_back({"E", rr.ecb_theta_e * 180.0 / pi, fe, rr.ecb_rotation_e});
        rr.hinges.push_back({"C", 90.0, fe, rr.ecb_rotation_e + rr.ecb_rotation_cb});
        rr.hinges.push_back({"B'", 180.0 - rr.ecb_psi * 180.0 / pi, fe, rr.ecb_rotation_cb});
      }
      res.rings.push_back(rr);
    }
    res.plastic_work_closed_form_j = total;
    res.lock_loss_j = lock_loss_;
    res.events = events_;
  }

  double psi0(int i) const { return psi0_[i]; }

 protected:
  Level3Input in_;
  Level3Ring r_;
  WrapMechanism w_;
  int n_, m_;
  double p0_ = 0, d_ = 0, R_ = 0;
  std::vector<bool> active_, locked_, wrap_started_, reinforced_;
  std::vector<double> first_, psi0_, theta_e_;  // theta_e_: E of the ring's E–C–B (rad)
  std::vector<EcbMechanism> ecb_;                // traced when the ring turns E
  std::vector<bool> ecb_started_;
  std::vector<double> bottom_frozen_;  // the bottom crush when E turned (the shared state's base)
  int soft_ = -1;
  double lock_loss_ = 0.0;
  bool arrested_ = false;
  std::vector<Level3Event> events_;
};

// The wrap table the chain runs with: F fixed at θ_F, travelling, or at least onset load.
WrapMechanism level3_wrap_for(const Level3Input& in);

}  // namespace ringcrush::hinge::level3_detail
