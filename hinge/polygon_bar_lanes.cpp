// The bar pass over flat runs of lanes (polygon_bar_lanes.hpp), one template over the vector
// width, compiled for SSE2, "avx2" and "avx512f" (contraction off).
#pragma GCC diagnostic ignored "-Wpsabi"  // the AVX copies (hinge/ring_lanes_wide.hpp)

#include "hinge/polygon_bar_lanes.hpp"

#include "hinge/ring_lanes_wide.hpp"

namespace ringcrush::hinge {

namespace {

// W consecutive values from `at`: W bars' worth of lanes (or part of one bar's).
template <int W>
[[gnu::always_inline]] inline void bar_values(const BarLanes& b, std::size_t at) {
  using O = lanes::Wide<W>;
  using V = typename O::V;
  const V bx = O::load(b.px + at + b.lanes) - O::load(b.px + at);
  const V by = O::load(b.py + at + b.lanes) - O::load(b.py + at);
  const V l = O::sqrt(bx * bx + by * by), inv = 1.0 / l;
  const V e_x = bx * inv, e_y = by * inv;
  O::store(b.ex + at, e_x);
  O::store(b.ey + at, e_y);
  O::store(b.gx + at, -e_y * inv);
  O::store(b.gy + at, e_x * inv);
  O::store(b.n + at, b.k_m * (l - b.l0));
}

// The run [first·lanes, last·lanes): Width values at a time, then 4 and 2 (the run is even).
template <int Width>
[[gnu::always_inline]] inline void bar_run(const BarLanes& b, int first, int last) {
  std::size_t at = static_cast<std::size_t>(first) * b.lanes;
  const std::size_t end = static_cast<std::size_t>(last) * b.lanes;
  if constexpr (Width >= 8)
    for (; at + 8 <= end; at += 8) bar_values<8>(b, at);
  if constexpr (Width >= 4)
    for (; at + 4 <= end; at += 4) bar_values<4>(b, at);
  for (; at < end; at += 2) bar_values<2>(b, at);
}

void bar_run_sse2(const BarLanes& b, int first, int last) { bar_run<2>(b, first, last); }

#if defined(__x86_64__) && !defined(__FMA__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
[[gnu::target("avx2")]] void bar_run_avx2(const BarLanes& b, int first, int last) { bar_run<4>(b, first, last); }
[[gnu::target("avx512f")]] void bar_run_avx512(const BarLanes& b, int first, int last) {
  bar_run<8>(b, first, last);
}
#pragma GCC pop_options
#else
void bar_run_avx2(const BarLanes& b, int first, int last) { bar_run<2>(b, first, last); }
void bar_run_avx512(const BarLanes& b, int first, int last) { bar_run<2>(b, first, last); }
#endif

}  // namespace

void bar_lanes(const BarLanes& b, int first, int last, int width) {
  if (width == 8)
    bar_run_avx512(b, first, last);
  else if (width == 4)
    bar_run_avx2(b, first, last);
  else
    bar_run_sse2(b, first, last);
}

}  // namespace ringcrush::hinge
