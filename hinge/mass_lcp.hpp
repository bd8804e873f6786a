// The small linear complementarity problems of rigid–plastic mechanisms (THEORY §4.4
// "Rigid rings … as a linear complementarity problem"): with a symmetric positive definite
// mass matrix 𝓜,
//
//   𝓜 x = p + Σ μ_i e_i,   for i complementary: x_i ≥ 0, μ_i ≥ 0, x_i μ_i = 0;
//                           for i held at zero:  x_i = 0, μ_i free;   otherwise μ_i = 0.
//
// At the velocity level (plastic impact: p = generalised momentum, x = velocities after
// the impact, μ = impulses of rings that stay rigid) and at the acceleration level (x =
// accelerations, μ = the margin of a rigid ring below its collapse force). 𝓜 positive
// definite makes it a P-matrix LCP with a unique solution, found by Murty's least-index
// principal pivoting (finite for P-matrices).
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace ringcrush::hinge {

struct MassLcpResult {
  Eigen::VectorXd x, mu;
  std::vector<char> held;  // x_i held at zero (complementary or fixed)
  int pivots = 0;
};

// complementary[i], zero[i]: flags per component (zero wins). Throws std::runtime_error if
// the pivoting does not terminate (a non-positive-definite 𝓜).
// Degenerate components (x_i ≈ 0 and μ_i ≈ 0) are held at zero unless prefer_free[i].
MassLcpResult solve_mass_lcp(const Eigen::MatrixXd& mass, const Eigen::VectorXd& p,
                             const std::vector<char>& complementary,
                             const std::vector<char>& zero,
                             const std::vector<char>& prefer_free = {});

// Accelerations of the coordinates that move, the others held (the acceleration level once
// the LCP has decided who moves): 𝓜_ff ẍ_f = r_f, written into x at the free indices (the
// caller zeroes the held ones). Its buffers live between calls: it runs at every right-hand
// side of Level 1 and of the inertial Level 3 chain.
class FreeMassSolve {
 public:
  void solve(const Eigen::MatrixXd& mass, const Eigen::VectorXd& r,
             const std::vector<Eigen::Index>& free, Eigen::VectorXd& x);

 private:
  Eigen::MatrixXd mf_;
  Eigen::VectorXd rf_;
  Eigen::LLT<Eigen::MatrixXd> llt_;  // of mf_
  bool factored_ = false;
};

// FreeMassSolve's problem for the inertial Level 3 chain (a few rings, a solve at every
// residual, root and Jacobian evaluation): the Cholesky factor and the two triangular solves
// written out on plain arrays, where Eigen's dynamic-size LLT spent most of a 1–6 unknown
// solve in its setup (h52). The factor is kept while 𝓜_ff is the same to the bit. Not
// FreeMassSolve's rounding (Level 1 keeps that one, bitwise).
class SmallFreeMassSolve {
 public:
  // Throws std::runtime_error if 𝓜_ff is not positive definite.
  void solve(const Eigen::MatrixXd& mass, const Eigen::VectorXd& r,
             const std::vector<Eigen::Index>& free, Eigen::VectorXd& x);
  // 𝓜_ff⁻¹ b in the free coordinates of the last solve() (its factor): the columns of the
  // chain's analytic Jacobian. Throws std::logic_error without a factor of b's size.
  Eigen::VectorXd solve_free(const Eigen::VectorXd& b) const;

 private:
  void substitute(double* b) const;  // b ← 𝓜_ff⁻¹ b in place
  std::vector<double> mf_, l_;       // 𝓜_ff and its lower factor, row-major
  std::vector<double> rf_;
  std::size_t nf_ = 0;
  bool factored_ = false;
};

}  // namespace ringcrush::hinge
