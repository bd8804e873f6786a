// RunResult as JSON, both ways (run_result.json in every results directory): what lets
// `ringcrush compare` serve a cached FE run without re-running it (issue 8 item 2), and lets
// scripts read a whole run, histories included, in one file.
//
// The format is the RunResult field names; non-finite numbers are refused on writing (a
// result with NaN is a failed run, DESIGN.md "Quality bars") and on reading.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "compare/run_result.hpp"

namespace ringcrush::compare {

// 2 (session 18): inverted_turning_deg per ring.
inline constexpr int run_result_format_version = 2;

nlohmann::json run_result_to_json(const RunResult& r);
// Throws std::runtime_error naming the missing or malformed field.
RunResult run_result_from_json(const nlohmann::json& j);

RunResult read_run_result(const std::filesystem::path& file);

}  // namespace ringcrush::compare
