// A contact contribution: up to 6 nodes, their force (gradient of the penalty energy, added
// to the internal force) and its tangent. Produced by the contact search each evaluation,
// scattered by the assembler like an element.
#pragma once

#include <Eigen/Core>
#include <array>

namespace ringcrush::fe {

struct ContactContribution {
  int count = 0;                        // nodes used
  std::array<int, 6> nodes{};
  Eigen::Matrix<double, 12, 1> force = Eigen::Matrix<double, 12, 1>::Zero();
  Eigen::Matrix<double, 12, 12> tangent = Eigen::Matrix<double, 12, 12>::Zero();
  // Penalty spring k and gap g < 0 of a frictionless penalty contact (0 where not set): its
  // main stiffness is k G Gᵀ with G = force / (k g), which the explicit step's assembled
  // estimate uses (fe/dynamics/assembled_eigenvalue.hpp).
  double stiffness = 0, gap = 0;
};

}  // namespace ringcrush::fe
