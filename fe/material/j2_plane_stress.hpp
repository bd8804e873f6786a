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
#include <cstddef>
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
  // yield_stress(peeq) and slope(peeq) from one search of the table, bitwise the two calls
  // (the return mapping's Newton iteration needs both at every iterate).
  void yield_stress_and_slope(double peeq, double& sy, double& h) const;
  // The smallest yield stress of the table (σy is piecewise linear: its minimum is at a point).
  double min_yield_stress() const { return min_yield_; }
  const std::vector<HardeningPoint>& points() const { return points_; }
  // Segment i (points i, i + 1): σy(i + 1) − σy(i) and ᾱ(i + 1) − ᾱ(i), the differences
  // yield_stress() forms (tabulated: the same values, not formed per call; the lane kernel
  // reads them too, cps8_force_lanes.cpp).
  double rise(std::size_t i) const { return rise_[i]; }
  double run(std::size_t i) const { return run_[i]; }

 private:
  std::vector<HardeningPoint> points_;
  std::vector<double> rise_, run_, slope_;  // per segment; slope_ = rise_ / run_
  double min_yield_ = 0.0;
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
  // driver's force-only path, where the tangent is never used. Inline (below): its elastic
  // branch is most of the material's share of an explicit step, and inlined into the
  // element kernel the unused fields of J2Update cost nothing.
  inline J2Update update_stress(const Vec3& strain_increment, const PointState& committed) const;

  const Mat3& elastic_tangent() const { return c_; }
  // C⁻¹ as update_stress() reads it (the lane kernel, cps8_force_lanes.cpp, repeats its elastic branch).
  const Mat3& elastic_compliance() const { return c_inv_; }
  double youngs_modulus() const { return e_; }
  double poisson_ratio() const { return nu_; }
  const HardeningTable& hardening() const { return table_; }

 private:
  J2Update return_map(const Vec3& strain_increment, const PointState& committed, bool want_tangent) const;

  double e_, nu_, g_;
  Mat3 c_, c_inv_, p_;
  HardeningTable table_;
  // ξ(Δγ₀) = k1 a1 + k2 a2 at the first bracket end Δγ₀ = 1/(2G) (return_map: lets the bracket
  // skip evaluating f(Δγ₀) where a bound shows it negative).
  double bracket_k1_ = 0.0, bracket_k2_ = 0.0;
};

// Most points of an explicit step are elastic: the trial check and the elastic result are
// written out in scalars (C, P and C⁻¹ of plane stress, same equations as return_map), and
// only points whose trial stress reaches the current yield stress go to the return mapping.
inline J2Update J2PlaneStress::update_stress(const Vec3& strain_increment, const PointState& committed) const {
  // C = f [[1, ν, 0], [ν, 1, 0], [0, 0, (1−ν)/2]], C⁻¹ = [[1, −ν, 0], [−ν, 1, 0], [0, 0, 2(1+ν)]] / E:
  // read from the tabulated matrices (no division per point).
  const double f = c_(0, 0), c_nu = c_(0, 1), inv_e = c_inv_(0, 0), inv_e_nu = c_inv_(0, 1);
  const Vec3& sn = committed.stress;
  const double de0 = strain_increment(0), de1 = strain_increment(1);
  const double t0 = sn(0) + f * de0 + c_nu * de1, t1 = sn(1) + c_nu * de0 + f * de1,
               t2 = sn(2) + g_ * strain_increment(2);
  const double sy_n = table_.yield_stress(committed.peeq);
  const double xi_trial = 2.0 / 3.0 * (t0 * t0 + t1 * t1 - t0 * t1) + 2.0 * t2 * t2;  // SᵀPS
  if (!(0.5 * xi_trial - sy_n * sy_n * (1.0 / 3.0) <= 1e-12 * sy_n * sy_n))
    return return_map(strain_increment, committed, false);
  J2Update out;
  out.peeq = committed.peeq;
  out.stress = Vec3(t0, t1, t2);
  out.tangent.setZero();  // not computed
  out.elastic_energy = 0.5 * (inv_e * (t0 * t0 + t1 * t1) + 2.0 * inv_e_nu * t0 * t1 + c_inv_(2, 2) * t2 * t2);
  out.strain33_increment = inv_e_nu * (t0 + t1 - sn(0) - sn(1));  // −ν/E (Δσ11 + Δσ22)
  return out;
}

// von Mises equivalent stress of a plane-stress Voigt stress.
double mises(const Vec3& s);

}  // namespace ringcrush::fe
