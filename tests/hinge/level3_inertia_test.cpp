// Level 3 with ring inertia (hinge/level3_inertia.cpp; issue 7 item 2): the few-hinge chain
// with each ring's mass, a force per ring from the dynamics. Checks: the energy balance,
// Level 1 recovered when only the Uniform mode can flow, the massless chain recovered as the
// ring mass tends to zero, and the bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "chain_fixtures.hpp"
#include "level3_ring_fixtures.hpp"
#include "compare/hinge_run_level3.hpp"
#include "hinge/level3_mechanism.hpp"
#include "test_files.hpp"

using namespace ringcrush;
using namespace ringcrush::hinge;

namespace {

// Test 30's chain with its rings' mass (level3_ring_fixtures.hpp).
Level3Input test30_level3(double velocity, bool plates) {
  return hinge::testing::test30_level3_chain(velocity, plates, true);
}

}  // namespace

// Kinetic + plastic work + plastic-impact losses = ½MV² along the whole history, with the
// wrap, the ring underneath and the locks all in play (welded, 27.7 and 50 m/s).
TEST(Level3Inertia, EnergyBalance) {
  for (double v : {27.7, 50.0}) {
    const auto r = simulate_level3(test30_level3(v, false), hinge::testing::tight(HybridIntegrator::Ida));
    ASSERT_GT(r.history.time_s.size(), 10u);
    EXPECT_LE(r.energy_balance_error(), 1e-6) << v << " m/s";
    EXPECT_GT(r.impact_loss_j, 0.0);  // the first contact is a plastic impact
    EXPECT_LT(r.impact_loss_j, r.initial_kinetic_energy_j);
    EXPECT_LE(r.history.impactor_velocity_m_s.back(), 1e-6 * v);
    for (const auto& rr : r.rings) EXPECT_TRUE(std::isfinite(rr.crush_m));
  }
}

// With only the Uniform mode admissible (plated joints: no ring can wrap) the chain is Level 1
// on the same inputs (plates of zero mass): DeRuntz–Hodge/Redwood rings with J(φ), written in
// δ here and in φ there — the final crush per ring agrees to 1e-6 (relative to d).
TEST(Level3Inertia, UniformOnlyEqualsLevel1) {
  for (double v : {27.7, 45.0}) {
    auto c1 = hinge::testing::test30_chain(ChainJoint::Plates);
    c1.plate_mass_kg = 0.0;
    c1.impactor_velocity_m_s = v;
    const auto l1 = simulate_level1(c1, hinge::testing::tight(HybridIntegrator::Ida));
    const auto in = test30_level3(v, true);
    const auto l3 = simulate_level3(in, hinge::testing::tight(HybridIntegrator::Ida));
    ASSERT_EQ(l1.final_crush_m.size(), l3.rings.size());
    const double d = in.ring.mean_diameter();
    for (std::size_t i = 0; i < l3.rings.size(); ++i) {
      EXPECT_NEAR(l3.rings[i].crush_m / d, l1.final_crush_m[i] / d, 1e-6) << v << " m/s, ring " << i + 1;
      EXPECT_EQ(l3.rings[i].mode, Level3Mode::Uniform);
    }
  }
}

// Ring mass → 0 tends to the massless chain: the largest difference of final crush per ring
// falls as m_r does (measured, of d: 0.049 at Test 30's m_r, 0.0073 at m_r/10, 0.0023 at
// m_r/30, 0.0005 at m_r/100, 0.0002 at m_r/300; the massless chain 0.6081 every ring).
TEST(Level3Inertia, MasslessLimit) {
  auto in = test30_level3(27.7, false);
  auto massless = in;
  massless.inertia = false;
  const auto ref = simulate_level3(massless, hinge::testing::tight(HybridIntegrator::Ida));
  const double d = in.ring.mean_diameter(), m = in.ring_mass_kg;
  std::vector<double> worst;
  for (double scale : {1e-1, 1e-2}) {
    in.ring_mass_kg = m * scale;
    const auto r = simulate_level3(in, hinge::testing::tight(HybridIntegrator::Ida));
    double w = 0.0;
    for (std::size_t i = 0; i < r.rings.size(); ++i)
      w = std::max(w, std::abs(r.rings[i].crush_m - ref.rings[i].crush_m) / d);
    worst.push_back(w);
    EXPECT_LE(r.energy_balance_error(), 1e-6) << scale;
  }
  EXPECT_LT(worst[1], worst[0]);
  EXPECT_LT(worst[1], 2e-3);
}

