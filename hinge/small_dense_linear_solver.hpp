// A direct SUNLinearSolver for IDA's Newton matrices of a few unknowns (the inertial Level 3
// chain's live state, 5–15 components, hinge/ida_live_state.hpp): LU with partial pivoting
// (the largest pivot in its column) written out on the SUNDIALS dense matrix's column-major
// array, and its two triangular solves. Eigen's dynamic-size PartialPivLU
// (hinge/eigen_dense_linear_solver.hpp, h36's) spent ~1.2k instructions a solve on setting
// up its blocks at these sizes (h52). Selected by IdaOptions::LinearSolver::SmallDense.
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

namespace ringcrush::hinge {

// A solver for n × n dense matrices (SUNDenseMatrix); owned by the caller (SUNLinSolFree).
SUNLinearSolver small_dense_linear_solver(sunindextype n, SUNContext context);

}  // namespace ringcrush::hinge
