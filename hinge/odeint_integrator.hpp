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

}  // namespace ringcrush::hinge
