// Runs the `ringcrush` executable for end-to-end tests: its exit status and everything it
// printed (stdout and stderr). `env` is prepended to the command line ("NAME=value ...").
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace cli_testing {  // not ringcrush::…: the helper is itself called ringcrush

struct CommandRun {
  int status;          // exit status, −1 if the process did not exit normally
  std::string output;  // stdout and stderr
};

inline CommandRun ringcrush(const std::string& args, const std::string& env = "") {
  const std::string cmd = (env.empty() ? "" : env + " ") + std::string(RINGCRUSH_EXE) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) throw std::runtime_error("popen failed");
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe)) out += buf.data();
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}

}  // namespace cli_testing
