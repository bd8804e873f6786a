// IDA's Newton matrix factorised by Eigen's partially pivoted LU (hinge/eigen_dense_linear_solver.hpp,
// IdaOptions::LinearSolver::EigenDense) against SUNDIALS' dense GETRF/GETRS: an index-1 DAE whose
// Newton matrix has a zero on the diagonal (so the LU must pivot) to its closed form and to the
// SUNDIALS solver; a singular Newton matrix is IDA's named error, as with SUNDIALS' solver.
#include <gtest/gtest.h>

#include <cmath>

#include "hinge/ida_solver.hpp"

using namespace ringcrush::hinge;

namespace {

// x′ = −k x + z, 0 = z − sin t, with the algebraic equation first among the residuals:
// ∂F/∂y + cj ∂F/∂y′ = [[0, 1], [cj + k, −1]] for y = (x, z), a zero pivot without a row
// exchange. Closed form with x(0) = 1: x = C e^{−kt} + (k sin t − cos t)/(1 + k²),
// C = 1 + 1/(1 + k²).
class SwappedDecay final : public DaeSystem {
 public:
  bool singular = false;  // the algebraic equation dropped: a zero row
  std::size_t size() const override { return 2; }
  void residual(double t, const double* y, const double* yp, double* r) override {
    r[0] = singular ? 0.0 : y[1] - std::sin(t);
    r[1] = yp[0] + k_ * y[0] - y[1];
  }
  std::vector<double> differential_mask() const override { return {1.0, 0.0}; }
  bool has_jacobian() const override { return true; }
  void jacobian(double, double cj, const double*, const double*, JacobianSink& j) override {
    if (!singular) j.set(0, 1, 1.0);
    j.set(1, 0, cj + k_);
    j.set(1, 1, -1.0);
  }
  double exact(double t) const {
    const double a = 1.0 + k_ * k_;
    return (1.0 + 1.0 / a) * std::exp(-k_ * t) + (k_ * std::sin(t) - std::cos(t)) / a;
  }

 private:
  double k_ = 3.0;
};

IdaOptions options(IdaOptions::LinearSolver solver) {
  IdaOptions o{.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12};
  o.linear_solver = solver;
  return o;
}

}  // namespace

// The same steps as SUNDIALS' dense solver and the same answer to 1e-12 (both solve the same
// 2 × 2 systems exactly up to round-off), the closed form to 1e-6 as IdaWiring holds IDA.
TEST(EigenDenseLinearSolver, PivotsAndMatchesSundialsDense) {
  SwappedDecay a, b;
  IdaSolver eigen(a, 0.0, {1.0, 0.0}, {-3.0, 0.0}, options(IdaOptions::LinearSolver::EigenDense));
  IdaSolver dense(b, 0.0, {1.0, 0.0}, {-3.0, 0.0}, options(IdaOptions::LinearSolver::Dense));
  for (double t : {0.5, 1.0, 2.0, 5.0}) {
    eigen.advance(t);
    dense.advance(t);
    EXPECT_NEAR(eigen.y()[0], a.exact(t), 1e-6) << t;
    EXPECT_NEAR(eigen.y()[1], std::sin(t), 1e-6) << t;
    EXPECT_NEAR(eigen.y()[1], dense.y()[1], 1e-12) << t;
    EXPECT_NEAR(eigen.y()[0], dense.y()[0], 1e-12) << t;
  }
  EXPECT_EQ(eigen.statistics().steps, dense.statistics().steps);
  EXPECT_GT(eigen.statistics().jacobian_evaluations, 0);
}

// A zero row: the LU reports the zero pivot as a recoverable setup failure, IDA cuts its step
// until it gives up, and IdaSolver names the failure (IdaError), as with SUNDIALS' solver.
TEST(EigenDenseLinearSolver, SingularMatrixIsANamedError) {
  for (auto solver : {IdaOptions::LinearSolver::EigenDense, IdaOptions::LinearSolver::Dense}) {
    SwappedDecay m;
    m.singular = true;
    IdaSolver ida(m, 0.0, {1.0, 0.0}, {-3.0, 0.0}, options(solver));
    EXPECT_THROW(ida.advance(1.0), IdaError) << static_cast<int>(solver);
  }
}
