#include "compare/compare_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "compare/fe_dynamic.hpp"
#include "compare/hinge_levels.hpp"
#include "compare/report_html.hpp"
#include "compare/result_cache.hpp"
#include "compare/run_output.hpp"
#include "compare/run_result_io.hpp"
#include "compare/svg_charts.hpp"
#include "compare/table_output.hpp"
#include "compare/version.hpp"

namespace ringcrush::compare {
namespace {

namespace fs = std::filesystem;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const HingeLevelRunner& hinge_runner(const Scene& scene) {
  const auto& levels = hinge_level_registry();
  const auto it = levels.find(scene.hinge.level);
  if (it == levels.end())
    throw std::invalid_argument(fmt::format("compare: hinge level \"{}\" is not available in this build",
                                            scene.hinge.level));
  return it->second;
}

// The FE run's results directory at `dir`: copied from the cache when an identical run is
// there, else run, written completely and stored.
bool fe_results(const Scene& scene, const CompareRunOptions& o, const fs::path& dir) {
  // From the text the scene was parsed from (a sweep case has no file of its own yet).
  const std::string canonical = canonical_scene_text(scene.text, scene.source.string());
  const ResultCache cache;
  const std::string key = ResultCache::key("fe", canonical, "", code_identity());
  if (o.use_cache)
    if (auto hit = cache.lookup(key); hit && fs::exists(*hit / "run_result.json")) {
      fs::copy(*hit, dir, fs::copy_options::recursive);
      return true;
    }
  const fe::ChainInput chain = fe_chain_input(scene);
  const fe::DynamicSolverInput solver = fe_dynamic_solver_input(scene);
  fe::DynamicCallbacks cb;
  cb.progress = o.fe_progress;
  const fe::DynamicResult result = fe::run_dynamic(chain, solver, cb);
  const RunResult run = fe_dynamic_run_result(scene, result);
  {
    ResultsDir out(dir);
    write_fe_dynamic_outputs(scene, result, run, out);
    out.commit();
  }
  if (o.use_cache) cache.store(key, dir);
  return false;
}

}  // namespace

CompareOutcome run_compare(const Scene& scene, const CompareRunOptions& o, ResultsDir& out) {
  if (scene.analysis.type != AnalysisType::Dynamic || !scene.impactor)
    throw std::invalid_argument("compare: the scene must be a dynamic impact (analysis.type = \"dynamic\")");
  (void)fe_chain_input(scene);  // refuse what the FE cannot run before spending time on the hinge model
  const HingeLevelRunner& hinge_run = hinge_runner(scene);

  CompareOutcome c;
  // The staging directory of `out`: the models' own results directories go inside it.
  const fs::path staging = out.file("summary.json").parent_path();
  {
    const HingeRunOptions opt{scene.hinge.level, scene.hinge.integrator, scene.hinge.relative_tolerance,
                              scene.hinge.absolute_tolerance};
    const auto t0 = std::chrono::steady_clock::now();
    c.hinge = hinge_run(scene, opt);
    c.hinge_wall_time_s = seconds_since(t0);
    ResultsDir h(staging / "hinge");
    write_run_result(c.hinge, scene, h);
    h.commit();
  }
  {
    const auto t0 = std::chrono::steady_clock::now();
    c.fe_from_cache = fe_results(scene, o, staging / "fe");
    c.fe_wall_time_s = seconds_since(t0);
    c.fe = read_run_result(staging / "fe" / "run_result.json");
  }
  c.agreement = assess_agreement(c.fe, c.hinge, o.thresholds);

  nlohmann::json summary;
  summary["model"] = "compare";
  summary["scene"] = scene.name;
  summary["analysis"] = "dynamic";
  summary["version"] = std::string(version());
  summary["wall_time_s"] = c.fe_wall_time_s + c.hinge_wall_time_s;
  summary["steps"] = c.fe.statistics.steps + c.hinge.statistics.steps;
  summary["crush_ratio"] = c.fe.crush_ratio;  // the verifier's, for sweep tables
  summary["fe"] = {{"solver", scene.fe.solver == FeSolver::Hht ? "hht" : "explicit"},
                   {"wall_time_s", c.fe.statistics.wall_time_s},
                   {"from_cache", c.fe_from_cache},
                   {"crush_ratio", c.fe.crush_ratio},
                   {"wrap_around", c.fe.wrap_around},
                   {"alternation_index", c.agreement.fe_alternation_index}};
  summary["hinge"] = {{"level", scene.hinge.level},
                      {"wall_time_s", c.hinge_wall_time_s},
                      {"crush_ratio", c.hinge.crush_ratio},
                      {"wrap_around", c.hinge.wrap_around},
                      {"alternation_index", c.agreement.hinge_alternation_index}};
  summary["agree"] = c.agreement.agree;
  summary["agreement"] = to_json(c.agreement, o.thresholds);
  write_json(out.file("summary.json"), summary);

  ReportInput report;
  report.scene = &scene;
  report.fe = &c.fe;
  report.hinge = &c.hinge;
  report.agreement = &c.agreement;
  report.thresholds = o.thresholds;
  report.fe_wall_time_s = c.fe.statistics.wall_time_s;
  report.hinge_wall_time_s = c.hinge_wall_time_s;
  report.fe_from_cache = c.fe_from_cache;
  report.code_version = std::string(version());
  std::ofstream(out.file("report.html")) << render_report_html(report);

  std::vector<std::string> categories;
  std::vector<double> cf, ch;
  for (const auto& r : c.agreement.rings) {
    categories.push_back(fmt::format("ring {}", r.ring));
    cf.push_back(r.fe_crush_ratio);
    ch.push_back(r.hinge_crush_ratio);
  }
  std::ofstream(out.file("crush_compare.svg"))
      << render_bar_chart("Final crush ratio per ring — " + scene.name, "crush ratio", categories,
                          {{"FE", cf}, {"hinge", ch}});
  return c;
}

}  // namespace ringcrush::compare
