#include "compare/run_result_io.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace ringcrush::compare {
namespace {

using nlohmann::json;

// Every vector<double> field of RunResult under its own name (one table, so writing and
// reading cannot drift apart).
struct VectorField {
  const char* name;
  std::vector<double> RunResult::*member;
};
constexpr VectorField vector_fields[] = {
    {"time_s", &RunResult::time_s},
    {"deflection_m", &RunResult::deflection_m},
    {"force_n", &RunResult::force_n},
    {"impactor_displacement_m", &RunResult::impactor_displacement_m},
    {"impactor_velocity_m_s", &RunResult::impactor_velocity_m_s},
    {"impactor_force_n", &RunResult::impactor_force_n},
    {"kinetic_j", &RunResult::kinetic_j},
    {"elastic_j", &RunResult::elastic_j},
    {"plastic_j", &RunResult::plastic_j},
    {"contact_j", &RunResult::contact_j},
    {"numerical_j", &RunResult::numerical_j},
    {"external_work_j", &RunResult::external_work_j},
    {"crush_ratio", &RunResult::crush_ratio},
    {"wrapped_angle_deg", &RunResult::wrapped_angle_deg},
    {"inverted_arc_m", &RunResult::inverted_arc_m},
    {"inverted_turning_deg", &RunResult::inverted_turning_deg},
};

void require_finite(const std::vector<double>& v, const char* name) {
  for (double x : v)
    if (!std::isfinite(x)) throw std::runtime_error(std::string("run result: non-finite value in ") + name);
}

const json& field(const json& j, const char* name) {
  if (!j.contains(name)) throw std::runtime_error(std::string("run result: missing field \"") + name + "\"");
  return j.at(name);
}

std::vector<double> numbers(const json& j, const char* name) {
  const json& a = field(j, name);
  if (!a.is_array()) throw std::runtime_error(std::string("run result: \"") + name + "\" is not an array");
  std::vector<double> v;
  v.reserve(a.size());
  for (const auto& x : a) {
    if (!x.is_number()) throw std::runtime_error(std::string("run result: \"") + name + "\" holds a non-number");
    v.push_back(x.get<double>());
  }
  require_finite(v, name);
  return v;
}

}  // namespace

json run_result_to_json(const RunResult& r) {
  json j;
  j["format_version"] = run_result_format_version;
  j["model"] = r.model;
  j["scene"] = r.scene;
  j["analysis"] = to_string(r.analysis);
  for (const auto& f : vector_fields) {
    require_finite(r.*f.member, f.name);
    j[f.name] = r.*f.member;
  }
  for (const auto& c : r.ring_crush_m) require_finite(c, "ring_crush_m");
  j["ring_crush_m"] = r.ring_crush_m;
  require_finite(r.bulk_viscous_j, "bulk_viscous_j");
  if (!r.bulk_viscous_j.empty()) j["bulk_viscous_j"] = r.bulk_viscous_j;  // optional field
  j["wrap_around"] = r.wrap_around;
  j["mode"] = r.mode;
  json outline = json::array();
  for (const auto& ring : r.ring_outline_m) {
    json pts = json::array();
    for (const auto& p : ring) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]))
        throw std::runtime_error("run result: non-finite value in ring_outline_m");
      pts.push_back({p[0], p[1]});
    }
    outline.push_back(std::move(pts));
  }
  j["ring_outline_m"] = std::move(outline);
  j["outline_half"] = r.outline_half;
  json events = json::array();
  for (const auto& e : r.events)
    events.push_back({{"time_s", e.time_s}, {"kind", e.kind}, {"ring", e.ring}, {"detail", e.detail}});
  j["events"] = std::move(events);
  j["statistics"] = {{"steps", r.statistics.steps},
                     {"rejected_steps", r.statistics.rejected_steps},
                     {"newton_iterations", r.statistics.newton_iterations},
                     {"wall_time_s", r.statistics.wall_time_s}};
  j["extra"] = r.extra;
  return j;
}

RunResult run_result_from_json(const json& j) {
  if (!j.is_object()) throw std::runtime_error("run result: not a JSON object");
  if (field(j, "format_version").get<int>() != run_result_format_version)
    throw std::runtime_error("run result: unsupported format_version");
  RunResult r;
  r.model = field(j, "model").get<std::string>();
  r.scene = field(j, "scene").get<std::string>();
  const std::string analysis = field(j, "analysis").get<std::string>();
  if (analysis == "static") r.analysis = AnalysisType::Static;
  else if (analysis == "dynamic") r.analysis = AnalysisType::Dynamic;
  else throw std::runtime_error("run result: analysis must be \"static\" or \"dynamic\"");
  for (const auto& f : vector_fields) r.*f.member = numbers(j, f.name);
  if (j.contains("bulk_viscous_j")) r.bulk_viscous_j = numbers(j, "bulk_viscous_j");
  for (const auto& c : field(j, "ring_crush_m")) {
    std::vector<double> v = c.get<std::vector<double>>();
    require_finite(v, "ring_crush_m");
    r.ring_crush_m.push_back(std::move(v));
  }
  r.wrap_around = field(j, "wrap_around").get<std::vector<bool>>();
  r.mode = field(j, "mode").get<std::vector<std::string>>();
  for (const auto& ring : field(j, "ring_outline_m")) {
    std::vector<std::array<double, 2>> pts;
    for (const auto& p : ring) {
      if (!p.is_array() || p.size() != 2) throw std::runtime_error("run result: ring_outline_m points are [x, y]");
      pts.push_back({p[0].get<double>(), p[1].get<double>()});
      if (!std::isfinite(pts.back()[0]) || !std::isfinite(pts.back()[1]))
        throw std::runtime_error("run result: non-finite value in ring_outline_m");
    }
    r.ring_outline_m.push_back(std::move(pts));
  }
  r.outline_half = field(j, "outline_half").get<bool>();
  for (const auto& e : field(j, "events"))
    r.events.push_back({e.at("time_s").get<double>(), e.at("kind").get<std::string>(), e.at("ring").get<int>(),
                        e.at("detail").get<std::string>()});
  const json& s = field(j, "statistics");
  r.statistics.steps = s.at("steps").get<long>();
  r.statistics.rejected_steps = s.at("rejected_steps").get<long>();
  r.statistics.newton_iterations = s.at("newton_iterations").get<long>();
  r.statistics.wall_time_s = s.at("wall_time_s").get<double>();
  r.extra = field(j, "extra");
  return r;
}

RunResult read_run_result(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("run result: cannot open " + file.string());
  json j;
  try {
    in >> j;
  } catch (const json::exception& e) {
    throw std::runtime_error("run result: " + file.string() + " is not JSON (" + e.what() + ")");
  }
  return run_result_from_json(j);
}

}  // namespace ringcrush::compare
