// Reading the fields of data lines with the line number in every error: numbers must be
// finite decimal numbers (NaN and Inf are refused), labels integers in [1, max_label].
// A data line that ends with a comma continues on the next line: lines are merged into
// records first (ABAQUS 4.8 continuation rule, used by the static deck's *SLIDE LINE).
#pragma once

#include <string>
#include <vector>

#include "fe/deck/deck_lexer.hpp"

namespace ringcrush::fe::deck {

struct Record {
  int line = 0;  // line of the record's first data line
  std::vector<std::string> fields;

  std::size_t size() const { return fields.size(); }
  bool empty_at(std::size_t i) const { return i >= fields.size() || fields[i].empty(); }
};

std::vector<Record> records(const Card& card);

// Field access bound to one keyword (for the message prefix "*NGEN: ").
class Fields {
 public:
  Fields(const Card& card, const Record& record) : card_(card), r_(record) {}

  double real(std::size_t i, const char* what) const;                  // required
  double real_or(std::size_t i, double fallback, const char* what) const;
  long long integer(std::size_t i, const char* what) const;            // required
  long long integer_or(std::size_t i, long long fallback, const char* what) const;
  int label(std::size_t i, const char* what) const;                    // node/element number
  std::string word(std::size_t i, const char* what) const;             // upper case, required
  [[noreturn]] void fail(const std::string& reason) const;

  const Record& record() const { return r_; }

 private:
  const Card& card_;
  const Record& r_;
};

// Parses a whole field as a finite real / an integer; false if it is not one.
bool parse_real(const std::string& text, double& out);
bool parse_integer(const std::string& text, long long& out);
bool is_integer_text(const std::string& text);

}  // namespace ringcrush::fe::deck
