#include "odeint_integrator.hpp"

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ringcrush::hinge {
namespace {
using State = std::vector<double>;

// Dormand–Prince 5(4) with dense output, step-size bounded when the options say so.
auto dense_dopri5(const OdeintOptions& options) {
  namespace odeint = boost::numeric::odeint;
  return options.max_step > 0.0
             ? odeint::make_dense_output(options.absolute_tolerance, options.relative_tolerance,
                                         options.max_step, odeint::runge_kutta_dopri5<State>())
             : odeint::make_dense_output(options.absolute_tolerance, options.relative_tolerance,
                                         odeint::runge_kutta_dopri5<State>());
}
}  // namespace

double integrate_dense(OdeSystem& system, std::vector<double>& y, double t0, double t1,
                       const OdeintOptions& options, const DenseStepObserver& observer,
                       OdeintStatistics* statistics) {
  if (y.size() != system.size())
    throw std::invalid_argument("integrate_dense: state size does not match the system");

  long rhs_evaluations = 0;
  auto rhs = [&](const State& x, State& dxdt, double t) {
    ++rhs_evaluations;
    system.rhs(t, x.data(), dxdt.data());
  };

  auto stepper = dense_dopri5(options);
  stepper.initialize(y, t0, std::min(options.initial_step, t1 - t0));

  long steps = 0;
  double t = t0;
  const auto at = [&](double tau, State& out) {
    out.resize(y.size());
    stepper.calc_state(tau, out);
  };
  while (t < t1) {
    const auto [t_prev, t_now] = stepper.do_step(rhs);
    ++steps;
    const bool keep_going = observer ? observer(t_prev, std::min(t_now, t1), at) : true;
    for (double v : stepper.current_state())
      if (!std::isfinite(v))
        throw std::runtime_error("integrate_dense: non-finite state at t = " + std::to_string(t_now));
    if (t_now >= t1) {
      stepper.calc_state(t1, y);
      t = t1;
      break;
    }
    t = t_now;
    y = stepper.current_state();
    if (!keep_going) break;
  }
  if (statistics) *statistics = {steps, rhs_evaluations};
  return t;
}

OdeintStop integrate_until_event(OdeSystem& system, std::vector<double>& y, double t0, double t1,
                                 const OdeintOptions& options, const OdeintEventOptions& events,
                                 const StepSampler& sample, OdeintStatistics* statistics) {
  if (y.size() != system.size())
    throw std::invalid_argument("integrate_until_event: state size does not match the system");
  const std::size_t nr = events.root_count;
  if (nr > 0 && !events.roots) throw std::invalid_argument("integrate_until_event: no root function");
  if (!events.masked.empty() && events.masked.size() != nr)
    throw std::invalid_argument("integrate_until_event: one mask entry per root function");

  long rhs_evaluations = 0;
  auto rhs = [&](const State& x, State& dxdt, double t) {
    ++rhs_evaluations;
    system.rhs(t, x.data(), dxdt.data());
  };
  auto stepper = dense_dopri5(options);
  stepper.initialize(y, t0, std::min(options.initial_step, t1 - t0));

  // Root values as watched: a masked root is replaced by its expected sign × tolerance (or
  // left out) until it has left zero; `sign` is the last watched sign (0: not yet known).
  std::vector<double> g(nr);
  std::vector<int> sign(nr, 0);
  std::vector<int> masked = events.masked.empty() ? std::vector<int>(nr, 0) : events.masked;
  const double mtol = events.mask_tolerance;
  auto watched = [&](std::size_t i, double value, bool release) -> double {
    const int m = masked[i];
    if (m == 0) return value;
    if (std::abs(value) > mtol) {
      if (release) masked[i] = 0;
      return value;
    }
    return (m == 1 || m == -1) ? m * mtol : 0.0;
  };
  auto sign_of = [](double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); };
  if (nr > 0) {
    events.roots(t0, y, g.data());
    for (std::size_t i = 0; i < nr; ++i) sign[i] = sign_of(watched(i, g[i], true));
  }

  OdeintStop stop;
  stop.t = t0;
  long steps = 0;
  State trial(y.size());
  std::vector<double> gt(nr);
  double t = t0;
  while (t < t1) {
    const auto [t_prev, t_step] = stepper.do_step(rhs);
    ++steps;
    for (double v : stepper.current_state())
      if (!std::isfinite(v))
        throw std::runtime_error("integrate_until_event: non-finite state at t = " + std::to_string(t_step));
    const double t_now = std::min(t_step, t1);
    stop.last_step = t_step - t_prev;
    if (t_step > t1) stepper.calc_state(t1, trial);
    else trial = stepper.current_state();

    // Roots with a sign change over (t_prev, t_now]: bisect each on the interpolant.
    double t_event = t_now;
    bool any = false;
    if (nr > 0) {
      events.roots(t_now, trial, gt.data());
      for (std::size_t i = 0; i < nr; ++i) {
        if (sign[i] == 0) continue;
        if (sign_of(watched(i, gt[i], false)) == sign[i]) continue;
        double lo = t_prev, hi = t_now;
        const double width = events.time_tolerance > 0.0
                                 ? events.time_tolerance
                                 : 64.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t_now), 1e-300);
        std::vector<double> gm(nr);
        State mid(y.size());
        for (int it = 0; it < 200 && hi - lo > width; ++it) {
          const double tm = 0.5 * (lo + hi);
          stepper.calc_state(tm, mid);
          events.roots(tm, mid, gm.data());
          if (sign_of(watched(i, gm[i], false)) == sign[i]) lo = tm;
          else hi = tm;
        }
        any = true;
        t_event = std::min(t_event, hi);
      }
    }
    if (any) {
      State at_event(y.size());
      stepper.calc_state(t_event, at_event);
      events.roots(t_event, at_event, gt.data());
      stop.roots_found.assign(nr, 0);
      for (std::size_t i = 0; i < nr; ++i) {
        if (sign[i] == 0) continue;
        if (sign_of(watched(i, gt[i], false)) != sign[i]) stop.roots_found[i] = sign[i] > 0 ? -1 : +1;
      }
      y = at_event;
      stop.t = t_event;
      stop.root_found = true;
      if (sample) sample(t_event, y);
      t = t_event;
      break;
    }
    for (std::size_t i = 0; i < nr; ++i) {
      const int sg = sign_of(watched(i, gt[i], true));
      if (sg != 0) sign[i] = sg;
    }
    y = trial;
    t = t_now;
    stop.t = t;
    if (sample && !sample(t, y)) {
      stop.stopped_by_sampler = true;
      break;
    }
  }
  if (statistics) {
    statistics->steps += steps;
    statistics->rhs_evaluations += rhs_evaluations;
  }
  return stop;
}

}  // namespace ringcrush::hinge
