// Scene loading: every shipped scene is valid, and each class of bad input is rejected with
// an error that names the file, the key and the reason.
#include "compare/hinge_run_2d.hpp"
#include "compare/scene.hpp"
#include "minimal_scene.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

using namespace ringcrush::compare;
namespace fs = std::filesystem;

namespace {
const fs::path scenes = fs::path(RINGCRUSH_SOURCE_DIR) / "data" / "scenes";

// A minimal valid dynamic scene; tests edit one line of it.
const std::string base = test_scenes::minimal_dynamic;

std::string with(const std::string& from, const std::string& to) {
  const auto pos = base.find(from);
  if (pos == std::string::npos) throw std::logic_error("test scene has no " + from);
  return base.substr(0, pos) + to + base.substr(pos + from.size());
}

// Expects a SceneError whose key and reason contain the given fragments.
void expect_error(const std::string& text, const std::string& key, const std::string& reason) {
  try {
    parse_scene(text, "bad.toml");
    ADD_FAILURE() << "accepted a scene that should fail on " << key;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), "bad.toml");
    EXPECT_NE(e.key().find(key), std::string::npos) << "key was: " << e.key();
    EXPECT_NE(e.reason().find(reason), std::string::npos) << "reason was: " << e.reason();
    EXPECT_NE(std::string(e.what()).find("bad.toml"), std::string::npos);
  }
}
}  // namespace

TEST(Scene, EveryShippedSceneLoads) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(scenes)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(load_scene(entry.path()));
    ++count;
  }
  // Tests 3, 4, 7; 8, 28–31 × {welded, free, plates}; thesis static and dynamic; Test 30
  // welded at Level 3 with ring inertia.
  EXPECT_EQ(count, 3 + 5 * 3 + 2 + 1);
}

TEST(Scene, ThesisScenesCarryTheDeckSettings) {
  const Scene st = load_scene(scenes / "thesis_static.toml");
  EXPECT_EQ(st.analysis.type, AnalysisType::Static);
  EXPECT_DOUBLE_EQ(st.analysis.crush_m, 0.046);
  EXPECT_DOUBLE_EQ(st.rings.outer_diameter_m, 0.0508);
  EXPECT_DOUBLE_EQ(st.rings.wall_thickness_m, 0.0016);
  EXPECT_DOUBLE_EQ(st.fe.ptol_n, 6.0);
  ASSERT_EQ(st.rings.material.hardening.size(), 2u);
  EXPECT_DOUBLE_EQ(st.rings.material.hardening[1].yield_stress_pa, 320e6);
  EXPECT_DOUBLE_EQ(st.rings.material.hardening[1].plastic_strain, 0.02113);

  const Scene dy = load_scene(scenes / "thesis_dynamic.toml");
  EXPECT_EQ(dy.rings.count, 6);
  EXPECT_EQ(dy.joints.type, JointType::Welded);
  ASSERT_TRUE(dy.impactor);
  EXPECT_DOUBLE_EQ(dy.impactor->mass_kg, 0.256);
  EXPECT_DOUBLE_EQ(dy.impactor->velocity_m_s, 30.0);
  EXPECT_DOUBLE_EQ(dy.rings.material.density_kg_m3, 8410.0);
  EXPECT_DOUBLE_EQ(dy.fe.hht_alpha, -0.105);
  EXPECT_DOUBLE_EQ(dy.fe.haftol_n, 1e4);
  EXPECT_EQ(dy.fe.solver, FeSolver::Hht);

  const Scene t30 = load_scene(scenes / "test30_plates.toml");
  EXPECT_EQ(t30.joints.type, JointType::Plates);
  EXPECT_GT(t30.joints.plate_mass_kg, 0.0);
  EXPECT_NEAR(t30.rings.material.hardening_modulus(), 2.224e9, 1e6);
}

TEST(Scene, EveryValueCarriesAUnitOrAComment) {
  // Keys end in a unit suffix, or the line carries a comment, or the value is a word/bool.
  const std::regex unit_key(R"(^\s*\w+_(m|kg|s|Pa|N|J|m_s|kg_m3)\s*=)");
  const std::regex dimensionless(R"(^\s*(count|title|type|section|symmetry|solver|level|integrator|integration|history|fields|plots|frames|stop_at_rest|elements_around|elements_through|nodes_per_ring)\s*=)");
  for (const auto& entry : fs::directory_iterator(scenes)) {
    if (entry.path().extension() != ".toml") continue;
    std::ifstream in(entry.path());
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      if (line.find('=') == std::string::npos || line.find('#') < line.find('=')) continue;
      const bool ok = std::regex_search(line, unit_key) || std::regex_search(line, dimensionless) ||
                      line.find('#') != std::string::npos;
      EXPECT_TRUE(ok) << entry.path().filename() << ":" << n << ": " << line;
    }
  }
}

