// The ABAQUS 4.8 card structure (ABAQUS User's Manual, "Input syntax rules"): a deck is a
// sequence of keyword lines (`*NAME, PARAM=VALUE, FLAG`) each followed by its data lines
// (comma-separated fields). `**` starts a comment line; a keyword line that ends with a comma
// continues on the next line; names and parameters are case-insensitive. This layer only
// splits the text into cards with their line numbers; what each keyword means is the reader's
// business (deck_reader.hpp).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ringcrush::fe::deck {

struct Parameter {
  std::string name;   // upper case, inner blanks collapsed: "CHANGE NUMBER"
  std::string value;  // upper case, trimmed; empty for a flag (`NLGEOM`)
  bool has_value = false;
};

struct DataLine {
  int line = 0;                     // 1-based line number in the file
  std::string text;                 // the line as written (trimmed), for free-text cards
  std::vector<std::string> fields;  // comma-separated fields, trimmed; "" for an empty field
  bool ends_with_comma = false;     // a data record continued on the next line
};

struct Card {
  int line = 0;          // line of the keyword
  std::string keyword;   // upper case without '*', inner blanks collapsed: "NODE PRINT"
  std::vector<Parameter> parameters;
  std::vector<DataLine> data;

  const Parameter* find(std::string_view name) const;
  bool has(std::string_view name) const { return find(name) != nullptr; }
  // The value of NAME=VALUE; throws DeckError if it is given as a bare flag.
  std::optional<std::string> value(std::string_view name) const;
  // Like value() but the parameter must be present.
  std::string required(std::string_view name) const;
};

// Splits deck text into cards. Throws DeckError (with the line) on text that is not a deck:
// control or non-ASCII bytes outside comments and the heading, data before the first keyword,
// an empty keyword, a malformed or repeated parameter, a continuation at end of file.
std::vector<Card> lex_deck(std::string_view text);

}  // namespace ringcrush::fe::deck
