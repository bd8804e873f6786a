#include "fe/solve/linear_solver.hpp"

namespace ringcrush::fe {

bool LinearSolver::factorize(const Eigen::SparseMatrix<double>& k, long pattern_version) {
  if (pattern_version != version_) {
    ldlt_.analyzePattern(k);
    version_ = pattern_version;
    ++analyses_;
  }
  ldlt_.factorize(k);
  ++factorizations_;
  return ldlt_.info() == Eigen::Success;
}

}  // namespace ringcrush::fe
