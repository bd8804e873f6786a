#include "fe/dynamics/hht_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fe/solve/linear_solver.hpp"
#include "fe/time/static_driver.hpp"  // SolveFailure

namespace ringcrush::fe {

HhtDriver::HhtDriver(DynamicSystem& system, const HhtOptions& options, const Eigen::VectorXd& u0)
    : sys_(system), opt_(options), solver_(std::make_unique<LinearSolver>()) {
  const auto bad = [](const char* name, double value, const char* rule) {
    throw std::invalid_argument(fmt::format("HHT-α: {} = {} {}", name, value, rule));
  };
  if (!(opt_.alpha >= -1.0 / 3.0 - 1e-12 && opt_.alpha <= 0)) bad("alpha", opt_.alpha, "must be in [−1/3, 0] (Hilber's sign)");
  if (!(opt_.min_step_s > 0)) bad("min_step_s", opt_.min_step_s, "must be > 0");
  if (!(opt_.max_step_s >= opt_.min_step_s)) bad("max_step_s", opt_.max_step_s, "must be ≥ min_step_s");
  if (!(opt_.initial_step_s >= opt_.min_step_s && opt_.initial_step_s <= opt_.max_step_s))
    bad("initial_step_s", opt_.initial_step_s, "must lie in [min_step_s, max_step_s]");
  if (!(opt_.haftol_n > 0)) bad("haftol_n", opt_.haftol_n, "must be > 0");
  if (!(opt_.ptol_n > 0)) bad("ptol_n", opt_.ptol_n, "must be > 0");
  if (!(opt_.correction_tolerance > 0)) bad("correction_tolerance", opt_.correction_tolerance, "must be > 0");
  if (opt_.max_iterations < 1) bad("max_iterations", opt_.max_iterations, "must be ≥ 1");
  beta_ = 0.25 * (1 - opt_.alpha) * (1 - opt_.alpha);
  gamma_ = 0.5 - opt_.alpha;
  dt_ = opt_.initial_step_s;

  const int n = sys_.dofs();
  mass_ = sys_.lumped_mass();
  if (mass_.size() != n) throw std::invalid_argument("HHT-α: lumped mass size differs from the dof count");
  std::vector<char> fixed(static_cast<std::size_t>(n), 0);
  for (int d : sys_.fixed_dofs()) fixed[static_cast<std::size_t>(d)] = 1;
  for (int d = 0; d < n; ++d)
    if (!fixed[static_cast<std::size_t>(d)]) {
      if (!(mass_(d) > 0)) bad("lumped mass of a free dof", mass_(d), "must be > 0");
      free_.push_back(d);
    }
  u_ = u0.size() ? u0 : Eigen::VectorXd::Zero(n);
  if (u_.size() != n) throw std::invalid_argument("HHT-α: initial displacement size differs from the dof count");
  v_ = sys_.initial_velocity();
  for (int d : sys_.fixed_dofs()) v_(d) = 0;
  sys_.evaluate(u_, false, ev_);
  sys_.commit(u_);
  contact_time_ += ev_.contact_time_s;
  if (!ev_.force.allFinite()) throw SolveFailure("HHT-α: non-finite initial force");
  // Initial acceleration from equilibrium, M a_0 = −f(u_0).
  a_ = Eigen::VectorXd::Zero(n);
  for (int d : free_) a_(d) = -ev_.force(d) / mass_(d);
  energy_.start(EnergyBalance::kinetic_energy(mass_, v_), ev_);
  f_prev_ = ev_.force;  // f_{−1} = f_0: the start satisfies M a_0 + f_0 = 0, i.e. (3.5-2a) with it
  r_ = Eigen::VectorXd::Zero(n);
}

HhtDriver::~HhtDriver() = default;

long HhtDriver::factorizations() const { return solver_->factorizations(); }

double HhtDriver::max_free(const Eigen::VectorXd& r, int& at) const {
  double m = 0;
  at = -1;
  for (int d : free_) {
    const double x = std::abs(r(d));
    if (!std::isfinite(x)) {
      at = d;
      return INFINITY;
    }
    if (x > m) {
      m = x;
      at = d;
    }
  }
  return m;
}

std::string HhtDriver::where(int dof) const {
  if (dof < 0) return "-";
  return describe_dof ? describe_dof(dof) : fmt::format("dof {}", dof);
}

void HhtDriver::fail(const std::string& what, double dt, double residual, int dof) const {
  throw SolveFailure(fmt::format(
      "HHT-α: {} at t = {:.6g} s (step {}, Δt = {:.4g} s, minimum {:.4g} s); largest residual {:.4g} N at {}", what, t_,
      steps_ + 1, dt, opt_.min_step_s, residual, where(dof)));
}

// K_eff = M/(βΔt²) + (1 + α) K: the system assembled K into its free-dof matrix; scale it
// and add the lumped mass on the diagonal (always in the pattern, dynamic_system.hpp).
void HhtDriver::add_mass_to_tangent(double c0) {
  SparseSystem& s = sys_.tangent_system();
  auto& k = s.matrix();
  if (diag_version_ != s.pattern_version()) {
    diag_pos_.assign(static_cast<std::size_t>(s.free_dofs()), -1);
    for (int i = 0; i < s.free_dofs(); ++i) {
      const int* begin = k.innerIndexPtr() + k.outerIndexPtr()[i];
      const int* end = k.innerIndexPtr() + k.outerIndexPtr()[i + 1];
      const int* it = std::lower_bound(begin, end, i);
      if (it == end || *it != i) throw std::logic_error("HHT-α: tangent pattern lacks a free diagonal entry");
      diag_pos_[static_cast<std::size_t>(i)] = static_cast<int>(it - k.innerIndexPtr());
    }
    diag_version_ = s.pattern_version();
  }
  double* v = k.valuePtr();
  const double scale = 1 + opt_.alpha;
  for (Eigen::Index j = 0; j < k.nonZeros(); ++j) v[j] *= scale;
  const auto& dofs = s.free_to_dof();
  for (int i = 0; i < s.free_dofs(); ++i)
    v[diag_pos_[static_cast<std::size_t>(i)]] += c0 * mass_(dofs[static_cast<std::size_t>(i)]);
}

// Newton on u_{n+1} for (3.5-2a), a_{n+1} eliminated through (3.5-2b).
HhtDriver::Newton HhtDriver::newton(double dt, Eigen::VectorXd& u, Eigen::VectorXd& a) {
  Newton out;
  const double c0 = 1.0 / (beta_ * dt * dt);
  // The unknown is the step increment Δu = u_{n+1} − u_n, so that the inertia term
  // M a_{n+1} = M (Δu − Δu*)/(βΔt²) is formed from small numbers: with u itself the
  // cancellation u − u* loses ~|u|·ε/(βΔt²) of force, which at the smallest steps exceeds PTOL.
  // Δu* = the part known at t_n; the predictor takes a_{n+1} = a_n.
  const Eigen::VectorXd du_star = dt * v_ + (0.5 - beta_) * dt * dt * a_;
  du_ = du_star + beta_ * dt * dt * a_;
  double last_correction = INFINITY, previous = INFINITY;
  SparseSystem& s = sys_.tangent_system();
  for (int it = 0;; ++it) {
    u = u_ + du_;
    double incr = 0;
    for (int d : free_) incr = std::max(incr, std::abs(du_(d)));
    // When the last correction already passes its test, this iteration most likely
    // converges: evaluate the force alone and assemble the tangent only if it does not.
    const bool correction_passed = last_correction <= opt_.correction_tolerance * std::max(incr, 1e-300);
    sys_.evaluate(u, !correction_passed, ev_trial_);
    contact_time_ += ev_trial_.contact_time_s;
    a = c0 * (du_ - du_star);
    for (int d : free_) r_(d) = mass_(d) * a(d) + (1 + opt_.alpha) * ev_trial_.force(d) - opt_.alpha * ev_.force(d);
    int at = -1;
    const double rmax = max_free(r_, at);
    out.iterations = it;
    out.residual = rmax;
    out.residual_dof = at;
    if (!std::isfinite(rmax)) {
      out.reason = "non-finite residual";
      return out;
    }
    if (rmax <= opt_.ptol_n && (correction_passed || rmax <= 1e-3 * opt_.ptol_n)) {
      out.converged = true;
      for (int d : sys_.fixed_dofs()) a(d) = 0;
      return out;
    }
    if (it >= opt_.max_iterations) {
      out.reason = fmt::format("no convergence in {} iterations", opt_.max_iterations);
      return out;
    }
    if (it >= 3 && rmax > opt_.ptol_n && rmax >= previous) {
      out.reason = fmt::format("residual not decreasing ({:.3g} N after {:.3g} N)", rmax, previous);
      return out;
    }
    previous = rmax;
    if (correction_passed) {
      sys_.evaluate(u, true, ev_trial_);
      contact_time_ += ev_trial_.contact_time_s;
    }
    add_mass_to_tangent(c0);
    if (!solver_->factorize(s.matrix(), s.pattern_version())) {
      out.reason = "effective tangent could not be factorised";
      return out;
    }
    const auto& dofs = s.free_to_dof();
    rhs_.resize(s.free_dofs());
    for (int i = 0; i < s.free_dofs(); ++i) rhs_(i) = -r_(dofs[static_cast<std::size_t>(i)]);
    dx_ = solver_->solve(rhs_);
    ++iterations_;
    if (!dx_.allFinite()) {
      out.reason = "non-finite Newton correction";
      return out;
    }
    for (int i = 0; i < s.free_dofs(); ++i) du_(dofs[static_cast<std::size_t>(i)]) += dx_(i);
    last_correction = dx_.cwiseAbs().maxCoeff();
  }
}

void HhtDriver::step(double t_limit) {
  if (!(t_limit > t_)) throw std::invalid_argument(fmt::format("HHT-α: step limit {} is not after t = {}", t_limit, t_));
  for (;;) {
    const double dt = std::min(dt_, t_limit - t_);
    HhtAttempt attempt;
    attempt.time_s = t_;
    attempt.step_s = dt;
    const Newton nw = newton(dt, u_new_, a_new_);
    attempt.iterations = nw.iterations;
    if (!nw.converged) {
      // Thesis §3.4/§3.5 practice: cut the increment to a quarter and retry from t.
      ++rejected_;
      small_count_ = 0;
      attempt.outcome = "newton cut-back";
      if (keep_attempts) attempts_.push_back(attempt);
      dt_ = 0.25 * dt;
      if (log) log(fmt::format("HHT-α: t = {:.6g} s, Newton failed with Δt = {:.4g} s ({}); Δt → {:.4g} s", t_, dt, nw.reason, dt_));
      if (dt_ < opt_.min_step_s) fail(fmt::format("Newton failed ({}) and Δt/4 is below the minimum", nw.reason), dt, nw.residual, nw.residual_dof);
      continue;
    }
    v_new_ = v_ + dt * ((1 - gamma_) * a_ + gamma_ * a_new_);
    if (opt_.half_step_control) {
      // Half-step residual (thesis §3.5): linear acceleration over the step, Newmark state
      // at τ = ½, equation (3.5-2a) written there.
      const double h = 0.5 * dt;
      a_half_ = 0.5 * (a_ + a_new_);
      u_half_ = u_ + h * v_ + h * h * ((0.5 - beta_) * a_ + beta_ * a_half_);
      sys_.evaluate(u_half_, false, ev_half_);
      contact_time_ += ev_half_.contact_time_s;
      // The α-term of (3.5-2a) lags one step: at t + Δt/2 it is taken, like the
      // accelerations, linear over the previous step, ½ (f_{n−1} + f_n).
      for (int d : free_)
        r_(d) = mass_(d) * a_half_(d) + (1 + opt_.alpha) * ev_half_.force(d) -
                0.5 * opt_.alpha * (f_prev_(d) + ev_.force(d));
      int at = -1;
      const double rh = max_free(r_, at);
      attempt.half_step_residual_n = rh;
      if (!(rh <= opt_.haftol_n)) {  // also catches a non-finite half-step residual
        ++rejected_;
        small_count_ = 0;
        attempt.outcome = "halved";
        if (keep_attempts) attempts_.push_back(attempt);
        dt_ = 0.5 * dt;
        if (dt_ < opt_.min_step_s)
          fail(fmt::format("half-step residual {:.4g} N > HAFTOL {:.4g} N and Δt/2 is below the minimum", rh, opt_.haftol_n),
               dt, rh, at);
        continue;
      }
      // Accepted. ev_trial_ still holds f(u_{n+1}) from Newton; commit(u_{n+1}) restores the
      // step-end trial states itself (dynamic_system.hpp), the half-step state never commits.
      if (rh > 0.5 * opt_.haftol_n) {
        small_count_ = 0;
        attempt.outcome = "kept";
      } else if (++small_count_ >= 2) {
        small_count_ = 0;
        dt_ = std::min(1.25 * dt_, opt_.max_step_s);
        attempt.outcome = "grown";
      } else {
        attempt.outcome = "small";
      }
    } else {
      attempt.outcome = "fixed";
    }
    attempt.accepted = true;
    if (keep_attempts) attempts_.push_back(attempt);

    sys_.commit(u_new_);
    f_prev_ = ev_.force;
    du_ = u_new_ - u_;  // the converged increment (a half-step evaluation does not touch it)
    energy_.add_step(ev_.force, ev_trial_.force, du_);
    std::swap(ev_, ev_trial_);
    u_.swap(u_new_);
    a_.swap(a_new_);
    v_.swap(v_new_);
    t_ += dt;
    last_dt_ = dt;
    ++steps_;
    min_dt_ = steps_ == 1 ? dt : std::min(min_dt_, dt);
    max_dt_ = std::max(max_dt_, dt);
    energy_.set_state(EnergyBalance::kinetic_energy(mass_, v_), ev_);
    if (!std::isfinite(energy_.kinetic)) fail("non-finite velocity", dt, 0, -1);
    if (opt_.energy_error_limit > 0 && energy_.relative_balance_error() > opt_.energy_error_limit)
      throw SolveFailure(fmt::format(
          "HHT-α: energy limit at t = {:.6g} s: |balance error| {:.4g} J = {:.3g} % of {:.4g} J exceeds "
          "energy_error_limit {:.3g} %",
          t_, std::abs(energy_.balance_error()), 100 * energy_.relative_balance_error(), energy_.reference(),
          100 * opt_.energy_error_limit));
    return;
  }
}

}  // namespace ringcrush::fe
