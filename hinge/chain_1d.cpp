#include "chain_1d.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "ring_laws.hpp"

namespace ringcrush::hinge {
namespace {
void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}
}  // namespace

double RingLaw::lock_angle() const { return std::asin(lock_deflection() / mean_diameter()); }
double RingLaw::collapse_load() const {
  return hinge::collapse_load(plastic_moment_nm, mean_diameter());
}
double RingLaw::hardening_k() const {
  return hardening_modulus_pa / (3.0 * yield_stress_pa * redwood_alpha);
}

// Same value as ring_laws' redwood_load (tested), with one asin instead of three: this is
// evaluated in every right-hand side and root function of Level 0.
double RingLaw::backbone_raw(double dp) const {
  const double d = mean_diameter();
  const double x = std::max(dp, 0.0) / d;
  if (!(x < 1.0)) throw std::domain_error("ring crush beyond the mean diameter");
  const double k = hardening_k();
  const double phi = k != 0.0 ? std::asin(x) : 0.0;
  return 8.0 * plastic_moment_nm / d * (1.0 + k * phi) / std::sqrt(1.0 - x * x);
}

// With f(φ) = (1 + kφ)/cos φ, P_b = P0 f(φ) and dφ/dδ = 1/(d cos φ):
//   f′ = k/c + (1 + kφ) s/c²,  f″ = 2k s/c² + (1 + kφ)(1 + s²)/c³,
// where s = sin φ = δ/d and c = cos φ = √(1 − s²) need no trigonometric calls.
double RingLaw::backbone_slope_raw(double dp) const {
  const double d = mean_diameter(), k = hardening_k();
  const double s = std::max(dp, 0.0) / d;
  if (!(s < 1.0)) throw std::domain_error("ring crush beyond the mean diameter");
  const double c = std::sqrt(1.0 - s * s), phi = k != 0.0 ? std::asin(s) : 0.0;
  const double f1 = k / c + (1.0 + k * phi) * s / (c * c);
  return 8.0 * plastic_moment_nm / d * f1 / (d * c);
}

double RingLaw::backbone_curvature_raw(double dp) const {
  const double d = mean_diameter(), k = hardening_k();
  const double s = std::max(dp, 0.0) / d;
  if (!(s < 1.0)) throw std::domain_error("ring crush beyond the mean diameter");
  const double c = std::sqrt(1.0 - s * s), phi = k != 0.0 ? std::asin(s) : 0.0;
  const double f1 = k / c + (1.0 + k * phi) * s / (c * c);
  const double f2 = 2.0 * k * s / (c * c) + (1.0 + k * phi) * (1.0 + s * s) / (c * c * c);
  // d/dδ [f′/(d c)] = (1/(d c)) · (f″/(d c) + f′ s/(d c²))
  return 8.0 * plastic_moment_nm / d / (d * c) * (f2 / (d * c) + f1 * s / (d * c * c));
}

// Past lock-up (δp > δ_L) the inner-wall contact carries the load (lock stiffness); the
// backbone is continued linearly (C¹) so that an overloaded chain, compressed beyond solid,
// stays defined instead of reaching the DeRuntz–Hodge singularity at δ = d. The work is
// continued consistently.
double RingLaw::backbone(double dp) const {
  const double dl = lock_deflection();
  if (dp <= dl) return backbone_raw(dp);
  return backbone_raw(dl) + backbone_slope_raw(dl) * (dp - dl);
}
double RingLaw::backbone_slope(double dp) const {
  const double dl = lock_deflection();
  return backbone_slope_raw(std::min(dp, dl));
}
double RingLaw::backbone_curvature(double dp) const {
  return dp <= lock_deflection() ? backbone_curvature_raw(dp) : 0.0;
}

double RingLaw::plastic_energy(double dp) const {
  const double dl = lock_deflection();
  if (dp > dl) {
    const double x = dp - dl;
    return plastic_energy(dl) + backbone_raw(dl) * x + 0.5 * backbone_slope_raw(dl) * x * x;
  }
  return redwood_energy(plastic_moment_nm, hardening_modulus_pa, yield_stress_pa, redwood_alpha,
                        std::max(dp, 0.0), mean_diameter());
}

double RingLaw::generalized_force(double phi) const {
  return 8.0 * plastic_moment_nm * (1.0 + hardening_k() * phi);
}

double RingLaw::plastic_energy_at_angle(double phi) const {
  return 8.0 * plastic_moment_nm * (phi + 0.5 * hardening_k() * phi * phi);
}

double RingLaw::mean_force_to_lock() const {
  return plastic_energy(lock_deflection()) / lock_deflection();
}

double RingLaw::inertia(double phi) const {
  const double r = 0.5 * mean_diameter();
  return 2.0 / std::numbers::pi * mass_kg * r * r * dh_inertia_factor(phi);
}

double RingLaw::inertia_derivative(double phi) const {
  const double r = 0.5 * mean_diameter();
  return 2.0 / std::numbers::pi * mass_kg * r * r * dh_inertia_factor_derivative(phi);
}

void RingLaw::validate() const {
  require(outer_diameter_m > 0 && std::isfinite(outer_diameter_m), "ring outer diameter must be positive");
  require(wall_thickness_m > 0 && wall_thickness_m < 0.5 * outer_diameter_m,
          "ring wall thickness must lie in (0, D/2)");
  require(plastic_moment_nm > 0 && std::isfinite(plastic_moment_nm), "plastic moment M0 must be positive");
  require(yield_stress_pa > 0, "yield stress must be positive");
  require(hardening_modulus_pa >= 0, "hardening modulus must not be negative");
  require(redwood_alpha > 0, "Redwood alpha must be positive");
  require(elastic_stiffness_n_m >= 0, "elastic stiffness must not be negative");
  require(lock_stiffness_n_m >= 0, "lock stiffness must not be negative");
  require(mass_kg > 0, "ring mass must be positive");
}

void ChainInput::validate() const {
  require(rings >= 1 && rings <= 1000, "ring count must lie in [1, 1000]");
  ring.validate();
  require(plate_mass_kg >= 0, "plate mass must not be negative");
  require(impactor_mass_kg > 0, "impactor mass must be positive");
  require(impactor_velocity_m_s > 0 && std::isfinite(impactor_velocity_m_s),
          "impactor velocity must be positive");
  require(impactor_spring_n_m >= 0, "impactor spring stiffness must not be negative");
}

double ChainResult::energy_balance_error() const {
  const auto& h = history;
  double worst = 0.0;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    const double total = h.kinetic_j[i] + h.elastic_j[i] + h.plastic_j[i] + h.impact_loss_j[i];
    worst = std::max(worst, std::abs(total - initial_kinetic_energy_j));
  }
  return worst / initial_kinetic_energy_j;
}

}  // namespace ringcrush::hinge
