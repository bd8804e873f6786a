// `ringcrush hinge` end to end: the stable outputs of DESIGN.md for levels 0, 1 and shock,
// integrator and tolerance flags, and a clear refusal of an unknown level.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>
#include <string>

namespace fs = std::filesystem;

namespace {

int run(const std::string& args, const fs::path& log) {
  const std::string cmd = std::string(RINGCRUSH_EXE) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string scene(const char* name) { return std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/" + name; }

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("ringcrush_hinge_cli_" + std::to_string(::getpid())) / name;
  fs::create_directories(p.parent_path());
  fs::remove_all(p);
  return p;
}

std::string first_line(const fs::path& f) {
  std::ifstream in(f);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

TEST(HingeCli, EveryOneDimensionalLevelWritesTheStableOutputs) {
  for (const std::string level : {"0", "1", "shock"}) {
    const auto out = scratch("level" + level);
    ASSERT_EQ(run("hinge " + scene("test30_plates.toml") + " --level " + level + " -o " + out.string(),
                  out.string() + ".log"), 0)
        << level;
    std::ifstream in(out / "summary.json");
    const auto s = nlohmann::json::parse(in);
    EXPECT_EQ(s["model"], "hinge");
    EXPECT_EQ(s["scene"], "test30_plates");
    EXPECT_EQ(s["analysis"], "dynamic");
    EXPECT_EQ(s["level"], level);
    for (const char* key : {"wall_time_s", "steps", "crush_ratio", "wrap_around", "wrapped_angle_deg",
                            "alternation_index", "energy_balance_error", "arrest_time_s", "peak_force_N",
                            "impactor_final_velocity_m_s"})
      EXPECT_TRUE(s.contains(key)) << key;
    EXPECT_EQ(s["crush_ratio"].size(), 6u);
    EXPECT_EQ(s["wrap_around"][0], false);
    EXPECT_LT(s["energy_balance_error"].get<double>(), 1e-5);
    EXPECT_GT(s["arrest_time_s"].get<double>(), 0.005);
    EXPECT_GT(s["peak_force_N"].get<double>(), 500.0);
    const std::string header = first_line(out / "history.csv");
    EXPECT_EQ(header.rfind("time_s,impactor_displacement_m,impactor_velocity_m_s,impactor_force_N,crush_ring_1_m", 0), 0u)
        << header;
    EXPECT_NE(header.find("crush_ring_6_m"), std::string::npos);
    EXPECT_NE(header.find("kinetic_J"), std::string::npos);
    EXPECT_NE(header.find("plastic_J"), std::string::npos);
    for (const char* svg : {"crush.svg", "impactor.svg", "force.svg", "energy.svg"})
      EXPECT_TRUE(fs::exists(out / svg)) << svg;
  }
}

TEST(HingeCli, IntegratorAndToleranceFlagsAreHonoured) {
  const auto a = scratch("ida"), b = scratch("odeint");
  ASSERT_EQ(run("hinge " + scene("test30_welded.toml") + " --level 0 --integrator ida --rtol 1e-9 -o " + a.string(), a.string() + ".log"), 0);
  ASSERT_EQ(run("hinge " + scene("test30_welded.toml") + " --level 0 --integrator odeint --rtol 1e-9 -o " + b.string(), b.string() + ".log"), 0);
  std::ifstream ia(a / "summary.json"), ib(b / "summary.json");
  const auto sa = nlohmann::json::parse(ia), sb = nlohmann::json::parse(ib);
  EXPECT_EQ(sa["integrator"], "ida");
  EXPECT_EQ(sb["integrator"], "odeint");
  EXPECT_EQ(sa["relative_tolerance"], 1e-9);
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(sa["crush_ratio"][i].get<double>(), sb["crush_ratio"][i].get<double>(), 1e-4);
}

TEST(HingeCli, UnknownLevelIsABadInputWithAClearMessage) {
  const auto out = scratch("nolevel");
  const fs::path log = out.string() + ".log";
  EXPECT_EQ(run("hinge " + scene("test30_plates.toml") + " --level 9 -o " + out.string(), log), 2);
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("hinge level \"9\" is not available"), std::string::npos) << text.str();
  EXPECT_FALSE(fs::exists(out));
  // A static scene is refused the same way, naming the alternative.
  EXPECT_EQ(run("hinge " + scene("thesis_static.toml") + " --level 1 -o " + out.string(), log), 2);
  EXPECT_FALSE(fs::exists(out));
}
