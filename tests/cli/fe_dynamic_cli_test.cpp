// End to end: `ringcrush fe SCENE -o DIR` on a cheap dynamic scene (the thesis chain cut to
// three rings on a coarse mesh, a short end time) writes the results directory of issue 4
// item 7; the --solver and --elements-around overrides reach the run; scenes the dynamic FE
// does not cover exit 2; a run stopped by its energy limit exits 1 with the diagnosis and
// leaves no results directory; `bench-fe-dynamic --quick` writes its tables.
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

fs::path scratch(const std::string& name) { return test_files::scratch_dir("ringcrush_fe_dynamic_cli_test_", name); }

using test_files::read_text;

// The thesis dynamic chain, cheap: 3 rings, 12 elements per half ring, 0.4 ms, 3 frames.
fs::path cheap_scene(const fs::path& dir, const test_files::Edits& more = {}) {
  test_files::Edits edits{{"count = 6", "count = 3"},
                          {"elements_around = 48", "elements_around = 12"},
                          {"end_time_s = 0\\.05", "end_time_s = 0.0004"},
                          {"frames = 20", "frames = 3"},
                          {"solver = \"hht\"", "solver = \"explicit\""}};
  edits.insert(edits.end(), more.begin(), more.end());
  return test_files::edited_scene("data/scenes/thesis_dynamic.toml", dir / "scene.toml", edits);
}

std::size_t data_rows(const fs::path& csv) {
  std::ifstream in(csv);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += !line.empty();
  return n - 1;
}
}  // namespace

