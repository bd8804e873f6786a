// A hybrid (piecewise-smooth, event-driven) model and the driver that integrates it with
// either SUNDIALS IDA or Boost.Odeint — the same model object on both paths.
//
// The model is a DAE F(t, y, y′) = 0 (DaeSystem) and, for the explicit path, the ODE
// y′ = f(t, y) of the same mode (OdeSystem; algebraic components carry f = 0 there and are
// not read by the model). Mode switches — hinge yield and unloading, a rigid ring starting
// to crush, contact opening, lock-up — are root functions g(t, y). At a located root the
// driver hands the state to on_event(), which switches modes and may apply a velocity jump
// (plastic impact); the integration then restarts: IDAReInit + IDACalcIC on IDA (stop time
// set per segment), a fresh dense-output stepper on Odeint. Roots that sit at zero at the
// restart (the one that just fired, typically) are masked until they have left zero.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dae_system.hpp"
#include "ode_system.hpp"

namespace ringcrush::hinge {

class HybridSystem : public DaeSystem, public OdeSystem {
 public:
  std::size_t size() const override = 0;

  // Event functions, shared by both paths; scale them to O(1) (see root masking).
  std::size_t root_count() const override = 0;
  virtual void event_roots(double t, const double* y, double* g) = 0;
  void roots(double t, const double* y, const double* /*yp*/, double* g) final {
    event_roots(t, y, g);
  }

  // Expected sign with which root i leaves zero right after a restart (+1, −1; 0: no
  // expectation). `fired` is the direction in which root i has just crossed (0 if it did
  // not): by default a root keeps going the way it crossed; a model whose mode switch gave
  // the root a new meaning says where the new function heads (e.g. a ring that has started
  // to crush: its crush rate grows). Roots sitting at zero after a restart are masked with
  // this sign, so that leaving zero the *other* way is still an event (IdaSolver::reinit).
  virtual int root_departure(std::size_t /*i*/, int fired) const { return fired; }

  enum class EventAction { Continue, Stop };
  // A root fired at t (fired[i] = +1 rising, −1 falling, 0 not). y is the state there; the
  // model may change its mode and y (jumps). Stop ends the run.
  virtual EventAction on_event(double t, std::vector<double>& y, const std::vector<int>& fired) = 0;

  // Called after every accepted step; true ends the run (e.g. the chain has come to rest).
  virtual bool finished(double /*t*/, const double* /*y*/) { return false; }

  // The components that can move until the next event, in the current mode (ascending,
  // distinct; empty: all). The others must have a zero derivative there. Read at every
  // restart when HybridOptions::ida_reduced_state is on (hinge/ida_live_state.hpp).
  virtual std::vector<std::size_t> live_components() const { return {}; }

  // The root functions that can change sign until the next event, in the current mode
  // (ascending, distinct; empty: all). The others must keep the sign they have at the restart
  // (a named error otherwise). Read at every restart when HybridOptions::ida_live_roots is on
  // (hinge/ida_live_roots.hpp).
  virtual std::vector<std::size_t> live_roots() const { return {}; }

