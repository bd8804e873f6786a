// IDA for the Level 2 polygon chain (THEORY §4.4): BDF on F(t, y, y′) = 0 with a Krylov
// linear solver (SPGMR) preconditioned by an exact sparse LU (Eigen SparseLU) of
// ∂F/∂y + cj ∂F/∂y′. The Jacobian is banded per ring plus contact couplings whose pattern
// changes as contacts open and close, so it is rebuilt (coloured finite differences,
// PolygonChain::sparse_jacobian) and refactorised at every preconditioner setup. The dense
// and band solvers of IdaSolver would cost O(n³) or O(n·bw²) with bw ≈ half a ring.
#pragma once

#include <memory>
#include <vector>

#include "ida_solver.hpp"
#include "polygon_chain.hpp"

namespace ringcrush::hinge {

struct PolygonIdaOptions {
  double relative_tolerance = 1e-6;
  // Absolute tolerance per component = absolute_scale × the component's scale
  // (PolygonChain::component_scales: R for positions, impact speed for velocities, 1 rad, KE).
  double absolute_scale = 1e-6;
  double max_step = 0.0;  // 0: no bound
  long max_steps = 2000000;
  double initial_step = 1e-8;
  // Highest BDF order. BDF1–2 are A-stable: they step over the undamped node-scale
  // vibrations of the polygon (ω ≈ 1e6 rad/s) instead of resolving them.
  int max_order = 5;
  // Relative change of cj that triggers a new preconditioner (IDASetDeltaCjLSetup; IDA's
  // default 0.25). A stale preconditioner only costs GMRES iterations.
  double cj_setup_ratio = 0.25;
};

struct PolygonIdaStatistics {
  long steps = 0, residual_evaluations = 0, nonlinear_iterations = 0, error_test_failures = 0,
       nonlinear_convergence_failures = 0, preconditioner_setups = 0, linear_iterations = 0;
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
  std::unique_ptr<Impl> impl_;
  double t_;
  std::vector<double> y_;
};

}  // namespace ringcrush::hinge
