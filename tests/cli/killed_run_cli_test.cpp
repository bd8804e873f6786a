// Issue 5 item 5: a run killed midway never leaves a results directory that looks complete.
// `ringcrush fe` on the thesis dynamic scene (minutes long) is killed (SIGKILL, and SIGTERM)
// while it computes: the target directory must not exist, and what is left is only the
// hidden staging directory ".NAME.partial-PID" without summary.json. A later run of the same
// target writes it completely.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace fs = std::filesystem;

namespace {

const std::string exe = RINGCRUSH_EXE;

// Staging directories of `target` (".NAME.partial-PID") in its parent.
int staging_dirs(const fs::path& target, bool* with_summary) {
  int n = 0;
  // Appended, not `"." + ...`: GCC 12's -Wrestrict false positive.
  std::string prefix = ".";
  prefix += target.filename().string();
  prefix += ".partial-";
  for (const auto& e : fs::directory_iterator(target.parent_path())) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0) {
      ++n;
      if (fs::exists(e.path() / "summary.json")) *with_summary = true;
    }
  }
  return n;
}

void kill_midway(int signal, const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("ringcrush_killed_run_" + tag);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "run";
  const std::string scene = std::string(RINGCRUSH_SOURCE_DIR) + "/data/scenes/thesis_dynamic.toml";
  const pid_t pid = fork();
  if (pid == 0) {
    execl(exe.c_str(), exe.c_str(), "fe", scene.c_str(), "-q", "-o", target.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until the run has set up its staging directory and computed a little.
  bool summary = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (staging_dirs(target, &summary) == 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, WNOHANG), 0) << "the run ended before it could be killed";
  kill(pid, signal);
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_FALSE(fs::exists(target)) << "a killed run left a results directory that looks complete";
  summary = false;
  EXPECT_LE(staging_dirs(target, &summary), 1);
  EXPECT_FALSE(summary);
}

}  // namespace

TEST(KilledRun, SigkillLeavesNoResultsDirectory) { kill_midway(SIGKILL, "kill"); }
TEST(KilledRun, SigtermLeavesNoResultsDirectory) { kill_midway(SIGTERM, "term"); }
