// End-to-end tests of the `ringcrush` command line: help, usage errors, the formula run and
// its results directory, and bad scenes that must exit non-zero and write nothing.
#include <gtest/gtest.h>

#include "command_run.hpp"
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include "test_files.hpp"

namespace fs = std::filesystem;

namespace {
using cli_testing::CommandRun;
using cli_testing::ringcrush;

const std::string scenes = std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/";

fs::path scratch(const std::string& name) { return test_files::scratch_dir("ringcrush_cli_test_", name); }

bool empty_dir(const fs::path& p) { return fs::is_empty(p); }
}  // namespace

TEST(Cli, HelpListsTheSubcommands) {
  const CommandRun r = ringcrush("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("formula"), std::string::npos);
  EXPECT_NE(r.output.find("validate"), std::string::npos);
}

TEST(Cli, EverySubcommandHasHelp) {
  for (const char* sub : {"formula", "validate"}) {
    const CommandRun r = ringcrush(std::string(sub) + " --help");
    EXPECT_EQ(r.status, 0) << sub;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
  }
}

TEST(Cli, BadUsageExitsNonZeroWithAMessage) {
  CommandRun r = ringcrush("");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("subcommand"), std::string::npos) << r.output;
  r = ringcrush("explode");
  EXPECT_NE(r.status, 0);
  r = ringcrush("formula --points 1 " + scenes + "thesis_static.toml");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--points"), std::string::npos) << r.output;
  r = ringcrush("formula --D 0.05");  // neither scene nor a complete set of flags
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--t"), std::string::npos) << r.output;
  r = ringcrush("formula --D 0.05 --t 0.03 --L 0.01 --sigma0 2e8");  // t ≥ D/2
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("D/2"), std::string::npos) << r.output;
}

