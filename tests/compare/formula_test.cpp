// The formula table built from a scene matches the closed forms it is made of.
#include "compare/formula.hpp"

#include <gtest/gtest.h>

using namespace ringcrush::compare;

TEST(Formula, ThesisRingFromItsScene) {
  const Scene s = load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_static.toml");
  FormulaInput in = formula_input(s);
  EXPECT_DOUBLE_EQ(in.yield_stress_pa, 273e6);
  EXPECT_NEAR(in.hardening_modulus_pa, 47e6 / 0.02113, 1.0);  // slope of the table
  const FormulaResult r = evaluate_formula(in, 21);
  EXPECT_NEAR(r.plastic_moment_nm, 2.184, 1e-9);
  EXPECT_NEAR(r.collapse_load_n, 355.122, 1e-3);
  EXPECT_NEAR(r.elastic_stiffness_n_m, 389.130e3, 1.0);
  EXPECT_NEAR(r.lock_deflection_m, 0.0476, 1e-12);
  EXPECT_NEAR(r.dh_energy_to_lock_j, 22.977, 1e-3);
  ASSERT_EQ(r.curves.rows.size(), 21u);
  EXPECT_EQ(r.curves.columns[0], "deflection_m");
  EXPECT_EQ(r.curves.columns[3], "force_redwood_alpha_0.5_N");
  // Every curve starts at P0 and rises; the last row is the lock-up deflection.
  for (std::size_t c = 2; c < 6; ++c) EXPECT_NEAR(r.curves.rows.front()[c], r.collapse_load_n, 1e-9);
  EXPECT_NEAR(r.curves.rows.back()[0], r.lock_deflection_m, 1e-15);
  EXPECT_NEAR(r.curves.rows.back()[2], 1403.93, 0.01);
  // Redwood with a short hinge (α = 0.5) hardens most.
  EXPECT_GT(r.curves.rows.back()[3], r.curves.rows.back()[4]);
  EXPECT_GT(r.curves.rows.back()[4], r.curves.rows.back()[5]);
}

TEST(Formula, PlaneStrainRaisesTheLoadBy2OverRoot3) {
  const Scene s = load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test03.toml");
  FormulaInput in = formula_input(s);
  const double p_stress = evaluate_formula(in).collapse_load_n;
  in.state = ringcrush::hinge::SectionState::PlaneStrain;
  const double p_strain = evaluate_formula(in).collapse_load_n;
  EXPECT_NEAR(p_stress, 2845.6, 0.1);
  EXPECT_NEAR(p_strain / p_stress, 2.0 / std::sqrt(3.0), 1e-12);
}

TEST(Formula, RejectsDegenerateRequests) {
  const Scene s = load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_static.toml");
  FormulaInput in = formula_input(s);
  EXPECT_THROW(evaluate_formula(in, 1), std::invalid_argument);
  in.alphas.clear();
  EXPECT_THROW(evaluate_formula(in), std::invalid_argument);
}
