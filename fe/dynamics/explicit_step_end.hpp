// The end of an explicit central-difference step, dof by dof (explicit_driver.hpp): once the
// force f_{n+1} of a dof is final,
//
//   a = −M⁻¹ f,   v_{n+1} = v_{n+½} + ½Δt a,
//
// the finiteness test of f (f − f is 0 for a finite f, NaN otherwise), and the dof's terms of
// the step's energy sums (energy_balance.hpp):
//
//   Σ m v²  (KE = ½ Σ m v²),   Σ (f_n + f_{n+1}) Δu  (W_f),   Σ (q_n + q_{n+1}) Δu  (W_v).
//
// The driver hands it to DynamicSystem::evaluate_explicit(), so that a system may run it inside
// its own final force sum on each dof as soon as that dof's force is final: the force, the
// velocity, the acceleration and the old forces are then read once a step instead of in five
// passes (the serial tail of the two-thread step, README "FE dynamics", session 13). a and v
// get per dof the operations of the unfused pass, whatever the order of the dofs, so the
// trajectory is bitwise the same; the energy sums are formed in another order than Eigen's dot
// products (and, per range, with four partial sums each), so they differ from those in round-off
// only (≤ 1e-12 of the reference energy; tests/fe/explicit_step_end_test.cpp).
#pragma once

#include <Eigen/Core>

namespace ringcrush::fe {

struct ExplicitStepEnd {
  // Per dof (all of the system's dofs): 1/M (0 on fixed dofs), M, the half-step velocity on
  // entry and v_{n+1} on exit, the acceleration (written), the last step's force and
  // bulk-viscous force, the step's displacement increment Δu.
  const double* inv_mass = nullptr;
  const double* mass = nullptr;
  double* velocity = nullptr;
  double* acceleration = nullptr;
  const double* old_force = nullptr;
  // The last step's bulk-viscous force (null: none) and zeros, which stand for the q_n or
  // q_{n+1} the system did not form when the other one is there (the first step has no q_n).
  const double* old_viscous = nullptr;
  const double* zeros = nullptr;
  const double* increment = nullptr;
  double half_step = 0;  // ½Δt

  // The sums over the dofs done so far.
  double not_finite = 0;    // Σ (f − f): 0 for finite forces, NaN otherwise
  double mass_v2 = 0;       // Σ m v²
  double force_du = 0;      // Σ (f_n + f_{n+1}) Δu
  double viscous_du = 0;    // Σ (q_n + q_{n+1}) Δu

  // The dofs [b, e) with their final force f[b..e) and bulk-viscous force q[b..e) (q null: the
  // system formed none). The dofs may come in any order and in any number of ranges, each once.
  void range(Eigen::Index b, Eigen::Index e, const double* f, const double* q) {
    if (old_viscous || q) {
      run<true>(b, e, f, q ? q : zeros, old_viscous ? old_viscous : zeros);
    } else {
      run<false>(b, e, f, q, nullptr);
    }
  }

 private:
  // Four partial sums per quantity (the loop is otherwise bound by the latency of one chain
  // of additions per sum); a and v are per dof as the plain pass forms them.
  template <bool Viscous>
  void run(Eigen::Index b, Eigen::Index e, const double* f, const double* q, const double* q_old) {
    double nf[4] = {0, 0, 0, 0}, kin[4] = {0, 0, 0, 0}, work[4] = {0, 0, 0, 0}, visc[4] = {0, 0, 0, 0};
    const double* inv_m = inv_mass;
    const double* m = mass;
    const double* f_old = old_force;
    const double* du = increment;
    double* v = velocity;
    double* a = acceleration;
    const double h = half_step;
    auto dof = [&](Eigen::Index i, int k) {
      nf[k] += f[i] - f[i];
      a[i] = -(inv_m[i] * f[i]);
      v[i] += h * a[i];
      kin[k] += v[i] * v[i] * m[i];
      work[k] += (f_old[i] + f[i]) * du[i];
      if constexpr (Viscous) visc[k] += (q_old[i] + q[i]) * du[i];
    };
    Eigen::Index i = b;
    for (; i + 4 <= e; i += 4) {
      dof(i, 0);
      dof(i + 1, 1);
      dof(i + 2, 2);
      dof(i + 3, 3);
    }
    for (int k = 0; i < e; ++i, ++k) dof(i, k);
    not_finite += (nf[0] + nf[1]) + (nf[2] + nf[3]);
    mass_v2 += (kin[0] + kin[1]) + (kin[2] + kin[3]);
    force_du += (work[0] + work[1]) + (work[2] + work[3]);
    if constexpr (Viscous) viscous_du += (visc[0] + visc[1]) + (visc[2] + visc[3]);
  }
};

}  // namespace ringcrush::fe
