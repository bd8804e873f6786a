// libFuzzer target for the scene parser compare::parse_scene (issue 5 item 4): any byte
// string must either parse into a Scene or be refused with a SceneError naming the key.
//   build-fuzz/tests/fuzz/fuzz_scene tests/fuzz/corpus/scene -dict=tests/fuzz/scene.dict
#include <cstddef>
#include <cstdint>
#include <string>

#include "compare/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)ringcrush::compare::parse_scene(text, "fuzz.toml");
  } catch (const ringcrush::compare::SceneError&) {
  }
  return 0;
}
