// libFuzzer target for the ABAQUS deck reader (issue 5 item 4): any byte string must either
// read into a DeckModel or be refused with a std::invalid_argument (DeckError); the ring
// recognition and the summaries must not crash on whatever reads. Any other exception, a
// sanitizer report, a hang or an allocation above -rss_limit_mb is a bug.
//   clang build:  cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DRINGCRUSH_FUZZ=ON
//                 cmake --build build-fuzz --target fuzz_deck
//                 build-fuzz/tests/fuzz/fuzz_deck tests/fuzz/corpus/deck -dict=tests/fuzz/deck.dict
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "fe/deck/deck_parameters.hpp"
#include "fe/deck/deck_reader.hpp"
#include "fe/deck/deck_summary.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fd = ringcrush::fe::deck;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fd::DeckModel model;
  try {
    model = fd::read_deck(text);
  } catch (const std::invalid_argument&) {
    return 0;  // refused with a reason: the expected outcome for most inputs
  }
  (void)fd::describe(model);
  try {
    (void)fd::describe(fd::deck_parameters(model));
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
