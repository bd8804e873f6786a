// The thesis's load formula (§4.1.2): DeRuntz–Hodge and Redwood load–deflection curves of
// one ring, with the energies and reference values that go with them (THEORY.md §1).
#pragma once

#include <vector>

#include "compare/scene.hpp"
#include "compare/table_output.hpp"
#include "hinge/ring_laws.hpp"

namespace ringcrush::compare {

struct FormulaInput {
  hinge::RingSection section;
  double yield_stress_pa;
  double hardening_modulus_pa;   // E′
  double youngs_modulus_pa;
  double poisson_ratio;
  hinge::SectionState state = hinge::SectionState::PlaneStress;
  std::vector<double> alphas{0.5, 1.0, 2.0};  // Redwood hinge-length factors
};

struct FormulaResult {
  double plastic_moment_nm;       // M0
  double collapse_load_n;         // P0
  double elastic_stiffness_n_m;   // k_el
  double first_yield_load_n;
  double lock_deflection_m;       // d − t
  double dh_energy_to_lock_j;
  std::vector<double> redwood_energy_to_lock_j;  // one per α
  CsvTable curves;                // deflection_m, force_deruntz_hodge_N, force_redwood_alpha_*_N, energies
};

FormulaInput formula_input(const Scene& scene);
hinge::SectionState section_state(SectionState s);
hinge::RingSection ring_section(const Rings& rings);

// Curves sampled at `points` deflections from 0 to the lock-up deflection.
FormulaResult evaluate_formula(const FormulaInput& input, int points = 41);

}  // namespace ringcrush::compare
