#include "fe/dynamics/element_eigenvalue.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace ringcrush::fe {

ElementMatrix element_elastic_stiffness(const ElementCoords& x, Integration rule, double width,
                                        const J2PlaneStress& material, const PointState* states, int points) {
  const Cps8Geometry geo = cps8_geometry(x, rule, width);
  // Zero stress, the committed thickness: a zero increment then gives the elastic tangent.
  std::array<PointState, 9> committed{}, trial{};
  for (int i = 0; states && i < points && i < 9; ++i) committed[i].thickness_stretch = states[i].thickness_stretch;
  Cps8Output out;
  const double du[16] = {};
  cps8_evaluate(geo, du, committed.data(), trial.data(), material, true, out);
  return out.tangent;
}

double element_max_eigenvalue(const ElementMatrix& k, const std::array<double, 8>& mass) {
  // M^{-1/2} K M^{-1/2}: the same eigenvalues as K v = λ M v for a diagonal M.
  Eigen::Matrix<double, 16, 1> s;
  for (int i = 0; i < 16; ++i) s(i) = 1.0 / std::sqrt(mass[i / 2]);
  const ElementMatrix a = s.asDiagonal() * k * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<ElementMatrix> eig(0.5 * (a + a.transpose()), Eigen::EigenvaluesOnly);
  return eig.eigenvalues().maxCoeff();
}

double element_max_eigenvalue(const ElementCoords& x, const std::array<double, 8>& mass, Integration rule,
                              double width, const J2PlaneStress& material, const PointState* states, int points) {
  return element_max_eigenvalue(element_elastic_stiffness(x, rule, width, material, states, points), mass);
}

}  // namespace ringcrush::fe
