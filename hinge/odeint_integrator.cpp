#include "odeint_integrator.hpp"

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <stdexcept>

namespace ringcrush::hinge {

double integrate_dense(OdeSystem& system, std::vector<double>& y, double t0, double t1,
                       const OdeintOptions& options, const DenseStepObserver& observer,
                       OdeintStatistics* statistics) {
  namespace odeint = boost::numeric::odeint;
  using State = std::vector<double>;
  if (y.size() != system.size())
    throw std::invalid_argument("integrate_dense: state size does not match the system");

  long rhs_evaluations = 0;
  auto rhs = [&](const State& x, State& dxdt, double t) {
    ++rhs_evaluations;
    system.rhs(t, x.data(), dxdt.data());
  };

  auto stepper = options.max_step > 0.0
                     ? odeint::make_dense_output(options.absolute_tolerance,
                                                 options.relative_tolerance, options.max_step,
                                                 odeint::runge_kutta_dopri5<State>())
                     : odeint::make_dense_output(options.absolute_tolerance,
                                                 options.relative_tolerance,
                                                 odeint::runge_kutta_dopri5<State>());
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

}  // namespace ringcrush::hinge
