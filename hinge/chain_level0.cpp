// Level 0: a 1-D chain of elastic–plastic ring springs between lumped masses
// (THEORY §4.4 "Level 0 equations").
//
// Masses (u positive toward the target): m_0 = M + m_r/2 (impactor with the top half of
// ring 1), m_k = m_r (+ plate mass) between rings, m_N = m_r/2 at a free far end; a fixed
// target holds u_N ≡ 0. Ring i sits between masses i and i+1 with crush δ_i = u_i − u_{i+1}.
//
// Ring force F_i = k_el (δ_i − δp_i) + k_lock⟨δ_i − δ_L⟩, with the elastic branch bounded by
// the DeRuntz–Hodge/Redwood backbone of the plastic crush, k_el(δ − δp) ≤ P_b(δp). The hinge
// law is rate-independent and event-driven: in the plastic mode the consistency condition
// d/dt[k_el(δ − δp) − P_b(δp)] = 0 gives δp′ = k_el δ′/(k_el + P_b′(δp)); yield, unloading
// (δ′ = 0), contact opening/closing (no tension for free and plated joints) and lock-up are
// root functions. Plastic work is then exactly W(δp) = 8M0(φ + kφ²/2) in closed form.
//
// The top half of ring 1 is at rest when the impactor arrives: the first contact is a
// perfectly plastic impact of M with m_r/2 (momentum kept), whose loss is booked as impact
// energy so that the balance closes on ½MV².
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "chain_1d.hpp"
#include "chain_run.hpp"

namespace ringcrush::hinge {
namespace {

enum class Branch { Elastic, Plastic, Open };

class Level0Chain final : public HybridSystem {
 public:
  explicit Level0Chain(const ChainInput& in) : in_(in), law_(in.ring) {
    n_ = in.rings;
    free_end_ = in.far_end == ChainFarEnd::Free;
    nm_ = n_ + (free_end_ ? 1 : 0);
    mass_.assign(nm_, law_.mass_kg + (in.joint == ChainJoint::Plates ? in.plate_mass_kg : 0.0));
    mass_[0] = in.impactor_mass_kg + 0.5 * law_.mass_kg;
    if (free_end_) mass_[nm_ - 1] = 0.5 * law_.mass_kg;
    tension_ = in.joint == ChainJoint::Welded;
    k_ = law_.elastic_stiffness_n_m;
    klock_ = law_.lock_stiffness_n_m;
    p0_ = law_.collapse_load();
    dl_ = law_.lock_deflection();
    vref_ = in.impactor_velocity_m_s;
    branch_.assign(n_, Branch::Elastic);
    locked_.assign(n_, 0);
    yielded_.assign(n_, 0);
    switched_.assign(n_, 0);
    double total = 0.0;
    for (double m : mass_) total += m;
    v_common_ = free_end_ ? in.impactor_mass_kg * vref_ / total : 0.0;
    // Elastic round trip along the chain, 2N √(m_r/k_el): the settling time after the last
    // plastic flow ends (see finished()).
    settle_time_ = 2.0 * n_ * std::sqrt(law_.mass_kg / k_);
  }

  std::size_t size() const override { return 2 * nm_ + n_; }
  std::size_t root_count() const override { return 4 * n_ + 1; }

  double delta(const double* y, int i) const {
    return y[i] - (i + 1 < nm_ ? y[i + 1] : 0.0);
  }
  double delta_rate(const double* y, int i) const {
    return y[nm_ + i] - (i + 1 < nm_ ? y[nm_ + i + 1] : 0.0);
  }
  double ring_force(const double* y, int i) const {
    const double dl = delta(y, i);
    double f = branch_[i] == Branch::Open ? 0.0 : k_ * (dl - y[2 * nm_ + i]);
    if (locked_[i]) f += klock_ * (dl - dl_);
    return f;
  }
  // δp′ per unit δ′ in the plastic branch.
  double flow_ratio(double dp) const { return k_ / (k_ + law_.backbone_slope(dp)); }

