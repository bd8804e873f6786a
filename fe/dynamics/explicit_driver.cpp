#include "fe/dynamics/explicit_driver.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "fe/dynamics/explicit_step_end.hpp"
#include "fe/time/static_driver.hpp"  // SolveFailure

namespace ringcrush::fe {

ExplicitDriver::ExplicitDriver(DynamicSystem& system, const ExplicitOptions& options, const Eigen::VectorXd& u0)
    : sys_(system), opt_(options) {
  if (!(opt_.safety > 0 && opt_.safety <= 1))
    throw std::invalid_argument(fmt::format("explicit: safety = {} must be in (0, 1]", opt_.safety));
  if (opt_.stable_step_every < 1)
    throw std::invalid_argument(fmt::format("explicit: stable_step_every = {} must be ≥ 1", opt_.stable_step_every));
  if (!(opt_.max_step_s > 0))
    throw std::invalid_argument(fmt::format("explicit: max_step_s = {} must be > 0", opt_.max_step_s));
  if (!(opt_.fixed_step_s >= 0) || !std::isfinite(opt_.fixed_step_s))
    throw std::invalid_argument(fmt::format("explicit: fixed_step_s = {} must be ≥ 0", opt_.fixed_step_s));
  if (!(opt_.mass_scaling_target_s >= 0) || !std::isfinite(opt_.mass_scaling_target_s))
    throw std::invalid_argument(
        fmt::format("explicit: mass_scaling_target_s = {} must be ≥ 0", opt_.mass_scaling_target_s));
  const int n = sys_.dofs();
  const Eigen::VectorXd& m = sys_.lumped_mass();
  if (m.size() != n) throw std::invalid_argument("explicit: lumped mass size differs from the dof count");
  inv_mass_ = Eigen::VectorXd::Zero(n);
  std::vector<char> fixed(static_cast<std::size_t>(n), 0);
  for (int d : sys_.fixed_dofs()) fixed[static_cast<std::size_t>(d)] = 1;
  for (int d = 0; d < n; ++d) {
    if (fixed[static_cast<std::size_t>(d)]) continue;
    if (!(m(d) > 0)) throw std::invalid_argument(fmt::format("explicit: lumped mass of free dof {} is {} (must be > 0)", d, m(d)));
    inv_mass_(d) = 1.0 / m(d);
  }
  u_ = u0.size() ? u0 : Eigen::VectorXd::Zero(n);
  if (u_.size() != n) throw std::invalid_argument("explicit: initial displacement size differs from the dof count");
  v_ = sys_.initial_velocity();
  for (int d : sys_.fixed_dofs()) v_(d) = 0;
  sys_.evaluate(u_, false, ev_);
  sys_.commit(u_);
  ++evaluations_;
  contact_time_ += ev_.contact_time_s;
  a_ = -inv_mass_.cwiseProduct(ev_.force);
  energy_.start(EnergyBalance::kinetic_energy(m, v_), ev_);
  if (!ev_.force.allFinite()) fail("non-finite initial force", -1);
}

void ExplicitDriver::fail(const std::string& what, int dof) const {
  const std::string where = dof < 0 ? std::string("-") : describe_dof ? describe_dof(dof) : fmt::format("dof {}", dof);
  throw SolveFailure(fmt::format(
      "explicit central difference: {} at t = {:.6g} s (step {}, Δt = {:.4g} s, stable step 2/ω_max = {:.4g} s "
      "limited by {}, safety {}); largest at {}",
      what, t_, steps_, dt_, dt_stable_, limited_by_.empty() ? "-" : limited_by_, opt_.safety, where));
}

// Δt = safety · 2/ω_max (issue 4 item 5); the bound includes the active contact stiffness.
// contact_only: the contact activity changed since the last full bound, whose element part
// the system may reuse (DynamicSystem::contact_stable_step); the full-bound schedule
// (stable_step_every) is kept.
void ExplicitDriver::bound_step(bool contact_only) {
  const StableStep s = contact_only ? sys_.contact_stable_step(u_) : sys_.stable_step(u_);
  ++(contact_only ? contact_bounds_ : full_bounds_);
  if (!(s.step_s > 0) || !std::isfinite(s.step_s)) fail(fmt::format("stable step {} is not positive", s.step_s), -1);
  dt_stable_ = s.step_s;
  limited_by_ = s.limited_by;
  dt_target_ = std::min(opt_.safety * s.step_s, opt_.max_step_s);
  if (opt_.safety * s.step_s > opt_.max_step_s) limited_by_ = "max_step_s";
  contact_rebound_ = false;
  if (!contact_only) {
    rebound_ = false;
    since_bound_ = 0;
  }
  // With mass scaling the elements were scaled to reach the target at the start; what still
  // holds the step below it (a contact spring, a crushed or thickened element) is named.
  // 1e-9: the scaled element's own bound meets the target to rounding.
  const bool was_below = below_target_;
  below_target_ = opt_.mass_scaling_target_s > 0 && dt_target_ < opt_.mass_scaling_target_s * (1 - 1e-9);
  // Log when the kind of limit changes (element / contact / cap), the step moved by more
  // than 10 % since the last line (contact nodes come and go every few steps), or the step
  // crossed the mass-scaling target.
  const std::string kind = limited_by_.substr(0, limited_by_.find(' '));
  if (log && (kind != logged_kind_ || std::abs(dt_target_ - logged_dt_) > 0.1 * logged_dt_ || was_below != below_target_)) {
    log(fmt::format("explicit: t = {:.6g} s, Δt = {:.4g} s ({} × 2/ω_max = {:.4g} s, limited by {}){}", t_, dt_target_,
                    opt_.safety, dt_stable_, limited_by_,
                    below_target_ ? fmt::format("; below the mass-scaling target {:.4g} s", opt_.mass_scaling_target_s)
                                  : std::string()));
    logged_kind_ = kind;
    logged_dt_ = dt_target_;
  }
}

void ExplicitDriver::step(double t_limit) {
  if (!(t_limit > t_)) throw std::invalid_argument(fmt::format("explicit: step limit {} is not after t = {}", t_limit, t_));
  if (opt_.fixed_step_s > 0) {
    dt_target_ = opt_.fixed_step_s;
    if (limited_by_.empty()) {
      limited_by_ = "fixed step";
      dt_stable_ = sys_.stable_step(u_).step_s;
    }
  } else if (rebound_ || since_bound_ >= opt_.stable_step_every) {
    bound_step(false);
  } else if (contact_rebound_) {
    bound_step(true);
  }
  dt_ = std::min(dt_target_, t_limit - t_);
  const Eigen::VectorXd& m = sys_.lumped_mass();
  const Eigen::Index n = u_.size();
  const double half = 0.5 * dt_;

  // Half-step velocity and the new displacement, in one pass over the dofs (the same
  // operations per dof as the vector expressions v += ½Δt a, du = Δt v, u += du; this loop is
  // serial between two dealt element passes, README "Two threads").
  if (du_.size() != n) du_.resize(n);
  {
    double *v = v_.data(), *du = du_.data(), *u = u_.data();
    const double* a = a_.data();
    for (Eigen::Index i = 0; i < n; ++i) {
      v[i] += half * a[i];
      du[i] = dt_ * v[i];
      u[i] += du[i];
    }
  }
  // The last forces become the old ones by exchanging the buffers (evaluate() overwrites
  // the other): no copy.
  f_old_.swap(ev_.force);
  q_old_.swap(ev_.viscous_force);
  sys_.set_increment_time(dt_);  // rate-dependent (bulk-viscous) forces: ε̇ = Δε/Δt
  // a = −M⁻¹ f, the second half-step of v, the finiteness test of f and the step's energy sums,
  // dof by dof as the system finishes each force (explicit_step_end.hpp; one pass over the
  // vectors on the serial tail of the two-thread step, README "FE dynamics").
  if (a_.size() != n) a_.resize(n);
  if (zeros_.size() != n) zeros_.setZero(n);
  ExplicitStepEnd end;
  end.inv_mass = inv_mass_.data();
  end.mass = m.data();
  end.velocity = v_.data();
  end.acceleration = a_.data();
  end.old_force = f_old_.data();
  end.old_viscous = q_old_.size() == n ? q_old_.data() : nullptr;
  end.zeros = zeros_.data();
  end.increment = du_.data();
  end.half_step = half;
  sys_.evaluate_explicit(u_, ev_, end);
  ++evaluations_;
  contact_time_ += ev_.contact_time_s;
  // The dof is looked for only when the test fails.
  if (!(end.not_finite == 0)) {
    int bad = 0;
    while (bad + 1 < ev_.force.size() && std::isfinite(ev_.force(bad))) ++bad;
    fail("non-finite internal force (the integration has blown up)", bad);
  }
  sys_.commit_evaluated(u_);  // the u just evaluated
  t_ += dt_;
  ++steps_;
  if (below_target_ && opt_.fixed_step_s == 0) ++steps_below_target_;
  ++since_bound_;
  min_dt_ = steps_ == 1 ? dt_ : std::min(min_dt_, dt_);
  max_dt_ = std::max(max_dt_, dt_);

  energy_.add_step_sums(end.force_du, end.viscous_du);
  energy_.set_state(0.5 * end.mass_v2, ev_);
  // A conservative system cannot gain kinetic energy beyond what it started with: growth is
  // the central-difference instability (Δt > 2/ω_max), caught before any NaN appears.
  if (!std::isfinite(energy_.kinetic) || energy_.kinetic > opt_.blowup_energy_factor * energy_.reference()) {
    int at = 0;
    m.cwiseProduct(v_.cwiseAbs2()).maxCoeff(&at);
    fail(fmt::format("blow-up: kinetic energy {:.4g} J > {} × reference {:.4g} J", energy_.kinetic,
                     opt_.blowup_energy_factor, energy_.reference()),
         at);
  }
  if (opt_.energy_error_limit > 0 && energy_.relative_balance_error() > opt_.energy_error_limit)
    fail(fmt::format("energy limit: |balance error| {:.4g} J = {:.3g} % of {:.4g} J exceeds energy_error_limit {:.3g} %",
                     std::abs(energy_.balance_error()), 100 * energy_.relative_balance_error(), energy_.reference(),
                     100 * opt_.energy_error_limit),
         -1);
}

}  // namespace ringcrush::fe
