// Owens & Symonds (1955) type analysis of a free rigid–perfectly-plastic ring under a
// concentrated dynamic force F at A (THEORY §2), small deflections.
//
// Rigid-body phase: a = F/m_r; the d'Alembert load is uniform, q = F/(2πR). Onset: the limit
// load of that static problem. The admissible mechanism {A, ±θ_E, B} with M_A = M_B = −M0,
// M_E = +M0 and H = F/(2π) from M(π) gives M(θ) = −M0 + (FR/2)(1 − θ/π) sin θ; the hinge E is
// where the shear vanishes (Q = dM/ds = 0): tan θ_E = π − θ_E, θ_E = 1.1113 rad (63.7°), and
// F_c = 4M0 / (R (1 − θ_E/π) sin θ_E) = 6.906 M0/R, with |M| ≤ M0 everywhere (statically
// admissible, so F_c is the exact limit load).
//
// Mechanism phase (F > F_c): generalised coordinates Y (translation of A) and α (rotation of
// arc A–E about A; arc E–B follows with ω₂ = −α̇(1 − cos θ_E)/(1 + cos θ_E), B on the axis);
// 2×2 mass matrix from the rigid arcs' distributed mass, hinge work 2M0(|ω₁| + |ω₂ − ω₁| +
// |ω₂|) per unit α. The hinge angle θ_E is fixed by the shear-free condition Q(θ_E) = 0 of
// the *dynamic* moment distribution (inertia loads of the accelerating arcs); it depends on F,
// so θ_E(F) is reported. A rectangular pulse F_p for τ is integrated (IDA or Odeint) with the
// hinge at θ_E(F_p) until the mechanism stops (α̇ = 0).
#pragma once

#include <vector>

#include "hybrid_system.hpp"

namespace ringcrush::hinge {

struct FreeRing {
  double mean_radius_m;
  double plastic_moment_nm;
  double mass_kg;
};

struct OnsetThreshold {
  double hinge_angle_rad;  // θ_E from tan θ = π − θ
  double force_n;          // F_c
  double max_moment_ratio; // max |M|/M0 over the ring at F_c (≤ 1: admissible)
};
OnsetThreshold owens_symonds_onset(const FreeRing& ring);

// Moment M(θ)/M0 along the half ring at the onset (rigid-body phase, F = F_c).
double onset_moment_ratio(const FreeRing& ring, double theta);

// Collapse force of the mechanism {A, ±θ, B} from the rigid-body phase by virtual power
// (d'Alembert loads, F_c(θ) = D m_r/|M_Yα|): the upper bound minimised by θ_E.
double mechanism_collapse_force(const FreeRing& ring, double theta);

struct MechanismState {
  double hinge_angle_rad;    // θ_E(F) from the dynamic shear-free condition
  double translation_acceleration;  // Ÿ (A, along F)
  double rotation_acceleration;     // α̈ of arc A–E
};
// Initial accelerations and hinge angle under a force F > F_c (from rest).
MechanismState owens_symonds_mechanism(const FreeRing& ring, double force_n);

struct PulseResponse {
  double hinge_angle_rad = 0.0;
  double final_rotation_rad = 0.0;       // α at the end of deformation
  double deformation_end_s = 0.0;        // α̇ returns to zero
  double external_work_j = 0.0, kinetic_j = 0.0, plastic_j = 0.0;
  double final_velocity_m_s = 0.0;       // rigid-body velocity after deformation
  std::vector<double> time_s, rotation_rad, rotation_rate;
  HybridOutcome outcome;
  double energy_balance_error() const;   // |W_ext − KE − D| / W_ext
};
PulseResponse owens_symonds_pulse(const FreeRing& ring, double force_n, double duration_s,
                                  const HybridOptions& options);

}  // namespace ringcrush::hinge
