// Issue 5 item 2: the thesis's static deck, run as it is, gives the same load curve as the
// equivalent TOML scene (within 1 %; in fact the same run, since the deck becomes that scene).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {
int ringcrush(const std::string& args) {
  const std::string cmd = std::string(RINGCRUSH_EXE) + " " + args + " > /dev/null 2>&1";
  const int raw = std::system(cmd.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// The force_N column of a static history.csv.
std::vector<double> forces(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream h(line);
  for (std::string f; std::getline(h, f, ',');) names.push_back(f);
  std::size_t col = 0;
  while (col < names.size() && names[col] != "force_N") ++col;
  EXPECT_LT(col, names.size()) << "no force_N column";
  std::vector<double> out;
  while (std::getline(in, line)) {
    std::stringstream r(line);
    std::string f;
    for (std::size_t k = 0; k <= col && std::getline(r, f, ','); ++k) {
    }
    out.push_back(std::stod(f));
  }
  return out;
}
}  // namespace

TEST(DeckRun, StaticDeckGivesTheSceneLoadCurve) {
  const fs::path dir = fs::temp_directory_path() / "ringcrush_deck_run";
  fs::remove_all(dir);
  const std::string src = RINGCRUSH_SOURCE_DIR;
  ASSERT_EQ(ringcrush("fe " + src + "/data/thesis/thesis_static.inp -q -o " + (dir / "deck").string()), 0);
  ASSERT_EQ(ringcrush("fe " + src + "/data/scenes/thesis_static.toml -q -o " + (dir / "toml").string()), 0);
  const auto a = forces(dir / "deck" / "history.csv"), b = forces(dir / "toml" / "history.csv");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 50u);
  double peak = 0;
  for (double f : b) peak = std::max(peak, std::abs(f));
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LE(std::abs(a[i] - b[i]), 0.01 * peak) << "row " << i;
}
