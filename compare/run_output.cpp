#include "compare/run_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "compare/measures.hpp"
#include "compare/run_result_io.hpp"
#include "compare/shape_output.hpp"
#include "compare/svg_plot.hpp"
#include "compare/version.hpp"

namespace ringcrush::compare {
namespace {

double initial_kinetic_energy(const Scene& s) {
  if (!s.impactor) return 0.0;
  return 0.5 * s.impactor->mass_kg * s.impactor->velocity_m_s * s.impactor->velocity_m_s;
}

double at(const std::vector<double>& v, std::size_t i) { return i < v.size() ? v[i] : 0.0; }

std::vector<double> scaled(const std::vector<double>& v, double f) {
  std::vector<double> out(v);
  for (auto& x : out) x *= f;
  return out;
}

}  // namespace

double energy_balance_error(const RunResult& r, const Scene& scene) {
  const double e0 = initial_kinetic_energy(scene);
  if (!(e0 > 0.0)) return 0.0;
  double worst = 0.0;
  for (std::size_t i = 0; i < r.kinetic_j.size(); ++i) {
    const double total = at(r.kinetic_j, i) + at(r.elastic_j, i) + at(r.plastic_j, i) +
                         at(r.contact_j, i) + at(r.numerical_j, i) + at(r.bulk_viscous_j, i) -
                         at(r.external_work_j, i);
    worst = std::max(worst, std::abs(total - e0));
  }
  return worst / e0;
}

double peak_force(const RunResult& r) {
  double peak = 0.0;
  for (double f : r.impactor_force_n) peak = std::max(peak, f);
  for (double f : r.force_n) peak = std::max(peak, f);
  return peak;
}

double peak_mean_force(const RunResult& r, double window_s) {
  const auto& t = r.time_s;
  const auto& f = r.impactor_force_n;
  const std::size_t n = std::min(t.size(), f.size());
  if (n < 2 || window_s <= 0.0) return peak_force(r);
  // Trapezoidal integral of F over [t_i, t_i + window] for every sample start i.
  double peak = 0.0;
  std::size_t j = 0;
  double integral = 0.0;  // over [t_i, t_j]
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) integral -= 0.5 * (f[i - 1] + f[i]) * (t[i] - t[i - 1]);
    if (j < i) { j = i; integral = 0.0; }
    while (j + 1 < n && t[j + 1] - t[i] <= window_s * (1.0 + 1e-9)) {
      integral += 0.5 * (f[j] + f[j + 1]) * (t[j + 1] - t[j]);
      ++j;
    }
    const double span = t[j] - t[i];
    if (span >= 0.5 * window_s) peak = std::max(peak, integral / span);
  }
  return peak > 0.0 ? peak : peak_force(r);
}

double mean_force(const RunResult& r) {
  const auto& x = r.impactor_displacement_m;
  const auto& f = r.impactor_force_n;
  const std::size_t n = std::min(x.size(), f.size());
  double work = 0.0, travel = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const double dx = x[i] - x[i - 1];
    if (dx > 0.0) work += 0.5 * (f[i] + f[i - 1]) * dx;  // loading travel only
    travel = std::max(travel, x[i]);
  }
  return travel > 0.0 ? work / travel : 0.0;
}

double absorbed_energy(const RunResult& r) { return r.plastic_j.empty() ? 0.0 : r.plastic_j.back(); }

double arrest_time(const RunResult& r) {
  if (r.extra.contains("arrest_time_s")) {
    const auto& a = r.extra["arrest_time_s"];
    return a.is_number() ? a.get<double>() : -1.0;
  }
  const auto& v = r.impactor_velocity_m_s;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i - 1] > 0.0 && v[i] <= 0.0) {
      const double f = v[i - 1] / (v[i - 1] - v[i]);
      return r.time_s[i - 1] + f * (r.time_s[i] - r.time_s[i - 1]);
    }
  return -1.0;
}

