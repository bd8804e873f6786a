// Force-only CPS8 evaluation (the explicit driver's path, thesis §3.6.1 element, §3.5
// explicit integration): the same internal force and trial states as cps8_evaluate() with
// the tangent, computed without the strain-displacement matrix B.
//
// With P = f S (first Piola–Kirchhoff stress of the increment), S : δE = P : δF, so the
// force on node a is   r_a = Σ_points w P ∇N_a   — 2×2 by 2 products per node instead of
// Bᵀ S with a 3×16 B (thesis §3.6.1.2 kinematics, kinematics.hpp).
//
// Selective rule (thesis §3.6.1.4, cps8_element.hpp): ΔĒ = ΔE + ½(Σ_r M_r tr ΔE_r − tr ΔE)
// [1, 1, 0]ᵀ, so S : δĒ = (S − p I) : δE + p Σ_r M_r δ tr ΔE_r with p = ½(S11 + S22), and
// δ tr ΔE_r = f_r : δF_r. The volumetric part is therefore gathered once per reduced point:
//   r_a = Σ_points w (f (S − p I)) ∇N_a + Σ_r q_r f_r ∇N^r_a,   q_r = Σ_points w p M_r.
#include "fe/element/cps8_element.hpp"

#include <algorithm>
#include <cmath>

#include "fe/kinematics.hpp"

namespace ringcrush::fe {

namespace {

// r_a += c · A ∇N_a for every node (A: a 2×2 stress-like matrix in the current frame).
inline void add_nodal_force(const ShapeGrad& d, const Mat2& a, double c, ElementVector& force) {
  const double a00 = c * a(0, 0), a01 = c * a(0, 1), a10 = c * a(1, 0), a11 = c * a(1, 1);
  for (int k = 0; k < 8; ++k) {
    const double nx = d(k, 0), ny = d(k, 1);
    force(2 * k) += a00 * nx + a01 * ny;
    force(2 * k + 1) += a10 * nx + a11 * ny;
  }
}

// Trial state of one point from the material update (as cps8_evaluate: Cauchy stress at
// the end of the increment, history variables, out-of-plane stretch).
inline void store_trial(const Mat2& f, const J2Update& up, const PointState& c, double w, PointState& t) {
  const double l3 = std::sqrt(std::max(1e-12, 1.0 + 2.0 * up.strain33_increment));
  t.stress = cauchy_from_pk2(f, up.stress, l3);
  t.plastic_strain = c.plastic_strain + up.plastic_increment;
  t.peeq = up.peeq;
  t.plastic_work = c.plastic_work + w * up.dissipation;
  t.thickness_stretch = c.thickness_stretch * l3;
}

}  // namespace

void cps8_force(const Cps8Geometry& geo, const double* u, const PointState* committed, PointState* trial,
                const J2PlaneStress& material, Cps8Output& out, const BulkViscousLoad* viscous) {
  out.force.setZero();
  out.elastic_energy = 0;
  out.plastic_work = 0;
  const bool selective = geo.rule == Integration::Selective;

  // Selective: f and tr ΔE at the 2×2 points.
  std::array<Mat2, 4> f_r;
  std::array<double, 4> tr_r{}, q_r{};
  if (selective)
    for (int r = 0; r < 4; ++r) {
      f_r[r] = deformation_gradient(geo.dndx_reduced[r], u);
      const Eigen::Vector3d e = green_lagrange(f_r[r]);
      tr_r[r] = e(0) + e(1);
    }

  for (int i = 0; i < geo.points; ++i) {
    const ShapeGrad& d = geo.dndx[i];
    const Mat2 f = deformation_gradient(d, u);
    Eigen::Vector3d e = green_lagrange(f);
    if (viscous) {
      // bulk_viscosity.hpp: the point's own (not the Barlow-averaged) volumetric rate.
      const double q = viscous->coefficient * (e(0) + e(1)) / viscous->dt;
      add_nodal_force(d, f, q * geo.weight[i], *viscous->force);
    }
    if (selective) {
      double tr_bar = 0;
      for (int r = 0; r < 4; ++r) tr_bar += geo.barlow(i, r) * tr_r[r];
      const double corr = 0.5 * (tr_bar - e(0) - e(1));
      e(0) += corr;
      e(1) += corr;
    }
    const J2Update up = material.update_stress(e, committed[i]);
    const double w = geo.weight[i] * committed[i].thickness_stretch;
    const Mat2 s = point_stress(up.stress, geo, i, w, q_r);
    add_nodal_force(d, f * s, w, out.force);
    out.elastic_energy += w * up.elastic_energy;
    store_trial(f, up, committed[i], w, trial[i]);
    out.plastic_work += trial[i].plastic_work;
  }
  if (selective)
    for (int r = 0; r < 4; ++r) add_nodal_force(geo.dndx_reduced[r], f_r[r], q_r[r], out.force);
}

}  // namespace ringcrush::fe
