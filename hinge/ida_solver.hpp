// RAII owner of one SUNDIALS IDA integration (SUNDIALS 6.4): one SUNContext per
// simulation, serial vectors, a dense or band direct linear solver, optional analytic
// Jacobian, consistent initial values (IDACalcIC) and event location (IDARootInit).
// Every SUNDIALS return code passes through check_ida(), which throws IdaError naming the
// function and the flag, with IDA's own message when it gave one.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "dae_system.hpp"

namespace ringcrush::hinge {

class IdaError : public std::runtime_error {
 public:
  IdaError(std::string function, int flag, const std::string& message);
  const std::string& function() const { return function_; }
  int flag() const { return flag_; }

 private:
  std::string function_;
  int flag_;
};

inline constexpr int root_mask_inactive = 2;

struct IdaOptions {
  double relative_tolerance = 1e-8;
  double absolute_tolerance = 1e-10;
  // EigenDense: Eigen's partially pivoted LU on the same dense matrix
  // (hinge/eigen_dense_linear_solver.hpp), for small systems; SmallDense: the same written out
  // (hinge/small_dense_linear_solver.hpp), for a few unknowns.
  enum class LinearSolver { Dense, Band, EigenDense, SmallDense } linear_solver = LinearSolver::Dense;
  long upper_bandwidth = 0;  // band solver only
  long lower_bandwidth = 0;
  long max_steps = 100000;   // per call to advance()
  double max_step = 0.0;     // 0: no bound
  bool suppress_algebraic_error_test = false;  // IDASetSuppressAlg, for multipliers
  // IDA's vectors with hinge/ida_small_vector_ops.hpp's operations: SUNDIALS' serial
  // arithmetic to the bit, without its per-call dispatch, for states of a few components.
  bool small_vector_ops = false;
  // A masked root function (see IdaSolver::reinit) is reported to IDA as exactly zero until
  // its magnitude exceeds this value; models scale their root functions to O(1).
  double root_mask_tolerance = 1e-9;
  // Step-size selection after a successful step (IDASetEtaFixedStepBounds, IDASetEtaMax): IDA
  // computes the ratio η the error estimate allows; η >= growth_threshold: the step grows by
  // min(η, growth_max); η <= hold_floor: it is cut; in between it is kept. 0: IDA's own
  // (2, 1, 2). hinge/hybrid_system.hpp, HybridOptions::ida_step_growth_*.
  struct StepGrowth {
    double growth_threshold = 0.0;
    double hold_floor = 0.0;
    double growth_max = 0.0;
  } step_growth{};
};

struct IdaStatistics {
  long steps = 0;
  long residual_evaluations = 0;
  long jacobian_evaluations = 0;
  long nonlinear_iterations = 0;
  long error_test_failures = 0;
  long nonlinear_convergence_failures = 0;
  long root_evaluations = 0;

  // Counts of several runs (restarts, one solver per state size) add up.
  IdaStatistics& operator+=(const IdaStatistics& o) {
    steps += o.steps;
    residual_evaluations += o.residual_evaluations;
    jacobian_evaluations += o.jacobian_evaluations;
    nonlinear_iterations += o.nonlinear_iterations;
    error_test_failures += o.error_test_failures;
    nonlinear_convergence_failures += o.nonlinear_convergence_failures;
    root_evaluations += o.root_evaluations;
    return *this;
  }
};

class IdaSolver {
 public:
  // y0 and yp0 need not be consistent when calc_initial_conditions() is called next.
  IdaSolver(DaeSystem& system, double t0, const std::vector<double>& y0,
            const std::vector<double>& yp0, const IdaOptions& options = {});
  ~IdaSolver();
  IdaSolver(const IdaSolver&) = delete;
  IdaSolver& operator=(const IdaSolver&) = delete;

  // IDACalcIC(IDA_YA_YDP_INIT): computes the algebraic components of y and the derivatives
  // y′ of the differential ones from the differential components of y; tout1 sets the scale.
  void calc_initial_conditions(double tout1);

  // Restart after a discontinuity (mode switch, velocity jump) at the current time.
  void reinit(double t, const std::vector<double>& y, const std::vector<double>& yp);
  // Restart with masked root functions. A root that has just fired sits at zero after the
  // mode switch and would fire again at once (chattering); masked, it is held at a value of
  // its expected sign until |g_i| exceeds root_mask_tolerance:
  //   mask[i] = 0       not masked;
  //   mask[i] = +1/−1   masked, expected to leave zero upward/downward: held at ±tolerance,
  //                     so leaving the *other* way is still a sign change that IDA locates;
  //   mask[i] = root_mask_inactive  masked without expectation: held at exactly 0, which IDA
  //                     treats as inactive until it leaves zero.
  void reinit(double t, const std::vector<double>& y, const std::vector<double>& yp,
              const std::vector<int>& mask);
  // From the next reinit() on, IDA is given only the root functions `live` (the model's
  // indices, ascending, distinct; empty: all) until the next call; the others must keep their
  // sign at that restart, and one that changes it is a std::logic_error from advance()/step()
  // (hinge/ida_live_roots.hpp). Masks and roots_found stay in the model's indices.
  void set_live_roots(const std::vector<std::size_t>& live);
  // The current mask (entries drop to 0 as roots are released).
  const std::vector<int>& root_mask() const;

  void set_stop_time(double t_stop);
  // Tolerances from the next step on: relative, and absolute per component (IDASVtolerances).
  void set_tolerances(double relative, const std::vector<double>& absolute);
  // The first step IDA tries after the next (re)start (IDASetInitStep; 0: IDA's own estimate,
  // 0.001 of the way to tout cut to 0.5/‖y′‖, which at tight tolerances is ~1e-11 s).
  void set_initial_step(double h);
  // The size of the last successful step (IDAGetLastStep; 0 before the first).
  double last_step() const;
  // +1 only rising, −1 only falling, 0 both (IDASetRootDirection).
  void set_root_direction(const std::vector<int>& direction);

  struct Step {
    double t;
    bool root_found;                 // stopped at an event
    bool stop_time_reached;          // stopped at the stop time
    std::vector<int> roots_found;    // per root: +1 rising, −1 falling, 0 none
  };
  // Integrate toward tout (IDA_NORMAL); returns at tout, at the stop time or at an event.
  Step advance(double tout);
  // One internal step toward tout (IDA_ONE_STEP).
  Step step(double tout);

  double time() const { return t_; }
  const std::vector<double>& y() const { return y_; }
  const std::vector<double>& yp() const { return yp_; }
  // Counters summed over every restart (IDAReInit resets IDA's own counters).
  IdaStatistics statistics() const;
  long restarts() const { return restarts_; }

 private:
  Step run(double tout, int mode);
  void pull();

  struct Impl;
  std::unique_ptr<Impl> impl_;
  DaeSystem& system_;
  double t_;
  std::vector<double> y_, yp_;
  IdaStatistics before_restarts_;
  long restarts_ = 0;
};

}  // namespace ringcrush::hinge
