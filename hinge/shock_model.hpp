// The Reid–Bell–Barr structural plastic shock model of a ring chain (r-p-p-l: rigid,
// perfectly plastic, locking; THEORY §3.2): closed form (fixed far end), the integrated ODE
// (X, v, v_f) on IDA or Odeint with arrest / front-at-the-far-end events (fixed and free
// far end), and the discrete sequential counterpart (one ring at a time, plastic impacts).
#pragma once

#include <vector>

#include "chain_1d.hpp"
#include "hybrid_system.hpp"

namespace ringcrush::hinge {

struct ShockInput {
  double impactor_mass_kg = 0.0;       // M
  double impactor_velocity_m_s = 0.0;  // V
  double plateau_force_n = 0.0;        // P_c
  double locking_strain = 0.0;         // ε_L = δ_L / pitch
  double mass_per_length_kg_m = 0.0;   // μ = m_r / pitch
  double pitch_m = 0.0;                // original chain length per ring (D)
  int rings = 6;
  ChainFarEnd far_end = ChainFarEnd::Fixed;
  void validate() const;
  // From a ring law: P_c = mean backbone force to lock, ε_L = δ_L/D, μ = m_r/D.
  static ShockInput from_ring(const RingLaw& ring, int rings, double impactor_mass_kg,
                              double impactor_velocity_m_s, ChainFarEnd far_end);
};

// Fixed far end, closed form [D]: X_f = (M/μ)(√(1 + μV²/(ε_L P_c)) − 1), t_f = MV/P_c,
// initial load P_c + μV²/ε_L, v* = √(P_c ε_L/μ), v²(X) from dw/dX = −(2ε_L P_c + 2μw)/(M + μX).
struct ShockClosedForm {
  double arrest_position_m;      // X_f (may exceed the chain: see reaches_far_end)
  double locked_rings;           // n = X_f / pitch
  double arrest_time_s;          // t_f
  double initial_load_n;         // P_c + μV²/ε_L
  double characteristic_velocity_m_s;  // v*
  bool reaches_far_end;          // X_f > N · pitch: the front hits the target first
  double velocity_at(double front_position_m) const;  // v(X)
  // kept for velocity_at
  double M, V, Pc, eps, mu;
};
ShockClosedForm shock_closed_form(const ShockInput& in);

struct ShockRun {
  std::vector<double> time_s, front_position_m, velocity_m_s, far_velocity_m_s,
      impactor_displacement_m, impactor_force_n, kinetic_j, plastic_j, shock_loss_j;
  std::vector<double> final_crush_m;   // per ring: δ_L × compacted fraction
  double arrest_time_s = -1.0;         // v = v_f
  bool front_reached_far_end = false;
  double far_end_loss_j = 0.0;         // fixed end: kinetic energy lost when the locked
                                       // column meets the target
  HybridOutcome outcome;
  double initial_kinetic_energy_j = 0.0;
  double energy_balance_error() const;
};
ShockRun integrate_shock(const ShockInput& in, const HybridOptions& options);

// Discrete sequential r-p-p-l [D]: the moving mass crushes ring k at P_c until δ_L, then
// meets the next contact mass m_r in a perfectly plastic impact. THEORY §5 #22 starts with
// the impactor plus the top half of ring 1 (M + m_r/2) moving at V. Fixed far end.
struct DiscreteShock {
  std::vector<double> crush_m;
  std::vector<double> time_locked_s;   // per ring, −1 if not locked
  double arrest_time_s = 0.0;
  double plastic_j = 0.0, impact_loss_j = 0.0, final_kinetic_j = 0.0;
};
DiscreteShock discrete_shock(int rings, double plateau_force_n, double lock_deflection_m,
                             double ring_mass_kg, double initial_moving_mass_kg,
                             double initial_velocity_m_s);

}  // namespace ringcrush::hinge
