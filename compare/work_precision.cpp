#include "compare/work_precision.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

#include "compare/agreement.hpp"
#include "compare/measures.hpp"
#include "compare/run_output.hpp"
#include "compare/svg_plot.hpp"

namespace ringcrush::compare {
namespace {

double relative_error(double value, double reference) {
  if (reference == 0.0) return value == 0.0 ? 0.0 : 1.0;
  return std::abs(value - reference) / std::abs(reference);
}

// The peak force of the agreement verdicts (impactor force averaged over its window), or
// the peak plate force of a static run (peak_mean_force falls back to the plain peak).
double peak_of(const RunResult& r) { return peak_mean_force(r, AgreementThresholds{}.peak_force_window_s); }

std::string number(double x) {
  if (!std::isfinite(x)) throw std::runtime_error(fmt::format("bench.csv: refusing to write the non-finite {}", x));
  return fmt::format("{:.6g}", x);
}

std::string optional_number(const std::optional<double>& x) { return x ? number(*x) : ""; }

std::string text(std::string s) {
  for (char& c : s)
    if (c == '"' || c == '\n') c = '\'';
  return s.find(',') == std::string::npos ? s : "\"" + s + "\"";
}

}  // namespace

RunErrors run_errors(const RunResult& run, const RunResult& reference) {
  if (run.crush_ratio.empty() || run.crush_ratio.size() != reference.crush_ratio.size())
    throw std::invalid_argument(fmt::format("run_errors: {} rings against {} in the reference",
                                            run.crush_ratio.size(), reference.crush_ratio.size()));
  RunErrors e;
  for (std::size_t i = 0; i < run.crush_ratio.size(); ++i)
    e.crush = std::max(e.crush, std::abs(run.crush_ratio[i] - reference.crush_ratio[i]));
  e.energy = relative_error(absorbed_energy(run), absorbed_energy(reference));
  e.peak_force = relative_error(peak_of(run), peak_of(reference));
  return e;
}

RunMeasures run_measures(const RunResult& run) {
  RunMeasures m;
  m.crush_ratio = run.crush_ratio;
  m.absorbed_energy_j = absorbed_energy(run);
  m.peak_force_n = peak_of(run);
  m.alternation_index = alternation(run.crush_ratio).index;
  m.steps = run.statistics.steps;
  return m;
}

std::string series_label(const BenchRow& row) {
  if (row.model == "hinge") return fmt::format("hinge {} {}", row.level_or_mesh, row.integrator);
  return fmt::format("{} {}", row.model, row.integrator);
}

void write_bench_csv(const std::filesystem::path& file, const std::vector<BenchRow>& rows) {
  std::size_t rings = 0;
  for (const auto& r : rows) rings = std::max(rings, r.measures.crush_ratio.size());
  std::string out =
      "group,model,scene,level_or_mesh,integrator,control,tolerance,reference,repeats,wall_s,cpu_s,bytes_written,"
      "steps,error_vs_reference,energy_error_vs_reference,peak_force_error_vs_reference,model_error_vs_fe,"
      "model_energy_error_vs_fe,model_peak_force_error_vs_fe,absorbed_energy_J,peak_force_N,alternation_index";
  for (std::size_t i = 0; i < rings; ++i) out += fmt::format(",crush_ratio_ring_{}", i + 1);
  out += '\n';
  for (const auto& r : rows) {
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", text(r.group), text(r.model), text(r.scene),
                       text(r.level_or_mesh), text(r.integrator), text(r.control), optional_number(r.tolerance),
                       r.reference ? 1 : 0, r.repeats, number(r.wall_s), number(r.cpu_s),
                       optional_number(r.bytes_written), r.measures.steps, number(r.error.crush),
                       number(r.error.energy), number(r.error.peak_force));
    if (r.model_error)
      out += fmt::format(",{},{},{}", number(r.model_error->crush), number(r.model_error->energy),
                         number(r.model_error->peak_force));
    else
      out += ",,,";
    out += fmt::format(",{},{},{}", number(r.measures.absorbed_energy_j), number(r.measures.peak_force_n),
                       number(r.measures.alternation_index));
    for (std::size_t i = 0; i < rings; ++i) {
      out += ',';
      if (i < r.measures.crush_ratio.size()) out += number(r.measures.crush_ratio[i]);
    }
    out += '\n';
  }
  std::ofstream f(file);
  if (!f) throw std::runtime_error("cannot write " + file.string());
  f << out;
}

std::string render_work_precision(const std::vector<BenchRow>& rows, const std::string& title, bool model_error) {
  std::map<std::string, Series> series;
  std::vector<std::string> order;
  for (const auto& r : rows) {
    if (r.group != "work_precision") continue;
    const bool use_model = model_error && r.model_error.has_value();
    const double e = use_model ? r.model_error->crush : r.error.crush;
    if (!(e > 0.0) || !(r.cpu_s > 0.0)) continue;  // a reference (0) has no place on a log axis
    const std::string label = series_label(r);
    if (!series.count(label)) {
      order.push_back(label);
      Series s;
      s.label = label;
      // A hinge level's runs come in tolerance order: a line is its work–precision curve.
      // The FE runs vary mesh and step control at once: points.
      s.markers = r.model != "hinge";
      s.dashed = r.integrator == "ida" || r.integrator == "explicit";
      series.emplace(label, s);
    }
    series[label].x.push_back(r.cpu_s);
    series[label].y.push_back(e);
  }
  SvgPlot plot(title, "CPU time of one run (s)",
               model_error ? "max |crush ratio - finest FE| (hinge) / vs FE reference (FE)"
                           : "max |crush ratio - reference of the same model|");
  plot.set_log_axes(true, true);
  for (const auto& label : order) plot.add(series[label]);
  return plot.render();
}

std::string bench_table(const std::vector<BenchRow>& rows) {
  std::string out = fmt::format("{:<15} {:<6} {:<11} {:<8} {:<10} {:>8} {:>3} {:>10} {:>10} {:>10} {:>9} {:>9} {:>9} {:>10}\n",
                                "group", "model", "level/mesh", "integ", "control", "tol", "ref", "cpu_s", "wall_s",
                                "bytes", "err_crush", "err_E", "err_F", "model_err");
  for (const auto& r : rows)
    out += fmt::format("{:<15} {:<6} {:<11} {:<8} {:<10} {:>8} {:>3} {:>10.4g} {:>10.4g} {:>10} {:>9.2e} {:>9.2e} {:>9.2e} {:>10}\n",
                       r.group, r.model, r.level_or_mesh, r.integrator, r.control,
                       r.tolerance ? fmt::format("{:g}", *r.tolerance) : "", r.reference ? "*" : "", r.cpu_s,
                       r.wall_s, r.bytes_written ? fmt::format("{:.0f}", *r.bytes_written) : "", r.error.crush,
                       r.error.energy, r.error.peak_force,
                       r.model_error ? fmt::format("{:.3e}", r.model_error->crush) : "");
  return out;
}

}  // namespace ringcrush::compare