TEST(SceneErrors, UnknownKey) {
  expect_error(with("width_m = 0.0125", "width_m = 0.0125\nwidht_mm = 3"), "rings.widht_mm", "unknown key");
  expect_error(base + "\n[solver]\nx = 1\n", "solver", "unknown key");
}

TEST(SceneErrors, WrongType) {
  expect_error(with("count = 2", "count = \"two\""), "rings.count", "expected an integer, got a string");
  expect_error(with("mass_kg = 0.257", "mass_kg = \"heavy\""), "impactor.mass_kg", "expected a number");
  expect_error(with("type = \"welded\"", "type = 3"), "joints.type", "expected a string");
  expect_error("impactor = 5\n" + with("[impactor]\nmass_kg = 0.257\nvelocity_m_s = 27.7\n", ""), "impactor", "expected a table");
}

TEST(SceneErrors, MissingField) {
  expect_error(with("wall_thickness_m = 0.0016\n", ""), "rings.wall_thickness_m", "missing");
  expect_error(with("end_time_s = 0.05", ""), "analysis.end_time_s", "missing");
  expect_error(with("[impactor]\nmass_kg = 0.257\nvelocity_m_s = 27.7\n", ""), "impactor", "missing");
}

TEST(SceneErrors, ThicknessAtLeastHalfTheDiameter) {
  expect_error(with("wall_thickness_m = 0.0016", "wall_thickness_m = 0.0254"), "rings.wall_thickness_m", "t < D/2");
}

TEST(SceneErrors, NonPositiveValues) {
  expect_error(with("mass_kg = 0.257", "mass_kg = 0.0"), "impactor.mass_kg", "positive");
  expect_error(with("wall_thickness_m = 0.0016", "wall_thickness_m = -0.0016"), "rings.wall_thickness_m", "positive");
  expect_error(with("width_m = 0.0125", "width_m = 0"), "rings.width_m", "positive");
  expect_error(with("youngs_modulus_Pa = 202e9", "youngs_modulus_Pa = -1.0"), "youngs_modulus_Pa", "positive");
  expect_error(with("count = 2", "count = 0"), "rings.count", "between 1 and 1000");
}

TEST(SceneErrors, DecreasingHardeningTable) {
  expect_error(with("[[273e6, 0.0], [320e6, 0.02113]]", "[[273e6, 0.0], [250e6, 0.02]]"), "hardening[1]", "decreases");
  expect_error(with("[[273e6, 0.0], [320e6, 0.02113]]", "[[273e6, 0.0], [320e6, 0.0]]"), "hardening[1]", "increase strictly");
  expect_error(with("[[273e6, 0.0], [320e6, 0.02113]]", "[[273e6, 0.01]]"), "hardening[0]", "plastic strain 0");
  expect_error(with("[[273e6, 0.0], [320e6, 0.02113]]", "[]"), "hardening", "at least one");
}

TEST(SceneErrors, ZeroVelocityForAnImpact) {
  expect_error(with("velocity_m_s = 27.7", "velocity_m_s = 0.0"), "impactor.velocity_m_s", "positive speed");
}

TEST(SceneErrors, NonFiniteNumbers) {
  expect_error(with("mass_kg = 0.257", "mass_kg = nan"), "impactor.mass_kg", "finite");
  expect_error(with("end_time_s = 0.05", "end_time_s = inf"), "analysis.end_time_s", "finite");
}

TEST(SceneErrors, UnknownChoice) {
  expect_error(with("type = \"welded\"", "type = \"glued\""), "joints.type", "not one of");
  expect_error(with("type = \"dynamic\"", "type = \"quasi\""), "analysis.type", "not one of");
}

TEST(SceneErrors, InconsistentCombinations) {
  expect_error(with("type = \"welded\"", "type = \"plates\""), "joints.plate_mass_kg", "missing");
  expect_error(with("type = \"welded\"", "type = \"welded\"\nplate_mass_kg = 0.01"), "joints.plate_mass_kg", "only meaningful");
  expect_error(with("width_m = 0.0125", "width_m = 0.0125\npitch_m = 0.04"), "rings.pitch_m", "overlap");
  expect_error(base + "\n[fe]\nsolver = \"static\"\n", "fe.solver", "static");
  expect_error(base + "\n[fe]\nhht_alpha = 0.2\n", "fe.hht_alpha", "[-1/3, 0]");
}

TEST(SceneErrors, NotToml) {
  expect_error("[rings\ncount = 1", "line 1", "not valid TOML");
  expect_error(std::string("\x01\x02\xff binary", 10), "line", "not valid TOML");
}

