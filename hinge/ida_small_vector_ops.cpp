#include "ida_small_vector_ops.hpp"

#include <cmath>

namespace ringcrush::hinge {
namespace {

// z = a x + b y. SUNDIALS' serial linear sum computes every case as a·x + b·y with the same
// rounding (its ±1 factors are exact), except two: a = b and a = −b (neither ±1), which it
// evaluates as a(x + y) and a(x − y); kept so, for the same bits.
void linear_sum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(x);
  const realtype *xd = NV_DATA_S(x), *yd = NV_DATA_S(y);
  realtype* zd = NV_DATA_S(z);
  const bool unit = a == 1.0 || a == -1.0 || b == 1.0 || b == -1.0;
  if (!unit && a == b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (!unit && a == -b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
  }
}

void scale(realtype c, N_Vector x, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(x);
  const realtype* xd = NV_DATA_S(x);
  realtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
}

void constant(realtype c, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  realtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}

realtype wrms_norm(N_Vector x, N_Vector w) {
  const sunindextype n = NV_LENGTH_S(x);
  const realtype *xd = NV_DATA_S(x), *wd = NV_DATA_S(w);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const realtype p = xd[i] * wd[i];
    sum += p * p;
  }
  const realtype mean = sum / static_cast<realtype>(n);
  return mean <= 0.0 ? 0.0 : std::sqrt(mean);
}

// SUNDIALS' fallback without fused operations: z = c₀X₀, then z = cᵢXᵢ + z term by term
// (a term may be z itself: each pass reads z as the last one left it).
int linear_combination(int nvec, realtype* c, N_Vector* X, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  realtype* zd = NV_DATA_S(z);
  const realtype* x0 = NV_DATA_S(X[0]);
  for (sunindextype j = 0; j < n; ++j) zd[j] = c[0] * x0[j];
  for (int i = 1; i < nvec; ++i) {
    const realtype ci = c[i];
    const realtype* xi = NV_DATA_S(X[i]);
    for (sunindextype j = 0; j < n; ++j) zd[j] = ci * xi[j] + zd[j];
  }
  return 0;
}

int linear_sum_vector_array(int nvec, realtype a, N_Vector* X, realtype b, N_Vector* Y, N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) linear_sum(a, X[i], b, Y[i], Z[i]);
  return 0;
}

}  // namespace

void use_small_vector_ops(N_Vector v) {
  v->ops->nvlinearsum = linear_sum;
  v->ops->nvscale = scale;
  v->ops->nvconst = constant;
  v->ops->nvwrmsnorm = wrms_norm;
  v->ops->nvlinearcombination = linear_combination;
  v->ops->nvlinearsumvectorarray = linear_sum_vector_array;
}

}  // namespace ringcrush::hinge
