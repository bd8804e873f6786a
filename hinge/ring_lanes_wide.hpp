// Elementwise kernels on flat arrays, 8, 4 or 2 doubles to a vector (AVX-512, AVX2, SSE2),
// chosen at run time. On the CPUs this runs on (AMD Zen 5: README, h63) a division or a square
// root costs the same issue slot of the divider whatever the vector's width — a `vdivpd zmm`
// about what one `divsd` does —, so where a pass's lanes are independent (bars, contact nodes)
// the widest vector divides and roots eight values for the price of one.
//
// Each lane does the scalar operations in the same order (IEEE add, multiply, divide, square
// root, correctly rounded), and no product is fused into a sum: "avx2" does not imply FMA in
// GCC, and the AVX-512 copies, where "avx512f" does, are compiled with contraction off
// (#pragma GCC optimize("fp-contract=off"), as fe/element/cps8_force_lanes.cpp). So every
// width gives the same bits. A build with FMA (RINGCRUSH_NATIVE) takes the SSE2 pairs only.
//
// The Quad and Oct types are used only in code compiled for "avx2" or "avx512f" (the files that
// include this header silence -Wpsabi: a function taking them by value out of line would have
// the non-AVX ABI; every such function here is always inlined).
#pragma once

#if defined(__x86_64__)
#include <immintrin.h>  // declares the 256- and 512-bit square-root builtins below
#endif

#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge::lanes {

typedef double Oct __attribute__((vector_size(64)));
typedef long long OctMask __attribute__((vector_size(64)));
typedef double OctMem __attribute__((vector_size(64), aligned(8), may_alias));

// W doubles anywhere in memory as one vector, and the vector's correctly rounded square root.
template <int W>
struct Wide;
template <>
struct Wide<2> {
  using V = Pair;
  [[gnu::always_inline]] static V load(const double* p) { return lanes::load(p); }
  [[gnu::always_inline]] static void store(double* p, V v) { lanes::store(p, v); }
  [[gnu::always_inline]] static V sqrt(V x) { return lanes::sqrt(x); }
};
#if defined(__x86_64__)
template <>
struct Wide<4> {
  using V = Quad;
  [[gnu::always_inline]] static V load(const double* p) { return *reinterpret_cast<const QuadMem*>(p); }
  [[gnu::always_inline]] static void store(double* p, V v) { *reinterpret_cast<QuadMem*>(p) = v; }
  [[gnu::always_inline]] static V sqrt(V x) { return __builtin_ia32_sqrtpd256(x); }
};
template <>
struct Wide<8> {
  using V = Oct;
  [[gnu::always_inline]] static V load(const double* p) { return *reinterpret_cast<const OctMem*>(p); }
  [[gnu::always_inline]] static void store(double* p, V v) { *reinterpret_cast<OctMem*>(p) = v; }
  [[gnu::always_inline]] static V sqrt(V x) {
    return __builtin_ia32_sqrtpd512_mask(x, x, static_cast<unsigned char>(0xff), _MM_FROUND_CUR_DIRECTION);
  }
};
#endif

}  // namespace ringcrush::hinge::lanes
