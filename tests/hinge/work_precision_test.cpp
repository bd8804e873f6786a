// Work–precision (issue verification f): the error of the final crush against a
// tight-tolerance reference falls as the tolerance falls, for both integrators, while the
// work (steps) grows. These are the data behind `ringcrush bench-hinge`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "chain_fixtures.hpp"

using namespace ringcrush::hinge;
using namespace ringcrush::hinge::testing;

namespace {

double max_error(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

class WorkPrecision : public ::testing::TestWithParam<std::tuple<int, HybridIntegrator>> {};

TEST_P(WorkPrecision, ErrorFallsWithTheTolerance) {
  const auto [level, integrator] = GetParam();
  const auto in = test30_chain(ChainJoint::Plates);
  auto simulate = [&](HybridIntegrator i, double rtol) {
    const auto o = tight(i, rtol, rtol * 1e-2);
    return level == 0 ? simulate_level0(in, o) : simulate_level1(in, o);
  };
  // Reference: the other integrator at a tighter tolerance still.
  const auto reference = simulate(HybridIntegrator::Odeint, 1e-12).final_permanent_crush_m;
  std::vector<double> errors;
  std::vector<long> steps;
  for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    const auto r = simulate(integrator, rtol);
    errors.push_back(max_error(r.final_permanent_crush_m, reference));
    steps.push_back(r.outcome.statistics.steps);
  }
  const double scale = *std::max_element(reference.begin(), reference.end());
  EXPECT_LT(errors[3], errors[0]);
  EXPECT_LT(errors[3], errors[1]);
  EXPECT_LT(errors[3] / scale, 1e-6);
  EXPECT_LT(errors[2] / scale, 1e-4);
  EXPECT_LT(steps[0], steps[3]);
}

INSTANTIATE_TEST_SUITE_P(Levels, WorkPrecision,
                         ::testing::Combine(::testing::Values(0, 1),
                                            ::testing::Values(HybridIntegrator::Ida, HybridIntegrator::Odeint)),
                         [](const auto& param_info) {
                           // Appended, not `"L" + ...`: GCC 12's -Wrestrict false positive.
                           std::string name = "L";
                           name += std::to_string(std::get<0>(param_info.param));
                           name += '_';
                           name += to_string(std::get<1>(param_info.param));
                           return name;
                         });

}  // namespace
