// The half model's damper + membrane band, ring by ring and two or four rings to a vector
// (polygon_band_lanes.hpp).
//
// ½ EᵀC_full E element by element: a bar or hinge of the first half and its mirror image
// fold onto the same independent nodes with equal contributions, so bars 0…N/2 − 1 and
// hinges 1…N/2 − 1 enter once with weight 1; the hinges on the axis (0 and N/2) are their own
// mirror images and enter with weight ½, their gradient folded (the mirrored node's part,
// x sign flipped, added to its independent twin). The axis nodes' x rows and columns are
// cleared at the end (those velocities stay 0).
//
// An entry of C is the sum over the elements on both its nodes of (w c gₚ) g_q, gₚ the row's
// gradient component, g_q the column's. The sums run in the element order
//   H0, B0, B1, H1, B2, H2, …, B_{N/2−1}, H_{N/2−1}, H_{N/2}
// (H hinges, B bars; the order of the element-by-element scatter of the profile assembly,
// whose bits they keep), and a node is touched by at most five of them: with the elements
// numbered in that order, E_0 = H0, E_1 = B0, E_{2k} = B_k, E_{2k+1} = H_k (0 < k < N/2),
// E_{N} empty, E_{N+1} = H_{N/2}, node j's are E_{2j−2}, E_{2j−1}, E_{2j}, E_{2j+1}, E_{2j+3} in
// that order — those two before node j's B_{j−1}, H_{j−1} pair at the ring's ends included. So
// each element's scaled gradients are formed once and each node's two band rows summed in
// registers and written once (no clearing, no read-modify-write).
//
// All forms below are one template over the vector type: the per-ring one on a one-lane
// "vector" (a double), whose x and y rows share a Pair in the row sums as before; the lane ones
// on Pairs of rings (SSE2) and on Quads (AVX2: compiled for "avx2" alone, no FMA, behind the
// CPU check; generic vector operations, a Quad's square root one vsqrtpd). Every
// value is formed by the same operations in the same order in all.
#pragma GCC diagnostic ignored "-Wpsabi"  // the AVX copy of the assembly (below)

#include "hinge/polygon_band_lanes.hpp"

#include <algorithm>

#include "hinge/polygon_band_solve.hpp"
#include "hinge/polygon_bar_direction.hpp"
#include "hinge/ring_lanes.hpp"
#include "hinge/ring_lanes_wide.hpp"

