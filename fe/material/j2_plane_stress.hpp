// J2 plasticity in plane stress with isotropic piecewise-linear hardening (thesis §3.6.1,
// DESIGN.md "Material"). Small elastic strain, incremental form: the law receives an
// objective strain increment (the element passes the Green–Lagrange strain of the increment,
// measured on the configuration at the start of the increment) and the committed stress, and
// returns the stress of the increment's work-conjugate pair; it knows nothing of rotations,
// elements or meshes (STYLE.md practice 2).
//
// Voigt order [11, 22, 12] with ENGINEERING shear strain (γ12 = 2 E12).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "fe/fe_input.hpp"

namespace ringcrush::fe {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// History variables of one integration point (committed or trial, STYLE.md practice 3).
struct PointState {
  Vec3 stress = Vec3::Zero();          // committed: Cauchy stress; trial: see cps8_element
  Vec3 plastic_strain = Vec3::Zero();  // accumulated plastic strain increments (Voigt)
  double peeq = 0.0;                   // equivalent plastic strain ᾱ
  double plastic_work = 0.0;           // dissipated energy per unit INITIAL volume (J/m³)
  double thickness_stretch = 1.0;      // plane-stress out-of-plane stretch λ3
};

// σy(ᾱ): piecewise linear through the table, flat after the last point.
class HardeningTable {
 public:
  explicit HardeningTable(std::vector<HardeningPoint> points);
  double yield_stress(double peeq) const;
  // Slope of the segment that holds `peeq` (right derivative at a break point); 0 beyond
  // the last point.
  double slope(double peeq) const;

 private:
  std::vector<HardeningPoint> points_;
};

struct J2Update {
  Vec3 stress;      // S(n+1)
  Mat3 tangent;     // algorithmic (consistent) tangent dS/dΔE
  Vec3 plastic_increment = Vec3::Zero();  // ΔEp
  double peeq = 0.0;                      // ᾱ(n+1)
  double dissipation = 0.0;               // ½ (S(n) + S(n+1)) : ΔEp per unit volume (trapezoid)
  double strain33_increment = 0.0;        // out-of-plane strain increment (plane stress)
  bool plastic = false;
  double elastic_energy = 0.0;            // ½ S : C⁻¹ : S per unit volume
};

class J2PlaneStress {
 public:
  explicit J2PlaneStress(const MaterialInput& m);

  // Backward-Euler return mapping from the committed stress and PEEQ for the strain
  // increment ΔE (Simo & Taylor's plane-stress projected algorithm; equations in the .cpp).
  J2Update update(const Vec3& strain_increment, const PointState& committed) const;
  // The same update without the consistent tangent (`tangent` set to zero): the explicit
  // driver's force-only path, where the tangent is never used.
  J2Update update_stress(const Vec3& strain_increment, const PointState& committed) const;

  const Mat3& elastic_tangent() const { return c_; }
  double youngs_modulus() const { return e_; }
  double poisson_ratio() const { return nu_; }
  const HardeningTable& hardening() const { return table_; }

 private:
  J2Update return_map(const Vec3& strain_increment, const PointState& committed, bool want_tangent) const;

  double e_, nu_, g_;
  Mat3 c_, c_inv_, p_;
  HardeningTable table_;
};

// von Mises equivalent stress of a plane-stress Voigt stress.
double mises(const Vec3& s);

}  // namespace ringcrush::fe
