#include "small_dense_linear_solver.hpp"

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <utility>
#include <vector>

namespace ringcrush::hinge {
namespace {

struct Content {
  std::vector<double> lu;        // column-major: U on and above the diagonal, L's multipliers below
  std::vector<sunindextype> p;   // row exchanged with row k at step k
  sunindextype n = 0;
  sunindextype last_flag = 0;
};

Content& content(SUNLinearSolver s) { return *static_cast<Content*>(s->content); }

SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID get_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }

int setup(SUNLinearSolver s, SUNMatrix a) {
  auto& c = content(s);
  if (SUNMatGetID(a) != SUNMATRIX_DENSE || SM_ROWS_D(a) != c.n || SM_COLUMNS_D(a) != c.n) return SUNLS_ILL_INPUT;
  const sunindextype n = c.n;
  const double* src = SM_DATA_D(a);
  c.lu.assign(src, src + n * n);
  double* m = c.lu.data();
  for (sunindextype k = 0; k < n; ++k) {
    sunindextype piv = k;
    double best = std::abs(m[k * n + k]);
    for (sunindextype i = k + 1; i < n; ++i)
      if (const double v = std::abs(m[k * n + i]); v > best) {
        best = v;
        piv = i;
      }
    c.p[static_cast<std::size_t>(k)] = piv;
    // A zero pivot: singular, recoverable for IDA (it retries with a smaller step).
    if (best == 0.0) {
      c.last_flag = k + 1;
      return SUNLS_LUFACT_FAIL;
    }
    if (piv != k)
      for (sunindextype j = 0; j < n; ++j) std::swap(m[j * n + k], m[j * n + piv]);
    const double inv = 1.0 / m[k * n + k];
    for (sunindextype i = k + 1; i < n; ++i) m[k * n + i] *= inv;
    for (sunindextype j = k + 1; j < n; ++j) {
      const double u = m[j * n + k];
      if (u == 0.0) continue;
      for (sunindextype i = k + 1; i < n; ++i) m[j * n + i] -= m[k * n + i] * u;
    }
  }
  c.last_flag = 0;
  return SUNLS_SUCCESS;
}

int solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  const auto& c = content(s);
  const sunindextype n = c.n;
  const double* m = c.lu.data();
  double* xd = N_VGetArrayPointer(x);
  const double* bd = N_VGetArrayPointer(b);
  if (xd != bd)
    for (sunindextype i = 0; i < n; ++i) xd[i] = bd[i];
  for (sunindextype k = 0; k < n; ++k)  // P b: every exchange first (they permuted whole rows of L)
    if (const sunindextype piv = c.p[static_cast<std::size_t>(k)]; piv != k) std::swap(xd[k], xd[piv]);
  for (sunindextype k = 0; k < n; ++k) {  // L z = P b (unit diagonal)
    const double zk = xd[k];
    if (zk != 0.0)
      for (sunindextype i = k + 1; i < n; ++i) xd[i] -= m[k * n + i] * zk;
  }
  for (sunindextype k = n; k-- > 0;) {  // U x = z
    xd[k] /= m[k * n + k];
    const double xk = xd[k];
    if (xk != 0.0)
      for (sunindextype i = 0; i < k; ++i) xd[i] -= m[k * n + i] * xk;
  }
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

SUNLinearSolver small_dense_linear_solver(sunindextype n, SUNContext context) {
  SUNLinearSolver s = SUNLinSolNewEmpty(context);
  if (!s) return nullptr;
  s->ops->gettype = get_type;
  s->ops->getid = get_id;
  s->ops->setup = setup;
  s->ops->solve = solve;
  s->ops->lastflag = last_flag;
  s->ops->free = free_solver;
  auto* c = new Content;
  c->n = n;
  c->lu.assign(static_cast<std::size_t>(n * n), 0.0);
  c->p.assign(static_cast<std::size_t>(n), 0);
  s->content = c;
  return s;
}

}  // namespace ringcrush::hinge
