#include "ring_laws.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ringcrush::hinge {
namespace {
constexpr double pi = std::numbers::pi;

void require_positive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::domain_error(std::string(what) + " must be positive and finite");
}
}  // namespace

double plastic_moment(const RingSection& s, double yield_stress, SectionState state) {
  require_positive(s.wall_thickness_m, "wall thickness");
  require_positive(s.width_m, "width");
  require_positive(yield_stress, "yield stress");
  const double plane_stress = yield_stress * s.wall_thickness_m * s.wall_thickness_m * s.width_m / 4.0;
  return state == SectionState::PlaneStress ? plane_stress : plane_stress * 2.0 / std::sqrt(3.0);
}

double collapse_load(double plastic_moment, double mean_diameter) {
  require_positive(mean_diameter, "mean diameter");
  return 8.0 * plastic_moment / mean_diameter;
}

double mechanism_angle(double deflection, double mean_diameter) {
  require_positive(mean_diameter, "mean diameter");
  const double x = deflection / mean_diameter;
  if (!(x >= 0.0 && x <= 1.0))
    throw std::domain_error("deflection must lie in [0, d] for the DeRuntz-Hodge mechanism");
  return std::asin(x);
}

double deruntz_hodge_load(double p0, double deflection, double mean_diameter) {
  const double phi = mechanism_angle(deflection, mean_diameter);
  if (phi >= 0.5 * pi) throw std::domain_error("DeRuntz-Hodge load is infinite at δ = d");
  return p0 / std::cos(phi);
}

double redwood_factor(double hardening_modulus, double yield_stress, double alpha,
                      double deflection, double mean_diameter) {
  require_positive(yield_stress, "yield stress");
  require_positive(alpha, "Redwood alpha");
  if (hardening_modulus < 0.0) throw std::domain_error("hardening modulus must be >= 0");
  const double phi = mechanism_angle(deflection, mean_diameter);
  return 1.0 + hardening_modulus * phi / (3.0 * yield_stress * alpha);
}

double redwood_load(double p0, double hardening_modulus, double yield_stress, double alpha,
                    double deflection, double mean_diameter) {
  return deruntz_hodge_load(p0, deflection, mean_diameter) *
         redwood_factor(hardening_modulus, yield_stress, alpha, deflection, mean_diameter);
}

double deruntz_hodge_energy(double plastic_moment, double deflection, double mean_diameter) {
  return 8.0 * plastic_moment * mechanism_angle(deflection, mean_diameter);
}

double redwood_energy(double plastic_moment, double hardening_modulus, double yield_stress,
                      double alpha, double deflection, double mean_diameter) {
  require_positive(yield_stress, "yield stress");
  require_positive(alpha, "Redwood alpha");
  const double phi = mechanism_angle(deflection, mean_diameter);
  const double k = hardening_modulus / (3.0 * yield_stress * alpha);
  return 8.0 * plastic_moment * (phi + 0.5 * k * phi * phi);
}

double elastic_stiffness(const RingSection& s, double youngs_modulus, double poisson_ratio,
                         SectionState state) {
  require_positive(youngs_modulus, "Young's modulus");
  const double e = state == SectionState::PlaneStress
                       ? youngs_modulus
                       : youngs_modulus / (1.0 - poisson_ratio * poisson_ratio);
  const double t = s.wall_thickness_m;
  const double inertia = s.width_m * t * t * t / 12.0;
  const double r = s.mean_radius();
  require_positive(r, "mean radius");
  return e * inertia / ((pi / 4.0 - 2.0 / pi) * r * r * r);
}

double first_yield_load(const RingSection& s, double yield_stress) {
  const double t = s.wall_thickness_m;
  return pi * yield_stress * s.width_m * t * t / (6.0 * s.mean_radius());
}

double dh_inertia_factor(double phi) {
  const double c = std::cos(phi), sn = std::sin(phi);
  return (2.0 + c * c) * (0.5 * pi - phi) - 4.0 * c + 2.0 * sn * c + phi * c * c;
}

double dh_inertia_factor_derivative(double phi) {
  // d/dφ of the expression above, term by term.
  const double c = std::cos(phi), sn = std::sin(phi);
  return -2.0 * sn * c * (0.5 * pi - phi) - (2.0 + c * c) + 4.0 * sn + 2.0 * (c * c - sn * sn) +
         c * c - 2.0 * phi * sn * c;
}

double dh_inertia_factor_second_derivative(double phi) {
  const double c = std::cos(phi), sn = std::sin(phi);
  return 4.0 * c * (1.0 - 2.0 * sn) - pi * std::cos(2.0 * phi);
}

double ring_mass(const RingSection& s, double density) {
  return density * pi * s.mean_diameter() * s.wall_thickness_m * s.width_m;
}

}  // namespace ringcrush::hinge
