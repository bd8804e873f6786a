// Level 2 on the thesis's Test 30 chains (six rings, 0.257 kg at 27.7 m/s, fixed target),
// issue 7 verification d and e, through the Scene runner (compare/hinge_run_2d):
//   d. welded and free: ring 1 wraps around ring 2 (flag decided on the inverted arc S; the
//      welded chain also has W > 45° at arrest, the free one bridges over ring 2's apex
//      where W reads 0), ring 2 does not wrap, and the crush alternates (alternation index above the threshold
//      documented with compare/measures); plated: no ring wraps and no alternation;
//   e. hinge map: ring 1 has plastic-rotation peaks at A (0°), C (90°) and B (180°); ring 2,
//      under the wrapped ring 1, has peaks at C and B, none at A and a weaker one at E
//      (30–60°) (thesis §4.2.3, THEORY §4.1). Tolerance ±11.25° = 1.5 node spacings at N = 48: a peak is located to
//      one node (7.5°), and the thesis places its hinges only to the element (3.75°) on
//      figures we do not have.
// Each case is a full impact (~15 ms simulated, 5–8 s CPU on one core; README, Level 2 speed).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "compare/hinge_run_2d.hpp"
#include "compare/measures.hpp"
#include "compare/scene.hpp"

using namespace ringcrush::compare;

namespace {

Level2Run run_scene(const std::string& name) {
  const Scene scene = load_scene(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/" + name + ".toml");
  HingeRunOptions o;
  o.level = "2";
  o.integrator = HingeIntegrator::Ida;
  o.relative_tolerance = Level2Settings{}.default_relative_tolerance;  // the scene's default run
  return run_level2(scene, o);
}

bool has_peak_near(const RingHingeMap& m, double angle_deg, double tolerance_deg) {
  for (const auto& p : m.peaks)
    if (std::abs(p.angle_deg - angle_deg) <= tolerance_deg) return true;
  return false;
}

constexpr double hinge_tolerance_deg = 11.25;

void expect_wrap_and_alternation(const Level2Run& run) {
  const auto& r = run.result;
  ASSERT_EQ(r.crush_ratio.size(), 6u);
  EXPECT_TRUE(r.wrap_around[0]) << "S1 = " << r.inverted_arc_m[0] << " m, W1 = " << r.wrapped_angle_deg[0];
  EXPECT_FALSE(r.wrap_around[1]) << "S2 = " << r.inverted_arc_m[1] << " m";
  EXPECT_GT(r.crush_ratio[0], r.crush_ratio[1] + 0.2);
  const auto a = alternation(r.crush_ratio);
  EXPECT_GT(a.index, alternation_threshold) << "A1 = " << a.lag1;
  EXPECT_LT(run.raw.energy_balance_error, 5e-4);  // rtol 3e-4: measured 1.3–2.2e-4
  EXPECT_GT(run.raw.arrest_time_s, 0.0);
}

// Two flattened rings lying on each other also give a large W; S is what tells a wrap.
void expect_supporting_wrapped_angle(const Level2Run& run) {
  EXPECT_GT(run.result.wrapped_angle_deg[0], 45.0);
}

void expect_thesis_hinges(const Level2Run& run) {
  ASSERT_GE(run.hinge_map.size(), 2u);
  const auto& ring1 = run.hinge_map[0];
  const auto& ring2 = run.hinge_map[1];
  // A and B on ring 1 as local ā peaks of at least a fifth of the ring's largest, as E below:
  // with the calibrated ζ_b (0.3 in sessions 14–16, 0.15 since 18; Level2Settings) C's ā, the
  // largest, grows from 0.67 to 0.99 rad on the welded chain (A 0.25, B 0.23 rad at ζ_b = 1,
  // and 0.24 / 0.23 at 0.7), so A and B fall under the map's default 0.3 of it.
  const auto ring1_weak = hinge_map(run.raw.history.shapes.back(), run.raw.first_yield_time_s, 0.2)[0];
  EXPECT_TRUE(has_peak_near(ring1_weak, 0.0, hinge_tolerance_deg)) << "A on ring 1";
  EXPECT_TRUE(has_peak_near(ring1, 90.0, hinge_tolerance_deg)) << "C on ring 1";
  EXPECT_TRUE(has_peak_near(ring1_weak, 180.0, hinge_tolerance_deg)) << "B on ring 1";
  EXPECT_TRUE(has_peak_near(ring2, 90.0, hinge_tolerance_deg)) << "C on ring 2";
  EXPECT_TRUE(has_peak_near(ring2, 180.0, hinge_tolerance_deg)) << "B on ring 2";
  EXPECT_FALSE(has_peak_near(ring2, 0.0, hinge_tolerance_deg)) << "no hinge at A on ring 2";
  // ... and a weaker one at E on the upper arc instead (thesis: θ_E between A and C; THEORY
  // §4.5 gives 30–60°): a local ā peak of at least a fifth of the ring's largest.
  const auto weak = hinge_map(run.raw.history.shapes.back(), run.raw.first_yield_time_s, 0.2);
  EXPECT_TRUE(has_peak_near(weak[1], 45.0, 15.0)) << "E on ring 2";
  // Ring 1 yields first, at A, at the impact; ring 2 later.
  EXPECT_NEAR(ring1.first_yield_angle_deg, 0.0, hinge_tolerance_deg);
  EXPECT_LT(ring1.first_yield_s, ring2.first_yield_s);
}

}  // namespace

TEST(PolygonTest30, WeldedRing1WrapsRing2AndCrushAlternates) {
  const auto run = run_scene("test30_welded");
  expect_wrap_and_alternation(run);
  expect_supporting_wrapped_angle(run);
  expect_thesis_hinges(run);
}

TEST(PolygonTest30, FreeRing1WrapsRing2AndCrushAlternates) {
  const auto run = run_scene("test30_free");
  expect_wrap_and_alternation(run);
  expect_thesis_hinges(run);
}

TEST(PolygonTest30, PlatedNeitherWrapsNorAlternates) {
  const auto run = run_scene("test30_plates");
  const auto& r = run.result;
  ASSERT_EQ(r.crush_ratio.size(), 6u);
  for (std::size_t i = 0; i < r.crush_ratio.size(); ++i)
    EXPECT_FALSE(r.wrap_around[i]) << "ring " << i + 1 << " S = " << r.inverted_arc_m[i];
  EXPECT_LT(alternation(r.crush_ratio).index, alternation_threshold);
  EXPECT_LT(run.raw.energy_balance_error, 5e-4);  // rtol 3e-4: measured 1.3–2.2e-4
}
