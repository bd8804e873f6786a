#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "hybrid_system.hpp"
#include "ida_live_state.hpp"
#include "ida_solver.hpp"
#include "odeint_integrator.hpp"

namespace ringcrush::hinge {
namespace {

// Roots at (or within the mask tolerance of) zero after a restart are masked.
std::vector<int> near_zero_roots(HybridSystem& system, double t, const std::vector<double>& y,
                                 double tolerance, const std::vector<int>& fired) {
  std::vector<double> g(system.root_count());
  if (g.empty()) return {};
  system.event_roots(t, y.data(), g.data());
  std::vector<int> masked(g.size(), 0);
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (std::abs(g[i]) > tolerance) continue;
    const int expected = system.root_departure(i, fired.empty() ? 0 : fired[i]);
    masked[i] = expected != 0 ? expected : root_mask_inactive;
  }
  return masked;
}

bool has_algebraic(const std::vector<double>& mask) {
  for (double m : mask)
    if (m == 0.0) return true;
  return false;
}

HybridOutcome run_ida(HybridSystem& system, double t0, std::vector<double>& y,
                      const HybridOptions& o, const HybridSampler& sample) {
  const std::size_t n = system.size();
  IdaOptions io;
  io.relative_tolerance = o.relative_tolerance;
  io.absolute_tolerance = o.absolute_tolerance;
  io.max_steps = o.max_steps_per_segment;
  io.max_step = o.max_step;
  io.root_mask_tolerance = o.root_mask_tolerance;
  if (o.ida_small_dense_lu.value_or(false)) io.linear_solver = IdaOptions::LinearSolver::SmallDense;
  else if (o.ida_eigen_lu.value_or(false)) io.linear_solver = IdaOptions::LinearSolver::EigenDense;
  io.small_vector_ops = o.ida_small_vector_ops.value_or(false);
  io.step_growth = {o.ida_step_growth_threshold.value_or(0.0), o.ida_step_hold_floor.value_or(0.0),
                    o.ida_step_growth_max.value_or(0.0)};
  const bool algebraic = has_algebraic(system.differential_mask());
  io.suppress_algebraic_error_test = algebraic;
  const bool reduced = o.ida_reduced_state.value_or(false);
  if (reduced && algebraic)
    throw std::invalid_argument(
        "run_hybrid: ida_reduced_state needs a system without algebraic components (IDACalcIC works on the whole state)");
  // Absolute tolerances per component (the model's), if asked for.
  std::vector<double> atol;
  if (o.ida_component_tolerances.value_or(false)) {
    atol = system.absolute_tolerances(o.relative_tolerance, o.absolute_tolerance);  // empty: scalar
    if (!atol.empty() && atol.size() != n)
      throw std::invalid_argument(fmt::format(
          "run_hybrid: ida_component_tolerances needs one absolute tolerance per component ({} for {})",
          atol.size(), n));
    for (double a : atol)
      if (!(a > 0.0) || !std::isfinite(a))
        throw std::invalid_argument(fmt::format("run_hybrid: absolute tolerance {} (need finite, > 0)", a));
  }
  // IDA on the root functions that can fire before the next event (hinge/ida_live_roots.hpp).
  const bool live_roots = o.ida_live_roots.value_or(false);
  // Whole state: one IDA. Reduced: one IDA per live size met so far (IDA cannot resize; the
  // restart after every event reinitialises whichever is used), all on the one live view.
  IdaLiveState live(system);
  std::map<std::size_t, std::unique_ptr<IdaSolver>> solvers;
  IdaSolver* ida = nullptr;
  // IDA's state as the model's (the held components filled in).
  auto pull = [&](std::vector<double>& out) {
    if (reduced) out = live.expand(ida->y());
    else out = ida->y();
  };
  // IDACalcIC needs a first output time for its scale: one hundredth of the run.
  const double ic_horizon = 1e-2 * (o.end_time - t0);
  auto restart = [&](double t, const std::vector<double>& state, const std::vector<int>& fired) {
    const bool from_last = o.ida_restart_step_fraction.value_or(0.0) > 0.0 && !fired.empty();
    const double h_last = from_last ? ida->last_step() : 0.0;
    std::vector<double> deriv(n);
    system.rhs(t, state.data(), deriv.data());
    DaeSystem* dae = &system;
    std::vector<double> y0 = state, yp0 = deriv;
    if (reduced) {
      live.hold(system.live_components(), state, deriv);
      dae = &live;
      y0 = live.gather(state);
      yp0 = live.gather(deriv);
    }
    auto& solver = solvers[y0.size()];
    if (!solver) {
      IdaOptions so = io;
      if (reduced) {
        so.relative_tolerance *= live.tolerance_scale();
        so.absolute_tolerance *= live.tolerance_scale();
      }
      solver = std::make_unique<IdaSolver>(*dae, t, y0, yp0, so);
    }
    ida = solver.get();
    if (!atol.empty()) {
      const double scale = reduced ? live.tolerance_scale() : 1.0;
      std::vector<double> a = reduced ? live.gather(atol) : atol;
      for (double& x : a) x *= scale;
      ida->set_tolerances(io.relative_tolerance * scale, a);
    }
    if (from_last) ida->set_initial_step(*o.ida_restart_step_fraction * h_last);
    if (live_roots) ida->set_live_roots(system.live_roots());
    ida->reinit(t, y0, yp0, near_zero_roots(system, t, state, o.root_mask_tolerance, fired));
    if (algebraic) ida->calc_initial_conditions(t + ic_horizon);
    ida->set_stop_time(o.end_time);
  };
  auto step = [&] {
    try {
      return ida->step(o.end_time);
    } catch (const IdaError&) {
      if (!live.failure().empty()) throw std::logic_error(live.failure());  // the model's live list
      throw;
    }
  };
  restart(t0, y, {});
  if (sample) {
    std::vector<double> y0;
    pull(y0);
    sample(t0, y0);
  }

  HybridOutcome out;
  long events = 0;
  while (true) {
    const auto s = step();
    pull(y);
    if (sample) sample(s.t, y);
    out.end_time = s.t;
    if (s.root_found) {
      ++events;
      if (events > o.max_events)
        throw std::runtime_error(fmt::format("hybrid run: more than {} events by t = {:.9g} s (chattering?)",
                                             o.max_events, s.t));
      const auto action = system.on_event(s.t, y, s.roots_found);
      if (sample) sample(s.t, y);
      if (action == HybridSystem::EventAction::Stop) {
        out.stopped_by_model = true;
        break;
      }
      restart(s.t, y, s.roots_found);
      pull(y);
      continue;
    }
    if (s.stop_time_reached || s.t >= o.end_time) break;
    if (o.stop_when_finished && system.finished(s.t, y.data())) {
      out.stopped_by_model = true;
      break;
    }
  }
  IdaStatistics st;
  long restarts = 0;
  for (const auto& [size, solver] : solvers) {
    st += solver->statistics();
    restarts += solver->restarts();
  }
  out.statistics = {st.steps, st.error_test_failures + st.nonlinear_convergence_failures,
                    st.residual_evaluations, st.jacobian_evaluations, st.nonlinear_iterations,
                    events, restarts};
  return out;
}

HybridOutcome run_odeint(HybridSystem& system, double t0, std::vector<double>& y,
                         const HybridOptions& o, const HybridSampler& sample) {
  OdeintOptions oo;
  oo.relative_tolerance = o.relative_tolerance;
  oo.absolute_tolerance = o.absolute_tolerance;
  oo.initial_step = o.initial_step;
  oo.max_step = o.max_step;
  OdeintEventOptions ev;
  ev.root_count = system.root_count();
  ev.roots = [&](double t, const std::vector<double>& x, double* g) { system.event_roots(t, x.data(), g); };
  ev.mask_tolerance = o.root_mask_tolerance;
  ev.time_tolerance = o.odeint_event_time_tolerance.value_or(0.0);

  HybridOutcome out;
  OdeintStatistics stats;
  long events = 0, restarts = 0;
  double t = t0;
  if (sample) sample(t0, y);
  std::vector<int> fired;
  while (t < o.end_time) {
    ev.masked = near_zero_roots(system, t, y, o.root_mask_tolerance, fired);
    bool stop_now = false;
    auto sampler = [&](double ts, const std::vector<double>& ys) {
      if (sample) sample(ts, ys);
      if (o.stop_when_finished && system.finished(ts, ys.data())) stop_now = true;
      return !stop_now;
    };
    const auto s = integrate_until_event(system, y, t, o.end_time, oo, ev, sampler, &stats);
    if (s.stopped_by_sampler) {
      t = s.t;
      out.stopped_by_model = true;
      break;
    }
    t = s.t;
    if (s.last_step > 0.0) oo.initial_step = s.last_step;
    if (!s.root_found) break;
    fired = s.roots_found;
    ++events;
    if (events > o.max_events)
      throw std::runtime_error(fmt::format("hybrid run: more than {} events by t = {:.9g} s (chattering?)",
                                           o.max_events, t));
    const auto action = system.on_event(t, y, s.roots_found);
    if (sample) sample(t, y);
    if (action == HybridSystem::EventAction::Stop) {
      out.stopped_by_model = true;
      break;
    }
    ++restarts;
  }
  out.end_time = t;
  out.statistics = {stats.steps, 0, stats.rhs_evaluations, 0, 0, events, restarts};
  return out;
}

}  // namespace

