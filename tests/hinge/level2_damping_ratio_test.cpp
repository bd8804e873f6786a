// Level 2's Kelvin–Voigt damping ratios as scene keys (issue 7 (d)): [hinge]
// membrane_damping_ratio and hinge_damping_ratio reach the polygon chain on every integrator,
// and unset they are Level2Settings' defaults.
#include <gtest/gtest.h>

#include <string>

#include "compare/hinge_run_2d.hpp"
#include "compare/scene.hpp"
#include "minimal_scene.hpp"

using namespace ringcrush::compare;

namespace {
Scene test30_welded() {
  return load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test30_welded.toml");
}
constexpr HingeIntegrator kIntegrators[] = {HingeIntegrator::Ida, HingeIntegrator::Odeint,
                                            HingeIntegrator::CentralDifference};
}  // namespace

// ... the same on every integrator since session 18 (the central difference had its own
// 0.15 in session 16, IDA and Odeint 0.3).
TEST(Level2DampingRatio, UnsetIsTheDefault) {
  const Scene scene = test30_welded();
  for (auto integrator : kIntegrators) {
    const auto in = polygon_input(scene, level2_settings(scene, integrator));
    EXPECT_EQ(in.membrane_damping_ratio, 1.0);
    EXPECT_EQ(in.hinge_damping_ratio, 0.15);
  }
  EXPECT_EQ(Level2Settings{}.hinge_damping_ratio, 0.15);
  EXPECT_EQ(Level2Settings{}.default_relative_tolerance, 3e-4);
}

TEST(Level2DampingRatio, SceneKeysReachTheChainInput) {
  Scene scene = test30_welded();
  scene.hinge.membrane_damping_ratio = 0.0;
  scene.hinge.hinge_damping_ratio = 0.35;
  for (auto integrator : kIntegrators) {
    const auto in = polygon_input(scene, level2_settings(scene, integrator));
    EXPECT_EQ(in.membrane_damping_ratio, 0.0);
    EXPECT_EQ(in.hinge_damping_ratio, 0.35);
  }
}

// Through the scene text as well: the keys parse into the settings summary.json echoes.
TEST(Level2DampingRatio, SceneTextSetsTheSettings) {
  const std::string text = test_scenes::minimal_dynamic + "[hinge]\nlevel = 2\nmembrane_damping_ratio = 0.5\nhinge_damping_ratio = 0.125\n";
  const Scene scene = parse_scene(text, "damping.toml");
  const Level2Settings s = level2_settings(scene, HingeIntegrator::CentralDifference);
  EXPECT_EQ(s.membrane_damping_ratio, 0.5);
  EXPECT_EQ(s.hinge_damping_ratio, 0.125);
}
