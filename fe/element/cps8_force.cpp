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
//
// Performance (issue 4, README "Performance"): this kernel is most of an explicit step, and
// it is arranged for the CPU without changing one operation of the point-by-point form
// (deformation_gradient(), add_bulk_viscous_force(), cauchy_from_pk2(): every sum in the same
// order, so every bit of the result is the same — tests/fe/explicit_speed_test.cpp):
//  - the deformation gradients of all 9 (+4 reduced) points are formed together, node by
//    node: the 4 × 13 running sums are independent (the CPU overlaps them instead of waiting
//    on one chain of 8 additions per entry), the two rows of a column one 2-wide operation;
//  - a nodal force is one 2-wide operation per node, and the stress and bulk-viscous forces
//    of a point share the pass over its ∇N;
//  - the divisions — bulk-viscous pressure, push-forward of the trial stress (with a square
//    root) — are done for all points in passes of their own, where the points overlap;
//  - the material's elastic branch and the push-forward are inline (j2_plane_stress.hpp,
//    kinematics.hpp).
#include "fe/element/cps8_element.hpp"

#include <algorithm>
#include <cmath>

#include "fe/kinematics.hpp"

namespace ringcrush::fe {

namespace {

constexpr int kMaxPoints = 13;  // 9 stress points + 4 reduced (Barlow) points

// f = I + Σ_a u_a ⊗ ∇N_a at n points at once, by columns: f e_j = e_j + Σ_a u_a ∂N_a/∂X_j.
// Each entry's sum runs over a = 0..7 in order, exactly as deformation_gradient()
// (kinematics.hpp) forms it; the two rows of a column are one 2-wide vector operation.
struct PointGradients {
  Vec2 col0[kMaxPoints], col1[kMaxPoints];
  Mat2 at(int i) const {
    Mat2 f;
    f << col0[i], col1[i];
    return f;
  }
};

inline void deformation_gradients(const ShapeGrad* const* d, int n, const double* u, PointGradients& g) {
  for (int i = 0; i < n; ++i) {
    g.col0[i] = Vec2(1.0, 0.0);
    g.col1[i] = Vec2(0.0, 1.0);
  }
  for (int a = 0; a < 8; ++a) {
    const Vec2 ua(u[2 * a], u[2 * a + 1]);
    for (int i = 0; i < n; ++i) {
      g.col0[i] += ua * (*d[i])(a, 0);
      g.col1[i] += ua * (*d[i])(a, 1);
    }
  }
}

// r_a += c · A ∇N_a for every node (A: a 2×2 stress-like matrix in the current frame); the
// node's two components are one 2-wide operation, each c A_i0 ∂N_a/∂X + c A_i1 ∂N_a/∂Y.
inline void add_nodal_force(const ShapeGrad& d, const Mat2& a, double c, double* force) {
  const Vec2 a0 = c * a.col(0), a1 = c * a.col(1);
  for (int k = 0; k < 8; ++k) Eigen::Map<Vec2>(force + 2 * k) += a0 * d(k, 0) + a1 * d(k, 1);
}

// The same for two matrices on one ∇N (stress force and bulk-viscous force of a point).
inline void add_nodal_forces(const ShapeGrad& d, const Mat2& a, double c, double* force, const Mat2& b, double cb,
                             double* other) {
  const Vec2 a0 = c * a.col(0), a1 = c * a.col(1), b0 = cb * b.col(0), b1 = cb * b.col(1);
  for (int k = 0; k < 8; ++k) {
    const double nx = d(k, 0), ny = d(k, 1);
    Eigen::Map<Vec2>(force + 2 * k) += a0 * nx + a1 * ny;
    Eigen::Map<Vec2>(other + 2 * k) += b0 * nx + b1 * ny;
  }
}

// Trial state of one point from the material update (as cps8_evaluate: Cauchy stress at
// the end of the increment, history variables, out-of-plane stretch), in two halves: the
// history variables now, and — once all points are done — the push-forward, which waits on a
// square root and a division (finish_trial). Apart, the push-forwards of the 9 points are
// independent of each other and of the force sums and overlap in the CPU; the arithmetic is
// that of one store: `stress` holds S and `thickness_stretch` 1 + 2 ΔE33 in between.
inline void start_trial(const J2Update& up, const PointState& c, double w, PointState& t) {
  t.stress = up.stress;
  t.thickness_stretch = 1.0 + 2.0 * up.strain33_increment;
  t.plastic_strain = c.plastic_strain + up.plastic_increment;
  t.peeq = up.peeq;
  t.plastic_work = c.plastic_work + w * up.dissipation;
}
inline void finish_trial(const Mat2& f, const PointState& c, PointState& t) {
  const double l3 = std::sqrt(std::max(1e-12, t.thickness_stretch));
  t.stress = cauchy_from_pk2(f, t.stress, l3);
  t.thickness_stretch = c.thickness_stretch * l3;
}

}  // namespace

void cps8_force(const Cps8Geometry& geo, const double* u, const PointState* committed, PointState* trial,
                const J2PlaneStress& material, Cps8Output& out, const BulkViscousLoad* viscous) {
  out.force.setZero();
  out.elastic_energy = 0;
  out.plastic_work = 0;
  const bool selective = geo.rule == Integration::Selective;
  const int np = geo.points, nr = selective ? 4 : 0;

  // f at the stress points [0, np) and, selective, at the 2×2 points [np, np + 4).
  const ShapeGrad* d[kMaxPoints];
  for (int i = 0; i < np; ++i) d[i] = &geo.dndx[i];
  for (int r = 0; r < nr; ++r) d[np + r] = &geo.dndx_reduced[r];
  PointGradients g;
  deformation_gradients(d, np + nr, u, g);

  // Selective: tr ΔE at the 2×2 points.
  std::array<double, 4> tr_r{}, q_r{};
  for (int r = 0; r < nr; ++r) {
    const Eigen::Vector3d e = green_lagrange(g.at(np + r));
    tr_r[r] = e(0) + e(1);
  }

  // ΔE at the stress points and, with bulk viscosity, the pressure q_i = coefficient tr ΔE_i
  // / dt of each (bulk_viscosity.hpp: the point's own, not the Barlow-averaged, rate) — all
  // divisions in one pass, where they overlap instead of stalling the force loop.
  std::array<Eigen::Vector3d, 9> strain;
  std::array<double, 9> q{};
  for (int i = 0; i < np; ++i) strain[i] = green_lagrange(g.at(i));
  if (viscous)
    for (int i = 0; i < np; ++i) q[i] = viscous->coefficient * (strain[i](0) + strain[i](1)) / viscous->dt;

  double* const force = out.force.data();
  double* const viscous_force = viscous ? viscous->force->data() : nullptr;
  for (int i = 0; i < np; ++i) {
    const ShapeGrad& di = geo.dndx[i];
    const Mat2 f = g.at(i);
    Eigen::Vector3d e = strain[i];
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
    if (viscous) add_nodal_forces(di, f * s, w, force, f, q[i] * geo.weight[i], viscous_force);
    else add_nodal_force(di, f * s, w, force);
    out.elastic_energy += w * up.elastic_energy;
    start_trial(up, committed[i], w, trial[i]);
    out.plastic_work += trial[i].plastic_work;
  }
  for (int i = 0; i < np; ++i) finish_trial(g.at(i), committed[i], trial[i]);
  for (int r = 0; r < nr; ++r) add_nodal_force(geo.dndx_reduced[r], g.at(np + r), q_r[r], force);
}

}  // namespace ringcrush::fe
