// Level 3 with ring inertia (issue 7 item 2, THEORY §4.4 "Level 1" and §4.5): the Level 3
// chain of the thesis's few-hinge mechanisms (§4.2.3: Uniform DeRuntz–Hodge, Wrap of the arc
// C–F–B, Bottom, E–C–B; their laws, tables and hardening exactly as the massless chain uses
// them, hinge/level3_chain.hpp) whose rings have mass, so that each ring carries its own force
// from the dynamics instead of one common F.
//
// Generalised coordinates: the ring crushes δ_i (fixed target). Body b (impactor b = 0, the
// joint between ring b and b + 1) moves at u̇_b = Σ_{j≥b} δ̇_j; ring i's mass m_r sits at its
// centre, ẇ_i = ½ δ̇_i + Σ_{j>i} δ̇_j, as in Level 1. The mechanism's own distributed
// inertia: in the Uniform mode Level 1's J(φ) (THEORY §1.3), in δ the generalised mass
// μ(δ) = J(φ)/(d cos φ)²; in the Wrap, Bottom and E–C–B modes it is neglected (μ = 0: only the
// centre translates; a stated simplification — the kinetic energy ½μδ̇² of a ring leaving the
// Uniform mode while it crushes is booked as an impact loss). With constant body
// coefficients Lagrange's equations are
//
//   𝓜(δ) δ̈ = −½ μ′(δ_i) δ̇_i² e_i − λ,   𝓜 = M 11ᵀ + m_r Σ_i w_i w_iᵀ + diag μ_i,
//
// λ_i = P_i (the load of ring i's current mechanism) while ring i crushes (δ̇_i > 0); a
// rigid ring has δ̇_i = 0 and a reaction λ_i up to the least load of its admissible
// mechanisms; a locked ring (every mechanism at its limit) any λ_i ≥ 0. Which rings crush is
// the complementarity problem of Level 1 (hinge/mass_lcp.hpp) at events; the first contact,
// and a ring locking while it moves, are plastic impacts whose losses are booked.
//
// Mode selection by least load, per ring: a rigid ring starts crushing in its admissible
// mechanism of least load when its force reaches that load; a crushing ring switches when
// another admissible mechanism of its own becomes cheaper than the current one (e.g. the
// wrap, whose load falls, against the hardening uniform mechanism). The wrap of ring i
// reinforces ring i + 1 (Bottom, or E–C–B when cheaper by the massless chain's margin).
// The lower-bound statics check (hinge/level3_statics.hpp) runs on each ring under its own
// two contact forces — the force from above F_i, from below F_i − m_r ẅ_i — and the
// d'Alembert load of its mass (the centre's ẅ_i and, in the Uniform mode, the DeRuntz–Hodge
// relative motion whose kinetic energy is J(φ)): Level3RingLoads, recorded per output state.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "chain_1d.hpp"
#include "level3_chain.hpp"
#include "level3_statics.hpp"
#include "mass_lcp.hpp"
#include "ring_laws.hpp"

namespace ringcrush::hinge {
namespace {

using level3_detail::kE;
using level3_detail::kL;
using level3_detail::kM;
using level3_detail::kU;
using level3_detail::kW;

enum class RingMotion { Crushing, Rigid, Locked };

class Level3InertialChain final : public level3_detail::Level3Chain {
 public:
  Level3InertialChain(const Level3Input& in, WrapMechanism wrap)
      : Level3Chain(in, std::move(wrap)), base_size_(static_cast<int>(Level3Chain::size())) {
    inertia_scale_ = 2.0 / std::numbers::pi * in.ring_mass_kg * 0.25 * d_ * d_;  // J = (2/π) m_r R² K
    motion_.assign(n_, RingMotion::Rigid);
    mech_.assign(n_, 0);
    own_cache_.assign(static_cast<std::size_t>(n_), OwnMass{});
    load_cache_.assign(static_cast<std::size_t>(m_), SlotLoad{});
    margin_cache_.assign(static_cast<std::size_t>(m_), SlotMargin{});
    for (int i = 0; i < n_; ++i) {
      mech_[i] = kM * i + kU;
      strength_.push_back(1.0 + tie_break * i);
    }
    const auto n = static_cast<Eigen::Index>(n_);
    m0_ = Eigen::MatrixXd::Constant(n, n, in.impactor_mass_kg);
    Eigen::VectorXd w(n);
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < n_; ++j) w(j) = j < i ? 0.0 : j == i ? 0.5 : 1.0;
      m0_ += in.ring_mass_kg * w * w.transpose();
    }
    mm_ = m0_;
    mm_mu_.assign(static_cast<std::size_t>(n_), 0.0);
    b_ = Eigen::VectorXd::Zero(n);
    vref_ = in.impactor_velocity_m_s;
  }

  // As in Level 1 (chain_level1.cpp): identical rigid rings that reach their load at the same
  // instant are told apart by a relative 1e-9·i, the ring nearer the impactor first.
  static constexpr double tie_break = 1e-9;

  std::size_t size() const override { return static_cast<std::size_t>(base_size_ + n_); }
  std::size_t root_count() const override { return static_cast<std::size_t>(m_ + 2 * n_ + 1); }
  int vel(int i) const { return base_size_ + i; }

