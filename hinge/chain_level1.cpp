// Level 1: a chain of rigid–plastic DeRuntz–Hodge/Redwood rings with their distributed
// inertia J(φ), separated by plates (THEORY §4.4 "Level 1", §1.3).
//
// Generalised coordinates: the mechanism angles φ_i (crush δ_i = d sin φ_i) and, for a free
// far end, the displacement u_N of the far side of the last ring. Body b (impactor b = 0,
// plates 1…N−1, far side N) moves at u̇_b = u̇_N + Σ_{j≥b} d cos φ_j φ̇_j; ring i's centre
// at the mean of its two sides. Lagrange's equations (each velocity coefficient depends on
// its own φ_j only, so the Christoffel terms reduce to the ȧ·q̇ products):
//
//   𝓜(q) q̈ = −Σ_b m_b a_b (ȧ_b·q̇) − Σ_i m_r w_i (ẇ_i·q̇) − ½ J′(φ_i) φ̇_i² − λ,
//
// λ_i = 8M0 h(φ_i) while ring i crushes (φ̇_i > 0); a rigid ring has φ̇_i = 0 and a reaction
// 0 ≤ λ_i ≤ 8M0 h(φ_i); a locked ring (φ_i = φ_L, inner walls in contact) has φ̇_i = 0 and
// any λ_i ≥ 0. Which rings crush is a complementarity problem, solved at events (a ring
// stops, a rigid ring reaches its collapse force) — not a penalty. The first contact and
// every lock-up are perfectly plastic impacts (velocity-level complementarity); their
// kinetic-energy losses are booked as impact energy.
//
// Optional elastic series spring (k_s, no tension) between the impactor and ring 1: the
// impactor then has its own coordinate x, ring 1's top face is massless, the spring force
// F_s = k_s⟨x − u_0(q)⟩ acts on x and, through ∂u_0/∂φ_j = d cos φ_j, on the rings; contact
// opening/closing of the spring is an event. Without it the first contact is a plastic impact.
//
// DAE form (IDA): y = [q, q̇, λ], λ algebraic, residual rows q′ − q̇, 𝓜 q̇′ − b + λ and, per
// ring, λ_i − 8M0h(φ_i) (crushing) or φ̈_i (rigid, locked); IDACalcIC finds λ at restarts.
// ODE form (Odeint): q̈ from the same equations with λ eliminated; λ components idle.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "chain_1d.hpp"
#include "chain_run.hpp"
#include "mass_lcp.hpp"

namespace ringcrush::hinge {
namespace {

enum class RingMode { Crushing, Rigid, Locked };

class Level1Chain final : public HybridSystem {
 public:
  explicit Level1Chain(const ChainInput& in) : in_(in), law_(in.ring) {
    n_ = in.rings;
    free_end_ = in.far_end == ChainFarEnd::Free;
    spring_ = in.impactor_spring_n_m > 0.0;
    nq_ = n_ + (free_end_ ? 1 : 0) + (spring_ ? 1 : 0);
    ix_ = nq_ - 1;
    body_mass_.assign(n_ + 1, in.joint == ChainJoint::Plates ? in.plate_mass_kg : 0.0);
    body_mass_[0] = spring_ ? 0.0 : in.impactor_mass_kg;
    body_mass_[n_] = 0.0;  // target, or nothing behind the last ring
    d_ = law_.mean_diameter();
    phi_lock_ = law_.lock_angle();
    vref_ = in.impactor_velocity_m_s;
    mode_.assign(n_, RingMode::Rigid);
    mode_before_ = mode_;
    for (int i = 0; i < n_; ++i) strength_.push_back(1.0 + tie_break * i);
    double total = in.impactor_mass_kg + n_ * law_.mass_kg;
    for (int b = 1; b < n_; ++b) total += body_mass_[b];
    v_common_ = free_end_ ? in.impactor_mass_kg * vref_ / total : 0.0;
    m_.resize(nq_, nq_);
    b_.resize(nq_);
    a_ = Eigen::VectorXd::Zero(nq_);
    w_ = Eigen::VectorXd::Zero(nq_);
  }

