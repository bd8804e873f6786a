// The assembled stable-step estimate (fe/dynamics/assembled_eigenvalue.hpp, ChainInput::
// step_bound = Assembled; issue 4 performance): the power iteration approaches λ_max of the
// assembled K v = λ M v from below and reaches it, and on small chains the step it gives is
// still below the true 2/ω_max of a dense eigen-solve while being closer to it than the
// element eigenvalue bound.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>

#include "fe/chain/chain_model.hpp"
#include "chain_omega_max.hpp"
#include "fe/dynamics/assembled_eigenvalue.hpp"

using namespace ringcrush::fe;

namespace {
constexpr double kDepth = 1.6e-3;

// Random symmetric positive semi-definite "element" matrices on a chain of 5 elements
// sharing 4 dofs with each neighbour, and their dense assembled λ_max(M^{-1/2} K M^{-1/2}).
struct ToySystem {
  std::vector<std::array<int, 16>> dofs;
  std::vector<ElementMatrix> k;
  Eigen::VectorXd inv_sqrt_mass;
  double truth = 0;
};
ToySystem toy(unsigned seed) {
  ToySystem t;
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-1, 1), m(0.5, 2.0);
  const int elements = 5, n = 12 * elements + 4;
  t.inv_sqrt_mass.resize(n);
  for (int i = 0; i < n; ++i) t.inv_sqrt_mass(i) = 1 / std::sqrt(m(gen));
  t.inv_sqrt_mass(0) = 0;  // a fixed dof
  Eigen::MatrixXd kk = Eigen::MatrixXd::Zero(n, n);
  for (int e = 0; e < elements; ++e) {
    std::array<int, 16> dof{};
    for (int i = 0; i < 16; ++i) dof[i] = 12 * e + i;
    ElementMatrix b;
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j) b(i, j) = d(gen);
    const ElementMatrix ke = b * b.transpose();
    t.dofs.push_back(dof);
    t.k.push_back(ke);
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j) kk(dof[i], dof[j]) += ke(i, j);
  }
  const Eigen::MatrixXd a = t.inv_sqrt_mass.asDiagonal() * kk * t.inv_sqrt_mass.asDiagonal();
  t.truth = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  return t;
}

double omega_max(ChainModel& model) { return test::chain_omega_max(model); }
}  // namespace

TEST(AssembledEigenvalue, PowerIterationApproachesTheDenseMaximumFromBelow) {
  for (unsigned seed : {1u, 2u, 3u}) {
    ToySystem t = toy(seed);
    AssembledEigenvalue est(t.dofs, t.inv_sqrt_mass);
    const std::vector<double> ones(t.k.size(), 1.0);
    double last = 0;
    for (int call = 0; call < 6; ++call) {  // warm-started calls of 3 iterations each
      const AssembledEstimate a = est.estimate(t.k, ones, 3, 3, 1e-12);
      EXPECT_LE(a.lambda, t.truth * (1 + 1e-12));
      EXPECT_GE(a.lambda, last * (1 - 1e-12));  // monotone for a fixed PSD matrix
      last = a.lambda;
    }
    const AssembledEstimate a = est.estimate(t.k, ones, 1, 5000, 1e-12);
    EXPECT_TRUE(a.converged);
    EXPECT_NEAR(a.lambda, t.truth, 1e-6 * t.truth);
    // Scaled element matrices scale the assembled λ_max.
    const std::vector<double> twice(t.k.size(), 2.0);
    EXPECT_NEAR(est.estimate(t.k, twice, 1, 5000, 1e-12).lambda, 2 * t.truth, 1e-6 * t.truth);
  }
}

TEST(AssembledEigenvalue, RejectsBadInput) {
  ToySystem t = toy(4);
  AssembledEigenvalue est(t.dofs, t.inv_sqrt_mass);
  const std::vector<double> ones(t.k.size(), 1.0);
  EXPECT_THROW(est.estimate({}, ones, 1, 10, 1e-6), std::invalid_argument);
  EXPECT_THROW(est.estimate(t.k, ones, 0, 10, 1e-6), std::invalid_argument);
  EXPECT_THROW(est.estimate(t.k, ones, 5, 4, 1e-6), std::invalid_argument);
  EXPECT_THROW(est.estimate(t.k, ones, 1, 10, 0.0), std::invalid_argument);
  auto bad = t.dofs;
  bad[0][3] = static_cast<int>(t.inv_sqrt_mass.size());
  EXPECT_THROW(AssembledEigenvalue(bad, t.inv_sqrt_mass), std::invalid_argument);
  ChainInput in;
  in.step_bound_margin = 0.9;
  EXPECT_THROW(validate(in), std::invalid_argument);
}

