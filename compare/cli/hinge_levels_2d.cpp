// Level 2 of the hinge model (hinge-spring polygon rings, THEORY §4.3–4.4) behind
// `ringcrush hinge SCENE --level 2`, the same run with its ring shapes, and its benchmark:
//
//   ringcrush hinge data/scenes/test30_welded.toml -o results/l2 --level 2
//   ringcrush hinge-shapes data/scenes/test30_welded.toml -o results/l2shapes [--frames 40]
//   ringcrush bench-hinge2 data/scenes/test30_welded.toml --repeat 5 [--integrator odeint]
//   ringcrush bench-hinge2 data/scenes/test30_welded.toml --integrator central_difference [--safety 0.8]
//       [--dampers implicit|explicit] [--step-breakdown]
//       [--step-bound gershgorin|power] [--landing 0.002] [--membrane-scale 0.25] [--penalty-scale 0.25]
//       [--membrane implicit|explicit]
//
// `hinge --level 2` writes summary.json, history.csv, the SVG plots, shapes.pvd +
// frames/shape_NNNN.vtp (ring mean lines over time for ParaView, with the plastic rotation
// per node; outputs.frames of them, none with outputs.fields = false) and shapes_final.svg
// (compare/shape_output.hpp). hinge-shapes is the same run with frames forced on and their
// number from --frames.
//
// bench-hinge2 runs the scene `repeat` times on one core and prints every wall time, the
// median, the steps, and the final crush per ring with the wrap flags, so that the speed is
// reported next to what it bought.
#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "compare/cli/commands.hpp"
#include "compare/hinge_run_2d.hpp"
#include "compare/results_dir.hpp"
#include "compare/run_output.hpp"

namespace ringcrush::compare {
namespace {

const HingeLevelRegistration level2{"2", run_hinge_level2};

// Level 2 run options from the command line, defaulting to the scene's.
HingeRunOptions level2_options(const Scene& scene, const std::string& integrator, std::optional<double> rtol) {
  HingeRunOptions opt;
  opt.level = "2";
  if (integrator == "ida") opt.integrator = HingeIntegrator::Ida;
  else if (integrator == "odeint") opt.integrator = HingeIntegrator::Odeint;
  else if (integrator == "central_difference") opt.integrator = HingeIntegrator::CentralDifference;
  else throw std::invalid_argument("--integrator must be ida, odeint or central_difference, not \"" + integrator + "\"");
  opt.relative_tolerance = rtol ? *rtol : scene.hinge.relative_tolerance;
  return opt;
}

struct BenchOptions {
  std::string scene;
  int repeat = 5;
  std::string integrator = "ida";
  std::optional<double> rtol;
  std::optional<double> safety;
  std::optional<int> jacobian_reuse, klu_ordering;
  std::optional<double> pattern_slack;
  std::string dampers = "implicit";
  bool step_breakdown = false;
  std::string step_bound = "power";
  std::optional<double> landing;
  std::optional<double> membrane_scale, penalty_scale;
  std::optional<std::string> membrane;  // implicit | explicit; unset: the scene's
};

// Quantiles of the step-bound breakdown over the run's samples (stable_step_breakdown,
// hinge/polygon_stiffness_spectrum.hpp): the Gershgorin step, each term's share, and how far
// the power-iteration 2/ω_max lies above the bound.
void print_step_breakdown(const std::vector<std::pair<double, hinge::StableStepBreakdown>>& samples) {
  if (samples.empty()) return;
  auto quantiles = [&](auto get) {
    std::vector<double> v;
    for (const auto& s : samples) v.push_back(get(s.second));
    std::sort(v.begin(), v.end());
    auto at = [&](double q) { return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))]; };
    return fmt::format("min {:.3g}  p10 {:.3g}  median {:.3g}  p90 {:.3g}  max {:.3g}", v.front(), at(0.1),
                       at(0.5), at(0.9), v.back());
  };
  int unconverged = 0;
  for (const auto& s : samples) unconverged += s.second.converged ? 0 : 1;
  fmt::print("step-bound breakdown over {} samples ({} power iterations not converged to 1e-4):\n",
             samples.size(), unconverged);
  using B = hinge::StableStepBreakdown;
  fmt::print("  Gershgorin step (us, no safety): {}\n", quantiles([](const B& b) { return b.gershgorin * 1e6; }));
  const std::pair<const char*, double B::*> rows[] = {
      {"power iteration 2/omega_max", &B::power_iteration},
      {"without membrane", &B::without_membrane},
      {"without hinges", &B::without_hinges},
      {"without ties", &B::without_ties},
      {"without contacts", &B::without_contacts},
      {"membrane only", &B::membrane_only},
      {"hinges only", &B::hinges_only},
      {"ties only", &B::ties_only},
      {"contacts only", &B::contacts_only}};
  for (const auto& [name, field] : rows)
    fmt::print("  {} / Gershgorin: {}\n", name, quantiles([f = field](const B& b) { return b.*f / b.gershgorin; }));
}