  // --- mechanics -------------------------------------------------------------------
  // Kept per mechanism slot for the crush it was evaluated at (load() reads y only there,
  // crush_of(y, j)): between events only a crushing ring's current mechanism moves, and the
  // root functions, called at every IDA step, re-evaluated the other ~20 slots' held loads
  // (asin, cos, the E–C–B onset pose). Bypassed while an event changes the mechanism flags,
  // ψ0 and the E–C–B tables the loads also depend on, and cleared after it (EventScope).
  double ring_load(const double* y, int j) const {
    if (in_event_) return strength_[j / kM] * load(y, j);
    auto& c = load_cache_[static_cast<std::size_t>(j)];
    const double crush = y[state(j)];
    if (c.valid && c.crush == crush) return c.load;
    c = {true, crush, strength_[j / kM] * load(y, j)};
    return c.load;
  }
  // The same for a slot's travel left (margin(): its ring's three mechanism crushes, and for
  // the bottom mechanism ψ through asin and sin), read by every root evaluation.
  double ring_margin(const double* y, int j) const {
    if (in_event_) return margin(y, j);
    auto& c = margin_cache_[static_cast<std::size_t>(j)];
    const double* q = y + state(kM * (j / kM));  // the ring's uniform, wrap and bottom / E–C–B crushes
    if (c.valid && c.crush[0] == q[0] && c.crush[1] == q[1] && c.crush[2] == q[2]) return c.margin;
    c = {true, {q[0], q[1], q[2]}, margin(y, j)};
    return c.margin;
  }
  struct EventScope {
    explicit EventScope(Level3InertialChain& c) : chain(c) { chain.in_event_ = true; }
    ~EventScope() {
      chain.in_event_ = false;
      for (auto& e : chain.load_cache_) e.valid = false;
      for (auto& e : chain.margin_cache_) e.valid = false;
    }
    Level3InertialChain& chain;
  };
  // Ring i's admissible mechanism of least load with travel left (−1: none); E–C–B replaces
  // the bottom mechanism only when cheaper by half the massless chain's switch margin.
  int least(const double* y, int i) const {
    int best = -1;
    double pbest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kM; ++k) {
      const int j = kM * i + k;
      if (!available(j) || margin(y, j) <= 1e-9 * d_) continue;
      const double p = load(y, j) * (1.0 + 0.5 * switch_margin(j));
      if (p < pbest) {
        pbest = p;
        best = j;
      }
    }
    return best;
  }
  bool uniform_inertia(int i) const { return mech_[i] % kM == kU && !wrap_started_[i] && !reinforced_[i]; }
  // μ_i = J(φ)/(d cos φ)² and dμ/dδ in the Uniform mode (δ = d sin φ), 0 otherwise.
  // Kept per ring for the last uniform crush it was evaluated at: the trigonometry of J(φ)
  // was a quarter of a run's instructions, and most calls (the rigid rings, the root
  // functions at a step's end) repeat a crush.
  void own_mass(const double* y, int i, double& mu, double& dmu) const {
    mu = dmu = 0.0;
    if (!uniform_inertia(i) || in_.ring_mass_kg == 0.0) return;
    auto& c0 = own_cache_[static_cast<std::size_t>(i)];
    const double crush = y[state(kM * i + kU)];
    if (crush == c0.crush) {
      mu = c0.mu;
      dmu = c0.dmu;
      return;
    }
    const Quadrant q = quadrant(y, i);
    const double dc = d_ * q.c;
    const double J = inertia_scale_ * dh_factor(q), Jp = inertia_scale_ * dh_factor_slope(q);
    mu = J / (dc * dc);
    dmu = (Jp / (dc * dc) + 2.0 * J * q.s / (dc * dc * q.c)) / dc;
    c0 = {crush, mu, dmu};
  }
  // The Uniform mode's quadrant angle φ with sin φ = δ/d and cos φ = √(1 − sin²φ) taken from
  // the crush (one asin instead of asin, then sin and cos of φ three times: J, J′ and μ;
  // h52), and THEORY §1.3's K(φ), K′(φ) = 4 sin φ (1 − sin φ) − π sin φ cos φ on them.
  struct Quadrant {
    double phi, s, c;
  };
  Quadrant quadrant(const double* y, int i) const {
    const double s = std::clamp(crush_of(y, kM * i + kU) / d_, 0.0, 1.0);
    return {std::asin(s), s, std::sqrt((1.0 - s) * (1.0 + s))};
  }
  static double dh_factor(const Quadrant& q) {
    return (2.0 + q.c * q.c) * (0.5 * std::numbers::pi - q.phi) - 4.0 * q.c + 2.0 * q.s * q.c + q.phi * q.c * q.c;
  }
  static double dh_factor_slope(const Quadrant& q) {
    return 4.0 * q.s * (1.0 - q.s) - std::numbers::pi * q.s * q.c;
  }
  // 𝓜 differs from the constant part m0_ only on the diagonal, by μ_i: a diagonal entry is
  // rewritten (m0_ + μ, as ever) only when its μ_i has changed since the last call — between
  // events only a crushing Uniform ring's does.
  void assemble(const double* y) {
    b_.setZero();
    for (int i = 0; i < n_; ++i) {
      double mu, dmu;
      own_mass(y, i, mu, dmu);
      const double v = y[vel(i)];
      auto& held = mm_mu_[static_cast<std::size_t>(i)];
      if (mu != held) {
        mm_(i, i) = m0_(i, i) + mu;
        held = mu;
      }
      b_(i) -= 0.5 * dmu * v * v;
    }
  }
  double kinetic(const double* y) {
    assemble(y);
    const Eigen::Map<const Eigen::VectorXd> v(y + base_size_, n_);
    return 0.5 * v.dot(mm_ * v);
  }
  // Accelerations and ring forces in the current motions (after assemble()).
  void accelerations(const double* y) {
    r_ = b_;
    lambda_.setZero(n_);
    free_.clear();
    for (int i = 0; i < n_; ++i)
      if (motion_[i] == RingMotion::Crushing) {
        lambda_(i) = ring_load(y, mech_[i]);
        r_(i) -= lambda_(i);
        free_.push_back(i);
      }
    qdd_.setZero(n_);
    free_solve_.solve(mm_, r_, free_, qdd_);
    for (int i = 0; i < n_; ++i)
      if (motion_[i] != RingMotion::Crushing) lambda_(i) = r_(i) - mm_.row(i).dot(qdd_);
  }

  void rhs(double, const double* y, double* f) override {
    std::fill(f, f + size(), 0.0);
    assemble(y);
    accelerations(y);
    f[0] = y[1];
    for (int i = 0; i < n_; ++i) {
      const double v = y[vel(i)];
      f[vel(i)] = qdd_(i);
      f[1] += qdd_(i);
      if (motion_[i] == RingMotion::Crushing) {
        f[state(mech_[i])] += v;
        f[3] += lambda_(i) * v;
      }
    }
  }
  void residual(double t, const double* y, const double* yp, double* r) override {
    rhs(t, y, r);
    const std::size_t n = size();
    for (std::size_t k = 0; k < n; ++k) r[k] = yp[k] - r[k];
  }

  // IDA's Jacobian ∂F/∂y + cj ∂F/∂y′ = cj I − ∂f/∂y, analytic. f depends only on the
  // impactor velocity (f₀ = y₁) and, per crushing ring k, its crush rate v_k and its
  // mechanism's crush δ_k (a rigid or locked ring's crush moves only its own reaction). With
  // 𝓜_CC q̈_C = r_C over the crushing rings C, r_k = −½ μ′_k v_k² − λ_k and λ_k = P_k(δ_k):
  //   ∂q̈_C/∂v_k = −μ′_k v_k z_k,   ∂q̈_C/∂δ_k = −(½ μ″_k v_k² + P′_k + μ′_k q̈_k) z_k,
  // z_k = 𝓜_CC⁻¹ e_k (𝓜 depends on δ_k through μ_k on its diagonal); f₁ = Σ q̈, f_δk = v_k,
  // f₃ = Σ λ_k v_k. One solve per crushing ring on the kept factor instead of the 1 + 2 ×
  // (rings crushing) right-hand sides of difference quotients (h48: 8 % of the run);
  // checked against them by level3_inertial_jacobian_check().
  bool has_jacobian() const override { return true; }
  void jacobian(double, double cj, const double* y, const double*, JacobianSink& jac) override {
    const std::size_t n = size();
    for (std::size_t k = 0; k < n; ++k) jac.set(k, k, cj);
    jac.set(0, 1, -1.0);
    assemble(y);
    accelerations(y);
    const auto nf = static_cast<Eigen::Index>(free_.size());
    Eigen::VectorXd e = Eigen::VectorXd::Zero(nf);
    for (Eigen::Index p = 0; p < nf; ++p) {
      const int k = static_cast<int>(free_[static_cast<std::size_t>(p)]);
      e.setZero();
      e(p) = 1.0;
      const Eigen::VectorXd z = free_solve_.solve_free(e);
      double mu, dmu;
      own_mass(y, k, mu, dmu);
      const double v = y[vel(k)], dload = strength_[k] * slope(y, mech_[k]);
      const double a = -dmu * v, b = -(0.5 * own_mass_curvature(y, k) * v * v + dload + dmu * qdd_(k));
      const auto cv = static_cast<std::size_t>(vel(k)), cd = static_cast<std::size_t>(state(mech_[k]));
      for (Eigen::Index q = 0; q < nf; ++q) {
        const auto row = static_cast<std::size_t>(vel(static_cast<int>(free_[static_cast<std::size_t>(q)])));
        jac.set(row, cv, (row == cv ? cj : 0.0) - a * z(q));
        jac.set(row, cd, -b * z(q));
      }
      jac.set(1, cv, -a * z.sum());
      jac.set(1, cd, -b * z.sum());
      jac.set(cd, cv, -1.0);
      jac.set(3, cv, -lambda_(k));
      jac.set(3, cd, -dload * v);
    }
  }
  // μ″(δ) in the Uniform mode (0 otherwise): with g(φ) = J/(d cos φ)², μ = g(φ(δ)) and
  // dφ/dδ = 1/(d cos φ), μ″ = (g″ + g′ tan φ)/(d cos φ)², g′ = (J′ + 2J tan φ)/(d cos φ)²,
  // g″ = (J″ + 4J′ tan φ + 4J tan²φ + 2J/cos²φ)/(d cos φ)² (THEORY §1.3's J(φ)).
  double own_mass_curvature(const double* y, int i) const {
    if (!uniform_inertia(i) || in_.ring_mass_kg == 0.0) return 0.0;
    const Quadrant q = quadrant(y, i);
    const double tn = q.s / q.c, dc2 = d_ * q.c * d_ * q.c;
    const double J = inertia_scale_ * dh_factor(q), Jp = inertia_scale_ * dh_factor_slope(q);
    const double Jpp = inertia_scale_ * dh_inertia_factor_second_derivative(q.phi);
    const double g1 = (Jp + 2.0 * J * tn) / dc2;
    const double g2 = (Jpp + 4.0 * Jp * tn + 4.0 * J * tn * tn + 2.0 * J / (q.c * q.c)) / dc2;
    return (g2 + g1 * tn) / dc2;
  }

  // The same Jacobian by one-sided second-order difference quotients of rhs() in the columns
  // f depends on, cj = 0 (−∂f/∂y), for level3_inertial_jacobian_check(): h = ∛ε × the
  // column's scale (forward only: a crush does not go below 0). A crush column is left out
  // (all zero) when its mechanism has less than 2h of travel left: its load table ends there
  // (held constant beyond), the analytic column has the table's end slope.
  void jacobian_by_differences(double t, const double* y, JacobianSink& jac) {
    const std::size_t n = size();
    std::vector<double> f0(n), f1(n), f2(n), yd(y, y + n);
    rhs(t, y, f0.data());
    jac.set(0, 1, -1.0);
    auto column = [&](int c, double scale, double travel) {
      const auto k = static_cast<std::size_t>(c);
      const double h = std::cbrt(std::numeric_limits<double>::epsilon()) * std::max(std::abs(y[k]), scale);
      if (travel < 2.0 * h) return;
      yd[k] = y[k] + h;
      rhs(t, yd.data(), f1.data());
      yd[k] = y[k] + 2.0 * h;
      rhs(t, yd.data(), f2.data());
      yd[k] = y[k];
      for (std::size_t r = 0; r < n; ++r) {
        const double d = (-3.0 * f0[r] + 4.0 * f1[r] - f2[r]) / (2.0 * h);
        if (d != 0.0) jac.set(r, k, -d);
      }
    };
    for (int i = 0; i < n_; ++i) {
      if (motion_[i] != RingMotion::Crushing) continue;
      column(vel(i), 1e-3 * vref_, std::numeric_limits<double>::infinity());
      column(state(mech_[i]), 1e-3 * d_, margin(y, mech_[i]));
    }
  }
  bool crushing(int i) const { return motion_[i] == RingMotion::Crushing; }
  int mechanism(int i) const { return mech_[i]; }

  // Roots. Slot j = kM·i + k of ring i: crushing in j, its travel left (limit); crushing in
  // another, load_j − load_current (a cheaper mechanism); rigid, load_j − λ_i (the ring
  // starts to crush). [m + 2i]: crushing ring's rate (it stops); [m + 2i + 1]: a rigid or
  // locked ring's force (tension). Last: the impactor's velocity (arrest).
  void event_roots(double, const double* y, double* g) override {
    assemble(y);
    accelerations(y);
    std::fill(g, g + root_count(), 1.0);
    for (int i = 0; i < n_; ++i) {
      const int m = mech_[i];
      if (motion_[i] == RingMotion::Locked) {
        g[m_ + 2 * i + 1] = lambda_(i) / p0_;
        continue;
      }
      const bool crushing = motion_[i] == RingMotion::Crushing;
      const double reference = crushing ? ring_load(y, m) : lambda_(i);
      for (int k = 0; k < kM; ++k) {
        const int j = kM * i + k;
        if (crushing && j == m) g[j] = ring_margin(y, j) / d_;
        else if (available(j) && ring_margin(y, j) > 1e-9 * d_)
          g[j] = std::clamp((ring_load(y, j) - reference * (1.0 - switch_margin(j))) / p0_, -1e3, 1e3);
      }
      if (crushing) g[m_ + 2 * i] = y[vel(i)] / vref_;
      else g[m_ + 2 * i + 1] = lambda_(i) / p0_;
    }
    g[m_ + 2 * n_] = y[1] / vref_;
  }
  // Every ring root heads away from zero after a restart (Level 1's convention): a margin,
  // a mechanism left for a cheaper one, a rigid ring's margin below its load or its force.
  int root_departure(std::size_t r, int fired) const override {
    if (r == static_cast<std::size_t>(m_ + 2 * n_)) return fired != 0 ? fired : (arrest_time_ < 0.0 ? 1 : 0);
    return 1;
  }
  bool finished(double, const double*) override { return false; }

  // Between events only the impactor (displacement, velocity), the plastic work and each
  // crushing ring's velocity and current mechanism's crush move: a rigid or locked ring has
  // δ̈ = 0 and the crushes of the mechanisms not flowing, and the massless chain's F, have
  // zero rate (rhs()). IDA's state is then 3 + 2 × (rings crushing) of the 28 components
  // (HybridOptions::ida_reduced_state, set by simulate_level3_inertial).
  std::vector<std::size_t> live_components() const override {
    std::vector<std::size_t> live{0, 1, 3};
    for (int i = 0; i < n_; ++i)
      if (motion_[i] == RingMotion::Crushing) {
        live.push_back(static_cast<std::size_t>(state(mech_[i])));
        live.push_back(static_cast<std::size_t>(vel(i)));
      }
    std::sort(live.begin(), live.end());
    return live;
  }

  // The roots that can change sign before the next event (HybridOptions::ida_live_roots, set
  // by simulate_level3_inertial): per ring, the slots of its available mechanisms (a margin, or
  // a load against the current load or the reaction λ_i, which move), and its rate root while
  // crushing or its force root while rigid or locked; the impactor's velocity. The rest read
  // the fixed 1 of event_roots() until the next event changes the flags (19–29 of 37 on
  // Test 30 welded: 18 live while no ring is reinforced, 8 near the end): a locked ring's
  // slots, the unavailable ones, a rigid ring's rate root and a crushing ring's force root.
  std::vector<std::size_t> live_roots() const override {
    std::vector<std::size_t> live;
    for (int i = 0; i < n_; ++i) {
      if (motion_[i] != RingMotion::Locked)
        for (int k = 0; k < kM; ++k) {
          const int j = kM * i + k;
          if ((motion_[i] == RingMotion::Crushing && j == mech_[i]) || available(j))
            live.push_back(static_cast<std::size_t>(j));
        }
    }
    for (int i = 0; i < n_; ++i)
      live.push_back(static_cast<std::size_t>(m_ + 2 * i + (motion_[i] == RingMotion::Crushing ? 0 : 1)));
    live.push_back(static_cast<std::size_t>(m_ + 2 * n_));
    return live;
  }

  // The absolute tolerance is given in metres (crushes, the impactor's travel). A velocity
  // is measured against the impact speed V₀ (relative × V₀), not its own value, which is zero
  // when a ring starts from rest: the scalar 1e-10 m/s there held IDA's order-1 restarts to
  // ~1e-9 s steps (1106 → 788 steps at 27.7 m/s, 1967 → 1291 at 45). Not below the metres per
  // the time the impactor takes to cross a ring, d/V₀. The work (J) likewise against ½MV₀², not
  // below P₀ × the metres; F (N, held) P₀/d.
  std::vector<double> absolute_tolerances(double relative, double absolute) const override {
    const double v = std::max(relative * vref_, absolute * vref_ / d_);
    const double ke = 0.5 * in_.impactor_mass_kg * vref_ * vref_;
    std::vector<double> a(size(), absolute);
    a[1] = v;
    a[2] = absolute * p0_ / d_;
    a[3] = std::max(relative * ke, absolute * p0_);
    for (int i = 0; i < n_; ++i) a[static_cast<std::size_t>(vel(i))] = v;
    return a;
  }

  // --- events ----------------------------------------------------------------------
  // Ring i takes mechanism j (it crushes in it, or it is its least load while rigid): the
  // hinge and wrap bookkeeping of the massless chain's select().
  void take(double t, std::vector<double>& y, int i, int j) {
    mech_[i] = j;
    if (motion_[i] != RingMotion::Crushing) return;
    if (first_[j] < 0) {
      first_[j] = t;
      events_.push_back({t, "hinge_formed", i,
                         fmt::format("{} mechanism at P = {:.1f} N", to_string(static_cast<Level3Mode>(j % kM)),
                                     ring_load(y.data(), j))});
    }
    if (j % kM == kW && !wrap_started_[i]) {
      wrap_started_[i] = true;
      reinforced_[i + 1] = true;
      psi0_[i + 1] = uniform_phi(y.data(), i + 1);
      if (in_.hinge_e == Level3HingeE::ShearFree) theta_e_[i + 1] = shear_free_e(y.data(), i);
      events_.push_back({t, "mode_selected", i,
                         fmt::format("wrap over ring {} (wrap load {:.1f} N <= uniform {:.1f} N)", i + 2,
                                     load(y.data(), j), load(y.data(), kM * i + kU))});
      retake(t, y, i + 1);
    }
    if (j % kM == kE && !ecb_started_[i]) switch_to_ecb(t, y, i);
  }
  // Ring i's mechanism after its current one left (limit, or no longer admissible).
  void retake(double t, std::vector<double>& y, int i) {
    if (motion_[i] == RingMotion::Locked) return;
    const int k = least(y.data(), i);
    if (k < 0) {
      motion_[i] = RingMotion::Locked;
      events_.push_back({t, "ring_locked", i, "no admissible mechanism with travel left"});
      return;
    }
    if (k != mech_[i] || first_[k] < 0) take(t, y, i, k);
  }

  EventAction on_event(double t, std::vector<double>& y, const std::vector<int>& fired) override {
    const EventScope scope(*this);
    double* s = y.data();
    const double ke_before = kinetic(s);
    std::vector<char> loaded(n_, 0);
    for (int i = 0; i < n_; ++i) {
      if (fired[m_ + 2 * i + 1] < 0 && motion_[i] != RingMotion::Crushing)
        throw std::runtime_error(fmt::format(
            "Level 3 with inertia: ring {} would carry tension at t = {:.9g} s; contact separation is "
            "not modelled at Level 3", i + 1, t));
      const int m = mech_[i];
      if (motion_[i] == RingMotion::Rigid) {
        for (int k = 0; k < kM; ++k) loaded[i] = loaded[i] || fired[kM * i + k] != 0;
        continue;
      }
      if (motion_[i] != RingMotion::Crushing) continue;
      if (fired[m] != 0 && margin(s, m) <= 1e-9 * d_) {
        locked_[m] = true;
        events_.push_back({t, "ring_locked", i,
                           fmt::format("{} mechanism at its limit", to_string(static_cast<Level3Mode>(m % kM)))});
        retake(t, y, i);
      } else {
        bool cheaper = false;
        for (int k = 0; k < kM; ++k) cheaper = cheaper || (kM * i + k != m && fired[kM * i + k] != 0);
        if (cheaper) retake(t, y, i);
      }
      if (motion_[i] == RingMotion::Crushing && fired[m_ + 2 * i] < 0) {
        s[vel(i)] = 0.0;
        motion_[i] = RingMotion::Rigid;
        events_.push_back({t, "ring_stopped", i, "crush rate fell to zero"});
      }
    }
    if (fired[m_ + 2 * n_] < 0 && arrest_time_ < 0.0) {
      arrest_time_ = t;
      events_.push_back({t, "impactor_arrested", -1, "impactor at rest"});
    }
    settle(t, y, loaded);
    impact_loss_ += ke_before - kinetic(s);
    for (int i = 0; i < n_; ++i)
      if (motion_[i] == RingMotion::Crushing) return EventAction::Continue;
    if (arrest_time_ < 0.0) arrest_time_ = t;
    events_.push_back({t, "chain_at_rest", -1, "no ring crushes"});
    return EventAction::Stop;
  }

  // Plastic impact of the rings that locked while moving, then the acceleration-level
  // selection; the impactor velocity state follows the rings'.
  void settle(double t, std::vector<double>& y, const std::vector<char>& loaded) {
    for (int i = 0; i < n_; ++i)
      if (motion_[i] == RingMotion::Locked && y[vel(i)] != 0.0) {
        apply_impact(t, y);
        break;
      }
    select_motions(t, y, loaded);
    y[1] = 0.0;
    for (int i = 0; i < n_; ++i) y[1] += y[vel(i)];
  }

  // Perfectly plastic impact (Level 1): the velocities after it minimise the kinetic energy
  // of the velocity change subject to δ̇ ≥ 0, δ̇ = 0 for locked rings.
  void apply_impact(double t, std::vector<double>& y) {
    assemble(y.data());
    Eigen::Map<Eigen::VectorXd> v(y.data() + base_size_, n_);
    const Eigen::VectorXd p = mm_ * v;
    std::vector<char> comp(n_, 1), zero(n_, 0);
    for (int i = 0; i < n_; ++i) zero[i] = motion_[i] == RingMotion::Locked;
    const auto lcp = solve_mass_lcp(mm_, p, comp, zero);
    v = lcp.x;
    for (int i = 0; i < n_; ++i) {
      if (motion_[i] == RingMotion::Locked) continue;
      if (lcp.held[i]) {
        v(i) = 0.0;
        motion_[i] = RingMotion::Rigid;
      } else if (motion_[i] != RingMotion::Crushing) {
        motion_[i] = RingMotion::Crushing;
        take(t, y, i, mech_[i]);
      }
    }
  }

  // Acceleration-level complementarity for the rings at rest (Level 1's select_modes): each
  // crushes in its least-load mechanism (δ̈ ≥ 0, λ = P) or stays rigid (δ̈ = 0, λ ≤ P). A
  // wrap that starts changes the ring underneath, so the problem is solved again.
  void select_motions(double t, std::vector<double>& y, const std::vector<char>& loaded) {
    for (int pass = 0; pass < 4; ++pass) {
      const double* s = y.data();
      std::vector<char> comp(n_, 0), zero(n_, 0);
      for (int i = 0; i < n_; ++i) {
        if (motion_[i] == RingMotion::Rigid) {
          const int k = least(s, i);
          if (k < 0) motion_[i] = RingMotion::Locked;
          else mech_[i] = k;
        }
      }
      assemble(s);
      Eigen::VectorXd r = b_;
      for (int i = 0; i < n_; ++i) {
        if (motion_[i] == RingMotion::Locked) {
          zero[i] = 1;
          continue;
        }
        r(i) -= ring_load(s, mech_[i]);
        comp[i] = motion_[i] == RingMotion::Rigid || s[vel(i)] <= 0.0;
      }
      std::vector<char> prefer(n_, 0);
      for (int i = 0; i < n_ && !loaded.empty(); ++i) prefer[i] = loaded[i];
      // A tie (a ring at its load with zero acceleration) goes to crushing, as in Level 1;
      // but solve_mass_lcp measures a free ring's degeneracy as x_i·𝓜_ii and a held one's as
      // μ_i, which differ by 𝓜_ii/S_i (S_i the Schur complement), and with light rings behind
      // a heavy impactor 𝓜 is nearly rank one (M 11ᵀ), so both tests can fail in turn and the
      // pivoting cycles. Then the tie is left to the events (held; its root fires again).
      MassLcpResult lcp;
      try {
        lcp = solve_mass_lcp(mm_, r, comp, zero, prefer);
      } catch (const std::runtime_error&) {
        lcp = solve_mass_lcp(mm_, r, comp, zero);
      }
      bool changed = false;
      for (int i = 0; i < n_; ++i) {
        if (!comp[i]) continue;
        if (lcp.held[i]) {
          motion_[i] = RingMotion::Rigid;
          y[vel(i)] = 0.0;
        } else if (motion_[i] != RingMotion::Crushing) {
          motion_[i] = RingMotion::Crushing;
          events_.push_back({t, "ring_crushing", i, "least mechanism load reached"});
          const bool wrapped = i + 1 < n_ && reinforced_[i + 1];
          take(t, y, i, mech_[i]);
          changed = changed || (i + 1 < n_ && reinforced_[i + 1] != wrapped);
        }
      }
      if (!changed) break;
    }
  }

  // First contact: the impactor's momentum M V shared by a plastic impact (Level 1).
  std::vector<double> initial_state() {
    const EventScope scope(*this);
    std::vector<double> y(size(), 0.0);
    assemble(y.data());
    const Eigen::VectorXd p = Eigen::VectorXd::Constant(n_, in_.impactor_mass_kg * in_.impactor_velocity_m_s);
    const auto lcp = solve_mass_lcp(mm_, p, std::vector<char>(n_, 1), std::vector<char>(n_, 0));
    for (int i = 0; i < n_; ++i) {
      y[vel(i)] = lcp.held[i] ? 0.0 : lcp.x(i);
      mech_[i] = std::max(least(y.data(), i), kM * i + kU);
      motion_[i] = lcp.held[i] ? RingMotion::Rigid : RingMotion::Crushing;
    }
    for (int i = 0; i < n_; ++i)
      if (motion_[i] == RingMotion::Crushing) take(0.0, y, i, mech_[i]);
    const double v0 = in_.impactor_velocity_m_s;
    impact_loss_ = 0.5 * in_.impactor_mass_kg * v0 * v0 - kinetic(y.data());
    const double ke = kinetic(y.data());
    select_motions(0.0, y, {});
    impact_loss_ += ke - kinetic(y.data());
    y[1] = 0.0;
    for (int i = 0; i < n_; ++i) y[1] += y[vel(i)];
    return y;
  }

  bool moving() const {
    for (auto m : motion_)
      if (m == RingMotion::Crushing) return true;
    return false;
  }

  // The massless chain's record with the inertial chain's kinetic energy, impactor force
  // (M times its deceleration), impact losses and ring forces.
  void record_state(double t, const std::vector<double>& y, Level3History& h) {
    record(t, y, h);
    assemble(y.data());
    accelerations(y.data());
    h.kinetic_j.back() = kinetic(y.data());
    h.force_n.back() = -in_.impactor_mass_kg * qdd_.sum();
    h.impact_loss_j.push_back(impact_loss_);
    h.ring_force_n.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) h.ring_force_n[static_cast<std::size_t>(i)].push_back(lambda_(i));
    h.ring_loads.push_back(ring_loads(y.data()));
  }

  // Each ring's contact forces and accelerations (after accelerations()): ring 1 takes the
  // impactor's −M ü₀ from above, ring i + 1 the force ring i passes on (massless joints),
  // each passing on what its own mass does not take, F_i − m_r ẅ_i, ẅ_i = ½ δ̈_i + Σ_{j>i} δ̈_j.
  std::vector<Level3RingLoads> ring_loads(const double* y) const {
    std::vector<Level3RingLoads> out(static_cast<std::size_t>(n_));
    double top = -in_.impactor_mass_kg * qdd_.sum(), below = qdd_.sum();
    for (int i = 0; i < n_; ++i) {
      auto& L = out[static_cast<std::size_t>(i)];
      below -= qdd_(i);  // Σ_{j>i} δ̈_j
      L.mass_kg = in_.ring_mass_kg;
      L.centre_accel_m_s2 = 0.5 * qdd_(i) + below;
      L.top_n = top;
      L.bottom_n = top - L.mass_kg * L.centre_accel_m_s2;
      top = L.bottom_n;
      L.radius_m = R_;
      double mu, dmu;
      own_mass(y, i, mu, dmu);
      if (mu > 0.0) {  // the Uniform mode's own motion, in φ (δ = d sin φ)
        const double phi = uniform_phi(y, i), dc = d_ * std::cos(phi), v = y[vel(i)];
        L.uniform_motion = true;
        L.phi = phi;
        L.phi_rate = v / dc;
        L.phi_accel = (qdd_(i) + d_ * std::sin(phi) * L.phi_rate * L.phi_rate) / dc;
      }
    }
    return out;
  }

  double impact_loss() const { return impact_loss_; }

 private:
  int base_size_;
  double inertia_scale_ = 0.0;  // (2/π) m_r R²: J(φ) = inertia_scale_ K(φ) (THEORY §1.3)
  std::vector<RingMotion> motion_;
  std::vector<int> mech_;  // ring i's current mechanism slot (kM·i + mode)
  std::vector<double> strength_;
  struct OwnMass {
    double crush = std::numeric_limits<double>::quiet_NaN(), mu = 0.0, dmu = 0.0;
  };
  mutable std::vector<OwnMass> own_cache_;
  struct SlotLoad {
    bool valid = false;
    double crush = 0.0, load = 0.0;
  };
  mutable std::vector<SlotLoad> load_cache_;  // ring_load() per mechanism slot
  struct SlotMargin {
    bool valid = false;
    double crush[3] = {0.0, 0.0, 0.0};
    double margin = 0.0;
  };
  mutable std::vector<SlotMargin> margin_cache_;  // ring_margin() per mechanism slot
  bool in_event_ = false;
  double vref_ = 1.0, impact_loss_ = 0.0, arrest_time_ = -1.0;
  Eigen::MatrixXd m0_, mm_;
  std::vector<double> mm_mu_;  // the μ_i in mm_'s diagonal (assemble())
  Eigen::VectorXd b_, r_, qdd_, lambda_;
  SmallFreeMassSolve free_solve_;
  std::vector<Eigen::Index> free_;
};

