// End to end: `ringcrush fe SCENE -o DIR` on a short static crush writes the DESIGN.md
// results (summary.json, history.csv, SVG, ParaView frames); a solve that fails exits 1
// with a diagnosis and leaves no results directory.
#include <gtest/gtest.h>

#include "command_run.hpp"
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include "test_files.hpp"

namespace fs = std::filesystem;

namespace {
using cli_testing::CommandRun;
using cli_testing::ringcrush;

fs::path scratch(const std::string& name) { return test_files::scratch_dir("ringcrush_fe_cli_test_", name); }

// The thesis scene with some keys replaced (crush, output frames...).
fs::path scene_variant(const fs::path& dir, const std::vector<std::pair<std::string, std::string>>& repl) {
  std::ifstream in(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_static.toml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  for (const auto& [pattern, value] : repl) text = std::regex_replace(text, std::regex(pattern), value);
  const fs::path p = dir / "scene.toml";
  std::ofstream(p) << text;
  return p;
}
}  // namespace

TEST(FeCli, StaticRunWritesTheResultsDirectory) {
  const fs::path dir = scratch("ok");
  const fs::path scene = scene_variant(dir, {{"crush_m = 0\\.046", "crush_m = 0.012"}, {"frames = 20", "frames = 3"}});
  const fs::path out = dir / "out";
  const auto r = ringcrush("fe " + scene.string() + " -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"summary.json", "history.csv", "load_deflection.svg", "series.pvd", "frames/frame_0000.vtu",
                        "frames/frame_0003.vtu"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  nlohmann::json s;
  std::ifstream(out / "summary.json") >> s;
  EXPECT_EQ(s["model"], "fe");
  EXPECT_EQ(s["analysis"], "static");
  EXPECT_EQ(s["scene"], "scene");
  EXPECT_NEAR(s["final_deflection_m"].get<double>(), 0.012, 1e-12);
  EXPECT_GT(s["max_force_N"].get<double>(), 300.0);
  EXPECT_LT(s["max_force_N"].get<double>(), 500.0);
  EXPECT_GT(s["steps"].get<int>(), 5);
  EXPECT_GT(s["wall_time_s"].get<double>(), 0.0);
  std::ifstream h(out / "history.csv");
  std::string header;
  std::getline(h, header);
  EXPECT_EQ(header.rfind("deflection_m,force_N,", 0), 0u) << header;
  const std::string vtu = (std::stringstream() << std::ifstream(out / "frames/frame_0003.vtu").rdbuf()).str();
  for (const char* field : {"displacement", "PEEQ", "Mises", "contact_pressure"})
    EXPECT_NE(vtu.find(std::string("Name=\"") + field + "\""), std::string::npos) << field;
  const std::string svg = (std::stringstream() << std::ifstream(out / "load_deflection.svg").rdbuf()).str();
  EXPECT_NE(svg.find("DeRuntz"), std::string::npos);
  EXPECT_NE(svg.find("Redwood"), std::string::npos);
}

TEST(FeCli, FailedSolveExitsOneWithDiagnosisAndNoResults) {
  const fs::path dir = scratch("fail");
  const fs::path scene = scene_variant(
      dir, {{"ptol_N = 6\\.0", "ptol_N = 1e-9\nmax_iterations = 2\nmin_increment = 0.001\nmax_increment = 0.05"},
            {"initial_increment = 0\\.001", "initial_increment = 0.05"}});
  const fs::path out = dir / "out";
  const auto r = ringcrush("fe " + scene.string() + " -o " + out.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("residual"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string().find("out"), std::string::npos) << e.path();
}

TEST(FeCli, UnsupportedSceneIsRejected) {
  const fs::path dir = scratch("bad");
  const fs::path scene = scene_variant(dir, {{"section = \"plane_stress\"", "section = \"plane_strain\""}});
  const auto r = ringcrush("fe " + scene.string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("plane"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}