nlohmann::json summary_json(const RunResult& r, const Scene& scene) {
  nlohmann::json j = {{"model", r.model},
                      {"scene", r.scene},
                      {"analysis", to_string(r.analysis)},
                      {"version", std::string(version())},
                      {"wall_time_s", r.statistics.wall_time_s},
                      {"steps", r.statistics.steps},
                      {"rejected_steps", r.statistics.rejected_steps},
                      {"newton_iterations", r.statistics.newton_iterations}};
  if (r.analysis == AnalysisType::Dynamic) {
    const auto alt = alternation(r.crush_ratio);
    j["crush_ratio"] = r.crush_ratio;
    j["wrap_around"] = r.wrap_around;
    j["wrapped_angle_deg"] = r.wrapped_angle_deg;
    j["inverted_arc_m"] = r.inverted_arc_m;
    j["inverted_turning_deg"] = r.inverted_turning_deg;
    j["mode"] = r.mode;
    j["alternation_index"] = alt.index;
    j["alternation"] = {{"A1_lag1", alt.lag1},
                        {"A2_amplitude", alt.amplitude},
                        {"sign_change_fraction", alt.sign_change_fraction},
                        {"alternates", alt.index > alternation_threshold}};
    j["energy_balance_error"] = energy_balance_error(r, scene);
    const double ta = arrest_time(r);
    j["arrest_time_s"] = ta >= 0.0 ? nlohmann::json(ta) : nlohmann::json();
    j["peak_force_N"] = peak_force(r);
    j["impactor_final_velocity_m_s"] = r.impactor_velocity_m_s.empty() ? 0.0 : r.impactor_velocity_m_s.back();
    j["initial_kinetic_energy_J"] = initial_kinetic_energy(scene);
    if (!r.kinetic_j.empty()) {
      j["final_energy_J"] = {{"kinetic", r.kinetic_j.back()},
                             {"elastic", at(r.elastic_j, r.kinetic_j.size() - 1)},
                             {"plastic", at(r.plastic_j, r.kinetic_j.size() - 1)},
                             {"contact", at(r.contact_j, r.kinetic_j.size() - 1)},
                             {"numerical", at(r.numerical_j, r.kinetic_j.size() - 1)},
                             {"external_work", at(r.external_work_j, r.kinetic_j.size() - 1)}};
      if (!r.bulk_viscous_j.empty()) j["final_energy_J"]["bulk_viscous"] = r.bulk_viscous_j.back();
    }
  } else {
    j["max_force_N"] = peak_force(r);
    j["final_deflection_m"] = r.deflection_m.empty() ? 0.0 : r.deflection_m.back();
  }
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : r.events)
    events.push_back({{"time_s", e.time_s},
                      {"kind", e.kind},
                      {"ring", e.ring >= 0 ? nlohmann::json(e.ring + 1) : nlohmann::json()},
                      {"detail", e.detail}});
  j["events"] = events;
  for (auto it = r.extra.begin(); it != r.extra.end(); ++it)
    if (!j.contains(it.key())) j[it.key()] = it.value();
  return j;
}

CsvTable history_table(const RunResult& r) {
  CsvTable t;
  const bool dynamic = r.analysis == AnalysisType::Dynamic;
  const auto& first = dynamic ? r.time_s : r.deflection_m;
  t.columns.push_back(dynamic ? "time_s" : "deflection_m");
  if (dynamic) {
    t.columns.insert(t.columns.end(), {"impactor_displacement_m", "impactor_velocity_m_s", "impactor_force_N"});
  } else {
    t.columns.push_back("force_N");
  }
  for (std::size_t i = 0; i < r.ring_crush_m.size(); ++i) t.columns.push_back(fmt::format("crush_ring_{}_m", i + 1));
  const bool energies = !r.kinetic_j.empty() || !r.plastic_j.empty();
  if (energies)
    t.columns.insert(t.columns.end(), {"kinetic_J", "elastic_J", "plastic_J", "contact_J", "numerical_J", "external_work_J"});
  const bool viscous = !r.bulk_viscous_j.empty();  // explicit FE with bulk viscosity
  if (viscous) t.columns.push_back("bulk_viscous_J");
  for (std::size_t k = 0; k < first.size(); ++k) {
    std::vector<double> row{first[k]};
    if (dynamic) {
      row.push_back(at(r.impactor_displacement_m, k));
      row.push_back(at(r.impactor_velocity_m_s, k));
      row.push_back(at(r.impactor_force_n, k));
    } else {
      row.push_back(at(r.force_n, k));
    }
    for (const auto& c : r.ring_crush_m) row.push_back(at(c, k));
    if (energies)
      for (const auto* e : {&r.kinetic_j, &r.elastic_j, &r.plastic_j, &r.contact_j, &r.numerical_j, &r.external_work_j})
        row.push_back(at(*e, k));
    if (viscous) row.push_back(at(r.bulk_viscous_j, k));
    t.add_row(std::move(row));
  }
  return t;
}

