// ringcrush compare SCENE -o DIR — the FE and the hinge model on the same impact, side by
// side, with agreement verdicts (issue 8 item 2; DESIGN.md "compare"; compare/compare_run.hpp).
//
//   ringcrush compare data/scenes/test30_welded.toml -o results/test30
//
// Prints the per-ring table and the verdicts with their thresholds, writes DIR completely
// or not at all, and says where the report is. Exit status 0 when the models agree, 3 when
// they disagree, 1 when a run fails, 2 for bad input.
#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "compare/cli/commands.hpp"
#include "compare/compare_run.hpp"
#include "compare/explain.hpp"
#include "compare/result_cache.hpp"

namespace ringcrush::compare::cli {
namespace {

namespace fs = std::filesystem;

struct CompareOptions {
  std::string scene;
  std::string output;
  bool no_cache = false;
  bool quiet = false;
  bool explain = false;
};

void print_outcome(const CompareOutcome& c) {
  const Agreement& a = c.agreement;
  fmt::print("\n{:>5} {:>9} {:>9} {:>8}  {:>7} {:>7}  {:<11} {:<11}\n", "ring", "FE crush", "hinge", "diff", "FE wrap",
             "h wrap", "FE mode", "hinge mode");
  for (const auto& r : a.rings)
    fmt::print("{:5d} {:9.3f} {:9.3f} {:+8.3f}  {:>7} {:>7}  {:<11} {:<11}\n", r.ring, r.fe_crush_ratio,
               r.hinge_crush_ratio, r.difference, r.fe_wrap ? "yes" : "no", r.hinge_wrap ? "yes" : "no", r.fe_mode,
               r.hinge_mode);
  fmt::print("\n{:<66} {:>8} {:>9}\n", "verdict", "value", "threshold");
  for (const auto& v : a.verdicts)
    fmt::print("{:<66} {:8.3g} {:9.3g}  {:<4}  {}\n", v.description, v.value, v.threshold, v.pass ? "pass" : "FAIL",
               v.detail);
}

void run(const CompareOptions& o) {
  const Scene scene = load_scene(o.scene);
  if (o.explain) {
    fmt::print("ringcrush compare {} would compute:\n", scene.name);
    for (const auto& line : explain_hinge(scene))
      if (line.find("FE model is not built") == std::string::npos) fmt::print("  hinge: {}\n", line);
    for (const auto& line : explain_fe(scene))
      if (line.find("hinge model is not built") == std::string::npos) fmt::print("  FE:    {}\n", line);
    fmt::print("  FE result served from the cache ({}) when the same scene ran with this build\n",
               o.no_cache ? "disabled by --no-cache" : ResultCache::default_root().string());
    return;
  }
  const fs::path target = o.output.empty() ? fs::path("results") / ("compare_" + scene.name) : fs::path(o.output);
  if (!o.quiet) fmt::print("scene {}: {}\n", scene.name, scene.title);
  CompareRunOptions options;
  options.use_cache = !o.no_cache;
  const bool tty = !o.quiet && isatty(fileno(stderr)) != 0;
  if (tty)
    options.fe_progress = [](const fe::DynamicProgress& p) {
      fmt::print(stderr, "\r  FE  t {:7.3f} ms  step {:8d}  dt {:.2e} s  v {:7.2f} m/s  KE {:5.1f} % ", 1e3 * p.time_s,
                 p.step, p.step_s, p.impactor_velocity_m_s, 100 * p.kinetic_fraction);
    };
  ResultsDir out(target);
  const CompareOutcome c = run_compare(scene, options, out);
  out.commit();
  if (tty) fmt::print(stderr, "\n");
  if (!o.quiet) {
    fmt::print("  hinge level {}: {:.3f} s\n", scene.hinge.level, c.hinge_wall_time_s);
    if (c.fe_from_cache)
      fmt::print("  FE: from the cache ({:.3f} s; the run took {:.2f} s)\n", c.fe_wall_time_s,
                 c.fe.statistics.wall_time_s);
    else
      fmt::print("  FE: {:.2f} s\n", c.fe_wall_time_s);
    print_outcome(c);
    fmt::print("\n{}\nreport: {}\n",
               c.agreement.agree ? "AGREE: every verdict passes" : "DISAGREE: at least one verdict fails",
               fs::absolute(target / "report.html").string());
  }
  if (!c.agreement.agree) command_exit_status() = exit_disagree;
}

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand("compare", "FE against the hinge model on one impact scene, with agreement verdicts");
  cmd->add_option("scene", o->scene, "Scene file (dynamic)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Results directory (default results/compare_SCENE)");
  cmd->add_flag("--no-cache", o->no_cache, "Run the FE even if an identical run is cached (and do not store it)");
  cmd->add_flag("-q,--quiet", o->quiet, "Print nothing on success");
  cmd->add_flag("--explain", o->explain, "Print what would be computed and why, and stop");
  cmd->callback([o] { run(*o); });
}

const CommandRegistration registration{15, add_compare_command};

}  // namespace
}  // namespace ringcrush::compare::cli
