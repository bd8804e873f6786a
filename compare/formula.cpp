#include "formula.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace ringcrush::compare {

hinge::SectionState section_state(SectionState s) {
  return s == SectionState::PlaneStress ? hinge::SectionState::PlaneStress
                                        : hinge::SectionState::PlaneStrain;
}

hinge::RingSection ring_section(const Rings& rings) {
  return {rings.outer_diameter_m, rings.wall_thickness_m, rings.width_m};
}

FormulaInput formula_input(const Scene& scene) {
  const auto& m = scene.rings.material;
  FormulaInput in{ring_section(scene.rings), m.initial_yield_stress(), m.hardening_modulus(),
                  m.youngs_modulus_pa, m.poisson_ratio, section_state(scene.rings.section)};
  return in;
}

FormulaResult evaluate_formula(const FormulaInput& in, int points) {
  if (points < 2) throw std::invalid_argument("formula: at least two points");
  if (in.alphas.empty()) throw std::invalid_argument("formula: at least one Redwood alpha");
  const double d = in.section.mean_diameter();
  FormulaResult r;
  r.plastic_moment_nm = hinge::plastic_moment(in.section, in.yield_stress_pa, in.state);
  r.collapse_load_n = hinge::collapse_load(r.plastic_moment_nm, d);
  r.elastic_stiffness_n_m =
      hinge::elastic_stiffness(in.section, in.youngs_modulus_pa, in.poisson_ratio, in.state);
  r.first_yield_load_n = hinge::first_yield_load(in.section, in.yield_stress_pa);
  if (in.state == hinge::SectionState::PlaneStrain) r.first_yield_load_n *= 2.0 / std::sqrt(3.0);
  r.lock_deflection_m = in.section.lock_deflection();
  r.dh_energy_to_lock_j = hinge::deruntz_hodge_energy(r.plastic_moment_nm, r.lock_deflection_m, d);
  for (double a : in.alphas)
    r.redwood_energy_to_lock_j.push_back(hinge::redwood_energy(
        r.plastic_moment_nm, in.hardening_modulus_pa, in.yield_stress_pa, a, r.lock_deflection_m, d));

  auto& c = r.curves;
  c.columns = {"deflection_m", "deflection_ratio", "force_deruntz_hodge_N"};
  for (double a : in.alphas) c.columns.push_back(fmt::format("force_redwood_alpha_{:g}_N", a));
  c.columns.push_back("energy_deruntz_hodge_J");
  for (double a : in.alphas) c.columns.push_back(fmt::format("energy_redwood_alpha_{:g}_J", a));
  for (int i = 0; i < points; ++i) {
    const double delta = r.lock_deflection_m * i / (points - 1);
    std::vector<double> row{delta, delta / d,
                            hinge::deruntz_hodge_load(r.collapse_load_n, delta, d)};
    for (double a : in.alphas)
      row.push_back(hinge::redwood_load(r.collapse_load_n, in.hardening_modulus_pa,
                                        in.yield_stress_pa, a, delta, d));
    row.push_back(hinge::deruntz_hodge_energy(r.plastic_moment_nm, delta, d));
    for (double a : in.alphas)
      row.push_back(hinge::redwood_energy(r.plastic_moment_nm, in.hardening_modulus_pa,
                                          in.yield_stress_pa, a, delta, d));
    c.add_row(std::move(row));
  }
  return r;
}

}  // namespace ringcrush::compare
