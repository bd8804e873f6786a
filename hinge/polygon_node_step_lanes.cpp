// The nodes' stable-step limits several to a vector (polygon_node_step_lanes.hpp), one
// template over the width, compiled for SSE2, "avx2" and "avx512f" (contraction off).
#pragma GCC diagnostic ignored "-Wpsabi"  // the AVX copies (hinge/ring_lanes_wide.hpp)

#include "hinge/polygon_node_step_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hinge/ring_lanes_wide.hpp"

namespace ringcrush::hinge {

// Belytschko, Liu & Moran §6.3: the central difference with damping at the half-step
// velocity (polygon_stable_step.cpp).
double node_step_limit(double K, double C, double mass) {
  if (!(K > 0.0)) return std::numeric_limits<double>::infinity();
  const double omega = std::sqrt(K / mass);
  const double xi = C / (2.0 * std::sqrt(K * mass));
  return 2.0 / omega * (std::sqrt(1.0 + xi * xi) - xi);
}

namespace {

// The limits of the W nodes at K, C, mass into the running minimum `low` (lane by lane: a limit below
// it replaces it, as std::min(low, limit)).
template <int W, class V>
[[gnu::always_inline]] inline V min_limits(V low, const double* K, const double* C, const double* mass) {
  using O = lanes::Wide<W>;
  const V k = O::load(K), c = O::load(C), m = O::load(mass);
  const V omega = O::sqrt(k / m);
  const V xi = c / (2.0 * O::sqrt(k * m));
  const V dt = 2.0 / omega * (O::sqrt(1.0 + xi * xi) - xi);
  // K ≤ 0 (or NaN): no limit. (dt < low) is false there, so such a lane keeps low.
  const auto take = (k > 0.0) & (dt < low);
  return take ? dt : low;
}

// Width nodes at a time; the last group padded with K = 0 (no limit) rather than run one by
// one (a node's three divisions and three square roots are what the vectors save).
template <int Width>
[[gnu::always_inline]] inline double min_run(double dt, const double* K, const double* C, const double* mass,
                                             int count) {
  using V = typename lanes::Wide<Width>::V;
  V low = V{} + std::numeric_limits<double>::infinity();
  int i = 0;
  for (; i + Width <= count; i += Width) low = min_limits<Width>(low, K + i, C + i, mass + i);
  if (i < count) {
    double k[Width] = {}, c[Width] = {}, m[Width];
    for (int l = 0; l < Width; ++l) {
      const bool node = i + l < count;
      k[l] = node ? K[i + l] : 0.0;
      c[l] = node ? C[i + l] : 0.0;
      m[l] = node ? mass[i + l] : 1.0;
    }
    low = min_limits<Width>(low, k, c, m);
  }
  for (int l = 0; l < Width; ++l) dt = std::min(dt, low[l]);
  return dt;
}

double min_run_sse2(double dt, const double* K, const double* C, const double* mass, int count) {
  return min_run<2>(dt, K, C, mass, count);
}

#if defined(__x86_64__) && !defined(__FMA__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
[[gnu::target("avx2")]] double min_run_avx2(double dt, const double* K, const double* C, const double* mass,
                                            int count) {
  return min_run<4>(dt, K, C, mass, count);
}
[[gnu::target("avx512f")]] double min_run_avx512(double dt, const double* K, const double* C, const double* mass,
                                                 int count) {
  return min_run<8>(dt, K, C, mass, count);
}
#pragma GCC pop_options
#else
double min_run_avx2(double dt, const double* K, const double* C, const double* mass, int count) {
  return min_run<2>(dt, K, C, mass, count);
}
double min_run_avx512(double dt, const double* K, const double* C, const double* mass, int count) {
  return min_run<2>(dt, K, C, mass, count);
}
#endif

}  // namespace

double min_node_step_limit(double dt, const double* K, const double* C, const double* mass, int count, int width) {
  if (width == 8) return min_run_avx512(dt, K, C, mass, count);
  if (width == 4) return min_run_avx2(dt, K, C, mass, count);
  return min_run_sse2(dt, K, C, mass, count);
}

}  // namespace ringcrush::hinge
