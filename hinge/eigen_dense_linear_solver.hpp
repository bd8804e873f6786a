// A direct SUNLinearSolver for IDA's small dense Newton matrices: Eigen's partially pivoted LU
// on the SUNDIALS dense matrix IDA fills. For the live state of Level 3 with ring inertia
// (5–15 components, hinge/ida_live_state.hpp) SUNDIALS' own dense GETRS was ~1.8k
// instructions a solve; Eigen's LU solves the same system in a fraction. Selected by
// IdaOptions::LinearSolver::EigenDense (SUNDIALS 6.4's custom linear solver interface:
// SUNLinSolNewEmpty with the setup, solve and free operations; type DIRECT).
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

namespace ringcrush::hinge {

// A solver for n × n dense matrices (SUNDenseMatrix); owned by the caller (SUNLinSolFree).
SUNLinearSolver eigen_dense_linear_solver(sunindextype n, SUNContext context);

}  // namespace ringcrush::hinge
