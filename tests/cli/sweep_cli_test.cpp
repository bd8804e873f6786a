// `ringcrush sweep` end to end: a sweep killed midway (SIGKILL) resumes without recomputing
// finished cases, and the merged table equals an uninterrupted run's (timings aside).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include "test_files.hpp"

namespace fs = std::filesystem;

namespace {
const std::string exe = RINGCRUSH_EXE;

fs::path scratch(const std::string& name) { return test_files::scratch_dir("ringcrush_sweep_cli_", name); }

int run(const std::string& args) {
  const int raw = std::system((exe + " " + args + " > /dev/null 2>&1").c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

int finished_cases(const fs::path& dir) {
  int n = 0;
  if (!fs::exists(dir)) return 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().front() != '.' && fs::exists(e.path() / "summary.json")) ++n;
  return n;
}

// The CSV without the columns that measure time spent (they differ between runs).
std::string without_timings(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line, out;
  std::vector<bool> keep;
  bool header = true;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    if (header) {
      for (const auto& name : f) keep.push_back(name.find("wall_time") == std::string::npos &&
                                                 name.find("statistics") == std::string::npos);
      header = false;
    }
    for (std::size_t i = 0; i < f.size() && i < keep.size(); ++i)
      if (keep[i]) out += f[i] + ",";
    out += "\n";
  }
  return out;
}

fs::path grid(const fs::path& dir) {
  const fs::path g = dir / "grid.toml";
  std::ofstream(g) << "base_scene = \"" << RINGCRUSH_SOURCE_DIR << "/data/scenes/test30_welded.toml\"\n"
                   << "model = \"hinge\"\n[[axis]]\nkey = \"hinge.level\"\nvalues = [0]\n"
                   << "[[axis]]\nkey = \"impactor.velocity_m_s\"\n"
                   << "values = [15.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0, 50.0]\n";
  return g;
}
}  // namespace

TEST(SweepCli, KilledSweepResumesAndMergesTheSameTable) {
  const fs::path dir = scratch("kill");
  const fs::path g = grid(dir);
  ASSERT_EQ(run("sweep " + g.string() + " -o " + (dir / "full").string() + " -j 2"), 0);

  const fs::path out = dir / "killed";
  const pid_t pid = fork();
  if (pid == 0) {
    execl(exe.c_str(), exe.c_str(), "sweep", g.c_str(), "-o", out.c_str(), "-j", "1", static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (finished_cases(out) < 2 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  const int before = finished_cases(out);
  ASSERT_GE(before, 2);
  ASSERT_LT(before, 8) << "the sweep finished before it could be killed";
  EXPECT_FALSE(fs::exists(out / "sweep.csv"));

  // Finished cases keep their files untouched on rerun.
  std::map<std::string, fs::file_time_type> stamps;
  for (const auto& e : fs::directory_iterator(out))
    if (fs::exists(e.path() / "summary.json")) stamps[e.path().filename()] = fs::last_write_time(e.path() / "summary.json");
  ASSERT_EQ(run("sweep " + g.string() + " -o " + out.string() + " -j 2"), 0);
  for (const auto& [name, t] : stamps) EXPECT_EQ(fs::last_write_time(out / name / "summary.json"), t) << name;
  EXPECT_EQ(finished_cases(out), 8);
  EXPECT_EQ(without_timings(out / "sweep.csv"), without_timings(dir / "full" / "sweep.csv"));
  EXPECT_TRUE(fs::exists(out / "sweep.svg"));
  for (const auto& e : fs::directory_iterator(out))  // no staging left behind
    EXPECT_NE(e.path().filename().string().front(), '.') << e.path();
}

TEST(SweepCli, BadGridsAndUsageExitNonZero) {
  const fs::path dir = scratch("bad");
  const fs::path g = dir / "g.toml";
  std::ofstream(g) << "base_scene = \"nope.toml\"\n[[axis]]\nkey = \"t_over_D\"\nvalues = [0.02]\n";
  EXPECT_EQ(run("sweep " + g.string() + " -o " + (dir / "o").string()), 2);
  EXPECT_EQ(run("sweep " + grid(dir).string()), 2);  // no -o
  // --list: the count, then one line per case (what a Slurm array needs).
  FILE* p = popen((exe + " sweep " + grid(dir).string() + " --list").c_str(), "r");
  char line[256] = {};
  ASSERT_TRUE(std::fgets(line, sizeof line, p));
  EXPECT_EQ(std::string(line), "8 cases\n");
  ASSERT_TRUE(std::fgets(line, sizeof line, p));
  EXPECT_EQ(std::string(line), "case_0000 0 15.0\n");
  pclose(p);
  EXPECT_EQ(run("sweep " + grid(dir).string() + " -o " + (dir / "o2").string() + " --case 99"), 2);
  EXPECT_FALSE(fs::exists(dir / "o"));
}
