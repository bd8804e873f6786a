// Two rings on the lanes of one SSE2 vector (GCC vector extension, as fe/element/element_lanes.hpp
// and the damper band of polygon_implicit_dampers.cpp): the chain's rings have the same N and
// layout, so one ring's loop over its bars, hinges and nodes runs on two rings at once. Each
// lane computes as the scalar code does (IEEE add, multiply, divide and square root, no
// contraction on the default x86-64 target), so the bits are the scalar code's.
#pragma once

#include <cmath>

namespace ringcrush::hinge::lanes {

typedef double Pair __attribute__((vector_size(16)));
typedef long long PairMask __attribute__((vector_size(16)));
// Two doubles anywhere in memory, read or written as one vector.
typedef double PairMem __attribute__((vector_size(16), aligned(8), may_alias));

// Four rings on the lanes of one AVX vector (the hinge pass of polygon_ring_lanes.cpp, the band
// of polygon_band_lanes.cpp and polygon_band_solve.cpp): only in code compiled for "avx2" (the
// runtime check there), with generic vector operations, in files that silence -Wpsabi (a
// function taking a Quad by value changes the ABI without AVX; every such one is inlined).
typedef double Quad __attribute__((vector_size(32)));
typedef long long QuadMask __attribute__((vector_size(32)));
typedef double QuadMem __attribute__((vector_size(32), aligned(8), may_alias));

// The widest vector, 8, 4 or 2 doubles (AVX-512, AVX2, SSE2), that this CPU and build run the
// elementwise kernels of hinge/ring_lanes_wide.hpp with (2 in a build with FMA).
int wide_lanes_available();

[[gnu::always_inline]] inline Pair load(const double* p) { return *reinterpret_cast<const PairMem*>(p); }
[[gnu::always_inline]] inline void store(double* p, Pair v) { *reinterpret_cast<PairMem*>(p) = v; }

// Correctly rounded, as std::sqrt: one sqrtpd where SSE2 is there.
[[gnu::always_inline]] inline Pair sqrt(Pair x) {
#if defined(__SSE2__)
  return __builtin_ia32_sqrtpd(x);
#else
  return Pair{std::sqrt(x[0]), std::sqrt(x[1])};
#endif
}

// std::sqrt of one double, correctly rounded as it, without its errno branch (a compare and a
// jump per call): for arguments that are never negative (sums of squares). One sqrtsd.
[[gnu::always_inline]] inline double sqrt_nonnegative(double x) {
#if defined(__SSE2__)
  return __builtin_ia32_sqrtsd(Pair{x, x})[0];
#else
  return std::sqrt(x);
#endif
}

// m ? a : b per lane (m from a lane comparison: all bits set or none).
[[gnu::always_inline]] inline Pair select(PairMask m, Pair a, Pair b) {
  return reinterpret_cast<Pair>((reinterpret_cast<PairMask>(a) & m) | (reinterpret_cast<PairMask>(b) & ~m));
}

// std::min(a, b) per lane: b where b < a, else a (the same operand as the scalar call, also
// for ±0 and NaN). minpd(x, y) is x < y ? x : y, so minpd(b, a) is exactly that.
[[gnu::always_inline]] inline Pair min(Pair a, Pair b) {
#if defined(__SSE2__)
  return __builtin_ia32_minpd(b, a);
#else
  return select(b < a, b, a);
#endif
}
// std::max(a, b) per lane: b where a < b, else a; maxpd(b, a) is b > a ? b : a.
[[gnu::always_inline]] inline Pair max(Pair a, Pair b) {
#if defined(__SSE2__)
  return __builtin_ia32_maxpd(b, a);
#else
  return select(a < b, b, a);
#endif
}

// Whether any lane of m is set (movmskpd where SSE2 is there: one instruction, not two lane
// extractions).
[[gnu::always_inline]] inline bool any(PairMask m) {
#if defined(__SSE2__)
  return __builtin_ia32_movmskpd(reinterpret_cast<Pair>(m)) != 0;
#else
  return (m[0] | m[1]) != 0;
#endif
}

// Whether a < b or c < d in some lane: a box test (the point below the low corner or above
// the high one). The comparisons go straight to cmpltpd, orpd and movmskpd: through the
// vector extension's boolean vectors GCC renormalised the or'ed masks lane by lane.
[[gnu::always_inline]] inline bool any_less(Pair a, Pair b, Pair c, Pair d) {
#if defined(__SSE2__)
  return __builtin_ia32_movmskpd(__builtin_ia32_orpd(__builtin_ia32_cmpltpd(a, b), __builtin_ia32_cmpltpd(c, d))) != 0;
#else
  return a[0] < b[0] || a[1] < b[1] || c[0] < d[0] || c[1] < d[1];
#endif
}

// |x| per lane (the sign bit cleared, as std::abs).
[[gnu::always_inline]] inline Pair abs(Pair x) {
  return reinterpret_cast<Pair>(reinterpret_cast<PairMask>(x) & PairMask{0x7fffffffffffffffLL, 0x7fffffffffffffffLL});
}

}  // namespace ringcrush::hinge::lanes
