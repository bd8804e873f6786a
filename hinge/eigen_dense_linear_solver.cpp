#include "eigen_dense_linear_solver.hpp"

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Dense>

namespace ringcrush::hinge {
namespace {

struct Content {
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  sunindextype last_flag = 0;
};

Content& content(SUNLinearSolver s) { return *static_cast<Content*>(s->content); }

SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID get_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }

int setup(SUNLinearSolver s, SUNMatrix a) {
  auto& c = content(s);
  if (SUNMatGetID(a) != SUNMATRIX_DENSE) return SUNLS_ILL_INPUT;
  const auto n = static_cast<Eigen::Index>(SM_ROWS_D(a));
  c.lu.compute(Eigen::Map<const Eigen::MatrixXd>(SM_DATA_D(a), n, n));  // column-major, as SUNDIALS
  // A zero pivot: singular, recoverable for IDA (it retries with a smaller step).
  const auto& d = c.lu.matrixLU().diagonal();
  for (Eigen::Index k = 0; k < n; ++k)
    if (d(k) == 0.0) {
      c.last_flag = k + 1;
      return SUNLS_LUFACT_FAIL;
    }
  c.last_flag = 0;
  return SUNLS_SUCCESS;
}

int solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  auto& c = content(s);
  const auto n = static_cast<Eigen::Index>(N_VGetLength(b));
  Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(x), n) = c.lu.solve(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(b), n));
  return SUNLS_SUCCESS;
}

sunindextype last_flag(SUNLinearSolver s) { return content(s).last_flag; }

int free_solver(SUNLinearSolver s) {
  if (!s) return SUNLS_SUCCESS;
  delete static_cast<Content*>(s->content);
  s->content = nullptr;
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver eigen_dense_linear_solver(sunindextype n, SUNContext context) {
  SUNLinearSolver s = SUNLinSolNewEmpty(context);
  if (!s) return nullptr;
  s->ops->gettype = get_type;
  s->ops->getid = get_id;
  s->ops->setup = setup;
  s->ops->solve = solve;
  s->ops->lastflag = last_flag;
  s->ops->free = free_solver;
  auto* c = new Content;
  c->lu = Eigen::PartialPivLU<Eigen::MatrixXd>(static_cast<Eigen::Index>(n));
  s->content = c;
  return s;
}

}  // namespace ringcrush::hinge