TEST(Cli, FormulaWritesACompleteResultsDirectory) {
  const fs::path dir = scratch("formula");
  const CommandRun r = ringcrush("formula " + scenes + "thesis_static.toml -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("P0 = 8 M0/d = 355.122 N"), std::string::npos) << r.output;
  for (const char* f : {"summary.json", "history.csv", "load_deflection.svg"})
    EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
  std::ifstream in(dir / "out" / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["model"], "formula");
  EXPECT_EQ(summary["scene"], "thesis_static");
  EXPECT_EQ(summary["analysis"], "static");
  EXPECT_NEAR(summary["M0_Nm"].get<double>(), 2.184, 1e-9);
  EXPECT_NEAR(summary["P0_N"].get<double>(), 355.122, 1e-3);
  for (const char* key : {"wall_time_s", "steps", "max_force_N", "final_deflection_m"})
    EXPECT_TRUE(summary.contains(key)) << key;
  std::ifstream csv(dir / "out" / "history.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("deflection_m,", 0), 0u) << header;
}

TEST(Cli, FormulaFromFlags) {
  const CommandRun r = ringcrush("formula --D 0.050 --t 0.0016 --L 0.100 --sigma0 269e6 --Ep 1.65e9 --plane-strain --alpha 1 2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("P0 = 8 M0/d = 3285.8"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("P_RW(2)_N"), std::string::npos);
}

TEST(Cli, BadSceneExitsNonZeroAndWritesNothing) {
  const fs::path dir = scratch("bad_scene");
  const fs::path bad = dir / "bad.toml";
  {
    std::ifstream in(scenes + "thesis_static.toml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("wall_thickness_m = 0.0016"), 25, "wall_thickness_m = 0.0300");
    std::ofstream(bad) << text;
  }
  const fs::path out = dir / "results";
  fs::create_directories(out);
  CommandRun r = ringcrush("formula " + bad.string() + " -o " + (out / "run").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("bad.toml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rings.wall_thickness_m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("t < D/2"), std::string::npos) << r.output;
  EXPECT_TRUE(empty_dir(out));
  r = ringcrush("validate " + bad.string());
  EXPECT_EQ(r.status, 2);
}

TEST(Cli, ValidateAcceptsEveryShippedScene) {
  const CommandRun r = ringcrush("validate " + scenes + "*.toml");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("test30_welded.toml: ok"), std::string::npos);
}

// Scene loading warns (stderr, once, exit status unchanged) on a chain whose FE section misses
// M0 by its Gauss rule (compare/through_wall_section.hpp): the thesis scene, on the thesis's
// mesh; not the Table 2 chains, which carry two elements through the wall.
TEST(Cli, ValidateWarnsOnAChainWhoseFeMissesThePlasticMoment) {
  const CommandRun thesis = ringcrush("validate " + scenes + "thesis_dynamic.toml " + scenes + "thesis_dynamic.toml");
  EXPECT_EQ(thesis.status, 0) << thesis.output;
  const auto first = thesis.output.find("warning: ");
  ASSERT_NE(first, std::string::npos) << thesis.output;
  EXPECT_EQ(thesis.output.find("warning: ", first + 1), std::string::npos) << thesis.output;  // once per run
  EXPECT_NE(thesis.output.find("0.861 M0"), std::string::npos) << thesis.output;
  EXPECT_NE(thesis.output.find("the thesis's mesh"), std::string::npos) << thesis.output;
  const CommandRun welded = ringcrush("validate " + scenes + "test30_welded.toml");
  EXPECT_EQ(welded.status, 0) << welded.output;
  EXPECT_EQ(welded.output.find("warning"), std::string::npos) << welded.output;
}

TEST(Cli, BenchHinge2StiffTermScalesOutOfRangeAreNamedErrors) {
  for (const char* flag : {"--membrane-scale", "--penalty-scale"})
    for (const char* bad : {"0", "1.5", "-0.25"}) {
      const CommandRun r = ringcrush("bench-hinge2 " + scenes + "test30_welded.toml --repeat 1 --integrator "
                                     "central_difference " + flag + " " + bad);
      EXPECT_NE(r.status, 0) << flag << " " << bad;
      EXPECT_NE(r.output.find(std::string(flag) + " must lie in (0, 1]"), std::string::npos) << r.output;
    }
}

// `--membrane` takes implicit or explicit, and the implicit membrane needs the implicit dampers
// (hinge/polygon_central_difference.hpp): named errors before any run.
TEST(Cli, BenchHinge2MembraneFlagBadValuesAreNamedErrors) {
  const std::string base = "bench-hinge2 " + scenes + "test30_welded.toml --repeat 1 --integrator central_difference ";
  CommandRun r = ringcrush(base + "--membrane stiff");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--membrane must be implicit or explicit, not \"stiff\""), std::string::npos) << r.output;
  r = ringcrush(base + "--membrane implicit --dampers explicit");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--membrane implicit needs --dampers implicit"), std::string::npos) << r.output;
}

// bench-level3 --accuracy (h52): the IDA run of the inertial Level 3 chain at the bench's rtol
// against Odeint at rtol 1e-12 prints its crush error (within the 1e-6 d bar at 45 m/s) and
// Odeint's event sequence; a run at rtol 1e-5 reports a larger error than at 1e-8.
TEST(Cli, BenchLevel3AccuracyAgainstOdeint) {
  auto crush_error = [](const std::string& out) {
    const auto at = out.find("crush error ");
    EXPECT_NE(at, std::string::npos) << out;
    return at == std::string::npos ? 1.0 : std::stod(out.substr(at + 12));
  };
  const std::string base = "bench-level3 " + scenes + "test30_welded_level3_inertia.toml --velocity 45 --repeat 1 --only ida --accuracy";
  const CommandRun tight = ringcrush(base);
  ASSERT_EQ(tight.status, 0) << tight.output;
  EXPECT_NE(tight.output.find("events the same (60 / 60)"), std::string::npos) << tight.output;
  const double e8 = crush_error(tight.output);
  EXPECT_LE(e8, 1e-6) << tight.output;
  const CommandRun loose = ringcrush(base + " --rtol 1e-5");
  ASSERT_EQ(loose.status, 0) << loose.output;
  EXPECT_GT(crush_error(loose.output), e8) << loose.output;
}