  // Identical rigid rings in series that carry the same force reach their collapse force at
  // the same instant: which of them crushes is then decided by round-off alone. The tie is
  // broken deterministically, and physically (the ring nearer the impactor is loaded first
  // through any real compliance), by weakening ring i by a relative 1e-9·i.
  static constexpr double tie_break = 1e-9;
  double collapse_force(int i, double phi) const { return strength_[i] * law_.generalized_force(phi); }

  std::size_t size() const override { return 2 * nq_ + n_; }
  std::size_t root_count() const override { return 3 * n_ + 1 + (spring_ ? 1 : 0); }

  // Position of ring 1's top face and the series spring's force.
  double top_position(const double* q) const {
    double u = free_end_ ? q[n_] : 0.0;
    for (int j = 0; j < n_; ++j) u += d_ * std::sin(q[j]);
    return u;
  }
  double spring_force(const double* q) const {
    if (!spring_ || spring_open_) return 0.0;
    return in_.impactor_spring_n_m * (q[ix_] - top_position(q));
  }
  std::vector<double> differential_mask() const override {
    std::vector<double> id(size(), 1.0);
    for (int i = 0; i < n_; ++i) id[2 * nq_ + i] = 0.0;
    return id;
  }

  // 𝓜(q) and b(q, q̇) (the right-hand side without λ).
  void assemble(const double* q, const double* qd) {
    m_.setZero();
    b_.setZero();
    std::vector<double>& c = c_;
    std::vector<double>& sq = sq_;  // d sin φ_j φ̇_j²
    c.resize(n_);
    sq.resize(n_);
    for (int j = 0; j < n_; ++j) {
      c[j] = d_ * std::cos(q[j]);
      sq[j] = d_ * std::sin(q[j]) * qd[j] * qd[j];
    }
    // Rank-one updates m · v vᵀ on the trailing block [lo, nq)², where v is non-zero.
    auto add_outer = [&](double m, const Eigen::VectorXd& v, int lo) {
      double* md = m_.data();
      for (int k = lo; k < nq_; ++k) {
        const double mk = m * v(k);
        double* col = md + static_cast<std::ptrdiff_t>(k) * nq_;
        for (int j = lo; j < nq_; ++j) col[j] += mk * v(j);
      }
    };
    // Bodies: a_b[j] = c_j for j ≥ b (and 1 for u_N); ȧ_b·q̇ = −Σ_{j≥b} d sin φ_j φ̇_j².
    double tail = 0.0;  // Σ_{j≥b} sq_j, built from the far end
    for (int b = n_; b >= 0; --b) {
      if (b < n_) tail += sq[b];
      const double mb = body_mass_[b];
      if (mb == 0.0) continue;
      for (int j = b; j < n_; ++j) a_(j) = c[j];
      if (free_end_) a_(n_) = 1.0;
      add_outer(mb, a_, b);
      for (int j = b; j < nq_; ++j) b_(j) += mb * tail * a_(j);  // −m a (ȧ·q̇) = +m a Σ sq
    }
    // Ring centres: w_i = (a_i + a_{i+1})/2.
    tail = 0.0;
    for (int i = n_ - 1; i >= 0; --i) {
      for (int j = i + 1; j < n_; ++j) w_(j) = c[j];
      w_(i) = 0.5 * c[i];
      if (free_end_) w_(n_) = 1.0;
      const double wdot = -(tail + 0.5 * sq[i]);
      add_outer(law_.mass_kg, w_, i);
      for (int j = i; j < nq_; ++j) b_(j) -= law_.mass_kg * wdot * w_(j);
      tail += sq[i];
    }
    if (spring_) {
      m_(ix_, ix_) += in_.impactor_mass_kg;
      const double fs = spring_force(q);
      b_(ix_) -= fs;
      for (int j = 0; j < n_; ++j) b_(j) += fs * c[j];
      if (free_end_) b_(n_) += fs;
    }
    for (int i = 0; i < n_; ++i) {
      m_(i, i) += law_.inertia(q[i]);
      b_(i) -= 0.5 * law_.inertia_derivative(q[i]) * qd[i] * qd[i];
    }
  }