TEST(AssembledEigenvalue, ChainStepStaysBelowTheTrueLimitAndBeatsTheElementBound) {
  // Two welded half rings pressed by the impactor (its penalty springs are in the truth; the
  // element bound adds the largest spring frequency² near contact, the assembled estimate
  // assembles the active springs), and one ring alone, nothing near contact: the step stays
  // safe, the estimate has converged (ω within √margin of the truth), never above the
  // element bound.
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    for (int around : {4, 8}) {
      for (int rings : {1, 2}) {
        ChainInput in;
        in.rings = rings;
        in.mesh.elements_around = around;
        in.joints = JointKind::Welded;
        in.integration = rule;
        in.fixed_target = rings == 2;
        ChainModel element_model(in);
        in.step_bound = StepBound::Assembled;
        ChainModel assembled_model(in);
        Eigen::VectorXd u = Eigen::VectorXd::Zero(element_model.dofs());
        u(element_model.impactor_dof()) = rings == 2 ? -0.1 * kDepth : 0.02;  // pressed / out of the way
        SystemEvaluation ev;
        element_model.evaluate(u, false, ev);
        assembled_model.evaluate(u, true, ev);
        const double truth = omega_max(assembled_model);
        const double element_bound = 2 / element_model.stable_step(u).step_s;
        const StableStep s = assembled_model.stable_step(u);
        const double sharp = 2 / s.step_s;
        SCOPED_TRACE(::testing::Message() << "rings " << rings << ", " << around << " around, " << s.limited_by
                                          << ": truth " << truth << ", assembled " << sharp << ", element " << element_bound);
        EXPECT_GE(sharp, truth * (1 - 1e-9));                                   // still a safe step
        EXPECT_LE(sharp, std::sqrt(in.step_bound_margin) * truth * (1 + 1e-2));  // converged
        EXPECT_LE(sharp, element_bound * (1 + 1e-12));
        // The gain is the contact springs: with them (two rings) the element bound adds the
        // largest spring's frequency² to the largest element's, though they are not one mode.
        // (0.83 of it with 8 elements around, 0.95 with 4.)
        if (rings == 2) {
          EXPECT_LT(sharp, 0.97 * element_bound);
        }
        EXPECT_EQ(assembled_model.step_bound_statistics().fallbacks, 0);
        // The contact-only re-bound reuses the element part and iterates on from the last
        // iterate: the same step to the iteration's tolerance, same contacts.
        EXPECT_NEAR(assembled_model.contact_stable_step(u).step_s, s.step_s, 1e-3 * s.step_s);
      }
    }
  }
}

// Two threads (use_threads): the element products are formed on both threads and summed on the
// caller in element order, so every warm-started estimate is bitwise the one-thread estimate
// (the explicit run's Δt, hence its whole history, depends on it). 37 elements: an odd count,
// the helper's half one element longer.
TEST(AssembledEigenvalue, TwoThreadsGiveTheOneThreadEstimateBitwise) {
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> d(-1, 1), m(0.5, 2.0);
  const int elements = 37, n = 12 * elements + 4;
  std::vector<std::array<int, 16>> dofs;
  std::vector<ElementMatrix> k;
  std::vector<double> scale;
  Eigen::VectorXd inv_sqrt_mass(n);
  for (int i = 0; i < n; ++i) inv_sqrt_mass(i) = 1 / std::sqrt(m(gen));
  for (int e = 0; e < elements; ++e) {
    std::array<int, 16> dof{};
    for (int i = 0; i < 16; ++i) dof[i] = 12 * e + i;  // 4 dofs shared with each neighbour
    ElementMatrix b;
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j) b(i, j) = d(gen);
    dofs.push_back(dof);
    k.push_back(b * b.transpose());
    scale.push_back(1.0 + 0.3 * d(gen));
  }
  // A penalty spring between nodes 3 and 40 (added after the elements on both paths).
  ContactContribution spring;
  spring.count = 2;
  spring.nodes[0] = 3;
  spring.nodes[1] = 40;
  spring.stiffness = 2.5;
  spring.gap = -0.01;
  spring.force(1) = spring.stiffness * spring.gap;
  spring.force(3) = -spring.stiffness * spring.gap;
  AssembledEigenvalue one(dofs, inv_sqrt_mass), two(dofs, inv_sqrt_mass);
  ForkJoin fork;
  two.use_threads(&fork);
  for (int call = 0; call < 5; ++call) {
    const AssembledEstimate a = one.estimate(k, scale, 3, 3, 1e-12, {spring});
    const AssembledEstimate b = two.estimate(k, scale, 3, 3, 1e-12, {spring});
    EXPECT_EQ(a.lambda, b.lambda);
    EXPECT_EQ(a.iterations, b.iterations);
    scale[static_cast<std::size_t>(call)] *= 1.01;  // the element matrices move between calls, as in a run
  }
  const AssembledEstimate a = one.estimate(k, scale, 1, 500, 1e-9);
  const AssembledEstimate b = two.estimate(k, scale, 1, 500, 1e-9);
  EXPECT_EQ(a.lambda, b.lambda);
  EXPECT_EQ(a.converged, b.converged);
  EXPECT_GT(a.iterations, 3);
}