  // IDA's absolute tolerance per component for the run's relative and absolute tolerances
  // (empty: `absolute` for every component), for a state whose components differ in units or
  // scale (m, m/s, J). Read at every restart when HybridOptions::ida_component_tolerances is
  // on (IDASVtolerances).
  virtual std::vector<double> absolute_tolerances(double /*relative*/, double /*absolute*/) const { return {}; }
};

enum class HybridIntegrator { Ida, Odeint };

struct HybridOptions {
  HybridIntegrator integrator = HybridIntegrator::Ida;
  double relative_tolerance = 1e-8;
  double absolute_tolerance = 1e-10;
  double end_time = 1.0;
  double initial_step = 1e-7;    // Odeint; IDA chooses its own
  // IDA's first step after an event: a fraction in (0, 1] of its last step before it (Odeint
  // always restarts from its last step); 0, IDA's own first step (0.5/‖y′‖ in its error
  // weights: ~1e-11 s at rtol 1e-8, then ~20 doublings back); unset, the model's choice (the
  // driver: 0). For models with many events (Level 3 with ring inertia sets 0.003).
  std::optional<double> ida_restart_step_fraction;
  // Odeint's event bisection stops at this width (s); unset, the model's choice (the driver:
  // 64 ulp of t, ~45 halvings of a step, each evaluating every root function).
  std::optional<double> odeint_event_time_tolerance;
  // IDA on the live components only (HybridSystem::live_components, hinge/ida_live_state.hpp):
  // the held ones leave IDA's vector at each restart, its tolerances scaled so that its error
  // norm is the whole state's. Unset, the model's choice (the driver: off). Not for systems
  // with algebraic components.
  std::optional<bool> ida_reduced_state;
  // IDA's absolute tolerance per component, the model's absolute_tolerances(). Unset, the
  // model's choice (the driver: off).
  std::optional<bool> ida_component_tolerances;
  // IDA given only the model's live_roots() at each restart (its per-step root work scales
  // with their number), a held root that changes sign being an error. Unset, the model's choice
  // (the driver: off).
  std::optional<bool> ida_live_roots;
  // IDA's Newton matrix factorised by Eigen's LU instead of SUNDIALS' dense GETRF/GETRS
  // (IdaOptions::LinearSolver::EigenDense), for small live states. Unset, the model's choice
  // (the driver: off).
  std::optional<bool> ida_eigen_lu;
  // The same factorisation written out (IdaOptions::LinearSolver::SmallDense,
  // hinge/small_dense_linear_solver.hpp), for a few unknowns; before ida_eigen_lu. Unset, the
  // model's choice (the driver: off).
  std::optional<bool> ida_small_dense_lu;
  // IDA's vector operations for a few components (IdaOptions::small_vector_ops,
  // hinge/ida_small_vector_ops.hpp): the same results to the bit, fewer instructions. Unset, the
  // model's choice (the driver: off).
  std::optional<bool> ida_small_vector_ops;
  // IDA's step-size changes after a successful step (IdaOptions::step_growth; SUNDIALS 6.4's
  // IDASetEtaFixedStepBounds / IDASetEtaMax). IDA keeps its step unless its error estimate
  // allows at least doubling it (then it doubles, no more) or asks for a cut: after each
  // restart it climbs back from order 1 in doublings held for k + 1 steps each. Unset, the
  // model's choice (the driver: IDA's 2 / 1 / 2).
  //   ida_step_growth_threshold  grow once the error allows this factor (IDA: 2; >= 1)
  //   ida_step_hold_floor        cut only when the error asks for less than this (IDA: 1; in (0, 1])
  //   ida_step_growth_max        the largest growth of one step (IDA: 2; >= the threshold)
  std::optional<double> ida_step_growth_threshold;
  std::optional<double> ida_step_hold_floor;
  std::optional<double> ida_step_growth_max;
  double max_step = 0.0;         // 0: unbounded
  long max_events = 100000;
  long max_steps_per_segment = 500000;
  double root_mask_tolerance = 1e-9;
  bool stop_when_finished = true;  // false: ignore finished() and run to end_time
};

struct HybridStatistics {
  long steps = 0;
  long rejected_steps = 0;        // IDA error-test failures (Odeint's rejections are internal)
  long function_evaluations = 0;  // residuals (IDA) or right-hand sides (Odeint)
  long jacobian_evaluations = 0;
  long nonlinear_iterations = 0;
  long events = 0;
  long restarts = 0;
};

struct HybridOutcome {
  double end_time = 0.0;
  bool stopped_by_model = false;  // on_event returned Stop or finished() returned true
  HybridStatistics statistics;
};

// Sees every accepted step, and each event twice (before and after the jump).
using HybridSampler = std::function<void(double t, const std::vector<double>& y)>;

// Integrates from (t0, y) until end_time or until the model stops; y is the final state.
HybridOutcome run_hybrid(HybridSystem& system, double t0, std::vector<double>& y,
                         const HybridOptions& options, const HybridSampler& sample);

std::string to_string(HybridIntegrator);

}  // namespace ringcrush::hinge