  // Accelerations and ring forces in the current modes (after assemble()): rigid and
  // locked rings have φ̈ = 0, the rest solve 𝓜_FF q̈_F = (b − λ_crushing)_F; the rigid rings'
  // reactions follow from their rows. Preallocated buffers: this runs in every rhs.
  void accelerations(const double* q, Eigen::VectorXd& qdd, Eigen::VectorXd& lambda) {
    r_ = b_;
    lambda.setZero(n_);
    free_.clear();
    for (int i = 0; i < n_; ++i)
      if (mode_[i] == RingMode::Crushing) {
        lambda(i) = collapse_force(i, q[i]);
        r_(i) -= lambda(i);
        free_.push_back(i);
      }
    for (int j = n_; j < nq_; ++j) free_.push_back(j);
    qdd.setZero(nq_);
    free_solve_.solve(m_, r_, free_, qdd);
    for (int i = 0; i < n_; ++i)
      if (mode_[i] != RingMode::Crushing) lambda(i) = r_(i) - m_.row(i).dot(qdd);
  }

  void rhs(double, const double* y, double* f) override {
    const double* q = y;
    const double* qd = y + nq_;
    assemble(q, qd);
    accelerations(q, qdd_, lambda_);
    for (int j = 0; j < nq_; ++j) {
      f[j] = qd[j];
      f[nq_ + j] = qdd_(j);
    }
    for (int i = 0; i < n_; ++i) f[2 * nq_ + i] = 0.0;
  }

  void residual(double, const double* y, const double* yp, double* r) override {
    const double* q = y;
    const double* qd = y + nq_;
    const double* lambda = y + 2 * nq_;
    assemble(q, qd);
    Eigen::Map<const Eigen::VectorXd> qdd(yp + nq_, nq_);
    const Eigen::VectorXd mq = m_ * qdd;
    for (int j = 0; j < nq_; ++j) {
      r[j] = yp[j] - qd[j];
      r[nq_ + j] = mq(j) - b_(j) + (j < n_ ? lambda[j] : 0.0);
    }
    for (int i = 0; i < n_; ++i)
      r[2 * nq_ + i] = mode_[i] == RingMode::Crushing ? lambda[i] - collapse_force(i, q[i])
                                                      : yp[nq_ + i] / vref_ * d_;
  }

  // Per ring i: [3i] crushing: φ̇ d/V (stops when it falls to 0); rigid: margin to the
  // collapse force (starts crushing when it falls to 0); [3i+1] rigid or locked: the ring
  // force λ_i (tension when it falls below 0); [3i+2] crushing: φ_L − φ (lock-up).
  // Last: impactor velocity relative to the final common velocity (arrest).
  void event_roots(double, const double* y, double* g) override {
    const double* q = y;
    const double* qd = y + nq_;
    assemble(q, qd);
    accelerations(q, qdd_, lambda_);
    const Eigen::VectorXd& lambda = lambda_;
    for (int i = 0; i < n_; ++i) {
      const double gi = collapse_force(i, q[i]);
      g[3 * i] = mode_[i] == RingMode::Crushing ? qd[i] * d_ / vref_
                 : mode_[i] == RingMode::Rigid  ? (gi - lambda(i)) / gi
                                                : 1.0;
      g[3 * i + 1] = mode_[i] == RingMode::Crushing ? 1.0 : lambda(i) / gi;
      g[3 * i + 2] = mode_[i] == RingMode::Crushing ? phi_lock_ - q[i] : 1.0;
    }
    g[3 * n_] = (impactor_velocity(q, qd) - v_common_) / vref_;
    if (spring_)
      g[3 * n_ + 1] = in_.impactor_spring_n_m * (q[ix_] - top_position(q)) / law_.collapse_load();
  }

