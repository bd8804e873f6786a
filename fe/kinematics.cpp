#include <Eigen/Dense>
#include "fe/kinematics.hpp"

#include <cmath>

namespace ringcrush::fe {

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
