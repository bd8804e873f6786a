// DeckError: an ABAQUS input deck that cannot be read. Carries the 1-based line number of the
// offending line (0 when the problem is the file as a whole, e.g. empty or truncated) and the
// reason, so a user can go straight to the line: "deck.inp:212: *BOUNDARY: unknown ...".
#pragma once

#include <stdexcept>
#include <string>

namespace ringcrush::fe::deck {

class DeckError : public std::invalid_argument {
 public:
  DeckError(int line, const std::string& reason)
      : std::invalid_argument(line > 0 ? "line " + std::to_string(line) + ": " + reason : reason),
        line_(line), reason_(reason) {}
  int line() const { return line_; }
  const std::string& reason() const { return reason_; }

 private:
  int line_;
  std::string reason_;
};

// Hard limits that keep a hostile or mistyped deck from exhausting memory (issue 5 item 4).
// ABAQUS 4.8 itself numbered nodes and elements below 10^8; the thesis decks stay below 10^4.
inline constexpr long long max_label = 99'999'999;     // largest node / element number
inline constexpr long long max_entities = 1'000'000;    // nodes, elements, or members of one set
inline constexpr std::size_t max_deck_bytes = 64u << 20; // 64 MiB of text
// Total of generated nodes, elements, set memberships, constraints and slide-line nodes:
// a few bytes of *NGEN and set references can otherwise ask for gigabytes.
inline constexpr long long max_generated = 4'000'000;
inline constexpr std::size_t max_parameters = 64;       // parameters on one keyword line

}  // namespace ringcrush::fe::deck
