// Elements on the lanes of one vector (cps8_force_lanes.hpp, geometry_update.hpp): four (an
// AVX2 or SSE2 vector) or eight (AVX-512), the vector types and their gathers from / scatters
// to the elements' own arrays. Internal to the lane kernels; every function is always inlined
// so that it is compiled for the instruction set of the kernel that uses it (portable, AVX2 or
// AVX-512), and every one is written for either width so that the kernels' arithmetic has one
// source: lane l of a width-8 vector does exactly what lane l of a width-4 vector does.
#pragma once

#include <cmath>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace ringcrush::fe::lanes {

typedef double Lanes __attribute__((vector_size(32)));  // one double per element of the group
typedef long long LaneMask __attribute__((vector_size(32)));
typedef double Lanes8 __attribute__((vector_size(64)));  // the same, eight elements (AVX-512)
typedef long long LaneMask8 __attribute__((vector_size(64)));
// Four consecutive doubles anywhere in memory, read or written as one vector (an unaligned
// vector load/store; memcpy went through the stack in two halves, and the full-width reload
// of the halves stalled on store forwarding — perf).
typedef double UnalignedLanes __attribute__((vector_size(32), aligned(8), may_alias));

// Elements per vector of type V.
template <class V>
constexpr int kWidthOf = static_cast<int>(sizeof(V) / sizeof(double));

// The vector of W lanes and its comparison mask.
template <int W>
struct LaneTypes;
template <>
struct LaneTypes<4> {
  using V = Lanes;
  using Mask = LaneMask;
};
template <>
struct LaneTypes<8> {
  using V = Lanes8;
  using Mask = LaneMask8;
};

// Whether every lane of a comparison mask is set.
template <class M>
[[gnu::always_inline]] inline bool all_lanes(const M& m) {
  bool all = true;
  for (int l = 0; l < kWidthOf<M>; ++l) all = all && m[l] != 0;
  return all;
}

// Bit l set where lane l of a comparison mask is clear.
template <class M>
[[gnu::always_inline]] inline unsigned clear_lanes(const M& m) {
  unsigned bits = 0;
  for (int l = 0; l < kWidthOf<M>; ++l) bits |= m[l] == 0 ? 1u << l : 0u;
  return bits;
}

// v[l] = √v[l] on every lane (IEEE square root, correctly rounded: the same bits as std::sqrt
// lane by lane). Four lanes: lane by lane, as before; eight: one AVX-512 instruction (the
// builtin behind _mm512_sqrt_pd, declared by <immintrin.h>, expanded only in the AVX-512 copy;
// the intrinsic itself, a target("avx512f") function, cannot be inlined into this template).
[[gnu::always_inline]] inline void sqrt_lanes(Lanes& v) {
  for (int l = 0; l < 4; ++l) v[l] = std::sqrt(v[l]);
}
#if defined(__x86_64__) || defined(__i386__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // never called: always inlined into the AVX-512 copy
[[gnu::always_inline]] inline void sqrt_lanes(Lanes8& v) {
  v = __builtin_ia32_sqrtpd512_mask(v, v, static_cast<unsigned char>(0xff), _MM_FROUND_CUR_DIRECTION);
}
#pragma GCC diagnostic pop
#endif

// r[l] = {c[0][l], c[1][l], c[2][l], c[3][l]}: the 4 × 4 transpose of lanes in registers.
[[gnu::always_inline]] inline void transpose4(const Lanes* c, Lanes* r) {
  const Lanes t0 = __builtin_shuffle(c[0], c[1], LaneMask{0, 4, 2, 6});
  const Lanes t1 = __builtin_shuffle(c[0], c[1], LaneMask{1, 5, 3, 7});
  const Lanes t2 = __builtin_shuffle(c[2], c[3], LaneMask{0, 4, 2, 6});
  const Lanes t3 = __builtin_shuffle(c[2], c[3], LaneMask{1, 5, 3, 7});
  r[0] = __builtin_shuffle(t0, t2, LaneMask{0, 1, 4, 5});
  r[1] = __builtin_shuffle(t1, t3, LaneMask{0, 1, 4, 5});
  r[2] = __builtin_shuffle(t0, t2, LaneMask{2, 3, 6, 7});
  r[3] = __builtin_shuffle(t1, t3, LaneMask{2, 3, 6, 7});
}

