// The last sums of the chain's force in one evaluation (ChainModel::evaluate): the element
// pass leaves the caller's half of the element sums in f and q (elements [0, split)) and the
// helper's half in f_h and q_h (elements [split, ne), nonzero only on [lo, lo + len)), the
// contact leaves its contributions; then
//
//   f = ((f + f_h) + c_1 + c_2 + …) + q,   q = q + q_h
//
// per dof, with the contributions c_k that touch the dof in their order. Unfused this is
// four passes over the dofs (f += f_h on the range, the contributions, q += q_h on the range,
// f += q); here it is one, in blocks, and each block's final f and q go to `end` while in the
// cache (the explicit step's end, explicit_step_end.hpp). Per dof the operations and their
// order are those of the unfused sums, so the result is bitwise theirs:
//  - a dof a contribution touches gets f + f_h first, then its contributions, and its f_h is
//    set to +0.0, so that the pass adds +0.0 there (and a second contribution to the dof adds
//    +0.0 first). Adding +0.0 changes no bit of these sums: each starts at +0.0 and, rounding
//    to nearest, a sum that starts at +0.0 is never −0.0;
//  - q gets no contributions: q + q_h, then f + q, as unfused.
// f_h is the helper's buffer: it zeroes it before its next half (ChainModel::Impl).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "fe/contact/contact_element.hpp"

namespace ringcrush::fe {

struct ChainForceParts {
  double* force = nullptr;            // the caller's half on entry, f on exit
  double* helper_force = nullptr;     // set to +0.0 where a contribution touches
  double* viscous = nullptr;          // null: no bulk viscosity; else q_caller on entry, q on exit
  const double* helper_viscous = nullptr;
  Eigen::Index size = 0, helper_lo = 0, helper_len = 0;
};

// No step end (HHT, the plain evaluate()).
struct NoForceEnd {
  void range(Eigen::Index, Eigen::Index, const double*, const double*) {}
};

template <class End>
void finish_chain_force(const ChainForceParts& p, const std::vector<ContactContribution>& contributions, End& end) {
  double* f = p.force;
  double* fh = p.helper_force;
  const Eigen::Index lo = p.helper_lo, hi = p.helper_lo + p.helper_len;
  for (const ContactContribution& c : contributions)
    for (int a = 0; a < c.count; ++a)
      for (int k = 0; k < 2; ++k) {
        const Eigen::Index d = 2 * static_cast<Eigen::Index>(c.nodes[a]) + k;
        if (d >= lo && d < hi) {
          f[d] += fh[d];
          fh[d] = 0.0;
        }
        f[d] += c.force(2 * a + k);
      }
  // Blocks of dofs small enough that end() finds their f and q in the cache.
  constexpr Eigen::Index kBlock = 256;
  double* q = p.viscous;
  const double* qh = p.helper_viscous;
  for (Eigen::Index b = 0; b < p.size; b += kBlock) {
    const Eigen::Index e = std::min(b + kBlock, p.size);
    const Eigen::Index h0 = std::clamp(lo, b, e), h1 = std::clamp(hi, b, e);
    for (Eigen::Index i = h0; i < h1; ++i) f[i] += fh[i];
    if (q) {
      for (Eigen::Index i = h0; i < h1; ++i) q[i] += qh[i];
      for (Eigen::Index i = b; i < e; ++i) f[i] += q[i];
    }
    end.range(b, e, f, q);
  }
}

}  // namespace ringcrush::fe
