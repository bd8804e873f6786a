// The interleaved band's L D Lᵀ solve, ring by ring, two rings to an SSE2 vector or four to an
// AVX one (polygon_band_solve.hpp).
//
// One row i of the factorisation of μ + h C (L unit lower triangular, D diagonal) in two parts:
// row_residual forms W(i, i − q) = (L D)(i, i − q) and L(i, i − q) = W(i, i − q)/D(i − q) for
// q = B…1, the pivot D(i) = A(i, i) − Σ W L in the diagonal slot and the forward substitution
// z_i = b_i − Σ L z in b; row_pivot takes 1/D(i). No square root (the Cholesky factor L D^½
// this replaced took one per row): the chain from one row's pivot to the next is a
// multiplication, a product, a subtraction and the division, so every sum adds the term that
// waits for the previous row last (q + 1 in W, 1 in D and z) and the others while that row's
// division runs. The rows' entries are at row[q S] (row i − q at row − 6 q S, its 1/D(i − q) at
// inv − q S). B is the row's bandwidth: 5 for a node's y row, 4 for its x row — its column
// i − 5 is the y of the node three back, which no bar or hinge couples to it, and the factor
// keeps that zero. The split lets the rings' divisions, the long latency of the chain, run side
// by side: every lane group's residual, then every group's pivot — or, where the lane stride is
// a compile-time constant, each group's residual and pivot in one (row_factor), its last 1/D
// kept in a register from row to row (h63).
//
// Each function is one template over the lane vector — a double (one ring), a Pair (two) or a
// Quad (four) — whose lanes do the one-ring operations in the same order: the same bits.
#pragma GCC diagnostic ignored "-Wpsabi"  // the AVX copy of the solve (below)

#include "hinge/polygon_band_solve.hpp"

#include "hinge/ring_lanes.hpp"