// transpose4() in each 256-bit half of four 8-wide vectors: r[l][h + j] = c[j][h + l] for the
// halves h = 0, 4 (the same unpacks, then the pairs of each half swapped).
[[gnu::always_inline]] inline void transpose4_halves(const Lanes8* c, Lanes8* r) {
  const Lanes8 t0 = __builtin_shufflevector(c[0], c[1], 0, 8, 2, 10, 4, 12, 6, 14);
  const Lanes8 t1 = __builtin_shufflevector(c[0], c[1], 1, 9, 3, 11, 5, 13, 7, 15);
  const Lanes8 t2 = __builtin_shufflevector(c[2], c[3], 0, 8, 2, 10, 4, 12, 6, 14);
  const Lanes8 t3 = __builtin_shufflevector(c[2], c[3], 1, 9, 3, 11, 5, 13, 7, 15);
  r[0] = __builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13);
  r[1] = __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13);
  r[2] = __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15);
  r[3] = __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15);
}

// c[m] = {p[0][at + m], p[1][at + m], p[2][at + m], p[3][at + m]}, m = 0..3: four vector
// loads and a 4 × 4 transpose (unpack the pairs, then swap the halves).
// Without AVX (two SSE2 halves per vector) a cross-half shuffle is lowered to single
// values through memory, and lanes filled one value at a time load straight into the halves:
// that copy gathers value by value.
template <bool kShuffle>
[[gnu::always_inline]] inline void gather_transposed(const double* const* p, int at, Lanes* c) {
  if constexpr (kShuffle) {
    Lanes r[4];
    for (int e = 0; e < 4; ++e) r[e] = *reinterpret_cast<const UnalignedLanes*>(p[e] + at);
    transpose4(r, c);
  } else {
    for (int m = 0; m < 4; ++m) c[m] = Lanes{p[0][at + m], p[1][at + m], p[2][at + m], p[3][at + m]};
  }
}
// Eight elements (AVX-512 only, hence always by shuffles): row k holds element k's 4 values in
// its low half and element k + 4's in its high half (one load and one 256-bit insert), then
// the 4 × 4 transpose above within each half, on 8-wide vectors (fewer instructions than two
// 4-wide transposes joined).
template <bool kShuffle>
[[gnu::always_inline]] inline void gather_transposed(const double* const* p, int at, Lanes8* c) {
  static_assert(kShuffle, "eight lanes are AVX-512 only");
  Lanes8 r[4];
  for (int k = 0; k < 4; ++k) {
    const Lanes lo = *reinterpret_cast<const UnalignedLanes*>(p[k] + at);
    const Lanes hi = *reinterpret_cast<const UnalignedLanes*>(p[k + 4] + at);
    r[k] = __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
  }
  transpose4_halves(r, c);
}

// The inverse: p[l][at + m] = c[m][l].
template <bool kShuffle>
[[gnu::always_inline]] inline void scatter_transposed(const Lanes* c, int at, double* const* p) {
  if constexpr (kShuffle) {
    Lanes r[4];
    transpose4(c, r);
    for (int l = 0; l < 4; ++l) *reinterpret_cast<UnalignedLanes*>(p[l] + at) = r[l];
  } else {
    for (int l = 0; l < 4; ++l)
      for (int m = 0; m < 4; ++m) p[l][at + m] = c[m][l];
  }
}
template <bool kShuffle>
[[gnu::always_inline]] inline void scatter_transposed(const Lanes8* c, int at, double* const* p) {
  static_assert(kShuffle, "eight lanes are AVX-512 only");
  Lanes8 r[4];
  transpose4_halves(c, r);
  for (int k = 0; k < 4; ++k) {
    *reinterpret_cast<UnalignedLanes*>(p[k] + at) = __builtin_shufflevector(r[k], r[k], 0, 1, 2, 3);
    *reinterpret_cast<UnalignedLanes*>(p[k + 4] + at) = __builtin_shufflevector(r[k], r[k], 4, 5, 6, 7);
  }
}

// v[l] = value(l) on every lane: values that are not 4 consecutive doubles of each element
// (one vector built from W values, as a braced vector literal).
template <class V, class F>
[[gnu::always_inline]] inline void lanes_from(F value, V& v) {
  if constexpr (kWidthOf<V> == 4)
    v = V{value(0), value(1), value(2), value(3)};
  else
    v = V{value(0), value(1), value(2), value(3), value(4), value(5), value(6), value(7)};
}

}  // namespace ringcrush::fe::lanes
