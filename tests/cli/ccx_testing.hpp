// The CalculiX cross-checks (tests/cli/calculix_*_test.cpp): is ccx installed, and run it on
// an exported deck.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace ccx_testing {

inline bool ccx_on_path() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

inline constexpr const char* kMissing =
    "ccx (CalculiX) is not on PATH; install it with `apt-get install calculix-ccx` (Debian) to run the cross-check";

// ccx -i JOB in `dir`, its output in dir/ccx.log; true on success.
inline bool run_ccx(const std::filesystem::path& dir, const std::string& job) {
  const std::string cmd = "cd " + dir.string() + " && ccx -i " + job + " > ccx.log 2>&1";
  return std::system(cmd.c_str()) == 0;
}

}  // namespace ccx_testing
