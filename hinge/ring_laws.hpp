// Closed-form laws of a single thin ring crushed between rigid flat plates.
//
// THEORY.md §1.1–1.4; thesis §4.1.2. Every function is pure and SI. The ring is
// described by its *outer* diameter D (as in the thesis's Tables 1 and 2), its wall
// thickness t and its width L (the plane-stress thickness of the FE model); the
// mechanics uses the mean diameter d = D − t.
#pragma once

namespace ringcrush::hinge {

enum class SectionState { PlaneStress, PlaneStrain };

struct RingSection {
  double outer_diameter_m;
  double wall_thickness_m;
  double width_m;

  double mean_diameter() const { return outer_diameter_m - wall_thickness_m; }
  double mean_radius() const { return 0.5 * mean_diameter(); }
  // Deflection at which the inner walls touch (lock-up): δ_lock = d − t (THEORY §1.3).
  double lock_deflection() const { return mean_diameter() - wall_thickness_m; }
};

// Fully plastic moment of the whole width: σ0 t² L/4 in plane stress, σ0 t² L/(2√3)
// in plane strain (von Mises yield 2σ0/√3), THEORY §1.2.
double plastic_moment(const RingSection& s, double yield_stress, SectionState state);

// Initial collapse load of the four-hinge mechanism, P0 = 8 M0 / d.
double collapse_load(double plastic_moment, double mean_diameter);

// DeRuntz–Hodge mechanism angle φ = asin(δ/d). Throws std::domain_error outside [0, d].
double mechanism_angle(double deflection, double mean_diameter);

// DeRuntz–Hodge rigid–perfectly-plastic load P = P0 / √(1 − (δ/d)²) (THEORY §1.3).
double deruntz_hodge_load(double p0, double deflection, double mean_diameter);

// Redwood's hardening factor 1 + E′ asin(δ/d) / (3 σ0 α); α = side-hinge length in
// wall thicknesses (THEORY §1.4).
double redwood_factor(double hardening_modulus, double yield_stress, double alpha,
                      double deflection, double mean_diameter);

// Redwood's load P_DH · redwood_factor (thesis §4.1.2).
double redwood_load(double p0, double hardening_modulus, double yield_stress, double alpha,
                    double deflection, double mean_diameter);

// Energy absorbed to a deflection, ∫₀^δ P dδ' in closed form:
//   DeRuntz–Hodge W = 8 M0 φ; Redwood W = 8 M0 (φ + k φ²/2), k = E′/(3 σ0 α).
double deruntz_hodge_energy(double plastic_moment, double deflection, double mean_diameter);
double redwood_energy(double plastic_moment, double hardening_modulus, double yield_stress,
                      double alpha, double deflection, double mean_diameter);

// Elastic diametral stiffness of a thin ring under two opposite point loads,
// k = EI / ((π/4 − 2/π) R³), I = L t³/12; plane strain uses E/(1 − ν²) (THEORY §1.1).
double elastic_stiffness(const RingSection& s, double youngs_modulus, double poisson_ratio,
                         SectionState state);

// Load at first yield of the outer fibre under the loads, P_y = π σ0 L t² / (6R).
double first_yield_load(const RingSection& s, double yield_stress);

// Inertia factor of the DeRuntz–Hodge mechanism, J(φ) = (2/π) m_r R² K(φ) (THEORY §1.3):
// K(φ) = (2 + cos²φ)(π/2 − φ) − 4 cos φ + 2 sin φ cos φ + φ cos²φ, and its derivative.
double dh_inertia_factor(double phi);
double dh_inertia_factor_derivative(double phi);
// K″(φ) = 4 cos φ (1 − 2 sin φ) − π cos 2φ (K′ = 4 sin φ (1 − sin φ) − π sin φ cos φ, the
// derivative above with its terms collected): the inertial Level 3 chain's analytic Jacobian.
double dh_inertia_factor_second_derivative(double phi);

// Mass of one ring, ρ π d t L.
double ring_mass(const RingSection& s, double density);

}  // namespace ringcrush::hinge
