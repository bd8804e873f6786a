// End-to-end tests of `ringcrush compare` (issue 8 item 2): both models on a small chain,
// the results directory, the exit status against the verdict, and the FE result cache (a
// rerun is served from the cache; a changed scene is not).
#include <gtest/gtest.h>

#include "command_run.hpp"
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
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

CommandRun ringcrush(const std::string& args, const fs::path& cache) {
  return cli_testing::ringcrush(args, "RINGCRUSH_CACHE_DIR='" + cache.string() + "'");
}

fs::path scratch(const std::string& name) { return test_files::scratch_dir("ringcrush_compare_cli_", name); }

std::string read(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Test 30 (welded) cut down to three coarse rings and 2 ms, hinge level 1: seconds per run.
fs::path small_scene(const fs::path& dir, double velocity) {
  std::string text = read(std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/test30_welded.toml");
  auto set = [&text](const std::string& key, const std::string& value) {
    const std::regex line("(^|\n)" + key + " *=[^\n]*");
    ASSERT_TRUE(std::regex_search(text, line)) << key;
    text = std::regex_replace(text, line, "$1" + key + " = " + value, std::regex_constants::format_first_only);
  };
  set("count", "3");
  set("elements_around", "12");
  set("velocity_m_s", std::to_string(velocity));
  set("end_time_s", "0.002");
  set("stop_at_rest", "false");
  set("level", "1");
  set("fields", "false");
  fs::create_directories(dir);
  const fs::path f = dir / "small_chain.toml";
  std::ofstream(f) << text;
  return f;
}
}  // namespace

TEST(CompareCli, WritesTheReportAndServesTheFeFromTheCache) {
  const fs::path dir = scratch("cache"), cache = dir / "cache";
  const fs::path scene = small_scene(dir, 27.7);

  const CommandRun first = ringcrush("compare " + scene.string() + " -o " + (dir / "a").string(), cache);
  ASSERT_TRUE(first.status == 0 || first.status == 3) << first.output;
  for (const char* f : {"summary.json", "report.html", "crush_compare.svg", "fe/summary.json", "fe/history.csv",
                        "fe/rings.csv", "fe/run_result.json", "hinge/summary.json"})
    EXPECT_TRUE(fs::exists(dir / "a" / f)) << f;
  const auto s = nlohmann::json::parse(read(dir / "a" / "summary.json"));
  EXPECT_EQ(s["model"], "compare");
  EXPECT_EQ(s["agreement"]["verdicts"].size(), 6u);
  EXPECT_EQ(s["agreement"]["rings"].size(), 3u);
  // The exit status is the verdict.
  EXPECT_EQ(first.status == 0, s["agreement"]["agree"].get<bool>());
  EXPECT_EQ(first.output.find("from the cache"), std::string::npos);
  EXPECT_NE(first.output.find("report:"), std::string::npos);
  EXPECT_EQ(read(dir / "a" / "report.html").find("nan"), std::string::npos);

  const CommandRun second = ringcrush("compare " + scene.string() + " -o " + (dir / "b").string(), cache);
  EXPECT_EQ(second.status, first.status);
  EXPECT_NE(second.output.find("from the cache"), std::string::npos) << second.output;
  const auto s2 = nlohmann::json::parse(read(dir / "b" / "summary.json"));
  EXPECT_EQ(s2["fe"]["crush_ratio"], s["fe"]["crush_ratio"]);
  EXPECT_TRUE(s2["fe"]["from_cache"].get<bool>());

  // A changed scene is never served stale.
  const fs::path changed = small_scene(dir / "changed", 20.0);
  const CommandRun third = ringcrush("compare " + changed.string() + " -o " + (dir / "c").string(), cache);
  ASSERT_TRUE(third.status == 0 || third.status == 3) << third.output;
  EXPECT_EQ(third.output.find("from the cache"), std::string::npos);
  const auto s3 = nlohmann::json::parse(read(dir / "c" / "summary.json"));
  EXPECT_NE(s3["fe"]["crush_ratio"], s["fe"]["crush_ratio"]);
}

TEST(CompareCli, StaticScenesAreRefusedAndWriteNothing) {
  const fs::path dir = scratch("static");
  const CommandRun r = ringcrush("compare " + std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_static.toml -o " +
                                     (dir / "out").string(),
                                 dir / "cache");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("dynamic"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Issue 8 verification f: a scene that asks for no fields writes no frames, and its summary
// numbers equal those of the same scene asking for frames (frames are output, not physics).
TEST(FeOutputs, NoFieldsWritesNoFramesAndTheSameSummary) {
  const fs::path dir = scratch("fields");
  const fs::path without = small_scene(dir / "without", 27.7);  // outputs.fields = false
  std::string text = read(without);
  text = std::regex_replace(text, std::regex("(^|\n)fields = false"), "$1fields = true");
  fs::create_directories(dir / "with");
  const fs::path with = dir / "with" / "small_chain.toml";
  std::ofstream(with) << text;
  ASSERT_EQ(ringcrush("fe " + without.string() + " -q -o " + (dir / "a").string(), dir / "cache").status, 0);
  ASSERT_EQ(ringcrush("fe " + with.string() + " -q -o " + (dir / "b").string(), dir / "cache").status, 0);
  EXPECT_FALSE(fs::exists(dir / "a" / "frames"));
  EXPECT_FALSE(fs::exists(dir / "a" / "series.pvd"));
  EXPECT_TRUE(fs::exists(dir / "b" / "series.pvd"));
  const auto a = nlohmann::json::parse(read(dir / "a" / "summary.json"));
  const auto b = nlohmann::json::parse(read(dir / "b" / "summary.json"));
  for (const char* key : {"crush_ratio", "wrap_around", "wrapped_angle_deg", "alternation_index", "peak_force_N",
                          "impactor_final_velocity_m_s", "energy_balance_error", "steps"})
    EXPECT_EQ(a[key], b[key]) << key;
}
