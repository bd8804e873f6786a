// A cache of model results keyed by what determines them (issue "ringcrush compare": a rerun
// of an unchanged scene is instant, a changed scene or a rebuilt code is never served stale).
//
// Key = FNV-1a 64 of: the model name, the scene in canonical form (the parsed TOML written
// back, so comments, spacing and number spelling do not matter), the run options that change
// results, and the code identity (a hash of the running executable's bytes plus the version
// string: any rebuild with a change gives a new key).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace ringcrush::compare {

// The scene text in canonical form (throws SceneError if it does not parse as TOML).
std::string canonical_scene_text(const std::string& toml_text, const std::string& file);

// Identity of the code that is running: hash of /proc/self/exe and the version string.
std::string code_identity();

std::uint64_t fnv1a64(std::string_view data, std::uint64_t seed = 14695981039346656037ull);

class ResultCache {
 public:
  // Root directory: $RINGCRUSH_CACHE_DIR, else $XDG_CACHE_HOME/ringcrush, else ~/.cache/ringcrush.
  static std::filesystem::path default_root();
  explicit ResultCache(std::filesystem::path root = default_root());

  static std::string key(const std::string& model, const std::string& canonical_scene,
                         const std::string& options, const std::string& code);

  // The cached results directory for `key`, if a complete one is there.
  std::optional<std::filesystem::path> lookup(const std::string& key) const;
  // Copies a complete results directory into the cache (atomically: staged, then renamed).
  void store(const std::string& key, const std::filesystem::path& results_dir) const;

  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

}  // namespace ringcrush::compare