  void rhs(double, const double* y, double* f) override {
    const double* v = y + nm_;
    const double* dp = y + 2 * nm_;
    for (int k = 0; k < nm_; ++k) f[k] = v[k];
    for (int k = 0; k < nm_; ++k) f[nm_ + k] = 0.0;
    for (int i = 0; i < n_; ++i) {
      const double fi = ring_force(y, i);
      f[nm_ + i] -= fi;
      if (i + 1 < nm_) f[nm_ + i + 1] += fi;
      f[2 * nm_ + i] = branch_[i] == Branch::Plastic ? flow_ratio(dp[i]) * delta_rate(y, i) : 0.0;
    }
    for (int k = 0; k < nm_; ++k) f[nm_ + k] /= mass_[k];
  }

  void residual(double t, const double* y, const double* yp, double* r) override {
    rhs(t, y, r);
    for (std::size_t j = 0; j < size(); ++j) r[j] = yp[j] - r[j];
  }

  bool has_jacobian() const override { return true; }
  // ∂F/∂y + cj ∂F/∂y′ with F = y′ − f(y): cj I − ∂f/∂y, all analytic.
  void jacobian(double, double cj, const double* y, const double*, JacobianSink& jac) override {
    const std::size_t n = size();
    jac_.assign(n * n, 0.0);
    auto at = [&](std::size_t row, std::size_t col) -> double& { return jac_[row * n + col]; };
    for (std::size_t j = 0; j < n; ++j) at(j, j) = cj;
    for (int k = 0; k < nm_; ++k) at(k, nm_ + k) = -1.0;
    for (int i = 0; i < n_; ++i) {
      // ∂F_i/∂u_i = kd, ∂F_i/∂u_{i+1} = −kd, ∂F_i/∂δp_i = kp
      const double kd = (branch_[i] == Branch::Open ? 0.0 : k_) + (locked_[i] ? klock_ : 0.0);
      const double kp = branch_[i] == Branch::Open ? 0.0 : -k_;
      const std::size_t ui = i, ui1 = i + 1, dpi = 2 * nm_ + i;
      const bool below = i + 1 < nm_;
      // v_i′ ∋ −F_i/m_i and v_{i+1}′ ∋ +F_i/m_{i+1}; the Jacobian carries −∂f/∂y.
      at(nm_ + i, ui) += kd / mass_[i];
      if (below) at(nm_ + i, ui1) -= kd / mass_[i];
      at(nm_ + i, dpi) += kp / mass_[i];
      if (below) {
        at(nm_ + i + 1, ui) -= kd / mass_[i + 1];
        at(nm_ + i + 1, ui1) += kd / mass_[i + 1];
        at(nm_ + i + 1, dpi) -= kp / mass_[i + 1];
      }
      if (branch_[i] == Branch::Plastic) {
        // δp′ = k δ′/(k + P_b′(δp)): ∂/∂δ′ = ratio, ∂/∂δp = −k δ′ P_b″/(k + P_b′)².
        const double dp = y[dpi];
        const double sl = law_.backbone_slope(dp), cu = law_.backbone_curvature(dp);
        const double ratio = k_ / (k_ + sl);
        const double rate = delta_rate(y, i);
        at(dpi, nm_ + i) -= ratio;
        if (below) at(dpi, nm_ + i + 1) += ratio;
        at(dpi, dpi) += k_ * cu * rate / ((k_ + sl) * (k_ + sl));
      }
    }
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t c = 0; c < n; ++c)
        if (jac_[r * n + c] != 0.0) jac.set(r, c, jac_[r * n + c]);
  }

