// The true highest frequency of a chain model's current state, for tests of stable-step
// bounds and estimates: the largest ω of K v = ω² M v over the free dofs, K the assembled
// tangent of the model's last evaluate() with want_tangent, M its lumped mass. Dense: small
// chains only.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <cmath>

#include "fe/chain/chain_model.hpp"

namespace ringcrush::fe::test {

inline double chain_omega_max(ChainModel& model) {
  SparseSystem& sys = model.tangent_system();
  const Eigen::MatrixXd k = Eigen::MatrixXd(sys.matrix());
  Eigen::VectorXd s(sys.free_dofs());
  for (int i = 0; i < sys.free_dofs(); ++i) s(i) = 1 / std::sqrt(model.lumped_mass()(sys.free_to_dof()[i]));
  const Eigen::MatrixXd a = s.asDiagonal() * k * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (a + a.transpose()), Eigen::EigenvaluesOnly);
  return std::sqrt(eig.eigenvalues().maxCoeff());
}

}  // namespace ringcrush::fe::test
