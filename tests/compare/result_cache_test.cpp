// The result cache: an unchanged scene (even reformatted) hits, a changed value, option or
// code identity misses; stored results come back whole.
#include "compare/result_cache.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace ringcrush::compare;
namespace fs = std::filesystem;

namespace {
const std::string scene_a = R"(
# a comment
[rings]
count = 6
outer_diameter_m = 0.0508
[impactor]
velocity_m_s = 27.7
)";
// Same values: other comments, spacing, key order and number spelling.
const std::string scene_a_reformatted = R"(
[impactor]
velocity_m_s    = 2.77e1   # m/s
[rings]
outer_diameter_m = 5.08e-2
count = 6
)";
const std::string scene_b = R"(
[rings]
count = 6
outer_diameter_m = 0.0508
[impactor]
velocity_m_s = 27.8
)";
}  // namespace

TEST(ResultCache, KeyDependsOnValuesNotOnFormatting) {
  const std::string code = "code-1";
  const auto ka = ResultCache::key("fe", canonical_scene_text(scene_a, "a"), "", code);
  EXPECT_EQ(ka, ResultCache::key("fe", canonical_scene_text(scene_a_reformatted, "a2"), "", code));
  EXPECT_NE(ka, ResultCache::key("fe", canonical_scene_text(scene_b, "b"), "", code));     // a changed value
  EXPECT_NE(ka, ResultCache::key("fe", canonical_scene_text(scene_a, "a"), "--x", code));  // an option
  EXPECT_NE(ka, ResultCache::key("fe", canonical_scene_text(scene_a, "a"), "", "code-2")); // new code
  EXPECT_NE(ka, ResultCache::key("hinge", canonical_scene_text(scene_a, "a"), "", code));  // other model
}

TEST(ResultCache, CodeIdentityIsStableWithinABinary) {
  EXPECT_EQ(code_identity(), code_identity());
  EXPECT_EQ(code_identity().size(), 16u);
}

TEST(ResultCache, StoresAndFindsCompleteResults) {
  const fs::path root = fs::temp_directory_path() / "ringcrush_cache_test";
  fs::remove_all(root);
  const fs::path results = fs::temp_directory_path() / "ringcrush_cache_test_results";
  fs::remove_all(results);
  fs::create_directories(results / "frames");
  std::ofstream(results / "summary.json") << "{\"model\": \"fe\"}";
  std::ofstream(results / "frames" / "f0.vtu") << "x";

  const ResultCache cache(root);
  const std::string key = ResultCache::key("fe", "s", "", "c");
  EXPECT_FALSE(cache.lookup(key));
  cache.store(key, results);
  const auto hit = cache.lookup(key);
  ASSERT_TRUE(hit);
  EXPECT_TRUE(fs::exists(*hit / "frames" / "f0.vtu"));
  cache.store(key, results);  // a second store of the same key is harmless
  EXPECT_TRUE(cache.lookup(key));
  // An incomplete entry (no summary) is not a hit.
  fs::create_directories(root / "fe-0000000000000000");
  EXPECT_FALSE(cache.lookup("fe-0000000000000000"));
}
