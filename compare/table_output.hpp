// CSV tables and summary.json, refusing to write non-finite numbers (DESIGN.md: no NaN in
// outputs; a NaN here is a solver failure that must be reported, not written).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ringcrush::compare {

struct CsvTable {
  std::vector<std::string> columns;  // names with units, e.g. "deflection_m"
  std::vector<std::vector<double>> rows;

  void add_row(std::vector<double> row);
  std::vector<double> column(const std::string& name) const;
  void write(const std::filesystem::path& file) const;
};

// Throws std::runtime_error naming the first non-finite number's JSON path.
void require_finite(const nlohmann::json& value, const std::string& path = "");
void write_json(const std::filesystem::path& file, const nlohmann::json& value);

}  // namespace ringcrush::compare
