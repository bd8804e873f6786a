#include "fe/element/cps8_shape.hpp"

#include <cmath>
#include <stdexcept>

namespace ringcrush::fe {

void cps8_shape(double g, double h, ShapeVec& n, ShapeGrad& dn) {
  // Corners: N = ¼(1 + g gᵢ)(1 + h hᵢ)(g gᵢ + h hᵢ − 1); mid-sides: ½(1 − g²)(1 + h hᵢ)
  // or ½(1 + g gᵢ)(1 − h²) (thesis §3.6.1.3).
  for (int a = 0; a < 4; ++a) {
    const double gi = cps8_node_coords[a][0], hi = cps8_node_coords[a][1];
    const double p = 1 + g * gi, q = 1 + h * hi, s = g * gi + h * hi - 1;
    n(a) = 0.25 * p * q * s;
    dn(a, 0) = 0.25 * gi * q * (s + p);
    dn(a, 1) = 0.25 * hi * p * (s + q);
  }
  for (int a = 4; a < 8; ++a) {
    const double gi = cps8_node_coords[a][0], hi = cps8_node_coords[a][1];
    if (gi == 0) {
      n(a) = 0.5 * (1 - g * g) * (1 + h * hi);
      dn(a, 0) = -g * (1 + h * hi);
      dn(a, 1) = 0.5 * (1 - g * g) * hi;
    } else {
      n(a) = 0.5 * (1 + g * gi) * (1 - h * h);
      dn(a, 0) = 0.5 * gi * (1 - h * h);
      dn(a, 1) = -h * (1 + g * gi);
    }
  }
}

std::vector<GaussPoint1d> gauss_rule_1d(int n) {
  if (n == 2) return {{-1 / std::sqrt(3.0), 1}, {1 / std::sqrt(3.0), 1}};
  if (n == 3) return {{-std::sqrt(0.6), 5.0 / 9}, {0, 8.0 / 9}, {std::sqrt(0.6), 5.0 / 9}};
  throw std::invalid_argument("gauss_rule: n must be 2 or 3");
}

std::vector<GaussPoint> gauss_rule(int n) {
  const auto p = gauss_rule_1d(n);
  std::vector<GaussPoint> r;
  for (const auto& b : p)
    for (const auto& a : p) r.push_back({a.x, b.x, a.weight * b.weight});
  return r;
}

}  // namespace ringcrush::fe