TEST(FeDynamicCli, CheapChainWritesTheResultsDirectory) {
  const fs::path dir = scratch("ok");
  const fs::path out = dir / "out";
  const auto r = ringcrush("fe " + cheap_scene(dir).string() + " -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"summary.json", "history.csv", "rings.csv", "series.pvd", "crush_per_ring.svg",
                        "impactor.svg", "force.svg", "energy.svg", "frames/frame_0000.vtu"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto j = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(j["model"], "fe");
  EXPECT_EQ(j["analysis"], "dynamic");
  EXPECT_EQ(j["solver"], "explicit");
  EXPECT_EQ(j["crush_ratio"].size(), 3u);
  EXPECT_EQ(j["wrap_around"].size(), 3u);
  for (const char* k : {"alternation_index", "energy_balance_error", "arrest_time_s", "peak_force_N",
                        "impactor_final_velocity_m_s", "numerical_dissipation", "end_reason"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["mesh"]["elements"], 3 * 12);
  // The impactor has hit ring 1 in 0.4 ms at 30 m/s: a force, and ring 1 crushed most.
  EXPECT_GT(j["peak_force_N"].get<double>(), 0.0);
  EXPECT_GT(j["crush_ratio"][0].get<double>(), j["crush_ratio"][2].get<double>());
  EXPECT_GE(data_rows(out / "history.csv"), 2u);
  EXPECT_EQ(data_rows(out / "rings.csv"), 3u);
  EXPECT_NE(r.output.find("explicit central difference"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("alternation index"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("end: "), std::string::npos) << r.output;
}

TEST(FeDynamicCli, OverridesReachTheRun) {
  const fs::path dir = scratch("override");
  const fs::path out = dir / "out";
  const auto r = ringcrush("fe " + cheap_scene(dir, {{"end_time_s = 0\\.0004", "end_time_s = 0.0001"}}).string() +
                           " --solver hht --elements-around 10 -q -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto j = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(j["solver"], "hht");
  EXPECT_EQ(j["mesh"]["elements"], 3 * 10);
}

// --safety reaches the explicit step (Δt = safety · 2/ω_max: half the safety, about twice the
// steps) and summary.json; outside (0, 1] it is a usage error, and a static scene refuses it
// (HHT ignores it, as it ignores the scene key).
TEST(FeDynamicCli, SafetyReachesTheExplicitStep) {
  const fs::path dir = scratch("safety");
  const std::string scene = cheap_scene(dir, {{"end_time_s = 0\\.0004", "end_time_s = 0.0001"}}).string();
  long steps[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const fs::path out = dir / (k == 0 ? "a" : "b");
    const auto r = ringcrush("fe " + scene + (k == 0 ? " --safety 0.8" : " --safety 0.4") + " -q -o " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    const auto j = nlohmann::json::parse(read_text(out / "summary.json"));
    EXPECT_DOUBLE_EQ(j["explicit_safety"].get<double>(), k == 0 ? 0.8 : 0.4);
    steps[k] = j["steps"].get<long>();
  }
  EXPECT_GT(static_cast<double>(steps[1]) / static_cast<double>(steps[0]), 1.8) << steps[0] << " " << steps[1];
  EXPECT_LT(static_cast<double>(steps[1]) / static_cast<double>(steps[0]), 2.2) << steps[0] << " " << steps[1];
  for (const char* bad : {"--safety 0", "--safety 1.5", "--safety -0.2", "--safety nan"}) {
    const auto r = ringcrush("fe " + scene + " " + bad + " -q -o " + (dir / "bad").string());
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--safety"), std::string::npos) << bad << ": " << r.output;
  }
  const auto stat = ringcrush("fe " + std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_static.toml --safety 0.5 -o " +
                              (dir / "bad").string());
  EXPECT_EQ(stat.status, 2) << stat.output;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

TEST(FeDynamicCli, RefusedScenesExitTwo) {
  const fs::path dir = scratch("refused");
  const auto friction = ringcrush("fe " + cheap_scene(dir, {{"\\[fe\\]", "[fe]\nfriction_coefficient = 0.1"}}).string() +
                                  " -o " + (dir / "out").string());
  EXPECT_EQ(friction.status, 2) << friction.output;
  EXPECT_NE(friction.output.find("friction"), std::string::npos) << friction.output;
  const auto odd = ringcrush("fe " + cheap_scene(dir).string() + " --elements-around 11 -o " + (dir / "out").string());
  EXPECT_EQ(odd.status, 2) << odd.output;
  const auto static_solver = ringcrush("fe " + std::string(RINGCRUSH_SOURCE_DIR) +
                                       "/data/scenes/thesis_static.toml --solver hht -o " + (dir / "out").string());
  EXPECT_EQ(static_solver.status, 2) << static_solver.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(FeDynamicCli, EnergyLimitStopExitsOneAndLeavesNoResults) {
  const fs::path dir = scratch("fail");
  const fs::path out = dir / "out";
  // A limit no real run meets: the driver must stop with a named reason.
  const auto r = ringcrush("fe " + cheap_scene(dir, {{"\\[fe\\]", "[fe]\nenergy_error_limit = 1e-14"}}).string() +
                           " -o " + out.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("energy"), std::string::npos) << r.output;
  // A half model: the driver's joules are said to be the half model's, the context's the chain's.
  EXPECT_NE(r.output.find("the driver's energies are the half model's"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".out.partial"), std::string::npos) << e.path();
}

TEST(FeDynamicCli, QuickBenchmarkWritesItsTables) {
  const fs::path dir = scratch("bench");
  const fs::path out = dir / "out";
  const auto r = ringcrush("bench-fe-dynamic --quick " + std::string(RINGCRUSH_SOURCE_DIR) +
                           "/data/scenes/thesis_dynamic.toml -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(data_rows(out / "thesis.csv"), 3u);     // explicit, hht, plates
  EXPECT_EQ(data_rows(out / "matrix.csv"), 6u);     // 2 drivers × 3 joints
  EXPECT_TRUE(fs::exists(out / "agreement.csv")) << r.output;
  const std::string matrix = read_text(out / "matrix.csv");
  EXPECT_FALSE(std::regex_search(matrix, std::regex("\\bnan\\b", std::regex::icase))) << matrix;
}

// --step-bound and --safety reach every explicit matrix run (and are written beside it), so
// the stability matrix can be run at the setting whose defaults are being decided; HHT runs
// keep the scene's.
TEST(FeDynamicCli, BenchStepBoundAndSafetyReachTheMatrix) {
  const fs::path dir = scratch("bench_step");
  const fs::path out = dir / "out";
  const auto r = ringcrush("bench-fe-dynamic --quick --no-thesis --filter '/welded/' --step-bound assembled "
                           "--safety 0.9 " + std::string(RINGCRUSH_SOURCE_DIR) +
                           "/data/scenes/thesis_dynamic.toml -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("explicit step: assembled bound, safety 0.9"), std::string::npos) << r.output;
  const std::string matrix = read_text(out / "matrix.csv");
  EXPECT_EQ(data_rows(out / "matrix.csv"), 2u) << matrix;  // explicit and hht, welded
  EXPECT_TRUE(std::regex_search(matrix, std::regex("\\nexplicit/welded/[^\\n]*,assembled,0\\.9,[0-9.e-]+,[0-9.e-]+\\n")))
      << matrix;
  EXPECT_TRUE(std::regex_search(matrix, std::regex("\\nhht/welded/[^\\n]*,,,[0-9.e-]+,[0-9.e-]+\\n"))) << matrix;
  EXPECT_FALSE(std::regex_search(matrix, std::regex("\\bnan\\b", std::regex::icase))) << matrix;
}

// --elements-through reaches every matrix run; without it the matrix keeps the mesh it was
// recorded on (one element through), although its base scenes (test30_*) now carry two.
TEST(FeDynamicCli, BenchElementsThroughReachesTheMatrix) {
  const fs::path dir = scratch("bench_through");
  const std::string args = "bench-fe-dynamic --quick --no-thesis --filter 'explicit/welded/' " +
                           std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_dynamic.toml -o ";
  const auto two = ringcrush(args + (dir / "two").string() + " --elements-through 2");
  ASSERT_EQ(two.status, 0) << two.output;
  EXPECT_NE(two.output.find("1 cases on 1 thread(s), 8 x 2 elements per half ring"), std::string::npos) << two.output;
  EXPECT_EQ(data_rows(dir / "two" / "matrix.csv"), 1u);
  const auto recorded = ringcrush(args + (dir / "one").string());
  ASSERT_EQ(recorded.status, 0) << recorded.output;
  EXPECT_NE(recorded.output.find("8 x 1 elements per half ring"), std::string::npos) << recorded.output;
  // Half the element depth through the wall: the explicit step shrinks, the step count grows.
  auto steps = [](const fs::path& csv) {
    std::istringstream rows(read_text(csv));
    std::string header, row, cell;
    std::getline(rows, header);
    std::getline(rows, row);
    std::istringstream cells(row);
    for (int column = 0; column <= 8; ++column) std::getline(cells, cell, ',');  // case, …, steps
    return std::stod(cell);
  };
  EXPECT_GT(steps(dir / "two" / "matrix.csv"), 1.3 * steps(dir / "one" / "matrix.csv"));
}

// Bad values are named and exit 2 before any run.
TEST(FeDynamicCli, BenchBadStepSettingsExitTwo) {
  const fs::path dir = scratch("bench_bad");
  const std::string tail = " --quick --no-thesis " + std::string(RINGCRUSH_SOURCE_DIR) +
                           "/data/scenes/thesis_dynamic.toml -o " + (dir / "out").string();
  for (const char* bad : {"--safety 1.5", "--safety 0", "--safety -0.2", "--safety nan"}) {
    const auto r = ringcrush(std::string("bench-fe-dynamic ") + bad + tail);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--safety"), std::string::npos) << bad << ": " << r.output;
  }
  for (const char* bad : {"--elements-through 0", "--elements-through -1", "--elements-through 17"}) {
    const auto r = ringcrush(std::string("bench-fe-dynamic ") + bad + tail);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--elements-through"), std::string::npos) << bad << ": " << r.output;
  }
  const auto bound = ringcrush("bench-fe-dynamic --step-bound exact" + tail);
  EXPECT_EQ(bound.status, 2) << bound.output;
  EXPECT_NE(bound.output.find("--step-bound"), std::string::npos) << bound.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}
