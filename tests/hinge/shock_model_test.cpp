// The Reid–Bell–Barr r-p-p-l shock model (THEORY §3.2): closed form against the integrated
// ODE on both integrators (issue verification c), and THEORY §5 checks #20–#22.
#include <gtest/gtest.h>

#include <cmath>

#include "chain_fixtures.hpp"
#include "hinge/shock_model.hpp"

using namespace ringcrush::hinge;
using namespace ringcrush::hinge::testing;

namespace {

ShockInput test30(double plateau) {
  ShockInput in;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = 27.7;
  in.plateau_force_n = plateau;
  in.locking_strain = 47.6 / 50.8;
  in.mass_per_length_kg_m = 0.477695;
  in.pitch_m = 0.0508;
  in.rings = 6;
  return in;
}

TEST(ShockModel, ClosedFormReproducesTheory20And21) {
  const auto a = shock_closed_form(test30(482.7));  // #20
  EXPECT_NEAR(a.locked_rings, 3.66, 0.005);
  EXPECT_NEAR(a.arrest_position_m, 0.1858, 0.0005);
  EXPECT_NEAR(a.arrest_time_s, 14.75e-3, 0.005e-3);
  EXPECT_NEAR(a.initial_load_n, 874.0, 0.5);
  EXPECT_NEAR(a.characteristic_velocity_m_s, 30.8, 0.05);
  EXPECT_FALSE(a.reaches_far_end);
  const auto b = shock_closed_form(test30(355.1));  // #21
  EXPECT_NEAR(b.locked_rings, 4.76, 0.005);
  EXPECT_NEAR(b.arrest_time_s, 20.05e-3, 0.005e-3);
  EXPECT_NEAR(b.initial_load_n, 746.0, 0.5);
  // From the ring law: P_c = W_DH(lock)/δ_L.
  const auto c = ShockInput::from_ring(test30_ring(0.0), 6, 0.257, 27.7, ChainFarEnd::Fixed);
  EXPECT_NEAR(c.plateau_force_n, 482.7, 0.05);
  EXPECT_NEAR(c.locking_strain, 0.93701, 1e-5);
  EXPECT_NEAR(c.mass_per_length_kg_m, 0.477695, 1e-5);
}

class ShockIntegrated : public ::testing::TestWithParam<HybridIntegrator> {};

TEST_P(ShockIntegrated, AgreesWithTheClosedFormTo1e6) {
  const auto in = test30(482.7);
  const auto exact = shock_closed_form(in);
  const auto run = integrate_shock(in, tight(GetParam()));
  ASSERT_GT(run.arrest_time_s, 0.0);
  EXPECT_NEAR(run.arrest_time_s / exact.arrest_time_s, 1.0, 1e-6);
  EXPECT_NEAR(run.front_position_m.back() / exact.arrest_position_m, 1.0, 1e-6);
  EXPECT_NEAR(run.impactor_force_n.front() / exact.initial_load_n, 1.0, 1e-9);
  for (std::size_t k = 0; k < run.time_s.size(); k += 5) {
    const double v = exact.velocity_at(run.front_position_m[k]);
    if (v > 1.0) {
      EXPECT_NEAR(run.velocity_m_s[k] / v, 1.0, 1e-6);
    }
  }
  EXPECT_LT(run.energy_balance_error(), 1e-8);
  // Step distribution: 3 rings locked, the 4th at 0.66, the rest untouched.
  EXPECT_NEAR(run.final_crush_m[0], 0.0476, 1e-9);
  EXPECT_NEAR(run.final_crush_m[3] / 0.0476, 0.659, 0.002);
  EXPECT_EQ(run.final_crush_m[4], 0.0);
}

TEST_P(ShockIntegrated, FreeEndKeepsEnergyAndMomentum) {
  auto in = test30(482.7);
  in.far_end = ChainFarEnd::Free;
  const auto run = integrate_shock(in, tight(GetParam()));
  EXPECT_LT(run.energy_balance_error(), 1e-8);
  ASSERT_GT(run.arrest_time_s, 0.0);
  // At arrest everything moves at one velocity: (M + μ N D) v = M V.
  const double total = in.impactor_mass_kg + in.mass_per_length_kg_m * in.rings * in.pitch_m;
  EXPECT_NEAR(run.velocity_m_s.back(), in.impactor_mass_kg * in.impactor_velocity_m_s / total, 1e-5);
  EXPECT_NEAR(run.velocity_m_s.back(), run.far_velocity_m_s.back(), 1e-6);
  // Less is crushed than with a fixed end.
  EXPECT_LT(run.front_position_m.back(), shock_closed_form(test30(482.7)).arrest_position_m);
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, ShockIntegrated,
                         ::testing::Values(HybridIntegrator::Ida, HybridIntegrator::Odeint),
                         [](const auto& param_info) { return to_string(param_info.param); });

TEST(ShockModel, DiscreteSequentialReproducesTheory22) {
  const double mr = 0.024267;
  const auto d = discrete_shock(6, 482.7, 0.0476, mr, 0.257 + mr / 2, 27.7);
  const double expected[] = {47.6, 47.6, 47.6, 45.8, 0.0, 0.0};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(d.crush_m[i] * 1e3, expected[i], 0.05) << "ring " << i + 1;
  EXPECT_NEAR(d.arrest_time_s, 15.44e-3, 0.01e-3);
  // energy: ½ m0 V² = plastic + impact losses
  EXPECT_NEAR(d.plastic_j + d.impact_loss_j + d.final_kinetic_j, 0.5 * (0.257 + mr / 2) * 27.7 * 27.7, 1e-9);
}

}  // namespace