namespace ringcrush::hinge {

namespace {

using lanes::Pair;
using lanes::Quad;

constexpr int kBand = 5;  // lower bandwidth: a hinge couples nodes two apart, 2 dofs each

// One element's w c G and G (x, y on three local nodes), 12 values: kWg at 0, kG at 6. An
// even-numbered element's local node 0 is node k of E_{2k}, an odd one's is node k − 1 of
// E_{2k+1}; E_1 = B0 is on its local nodes 1, 2, and the unused local nodes stay 0.
constexpr int kElementSize = 12, kWg = 0, kG = 6;

constexpr int kElementPad = 2;  // empty elements before E_0 (for nodes 0 and 1)

// Elements E_{−2} … E_{N+3} of one ring.
inline int element_values(int n_ind) { return kElementSize * (2 * (n_ind - 1) + 2 + 2 * kElementPad); }

// The vector of W rings' values: a double (W = 1), a Pair (W = 2) or a Quad (W = 4), value i
// of lane l at p[i W + l]; each bar's direction from polygon_bar_direction.hpp's one formula.
template <class V>
struct Lanes;
template <>
struct Lanes<double> {
  static constexpr int W = 1;
  static double load(const double* p) { return *p; }
  static BarDirection direction(double wx, double wy) { return bar_direction(wx, wy); }
};
template <>
struct Lanes<Pair> {
  static constexpr int W = 2;
  [[gnu::always_inline]] static Pair load(const double* p) { return lanes::load(p); }
  [[gnu::always_inline]] static void store(double* p, Pair v) { lanes::store(p, v); }
  [[gnu::always_inline]] static auto direction(Pair wx, Pair wy) { return bar_direction_lanes<PairSqrt>(wx, wy); }
};
// A Quad's square root as one vsqrtpd (correctly rounded as std::sqrt; the builtin is declared
// by <immintrin.h>, through hinge/ring_lanes_wide.hpp, and these helpers are inlined into the
// "avx2" copy only). Its halves' two sqrtpd took two slots of the divider, which one 256-bit
// root takes alone on the test machine (README, h63).
struct QuadSqrt {
  [[gnu::always_inline]] static Quad of(Quad x) { return lanes::Wide<4>::sqrt(x); }
};
template <>
struct Lanes<Quad> {
  static constexpr int W = 4;
  [[gnu::always_inline]] static Quad load(const double* p) { return *reinterpret_cast<const lanes::QuadMem*>(p); }
  [[gnu::always_inline]] static void store(double* p, Quad v) { *reinterpret_cast<lanes::QuadMem*>(p) = v; }
  [[gnu::always_inline]] static auto direction(Quad wx, Quad wy) { return bar_direction_lanes<QuadSqrt>(wx, wy); }
};
// Eight rings to an AVX-512 vector (6 rings: one Oct with two spare lanes, where AVX2 took a
// Quad and a Pair): only in the "avx512f" copy, contraction off.
using lanes::Oct;
#if defined(__x86_64__)
struct OctSqrt {
  [[gnu::always_inline]] static Oct of(Oct x) { return lanes::Wide<8>::sqrt(x); }
};
template <>
struct Lanes<Oct> {
  static constexpr int W = 8;
  [[gnu::always_inline]] static Oct load(const double* p) { return lanes::Wide<8>::load(p); }
  [[gnu::always_inline]] static void store(double* p, Oct v) { lanes::Wide<8>::store(p, v); }
  [[gnu::always_inline]] static auto direction(Oct wx, Oct wy) { return bar_direction_lanes<OctSqrt>(wx, wy); }
};
#endif

// Writes the Live lanes of v (all but a spare one) to p.
template <int Live = 0, class V>
[[gnu::always_inline]] inline void put(double* p, V v) {
  if constexpr (Lanes<V>::W == 1) {
    *p = v;
  } else if constexpr (Live == 0 || Live == Lanes<V>::W) {
    Lanes<V>::store(p, v);
  } else if constexpr (Lanes<V>::W == 8) {  // one masked store (AVX-512), the spare lanes' slots untouched
    __builtin_ia32_storeupd512_mask(p, v, static_cast<unsigned char>((1u << Live) - 1u));
  } else {
    for (int l = 0; l < Live; ++l) p[l] = v[l];
  }
}

// Value i of W rings' values at p (a function, not a lambda: a lambda does not take the
// caller's "avx2" target, and one returning a Quad by value out of line would be the non-AVX ABI).
template <class V>
[[gnu::always_inline]] inline V lane(const double* p, int i) {
  return Lanes<V>::load(p + i * Lanes<V>::W);
}

template <class V, int Count>
[[gnu::always_inline]] inline void set_element(double* e, int local, const V (&g)[Count][2], double wc) {
  constexpr int W = Lanes<V>::W;
  for (int p = 0; p < Count; ++p)
    for (int c = 0; c < 2; ++c) {
      put(e + (kG + 2 * (local + p) + c) * W, g[p][c]);
      put(e + (kWg + 2 * (local + p) + c) * W, wc * g[p][c]);
    }
}

// The elements E_0 … E_{N+1} of W rings (node j's x, y at px, py[j W]; n_ind independent
// nodes; the bar and hinge damper coefficients) into `elements` (E_{−2} first); each bar's n/ℓ
// and e into bars ([nx, ny, ex, ey] of bar k at (4 k) W). Each bar's direction from one
// division and one square root (bar_direction, whose e the membrane's K_m products take too).
// Elements whose coefficient is not positive are skipped, so with either coefficient off the
// elements are cleared first: the scratch outlives the call, and an earlier call may have
// filled them (the membrane kick's bars carry c_b + h k_m, a plain damper step at c_b = 0
// none); the rows then sum +0 terms, the bits of a fresh scratch. Out of the element loops, so
// that the default path (c_b, c_θ > 0) is the same code plus one test.
template <class V>
[[gnu::always_inline]] inline void band_elements(const double* px, const double* py, int n_ind, double c_bar,
                                                 double c_hinge, double* elements, double* bars) {
  using O = Lanes<V>;
  constexpr int W = O::W;
  const int last = n_ind - 1;
  auto E = [&](int k) { return elements + kElementSize * (k + kElementPad) * W; };
  if (!(c_bar > 0 && c_hinge > 0)) std::fill_n(elements, element_values(n_ind) * W, 0.0);
  V ax{}, ay{};  // n/ℓ of the previous bar
  // Hinge 0 (weight ½): bars N−1 (from the mirror of node 1 to node 0) and 0.
  if (c_hinge > 0) {
    const V ux = lane<V>(px, 0) + lane<V>(px, 1), uy = lane<V>(py, 0) - lane<V>(py, 1);  // p0 − (−x1, y1)
    const V wx = lane<V>(px, 1) - lane<V>(px, 0), wy = lane<V>(py, 1) - lane<V>(py, 0);
    const V lu = ux * ux + uy * uy, lw = wx * wx + wy * wy;
    const V a0x = -uy / lu, a0y = ux / lu, bx = -wy / lw, by = wx / lw;
    const V g[2][2] = {{a0x + bx, a0y + by}, {a0x - bx, -a0y - by}};
    set_element(E(0), 0, g, 0.5 * c_hinge);
  }
  // Each bar's e and n/ℓ first, then the elements from them.
  for (int k = 0; k < last; ++k) {
    const auto g = O::direction(lane<V>(px, k + 1) - lane<V>(px, k), lane<V>(py, k + 1) - lane<V>(py, k));
    put(bars + (4 * k) * W, g.nx);
    put(bars + (4 * k + 1) * W, g.ny);
    put(bars + (4 * k + 2) * W, g.ex);
    put(bars + (4 * k + 3) * W, g.ey);
  }
  for (int k = 0; k < last; ++k) {
    const V ex = O::load(bars + (4 * k + 2) * W), ey = O::load(bars + (4 * k + 3) * W);
    if (c_bar > 0) {
      const V g[2][2] = {{-ex, -ey}, {ex, ey}};
      if (k == 0)
        set_element(E(1), 1, g, c_bar);
      else
        set_element(E(2 * k), 0, g, c_bar);
    }
    const V bx = O::load(bars + 4 * k * W), by = O::load(bars + (4 * k + 1) * W);
    if (k > 0 && c_hinge > 0) {  // hinge k on nodes k − 1, k, k + 1
      const V g[3][2] = {{-ax, -ay}, {ax + bx, ay + by}, {-bx, -by}};
      set_element(E(2 * k + 1), 0, g, c_hinge);
    }
    ax = bx;
    ay = by;
  }
  // Hinge N/2 (weight ½): bar N/2 − 1 and bar N/2 to the mirror of node N/2 − 1.
  if (c_hinge > 0) {
    const V wx = -lane<V>(px, last - 1) - lane<V>(px, last), wy = lane<V>(py, last - 1) - lane<V>(py, last);
    const V l = wx * wx + wy * wy;
    const V bx = -wy / l, by = wx / l;
    const V g[2][2] = {{-ax + bx, -ay - by}, {ax + bx, ay + by}};
    set_element(E(2 * last + 1), 0, g, 0.5 * c_hinge);
  }
}

// Every node's two band rows of W rings from their elements (E at E_0), C(i, i − q) of lane l
// at band[(6 i + q) S + l]; the first Live lanes written (a spare one not).
template <class V, int Live>
[[gnu::always_inline]] inline void band_rows(const double* E, int last, double* band, std::ptrdiff_t S) {
  using O = Lanes<V>;
  constexpr int W = O::W;
  for (int j = 0; j <= last; ++j) {
    // Node j's elements in the summation order and its local node in each, with those of
    // nodes j − 1 and j − 2 where the element holds them.
    const double* a = E + kElementSize * (2 * j - 2) * W;  // B_{j−1} (H0 for j = 1): j at 1, j − 1 at 0
    const double* b = E + kElementSize * (2 * j - 1) * W;  // H_{j−1} (B0 for j = 1): j at 2, j − 1 at 1, j − 2 at 0
    const double* c = E + kElementSize * (2 * j) * W;      // B_j (H0 for j = 0): j at 0
    const double* d = E + kElementSize * (2 * j + 1) * W;  // H_j (B0 for 0, H_{N/2} for the last): j at 1, j − 1 at 0
    const double* e = E + kElementSize * (2 * j + 3) * W;  // H_{j+1}: j at 0
    double* rx = band + 12 * j * S;
    double* ry = rx + 6 * S;
    // The diagonal block's (x, x) and (y, y), then nodes j − 1 and j − 2, y column then x, at
    // distances 1 … 4 (x row) and 2 … 5 (y), then (y, x): each a sum from 0 in element order.
    for (int dim = 0; dim < 2; ++dim) {
      V s = V{} + 0.0;
      s += lane<V>(a, kWg + 2 + dim) * lane<V>(a, kG + 2 + dim);
      s += lane<V>(b, kWg + 4 + dim) * lane<V>(b, kG + 4 + dim);
      s += lane<V>(c, kWg + dim) * lane<V>(c, kG + dim);
      s += lane<V>(d, kWg + 2 + dim) * lane<V>(d, kG + 2 + dim);
      s += lane<V>(e, kWg + dim) * lane<V>(e, kG + dim);
      put<Live>(dim == 0 ? rx : ry, s);
    }
    for (int cc = 1; cc >= 0; --cc)
      for (int dim = 0; dim < 2; ++dim) {
        V t = V{} + 0.0;
        t += lane<V>(a, kWg + 2 + dim) * lane<V>(a, kG + cc);
        t += lane<V>(b, kWg + 4 + dim) * lane<V>(b, kG + 2 + cc);
        t += lane<V>(d, kWg + 2 + dim) * lane<V>(d, kG + cc);
        put<Live>(dim == 0 ? rx + (2 - cc) * S : ry + (3 - cc) * S, t);
        const V u = 0.0 + lane<V>(b, kWg + 4 + dim) * lane<V>(b, kG + cc);  // from 0 as the sums: −0 → +0
        put<Live>(dim == 0 ? rx + (4 - cc) * S : ry + (5 - cc) * S, u);
      }
    {  // (y, x) of node j
      V yx = V{} + 0.0;
      yx += lane<V>(a, kWg + 3) * lane<V>(a, kG + 2);
      yx += lane<V>(b, kWg + 5) * lane<V>(b, kG + 4);
      yx += lane<V>(c, kWg + 1) * lane<V>(c, kG + 0);
      yx += lane<V>(d, kWg + 3) * lane<V>(d, kG + 2);
      yx += lane<V>(e, kWg + 1) * lane<V>(e, kG + 0);
      put<Live>(ry + S, yx);
    }
  }
  // Axis nodes' x: row and column cleared.
  const V zero = V{} + 0.0;
  for (const int i : {0, 2 * last}) {
    for (int q = 0; q <= kBand; ++q) put<Live>(band + (6 * i + q) * S, zero);
    for (int r = i + 1; r <= std::min(2 * last + 1, i + kBand); ++r) put<Live>(band + (6 * r + (r - i)) * S, zero);
  }
}

// The lane scratch of W rings: elements, bars, then the nodes' x and y.
template <int W>
struct LaneScratch {
  double *elements, *bars, *px, *py;
  LaneScratch(double* s, int n_ind)
      : elements(s),
        bars(s + element_values(n_ind) * W),
        px(bars + 4 * (n_ind - 1) * W),
        py(px + n_ind * W) {}
  static std::size_t size(int n_ind) {
    return static_cast<std::size_t>((element_values(n_ind) + 4 * (n_ind - 1) + 2 * n_ind) * W);
  }
};

// Each vector width its own part of the scratch (the slots no element writes stay 0 in each:
// a Pair's layout would read a Quad's values there).
template <int W>
double* scratch_of(double* scratch, int n_ind) {
  if constexpr (W == 1) return scratch;
  else return scratch_of<W / 2>(scratch, n_ind) + LaneScratch<W / 2>::size(n_ind);
}

}  // namespace

std::size_t ring_band_scratch_size(int n_ind) {
  return LaneScratch<1>::size(n_ind) + LaneScratch<2>::size(n_ind) + LaneScratch<4>::size(n_ind) +
         LaneScratch<8>::size(n_ind);
}

void assemble_ring_band(const double* y, int n_ind, double c_bar, double c_hinge, double* band, std::ptrdiff_t S,
                        double* scratch, double* bar_e) {
  const LaneScratch<1> s(scratch_of<1>(scratch, n_ind), n_ind);
  for (int j = 0; j < n_ind; ++j) {
    s.px[j] = y[6 * j];
    s.py[j] = y[6 * j + 1];
  }
  band_elements<double>(s.px, s.py, n_ind, c_bar, c_hinge, s.elements, s.bars);
  if (bar_e)
    for (int k = 0; k < n_ind - 1; ++k) {
      bar_e[2 * k] = s.bars[4 * k + 2];
      bar_e[2 * k + 1] = s.bars[4 * k + 3];
    }
  band_rows<double, 1>(s.elements + kElementSize * kElementPad, n_ind - 1, band, S);
}

namespace {

// Every node's two band rows of the lane group from its elements, the first `live` lanes
// written.
template <class V>
[[gnu::always_inline]] inline void band_rows_live(const double* E, int last, double* band, std::ptrdiff_t S, int live) {
  constexpr int W = Lanes<V>::W;
  if (live == W) {
    band_rows<V, W>(E, last, band, S);
  } else if (live == 1) {
    band_rows<V, 1>(E, last, band, S);
  } else if constexpr (W == 4) {
    if (live == 2)
      band_rows<V, 2>(E, last, band, S);
    else
      band_rows<V, 3>(E, last, band, S);
  } else if constexpr (W == 8) {
    switch (live) {
      case 2: band_rows<V, 2>(E, last, band, S); break;
      case 3: band_rows<V, 3>(E, last, band, S); break;
      case 4: band_rows<V, 4>(E, last, band, S); break;
      case 5: band_rows<V, 5>(E, last, band, S); break;
      case 6: band_rows<V, 6>(E, last, band, S); break;
      default: band_rows<V, 7>(E, last, band, S);
    }
  }
}

// Rings p … p + W − 1 on the lanes of a V (a spare lane a copy of ring p, not written).
template <class V>
[[gnu::always_inline]] inline void ring_group(const double* y, std::size_t ring_stride, int rings, int n_ind,
                                              double c_bar, double c_hinge, double* band, std::ptrdiff_t S,
                                              double* scratch, double* bar_e, int p) {
  constexpr int W = Lanes<V>::W;
  const LaneScratch<W> s(scratch_of<W>(scratch, n_ind), n_ind);
  const int last = n_ind - 1;
  const int live = std::min(W, rings - p);
  const double* yl[W];
  for (int l = 0; l < W; ++l) yl[l] = y + static_cast<std::size_t>(l < live ? p + l : p) * ring_stride;
  for (int j = 0; j < n_ind; ++j)  // (x, y) of the rings into their lanes, two rings at a time
    for (int l = 0; l < W; l += 2) {
      const Pair a = lanes::load(yl[l] + 6 * j), b = lanes::load(yl[l + 1] + 6 * j);
      lanes::store(s.px + W * j + l, __builtin_shuffle(a, b, lanes::PairMask{0, 2}));
      lanes::store(s.py + W * j + l, __builtin_shuffle(a, b, lanes::PairMask{1, 3}));
    }
  band_elements<V>(s.px, s.py, n_ind, c_bar, c_hinge, s.elements, s.bars);
  if (bar_e)
    for (int l = 0; l < live; ++l) {
      double* e = bar_e + 2 * static_cast<std::ptrdiff_t>((p + l) * last);
      for (int k = 0; k < last; ++k) {
        e[2 * k] = s.bars[(4 * k + 2) * W + l];
        e[2 * k + 1] = s.bars[(4 * k + 3) * W + l];
      }
    }
  band_rows_live<V>(s.elements + kElementSize * kElementPad * W, last, band + p, S, live);
}

// All rings, Width to a vector: Pairs (2), or Quads and a Pair for the rest (4; S is even).
template <std::ptrdiff_t kS, int Width>
[[gnu::always_inline]] inline void rings_in_lanes(const double* y, std::size_t ring_stride, int rings, int n_ind,
                                                  double c_bar, double c_hinge, double* band, std::ptrdiff_t lanes,
                                                  double* scratch, double* bar_e) {
  const std::ptrdiff_t S = kS > 0 ? kS : lanes;
  int p = 0;
  if constexpr (Width == 8)  // every ring in Octs, the last one's spare lanes masked off
    for (; p < rings; p += 8)
      ring_group<Oct>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, S, scratch, bar_e, p);
  if constexpr (Width == 4)
    for (; p + 4 <= S; p += 4)
      ring_group<Quad>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, S, scratch, bar_e, p);
  for (; p < rings; p += 2)
    ring_group<Pair>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, S, scratch, bar_e, p);
}

