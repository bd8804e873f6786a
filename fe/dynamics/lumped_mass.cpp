#include "fe/dynamics/lumped_mass.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <stdexcept>

#include "fe/element/cps8_shape.hpp"

namespace ringcrush::fe {

std::array<double, 8> hrz_lumped_mass(const ElementCoords& x, double density, double thickness) {
  std::array<double, 8> diag{};
  double volume = 0;
  ShapeVec n;
  ShapeGrad dn;
  for (const GaussPoint& p : gauss_rule(3)) {
    cps8_shape(p.g, p.h, n, dn);
    const double det = (dn.transpose() * x).determinant();
    if (!(det > 0)) throw std::invalid_argument(fmt::format("lumped mass: CPS8 element degenerate (det J = {:g})", det));
    const double w = p.weight * det * thickness;
    volume += w;
    for (int a = 0; a < 8; ++a) diag[a] += w * n(a) * n(a);
  }
  double sum = 0;
  for (double d : diag) sum += d;
  // Scale the consistent diagonal to the element mass ρ t A (HRZ).
  const double scale = density * volume / sum;
  for (double& d : diag) d *= scale;
  return diag;
}

}  // namespace ringcrush::fe
