// A results directory that is written completely or not at all (DESIGN.md "Results").
// Files go to a hidden staging directory beside the target; commit() renames it into
// place in one step. A run that throws, or is killed, leaves only the staging directory,
// whose name (".NAME.partial-PID") never looks like a finished result.
#pragma once

#include <filesystem>
#include <string>

namespace ringcrush::compare {

class ResultsDir {
 public:
  explicit ResultsDir(std::filesystem::path target);
  ~ResultsDir();
  ResultsDir(const ResultsDir&) = delete;
  ResultsDir& operator=(const ResultsDir&) = delete;

  // Path of a file inside the (staging) directory; sub-directories are created.
  std::filesystem::path file(const std::string& relative) const;
  const std::filesystem::path& target() const { return target_; }
  // Moves the staging directory to the target, replacing an older result there.
  void commit();

 private:
  std::filesystem::path target_, staging_;
  bool committed_ = false;
};

}  // namespace ringcrush::compare