void bench(const BenchOptions& o) {
  const Scene scene = load_scene(o.scene);
  const HingeRunOptions opt = level2_options(scene, o.integrator, o.rtol);
  Level2Settings settings = level2_settings(scene, opt.integrator);
  if (o.safety) settings.central_difference_safety = *o.safety;
  if (o.jacobian_reuse) settings.jacobian_reuse_steps = *o.jacobian_reuse;
  if (o.klu_ordering) settings.klu_ordering = *o.klu_ordering;
  if (o.pattern_slack) settings.pattern_slack = *o.pattern_slack;
  if (o.dampers != "implicit" && o.dampers != "explicit")
    throw std::invalid_argument("--dampers must be implicit or explicit, not \"" + o.dampers + "\"");
  settings.central_difference_implicit_dampers = o.dampers == "implicit";
  // Explicit dampers without --membrane: the explicit membrane (the default's implicit one
  // needs the implicit dampers), at the scales the scene resolved to.
  if (!o.membrane && o.dampers == "explicit") settings.central_difference_implicit_membrane = false;
  if (o.membrane) {
    if (*o.membrane != "implicit" && *o.membrane != "explicit")
      throw std::invalid_argument("--membrane must be implicit or explicit, not \"" + *o.membrane + "\"");
    settings.central_difference_implicit_membrane = *o.membrane == "implicit";
  }
  if (settings.central_difference_implicit_membrane && !settings.central_difference_implicit_dampers)
    throw std::invalid_argument("--membrane implicit needs --dampers implicit (one banded solve for both)");
  settings.step_breakdown = o.step_breakdown;
  if (o.step_bound != "gershgorin" && o.step_bound != "power")
    throw std::invalid_argument("--step-bound must be gershgorin or power, not \"" + o.step_bound + "\"");
  settings.central_difference_power_bound = o.step_bound == "power";
  if (o.landing) {
    if (!(*o.landing >= 0.0)) throw std::invalid_argument("--landing must be ≥ 0");
    settings.central_difference_landing_depth_ratio = *o.landing;
  }
  // The stiff-term scales replace the scene's (Level2Settings::membrane_stiffness_scale).
  const auto scale = [](std::optional<double> v, const char* flag) {
    if (!(*v > 0.0 && *v <= 1.0)) throw std::invalid_argument(fmt::format("{} must lie in (0, 1], not {}", flag, *v));
    return *v;
  };
  if (o.membrane_scale) settings.membrane_stiffness_scale = scale(o.membrane_scale, "--membrane-scale");
  if (o.penalty_scale) {
    const Level2Settings unscaled;
    settings.contact_stiffness_scale = unscaled.contact_stiffness_scale * scale(o.penalty_scale, "--penalty-scale");
    settings.tie_stiffness_scale = unscaled.tie_stiffness_scale * *o.penalty_scale;
  }
  std::vector<double> walls;
  Level2Run last;
  for (int i = 0; i < o.repeat; ++i) {
    last = run_level2(scene, opt, settings);
    walls.push_back(last.raw.wall_time_s);
    fmt::print("run {}: {:.3f} s, {} steps\n", i + 1, walls.back(), last.raw.steps);
  }
  std::vector<double> sorted = walls;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  fmt::print("scene {} level 2 ({}, N = {}, rtol {:g}): median wall {:.3f} s over {} runs; {} steps, "
             "{} residuals, {} Jacobian setups ({} symbolic), {} linear iterations, energy balance {:.2e}\n",
             scene.name, o.integrator, scene.hinge.nodes_per_ring, last.relative_tolerance_used, median,
             walls.size(), last.raw.steps, last.raw.rhs_evaluations, last.raw.jacobian_setups,
             last.raw.symbolic_factorisations, last.raw.linear_iterations, last.raw.energy_balance_error);
  if (opt.integrator == HingeIntegrator::Ida)
    fmt::print("IDA: {} matrix formations, {} new patterns, {} kept patterns, {} rejected steps, {} Newton "
               "iterations\n",
               last.raw.jacobian_formations, last.raw.pattern_rebuilds, last.raw.pattern_remaps,
               last.raw.rejected_steps, last.raw.nonlinear_iterations);
  if (opt.integrator == HingeIntegrator::CentralDifference)
    fmt::print("central difference: {} dampers, {} step bound ({} estimates), landing {:g} t ({} steps), safety {:g}, "
               "steps {:.3g}–{:.3g} s ({:.2f} us per step), shortest flow relaxation time {:.3g} s\n",
               o.dampers,
               o.step_bound == "power" && o.dampers == "explicit" ? "gershgorin (power needs implicit dampers)"
                                                                   : o.step_bound,
               last.raw.power_refreshes, settings.central_difference_landing_depth_ratio,
               last.raw.landing_steps, settings.central_difference_safety,
               last.raw.min_step_s, last.raw.max_step_s,
               median / static_cast<double>(std::max(1L, last.raw.steps)) * 1e6, last.raw.min_flow_relaxation_s);
  if (opt.integrator == HingeIntegrator::CentralDifference && settings.central_difference_implicit_membrane)
    fmt::print("implicit membrane: correction work {:.3g} J ({:.2e} of KE0; in the damping energy)\n",
               last.raw.membrane_correction_work_j,
               last.raw.membrane_correction_work_j / std::max(last.raw.initial_energy_j, 1e-300));
  print_step_breakdown(last.raw.step_breakdown);
  fmt::print("stiff terms: membrane x {:g}, contact x {:g}, ties x {:g}; over the samples max penetration "
             "{:.3g} t, max membrane strain {:.3g}\n",
             settings.membrane_stiffness_scale, settings.contact_stiffness_scale, settings.tie_stiffness_scale,
             last.raw.max_penetration_m / scene.rings.wall_thickness_m, last.raw.max_membrane_strain);
  const auto alt = alternation(last.result.crush_ratio);
  fmt::print("alternation index {:.3f} (A1 {:.3f}), arrest {:.3f} ms\n", alt.index, alt.lag1,
             last.raw.arrest_time_s * 1e3);
  for (std::size_t r = 0; r < last.result.crush_ratio.size(); ++r)
    fmt::print("ring {}: c = {:.3f}  W = {:5.1f} deg  S = {:5.1f} mm  T = {:5.1f} deg  {}\n", r + 1,
               last.result.crush_ratio[r], last.result.wrapped_angle_deg[r], last.result.inverted_arc_m[r] * 1e3,
               last.result.inverted_turning_deg[r], last.result.mode[r]);
}

