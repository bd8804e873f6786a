// The rotation of a polygon hinge from its two bars (THEORY §4.3), without an atan2 per bar.
// The hinge k turns by τ = β_{k−1} − β_k; its rotation from the undeformed ring is
// θ = τ − 2π/N, the angle from bar k to bar k − 1 turned back by 2π/N:
//   θ = atan2(c, d), (d, c) = (e_k · u, e_k × u), u = R(−2π/N) e_{k−1},
// with e the bars' unit vectors, so that d² + c² = 1 to round-off and tan(θ/2) = c/(1 + d).
// Most hinges of a crushing ring stay within a few degrees of their rest angle (README
// "cheaper hinge angle"), where θ = 2 atan(w), w = c/(1 + d), is an odd series in w; the
// others take atan2. The result is that of wrap(β_{k−1} − β_k) − 2π/N to round-off, in the
// same range (−π − 2π/N, π − 2π/N].
#pragma once

#include <cmath>

namespace ringcrush::hinge {

// |w| ≤ kHingeSeriesLimit (|θ| ≤ 2 atan 0.2 ≈ 0.395 rad) takes the series. The first term
// left out, w²³/23 ≤ 1.8e-18 at w = 0.2, is 1e-17 of atan(0.2) ≈ 0.197, a tenth of an ulp:
// the series is as exact as its rounding.
inline constexpr double kHingeSeriesLimit = 0.2;

// atan(w) for |w| ≤ kHingeSeriesLimit: w − w s p(s), s = w², p = 1/3 − s/5 + s²/7 − … − s⁹/21,
// p by Estrin's scheme (pairs, then s², s⁴, s⁸) rather than Horner's: four levels of
// dependent multiply-adds instead of ten, so that the hinges' series overlap. T is double or
// a vector of doubles (hinge/ring_lanes.hpp: two rings' hinges at once, the same bits).
// Always inlined: the vector copy is compiled for the instruction set of its caller.
template <class T>
[[gnu::always_inline]] inline T small_atan(T w) {
  const T s = w * w, s2 = s * s, s4 = s2 * s2, s8 = s4 * s4;
  const T q01 = 1.0 / 3.0 - s * (1.0 / 5.0), q23 = 1.0 / 7.0 - s * (1.0 / 9.0);
  const T q45 = 1.0 / 11.0 - s * (1.0 / 13.0), q67 = 1.0 / 15.0 - s * (1.0 / 17.0);
  const T q89 = 1.0 / 19.0 - s * (1.0 / 21.0);
  const T p = (q01 + s2 * q23) + s4 * (q45 + s2 * q67) + s8 * q89;
  return w - w * (s * p);
}

// θ = atan2(cross, dot) of two unit vectors (a hinge's turned bars), in
// (−π − turn0, π − turn0]. dot > 0 keeps 1 + dot away from the cancellation near θ = π.
// The branch beyond the series: atan2 moved into the range.
inline double hinge_rotation_atan2(double cross, double dot, double turn0) {
  constexpr double pi = 3.141592653589793238462643383279502884;
  const double theta = std::atan2(cross, dot);
  return theta > pi - turn0 ? theta - 2.0 * pi : theta;
}

inline double hinge_rotation(double cross, double dot, double turn0) {
  if (dot > 0.0) {
    const double w = cross / (1.0 + dot);
    if (std::abs(w) <= kHingeSeriesLimit) return 2.0 * small_atan(w);
  }
  return hinge_rotation_atan2(cross, dot, turn0);
}

// ∂θ/∂p of a hinge for its nodes (k − 1, k, k + 1), from its bars u = p_k − p_{k−1} and
// w = p_{k+1} − p_k: ∂β/∂p of a bar b is ± n/ℓ = ±(−b_y, b_x)/|b|² (THEORY §4.3), and θ turns
// with β_{k−1} − β_k. The Kelvin–Voigt hinge damper's geometry (polygon_implicit_dampers.cpp).
struct HingeAngleGradient {
  double g[3][2];
};
inline HingeAngleGradient hinge_angle_gradient(double ux, double uy, double wx, double wy) {
  const double lu = ux * ux + uy * uy, lw = wx * wx + wy * wy;
  const double ax = -uy / lu, ay = ux / lu, bx = -wy / lw, by = wx / lw;
  return {{{-ax, -ay}, {ax + bx, ay + by}, {-bx, -by}}};
}

}  // namespace ringcrush::hinge
