#include "results_dir.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <stdexcept>

namespace ringcrush::compare {
namespace fs = std::filesystem;

ResultsDir::ResultsDir(fs::path target) : target_(fs::absolute(std::move(target)).lexically_normal()) {
  if (target_.filename().empty()) target_ = target_.parent_path();
  const fs::path parent = target_.parent_path();
  fs::create_directories(parent);
  staging_ = parent / fmt::format(".{}.partial-{}", target_.filename().string(), ::getpid());
  fs::remove_all(staging_);
  fs::create_directory(staging_);
}

ResultsDir::~ResultsDir() {
  if (!committed_) {
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
  }
}

fs::path ResultsDir::file(const std::string& relative) const {
  if (committed_) throw std::logic_error("ResultsDir: already committed");
  const fs::path p = staging_ / relative;
  fs::create_directories(p.parent_path());
  return p;
}

void ResultsDir::commit() {
  if (committed_) return;
  if (fs::exists(target_)) {
    // Keep the old result until the new one is in place, then drop it.
    const fs::path old = target_.parent_path() / fmt::format(".{}.old-{}", target_.filename().string(), ::getpid());
    fs::rename(target_, old);
    fs::rename(staging_, target_);
    fs::remove_all(old);
  } else {
    fs::rename(staging_, target_);
  }
  committed_ = true;
}

}  // namespace ringcrush::compare
