// Adaptive Dormand–Prince 5(4) with dense output (Boost.Odeint) over an OdeSystem.
// Used for the ODE forms of the hinge models and as the cross-check of the IDA path.
#pragma once

#include <functional>
#include <vector>

#include "ode_system.hpp"

namespace ringcrush::hinge {

struct OdeintOptions {
  double relative_tolerance = 1e-8;
  double absolute_tolerance = 1e-10;
  double initial_step = 1e-6;
  double max_step = 0.0;  // 0: no bound
};

struct OdeintStatistics {
  long steps = 0;
  long rhs_evaluations = 0;
};

// Observer called after every accepted step with the dense-output interpolant: it may
// sample the step [t_prev, t] through `at(τ, y)`; return false to stop integrating.
using DenseStepObserver = std::function<bool(
    double t_prev, double t, const std::function<void(double, std::vector<double>&)>& at)>;

// Integrates from t0 to t1 (or until the observer says stop); y holds y(t0) on entry and
// the state at the returned time on exit.
double integrate_dense(OdeSystem& system, std::vector<double>& y, double t0, double t1,
                       const OdeintOptions& options, const DenseStepObserver& observer,
                       OdeintStatistics* statistics = nullptr);

// Event location on the Odeint path (Odeint has no root finding, THEORY §4.4): after every
// accepted step the root functions are evaluated at the step end; a sign change of an
// active root is located by bisection on the step's dense-output interpolant, and the
// integration stops just past the earliest root. A masked root (masked[i] != 0) is ignored
// until |g_i| exceeds `mask_tolerance` (same convention as IdaSolver::reinit: ±1 = expected
// departure sign, held at ±tolerance so that leaving the other way is still located; any
// other non-zero value: ignored until it has left zero).
using RootFunction = std::function<void(double t, const std::vector<double>& y, double* g)>;
// Returns false to end the integration at that point (no event).
using StepSampler = std::function<bool(double t, const std::vector<double>& y)>;

struct OdeintEventOptions {
  std::size_t root_count = 0;
  RootFunction roots;
  std::vector<int> masked;         // per root; empty: none masked
  double mask_tolerance = 1e-9;
  double time_tolerance = 0.0;     // bisection width; 0: 64 ulp of t
};

struct OdeintStop {
  double t;
  bool root_found = false;
  bool stopped_by_sampler = false;
  std::vector<int> roots_found;    // per root: +1 rising, −1 falling, 0 none
  double last_step = 0.0;          // size of the last accepted step (to restart with)
};

// Integrates from t0 toward t1, stopping at the first event. y holds y(t0) on entry and the
// state at the returned time on exit; `sample` sees every accepted step end (and the event
// point). Statistics are added to *statistics.
OdeintStop integrate_until_event(OdeSystem& system, std::vector<double>& y, double t0, double t1,
                                 const OdeintOptions& options, const OdeintEventOptions& events,
                                 const StepSampler& sample, OdeintStatistics* statistics = nullptr);

}  // namespace ringcrush::hinge
