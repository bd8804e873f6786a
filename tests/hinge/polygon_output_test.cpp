// Level 2 through the Scene runner on a short run (two Test 30 rings, the first 0.4 ms):
// the RunResult contract (histories, per-ring measures, hinge map, events) and the shape
// outputs of issue 7 item 4 (ParaView polylines over time, final-shape SVG).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "compare/hinge_run_2d.hpp"
#include "compare/shape_output.hpp"
#include "compare/results_dir.hpp"
#include "compare/scene.hpp"

using namespace ringcrush::compare;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

Scene short_scene() {
  const fs::path file = fs::path(RINGCRUSH_SOURCE_DIR) / "data/scenes/test30_welded.toml";
  std::string text = read(file);
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("count = 6", "count = 2");
  replace("end_time_s = 0.05", "end_time_s = 0.0004");
  return parse_scene(text, file.string());
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(PolygonOutput, RunResultAndShapeFiles) {
  Scene scene = short_scene();
  scene.outputs.frames = 5;
  HingeRunOptions o;
  o.level = "2";
  o.relative_tolerance = 1e-8;  // below Level 2's floor: raised and reported
  const auto run = run_level2(scene, o);
  const auto& r = run.result;
  EXPECT_EQ(r.model, "hinge");
  EXPECT_DOUBLE_EQ(run.relative_tolerance_used, Level2Settings{}.default_relative_tolerance);
  EXPECT_TRUE(r.extra.contains("note"));
  ASSERT_EQ(r.ring_crush_m.size(), 2u);
  const auto n = r.time_s.size();
  EXPECT_GT(n, 10u);
  EXPECT_DOUBLE_EQ(r.time_s.front(), 0.0);
  EXPECT_NEAR(r.time_s.back(), 4e-4, 1e-12);
  for (const auto* h : {&r.impactor_displacement_m, &r.impactor_velocity_m_s, &r.impactor_force_n,
                        &r.kinetic_j, &r.elastic_j, &r.plastic_j, &r.contact_j, &r.numerical_j,
                        &r.external_work_j, &r.ring_crush_m[0], &r.ring_crush_m[1]})
    EXPECT_EQ(h->size(), n);
  EXPECT_NEAR(r.impactor_velocity_m_s.front(), 27.7, 1e-12);
  EXPECT_NEAR(r.ring_crush_m[0].front(), 0.0, 1e-9);
  EXPECT_GT(r.ring_crush_m[0].back(), 1e-3);  // ring 1 is being crushed at 0.4 ms
  ASSERT_EQ(r.crush_ratio.size(), 2u);
  ASSERT_EQ(r.wrap_around.size(), 2u);
  ASSERT_EQ(r.inverted_arc_m.size(), 2u);
  ASSERT_EQ(run.hinge_map.size(), 2u);
  EXPECT_GE(run.hinge_map[0].first_yield_s, 0.0);
  ASSERT_FALSE(r.events.empty());
  EXPECT_EQ(r.events.front().kind, "hinge_formed");
  EXPECT_EQ(r.events.front().ring, 0);

  ASSERT_EQ(r.shape_frames.size(), 5u);  // scene.outputs.frames, first and last sample included
  EXPECT_DOUBLE_EQ(r.shape_frames.front().time_s, 0.0);
  EXPECT_NEAR(r.shape_frames.back().time_s, 4e-4, 1e-12);
  ASSERT_EQ(r.shape_frames.back().rings.size(), 2u);
  EXPECT_EQ(r.shape_frames.back().rings[0].size(), 48u);

  const fs::path dir = fs::temp_directory_path() / ("ringcrush_polygon_output_" + std::to_string(::getpid()));
  {
    ResultsDir out(dir);
    write_shape_frames(r, out);
    write_final_shapes_svg(r, scene, out);
    out.commit();
  }
  const std::string pvd = read(dir / "shapes.pvd");
  EXPECT_EQ(count(pvd, "<DataSet"), 5);
  ASSERT_TRUE(fs::exists(dir / "frames/shape_0004.vtp"));
  const std::string vtp = read(dir / "frames/shape_0000.vtp");
  // Two rings (closed polylines of N = 48 points) and the impactor and target faces.
  EXPECT_NE(vtp.find("NumberOfPoints=\"100\""), std::string::npos);
  EXPECT_NE(vtp.find("NumberOfLines=\"4\""), std::string::npos);
  EXPECT_NE(vtp.find("Name=\"plastic_rotation\""), std::string::npos);
  const std::string svg = read(dir / "shapes_final.svg");
  EXPECT_EQ(count(svg, "<polygon"), 4);  // undeformed and final, two rings
  EXPECT_NE(svg.find("ring 1: c = "), std::string::npos);
  fs::remove_all(dir);
}

TEST(ShapeOutput, FrameSamplesAreEvenFirstAndLastIncludedWithoutRepeats) {
  EXPECT_TRUE(frame_samples(100, 0).empty());  // outputs.frames = 0: no shapes kept
  EXPECT_TRUE(frame_samples(0, 5).empty());
  EXPECT_EQ(frame_samples(100, 1), (std::vector<std::size_t>{99}));
  EXPECT_EQ(frame_samples(9, 5), (std::vector<std::size_t>{0, 2, 4, 6, 8}));
  EXPECT_EQ(frame_samples(3, 10), (std::vector<std::size_t>{0, 1, 2}));
}

TEST(PolygonOutput, NoFieldsKeepsNoShapes) {
  Scene scene = short_scene();
  scene.outputs.fields = false;
  HingeRunOptions o;
  o.level = "2";
  EXPECT_TRUE(run_level2(scene, o).result.shape_frames.empty());
}