  double impactor_velocity(const double* q, const double* qd) const {
    if (spring_) return qd[ix_];
    double v = free_end_ ? qd[n_] : 0.0;
    for (int j = 0; j < n_; ++j) v += d_ * std::cos(q[j]) * qd[j];
    return v;
  }

  // After a restart every ring root is expected to grow away from zero: a crushing ring's
  // rate, a rigid ring's margin below collapse, its (compressive) force, the distance to lock.
  int root_departure(std::size_t r, int fired) const override {
    if (r == static_cast<std::size_t>(3 * n_)) return fired != 0 ? fired : (arrest_time_ < 0.0 ? 1 : 0);
    if (r == static_cast<std::size_t>(3 * n_ + 1)) return fired != 0 ? fired : (spring_open_ ? -1 : 1);
    // Ring roots: positive in every admissible state of the current mode. A root that
    // crossed without a mode change (a degenerate complementarity kept the ring rigid) must
    // grow again, or cross again and be re-examined.
    return 1;
  }

  EventAction on_event(double t, std::vector<double>& y, const std::vector<int>& fired) override {
    double* q = y.data();
    double* qd = y.data() + nq_;
    bool impact = false;
    mode_before_ = mode_;
    if (spring_ && fired[3 * n_ + 1] < 0 && !spring_open_) {
      spring_open_ = true;
      log(t, "contact_opened", -1, "impactor spring unloaded (no tension)");
    } else if (spring_ && fired[3 * n_ + 1] > 0 && spring_open_) {
      spring_open_ = false;
      log(t, "contact_closed", -1, "impactor spring");
    }
    // A rigid ring's force reaching zero as the series spring lets go is the unloading of
    // the whole (rigid, at rest) chain, not tension.
    if (spring_ && !spring_open_ && std::abs(spring_force(q)) < 1e-9 * law_.collapse_load()) {
      for (int i = 0; i < n_; ++i)
        if (fired[3 * i + 1] < 0) {
          spring_open_ = true;
          log(t, "contact_opened", -1, "impactor spring unloaded (no tension)");
          break;
        }
    }
    for (int i = 0; i < n_; ++i) {
      if (fired[3 * i + 1] < 0 && !(spring_ && spring_open_))
        throw std::runtime_error(fmt::format(
            "Level 1: ring {} would carry tension at t = {:.9g} s; contact separation is not "
            "modelled at Level 1 (use Level 0)", i + 1, t));
      if (fired[3 * i + 2] < 0 && mode_[i] == RingMode::Crushing) {
        mode_[i] = RingMode::Locked;
        q[i] = phi_lock_;
        impact = true;
        log(t, "ring_locked", i, "inner walls in contact: plastic impact");
      }
      if (fired[3 * i] < 0 && mode_[i] == RingMode::Crushing) {
        qd[i] = 0.0;
        mode_[i] = RingMode::Rigid;
        log(t, "ring_stopped", i, "crush rate fell to zero");
      }
    }
    if (fired[3 * n_] < 0 && arrest_time_ < 0.0) {
      arrest_time_ = t;
      log(t, "impactor_arrested", -1, free_end_ ? "impactor at the common velocity" : "impactor at rest");
    }
    if (impact) apply_impact(q, qd);
    std::vector<char> loaded(n_, 0);
    for (int i = 0; i < n_; ++i) loaded[i] = fired[3 * i] < 0 && mode_before_[i] == RingMode::Rigid;
    select_modes(q, qd, t, loaded);
    for (int i = 0; i < n_; ++i)
      if (mode_[i] == RingMode::Crushing) return EventAction::Continue;
    // With the series spring the impactor can still load the (rigid) chain: go on until it
    // has been arrested and the spring has let go.
    if (spring_ && !(arrest_time_ >= 0.0 && spring_open_)) return EventAction::Continue;
    if (arrest_time_ < 0.0) arrest_time_ = t;
    log(t, "chain_at_rest", -1, free_end_ ? "no ring crushes: rigid-body motion" : "no ring crushes");
    return EventAction::Stop;
  }