constexpr double kIdaRestartStepFraction = 0.003;
constexpr double kIdaStepGrowthThreshold = 1.7;
constexpr double kIdaStepHoldFloor = 0.9;
constexpr double kIdaStepGrowthMax = 100.0;
constexpr double kOdeintEventTimeTolerance = 1e-13;

// The chain's integrator settings on top of the caller's (each unset one).
HybridOptions inertial_options(const HybridOptions& options) {
  HybridOptions opt = options;
  if (!opt.ida_restart_step_fraction) opt.ida_restart_step_fraction = kIdaRestartStepFraction;
  if (!opt.ida_step_growth_threshold) opt.ida_step_growth_threshold = kIdaStepGrowthThreshold;
  if (!opt.ida_step_hold_floor) opt.ida_step_hold_floor = kIdaStepHoldFloor;
  if (!opt.ida_step_growth_max) opt.ida_step_growth_max = kIdaStepGrowthMax;
  // Odeint's events to 1e-13 s instead of 64 ulp of t (~1e-18 s): the roots were half of its
  // instructions, most in ~45 bisections per fired root; 1e-13 s at 50 m/s is 5e-12 m of crush.
  if (!opt.odeint_event_time_tolerance) opt.odeint_event_time_tolerance = kOdeintEventTimeTolerance;
  // IDA on the live components (live_components()): 5–15 instead of 28, tolerances scaled to
  // keep the whole state's error norm, so the same steps (hinge/ida_live_state.hpp).
  // IDA instructions 209 → 93 M at 45 m/s. And the absolute tolerance per component
  // (absolute_tolerances()): velocities against V₀, not 1e-10 m/s; 93 → 58 M with the load cache.
  if (!opt.ida_reduced_state) opt.ida_reduced_state = true;
  if (!opt.ida_component_tolerances) opt.ida_component_tolerances = true;
  // IDA given only the roots that can fire (live_roots()): 8–18 of 37 on Test 30 welded; IDA's
  // step-end root check −31 to −37 % instructions (the model's roots aside), the IDA run −3 to
  // −4 %, history.csv byte-identical.
  if (!opt.ida_live_roots) opt.ida_live_roots = true;
  // Eigen's LU on IDA's 5–15 × 5–15 Newton matrix (h36's; SUNDIALS' dense GETRS was ~1.8k
  // instructions a solve): IDA's linear solves 5.0 → 3.2 M instructions at 45 m/s, the run
  // −3.5 %; the same steps and events, event times within 3e-10 s (round-off moving a grazing
  // root), final crush to 1e-9 d.
  if (!opt.ida_eigen_lu) opt.ida_eigen_lu = true;
  // And that LU written out on the 5–15 unknowns (hinge/small_dense_linear_solver.hpp): Eigen's
  // dynamic-size LU spent most of a solve setting up (h52).
  if (!opt.ida_small_dense_lu) opt.ida_small_dense_lu = true;
  // IDA's vector operations without SUNDIALS' dispatch (hinge/ida_small_vector_ops.hpp): on
  // 5–15 components the calls were a quarter of the run's instructions; the same bits.
  if (!opt.ida_small_vector_ops) opt.ida_small_vector_ops = true;
  return opt;
}

}  // namespace

