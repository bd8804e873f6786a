// Plain inputs and outputs of the one-dimensional ring-chain models (THEORY §4.2–4.4):
// Level 0 (ring springs with an elastic branch, a DeRuntz–Hodge/Redwood backbone and lock-up,
// lumped masses) and Level 1 (DeRuntz–Hodge kinematics with distributed inertia J(φ) per ring,
// rigid–plastic rings as a complementarity). No TOML, no compare/: compare/ builds these.
#pragma once

#include <string>
#include <vector>

#include "hybrid_system.hpp"

namespace ringcrush::hinge {

// One ring's force–crush law along the chain axis. Hardening follows Redwood (THEORY §1.4):
// P_b(δ) = P0/cos φ · (1 + kφ), φ = asin(δ/d), k = E′/(3σ0α); k = 0 is DeRuntz–Hodge.
struct RingLaw {
  double outer_diameter_m = 0.0;
  double wall_thickness_m = 0.0;
  double plastic_moment_nm = 0.0;      // M0 of the whole width
  double hardening_modulus_pa = 0.0;   // E′; 0: rigid–perfectly-plastic (DeRuntz–Hodge)
  double yield_stress_pa = 0.0;        // σ0
  double redwood_alpha = 2.0;          // side-hinge length in wall thicknesses
  double elastic_stiffness_n_m = 0.0;  // k_el of the series elastic branch (Level 0)
  double lock_stiffness_n_m = 0.0;     // inner-wall contact stiffness past δ_L (Level 0)
  double mass_kg = 0.0;                // m_r

  double mean_diameter() const { return outer_diameter_m - wall_thickness_m; }
  double lock_deflection() const { return mean_diameter() - wall_thickness_m; }  // δ_L = d − t
  double lock_angle() const;                                                        // φ_L
  double collapse_load() const;                                                     // P0 = 8M0/d
  double hardening_k() const;                                                       // E′/(3σ0α)
  // Backbone in terms of the plastic crush δp, its first and second derivatives; continued
  // linearly past δ_L (where the lock-up contact carries the load).
  double backbone(double dp) const;
  double backbone_slope(double dp) const;
  double backbone_curvature(double dp) const;
  // Plastic work ∫P_b dδp = 8M0(φ + kφ²/2) (closed form, ring_laws).
  double plastic_energy(double dp) const;
  // Mechanism forms: generalised resisting force 8M0 h(φ) and its work.
  double generalized_force(double phi) const;
  double plastic_energy_at_angle(double phi) const;
  // Mean backbone force to lock, W(δ_L)/δ_L (the r-p-p-l plateau P_c of THEORY §3.2).
  double mean_force_to_lock() const;
  // Distributed inertia J(φ) = (2/π) m_r R² K(φ) and J′(φ) (THEORY §1.3).
  double inertia(double phi) const;
  double inertia_derivative(double phi) const;
  void validate() const;  // throws std::invalid_argument naming the bad value

 private:
  double backbone_raw(double dp) const;
  double backbone_slope_raw(double dp) const;
  double backbone_curvature_raw(double dp) const;
};

enum class ChainJoint { Welded, Free, Plates };
enum class ChainFarEnd { Fixed, Free };

struct ChainInput {
  int rings = 6;
  RingLaw ring;
  ChainJoint joint = ChainJoint::Welded;
  double plate_mass_kg = 0.0;           // plates only
  ChainFarEnd far_end = ChainFarEnd::Fixed;
  double impactor_mass_kg = 0.0;        // full mass
  double impactor_velocity_m_s = 0.0;   // toward the chain
  // Level 1 only: an elastic series spring between the impactor and ring 1 (no tension);
  // 0: rigid contact (the first contact is then a plastic impact).
  double impactor_spring_n_m = 0.0;
  void validate() const;
};

struct ChainEvent {
  double time_s;
  std::string kind;  // "hinge_formed", "ring_unloaded", "contact_opened", "ring_locked", ...
  int ring = -1;     // 0-based; −1 for the impactor / chain
  std::string detail;
};

// Histories sampled at every accepted step and at both sides of every event.
struct ChainHistory {
  std::vector<double> time_s, impactor_displacement_m, impactor_velocity_m_s, impactor_force_n;
  std::vector<std::vector<double>> ring_crush_m;  // [ring][sample]
  std::vector<double> kinetic_j, elastic_j, plastic_j, impact_loss_j;
  std::vector<std::vector<double>> ring_plastic_j;  // [ring][sample]
};

struct ChainResult {
  ChainHistory history;
  std::vector<ChainEvent> events;
  HybridOutcome outcome;
  double initial_kinetic_energy_j = 0.0;  // ½MV²
  double arrest_time_s = -1.0;            // impactor at rest (fixed end) or at the common
                                          // velocity (free end); −1: not reached
  std::vector<double> final_crush_m;            // δ_i at the end (Level 0: with the
                                                // elastic part of a still-vibrating chain)
  std::vector<double> final_permanent_crush_m;  // Level 0: plastic crush δp_i (after
                                                // springback); Level 1: δ_i
  // max over the history of |KE + elastic + plastic + impact loss − ½MV²| / ½MV²
  double energy_balance_error() const;
};

// Level 0 (THEORY §4.4 "Level 0 equations"): rate-independent elastic–plastic ring springs,
// event-driven (yield, unloading, contact opening/closing, lock-up).
// record_history = false keeps only the first and the last sample (sweeps, benchmarks).
ChainResult simulate_level0(const ChainInput& input, const HybridOptions& options,
                            bool record_history = true);

// Level 1 (THEORY §4.4 "Level 1"): rigid–plastic DeRuntz–Hodge/Redwood rings with J(φ),
// plates (or joints treated as flat contacts) between rings, rigid rings by complementarity.
ChainResult simulate_level1(const ChainInput& input, const HybridOptions& options,
                            bool record_history = true);

}  // namespace ringcrush::hinge