TEST(SceneErrors, MissingFile) {
  EXPECT_THROW(load_scene("/nonexistent/scene.toml"), SceneError);
}

TEST(SceneErrors, Level2StiffTermScales) {
  for (const char* key : {"level2_membrane_stiffness_scale", "level2_penalty_stiffness_scale"})
    for (const char* bad : {"0.0", "-0.25", "1.5", "nan"})
      expect_error(base + "\n[hinge]\n" + key + " = " + bad + "\n", std::string("hinge.") + key,
                   std::string(bad) == "nan" ? "finite" : "(0, 1]");
  const Scene s = parse_scene(
      base + "\n[hinge]\nlevel2_membrane_stiffness_scale = 0.25\nlevel2_penalty_stiffness_scale = 0.0625\n", "ok.toml");
  EXPECT_EQ(s.hinge.level2_membrane_stiffness_scale, 0.25);
  EXPECT_EQ(s.hinge.level2_penalty_stiffness_scale, 0.0625);
  const Scene d = parse_scene(base, "ok.toml");
  EXPECT_FALSE(d.hinge.level2_membrane_stiffness_scale.has_value());  // the integrator's default
  EXPECT_FALSE(d.hinge.level2_penalty_stiffness_scale.has_value());
}

TEST(SceneErrors, Level2DampingRatios) {
  for (const char* key : {"membrane_damping_ratio", "hinge_damping_ratio"}) {
    for (const char* bad : {"-0.1", "-1e-12"})
      expect_error(base + "\n[hinge]\n" + key + " = " + bad + "\n", std::string("hinge.") + key, ">= 0");
    for (const char* bad : {"nan", "inf", "-inf"})
      expect_error(base + "\n[hinge]\n" + key + " = " + bad + "\n", std::string("hinge.") + key, "finite");
    expect_error(base + "\n[hinge]\n" + key + " = \"low\"\n", std::string("hinge.") + key, "expected a number");
  }
  const Scene s = parse_scene(base + "\n[hinge]\nmembrane_damping_ratio = 0\nhinge_damping_ratio = 0.25\n", "ok.toml");
  EXPECT_EQ(s.hinge.membrane_damping_ratio, 0.0);  // 0 is allowed: no damper
  EXPECT_EQ(s.hinge.hinge_damping_ratio, 0.25);
  const Scene d = parse_scene(base, "ok.toml");
  EXPECT_FALSE(d.hinge.membrane_damping_ratio.has_value());  // Level2Settings' default
  EXPECT_FALSE(d.hinge.hinge_damping_ratio.has_value());
}

// The Level 2 hinge flow law's D and q (compare/hinge_run_2d.hpp Level2Settings; README "FE
// against the hinge model", session 15): D > 0 and q >= 1, unset the Perzyna default.
TEST(SceneErrors, Level2FlowLaw) {
  for (const char* bad : {"0", "-1e4"})
    expect_error(base + "\n[hinge]\nlevel2_flow_rate_per_s = " + bad + "\n", "hinge.level2_flow_rate_per_s",
                 "positive");
  for (const char* bad : {"0.5", "-2", "0"})
    expect_error(base + "\n[hinge]\nlevel2_flow_exponent = " + bad + "\n", "hinge.level2_flow_exponent", ">= 1");
  for (const char* key : {"level2_flow_rate_per_s", "level2_flow_exponent"}) {
    expect_error(base + "\n[hinge]\n" + key + " = nan\n", std::string("hinge.") + key, "finite");
    expect_error(base + "\n[hinge]\n" + key + " = \"fast\"\n", std::string("hinge.") + key, "expected a number");
  }
  const Scene s = parse_scene(base + "\n[hinge]\nlevel2_flow_rate_per_s = 40.4\nlevel2_flow_exponent = 5\n", "ok.toml");
  EXPECT_EQ(s.hinge.level2_flow_rate_per_s, 40.4);
  EXPECT_EQ(s.hinge.level2_flow_exponent, 5.0);
  const Level2Settings l2 = level2_settings(s, HingeIntegrator::CentralDifference);
  EXPECT_EQ(l2.flow_d_per_s, 40.4);
  EXPECT_EQ(l2.flow_q, 5.0);
  const Scene d = parse_scene(base, "ok.toml");
  EXPECT_FALSE(d.hinge.level2_flow_rate_per_s.has_value());
  EXPECT_FALSE(d.hinge.level2_flow_exponent.has_value());
  EXPECT_EQ(level2_settings(d, HingeIntegrator::Ida).flow_d_per_s, Level2Settings{}.flow_d_per_s);
  EXPECT_EQ(level2_settings(d, HingeIntegrator::Ida).flow_q, Level2Settings{}.flow_q);
}