void add_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand("bench-hinge2", "Benchmark the Level 2 polygon-ring hinge model on a scene");
  cmd->add_option("scene", o->scene, "Scene file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--repeat", o->repeat, "Number of runs (median reported)")->check(CLI::Range(1, 1000));
  cmd->add_option("--integrator", o->integrator, "ida | odeint | central_difference");
  cmd->add_option("--rtol", o->rtol, "Relative tolerance (Level 2 raises values below 1e-6 to 1e-3)");
  cmd->add_option("--safety", o->safety, "central_difference: factor on the stable-step bound, in (0, 1]");
  cmd->add_option("--jacobian-reuse", o->jacobian_reuse, "ida: steps a formed dphi/dy may serve (0: every setup)");
  cmd->add_option("--klu-ordering", o->klu_ordering, "ida: KLU ordering, 0 AMD, 1 COLAMD, 2 natural");
  cmd->add_option("--pattern-slack", o->pattern_slack, "ida: fraction of stale zero entries kept in the pattern, [0, 1)");
  cmd->add_option("--dampers", o->dampers,
                  "central_difference: Kelvin–Voigt ring dampers implicit (default) | explicit");
  cmd->add_option("--step-bound", o->step_bound,
                  "central_difference: power (default: power-iteration estimate of omega_max; implicit dampers "
                  "only, explicit ones keep the damped bound) | gershgorin");
  cmd->add_option("--landing", o->landing,
                  "central_difference: contact landing depth as a fraction of t (default 0.001; 0: off)");
  cmd->add_option("--membrane-scale", o->membrane_scale,
                  "factor on the membrane bars' EA, in (0, 1] (default: the scene's level2_membrane_stiffness_scale)");
  cmd->add_option("--penalty-scale", o->penalty_scale,
                  "factor on the contact and tie penalty stiffness, in (0, 1] (default: the scene's "
                  "level2_penalty_stiffness_scale)");
  cmd->add_option("--membrane", o->membrane,
                  "central_difference: membrane bars implicit (out of the step bound; needs implicit dampers) | "
                  "explicit (default: the scene's level2_implicit_membrane, else implicit; explicit with --dampers "
                  "explicit)");
  cmd->add_flag("--step-breakdown", o->step_breakdown,
               "at every output sample: the stable-step bound with each stiffness term left out, and the "
               "power-iteration 2/omega_max (diagnostic)");
  cmd->callback([o] { bench(*o); });
}

