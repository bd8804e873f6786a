// The CalculiX tests (tests/cli/calculix_*_test.cpp): is ccx installed, run it on an exported
// deck, read a deck's keyword blocks.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace ccx_testing {

inline bool ccx_on_path() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

inline constexpr const char* kMissing =
    "ccx (CalculiX) is not on PATH; install it with `apt-get install calculix-ccx` (Debian) to run the cross-check";

// ccx -i JOB in `dir`, its output in dir/ccx.log; true on success.
inline bool run_ccx(const std::filesystem::path& dir, const std::string& job) {
  const std::string cmd = "cd " + dir.string() + " && ccx -i " + job + " > ccx.log 2>&1";
  return std::system(cmd.c_str()) == 0;
}

// The data lines under each keyword line of a deck (comment lines dropped), keyed by the
// keyword line as written; a repeated keyword gets an entry of its own.
inline std::multimap<std::string, std::vector<std::string>> deck_blocks(const std::string& deck) {
  std::multimap<std::string, std::vector<std::string>> out;
  std::istringstream in(deck);
  std::vector<std::string>* cur = nullptr;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("**", 0) == 0) continue;
    if (!line.empty() && line[0] == '*') cur = &out.emplace(line, std::vector<std::string>{})->second;
    else if (cur) cur->push_back(line);
  }
  return out;
}

}  // namespace ccx_testing
