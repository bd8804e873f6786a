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

#include "fe/dof_pair.hpp"

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
  // Two dofs at a time in the lanes of a 16-byte vector (dof_pair.hpp: per lane the scalar
  // IEEE operations), two such pairs per turn, so that each sum has four partial sums (one
  // chain of additions per sum would bound the loop by its latency); a and v are per dof those
  // of the plain pass. A range may start at an odd dof: a pair need not be one node's.
  template <bool Viscous>
  void run(Eigen::Index b, Eigen::Index e, const double* f, const double* q, const double* q_old) {
    // Local copies: the stores below may alias the members as far as the compiler knows.
    const double *inv_m = inv_mass, *m = mass, *f_old = old_force, *inc = increment;
    double *acc = acceleration, *vel = velocity;
    const DofPair h = {half_step, half_step};
    DofPair nf[2] = {}, kin[2] = {}, work[2] = {}, visc[2] = {};
    auto pair = [&](Eigen::Index i, int k) {
      const DofPair fi = load_dof_pair(f + i);
      nf[k] += fi - fi;
      const DofPair a = -(load_dof_pair(inv_m + i) * fi);
      store_dof_pair(acc + i, a);
      const DofPair v = load_dof_pair(vel + i) + h * a;
      store_dof_pair(vel + i, v);
      kin[k] += v * v * load_dof_pair(m + i);
      const DofPair du = load_dof_pair(inc + i);
      work[k] += (load_dof_pair(f_old + i) + fi) * du;
      if constexpr (Viscous) visc[k] += (load_dof_pair(q_old + i) + load_dof_pair(q + i)) * du;
    };
    Eigen::Index i = b;
    for (; i + 4 <= e; i += 4) {
      pair(i, 0);
      pair(i + 2, 1);
    }
    if (i + 2 <= e) {
      pair(i, 0);
      i += 2;
    }
    double tail_nf = 0, tail_kin = 0, tail_work = 0, tail_visc = 0;
    if (i < e) {  // the last dof of an odd range
      tail_nf = f[i] - f[i];
      acceleration[i] = -(inv_mass[i] * f[i]);
      velocity[i] += half_step * acceleration[i];
      tail_kin = velocity[i] * velocity[i] * mass[i];
      tail_work = (old_force[i] + f[i]) * increment[i];
      if constexpr (Viscous) tail_visc = (q_old[i] + q[i]) * increment[i];
    }
    const DofPair snf = nf[0] + nf[1], skin = kin[0] + kin[1], swork = work[0] + work[1];
    not_finite += (snf[0] + snf[1]) + tail_nf;
    mass_v2 += (skin[0] + skin[1]) + tail_kin;
    force_du += (swork[0] + swork[1]) + tail_work;
    if constexpr (Viscous) {
      const DofPair svisc = visc[0] + visc[1];
      viscous_du += (svisc[0] + svisc[1]) + tail_visc;
    }
  }
};

}  // namespace ringcrush::fe