Level3Result simulate_level3_inertial(const Level3Input& in, const HybridOptions& options, bool record_history) {
  in.validate();
  if (!in.inertia) throw std::invalid_argument("simulate_level3_inertial: Level3Input::inertia is false");
  Level3Result res;
  res.wrap = level3_detail::level3_wrap_for(in);
  res.theta_f = res.wrap.theta_f;
  // IDA restarts from a fraction of its last step: 30–60 events a run, each otherwise starting
  // from IDA's own ~1e-11 s (hybrid_system.hpp); h36's tenth: 1243 → 1106 steps at 27.7 m/s.
  // And IDA's step control (HybridOptions::ida_step_growth_*): after each restart IDA climbs
  // back from order 1 in doublings, granted only when the error would allow 2× and held for
  // k + 1 steps (0.5 of the steps at 45 m/s were that climb: 12–20 a restart). From 0.003 ×
  // the last step, a step grows by any factor >= 1.7 the error allows (up to 100×) and is cut
  // only when the error asks for < 0.9: 788 / 1291 / 1063 → 637 / 1059 / 903 steps at 27.7 /
  // 45 / 50 m/s, IDA instructions −10 to −13 %, the same events and crush within the bar
  // against Odeint at rtol 1e-12 (README "Hinge models", h48; the three values were chosen
  // together on these three speeds, ±3 % around them).
  const HybridOptions opt = inertial_options(options);
  Level3InertialChain chain(in, res.wrap);
  res.initial_kinetic_energy_j = 0.5 * in.impactor_mass_kg * in.impactor_velocity_m_s * in.impactor_velocity_m_s;
  std::vector<double> y = chain.initial_state();
  std::vector<double> last;
  double t_last = 0.0;
  if (chain.moving()) {
    res.outcome = run_hybrid(chain, 0.0, y, opt, [&](double t, const std::vector<double>& s) {
      if (record_history || res.history.time_s.empty()) chain.record_state(t, s, res.history);
      last = s;
      t_last = t;
    });
    if (!record_history && !last.empty()) chain.record_state(t_last, last, res.history);
  } else {
    chain.record_state(0.0, y, res.history);
  }
  chain.finish(y, res);
  res.impact_loss_j = chain.impact_loss();
  level3_check_history(in, res);
  return res;
}

