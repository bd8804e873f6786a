// Sweeps: grid expansion and validation, idempotent resume after an interrupted run (the
// merged table equals an uninterrupted run's), failures recorded, ranks splitting the cases.
#include "compare/sweep.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <set>
#include <sstream>

#include "compare/table_output.hpp"

using namespace ringcrush::compare;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("ringcrush_sweep_test_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

fs::path write_grid(const fs::path& dir, const std::string& axes) {
  const fs::path grid = dir / "grid.toml";
  std::ofstream(grid) << "base_scene = \"" << RINGCRUSH_SOURCE_DIR << "/data/scenes/test30_welded.toml\"\n"
                      << "model = \"fake\"\n" << axes;
  return grid;
}

const std::string two_axes = R"(
[[axis]]
key = "impactor.velocity_m_s"
values = [15.0, 30.0, 50.0]
[[axis]]
key = "joints.type"
values = ["welded", "free"]
)";

// A stand-in model: a deterministic function of the scene, so reruns are comparable.
void fake_model(const Scene& s, ResultsDir& out) {
  const double v = s.impactor->velocity_m_s;
  nlohmann::json j = {{"model", "fake"},
                      {"crush_ratio", {v / 100, v / 200}},
                      {"wrap_around", {s.joints.type == JointType::Welded, false}},
                      {"thickness_m", s.rings.wall_thickness_m}};
  write_json(out.file("summary.json"), j);
}

std::string read(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(Sweep, ExpandsTheCartesianProductFirstAxisSlowest) {
  const auto dir = scratch("expand");
  const SweepGrid g = load_sweep_grid(write_grid(dir, two_axes));
  ASSERT_EQ(g.cases.size(), 6u);
  EXPECT_EQ(g.cases[0].values, (std::vector<std::string>{"15.0", "welded"}));
  EXPECT_EQ(g.cases[1].values, (std::vector<std::string>{"15.0", "free"}));
  EXPECT_EQ(g.cases[5].values, (std::vector<std::string>{"50.0", "free"}));
  EXPECT_EQ(g.cases[5].name, "case_0005");
  const Scene s = parse_scene(g.cases[3].scene_toml, "case_0003");
  EXPECT_DOUBLE_EQ(s.impactor->velocity_m_s, 30.0);
  EXPECT_EQ(s.joints.type, JointType::Free);
  EXPECT_EQ(s.rings.count, 6);  // untouched keys come from the base scene
}

TEST(Sweep, ThicknessRatioAxisSetsTheWall) {
  const auto dir = scratch("t_over_d");
  const SweepGrid g = load_sweep_grid(write_grid(dir, "[[axis]]\nkey = \"t_over_D\"\nvalues = [0.02, 0.06]\n"));
  EXPECT_NEAR(parse_scene(g.cases[1].scene_toml, "c").rings.wall_thickness_m, 0.06 * 0.0508, 1e-15);
}

TEST(Sweep, BadGridsAreRejectedBeforeAnythingRuns) {
  const auto dir = scratch("bad");
  // A value that makes a case non-physical names the case and the key.
  try {
    load_sweep_grid(write_grid(dir, "[[axis]]\nkey = \"impactor.mass_kg\"\nvalues = [0.1, -1.0]\n"));
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("case_0001"), std::string::npos) << e.what();
    EXPECT_EQ(e.key(), "impactor.mass_kg");
  }
  EXPECT_THROW(load_sweep_grid(write_grid(dir, "")), SceneError);                       // no axis
  EXPECT_THROW(load_sweep_grid(write_grid(dir, "[[axis]]\nkey = \"x\"\nvalues = []\n")), SceneError);
  EXPECT_THROW(load_sweep_grid(write_grid(dir, "[[axis]]\nkey = \"rings.colour\"\nvalues = [1]\n")), SceneError);
  EXPECT_THROW(load_sweep_grid(write_grid(dir, "speed = 3\n[[axis]]\nkey = \"t_over_D\"\nvalues = [0.02]\n")), SceneError);
}

TEST(Sweep, ResumesAfterAnInterruptionAndMergesTheSameTable) {
  const auto dir = scratch("resume");
  const SweepGrid g = load_sweep_grid(write_grid(dir, two_axes));

  // Uninterrupted reference.
  const SweepReport full = run_sweep(g, dir / "full", fake_model, {.threads = 2, .progress = false});
  EXPECT_EQ(full.run, 6);
  merge_sweep(g, dir / "full", dir / "full.csv");

  // A run that dies after three cases (the fourth throws, like a killed process would stop).
  std::atomic<int> calls{0};
  auto dying = [&](const Scene& s, ResultsDir& out) {
    if (++calls > 3) throw std::runtime_error("killed");
    fake_model(s, out);
  };
  const SweepReport first = run_sweep(g, dir / "resumed", dying, {.threads = 1, .progress = false});
  EXPECT_EQ(first.run, 3);
  EXPECT_EQ(first.failed, 3);
  EXPECT_TRUE(fs::exists(dir / "resumed" / "case_0004.failed"));
  int missing = 0;
  EXPECT_EQ(merge_sweep(g, dir / "resumed", dir / "partial.csv", &missing), 3);
  EXPECT_EQ(missing, 3);

  // Rerun: only the unfinished cases run.
  std::set<std::string> ran;
  std::mutex m;
  auto counting = [&](const Scene& s, ResultsDir& out) {
    {
      std::lock_guard lock(m);
      ran.insert(out.target().filename().string());
    }
    fake_model(s, out);
  };
  const SweepReport second = run_sweep(g, dir / "resumed", counting, {.threads = 2, .progress = false});
  EXPECT_EQ(second.skipped, 3);
  EXPECT_EQ(second.run, 3);
  EXPECT_EQ(ran, (std::set<std::string>{"case_0003", "case_0004", "case_0005"}));
  EXPECT_FALSE(fs::exists(dir / "resumed" / "case_0004.failed"));
  merge_sweep(g, dir / "resumed", dir / "resumed.csv");
  EXPECT_EQ(read(dir / "resumed.csv"), read(dir / "full.csv"));

  const std::string csv = read(dir / "full.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "case,impactor.velocity_m_s,joints.type,crush_ratio_1,crush_ratio_2,thickness_m,wrap_around_1,wrap_around_2");
}

TEST(Sweep, RanksSplitTheCasesWithoutOverlap) {
  const auto dir = scratch("ranks");
  const SweepGrid g = load_sweep_grid(write_grid(dir, two_axes));
  const auto r0 = run_sweep(g, dir / "out", fake_model, {.threads = 1, .rank = 0, .ranks = 2, .progress = false});
  const auto r1 = run_sweep(g, dir / "out", fake_model, {.threads = 1, .rank = 1, .ranks = 2, .progress = false});
  EXPECT_EQ(r0.run + r1.run, 6);
  EXPECT_EQ(r0.skipped + r1.skipped, 0);
  EXPECT_EQ(merge_sweep(g, dir / "out", dir / "out.csv"), 6);
  EXPECT_TRUE(fs::exists(dir / "out" / "case_0002" / "scene.toml"));
}
