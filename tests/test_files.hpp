// Files for the end-to-end tests: a fresh scratch directory per test, whole-file reads, and
// a shipped scene with some of its lines edited (the tests run cheap variants of the real
// scenes rather than copies that could drift from them).
#pragma once

#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace test_files {

namespace fs = std::filesystem;

// An empty directory <tmp>/<prefix><name>, removed first if a previous run left it.
inline fs::path scratch_dir(const std::string& prefix, const std::string& name) {
  const fs::path p = fs::temp_directory_path() / (prefix + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The comma-separated numbers of one line (deck data lines, CSV rows).
inline std::vector<double> numbers(const std::string& line) {
  std::vector<double> v;
  std::string item;
  std::istringstream in(line);
  while (std::getline(in, item, ',')) v.push_back(std::strtod(item.c_str(), nullptr));
  return v;
}

// The numeric rows of a CSV file after its header line (history.csv).
inline std::vector<std::vector<double>> csv_rows(const fs::path& p) {
  std::vector<std::vector<double>> rows;
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) rows.push_back(numbers(line));
  return rows;
}

// `source` (relative to the source tree) with each (regex, replacement) applied in order,
// written to `out`.
using Edits = std::vector<std::pair<std::string, std::string>>;
inline fs::path edited_scene(const std::string& source, const fs::path& out, const Edits& edits) {
  std::string text = read_text(fs::path(RINGCRUSH_SOURCE_DIR) / source);
  for (const auto& [pattern, value] : edits) text = std::regex_replace(text, std::regex(pattern), value);
  std::ofstream(out) << text;
  return out;
}

// The text of `source` (relative to the source tree) with `lines` inserted at the top of its
// `[table]` section: a shipped scene with a few keys added, parsed in memory by the scene
// tests (parse_scene) so that they follow the shipped file.
inline std::string scene_text_with(const std::string& source, const std::string& table, const std::string& lines) {
  std::string text = read_text(fs::path(RINGCRUSH_SOURCE_DIR) / source);
  const std::string header = "[" + table + "]\n";
  const auto at = text.find(header);
  if (at == std::string::npos) throw std::runtime_error(source + " has no " + header);
  text.insert(at + header.size(), lines + "\n");
  return text;
}

}  // namespace test_files
