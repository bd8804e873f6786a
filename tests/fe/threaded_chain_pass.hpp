// One chain evaluated on one thread and on two, over the same random committed increments: the
// threaded element pass (work_dealer.hpp, the fixed halves of the sums) must give bitwise the
// one-thread force, viscous force and energies (README "Two threads"). Shared by the tests of
// the fused viscous pass and of the two-ended dealer, which differ in the chain's size.
#pragma once

#include <functional>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "fe/chain/chain_model.hpp"

namespace ringcrush::fe::test_support {

struct ThreadedChainPass {
  ChainModel serial;
  ChainModel threaded;
  Eigen::VectorXd u;

  static ChainInput with_threads(ChainInput in, int threads) {
    in.threads = threads;
    return in;
  }
  explicit ThreadedChainPass(const ChainInput& in)
      : serial(with_threads(in, 1)), threaded(with_threads(in, 2)), u(Eigen::VectorXd::Zero(serial.dofs())) {}

  // `steps` increments of ±2 µm per dof at Δt = 5e-8 s; after each evaluation the passes are
  // compared to the bit, `also` sees the one-thread evaluation, and both models commit.
  void run(int steps, unsigned seed, const std::function<void(const SystemEvaluation&)>& also = {}) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> d(-2e-6, 2e-6);
    for (int step = 0; step < steps; ++step) {
      for (int i = 0; i < serial.dofs(); ++i) u(i) += d(gen);
      for (int dof : serial.fixed_dofs()) u(dof) = 0;
      SystemEvaluation a, b;
      serial.set_increment_time(5e-8);
      threaded.set_increment_time(5e-8);
      serial.evaluate(u, false, a);
      threaded.evaluate(u, false, b);
      const std::string where = "step " + std::to_string(step);
      ASSERT_EQ(a.viscous_force.size(), serial.dofs()) << where;
      EXPECT_EQ(a.force, b.force) << where;
      EXPECT_EQ(a.viscous_force, b.viscous_force) << where;
      EXPECT_EQ(a.elastic_energy, b.elastic_energy) << where;
      EXPECT_EQ(a.plastic_work, b.plastic_work) << where;
      EXPECT_GT(a.force.norm(), 0.0) << where;
      EXPECT_GT(a.viscous_force.norm(), 0.0) << where;
      if (also) also(a);
      serial.commit(u);  // the next pass re-derives the geometry on this configuration
      threaded.commit(u);
    }
  }
};

}  // namespace ringcrush::fe::test_support