// The lane stride a compile-time constant for the usual ring counts: the strided stores
// then take immediate offsets.
template <int Width>
[[gnu::always_inline]] inline void assemble_in_lanes(const double* y, std::size_t ring_stride, int rings, int n_ind,
                                                     double c_bar, double c_hinge, double* band, double* scratch,
                                                     double* bar_e) {
  const int S = band_lane_count(rings);
  switch (S) {
    case 2: rings_in_lanes<2, Width>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, 2, scratch, bar_e); break;
    case 4: rings_in_lanes<4, Width>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, 4, scratch, bar_e); break;
    case 6: rings_in_lanes<6, Width>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, 6, scratch, bar_e); break;
    case 8: rings_in_lanes<8, Width>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, 8, scratch, bar_e); break;
    default: rings_in_lanes<0, Width>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, S, scratch, bar_e);
  }
}

void assemble_sse2(const double* y, std::size_t ring_stride, int rings, int n_ind, double c_bar, double c_hinge,
                   double* band, double* scratch, double* bar_e) {
  assemble_in_lanes<2>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, scratch, bar_e);
}

#if defined(__x86_64__) && !defined(__FMA__)
[[gnu::target("avx2")]] void assemble_avx2(const double* y, std::size_t ring_stride, int rings, int n_ind,
                                           double c_bar, double c_hinge, double* band, double* scratch,
                                           double* bar_e) {
  assemble_in_lanes<4>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, scratch, bar_e);
}
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")  // avx512f implies FMA: no product fused into a sum
[[gnu::target("avx512f")]] void assemble_avx512(const double* y, std::size_t ring_stride, int rings, int n_ind,
                                                double c_bar, double c_hinge, double* band, double* scratch,
                                                double* bar_e) {
  assemble_in_lanes<8>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, scratch, bar_e);
}
#pragma GCC pop_options
#else
void assemble_avx2(const double* y, std::size_t ring_stride, int rings, int n_ind, double c_bar, double c_hinge,
                   double* band, double* scratch, double* bar_e) {
  assemble_in_lanes<2>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, scratch, bar_e);
}
void assemble_avx512(const double* y, std::size_t ring_stride, int rings, int n_ind, double c_bar, double c_hinge,
                     double* band, double* scratch, double* bar_e) {
  assemble_in_lanes<2>(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, scratch, bar_e);
}
#endif

}  // namespace

void assemble_ring_bands(const double* y, std::size_t ring_stride, int rings, int n_ind, double c_bar,
                         double c_hinge, double* band, double* scratch, double* bar_e, int width) {
  if (width == 8 && lanes::wide_lanes_available() == 8)
    assemble_avx512(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, scratch, bar_e);
  else if (width >= 4 && band_lanes_avx2())
    assemble_avx2(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, scratch, bar_e);
  else
    assemble_sse2(y, ring_stride, rings, n_ind, c_bar, c_hinge, band, scratch, bar_e);
}

}  // namespace ringcrush::hinge
