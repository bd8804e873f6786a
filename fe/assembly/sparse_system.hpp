// Degrees of freedom and the sparse tangent (DESIGN.md "Performance"): the sparsity pattern
// is built from the element connectivity once, and only grows when a contact pair couples
// nodes that were never coupled before (counted, so the report can show how often the
// symbolic factorisation was redone). Element scatter positions are precomputed; assembly
// writes straight into the compressed matrix, with no allocation per iteration.
#pragma once

#include <Eigen/Sparse>
#include <array>
#include <set>
#include <utility>
#include <vector>

namespace ringcrush::fe {

class SparseSystem {
 public:
  // nodes: number of nodes (2 dofs each); fixed: dofs held at zero; elements: connectivity.
  SparseSystem(int nodes, const std::vector<int>& fixed_dofs, const std::vector<std::array<int, 8>>& elements);

  int free_dofs() const { return free_count_; }
  int free_index(int dof) const { return free_of_[dof]; }   // −1 when fixed
  const std::vector<int>& free_to_dof() const { return dof_of_; }

  // Makes sure every pair of the given nodes is in the pattern; returns true if it grew.
  bool ensure_coupled(const int* nodes, int count);
  long pattern_version() const { return version_; }

  Eigen::SparseMatrix<double>& matrix() { return k_; }
  void zero() { std::fill(k_.valuePtr(), k_.valuePtr() + k_.nonZeros(), 0.0); }
  // Adds an element block (16×16, column-major, element dof order).
  void add_element(int element, const double* block);
  // Adds a block over arbitrary nodes (n = 2·count, column-major n×n with leading dim ld).
  void add_nodes(const int* nodes, int count, const double* block, int ld);

 private:
  void rebuild();
  int position(int row, int col) const;

  int nodes_;
  std::vector<int> free_of_, dof_of_;
  int free_count_ = 0;
  std::vector<std::array<int, 8>> elements_;
  std::set<std::pair<int, int>> extra_;  // contact node couplings (a < b)
  std::vector<std::array<int, 256>> element_pos_;
  Eigen::SparseMatrix<double> k_;
  long version_ = 0;
};

}  // namespace ringcrush::fe
