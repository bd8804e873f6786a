#include "hinge/redwood_hinge_length.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace ringcrush::hinge {

double redwood_hinge_length(double alpha, double bar_length_m) {
  if (!(alpha >= 1.0 && alpha <= 4.0))
    throw std::invalid_argument(fmt::format(
        "Redwood-fitted hinge length: redwood_alpha = {} is outside the fitted range [1, 4]", alpha));
  if (!(bar_length_m > 0) || !std::isfinite(bar_length_m))
    throw std::invalid_argument(fmt::format("Redwood-fitted hinge length: bar length {} m must be positive", bar_length_m));
  return bar_length_m * (0.119 * alpha + 0.0432 * alpha * alpha);
}

}  // namespace ringcrush::hinge
