#include "fe/contact/penalty_step_cap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ringcrush::fe {

double spring_to_element_omega2_limit(double fraction) {
  if (!(fraction > 0 && fraction <= 0.5))
    throw std::invalid_argument(
        fmt::format("contact penalty step fraction {} must lie in (0, 0.5] (0: off, the penalty scale as given)", fraction));
  const double keep = 1.0 - fraction;
  return 1.0 / (keep * keep) - 1.0;
}

double penalty_step_factor(double fraction, double element_omega2, double spring_omega2) {
  const double limit = spring_to_element_omega2_limit(fraction);
  if (!(element_omega2 > 0) || !std::isfinite(element_omega2))
    throw std::invalid_argument(fmt::format("penalty step factor: element ω² = {} must be > 0 and finite", element_omega2));
  if (!(spring_omega2 > 0) || !std::isfinite(spring_omega2))
    throw std::invalid_argument(fmt::format("penalty step factor: spring ω² = {} must be > 0 and finite", spring_omega2));
  return std::min(1.0, limit * element_omega2 / spring_omega2);
}

// The same expression as SurfaceContact::set_mass (ring_pair_contact.cpp), maximised.
double surface_spring_omega2(const std::vector<ContactPass>& passes, const Eigen::VectorXd& mass) {
  double out = 0;
  for (const auto& pass : passes) {
    double inv_master = 0;
    for (const auto& q : pass.pieces)
      for (int a = 0; a < q.count; ++a) inv_master = std::max(inv_master, 1.0 / mass(2 * q.nodes[a] + 1));
    for (std::size_t s = 0; s < pass.slaves.size(); ++s)
      out = std::max(out, pass.slave_k[s] * (1.0 / mass(2 * pass.slaves[s] + 1) + 1.25 * inv_master));
  }
  return out;
}

}  // namespace ringcrush::fe
