// Fixed mass scaling of the explicit solver (issue 4 performance; ABAQUS/Explicit
// *FIXED MASS SCALING): a named, opt-in CHANGE OF THE PHYSICS that buys a larger stable step
// by adding mass where the step is smallest. Off by default; with it off nothing is touched
// (the ChainModel's masses, hence every result, are bitwise those of a build without it).
//
//  - factor f ≥ 1 (ABAQUS FACTOR=, TYPE=UNIFORM): every element's density × f; its stable
//    step grows by √f.
//  - target Δt* > 0 (ABAQUS DT=, TYPE=BELOW MIN): after the factor, every element whose own
//    step Δt_e is below Δt* gets its density × (Δt*/Δt_e)², so that Δt_e reaches Δt*
//    exactly (λ_max(K_e, s M_e) = λ_max(K_e, M_e)/s for the diagonal HRZ mass); the others
//    keep their mass bit for bit. Both given: the factor first, then the target, as ABAQUS.
//
// The element's own step is the one the explicit driver would take if that element alone
// set ω_max: Δt_e = safety · (√(1 + b1²) − b1) · 2/√λ_max(K_e, M_e), WITH the driver's safety
// factor and the bulk-viscosity reduction (chain_model.cpp, contact_stable_step). So Δt* is
// the step the user asks the driver to take: when the elements limit (no contact stiffer,
// no element crushed since the start), the step taken is Δt*. The scaling is fixed at the
// start, on the reference shape (ABAQUS "fixed" scaling, at the beginning of the step):
// crushed and thickened elements, and the contact penalty springs (their ω² = k/m rises with
// the scaled nodal mass but not to the target), can still pull the step below Δt*; the
// driver then logs what limited it and counts those steps.
//
// What it costs: the scaled mass is the mass everywhere — the lumped mass, the kinetic
// energy, the momentum, the energy balance, the contact part of the stable step, the bulk
// viscosity (its coefficient b1 ρ c_d L_e follows ρ: same fraction of critical damping of
// the scaled element) — so the impact now meets a heavier chain. The added mass is
// reported next to the time it buys (README, "Mass scaling").
#pragma once

#include <array>
#include <vector>

namespace ringcrush::fe {

struct MassScaling {
  double target_step_s = 0;  // Δt*, BELOW MIN; 0 = off
  double factor = 1;         // f, UNIFORM; 1 = off
  // The explicit driver's safety (Δt = safety · 2/ω_max). run_dynamic sets it from
  // DynamicSolverInput::safety; only a ChainModel built by hand needs it set.
  double safety = 0.8;
  bool active() const { return target_step_s > 0 || factor != 1; }
};

// Throws std::invalid_argument naming the value: target negative or not finite, factor < 1
// or not finite, safety outside (0, 1].
void validate(const MassScaling& scaling);

struct MassScalingReport {
  bool active = false;
  double target_step_s = 0, factor = 1;
  int elements = 0, scaled_elements = 0;      // scaled: mass changed (by the factor or the target)
  double element_mass_kg = 0;                 // Σ unscaled element masses (model: a half model's half)
  double added_mass_kg = 0;                   // Σ (scaled − unscaled) element masses (model)
  double min_element_step_s = 0;              // smallest Δt_e before scaling
  double min_scaled_element_step_s = 0;       // smallest Δt_e after
  std::vector<double> element_scale;          // density multiplier per element (1: untouched)
};

// Scales element_mass[e] (HRZ nodal masses of element e) and omega2[e] = λ_max(K_e, M_e) in
// place; step_fraction = safety · (√(1 + b1²) − b1), so that Δt_e = step_fraction · 2/√omega2[e].
// Inactive: nothing is touched and the report says so. The caller re-solves omega2 of the
// scaled elements if it wants it from the eigenproblem rather than the division here.
MassScalingReport scale_element_masses(const MassScaling& scaling, double step_fraction,
                                       std::vector<std::array<double, 8>>& element_mass,
                                       std::vector<double>& omega2);

}  // namespace ringcrush::fe
