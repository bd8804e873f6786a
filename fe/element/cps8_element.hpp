// The CPS8 element as a pure local function (STYLE.md practice 1): reference geometry,
// element displacements, committed point states and the material in; internal force,
// consistent tangent, energies and trial point states out. No global numbering here.
//
// Incremental (updated-Lagrangian) form, plane stress, thickness = ring width: the reference
// is the configuration x_n at the start of the increment, the unknown is the displacement
// increment Δu (kinematics.hpp explains why this is an objective finite-rotation update
// equivalent to thesis §3.6.1.2). Integration rules of thesis §3.6.1.4:
//  - Full: 3×3 Gauss;  Reduced: 2×2 Gauss;
//  - Selective: 3×3 Gauss, with the in-plane volumetric strain tr E at each point replaced by
//    the bilinear interpolation M^R of its values at the 2×2 (Barlow) points — the
//    total-Lagrangian form of the thesis's ΔD = sym(∂Δu/∂x) + ½ I (tr(·)^R − tr(·)^I):
//      ΔĒ = ΔE + ½ (Σ_r M_r tr ΔE_r − tr ΔE) [1, 1, 0]ᵀ.
//    Its variation B̄ and second variation (geometric stiffness) follow exactly, so the
//    tangent stays consistent and symmetric.
#pragma once

#include <Eigen/Core>
#include <array>

#include "fe/element/cps8_shape.hpp"
#include "fe/fe_input.hpp"
#include "fe/material/j2_plane_stress.hpp"

namespace ringcrush::fe {

using ElementCoords = Eigen::Matrix<double, 8, 2>;  // reference coordinates of the 8 nodes
using ElementVector = Eigen::Matrix<double, 16, 1>;
using ElementMatrix = Eigen::Matrix<double, 16, 16>;

// Everything about an element that does not change during an increment (precomputed once
// per increment from the configuration x_n).
struct Cps8Geometry {
  Integration rule = Integration::Full;
  int points = 0;                     // stress points: 9 (Full, Selective) or 4 (Reduced)
  std::array<ShapeGrad, 9> dndx{};    // ∂N/∂X at the stress points
  std::array<double, 9> weight{};     // Gauss weight · det J · initial thickness
  std::array<ShapeVec, 9> n{};        // N at the stress points (output extrapolation)
  std::array<ShapeGrad, 4> dndx_reduced{};  // Selective: ∂N/∂X at the 2×2 points
  Eigen::Matrix<double, 9, 4> barlow = Eigen::Matrix<double, 9, 4>::Zero();  // M^R_r(point)
};

// Throws std::invalid_argument if the element is inverted or degenerate (det J₀ ≤ 0).
Cps8Geometry cps8_geometry(const ElementCoords& x, Integration rule, double thickness);

struct Cps8Output {
  ElementVector force;    // internal force (residual contribution)
  ElementMatrix tangent;  // ∂force/∂Δu (material + geometric), if requested
  double elastic_energy = 0;  // J
  double plastic_work = 0;    // J, accumulated since the start of the run
};

// du: 16 displacement increments since x_n [Δux1, Δuy1, ...]; committed/trial: `geo.points`
// states each. The trial stress is the Cauchy stress at the end of the increment,
// σ = f S fᵀ / (det f · λ3), f = ∂x/∂x_n, so that committing it starts the next increment.
void cps8_evaluate(const Cps8Geometry& geo, const double* du, const PointState* committed,
                   PointState* trial, const J2PlaneStress& material, bool want_tangent,
                   Cps8Output& out);

// Bulk viscosity riding along the force-only path (explicit driver; bulk_viscosity.hpp):
// q_i = coefficient · tr ΔE_i / dt at every stress point, from the deformation gradient the
// element has just formed, its nodal force Σ_i q_i w_i f_i ∇N_a added to *force — the same
// arithmetic as add_bulk_viscous_force(), without forming f and ΔE a second time.
struct BulkViscousLoad {
  double coefficient = 0;  // b1 ρ c_d L_e (Pa·s)
  double dt = 0;           // the step of the increment (s, > 0)
  ElementVector* force = nullptr;
};

// Force-only path of cps8_evaluate (want_tangent = false dispatches here; cps8_force.cpp):
// the same force, energies and trial states to round-off, without B or the tangent.
// out.tangent is left untouched. viscous (optional): the bulk-viscous force of the increment.
void cps8_force(const Cps8Geometry& geo, const double* du, const PointState* committed, PointState* trial,
                const J2PlaneStress& material, Cps8Output& out, const BulkViscousLoad* viscous = nullptr);

// The stress a point contributes through its own ∂N/∂X (both element paths): S itself, or
// for the selective rule S − p I, p = ½(S11 + S22), with w p M_r added to the weight q_r of
// reduced point r — S : δĒ = (S − p I) : δE + p Σ_r M_r δ tr ΔE_r (thesis §3.6.1.4).
inline Eigen::Matrix2d point_stress(const Eigen::Vector3d& stress, const Cps8Geometry& geo, int point, double w,
                         std::array<double, 4>& q_r) {
  Eigen::Matrix2d s;
  s << stress(0), stress(2), stress(2), stress(1);
  if (geo.rule == Integration::Selective) {
    const double p = 0.5 * (stress(0) + stress(1));
    s(0, 0) -= p;
    s(1, 1) -= p;
    for (int r = 0; r < 4; ++r) q_r[r] += w * p * geo.barlow(point, r);
  }
  return s;
}

// Point-averaged von Mises (Cauchy) stress and PEEQ of committed states (field output).
struct Cps8Fields {
  double mises = 0, peeq = 0;
  double sxx = 0, syy = 0, sxy = 0;  // Cauchy stress, average of the points (global axes)
};
Cps8Fields cps8_fields(const PointState* states, int points);

}  // namespace ringcrush::fe
