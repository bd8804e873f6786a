// Sparse direct solver for the Newton corrections. Frictionless, the tangent is symmetric
// (J2 consistent tangent, total-Lagrangian geometric stiffness and penalty contact are all
// second derivatives of one potential): LDLᵀ. With Coulomb friction the consistent tangent of
// a slipping contact is not symmetric (the friction force depends on the normal force,
// fe/contact/plate_friction.hpp): sparse LU (COLAMD ordering, partial pivoting). Either way
// the symbolic analysis is done once per sparsity pattern; each iteration only factorises
// numerically.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

namespace ringcrush::fe {

class LinearSolver {
 public:
  // symmetric = false selects the LU factorisation (the whole matrix is used).
  explicit LinearSolver(bool symmetric = true) : symmetric_(symmetric) {}
  // Returns false when the factorisation fails (singular or numerically broken tangent).
  bool factorize(const Eigen::SparseMatrix<double>& k, long pattern_version);
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const {
    if (symmetric_) return ldlt_.solve(rhs);
    return lu_.solve(rhs);
  }
  bool symmetric() const { return symmetric_; }
  long analyses() const { return analyses_; }
  long factorizations() const { return factorizations_; }

 private:
  bool symmetric_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  long version_ = -1;
  long analyses_ = 0, factorizations_ = 0;
};

}  // namespace ringcrush::fe
