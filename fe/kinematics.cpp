#include <Eigen/Dense>
#include "fe/kinematics.hpp"

#include <cmath>

namespace ringcrush::fe {

Eigen::Vector3d cauchy_from_pk2(const Mat2& f, const Eigen::Vector3d& s, double stretch33) {
  Mat2 sm;
  sm << s(0), s(2), s(2), s(1);
  const Mat2 sigma = f * sm * f.transpose() / (f.determinant() * stretch33);
  return {sigma(0, 0), sigma(1, 1), sigma(0, 1)};
}

Mat2 rotation(double angle) {
  Mat2 r;
  r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return r;
}

Mat2 hughes_winget_rotation(const Mat2& grad_du_mid) {
  const Mat2 w = 0.5 * (grad_du_mid - grad_du_mid.transpose());
  const Mat2 i = Mat2::Identity();
  return (i - 0.5 * w).inverse() * (i + 0.5 * w);
}

}  // namespace ringcrush::fe
