// IDA's vector operations for a few components (h52; hinge/ida_small_vector_ops.hpp,
// HybridOptions::ida_small_vector_ops, set by the inertial Level 3 chain): SUNDIALS' serial
// arithmetic to the bit. Level 3 with ring inertia on Test 30 welded at 27.7, 45 and 50 m/s
// with them and without: every history sample (time, impactor, crushes, kinetic energy,
// work), the events and IDA's counters identical; and the massless Level 3 chain, whose whole
// 28-component state IDA integrates, likewise with the option set.
#include <gtest/gtest.h>

#include "chain_fixtures.hpp"
#include "level3_ring_fixtures.hpp"
#include "hinge/level3_mechanism.hpp"

using namespace ringcrush;
using namespace ringcrush::hinge;

namespace {

void expect_identical(const Level3Result& a, const Level3Result& b, const std::string& what) {
  const auto &ha = a.history, &hb = b.history;
  ASSERT_EQ(ha.time_s.size(), hb.time_s.size()) << what;
  for (std::size_t k = 0; k < ha.time_s.size(); ++k) {
    ASSERT_EQ(ha.time_s[k], hb.time_s[k]) << what << ", sample " << k;
    ASSERT_EQ(ha.impactor_velocity_m_s[k], hb.impactor_velocity_m_s[k]) << what << ", sample " << k;
    ASSERT_EQ(ha.impactor_displacement_m[k], hb.impactor_displacement_m[k]) << what << ", sample " << k;
    ASSERT_EQ(ha.kinetic_j[k], hb.kinetic_j[k]) << what << ", sample " << k;
    ASSERT_EQ(ha.plastic_j[k], hb.plastic_j[k]) << what << ", sample " << k;
    for (std::size_t i = 0; i < ha.ring_crush_m.size(); ++i)
      ASSERT_EQ(ha.ring_crush_m[i][k], hb.ring_crush_m[i][k]) << what << ", ring " << i + 1 << ", sample " << k;
  }
  ASSERT_EQ(a.events.size(), b.events.size()) << what;
  for (std::size_t e = 0; e < a.events.size(); ++e) {
    EXPECT_EQ(a.events[e].time_s, b.events[e].time_s) << what << ", event " << e;
    EXPECT_EQ(a.events[e].kind, b.events[e].kind) << what << ", event " << e;
  }
  const auto &sa = a.outcome.statistics, &sb = b.outcome.statistics;
  EXPECT_EQ(sa.steps, sb.steps) << what;
  EXPECT_EQ(sa.rejected_steps, sb.rejected_steps) << what;
  EXPECT_EQ(sa.function_evaluations, sb.function_evaluations) << what;
  EXPECT_EQ(sa.jacobian_evaluations, sb.jacobian_evaluations) << what;
  EXPECT_EQ(sa.nonlinear_iterations, sb.nonlinear_iterations) << what;
}

}  // namespace

TEST(IdaSmallVectorOps, InertialLevel3BitIdenticalAtThreeSpeeds) {
  for (double v : {27.7, 45.0, 50.0}) {
    const auto in = hinge::testing::test30_level3_chain(v, false, true);
    auto off = hinge::testing::tight(HybridIntegrator::Ida, 1e-8, 1e-10);
    off.ida_small_vector_ops = false;
    const auto plain = simulate_level3(in, off, true);
    const auto small = simulate_level3(in, hinge::testing::tight(HybridIntegrator::Ida, 1e-8, 1e-10), true);
    EXPECT_GT(small.outcome.statistics.steps, 500) << v << " m/s";
    expect_identical(plain, small, std::to_string(v) + " m/s");
  }
}

TEST(IdaSmallVectorOps, MasslessLevel3BitIdentical) {
  const auto in = hinge::testing::test30_level3_chain(45.0, false, false);
  const auto plain = simulate_level3(in, hinge::testing::tight(HybridIntegrator::Ida, 1e-8, 1e-10), true);
  auto on = hinge::testing::tight(HybridIntegrator::Ida, 1e-8, 1e-10);
  on.ida_small_vector_ops = true;
  const auto small = simulate_level3(in, on, true);
  expect_identical(plain, small, "massless, 45 m/s");
}
