#include "fe/dynamics/mass_scaling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ringcrush::fe {

void validate(const MassScaling& s) {
  if (!std::isfinite(s.target_step_s) || s.target_step_s < 0)
    throw std::invalid_argument(
        fmt::format("mass scaling: mass_scaling_dt = {} s must be >= 0 and finite (0: off)", s.target_step_s));
  if (!std::isfinite(s.factor) || !(s.factor >= 1))
    throw std::invalid_argument(
        fmt::format("mass scaling: mass_scaling_factor = {} must be >= 1 and finite (1: off)", s.factor));
  if (!(s.safety > 0 && s.safety <= 1))
    throw std::invalid_argument(fmt::format("mass scaling: safety = {} must be in (0, 1]", s.safety));
}

MassScalingReport scale_element_masses(const MassScaling& scaling, double step_fraction,
                                       std::vector<std::array<double, 8>>& element_mass, std::vector<double>& omega2) {
  validate(scaling);
  if (!(step_fraction > 0 && step_fraction <= 1))
    throw std::invalid_argument(fmt::format("mass scaling: step fraction {} must be in (0, 1]", step_fraction));
  if (element_mass.size() != omega2.size())
    throw std::invalid_argument(fmt::format("mass scaling: {} element masses for {} eigenvalues", element_mass.size(),
                                            omega2.size()));
  MassScalingReport r;
  r.active = scaling.active();
  r.target_step_s = scaling.target_step_s;
  r.factor = scaling.factor;
  r.elements = static_cast<int>(element_mass.size());
  r.element_scale.assign(element_mass.size(), 1.0);
  const auto step_of = [&](double w2) { return step_fraction * 2.0 / std::sqrt(w2); };
  double before = INFINITY, after = INFINITY;
  for (std::size_t e = 0; e < element_mass.size(); ++e) {
    if (!(omega2[e] > 0) || !std::isfinite(omega2[e]))
      throw std::invalid_argument(fmt::format("mass scaling: element {} has eigenvalue {}", e + 1, omega2[e]));
    double mass = 0;
    for (double m : element_mass[e]) mass += m;
    r.element_mass_kg += mass;
    const double dt = step_of(omega2[e]);
    before = std::min(before, dt);
    if (!r.active) continue;
    // UNIFORM first: Δt_e grows by √f. Then BELOW MIN: s = (Δt*/Δt_e)² brings it to Δt*.
    double s = scaling.factor;
    const double dt_f = dt * std::sqrt(s);
    if (scaling.target_step_s > dt_f) s *= (scaling.target_step_s / dt_f) * (scaling.target_step_s / dt_f);
    if (s != 1.0) {
      r.element_scale[e] = s;
      ++r.scaled_elements;
      for (double& m : element_mass[e]) m *= s;
      omega2[e] /= s;
      r.added_mass_kg += (s - 1.0) * mass;
    }
    after = std::min(after, step_of(omega2[e]));
  }
  r.min_element_step_s = element_mass.empty() ? 0 : before;
  r.min_scaled_element_step_s = element_mass.empty() ? 0 : r.active ? after : before;
  return r;
}

}  // namespace ringcrush::fe