namespace ringcrush::hinge {

namespace {

using lanes::Pair;
using lanes::Quad;

// The lane vectors: W rings' values side by side, lane l of a value at p[l].
template <class V>
struct Lanes;
template <>
struct Lanes<double> {
  static constexpr int W = 1;
  static double load(const double* p) { return *p; }
  static void store(double* p, double v) { *p = v; }
  static bool positive(double s) { return s > 0.0; }
};
template <>
struct Lanes<Pair> {
  static constexpr int W = 2;
  [[gnu::always_inline]] static Pair load(const double* p) { return lanes::load(p); }
  [[gnu::always_inline]] static void store(double* p, Pair v) { lanes::store(p, v); }
  [[gnu::always_inline]] static bool positive(Pair s) { return s[0] > 0.0 && s[1] > 0.0; }
};
template <>
struct Lanes<Quad> {  // generic vector operations only: inlined into the avx2 copy (below)
  static constexpr int W = 4;
  [[gnu::always_inline]] static Quad load(const double* p) { return *reinterpret_cast<const lanes::QuadMem*>(p); }
  [[gnu::always_inline]] static void store(double* p, Quad v) { *reinterpret_cast<lanes::QuadMem*>(p) = v; }
  [[gnu::always_inline]] static bool positive(Quad s) { return s[0] > 0.0 && s[1] > 0.0 && s[2] > 0.0 && s[3] > 0.0; }
};

// Returns the pivot D(i). inv_last: 1/D(i − 1) where the caller carries it in a register
// (Carried), else it is read from inv − S as the older ones are.
template <int B, bool Carried = false, class V>
[[gnu::always_inline]] inline V row_residual(const double* c, double h, V mass, double* row, const double* inv,
                                             double* b, std::ptrdiff_t S, V inv_last = V{}) {
  using O = Lanes<V>;
  V w[B + 1], l[B + 1];
  for (int q = 0; q <= B; ++q) w[q] = h * O::load(c + q * S);
  w[0] += mass;
  for (int q = B; q >= 1; --q) {
    const double* lj = row - 6 * q * S;
    V s = w[q];
    for (int m = B; m > q; --m) s -= w[m] * O::load(lj + (m - q) * S);
    w[q] = s;
    l[q] = s * (Carried && q == 1 ? inv_last : O::load(inv - q * S));
  }
  V s = w[0];
  for (int m = B; m >= 1; --m) s -= w[m] * l[m];
  O::store(row, s);
  for (int q = 1; q <= B; ++q) O::store(row + q * S, l[q]);
  V z = O::load(b);
  for (int m = B; m >= 1; --m) z -= l[m] * O::load(b - m * S);
  O::store(b, z);
  return s;
}

template <class V>
[[gnu::always_inline]] inline bool row_pivot(const double* row, double* inv) {
  using O = Lanes<V>;
  const V s = O::load(row);
  O::store(inv, 1.0 / s);
  return O::positive(s);
}

// One row's residual and pivot with the chain's last link in registers: the previous row's
// 1/D comes in as inv_last and this row's goes out, D goes from the residual to its division
// without the store and load of the two-stage form (each a store-to-load forwarding, ≈ 7
// cycles, on the chain D(i − 1) → 1/D(i − 1) → L(i, i − 1) → D(i) → 1/D(i), which is this
// solve's latency). The same operations on the same values: the same bits.
template <int B, class V>
[[gnu::always_inline]] inline V row_factor(const double* c, double h, V mass, double* row, double* inv, double* b,
                                           std::ptrdiff_t S, V inv_last, bool& definite) {
  using O = Lanes<V>;
  const V s = row_residual<B, true>(c, h, mass, row, inv, b, S, inv_last);
  const V inv_s = 1.0 / s;
  O::store(inv, inv_s);
  definite &= O::positive(s);
  return inv_s;
}

// Row i of the backward substitution Lᵀ x = D⁻¹ z: the column of L below the diagonal,
// L(i + m, i) at row[(6 m + m) S]. B as above, of the rows below: a y row's column reaches the
// x row five down only through that row's structural zero.
template <int B, class V>
[[gnu::always_inline]] inline void back_row(const double* row, const double* inv, double* b, std::ptrdiff_t S) {
  using O = Lanes<V>;
  V s = O::load(b) * O::load(inv);
  for (int m = B; m >= 1; --m) s -= O::load(row + 7 * m * S) * O::load(b + m * S);
  O::store(b, s);
}

// The masses of node j's x rows on the lanes r … r + W − 1 (1 on a spare lane: its identity).
template <class V>
[[gnu::always_inline]] inline V lane_masses(const double* mu, int n_ind, int rings, int r, int j) {
  auto mass = [&](int ring) { return ring < rings ? mu[static_cast<std::size_t>((ring * n_ind + j) * 6 + 2)] : 1.0; };
  if constexpr (Lanes<V>::W == 1) {
    return mass(r);
  } else {
    V m;
    for (int l = 0; l < Lanes<V>::W; ++l) m[l] = mass(r + l);
    return m;
  }
}

// Width rings to a vector over one band row's S lanes: the rings one by one (Width 1), in pairs
// (2), or in quads and a pair for the rest (4; S is even).
template <int Width, class Stage>
[[gnu::always_inline]] inline void each_lane_group(Stage& stage, std::ptrdiff_t S, int rings) {
  if constexpr (Width == 1) {
    for (int r = 0; r < rings; ++r) stage.template run<double>(r);
  } else {
    int r = 0;
    if constexpr (Width == 4)
      for (; r + 4 <= S; r += 4) stage.template run<Quad>(r);
    for (; r < S; r += 2) stage.template run<Pair>(r);
  }
}

// The stages of one node's two rows (the x row's bandwidth 4, the y row's 5) and of the
// backward substitution, each on one lane group from lane r.
template <int B>
struct Residual {
  const double *C, *mu;
  double *L, *inv, *b;
  double h;
  std::ptrdiff_t S;
  int n_ind, rings, j;
  template <class V>
  [[gnu::always_inline]] void run(int r) {
    row_residual<B>(C + r, h, lane_masses<V>(mu, n_ind, rings, r, j), L + r, inv + r, b + r, S);
  }
};
struct Pivot {
  const double* L;
  double* inv;
  bool definite;
  template <class V>
  [[gnu::always_inline]] void run(int r) {
    definite &= row_pivot<V>(L + r, inv + r);
  }
};
struct Backward {
  const double *L, *inv;
  double* b;
  std::ptrdiff_t S;
  template <class V>
  [[gnu::always_inline]] void run(int r) {
    back_row<4, V>(L + 6 * S + r, inv + S + r, b + S + r, S);
    back_row<5, V>(L + r, inv + r, b + r, S);
  }
};

// The solve on S lanes; kS the lane stride when known at compile time (0: from the ring count),
// so that the rows' strided loads take immediate offsets.
template <int kS, int Width>
[[gnu::always_inline]] inline bool solve_band(const BandSolve& p) {
  const std::ptrdiff_t S = kS > 0 ? kS : band_lane_count(p.rings);
  const int R = p.rings, n_ind = p.n_ind;
  const double h = p.h;  // a local: a store through the arrays could alias p.h for the compiler
  const double *C = p.C, *mu = p.mu;
  double *L = p.L, *b = p.b, *inv = p.inv, *v = p.v, *d = p.d;
  auto node = [&](int r, int j) { return static_cast<std::size_t>((r * n_ind + j) * 6); };  // node_offset
  bool definite = true;
  // With the lane stride known (kS) and the rings in vectors, each lane group's last 1/D is
  // carried in a register from row to row (row_factor): Quads first, then Pairs, as
  // each_lane_group orders them. Else the two stages through memory.
  constexpr bool kCarried = kS > 0 && Width >= 2;
  constexpr int kQuads = kCarried && Width == 4 ? kS / 4 : 0;
  constexpr int kPairs = kCarried ? (kS - 4 * kQuads) / 2 : 0;
  Quad inv_quad[kQuads > 0 ? kQuads : 1];
  Pair inv_pair[kPairs > 0 ? kPairs : 1];
  if constexpr (kCarried) {  // the pad row's 1/D (1) before row 0
    for (int g = 0; g < kQuads; ++g) inv_quad[g] = Lanes<Quad>::load(inv - S + 4 * g);
    for (int g = 0; g < kPairs; ++g) inv_pair[g] = Lanes<Pair>::load(inv - S + 4 * kQuads + 2 * g);
  }
  for (int j = 0; j < n_ind; ++j) {
    const bool axis = j == 0 || j == n_ind - 1;  // axis nodes' x stays 0
    const std::ptrdiff_t at = 12 * static_cast<std::ptrdiff_t>(j) * S;
    double* bx = b + 2 * static_cast<std::ptrdiff_t>(j) * S;
    double* ix = inv + 2 * static_cast<std::ptrdiff_t>(j) * S;
    for (int r = 0; r < R; ++r) {  // μ v* of the node's two rows as one Pair (the x row's μ for both)
      const std::size_t o = node(r, j) + 2;
      const Pair mv = mu[o] * lanes::load(v + o);
      bx[r] = axis ? 0.0 : mv[0];
      bx[S + r] = mv[1];
    }
    if constexpr (kCarried) {
      // The node's x row (bandwidth 4), then its y row (5), each lane group in turn.
      const std::ptrdiff_t rows[2] = {0, S};
      for (int row = 0; row < 2; ++row) {
        const std::ptrdiff_t at_row = at + 6 * rows[row];
        for (int g = 0; g < kQuads; ++g) {
          const int r = 4 * g;
          const Quad mass = lane_masses<Quad>(mu, n_ind, R, r, j);
          inv_quad[g] = row == 0 ? row_factor<4>(C + at_row + r, h, mass, L + at_row + r, ix + r, bx + r, S,
                                                 inv_quad[g], definite)
                                 : row_factor<5>(C + at_row + r, h, mass, L + at_row + r, ix + S + r, bx + S + r, S,
                                                 inv_quad[g], definite);
        }
        for (int g = 0; g < kPairs; ++g) {
          const int r = 4 * kQuads + 2 * g;
          const Pair mass = lane_masses<Pair>(mu, n_ind, R, r, j);
          inv_pair[g] = row == 0 ? row_factor<4>(C + at_row + r, h, mass, L + at_row + r, ix + r, bx + r, S,
                                                 inv_pair[g], definite)
                                 : row_factor<5>(C + at_row + r, h, mass, L + at_row + r, ix + S + r, bx + S + r, S,
                                                 inv_pair[g], definite);
        }
      }
    } else {
      Residual<4> x_row{C + at, mu, L + at, ix, bx, h, S, n_ind, R, j};
      each_lane_group<Width>(x_row, S, R);
      Pivot x_pivot{L + at, ix, true};
      each_lane_group<Width>(x_pivot, S, R);
      Residual<5> y_row{C + at + 6 * S, mu, L + at + 6 * S, ix + S, bx + S, h, S, n_ind, R, j};
      each_lane_group<Width>(y_row, S, R);
      Pivot y_pivot{L + at + 6 * S, ix + S, true};
      each_lane_group<Width>(y_pivot, S, R);
      definite = definite && x_pivot.definite && y_pivot.definite;
    }
  }
  if (!definite) return false;
  for (int j = n_ind - 1; j >= 0; --j) {
    Backward back{L + 12 * static_cast<std::ptrdiff_t>(j) * S, inv + 2 * static_cast<std::ptrdiff_t>(j) * S,
                  b + 2 * static_cast<std::ptrdiff_t>(j) * S, S};
    each_lane_group<Width>(back, S, R);
  }
  // v, and d = C v from the system itself: (μ + h C) v = μ v* gives C v = μ (v* − v)/h, three
  // operations per row instead of the band product (h > 0 here: ring_damper_step). Its
  // rounding, ≈ ε μ|v|/h, is that of the step's own acceleration (v − v_{n+½})/(½Δt); d enters
  // only the damper work, so the motion keeps its bits.
  // A node's two rows as one Pair.
  const double inv_h = 1.0 / h;
  for (int r = 0; r < R; ++r)
    for (int j = 0; j < n_ind; ++j) {
      const std::size_t o = node(r, j) + 2;
      const double* x = b + 2 * static_cast<std::ptrdiff_t>(j) * S + r;
      const Pair solved = {x[0], x[S]};
      Pair cv = mu[o] * (lanes::load(v + o) - solved) * inv_h;
      if (j == 0 || j == n_ind - 1) cv[0] = 0.0;  // axis nodes' x: no C row
      lanes::store(d + o, cv);
      lanes::store(v + o, solved);
    }
  return true;
}

// The lane stride a compile-time constant for the usual ring counts.
template <int Width>
[[gnu::always_inline]] inline bool solve_any(const BandSolve& p) {
  switch (band_lane_count(p.rings)) {
    case 2: return solve_band<2, Width>(p);
    case 4: return solve_band<4, Width>(p);
    case 6: return solve_band<6, Width>(p);
    case 8: return solve_band<8, Width>(p);
    default: return solve_band<0, Width>(p);
  }
}

bool solve_ring_by_ring(const BandSolve& p) { return solve_any<1>(p); }
bool solve_sse2(const BandSolve& p) { return solve_any<2>(p); }

#if defined(__x86_64__) && !defined(__FMA__)
[[gnu::target("avx2")]] bool solve_avx2(const BandSolve& p) { return solve_any<4>(p); }
bool avx2_available() { return __builtin_cpu_supports("avx2"); }
#else
bool solve_avx2(const BandSolve& p) { return solve_any<2>(p); }
bool avx2_available() { return false; }
#endif

}  // namespace

void band_factor_rows(int n_ind, int rings, std::vector<double>& L, std::vector<double>& inv, std::vector<double>& b) {
  const auto rows = static_cast<std::size_t>(2 * n_ind + 2 * kBandPadRows);
  const auto S = static_cast<std::size_t>(band_lane_count(rings));
  L.assign(6 * rows * S, 0.0);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t r = 0; r < S; ++r)
      if (i < static_cast<std::size_t>(kBandPadRows) || r >= static_cast<std::size_t>(rings)) L[6 * i * S + r] = 1.0;
  inv.assign(rows * S, 1.0);
  b.assign(rows * S, 0.0);
}

bool band_lanes_avx2() {
  static const bool avx2 = avx2_available();
  return avx2;
}

bool solve_ring_bands(const BandSolve& p, int width) {
  if (width == 1) return solve_ring_by_ring(p);
  if (width == 4 && band_lanes_avx2()) return solve_avx2(p);
  return solve_sse2(p);
}

}  // namespace ringcrush::hinge
