#include "fe/element/through_wall_plastic_moment.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "fe/element/cps8_shape.hpp"

namespace ringcrush::fe {

int gauss_points_through(Integration rule) { return rule == Integration::Reduced ? 2 : 3; }

double through_wall_plastic_moment(int elements_through, Integration rule) {
  if (elements_through < 1)
    throw std::invalid_argument(
        fmt::format("through_wall_plastic_moment: elements_through {} must be ≥ 1", elements_through));
  const auto points = gauss_rule_1d(gauss_points_through(rule));
  const double half = 1.0 / elements_through;  // element half-depth in ξ = 2y/t
  double factor = 0;
  for (int k = 0; k < elements_through; ++k) {
    const double centre = -1.0 + (2 * k + 1) * half;
    for (const auto& p : points) factor += p.weight * half * std::abs(centre + half * p.x);
  }
  return factor;
}

}  // namespace ringcrush::fe
