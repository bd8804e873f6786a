// IDA's Newton matrix factorised by Eigen's partially pivoted LU (hinge/eigen_dense_linear_solver.hpp,
// IdaOptions::LinearSolver::EigenDense) and by the same written out (h52,
// hinge/small_dense_linear_solver.hpp, SmallDense) against SUNDIALS' dense GETRF/GETRS: an index-1 DAE whose
// Newton matrix has a zero on the diagonal (so the LU must pivot) to its closed form and to the
// SUNDIALS solver; a singular Newton matrix is IDA's named error, as with SUNDIALS' solver.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>
#include <algorithm>

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

TEST(SmallDenseLinearSolver, PivotsAndMatchesSundialsDense) {
  SwappedDecay a, b;
  IdaSolver small(a, 0.0, {1.0, 0.0}, {-3.0, 0.0}, options(IdaOptions::LinearSolver::SmallDense));
  IdaSolver dense(b, 0.0, {1.0, 0.0}, {-3.0, 0.0}, options(IdaOptions::LinearSolver::Dense));
  for (double t : {0.5, 1.0, 2.0, 5.0}) {
    small.advance(t);
    dense.advance(t);
    EXPECT_NEAR(small.y()[0], a.exact(t), 1e-6) << t;
    EXPECT_NEAR(small.y()[1], std::sin(t), 1e-6) << t;
    EXPECT_NEAR(small.y()[1], dense.y()[1], 1e-12) << t;
    EXPECT_NEAR(small.y()[0], dense.y()[0], 1e-12) << t;
  }
  EXPECT_EQ(small.statistics().steps, dense.statistics().steps);
  EXPECT_GT(small.statistics().jacobian_evaluations, 0);
}

// A zero row: the LU reports the zero pivot as a recoverable setup failure, IDA cuts its step
// until it gives up, and IdaSolver names the failure (IdaError), as with SUNDIALS' solver.
TEST(EigenDenseLinearSolver, SingularMatrixIsANamedError) {
  for (auto solver : {IdaOptions::LinearSolver::EigenDense, IdaOptions::LinearSolver::SmallDense,
                      IdaOptions::LinearSolver::Dense}) {
    SwappedDecay m;
    m.singular = true;
    IdaSolver ida(m, 0.0, {1.0, 0.0}, {-3.0, 0.0}, options(solver));
    EXPECT_THROW(ida.advance(1.0), IdaError) << static_cast<int>(solver);
  }
}

namespace {

// y′ = A y on n components with the residual rows permuted (row k holds component (k + 1) mod n
// reversed): the Newton matrix's diagonal is mostly off-diagonal entries of cj I − A, zero
// where A's are, so the LU must pivot at every size.
class PermutedLinear final : public DaeSystem {
 public:
  explicit PermutedLinear(int n) : n_(n), a_(n, n) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) a_(i, j) = i == j ? -2.0 - 0.1 * i : (i + 2 * j) % 3 == 0 ? 0.0 : 0.05 * (i - j);
  }
  std::size_t size() const override { return static_cast<std::size_t>(n_); }
  int row(int i) const { return n_ - 1 - (i + 1) % n_; }
  void residual(double, const double* y, const double* yp, double* r) override {
    for (int i = 0; i < n_; ++i) {
      double f = 0.0;
      for (int j = 0; j < n_; ++j) f += a_(i, j) * y[j];
      r[row(i)] = yp[i] - f;
    }
  }
  bool has_jacobian() const override { return true; }
  void jacobian(double, double cj, const double*, const double*, JacobianSink& jac) override {
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j) jac.set(static_cast<std::size_t>(row(i)), static_cast<std::size_t>(j), (i == j ? cj : 0.0) - a_(i, j));
  }

 private:
  int n_;
  Eigen::MatrixXd a_;
};

}  // namespace

// On the sizes IDA's live state takes (1–15), pivoting at every size: the same steps as
// SUNDIALS' dense solver and the same solution to 1e-11 of its size.
TEST(SmallDenseLinearSolver, PivotsOnTheLiveSizes) {
  for (int n = 1; n <= 15; ++n) {
    PermutedLinear a(n), b(n);
    std::vector<double> y0(static_cast<std::size_t>(n)), yp0(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i) y0[static_cast<std::size_t>(i)] = 1.0 + 0.1 * i;
    std::vector<double> r(static_cast<std::size_t>(n));
    a.residual(0.0, y0.data(), yp0.data(), r.data());
    for (int i = 0; i < n; ++i) yp0[static_cast<std::size_t>(i)] = -r[static_cast<std::size_t>(a.row(i))];
    IdaSolver small(a, 0.0, y0, yp0, options(IdaOptions::LinearSolver::SmallDense));
    IdaSolver dense(b, 0.0, y0, yp0, options(IdaOptions::LinearSolver::Dense));
    small.advance(1.0);
    dense.advance(1.0);
    double scale = 0.0;
    for (double v : dense.y()) scale = std::max(scale, std::abs(v));
    for (std::size_t i = 0; i < y0.size(); ++i) EXPECT_NEAR(small.y()[i], dense.y()[i], 1e-11 * scale) << n << ", " << i;
    EXPECT_EQ(small.statistics().steps, dense.statistics().steps) << n;
  }
}
