#include "fe/deck/deck_fields.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

#include "fe/deck/deck_error.hpp"

namespace ringcrush::fe::deck {

std::vector<Record> records(const Card& card) {
  std::vector<Record> out;
  bool continuing = false;
  for (const DataLine& d : card.data) {
    if (!continuing) out.push_back(Record{d.line, {}});
    out.back().fields.insert(out.back().fields.end(), d.fields.begin(), d.fields.end());
    continuing = d.ends_with_comma;
  }
  return out;
}

bool parse_real(const std::string& text, double& out) {
  std::string_view s = text;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  // from_chars also accepts "inf" and "nan": only digits, a point, a sign and an exponent
  // may appear in a deck number.
  for (char c : s)
    if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' || c == 'E' ||
          c == 'e'))
      return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size() && std::isfinite(out);
}

bool is_integer_text(const std::string& text) {
  std::string_view s = text;
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) s.remove_prefix(1);
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

bool parse_integer(const std::string& text, long long& out) {
  if (!is_integer_text(text)) return false;
  std::string_view s = text;
  if (s.front() == '+') s.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

void Fields::fail(const std::string& reason) const { throw DeckError(r_.line, "*" + card_.keyword + ": " + reason); }

double Fields::real(std::size_t i, const char* what) const {
  if (r_.empty_at(i)) fail(std::string("missing ") + what + " (field " + std::to_string(i + 1) + ")");
  double v = 0;
  if (!parse_real(r_.fields[i], v))
    fail(std::string(what) + " '" + r_.fields[i] + "' is not a finite number");
  return v;
}

double Fields::real_or(std::size_t i, double fallback, const char* what) const {
  return r_.empty_at(i) ? fallback : real(i, what);
}

long long Fields::integer(std::size_t i, const char* what) const {
  if (r_.empty_at(i)) fail(std::string("missing ") + what + " (field " + std::to_string(i + 1) + ")");
  long long v = 0;
  if (!parse_integer(r_.fields[i], v)) fail(std::string(what) + " '" + r_.fields[i] + "' is not an integer");
  return v;
}

long long Fields::integer_or(std::size_t i, long long fallback, const char* what) const {
  return r_.empty_at(i) ? fallback : integer(i, what);
}

int Fields::label(std::size_t i, const char* what) const {
  const long long v = integer(i, what);
  if (v < 1 || v > max_label)
    fail(std::string(what) + " " + std::to_string(v) + " outside 1.." + std::to_string(max_label));
  return static_cast<int>(v);
}

std::string Fields::word(std::size_t i, const char* what) const {
  if (r_.empty_at(i)) fail(std::string("missing ") + what + " (field " + std::to_string(i + 1) + ")");
  std::string w = r_.fields[i];
  for (char& c : w) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return w;
}

}  // namespace ringcrush::fe::deck
