// Sparse direct solver for the Newton corrections: LDLᵀ (the frictionless tangent is
// symmetric: J2 consistent tangent, total-Lagrangian geometric stiffness and penalty
// contact are all second derivatives of one potential). The symbolic analysis (AMD
// ordering, elimination tree) is done once per sparsity pattern; each iteration only
// factorises numerically.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

namespace ringcrush::fe {

class LinearSolver {
 public:
  // Returns false when the factorisation fails (singular or numerically broken tangent).
  bool factorize(const Eigen::SparseMatrix<double>& k, long pattern_version);
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const { return ldlt_.solve(rhs); }
  long analyses() const { return analyses_; }
  long factorizations() const { return factorizations_; }

 private:
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  long version_ = -1;
  long analyses_ = 0, factorizations_ = 0;
};

}  // namespace ringcrush::fe