  // Roots per ring i: [4i] yield (elastic) or unloading (plastic); [4i+1] contact gap
  // (no-tension joints); [4i+2] lock-up; [4i+3] reserved for the rate of the crush in the
  // open branch (re-closing); last: impactor velocity relative to the final common velocity.
  void event_roots(double, const double* y, double* g) override {
    for (int i = 0; i < n_; ++i) {
      const double dp = y[2 * nm_ + i];
      const double e = delta(y, i) - dp;
      g[4 * i] = branch_[i] == Branch::Elastic ? (law_.backbone(dp) - k_ * e) / p0_
                 : branch_[i] == Branch::Plastic ? delta_rate(y, i) / vref_
                                                 : 1.0;
      g[4 * i + 1] = (!tension_ && branch_[i] != Branch::Plastic) ? k_ * e / p0_ : 1.0;
      g[4 * i + 2] = (delta(y, i) - dl_) / law_.wall_thickness_m;
      g[4 * i + 3] = 1.0;
    }
    g[4 * n_] = (y[nm_] - v_common_) / vref_;
  }

  int root_departure(std::size_t r, int fired) const override {
    if (r == static_cast<std::size_t>(4 * n_)) return fired != 0 ? fired : (arrest_time_ < 0.0 ? 1 : 0);
    const int i = static_cast<int>(r / 4);
    switch (r % 4) {
      // yield margin (elastic) or crush rate (plastic): both grow after a switch
      case 0: return switched_[i] ? 1 : (fired != 0 ? fired : 1);
      case 1: return fired != 0 ? fired : (branch_[i] == Branch::Open ? -1 : 1);
      case 2: return fired != 0 ? fired : (locked_[i] ? 1 : -1);
      default: return 0;
    }
  }

  EventAction on_event(double t, std::vector<double>& y, const std::vector<int>& fired) override {
    // Only the physically meaningful crossing direction switches a mode; the other one
    // (e.g. the yield margin growing again right after unloading) is a restart, no more.
    std::fill(switched_.begin(), switched_.end(), 0);
    for (int i = 0; i < n_; ++i) {
      const Branch before = branch_[i];
      const double rate = delta_rate(y.data(), i);
      if (fired[4 * i] < 0) {
        if (branch_[i] == Branch::Elastic && rate > 0.0) {
          branch_[i] = Branch::Plastic;
          log(t, yielded_[i] ? "ring_reloaded" : "hinge_formed", i, "elastic limit reached on the backbone");
          yielded_[i] = 1;
        } else if (branch_[i] == Branch::Plastic) {
          branch_[i] = Branch::Elastic;
          last_plastic_end_ = t;
          log(t, "ring_unloaded", i, "crush rate reversed: elastic unloading");
        }
      }
      if (fired[4 * i + 1] < 0 && branch_[i] == Branch::Elastic) {
        branch_[i] = Branch::Open;
        log(t, "contact_opened", i, "ring force fell to zero (no tension)");
      } else if (fired[4 * i + 1] > 0 && branch_[i] == Branch::Open) {
        branch_[i] = Branch::Elastic;
        log(t, "contact_closed", i, "");
      }
      switched_[i] = branch_[i] != before;
      if (fired[4 * i + 2]) {
        const bool lock = fired[4 * i + 2] > 0;
        if (lock != static_cast<bool>(locked_[i])) {
          locked_[i] = lock;
          log(t, lock ? "ring_locked" : "ring_unlocked", i, "inner walls in contact at d - t");
        }
      }
    }
    if (fired[4 * n_] < 0 && arrest_time_ < 0.0) {
      arrest_time_ = t;
      log(t, "impactor_arrested", -1, free_end_ ? "impactor at the common velocity" : "impactor at rest");
    }
    (void)y;
    return EventAction::Continue;
  }

  // The run ends once the impactor has been arrested, no ring is flowing, and either no ring
  // can yield again with the energy left (kinetic relative to the centre of mass plus
  // elastic, below the elastic energy any ring needs to reach its backbone) or an elastic
  // round trip has passed without plastic flow.
  bool finished(double t, const double* y) override {
    if (arrest_time_ < 0.0) return false;
    for (auto b : branch_)
      if (b == Branch::Plastic) return false;
    double energy = 0.0, min_yield = 1e300, p = 0.0, m = 0.0;
    for (int k = 0; k < nm_; ++k) {
      energy += 0.5 * mass_[k] * y[nm_ + k] * y[nm_ + k];
      p += mass_[k] * y[nm_ + k];
      m += mass_[k];
    }
    if (free_end_) energy -= 0.5 * p * p / m;
    for (int i = 0; i < n_; ++i) {
      energy += elastic_energy(y, i);
      const double pb = law_.backbone(y[2 * nm_ + i]);
      min_yield = std::min(min_yield, 0.5 * pb * pb / k_);
    }
    if (energy < min_yield) return true;
    return t - std::max(last_plastic_end_, arrest_time_) > settle_time_;
  }