void write_run_plots(const RunResult& r, const Scene& scene, ResultsDir& out) {
  if (r.analysis != AnalysisType::Dynamic || r.time_s.empty()) return;
  const auto ms = scaled(r.time_s, 1e3);
  const std::string who = fmt::format("{} {}", r.model, r.extra.contains("level") ? "level " + r.extra["level"].get<std::string>() : "");
  {
    SvgPlot p(fmt::format("Crush per ring — {} ({})", scene.name, who), "time (ms)", "crush δ (mm)");
    for (std::size_t i = 0; i < r.ring_crush_m.size(); ++i)
      p.add({fmt::format("ring {}", i + 1), ms, scaled(r.ring_crush_m[i], 1e3)});
    p.write(out.file("crush.svg"));
  }
  {
    SvgPlot p(fmt::format("Final crush ratio — {} ({})", scene.name, who), "ring", "crush ratio δ/D");
    std::vector<double> idx;
    for (std::size_t i = 0; i < r.crush_ratio.size(); ++i) idx.push_back(static_cast<double>(i + 1));
    p.add({"c_i", idx, r.crush_ratio, false, true});
    p.add({"", idx, r.crush_ratio, true, false});
    p.write(out.file("crush_final.svg"));
  }
  {
    SvgPlot p(fmt::format("Impactor velocity — {} ({})", scene.name, who), "time (ms)", "velocity (m/s)");
    p.add({"impactor", ms, r.impactor_velocity_m_s});
    p.write(out.file("impactor.svg"));
  }
  {
    SvgPlot p(fmt::format("Impactor force — {} ({})", scene.name, who), "time (ms)", "force (N)");
    p.add({"impactor", ms, r.impactor_force_n});
    p.write(out.file("force.svg"));
  }
  {
    SvgPlot p(fmt::format("Energies — {} ({})", scene.name, who), "time (ms)", "energy (J)");
    p.add({"kinetic", ms, r.kinetic_j});
    if (!r.elastic_j.empty()) p.add({"elastic", ms, r.elastic_j});
    p.add({"plastic", ms, r.plastic_j});
    if (!r.contact_j.empty()) p.add({"contact / impact", ms, r.contact_j});
    std::vector<double> total;
    for (std::size_t i = 0; i < r.time_s.size(); ++i)
      total.push_back(at(r.kinetic_j, i) + at(r.elastic_j, i) + at(r.plastic_j, i) + at(r.contact_j, i) +
                      at(r.numerical_j, i) - at(r.external_work_j, i));
    p.add({"total", ms, total, true});
    p.write(out.file("energy.svg"));
  }
}

void write_run_result(const RunResult& r, const Scene& scene, ResultsDir& out) {
  write_json(out.file("summary.json"), summary_json(r, scene));
  history_table(r).write(out.file("history.csv"));
  // The whole RunResult, for `ringcrush compare` (cached runs) and scripts.
  write_json(out.file("run_result.json"), run_result_to_json(r));
  if (scene.outputs.plots) write_run_plots(r, scene, out);
  write_shape_frames(r, out);  // models with shapes; the runner picked outputs.frames of them
  if (scene.outputs.plots) write_final_shapes_svg(r, scene, out);
}

}  // namespace ringcrush::compare
