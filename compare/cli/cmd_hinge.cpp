// ringcrush hinge SCENE -o DIR — the plastic-hinge mechanism models of a ring chain under
// impact (THEORY §3.2, §4.2–4.4; DESIGN.md "hinge").
//
//   ringcrush hinge data/scenes/test30_plates.toml -o results/hinge30 --level 1
//   ringcrush hinge data/scenes/test30_welded.toml -o results/l0 --level 0 --integrator odeint
//   ringcrush hinge data/scenes/test30_plates.toml -o results/shock --level shock
//
// Levels: 0 (elastic–plastic ring springs, lumped masses), 1 (rigid–plastic DeRuntz–Hodge/
// Redwood rings with distributed inertia, rigid rings by complementarity), shock (Reid–Bell–
// Barr r-p-p-l), and 2 / 3 when built in. The level, integrator and tolerances come from the
// scene's [hinge] table unless given as flags. A correct run echoes the options, then prints
// the crush per ring, arrest time, peak force, energy-balance error and solver statistics,
// and writes summary.json, history.csv and crush/impactor/force/energy SVG plots.
#include <fmt/format.h>

#include <optional>

#include "compare/cli/commands.hpp"
#include "compare/hinge_levels.hpp"
#include "compare/results_dir.hpp"
#include "compare/run_output.hpp"

namespace ringcrush::compare::cli {
namespace {

struct HingeOptions {
  std::string scene;
  std::string output;
  std::optional<std::string> level;
  std::optional<std::string> integrator;
  std::optional<double> rtol, atol;
  bool quiet = false;
};

HingeRunOptions resolve(const Scene& s, const HingeOptions& o) {
  HingeRunOptions r;
  r.level = o.level ? *o.level : s.hinge.level;
  r.integrator = s.hinge.integrator;
  if (o.integrator) {
    if (*o.integrator == "ida") r.integrator = HingeIntegrator::Ida;
    else if (*o.integrator == "odeint") r.integrator = HingeIntegrator::Odeint;
    else if (*o.integrator == "central_difference") r.integrator = HingeIntegrator::CentralDifference;
    else throw std::invalid_argument(
        fmt::format("--integrator must be ida, odeint or central_difference (level 2), not \"{}\"", *o.integrator));
  }
  r.relative_tolerance = o.rtol ? *o.rtol : s.hinge.relative_tolerance;
  r.absolute_tolerance = o.atol ? *o.atol : s.hinge.absolute_tolerance;
  if (!(r.relative_tolerance > 0 && r.relative_tolerance < 1))
    throw std::invalid_argument("--rtol must lie in (0, 1)");
  if (!(r.absolute_tolerance > 0)) throw std::invalid_argument("--atol must be positive");
  return r;
}

void run(const HingeOptions& o) {
  const Scene scene = load_scene(o.scene);
  const HingeRunOptions opt = resolve(scene, o);
  const auto& registry = hinge_level_registry();
  const auto it = registry.find(opt.level);
  if (it == registry.end()) {
    std::string known;
    for (const auto& [name, runner] : registry) known += (known.empty() ? "" : ", ") + name;
    throw std::invalid_argument(fmt::format("hinge level \"{}\" is not available in this build (available: {})",
                                            opt.level, known.empty() ? "none" : known));
  }
  const char* integ = hinge_integrator_name(opt.integrator);
  if (!o.quiet) {
    fmt::print("scene {}: {}\n", scene.name, scene.title);
    fmt::print("hinge level {} on {}, rtol {:g}, atol {:g}; {} rings, joints {}, far end {}\n", opt.level,
               integ, opt.relative_tolerance, opt.absolute_tolerance, scene.rings.count,
               to_string(scene.joints.type), scene.far_end == FarEnd::Fixed ? "fixed" : "free");
    if (scene.impactor)
      fmt::print("impactor {:g} kg at {:g} m/s (KE {:.3f} J); Redwood alpha {:g}\n", scene.impactor->mass_kg,
                 scene.impactor->velocity_m_s,
                 0.5 * scene.impactor->mass_kg * scene.impactor->velocity_m_s * scene.impactor->velocity_m_s,
                 scene.hinge.redwood_alpha);
  }
  const RunResult r = it->second(scene, opt);
  const auto summary = summary_json(r, scene);

  if (!o.quiet) {
    fmt::print("\n{:>5} {:>10} {:>8}  {}\n", "ring", "crush_mm", "ratio", "mode");
    for (std::size_t i = 0; i < r.crush_ratio.size(); ++i)
      fmt::print("{:5d} {:10.3f} {:8.4f}  {}\n", i + 1, r.crush_ratio[i] * scene.rings.outer_diameter_m * 1e3,
                 r.crush_ratio[i], i < r.mode.size() ? r.mode[i] : "");
    if (r.extra.contains("moment_ratio_max")) {  // Level 3 statics check (> 1: another hinge needed)
      fmt::print("largest |M|/M_p per ring (statics check; M_p = M0 x Redwood factor):");
      for (const auto& v : r.extra["moment_ratio_max"]) fmt::print(" {:.3f}", v.get<double>());
      fmt::print("\n");
    }
    if (scene.analysis.type == AnalysisType::Static) {
      fmt::print("\nmax force {:.1f} N at final deflection {:.3f} mm\n", summary["max_force_N"].get<double>(),
                 summary["final_deflection_m"].get<double>() * 1e3);
    } else {
      const auto& ta = summary["arrest_time_s"];
      fmt::print("\narrest {}   peak force {:.1f} N   final velocity {:.3f} m/s\n",
                 ta.is_number() ? fmt::format("{:.4f} ms", ta.get<double>() * 1e3) : std::string("not reached"),
                 summary["peak_force_N"].get<double>(), summary["impactor_final_velocity_m_s"].get<double>());
      fmt::print("alternation index {:.3f} (A1 {:.3f})   energy balance error {:.2e}\n",
                 summary["alternation_index"].get<double>(), summary["alternation"]["A1_lag1"].get<double>(),
                 summary["energy_balance_error"].get<double>());
    }
    fmt::print("{} steps, {} rejected, {} Newton iterations, {} events, wall {:.3f} ms\n", r.statistics.steps,
               r.statistics.rejected_steps, r.statistics.newton_iterations, r.events.size(),
               r.statistics.wall_time_s * 1e3);
  }
  if (o.output.empty()) return;
  ResultsDir out(o.output);
  write_run_result(r, scene, out);
  out.commit();
  if (!o.quiet) fmt::print("wrote {}/{{summary.json, history.csv, *.svg}}\n", out.target().string());
}

void add_hinge_command(CLI::App& app) {
  auto o = std::make_shared<HingeOptions>();
  auto* cmd = app.add_subcommand("hinge", "Plastic-hinge mechanism model of the ring chain (THEORY §3.2, §4)");
  cmd->add_option("scene", o->scene, "Scene file")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Results directory (written completely or not at all)");
  cmd->add_option("--level", o->level, "Model level: 0, 1, 2, 3, shock; default from the scene");
  cmd->add_option("--integrator", o->integrator, "ida | odeint | central_difference (level 2); default from the scene");
  cmd->add_option("--rtol", o->rtol, "Relative tolerance; default from the scene");
  cmd->add_option("--atol", o->atol, "Absolute tolerance; default from the scene");
  cmd->add_flag("-q,--quiet", o->quiet, "Print nothing on success");
  cmd->callback([o] { run(*o); });
}

const CommandRegistration registration{30, add_hinge_command};

}  // namespace
}  // namespace ringcrush::compare::cli