Level3JacobianCheck level3_inertial_jacobian_check(const Level3Input& in, const HybridOptions& options) {
  in.validate();
  if (!in.inertia) throw std::invalid_argument("level3_inertial_jacobian_check: Level3Input::inertia is false");
  Level3InertialChain chain(in, level3_detail::level3_wrap_for(in));
  const std::size_t n = chain.size();
  struct Dense final : JacobianSink {
    std::size_t n;
    std::vector<double> a;
    explicit Dense(std::size_t size) : n(size), a(size * size, 0.0) {}
    void set(std::size_t r, std::size_t c, double v) override { a[c * n + r] = v; }
  };
  Level3JacobianCheck check;
  auto compare = [&](double t, const std::vector<double>& y) {
    Dense exact(n), differences(n);
    chain.jacobian(t, 0.0, y.data(), y.data(), exact);
    chain.jacobian_by_differences(t, y.data(), differences);
    ++check.states;
    for (int i = 0; i < in.rings; ++i) {
      if (!chain.crushing(i)) continue;
      for (int c : {chain.vel(i), level3_detail::Level3Chain::state(chain.mechanism(i))}) {
        const auto col = static_cast<std::size_t>(c);
        double scale = 0.0, worst = 0.0;
        for (std::size_t r = 0; r < n; ++r) {
          scale = std::max(scale, std::abs(differences.a[col * n + r]));
          worst = std::max(worst, std::abs(exact.a[col * n + r] - differences.a[col * n + r]));
        }
        if (scale == 0.0) continue;  // left out (jacobian_by_differences)
        ++check.columns;
        if (worst / scale > check.worst_relative) {
          check.worst_relative = worst / scale;
          check.worst_time_s = t;
          check.worst_ring = i;
          check.worst_is_rate = c == chain.vel(i);
        }
      }
    }
  };
  std::vector<double> y = chain.initial_state();
  if (chain.moving()) run_hybrid(chain, 0.0, y, inertial_options(options), compare);
  return check;
}

}  // namespace ringcrush::hinge
