// A chain whose rings (not the impactor) start with their own vertical velocity: the free-
// flight and collision checks of issue 4 (verification a, d) on the explicit and HHT drivers.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Dense>

#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/dynamic_system.hpp"

namespace ringcrush::fe::test_support {

// The chain with an initial velocity along y per ring (ChainInput only moves the impactor):
// forwards everything else to the ChainModel.
class RingsInMotion final : public DynamicSystem {
 public:
  RingsInMotion(ChainModel& model, std::vector<double> ring_vy) : m_(model) {
    v0_ = m_.initial_velocity();
    const auto& mesh = m_.mesh();
    for (std::size_t e = 0; e < mesh.elements.size(); ++e)
      for (int n : mesh.elements[e]) v0_(2 * n + 1) = ring_vy[static_cast<std::size_t>(mesh.element_ring[e])];
  }
  int dofs() const override { return m_.dofs(); }
  const std::vector<int>& fixed_dofs() const override { return m_.fixed_dofs(); }
  const Eigen::VectorXd& lumped_mass() const override { return m_.lumped_mass(); }
  Eigen::VectorXd initial_velocity() const override { return v0_; }
  void evaluate(const Eigen::VectorXd& u, bool t, SystemEvaluation& out) override { m_.evaluate(u, t, out); }
  void commit(const Eigen::VectorXd& u) override { m_.commit(u); }
  SparseSystem& tangent_system() override { return m_.tangent_system(); }
  StableStep stable_step(const Eigen::VectorXd& u) const override { return m_.stable_step(u); }

 private:
  ChainModel& m_;
  Eigen::VectorXd v0_;
};

}  // namespace ringcrush::fe::test_support
