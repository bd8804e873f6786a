// SmallFreeMassSolve (hinge/mass_lcp.hpp, h52): the inertial Level 3 chain's free-ring solve on
// a hand-written Cholesky factor, against Eigen's LLT on the same 𝓜_ff (a Test-30-like chain
// matrix M 11ᵀ + m_r Σ w wᵀ + diag μ), its kept factor after a diagonal change, the columns
// of 𝓜_ff⁻¹, and a named error for a matrix that is not positive definite.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "hinge/mass_lcp.hpp"

using namespace ringcrush::hinge;

namespace {

Eigen::MatrixXd chain_mass(int n, double impactor, double ring) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Constant(n, n, impactor);
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) w(j) = j < i ? 0.0 : j == i ? 0.5 : 1.0;
    m += ring * w * w.transpose();
  }
  return m;
}

}  // namespace

TEST(SmallFreeMassSolve, MatchesEigensLltOnTheFreeRings) {
  Eigen::MatrixXd m = chain_mass(6, 0.257, 0.0243);
  const Eigen::VectorXd r = (Eigen::VectorXd(6) << -1200.0, 300.0, -950.0, 10.0, -2.0, 700.0).finished();
  const std::vector<Eigen::Index> free{0, 2, 5};
  SmallFreeMassSolve solve;
  for (double mu : {0.0, 3e-3, 7e-3}) {  // a crushing ring's own mass μ on the diagonal
    m(2, 2) = chain_mass(6, 0.257, 0.0243)(2, 2) + mu;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(6);
    solve.solve(m, r, free, x);
    Eigen::MatrixXd mf(3, 3);
    Eigen::VectorXd rf(3);
    for (int i = 0; i < 3; ++i) {
      rf(i) = r(free[i]);
      for (int j = 0; j < 3; ++j) mf(i, j) = m(free[i], free[j]);
    }
    const Eigen::VectorXd ref = mf.llt().solve(rf);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(x(free[i]), ref(i), 1e-12 * ref.cwiseAbs().maxCoeff()) << mu;
    for (Eigen::Index i : {1, 3, 4}) EXPECT_EQ(x(i), 0.0);
    const Eigen::MatrixXd inv = mf.inverse();
    for (int k = 0; k < 3; ++k) {
      const Eigen::VectorXd col = solve.solve_free(Eigen::VectorXd::Unit(3, k));
      EXPECT_LE((col - inv.col(k)).cwiseAbs().maxCoeff(), 1e-12 * inv.cwiseAbs().maxCoeff()) << mu << " column " << k;
    }
  }
}

TEST(SmallFreeMassSolve, NamedErrors) {
  SmallFreeMassSolve solve;
  EXPECT_THROW(solve.solve_free(Eigen::VectorXd::Ones(2)), std::logic_error);
  Eigen::MatrixXd m = Eigen::MatrixXd::Identity(2, 2);
  m(1, 1) = -1.0;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
  EXPECT_THROW(solve.solve(m, Eigen::VectorXd::Ones(2), {0, 1}, x), std::runtime_error);
}
