#include "table_output.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace ringcrush::compare {

void CsvTable::add_row(std::vector<double> row) {
  if (row.size() != columns.size())
    throw std::logic_error(fmt::format("CsvTable: row of {} values for {} columns", row.size(), columns.size()));
  for (std::size_t i = 0; i < row.size(); ++i)
    if (!std::isfinite(row[i]))
      throw std::runtime_error(fmt::format("non-finite value in column {} at row {}", columns[i], rows.size()));
  rows.push_back(std::move(row));
}

std::vector<double> CsvTable::column(const std::string& name) const {
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c] != name) continue;
    std::vector<double> out;
    out.reserve(rows.size());
    for (const auto& r : rows) out.push_back(r[c]);
    return out;
  }
  throw std::out_of_range("CsvTable: no column " + name);
}

void CsvTable::write(const std::filesystem::path& file) const {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << '\n';
  for (const auto& r : rows) {
    for (std::size_t c = 0; c < r.size(); ++c) out << (c ? "," : "") << fmt::format("{:.10g}", r[c]);
    out << '\n';
  }
  if (!out) throw std::runtime_error("error writing " + file.string());
}

void require_finite(const nlohmann::json& value, const std::string& path) {
  if (value.is_number_float() && !std::isfinite(value.get<double>()))
    throw std::runtime_error(fmt::format("non-finite number at {} in summary", path.empty() ? "/" : path));
  if (value.is_object())
    for (auto it = value.begin(); it != value.end(); ++it) require_finite(*it, path + "/" + it.key());
  if (value.is_array())
    for (std::size_t i = 0; i < value.size(); ++i) require_finite(value[i], fmt::format("{}/{}", path, i));
}

void write_json(const std::filesystem::path& file, const nlohmann::json& value) {
  require_finite(value);
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  out << value.dump(2) << '\n';
  if (!out) throw std::runtime_error("error writing " + file.string());
}

}  // namespace ringcrush::compare
