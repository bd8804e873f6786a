#include "fe/element/bulk_viscosity.hpp"

#include <array>

#include "fe/kinematics.hpp"

namespace ringcrush::fe {

double add_bulk_viscous_force(const Cps8Geometry& geo, const double* du, double dt, double coefficient,
                              ElementVector& force) {
  double volume = 0, volumetric = 0;  // Σ w, Σ w q
  for (int i = 0; i < geo.points; ++i) {
    const Mat2 f = deformation_gradient(geo.dndx[i], du);
    const Eigen::Vector3d e = green_lagrange(f);
    const double q = coefficient * (e(0) + e(1)) / dt;
    volume += geo.weight[i];
    volumetric += geo.weight[i] * q;
    const Mat2 a = (q * geo.weight[i]) * f;
    const ShapeGrad& d = geo.dndx[i];
    for (int k = 0; k < 8; ++k) {
      force(2 * k) += a(0, 0) * d(k, 0) + a(0, 1) * d(k, 1);
      force(2 * k + 1) += a(1, 0) * d(k, 0) + a(1, 1) * d(k, 1);
    }
  }
  return volumetric / volume;
}

}  // namespace ringcrush::fe
