// Two consecutive dofs of a dof-ordered array — a node's (x, y) where the first index is even —
// in the lanes of one 16-byte vector (GCC vector extension: per lane the scalar IEEE operation,
// so a sum or product of pairs is bitwise the two scalar ones). Loaded and stored by memcpy
// (one unaligned move): a pair may start at any double (ExplicitStepEnd's ranges may begin at
// an odd dof), and the arrays are plain doubles to everything else, so neither alignment nor a
// vector type's aliasing is assumed. Used by ChainModel's element gather and scatter
// (chain_model.cpp) and ExplicitStepEnd (explicit_step_end.hpp).
#pragma once

#include <cstring>

namespace ringcrush::fe {

using DofPair = double __attribute__((vector_size(16)));

inline DofPair load_dof_pair(const double* p) {
  DofPair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store_dof_pair(double* p, DofPair v) { std::memcpy(p, &v, sizeof v); }

}  // namespace ringcrush::fe