// Bad input: inertia without a ring mass, a negative or NaN mass — errors naming the value;
// the scene key takes true | false only, and reaches the run.
TEST(Level3Inertia, BadInput) {
  auto in = test30_level3(27.7, false);
  in.ring_mass_kg = 0.0;
  EXPECT_THROW(simulate_level3(in, hinge::testing::tight(HybridIntegrator::Ida)), std::invalid_argument);
  in.ring_mass_kg = -1.0;
  in.inertia = false;
  try {
    in.validate();
    ADD_FAILURE() << "accepted ring_mass_kg = -1";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ring_mass_kg = -1"), std::string::npos) << e.what();
  }
  in.ring_mass_kg = std::nan("");
  EXPECT_THROW(in.validate(), std::invalid_argument);

  const std::string scene = test_files::read_text(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test30_welded.toml");
  auto text = [](const std::string& line) {
    return test_files::scene_text_with("data/scenes/test30_welded.toml", "hinge", line);
  };
  const auto on = compare::parse_scene(text("level3_inertia = true"), "t30.toml");
  EXPECT_TRUE(compare::level3_input(on, {}).inertia);
  EXPECT_GT(compare::level3_input(on, {}).ring_mass_kg, 0.0);
  EXPECT_FALSE(compare::level3_input(compare::parse_scene(scene, "t30.toml"), {}).inertia);  // the default
  try {
    compare::parse_scene(text("level3_inertia = \"yes\""), "bad.toml");
    ADD_FAILURE() << "accepted level3_inertia = \"yes\"";
  } catch (const compare::SceneError& e) {
    EXPECT_NE(e.key().find("level3_inertia"), std::string::npos) << e.key();
  }
}

// The same model on both integrators (one HybridSystem): IDA and Odeint give the same final
// crush per ring, through the wrap, the E–C–B switch and the locks at 50 m/s.
TEST(Level3Inertia, IdaAndOdeintAgree) {
  const auto in = test30_level3(50.0, false);
  const auto ida = simulate_level3(in, hinge::testing::tight(HybridIntegrator::Ida));
  const auto ode = simulate_level3(in, hinge::testing::tight(HybridIntegrator::Odeint));
  const double d = in.ring.mean_diameter();
  ASSERT_EQ(ida.rings.size(), ode.rings.size());
  for (std::size_t i = 0; i < ida.rings.size(); ++i) {
    EXPECT_NEAR(ida.rings[i].crush_m / d, ode.rings[i].crush_m / d, 1e-6) << "ring " << i + 1;
    EXPECT_EQ(ida.rings[i].mode, ode.rings[i].mode) << "ring " << i + 1;
  }
  EXPECT_TRUE(ida.rings[0].wrap_started);  // ring 1 reaches the wrap onset first at 50 m/s
}

// Speed without changing results (issue 7 item 2): the chain restarts IDA from a fraction of its
// last step and gives IDA its Jacobian in the columns f depends on. Against IDA's own first
// step (fraction 0) and, through the same model, Odeint: final crush per ring to 1e-6 d, the
// same modes, energy to 1e-6, and fewer steps at the bench's rtol (counted, not timed). A fraction outside
// [0, 1] is a named error.
TEST(Level3Inertia, IdaRestartStepKeepsTheResult) {
  const auto in = test30_level3(50.0, false);
  auto own = hinge::testing::tight(HybridIntegrator::Ida);
  own.ida_restart_step_fraction = 0.0;
  const auto ref = simulate_level3(in, own);
  const auto fast = simulate_level3(in, hinge::testing::tight(HybridIntegrator::Ida));
  const double d = in.ring.mean_diameter();
  ASSERT_EQ(ref.rings.size(), fast.rings.size());
  for (std::size_t i = 0; i < ref.rings.size(); ++i) {
    EXPECT_NEAR(fast.rings[i].crush_m / d, ref.rings[i].crush_m / d, 1e-6) << "ring " << i + 1;
    EXPECT_EQ(fast.rings[i].mode, ref.rings[i].mode) << "ring " << i + 1;
  }
  EXPECT_LE(fast.energy_balance_error(), 1e-6);
  // The steps at the bench's rtol 1e-8 (bench-level3): with the chain's step control (h48, a
  // step grows up to 100× at once) IDA's own ~1e-11 s first step costs only a few more steps
  // there (926 against 917 on this chain at 50 m/s; 2858 against 2759 steps and rejections
  // over the scene's three speeds), and none at rtol 1e-10 (1883 against 1884).
  auto bench_own = hinge::testing::tight(HybridIntegrator::Ida, 1e-8, 1e-10);
  bench_own.ida_restart_step_fraction = 0.0;
  const auto bench_ref = simulate_level3(in, bench_own, false);
  const auto bench_fast = simulate_level3(in, hinge::testing::tight(HybridIntegrator::Ida, 1e-8, 1e-10), false);
  EXPECT_LT(bench_fast.outcome.statistics.steps, bench_ref.outcome.statistics.steps);
  auto bad = own;
  bad.ida_restart_step_fraction = 2.0;
  try {
    simulate_level3(in, bad);
    ADD_FAILURE() << "accepted ida_restart_step_fraction = 2";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ida_restart_step_fraction = 2"), std::string::npos) << e.what();
  }
}