const cli::CommandRegistration bench_registration{92, add_bench_command};

struct ShapesOptions {
  std::string scene;
  std::string output;
  std::string integrator = "ida";
  std::optional<double> rtol;
  std::optional<int> frames;
};

void shapes(const ShapesOptions& o) {
  Scene scene = load_scene(o.scene);
  if (o.frames) scene.outputs.frames = *o.frames;
  scene.outputs.fields = true;
  const HingeRunOptions opt = level2_options(scene, o.integrator, o.rtol);
  fmt::print("scene {}: {}\nhinge level 2 (polygon rings, N = {}) on {}\n", scene.name, scene.title,
             scene.hinge.nodes_per_ring, o.integrator);
  const auto run = run_level2(scene, opt, level2_settings(scene, opt.integrator));
  const auto& r = run.result;
  for (std::size_t i = 0; i < r.crush_ratio.size(); ++i)
    fmt::print("ring {}: c = {:.3f}  W = {:5.1f} deg  S = {:5.1f} mm  T = {:5.1f} deg  {}\n", i + 1, r.crush_ratio[i],
               r.wrapped_angle_deg[i], r.inverted_arc_m[i] * 1e3, r.inverted_turning_deg[i], r.mode[i]);
  fmt::print("alternation index {:.3f}, energy balance {:.2e}, {} steps, wall {:.2f} s\n",
             alternation(r.crush_ratio).index, run.raw.energy_balance_error, run.raw.steps,
             run.raw.wall_time_s);
  ResultsDir out(o.output);
  write_run_result(r, scene, out);  // with the shape frames and shapes_final.svg
  out.commit();
  fmt::print("wrote {}/{{summary.json, history.csv, shapes.pvd, frames/, shapes_final.svg, *.svg}}\n",
             out.target().string());
}

void add_shapes_command(CLI::App& app) {
  auto o = std::make_shared<ShapesOptions>();
  auto* cmd = app.add_subcommand("hinge-shapes", "Level 2 hinge model run with ring shapes (ParaView polylines, SVG)");
  cmd->add_option("scene", o->scene, "Scene file")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Results directory (written completely or not at all)")->required();
  cmd->add_option("--integrator", o->integrator, "ida | odeint | central_difference");
  cmd->add_option("--rtol", o->rtol, "Relative tolerance (Level 2 raises values below 1e-6 to 1e-3)");
  cmd->add_option("--frames", o->frames, "Shape frames over the run; default from the scene")->check(CLI::Range(2, 100000));
  cmd->callback([o] { shapes(*o); });
}

const cli::CommandRegistration shapes_registration{31, add_shapes_command};

}  // namespace
}  // namespace ringcrush::compare
