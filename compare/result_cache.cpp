#include "compare/result_cache.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "compare/scene.hpp"
#include "compare/version.hpp"

namespace ringcrush::compare {
namespace fs = std::filesystem;

std::uint64_t fnv1a64(std::string_view data, std::uint64_t h) {
  for (unsigned char c : data) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string canonical_scene_text(const std::string& text, const std::string& file) {
  toml::table t;
  try {
    t = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw SceneError(file, fmt::format("line {}", e.source().begin.line),
                     fmt::format("not valid TOML: {}", e.description()));
  }
  std::ostringstream out;
  out << toml::toml_formatter(t);  // tables and keys sorted, comments and spacing gone
  return out.str();
}

std::string code_identity() {
  static const std::string identity = [] {
    std::ifstream exe("/proc/self/exe", std::ios::binary);
    std::uint64_t h = fnv1a64(version());
    std::string buffer(1 << 16, '\0');
    while (exe.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || exe.gcount() > 0) {
      h = fnv1a64(std::string_view(buffer.data(), static_cast<std::size_t>(exe.gcount())), h);
      if (!exe) break;
    }
    return fmt::format("{:016x}", h);
  }();
  return identity;
}

fs::path ResultCache::default_root() {
  if (const char* dir = std::getenv("RINGCRUSH_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "ringcrush";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "ringcrush";
  return fs::temp_directory_path() / "ringcrush-cache";
}

ResultCache::ResultCache(fs::path root) : root_(std::move(root)) {}

std::string ResultCache::key(const std::string& model, const std::string& canonical_scene,
                             const std::string& options, const std::string& code) {
  std::uint64_t h = fnv1a64(model);
  for (const std::string* part : {&canonical_scene, &options, &code}) {
    h = fnv1a64("\x1f", h);  // separator: ("ab", "c") and ("a", "bc") differ
    h = fnv1a64(*part, h);
  }
  return fmt::format("{}-{:016x}", model, h);
}

std::optional<fs::path> ResultCache::lookup(const std::string& key) const {
  const fs::path dir = root_ / key;
  if (fs::exists(dir / "summary.json")) return dir;
  return std::nullopt;
}

void ResultCache::store(const std::string& key, const fs::path& results_dir) const {
  fs::create_directories(root_);
  const fs::path staging = root_ / fmt::format(".{}.partial-{}", key, ::getpid());
  fs::remove_all(staging);
  fs::copy(results_dir, staging, fs::copy_options::recursive);
  const fs::path target = root_ / key;
  std::error_code ec;
  fs::rename(staging, target, ec);
  if (ec) {  // another process stored the same key first: keep theirs
    fs::remove_all(staging);
  }
}

}  // namespace ringcrush::compare