  double elastic_energy(const double* y, int i) const {
    const double dl = delta(y, i);
    const double e = dl - y[2 * nm_ + i];
    double w = branch_[i] == Branch::Open ? 0.0 : 0.5 * k_ * e * e;
    if (locked_[i]) w += 0.5 * klock_ * (dl - dl_) * (dl - dl_);
    return w;
  }

  void record(double t, const std::vector<double>& y, ChainHistory& h) const {
    const double* s = y.data();
    h.time_s.push_back(t);
    h.impactor_displacement_m.push_back(s[0]);
    h.impactor_velocity_m_s.push_back(s[nm_]);
    // Force on the impactor body: its share M/m_0 of the force that decelerates mass 0.
    h.impactor_force_n.push_back(in_.impactor_mass_kg / mass_[0] * ring_force(s, 0));
    double ke = 0.0, el = 0.0, pl = 0.0;
    for (int k = 0; k < nm_; ++k) ke += 0.5 * mass_[k] * s[nm_ + k] * s[nm_ + k];
    for (int i = 0; i < n_; ++i) {
      h.ring_crush_m[i].push_back(delta(s, i));
      el += elastic_energy(s, i);
      const double w = law_.plastic_energy(s[2 * nm_ + i]);
      h.ring_plastic_j[i].push_back(w);
      pl += w;
    }
    h.kinetic_j.push_back(ke);
    h.elastic_j.push_back(el);
    h.plastic_j.push_back(pl);
    h.impact_loss_j.push_back(impact_loss_);
  }

  std::vector<double> initial_state() {
    std::vector<double> y(size(), 0.0);
    // Perfectly plastic first contact of M with the top half of ring 1.
    const double M = in_.impactor_mass_kg, V = in_.impactor_velocity_m_s;
    y[nm_] = M * V / mass_[0];
    impact_loss_ = 0.5 * M * V * V - 0.5 * mass_[0] * y[nm_] * y[nm_];
    return y;
  }

  double arrest_time() const { return arrest_time_; }
  std::vector<ChainEvent> events;

 private:
  void log(double t, const char* kind, int ring, std::string detail) {
    events.push_back({t, kind, ring, std::move(detail)});
  }
 private:
  ChainInput in_;
  RingLaw law_;
  int n_ = 0, nm_ = 0;
  bool free_end_ = false, tension_ = false;
  std::vector<double> mass_;
  double k_ = 0, klock_ = 0, p0_ = 0, dl_ = 0, vref_ = 1, v_common_ = 0, settle_time_ = 0;
  std::vector<Branch> branch_;
  std::vector<char> locked_, yielded_, switched_;
  double impact_loss_ = 0.0;
  double arrest_time_ = -1.0, last_plastic_end_ = -1.0;
  std::vector<double> jac_;
};

}  // namespace

ChainResult simulate_level0(const ChainInput& input, const HybridOptions& options, bool record_history) {
  input.validate();
  if (!(input.ring.elastic_stiffness_n_m > 0))
    throw std::invalid_argument("Level 0 needs a positive elastic ring stiffness");
  if (!(input.ring.lock_stiffness_n_m > 0))
    throw std::invalid_argument("Level 0 needs a positive lock-up stiffness");
  Level0Chain model(input);
  std::vector<double> y;
  ChainResult result = run_chain(model, input, options, record_history, y);
  const int permanent = 2 * (input.rings + (input.far_end == ChainFarEnd::Free ? 1 : 0));
  for (int i = 0; i < input.rings; ++i) result.final_permanent_crush_m.push_back(y[permanent + i]);
  return result;
}

}  // namespace ringcrush::hinge
