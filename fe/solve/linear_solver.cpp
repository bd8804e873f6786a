#include "fe/solve/linear_solver.hpp"

namespace ringcrush::fe {

bool LinearSolver::factorize(const Eigen::SparseMatrix<double>& k, long pattern_version) {
  if (pattern_version != version_) {
    if (symmetric_) ldlt_.analyzePattern(k);
    else lu_.analyzePattern(k);
    version_ = pattern_version;
    ++analyses_;
  }
  ++factorizations_;
  if (symmetric_) {
    ldlt_.factorize(k);
    return ldlt_.info() == Eigen::Success;
  }
  lu_.factorize(k);
  return lu_.info() == Eigen::Success;
}

}  // namespace ringcrush::fe