  // Perfectly plastic impact: the velocities after it minimise the kinetic energy of the
  // velocity change subject to φ̇ ≥ 0 (φ̇ = 0 for locked rings).
  void apply_impact(double* q, double* qd) {
    assemble(q, qd);
    Eigen::Map<Eigen::VectorXd> v(qd, nq_);
    const double before = 0.5 * v.dot(m_ * v);
    const Eigen::VectorXd p = m_ * v;
    std::vector<char> comp(nq_, 0), zero(nq_, 0);
    for (int i = 0; i < n_; ++i) {
      comp[i] = 1;
      zero[i] = mode_[i] == RingMode::Locked;
    }
    const auto lcp = solve_mass_lcp(m_, p, comp, zero);
    v = lcp.x;
    for (int i = 0; i < n_; ++i) {
      if (lcp.held[i] && mode_[i] != RingMode::Locked) mode_[i] = RingMode::Rigid;
      if (!lcp.held[i]) mode_[i] = RingMode::Crushing;
      if (lcp.held[i]) qd[i] = 0.0;
    }
    assemble(q, qd);
    impact_loss_ += before - 0.5 * v.dot(m_ * v);
  }

  // Acceleration-level complementarity for the rings at rest (not locked): each either
  // crushes (φ̈ ≥ 0, λ = 8M0h) or stays rigid (φ̈ = 0, λ ≤ 8M0h).
  void select_modes(const double* q, const double* qd, double t, const std::vector<char>& loaded = {}) {
    assemble(q, qd);
    Eigen::VectorXd r = b_;
    std::vector<char> comp(nq_, 0), zero(nq_, 0);
    for (int i = 0; i < n_; ++i) {
      if (mode_[i] == RingMode::Locked) {
        zero[i] = 1;
        continue;
      }
      r(i) -= collapse_force(i, q[i]);
      if (mode_[i] == RingMode::Rigid || qd[i] <= 0.0) comp[i] = 1;
    }
    // A rigid ring whose force has just reached its collapse force crushes in a tie; a ring
    // that has just stopped stays rigid in a tie.
    std::vector<char> prefer(nq_, 0);
    for (int i = 0; i < n_ && !loaded.empty(); ++i) prefer[i] = loaded[i];
    const auto lcp = solve_mass_lcp(m_, r, comp, zero, prefer);
    for (int i = 0; i < n_; ++i) {
      if (!comp[i]) continue;
      const RingMode next = lcp.held[i] ? RingMode::Rigid : RingMode::Crushing;
      if (next != mode_[i]) {
        if (next == RingMode::Crushing) log(t, "ring_crushing", i, "collapse load reached");
        mode_[i] = next;
      }
    }
  }

  std::vector<double> initial_state() {
    std::vector<double> y(size(), 0.0);
    double* q = y.data();
    double* qd = y.data() + nq_;
    if (spring_) {
      // The spring starts unloaded: the impactor moves, every ring is at rest and rigid.
      qd[ix_] = in_.impactor_velocity_m_s;
      for (int i = 0; i < n_; ++i) mode_[i] = RingMode::Rigid;
      impact_loss_ = 0.0;
      select_modes(q, qd, 0.0);
      Eigen::VectorXd qdd, lambda;
      assemble(q, qd);
      accelerations(q, qdd, lambda);
      for (int i = 0; i < n_; ++i) y[2 * nq_ + i] = lambda(i);
      return y;
    }
    // First contact: the impactor's momentum M V a_0 shared by a plastic impact.
    assemble(q, qd);
    Eigen::VectorXd a0 = Eigen::VectorXd::Zero(nq_);
    for (int j = 0; j < n_; ++j) a0(j) = d_;
    if (free_end_) a0(n_) = 1.0;
    const double M = in_.impactor_mass_kg, V = in_.impactor_velocity_m_s;
    const Eigen::VectorXd p = M * V * a0;
    std::vector<char> comp(nq_, 0), zero(nq_, 0);
    for (int i = 0; i < n_; ++i) comp[i] = 1;
    const auto lcp = solve_mass_lcp(m_, p, comp, zero);
    for (int j = 0; j < nq_; ++j) qd[j] = lcp.x(j);
    for (int i = 0; i < n_; ++i) mode_[i] = lcp.held[i] ? RingMode::Rigid : RingMode::Crushing;
    const Eigen::Map<Eigen::VectorXd> v(qd, nq_);
    impact_loss_ = 0.5 * M * V * V - 0.5 * v.dot(m_ * v);
    select_modes(q, qd, 0.0);
    // λ: consistent values (IDACalcIC refines them).
    Eigen::VectorXd qdd, lambda;
    assemble(q, qd);
    accelerations(q, qdd, lambda);
    for (int i = 0; i < n_; ++i) y[2 * nq_ + i] = lambda(i);
    return y;
  }

