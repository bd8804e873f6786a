// IDA for the Level 2 polygon chain (THEORY §4.4): BDF on F(t, y, y′) = 0. The iteration
// matrix ∂F/∂y + cj ∂F/∂y′ is banded per ring plus contact couplings whose pattern changes as
// contacts open and close; it is formed at linear-solver setups (analytic by default,
// PolygonChain::analytic_jacobian_scatter, or coloured differences) with ∂F/∂y kept apart
// from cj ∂F/∂y′ = cj diag μ (README, Level 2 per-step cost). The dense and band solvers of
// IdaSolver would cost O(n³) or O(n·bw²) with bw ≈ half a ring. Two linear solvers:
//   * Direct (default): a sparse direct solve (SUNDIALS' KLU on a compressed-column matrix;
//     the symbolic analysis is redone only when the contact pattern changes). One
//     forward/back substitution per Newton iteration.
//   * Krylov: SPGMR preconditioned by a sparse LU (Eigen SparseLU) of the same matrix, with
//     difference-quotient Jacobian–vector products (one residual per GMRES iteration). Kept
//     for comparison: on Test 30 it costs 2.4–3.7× the CPU time of the direct solve on the
//     analytic matrix (README, Level 2 speed): a preconditioner gone stale with cj or the
//     contacts makes GMRES iterate (≈ 25 000 iterations per run).
#pragma once

#include <memory>
#include <vector>

#include "ida_solver.hpp"
#include "polygon_chain.hpp"

namespace ringcrush::hinge {

enum class PolygonLinearSolver { Direct, Krylov };
// Iteration matrix: from the force-law derivatives (PolygonChain::analytic_jacobian, one
// residual-like pass) or by coloured differences (PolygonChain::sparse_jacobian, ~6 × colours
// residuals).
enum class PolygonJacobian { Analytic, Differences };

// One accepted BDF step, for diagnostics (PolygonIdaOptions::step_log): its end time, size
// and order, and the component whose weighted local error estimate |e_i| w_i was largest —
// which unknown limited the step.
struct PolygonIdaStep {
  double t = 0, h = 0;
  int order = 0;
  long worst_component = -1;
  double worst_weighted_error = 0;
};

struct PolygonIdaOptions {
  PolygonLinearSolver linear_solver = PolygonLinearSolver::Direct;
  PolygonJacobian jacobian = PolygonJacobian::Analytic;
  double relative_tolerance = 1e-6;
  // Absolute tolerance per component = absolute_scale × the component's scale
  // (PolygonChain::component_scales: R for positions, impact speed for velocities, 1 rad, KE).
  double absolute_scale = 1e-6;
  // Factors on that absolute tolerance for the velocities (nodes and bodies) and for the
  // hinge plastic rotations θp, ā. Kept apart because they set the step count on Test 30
  // (README, Level 2 speed): the largest weighted local errors are almost always node
  // velocities — the sideways vx of nodes that hardly move, whose tolerance is the absolute
  // one — then θp and ā of hinges that start or stop to yield; positions and the energy
  // accumulators rarely limit a step.
  double velocity_tolerance_factor = 1.0;
  double plastic_tolerance_factor = 1.0;
  double max_step = 0.0;  // 0: no bound
  long max_steps = 2000000;
  double initial_step = 1e-8;
  // Highest BDF order. BDF1–2 are A-stable: they step over the undamped node-scale
  // vibrations of the polygon (ω ≈ 1e6 rad/s) instead of resolving them.
  int max_order = 5;
  // Relative change of cj that triggers a new Jacobian (IDASetDeltaCjLSetup; IDA's default
  // 0.25). A stale matrix only costs Newton (direct) or GMRES (Krylov) iterations.
  double cj_setup_ratio = 0.25;
  // Newton stops when its estimated error is below this fraction of the local error
  // tolerance (IDASetNonlinConvCoef; IDA's default 0.33). The default is too loose for the
  // direct solver with its matrix kept over several steps: a stopped Newton leaves every
  // step's energy slightly behind, always the same way, and on Test 30 at rtol 1e-3 the
  // energy balance drifts to 1.0e-3 (welded) and 1.9e-3 (plated) at 0.33, 0.4e-3 and
  // 1.3e-3 at 0.1; 0.03 brings it to 0.9e-4 and 2.5e-4 for ~10–20 % more Newton work.
  // (SPGMR, whose Jacobian–vector products are exact, drifts less at 0.33: 2.3e-4.)
  double nonlinear_convergence_coefficient = 0.03;
  // Direct solver: a setup keeps the last ∂φ/∂y (and only adds the new cj ∂F/∂y′ = cj diag μ)
  // while fewer than this many steps have been accepted since it was formed and no step has
  // failed since; 0 forms it at every setup. IDA asks for a setup when cj has changed, with
  // the state barely moved.
  int jacobian_reuse_steps = 0;
  // KLU's fill-reducing ordering (SUNLinSol_KLUSetOrdering): 0 AMD, 1 COLAMD (SUNDIALS'
  // default), 2 natural. The matrix is structurally near-symmetric (ring bands, contact
  // couplings both ways), the case AMD is made for.
  int klu_ordering = 1;
  // Direct solver: when the contact pattern changes, entries that vanished stay in the
  // compressed-column pattern as zeros while they make up at most this fraction of it, so
  // that a contact that returns needs no new symbolic factorisation; 0 keeps the exact
  // pattern.
  double pattern_slack = 0.0;
  // When set, every accepted step is appended here (IDA is then driven one step at a time;
  // the steps are the same as without the log).
  std::vector<PolygonIdaStep>* step_log = nullptr;
};

struct PolygonIdaStatistics {
  long steps = 0, residual_evaluations = 0, nonlinear_iterations = 0, error_test_failures = 0,
       nonlinear_convergence_failures = 0, preconditioner_setups = 0, linear_iterations = 0,
       symbolic_factorisations = 0,  // direct solver: setups whose contact pattern changed
       jacobian_formations = 0,      // direct solver: setups that formed ∂φ/∂y anew
       pattern_rebuilds = 0,  // direct solver: entry sequences that needed a new CSC pattern
       pattern_remaps = 0;    // … and those mapped onto the old one (pattern_slack)
};

class PolygonIdaSolver {
 public:
  // y0 must be a consistent state; y′0 is computed from the model's explicit form.
  PolygonIdaSolver(PolygonChain& system, double t0, const std::vector<double>& y0,
                   const PolygonIdaOptions& options = {});
  ~PolygonIdaSolver();
  PolygonIdaSolver(const PolygonIdaSolver&) = delete;
  PolygonIdaSolver& operator=(const PolygonIdaSolver&) = delete;

  // Integrates to tout (IDA_NORMAL, interpolated output) and returns the reached time.
  double advance(double tout);
  double time() const { return t_; }
  const std::vector<double>& y() const { return y_; }
  PolygonIdaStatistics statistics() const;

 private:
  struct Impl;
  static void log_step(Impl& m, double t);
  std::unique_ptr<Impl> impl_;
  double t_;
  std::vector<double> y_;
};

}  // namespace ringcrush::hinge
