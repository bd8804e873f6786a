// The inertial Level 3 chain's analytic IDA Jacobian (h52; hinge/level3_inertia.cpp, μ″ of the
// Uniform mode from K″(φ), hinge/ring_laws.hpp) against one-sided second-order difference
// quotients of its right-hand side at every state of an IDA run on Test 30 welded at 27.7,
// 45 and 50 m/s (the Uniform mode's own inertia; wraps, bottoms and E–C–B), each column's
// entries to 1e-5 of its largest. Leaving out μ″ (the ½ μ″ v² term) fails it (README).
#include <gtest/gtest.h>

#include "chain_fixtures.hpp"
#include "level3_ring_fixtures.hpp"
#include "hinge/level3_mechanism.hpp"

using namespace ringcrush;
using namespace ringcrush::hinge;

TEST(Level3InertiaJacobian, AnalyticMatchesDifferencesAtThreeSpeeds) {
  for (double v : {27.7, 45.0, 50.0}) {
    const auto in = hinge::testing::test30_level3_chain(v, false, true);
    const auto check = level3_inertial_jacobian_check(in, hinge::testing::tight(HybridIntegrator::Ida, 1e-8, 1e-10));
    EXPECT_GT(check.states, 300) << v << " m/s";
    EXPECT_GT(check.columns, 2 * check.states) << v << " m/s";
    EXPECT_LE(check.worst_relative, 1e-5) << v << " m/s, t = " << check.worst_time_s << " s, ring "
                                          << check.worst_ring + 1 << (check.worst_is_rate ? " rate" : " crush");
  }
}

TEST(Level3InertiaJacobian, NeedsTheInertialChain) {
  auto in = hinge::testing::test30_level3_chain(27.7, false, false);
  EXPECT_THROW(level3_inertial_jacobian_check(in, hinge::testing::tight(HybridIntegrator::Ida)), std::invalid_argument);
}