HybridOutcome run_hybrid(HybridSystem& system, double t0, std::vector<double>& y,
                         const HybridOptions& options, const HybridSampler& sample) {
  if (y.size() != system.size()) throw std::invalid_argument("run_hybrid: state size does not match the system");
  if (!(options.end_time > t0)) throw std::invalid_argument("run_hybrid: end time must follow the start");
  if (const double f = options.ida_restart_step_fraction.value_or(0.0); !(f >= 0.0 && f <= 1.0))
    throw std::invalid_argument(fmt::format("run_hybrid: ida_restart_step_fraction = {} (need 0 (off) to 1)", f));
  // IDA's step-size changes (HybridOptions::ida_step_growth_*): IDA would quietly put its own
  // value in place of one out of range.
  const double growth = options.ida_step_growth_threshold.value_or(2.0);
  if (!(growth >= 1.0 && std::isfinite(growth)))
    throw std::invalid_argument(fmt::format("run_hybrid: ida_step_growth_threshold = {} (need finite, >= 1)", growth));
  if (const double f = options.ida_step_hold_floor.value_or(1.0); !(f > 0.0 && f <= 1.0))
    throw std::invalid_argument(fmt::format("run_hybrid: ida_step_hold_floor = {} (need 0 < floor <= 1)", f));
  if (const double g = options.ida_step_growth_max.value_or(std::max(2.0, growth)); !(g >= growth && std::isfinite(g)))
    throw std::invalid_argument(
        fmt::format("run_hybrid: ida_step_growth_max = {} (need finite, >= the growth threshold {})", g, growth));
  if (const double w = options.odeint_event_time_tolerance.value_or(0.0); !(w >= 0.0 && std::isfinite(w)))
    throw std::invalid_argument(fmt::format("run_hybrid: odeint_event_time_tolerance = {} s (need finite, >= 0)", w));
  return options.integrator == HybridIntegrator::Ida ? run_ida(system, t0, y, options, sample)
                                                     : run_odeint(system, t0, y, options, sample);
}

std::string to_string(HybridIntegrator i) { return i == HybridIntegrator::Ida ? "ida" : "odeint"; }

}  // namespace ringcrush::hinge
