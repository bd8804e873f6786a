#include "fe/deck/deck_lexer.hpp"

#include <cctype>

#include "fe/deck/deck_error.hpp"

namespace ringcrush::fe::deck {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Upper case with runs of blanks collapsed to one space: "change  number" -> "CHANGE NUMBER".
std::string normalise(std::string_view s) {
  std::string out;
  bool blank = false;
  for (char c : trim(s)) {
    if (c == ' ' || c == '\t') {
      blank = true;
      continue;
    }
    if (blank && !out.empty()) out.push_back(' ');
    blank = false;
    out.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  }
  return out;
}

std::vector<std::string> split_fields(std::string_view s) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = s.find(',', start);
    const std::string_view f = s.substr(start, comma == std::string_view::npos ? s.npos : comma - start);
    fields.emplace_back(trim(f));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

// Control bytes never belong in a deck; bytes above 127 only in comments and the heading
// (ABAQUS 4.8 read 7-bit text; the thesis heading is Portuguese but written without accents).
void check_bytes(std::string_view line, int number, bool free_text) {
  for (char ch : line) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\t') || c == 0x7f)
      throw DeckError(number, "control character (byte " + std::to_string(c) + ") in the deck text");
    if (c >= 0x80 && !free_text)
      throw DeckError(number, "non-ASCII byte " + std::to_string(c) + " outside a comment or heading");
  }
}

Card parse_keyword_line(std::string_view text, int number) {
  const std::vector<std::string> parts = split_fields(text.substr(1));
  Card card;
  card.line = number;
  card.keyword = normalise(parts.front());
  if (card.keyword.empty()) throw DeckError(number, "keyword line without a keyword name");
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (p.empty()) throw DeckError(number, "*" + card.keyword + ": empty parameter (two commas in a row)");
    Parameter par;
    const std::size_t eq = p.find('=');
    par.name = normalise(std::string_view(p).substr(0, eq));
    if (eq != std::string::npos) {
      par.has_value = true;
      par.value = normalise(std::string_view(p).substr(eq + 1));
      if (par.value.empty())
        throw DeckError(number, "*" + card.keyword + ": parameter " + par.name + "= has no value");
    }
    if (par.name.empty()) throw DeckError(number, "*" + card.keyword + ": parameter without a name");
    if (card.parameters.size() >= max_parameters)
      throw DeckError(number, "*" + card.keyword + ": more than " + std::to_string(max_parameters) + " parameters");
    if (card.find(par.name) != nullptr)
      throw DeckError(number, "*" + card.keyword + ": parameter " + par.name + " given twice");
    card.parameters.push_back(std::move(par));
  }
  return card;
}

}  // namespace

const Parameter* Card::find(std::string_view name) const {
  for (const auto& p : parameters)
    if (p.name == name) return &p;
  return nullptr;
}

std::optional<std::string> Card::value(std::string_view name) const {
  const Parameter* p = find(name);
  if (p == nullptr) return std::nullopt;
  if (!p->has_value)
    throw DeckError(line, "*" + keyword + ": parameter " + std::string(name) + " needs a value (" +
                              std::string(name) + "=...)");
  return p->value;
}

std::string Card::required(std::string_view name) const {
  auto v = value(name);
  if (!v) throw DeckError(line, "*" + keyword + ": required parameter " + std::string(name) + " is missing");
  return *v;
}

std::vector<Card> lex_deck(std::string_view text) {
  if (text.size() > max_deck_bytes)
    throw DeckError(0, "deck is " + std::to_string(text.size()) + " bytes, above the limit of " +
                           std::to_string(max_deck_bytes));
  std::vector<Card> cards;
  std::string pending_keyword;  // a keyword line continued with a trailing comma
  int pending_line = 0;
  int number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view raw = text.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
    const std::string_view line = trim(raw);
    const bool comment = line.size() >= 2 && line[0] == '*' && line[1] == '*';
    const bool heading_text = !comment && pending_keyword.empty() && !cards.empty() &&
                              cards.back().keyword == "HEADING" && (line.empty() || line[0] != '*');
    check_bytes(raw, number, comment || heading_text);
    if (comment || line.empty()) continue;

    if (!pending_keyword.empty()) {  // continuation of a keyword line
      pending_keyword += line;
      if (line.back() == ',') continue;
      cards.push_back(parse_keyword_line(pending_keyword, pending_line));
      pending_keyword.clear();
      continue;
    }
    if (line[0] == '*') {
      if (line.back() == ',') {
        pending_keyword = line;
        pending_line = number;
        continue;
      }
      cards.push_back(parse_keyword_line(line, number));
      continue;
    }
    if (cards.empty()) throw DeckError(number, "data line before the first keyword line");
    DataLine d;
    d.line = number;
    d.text = line;
    d.fields = split_fields(line);
    d.ends_with_comma = line.back() == ',';
    if (d.ends_with_comma) d.fields.pop_back();  // the empty field after the last comma
    cards.back().data.push_back(std::move(d));
  }
  if (!pending_keyword.empty())
    throw DeckError(pending_line, "keyword line ends with a comma but the file ends (truncated deck?)");
  if (cards.empty()) throw DeckError(0, "deck has no keyword lines (empty or not an ABAQUS deck)");
  return cards;
}

}  // namespace ringcrush::fe::deck
