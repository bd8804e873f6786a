// The chain's highest frequency by power iteration (hinge/polygon_stiffness_spectrum.hpp)
// against a dense eigen-solve of the same assembled M^{-1/2} K M^{-1/2}, and the central-
// difference step bound (PolygonChain::stable_step, Gershgorin) against both, on randomly
// distorted two-ring chains pressed into contact (ring–ring, impactor, ties, plates).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "hinge/polygon_stiffness_spectrum.hpp"
#include "two_ring_chain.hpp"

using namespace ringcrush::hinge;

namespace {

// Nodes moved by up to ±2 % of t and given velocities of up to ±2 m/s; ring 2 pushed 0.1 t
// into ring 1 and the impactor 0.1 t into ring 1's top, so that contacts carry load.
std::vector<double> distorted_state(const PolygonChain& chain, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double t = chain.input().wall_thickness_m;
  std::vector<double> y = chain.initial_state();
  const bool half = chain.input().half_symmetry;
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) {
      const auto o = chain.node_offset(r, j);
      const bool axis = half && (j == 0 || j == chain.independent_nodes() - 1);
      if (!axis) {
        y[o] += 0.02 * t * u(gen);
        y[o + 2] += 2.0 * u(gen);
      }
      y[o + 1] += 0.02 * t * u(gen) + (r == 1 ? 0.1 * t : 0.0);
      y[o + 3] += 2.0 * u(gen);
    }
  y[chain.body_offset(0)] -= 0.1 * t;
  return y;
}

double dense_highest(const PolygonStiffnessSpectrum& s, double& asymmetry) {
  const auto n = static_cast<Eigen::Index>(s.position_rows().size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (const auto& e : s.entries()) A(e.i, e.j) += e.a;
  asymmetry = (A - A.transpose()).norm() / A.norm();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()));
  return es.eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace

TEST(PolygonStiffnessSpectrum, PowerIterationReachesTheDenseEigenvalueAndGershgorinBoundsIt) {
  unsigned seed = 7;
  for (bool half : {true, false})
    for (auto joint : {PolygonJoint::Free, PolygonJoint::Welded, PolygonJoint::Plates}) {
      PolygonChainInput in = two_ring_chain::input(joint);
      in.half_symmetry = half;
      // Undamped contact: the Gershgorin step then carries no damping factor, and the
      // Hunt–Crossley slope k(1 + χṗ) is k on both sides.
      in.contact_damping_s_per_m = 0.0;
      PolygonChain c(in);
      c.set_implicit_ring_dampers(true);  // the central difference's default: no ξ in the step
      const auto y = distorted_state(c, ++seed);
      ASSERT_GT(c.energies(0.0, y.data()).contact, 0.0) << "the state must press contacts";
      PolygonStiffnessSpectrum spectrum(c);
      const auto est = spectrum.estimate(0.0, y.data(), 50, 20000, 1e-12);
      double asym = 0.0;
      const double lambda = dense_highest(spectrum, asym);
      const auto tag = ::testing::Message() << "half " << half << " joint " << static_cast<int>(joint);
      EXPECT_LT(asym, 1e-12) << tag;  // the analytic blocks are symmetric
      EXPECT_LE(est.lambda, lambda * (1.0 + 1e-12)) << tag;  // from below
      EXPECT_GE(est.lambda, lambda * (1.0 - 1e-3)) << tag;
      // The Gershgorin step of the same state (contact rows of the same evaluation) is a
      // bound: 2/√λ_G ≤ 2/√λ_max.
      std::vector<double> phi(y.size());
      c.generalised_forces(0.0, y.data(), phi.data());
      const double bound = c.stable_step();
      EXPECT_LE(bound, 2.0 / std::sqrt(lambda) * (1.0 + 1e-12)) << tag;
      // Pessimistic by 0.70–0.79 here (the bars' rows add to the contacts' and hinges' across
      // directions that the true modes keep apart), as on the unloaded rings.
      EXPECT_GE(bound, 0.65 * 2.0 / std::sqrt(lambda)) << tag;
    }
}

TEST(PolygonStiffnessSpectrum, BreakdownLeavesTermsOut) {
  PolygonChainInput in = two_ring_chain::input(PolygonJoint::Welded);
  in.contact_damping_s_per_m = 0.0;
  PolygonChain c(in);
  c.set_implicit_ring_dampers(true);
  const auto y = distorted_state(c, 3);
  std::vector<double> phi(y.size());
  c.generalised_forces(0.0, y.data(), phi.data());
  const double all = c.stable_step();
  PolygonStiffnessSpectrum spectrum(c);
  const auto b = stable_step_breakdown(c, spectrum, 0.0, y.data());
  EXPECT_EQ(b.gershgorin, all);  // the mask of every term is the default, to the bit
  for (double partial : {b.without_membrane, b.without_hinges, b.without_ties, b.without_contacts,
                         b.membrane_only, b.hinges_only, b.ties_only, b.contacts_only})
    EXPECT_GE(partial, all);
  EXPECT_GT(b.without_membrane, 1.2 * all);  // the bars are the stiff term of this state
  EXPECT_LT(b.without_hinges, 1.1 * all);
  EXPECT_GE(b.power_iteration, all);
  EXPECT_TRUE(b.converged);
}

TEST(PolygonStiffnessSpectrum, BadIterationLimitsAreErrors) {
  PolygonChain c(two_ring_chain::input(PolygonJoint::Free));
  PolygonStiffnessSpectrum spectrum(c);
  const auto y = c.initial_state();
  EXPECT_THROW(spectrum.estimate(0.0, y.data(), 0, 10, 1e-6), std::invalid_argument);
  EXPECT_THROW(spectrum.estimate(0.0, y.data(), 5, 4, 1e-6), std::invalid_argument);
  EXPECT_THROW(spectrum.estimate(0.0, y.data(), 1, 10, 0.0), std::invalid_argument);
}
