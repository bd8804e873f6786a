#include "fe/assembly/sparse_system.hpp"

#include <algorithm>
#include <stdexcept>

namespace ringcrush::fe {

SparseSystem::SparseSystem(int nodes, const std::vector<int>& fixed_dofs, const std::vector<std::array<int, 8>>& elements)
    : nodes_(nodes), free_of_(2 * nodes, 0), elements_(elements) {
  for (int d : fixed_dofs) free_of_.at(d) = -1;
  for (int d = 0; d < 2 * nodes; ++d)
    if (free_of_[d] >= 0) {
      free_of_[d] = free_count_++;
      dof_of_.push_back(d);
    }
  rebuild();
}

void SparseSystem::rebuild() {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(elements_.size() * 256 + extra_.size() * 8 + 2 * nodes_);
  auto couple = [&](int a, int b) {
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const int r = free_of_[2 * a + i], c = free_of_[2 * b + j];
        if (r >= 0 && c >= 0) t.emplace_back(r, c, 0.0);
      }
  };
  for (const auto& e : elements_)
    for (int a : e)
      for (int b : e) couple(a, b);
  for (const auto& [a, b] : extra_) {
    couple(a, b);
    couple(b, a);
  }
  for (int d = 0; d < free_count_; ++d) t.emplace_back(d, d, 0.0);
  k_ = Eigen::SparseMatrix<double>(free_count_, free_count_);
  k_.setFromTriplets(t.begin(), t.end());
  k_.makeCompressed();
  element_pos_.assign(elements_.size(), {});
  for (std::size_t e = 0; e < elements_.size(); ++e)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) {
        const int r = free_of_[2 * elements_[e][i / 2] + i % 2], c = free_of_[2 * elements_[e][j / 2] + j % 2];
        element_pos_[e][j * 16 + i] = (r >= 0 && c >= 0) ? position(r, c) : -1;
      }
  ++version_;
}

int SparseSystem::position(int row, int col) const {
  const int* begin = k_.innerIndexPtr() + k_.outerIndexPtr()[col];
  const int* end = k_.innerIndexPtr() + k_.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  if (it == end || *it != row) return -1;
  return static_cast<int>(it - k_.innerIndexPtr());
}

bool SparseSystem::ensure_coupled(const int* nodes, int count) {
  bool grew = false;
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j) {
      const int a = std::min(nodes[i], nodes[j]), b = std::max(nodes[i], nodes[j]);
      if (a == b) continue;
      // Already coupled through an element or an earlier contact?
      bool found = false;
      for (int di = 0; di < 2 && !found; ++di)
        for (int dj = 0; dj < 2 && !found; ++dj) {
          const int r = free_of_[2 * a + di], c = free_of_[2 * b + dj];
          if (r >= 0 && c >= 0) found = position(r, c) >= 0;
        }
      const bool any_free = (free_of_[2 * a] >= 0 || free_of_[2 * a + 1] >= 0) && (free_of_[2 * b] >= 0 || free_of_[2 * b + 1] >= 0);
      if (!found && any_free) {
        extra_.insert({a, b});
        grew = true;
      }
    }
  if (grew) rebuild();
  return grew;
}

void SparseSystem::add_element(int element, const double* block) {
  double* v = k_.valuePtr();
  const auto& pos = element_pos_[element];
  for (int k = 0; k < 256; ++k)
    if (pos[k] >= 0) v[pos[k]] += block[k];
}

void SparseSystem::add_nodes(const int* nodes, int count, const double* block, int ld) {
  double* v = k_.valuePtr();
  for (int j = 0; j < 2 * count; ++j) {
    const int c = free_of_[2 * nodes[j / 2] + j % 2];
    if (c < 0) continue;
    for (int i = 0; i < 2 * count; ++i) {
      const int r = free_of_[2 * nodes[i / 2] + i % 2];
      if (r < 0) continue;
      const int p = position(r, c);
      if (p < 0) throw std::logic_error("SparseSystem::add_nodes: coupling missing from the pattern");
      v[p] += block[j * ld + i];
    }
  }
}

}  // namespace ringcrush::fe