  void record(double t, const std::vector<double>& y, ChainHistory& h) {
    const double* q = y.data();
    const double* qd = y.data() + nq_;
    assemble(q, qd);
    Eigen::VectorXd qdd, lambda;
    accelerations(q, qdd, lambda);
    double u0 = free_end_ ? q[n_] : 0.0, v0 = free_end_ ? qd[n_] : 0.0, a0 = free_end_ ? qdd(n_) : 0.0;
    double pl = 0.0;
    for (int j = 0; j < n_; ++j) {
      const double c = std::cos(q[j]), s = std::sin(q[j]);
      u0 += d_ * s;
      v0 += d_ * c * qd[j];
      a0 += d_ * (c * qdd(j) - s * qd[j] * qd[j]);
      h.ring_crush_m[j].push_back(d_ * s);
      const double w = strength_[j] * law_.plastic_energy_at_angle(q[j]);
      h.ring_plastic_j[j].push_back(w);
      pl += w;
    }
    Eigen::Map<const Eigen::VectorXd> v(qd, nq_);
    h.time_s.push_back(t);
    double elastic = 0.0;
    if (spring_) {
      const double fs = spring_force(q);
      h.impactor_displacement_m.push_back(q[ix_]);
      h.impactor_velocity_m_s.push_back(qd[ix_]);
      h.impactor_force_n.push_back(fs);
      elastic = 0.5 * fs * fs / in_.impactor_spring_n_m;
    } else {
      h.impactor_displacement_m.push_back(u0);
      h.impactor_velocity_m_s.push_back(v0);
      h.impactor_force_n.push_back(-in_.impactor_mass_kg * a0);
    }
    h.kinetic_j.push_back(0.5 * v.dot(m_ * v));
    h.elastic_j.push_back(elastic);
    h.plastic_j.push_back(pl);
    h.impact_loss_j.push_back(impact_loss_);
  }

  double arrest_time() const { return arrest_time_; }
  std::vector<ChainEvent> events;

 private:
  void log(double t, const char* kind, int ring, std::string detail) {
    events.push_back({t, kind, ring, std::move(detail)});
  }

  ChainInput in_;
  RingLaw law_;
  int n_ = 0, nq_ = 0, ix_ = -1;
  bool free_end_ = false, spring_ = false, spring_open_ = false;
  std::vector<double> body_mass_;
  double d_ = 0, phi_lock_ = 0, vref_ = 1, v_common_ = 0;
  std::vector<RingMode> mode_, mode_before_;
  std::vector<double> strength_;
  double impact_loss_ = 0.0, arrest_time_ = -1.0;
  Eigen::MatrixXd m_;
  Eigen::VectorXd b_, a_, w_, r_, qdd_, lambda_;
  FreeMassSolve free_solve_;
  std::vector<Eigen::Index> free_;
  std::vector<double> c_, sq_;
};

}  // namespace

ChainResult simulate_level1(const ChainInput& input, const HybridOptions& options, bool record_history) {
  input.validate();
  Level1Chain model(input);
  std::vector<double> y;
  ChainResult result = run_chain(model, input, options, record_history, y);
  result.final_permanent_crush_m = result.final_crush_m;
  return result;
}

}  // namespace ringcrush::hinge
