#include "mass_lcp.hpp"

#include <cmath>
#include <stdexcept>

namespace ringcrush::hinge {

MassLcpResult solve_mass_lcp(const Eigen::MatrixXd& mass, const Eigen::VectorXd& p,
                             const std::vector<char>& complementary, const std::vector<char>& zero,
                             const std::vector<char>& prefer_free) {
  const Eigen::Index n = p.size();
  if (mass.rows() != n || mass.cols() != n) throw std::invalid_argument("solve_mass_lcp: size mismatch");
  MassLcpResult r;
  r.held.assign(n, 0);
  for (Eigen::Index i = 0; i < n; ++i) r.held[i] = zero[i] ? 1 : 0;
  const double scale = std::max(p.cwiseAbs().maxCoeff(), 1e-300);
  const double tol = 1e-12 * scale;
  const int max_pivots = 50 * static_cast<int>(n) + 100;
  for (;;) {
    std::vector<Eigen::Index> free;
    for (Eigen::Index i = 0; i < n; ++i)
      if (!r.held[i]) free.push_back(i);
    const auto nf = static_cast<Eigen::Index>(free.size());
    r.x = Eigen::VectorXd::Zero(n);
    if (nf > 0) {
      Eigen::MatrixXd a(nf, nf);
      Eigen::VectorXd b(nf);
      for (Eigen::Index i = 0; i < nf; ++i) {
        b(i) = p(free[i]);
        for (Eigen::Index j = 0; j < nf; ++j) a(i, j) = mass(free[i], free[j]);
      }
      const Eigen::VectorXd xf = a.llt().solve(b);
      for (Eigen::Index i = 0; i < nf; ++i) r.x(free[i]) = xf(i);
    }
    r.mu = mass * r.x - p;
    for (Eigen::Index i = 0; i < n; ++i)
      if (!r.held[i]) r.mu(i) = 0.0;
    // Least-index violation (Murty): a free complementary x_i < 0, or a held μ_i < 0. A
    // degenerate x_i ≈ 0 counts as held (a ring on the verge of crushing stays rigid; the
    // event machinery lets it go once its force really exceeds the collapse force).
    Eigen::Index flip = -1;
    for (Eigen::Index i = 0; i < n && flip < 0; ++i) {
      if (!complementary[i] || zero[i]) continue;
      const double xs = r.x(i) * mass(i, i);  // on the scale of p
      const bool free_wins = !prefer_free.empty() && prefer_free[i];
      if ((!r.held[i] && xs < (free_wins ? -tol : tol)) || (r.held[i] && r.mu(i) < (free_wins ? tol : -tol)))
        flip = i;
    }
    if (flip < 0) return r;
    r.held[flip] = !r.held[flip];
    if (++r.pivots > max_pivots) throw std::runtime_error("solve_mass_lcp: pivoting did not terminate");
  }
}

void FreeMassSolve::solve(const Eigen::MatrixXd& mass, const Eigen::VectorXd& r,
                          const std::vector<Eigen::Index>& free, Eigen::VectorXd& x) {
  const auto nf = static_cast<Eigen::Index>(free.size());
  if (nf == 0) return;
  // The factor is kept while 𝓜_ff is the same to the bit: between events the inertial Level 3
  // chain's 𝓜 changes only through the Uniform mode's μ(δ) of a crushing ring (constant
  // through the wrap, bottom and E–C–B modes and in the velocity columns of its Jacobian).
  bool same = factored_ && mf_.rows() == nf;
  if (!same) mf_.resize(nf, nf);
  rf_.resize(nf);
  for (Eigen::Index i = 0; i < nf; ++i) {
    rf_(i) = r(free[i]);
    for (Eigen::Index j = 0; j < nf; ++j) {
      const double m = mass(free[i], free[j]);
      same = same && mf_(i, j) == m;
      mf_(i, j) = m;
    }
  }
  if (!same) llt_.compute(mf_);
  factored_ = true;
  rf_ = llt_.solve(rf_);
  for (Eigen::Index i = 0; i < nf; ++i) x(free[i]) = rf_(i);
}

void SmallFreeMassSolve::solve(const Eigen::MatrixXd& mass, const Eigen::VectorXd& r,
                               const std::vector<Eigen::Index>& free, Eigen::VectorXd& x) {
  const std::size_t nf = free.size();
  if (nf == 0) return;
  bool same = factored_ && nf_ == nf;
  if (!same) {
    nf_ = nf;
    mf_.assign(nf * nf, 0.0);
    l_.assign(nf * nf, 0.0);
  }
  rf_.resize(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    rf_[i] = r(free[i]);
    for (std::size_t j = 0; j < nf; ++j) {
      const double m = mass(free[i], free[j]);
      same = same && mf_[i * nf + j] == m;
      mf_[i * nf + j] = m;
    }
  }
  if (!same) {
    factored_ = false;
    for (std::size_t j = 0; j < nf; ++j) {
      double d = mf_[j * nf + j];
      for (std::size_t k = 0; k < j; ++k) d -= l_[j * nf + k] * l_[j * nf + k];
      if (!(d > 0.0)) throw std::runtime_error("SmallFreeMassSolve: the free mass matrix is not positive definite");
      const double ljj = std::sqrt(d);
      l_[j * nf + j] = ljj;
      for (std::size_t i = j + 1; i < nf; ++i) {
        double a = mf_[i * nf + j];
        for (std::size_t k = 0; k < j; ++k) a -= l_[i * nf + k] * l_[j * nf + k];
        l_[i * nf + j] = a / ljj;
      }
    }
  }
  factored_ = true;
  substitute(rf_.data());
  for (std::size_t i = 0; i < nf; ++i) x(free[i]) = rf_[i];
}

void SmallFreeMassSolve::substitute(double* b) const {
  const std::size_t nf = nf_;
  for (std::size_t i = 0; i < nf; ++i) {  // L z = b
    double a = b[i];
    for (std::size_t k = 0; k < i; ++k) a -= l_[i * nf + k] * b[k];
    b[i] = a / l_[i * nf + i];
  }
  for (std::size_t i = nf; i-- > 0;) {  // Lᵀ x = z
    double a = b[i];
    for (std::size_t k = i + 1; k < nf; ++k) a -= l_[k * nf + i] * b[k];
    b[i] = a / l_[i * nf + i];
  }
}

Eigen::VectorXd SmallFreeMassSolve::solve_free(const Eigen::VectorXd& b) const {
  if (!factored_ || static_cast<std::size_t>(b.size()) != nf_)
    throw std::logic_error("SmallFreeMassSolve::solve_free: no factor of that size (solve() first)");
  Eigen::VectorXd x = b;
  substitute(x.data());
  return x;
}

}  // namespace ringcrush::hinge
