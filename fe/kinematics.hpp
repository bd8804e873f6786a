// Kinematics of the CPS8 ring model in one named place (STYLE.md practice 4).
//
// Finite rotations, small elastic strain (thesis §3.6.1.2, DESIGN.md "Kinematics"). Each
// increment is described on the configuration x_n at its start (updated Lagrangian): the
// relative deformation gradient f = ∂x_{n+1}/∂x_n gives the objective Green–Lagrange strain
// increment ΔE = ½(fᵀf − I); the material returns S = σ_n + ΔS (2nd Piola–Kirchhoff stress
// relative to x_n, equal to the Cauchy stress σ_n when f = I), and the Cauchy stress at the
// end of the increment is the push-forward σ_{n+1} = f S fᵀ / (det f · λ3).
//   - Objectivity: a rigid rotation f = R gives ΔE = 0 and σ_{n+1} = R σ_n Rᵀ exactly, as the
//     thesis's Hughes–Winget update does (for a rigid rotation its ΔR equals R exactly).
//   - Large plastic strain: the yield condition is applied to the stress of the increment,
//     which differs from the Cauchy stress by O(ΔE) only, so the Cauchy stress stays on the
//     yield surface however large the accumulated plastic strain (a total-Lagrangian
//     Green–Lagrange model would not: its Cauchy stress drifts off yield at hinge strains).
//   - The tangent of the increment (material + geometric) is exact: Newton converges
//     quadratically, which the Hughes–Winget mid-point update does not allow in closed form.
// hughes_winget_rotation() is the thesis's incremental rotation; the tests use it to check
// that both descriptions rotate a pre-stressed element identically.
#pragma once

#include <Eigen/Core>

namespace ringcrush::fe {

using Mat2 = Eigen::Matrix2d;
using Vec2 = Eigen::Vector2d;

// F = I + Σ_a u_a ⊗ ∇₀N_a; dndx is 8×2 (reference gradients), u holds [ux1, uy1, ux2, ...].
inline Mat2 deformation_gradient(const Eigen::Matrix<double, 8, 2>& dndx, const double* u) {
  Mat2 f = Mat2::Identity();
  for (int a = 0; a < 8; ++a) {
    f(0, 0) += u[2 * a] * dndx(a, 0);
    f(0, 1) += u[2 * a] * dndx(a, 1);
    f(1, 0) += u[2 * a + 1] * dndx(a, 0);
    f(1, 1) += u[2 * a + 1] * dndx(a, 1);
  }
  return f;
}

// Green–Lagrange strain, Voigt [E11, E22, 2 E12].
inline Eigen::Vector3d green_lagrange(const Mat2& f) {
  const Mat2 c = f.transpose() * f;
  return {0.5 * (c(0, 0) - 1.0), 0.5 * (c(1, 1) - 1.0), c(0, 1)};
}

// Cauchy stress (Voigt [σ11, σ22, σ12]) from PK2 in plane stress; stretch33 is the
// out-of-plane stretch λ3 (J = det F · λ3). Inline: every stress point of every explicit
// step pushes its stress forward (element kernels, cps8_force.cpp).
inline Eigen::Vector3d cauchy_from_pk2(const Mat2& f, const Eigen::Vector3d& s, double stretch33) {
  Mat2 sm;
  sm << s(0), s(2), s(2), s(1);
  const double det = f(0, 0) * f(1, 1) - f(1, 0) * f(0, 1);  // as Eigen's 2×2 determinant()
  const Mat2 sigma = f * sm * f.transpose() / (det * stretch33);
  return {sigma(0, 0), sigma(1, 1), sigma(0, 1)};
}

Mat2 rotation(double angle);

// Hughes–Winget incremental rotation (thesis §3.6.1.2): with L = ∂Δu/∂x at the
// mid-increment configuration x(t+Δt/2) = ½(x_t + x_{t+Δt}) and Δω = skew(L),
// ΔR = (I − ½Δω)⁻¹ (I + ½Δω). Exactly orthogonal; exact for a rigid rotation.
Mat2 hughes_winget_rotation(const Mat2& grad_du_mid);

}  // namespace ringcrush::fe
