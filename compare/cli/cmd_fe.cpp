// ringcrush fe SCENE -o DIR — the CPS8 finite-element model (thesis §3.4, §3.6; DESIGN.md "fe").
//
//   ringcrush fe data/scenes/thesis_static.toml -o results/fe_static
//
// A static scene crushes one ring between rigid plates (the driven top plate travels
// analysis.crush_m) and writes summary.json, history.csv (deflection_m, force_N for the
// whole ring, energies), load_deflection.svg (with DeRuntz–Hodge and Redwood) and, if
// outputs.fields, frames/*.vtu + series.pvd. A correct run prints the options, the initial
// contact check, one updating progress line, then the peak load and the run statistics.
// A failed solve prints its diagnosis, exits 1 and leaves no results directory.
//
//   ringcrush fe data/scenes/thesis_dynamic.toml -o results/thesis_dynamic [--solver explicit]
//
// A dynamic scene (issue 4; thesis §3.5, §4.2) runs the ring chain under impact with the
// explicit central-difference or the HHT-α driver until the impactor stops or rebounds and
// the rings are at rest, and writes summary.json, history.csv, rings.csv, SVG plots and
// ParaView frames (compare/fe_dynamic.hpp). --solver and --elements-around override the scene.
//
// ringcrush bench-fe-static [SCENE] — the performance and mesh-convergence benchmark of the
// static crush (README "Measured results"): the scene on its own mesh, on a 4× finer mesh
// (2× around, 2× through), and a mesh convergence study of the load at δ/d = 0.3, 0.6
// (meshes refined 1×, 2×, 3× in both directions, plus 4× for information).
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "compare/cli/commands.hpp"
#include "compare/deck_scene.hpp"
#include "compare/explain.hpp"
#include "compare/cli/fe_dynamic_terminal.hpp"
#include "compare/fe_dynamic.hpp"
#include "compare/fe_static.hpp"
#include "compare/results_dir.hpp"

namespace ringcrush::compare::cli {
namespace {

struct FeOptions {
  std::string scene;
  std::string output;
  bool quiet = false;
  bool explain = false;
  std::string solver;       // "explicit" | "hht": overrides fe.solver of a dynamic scene
  int elements_around = 0;  // > 0: overrides fe.elements_around
  double end_time_s = 0;    // > 0: overrides analysis.end_time_s of a dynamic scene (timings)
  int threads = 0;          // element-loop threads of a dynamic run (0: automatic, chain_input.hpp)
  std::string step_bound;   // explicit: "element" | "assembled" (the scene default; compare/scene.hpp)
  double mass_scaling_dt = -1;  // ≥ 0: overrides fe.mass_scaling_dt (explicit; 0 = off)
  double penalty_step_fraction = -1;  // ≥ 0: overrides fe.contact_penalty_step_fraction (0 = off)
  std::optional<double> safety;  // overrides fe.explicit_safety (as bench-fe-dynamic --safety)
};

const char* integration_name(fe::Integration i) {
  switch (i) {
    case fe::Integration::Full: return "full 3x3";
    case fe::Integration::Reduced: return "reduced 2x2";
    case fe::Integration::Selective: return "selective (3x3, volumetric at 2x2)";
  }
  return "?";
}

fe::StaticCallbacks terminal_callbacks(bool quiet) {
  fe::StaticCallbacks cb;
  const bool tty = isatty(fileno(stderr)) != 0;
  cb.log = [quiet](const std::string& m) {
    if (!quiet) fmt::print(stderr, "{}\n", m);
  };
  if (!quiet && tty)
    cb.progress = [](const fe::StaticProgress& p) {
      fmt::print(stderr, "\r  {:5.1f} %  delta {:7.3f} mm  P {:9.2f} N  inc {:5d}  d{:.2e}  it {:2d} ",
                 100 * p.fraction, p.deflection_m * 1e3, p.force_n, p.step, p.increment, p.iterations);
      if (p.fraction >= 1.0) fmt::print(stderr, "\n");
    };
  return cb;
}

void echo(const Scene& s, const fe::FeInput& in) {
  fmt::print("scene {}: {}\n", s.name, s.title);
  fmt::print("  ring D = {:.2f} mm, t = {:.2f} mm, L = {:.2f} mm; E = {:.0f} GPa, nu = {:.2f}, {} hardening points\n",
             2e3 * in.ring.outer_radius_m, 1e3 * (in.ring.outer_radius_m - in.ring.inner_radius_m),
             1e3 * in.ring.width_m, in.material.youngs_modulus_pa / 1e9, in.material.poisson_ratio,
             in.material.hardening.size());
  fmt::print("  mesh: {} ring, {} CPS8 around (per half) x {} through, grading {:g}; integration {}\n",
             in.mesh.half_ring ? "half" : "full", in.mesh.elements_around, in.mesh.elements_through,
             in.mesh.grading, integration_name(in.integration));
  fmt::print("  contact: penalty scale {:g}, smoothing {:g}, inner-wall self contact {}\n",
             in.contact.penalty_scale, in.contact.smoothing, in.contact.self_contact ? "on" : "off");
  fmt::print("  static: crush {:.2f} mm, increments initial {:g} / min {:g} / max {:g}, PTOL {:g} N, {} iterations\n",
             in.solver.crush_m * 1e3, in.solver.initial_increment, in.solver.min_increment,
             in.solver.max_increment, in.solver.force_tolerance_n, in.solver.max_iterations);
}

// The scene with the command-line overrides applied.
Scene scene_with_overrides(const FeOptions& o) {
  // An ABAQUS deck (.inp, issue 5 item 2) runs as its equivalent scene (compare/deck_scene.hpp).
  const std::filesystem::path file(o.scene);
  Scene s = file.extension() == ".inp" || file.extension() == ".INP" ? scene_from_deck(file) : load_scene(file);
  if (o.elements_around > 0) {
    if (o.elements_around % 2 != 0)
      throw std::invalid_argument(fmt::format("ringcrush fe: --elements-around {} must be even", o.elements_around));
    s.fe.elements_around = o.elements_around;
  }
  if (!o.solver.empty()) {
    if (s.analysis.type == AnalysisType::Static)
      throw std::invalid_argument("ringcrush fe: --solver applies to dynamic scenes only");
    s.fe.solver = o.solver == "hht" ? FeSolver::Hht : FeSolver::Explicit;
  }
  if (o.mass_scaling_dt >= 0) {
    if (s.analysis.type == AnalysisType::Static)
      throw std::invalid_argument("ringcrush fe: --mass-scaling-dt applies to dynamic scenes (explicit solver) only");
    s.fe.mass_scaling_dt = o.mass_scaling_dt;
  }
  if (o.penalty_step_fraction >= 0) {
    if (s.analysis.type == AnalysisType::Static)
      throw std::invalid_argument("ringcrush fe: --penalty-step-fraction applies to dynamic scenes only");
    if (o.penalty_step_fraction > 0.5)
      throw std::invalid_argument(fmt::format(
          "ringcrush fe: --penalty-step-fraction {} must be 0 (off) or lie in (0, 0.5]", o.penalty_step_fraction));
    s.fe.contact_penalty_step_fraction = o.penalty_step_fraction;
  }
  if (o.safety) {
    if (s.analysis.type == AnalysisType::Static)
      throw std::invalid_argument("ringcrush fe: --safety applies to dynamic scenes (explicit solver) only");
    if (!(*o.safety > 0 && *o.safety <= 1))
      throw std::invalid_argument(fmt::format("ringcrush fe: --safety {} must lie in (0, 1]", *o.safety));
    s.fe.explicit_safety = *o.safety;
  }
  if (o.end_time_s > 0) {
    if (s.analysis.type == AnalysisType::Static)
      throw std::invalid_argument("ringcrush fe: --end-time applies to dynamic scenes only");
    s.analysis.end_time_s = o.end_time_s;
  }
  return s;
}

void run_fe_dynamic(const Scene& s, const FeOptions& o) {
  fe::ChainInput chain = fe_chain_input(s);
  chain.threads = o.threads;
  // --step-bound overrides the scene's [fe] step_bound.
  if (o.step_bound == "assembled") chain.step_bound = fe::StepBound::Assembled;
  if (o.step_bound == "element") chain.step_bound = fe::StepBound::Element;
  const fe::DynamicSolverInput solver = fe_dynamic_solver_input(s);
  if (!o.quiet) {
    echo_dynamic(s, chain, solver);
    std::fflush(stdout);  // the echo before the progress line on stderr
  }
  ResultsDir out(o.output);
  const fe::DynamicResult r = fe::run_dynamic(chain, solver, dynamic_terminal_callbacks(o.quiet));
  const RunResult run = fe_dynamic_run_result(s, r);
  write_fe_dynamic_outputs(s, r, run, out);
  out.commit();
  if (!o.quiet) print_dynamic_result(s, r, run);
  fmt::print("wrote {}\n", out.target().string());
}

void run_fe(const FeOptions& o) {
  const Scene s = scene_with_overrides(o);
  if (o.explain) {
    fmt::print("ringcrush fe {} would compute:\n", s.name);
    for (const auto& line : explain_fe(s)) fmt::print("  {}\n", line);
    return;
  }
  if (o.output.empty()) throw std::invalid_argument("ringcrush fe: -o DIR is required");
  if (s.analysis.type == AnalysisType::Dynamic) return run_fe_dynamic(s, o);
  const fe::FeInput in = fe_static_input(s);
  if (!o.quiet) {
    echo(s, in);
    std::fflush(stdout);  // the echo before the progress line on stderr
  }
  ResultsDir out(o.output);
  const fe::StaticResult r = fe::run_static(in, terminal_callbacks(o.quiet));
  const RunResult run = fe_static_run_result(s, r);
  write_fe_static_outputs(s, r, run, out);
  out.commit();
  const auto& st = r.statistics;
  double pmax = 0;
  for (double p : run.force_n) pmax = std::max(pmax, p);
  fmt::print("done: delta = {:.3f} mm, P = {:.2f} N (max {:.2f} N); {} increments, {} cut-backs, {} Newton "
             "iterations ({:.2f}/increment), {:.3f} s ({:.1f} us/iteration)\n",
             run.deflection_m.back() * 1e3, run.force_n.back(), pmax, st.increments, st.cutbacks,
             st.newton_iterations, st.increments ? double(st.newton_iterations) / double(st.increments) : 0.0,
             st.wall_time_s, st.newton_iterations ? 1e6 * st.wall_time_s / double(st.newton_iterations) : 0.0);
  fmt::print("wrote {}\n", out.target().string());
}

void add_fe_command(CLI::App& app) {
  auto o = std::make_shared<FeOptions>();
  auto* cmd = app.add_subcommand(
      "fe", "CPS8 finite-element model of a scene (static crush, thesis §3.4, §3.6; impact of a chain, §3.5, §4.2)");
  cmd->add_option("scene", o->scene, "Scene file (.toml), or an ABAQUS deck (.inp) of the thesis")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Results directory (written completely or not at all; required)");
  cmd->add_flag("-q,--quiet", o->quiet, "No progress or echo on the terminal");
  cmd->add_flag("--explain", o->explain, "Print what the run would compute and why, and stop");
  cmd->add_option("--solver", o->solver, "Dynamic scenes: override fe.solver")
      ->check(CLI::IsMember({"explicit", "hht"}));
  cmd->add_option("--elements-around", o->elements_around, "Override fe.elements_around (per half ring, even)")
      ->check(CLI::Range(8, 4096));
  cmd->add_option("--end-time", o->end_time_s, "Dynamic scenes: override analysis.end_time_s (s)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threads", o->threads, "Dynamic scenes: element-loop threads (0 automatic, 1, 2)")
      ->check(CLI::Range(0, 2));
  cmd->add_option("--step-bound", o->step_bound,
                  "Explicit: stable-step omega_max from the element bound or the assembled power-iteration estimate")
      ->check(CLI::IsMember({"element", "assembled"}));
  cmd->add_option("--safety", o->safety,
                  "Explicit: step = safety x 2/omega_max, in (0, 1]; overrides fe.explicit_safety (default 0.8)");
  cmd->add_option("--mass-scaling-dt", o->mass_scaling_dt,
                  "Explicit: fixed mass scaling to this target step (s; 0 off), overrides fe.mass_scaling_dt "
                  "(changes the physics: the added mass is reported)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--penalty-step-fraction", o->penalty_step_fraction,
                  "Dynamic: lower the contact penalty until its springs cost at most this fraction of the element "
                  "step (0 off, (0, 0.5]), overrides fe.contact_penalty_step_fraction")
      ->check(CLI::NonNegativeNumber);
  cmd->callback([o] { run_fe(*o); });
}

// ---- benchmark -------------------------------------------------------------------------

struct BenchOptions {
  std::string scene = "data/scenes/thesis_static.toml";
  int repeats = 3;
  bool convergence = true;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

using fe::load_at;

void run_bench(const BenchOptions& o) {
  const Scene s = load_scene(o.scene);
  fe::FeInput base = fe_static_input(s);
  base.solver.frames = 0;
  fmt::print("bench-fe-static: {} (one core; median of {} runs)\n", s.name, o.repeats);
  fmt::print("{:>22} {:>6} {:>6} {:>6} {:>6} {:>9} {:>9} {:>10} {:>10}\n", "mesh", "elems", "dofs", "incs",
             "cuts", "it/inc", "us/it", "median_s", "Pmax_N");
  auto bench = [&](const std::string& label, fe::FeInput in) {
    std::vector<double> times;
    fe::StaticResult r;
    for (int k = 0; k < o.repeats; ++k) {
      r = fe::run_static(in);
      times.push_back(r.statistics.wall_time_s);
    }
    const auto& st = r.statistics;
    double pmax = 0;
    for (const auto& h : r.history) pmax = std::max(pmax, h.force_n);
    fmt::print("{:>22} {:>6} {:>6} {:>6} {:>6} {:>9.2f} {:>9.1f} {:>10.3f} {:>10.2f}\n", label,
               r.mesh.elements.size(), 2 * r.mesh.nodes.size(), st.increments, st.cutbacks,
               double(st.newton_iterations) / double(st.increments),
               1e6 * st.wall_time_s / double(st.newton_iterations), median(times), pmax);
    return r;
  };
  auto mesh_label = [](const fe::FeInput& in) {
    return fmt::format("{}x{} ({})", in.mesh.elements_around, in.mesh.elements_through,
                       in.mesh.half_ring ? "half" : "full");
  };
  bench(mesh_label(base), base);
  fe::FeInput fine = base;
  fine.mesh.elements_around *= 2;
  fine.mesh.elements_through *= 2;
  bench(mesh_label(fine) + " 4x", fine);
  if (!o.convergence) return;
  // Mesh convergence of the load at δ/d = 0.3 and 0.6 (issue 3 verification f): the scene's
  // mesh refined 1×, 2×, 3× in both directions; a 4× row is printed for information.
  const double d = s.rings.outer_diameter_m - s.rings.wall_thickness_m;
  fmt::print("\nmesh convergence (load at delta/d = 0.3 and 0.6):\n{:>22} {:>12} {:>12} {:>10}\n", "mesh",
             "P(0.3)_N", "P(0.6)_N", "time_s");
  std::vector<std::pair<double, double>> loads;
  for (int k = 1; k <= 4; ++k) {
    fe::FeInput in = base;
    in.mesh.elements_around = base.mesh.elements_around * k;
    in.mesh.elements_through = base.mesh.elements_through * k;
    in.solver.crush_m = std::min(base.solver.crush_m, 0.61 * d);
    const fe::StaticResult r = fe::run_static(in);
    loads.emplace_back(load_at(r, 0.3 * d), load_at(r, 0.6 * d));
    fmt::print("{:>22} {:>12.2f} {:>12.2f} {:>10.3f}\n", mesh_label(in) + (k == 4 ? " (info)" : ""),
               loads.back().first, loads.back().second, r.statistics.wall_time_s);
  }
  fmt::print("1x/2x/3x: the two finest (2x, 3x) differ by {:.2f} % at 0.3 and {:.2f} % at 0.6\n",
             100 * std::abs(loads[2].first - loads[1].first) / loads[2].first,
             100 * std::abs(loads[2].second - loads[1].second) / loads[2].second);
}

void add_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand("bench-fe-static",
                                 "Benchmark the FE static crush: own mesh, 4x finer mesh, mesh convergence");
  cmd->add_option("scene", o->scene, "Static scene (default data/scenes/thesis_static.toml)")->check(CLI::ExistingFile);
  cmd->add_option("--repeats", o->repeats, "Timed runs per mesh (median reported)")->check(CLI::Range(1, 50));
  cmd->add_flag("!--no-convergence", o->convergence, "Skip the three-mesh convergence study");
  cmd->callback([o] { run_bench(*o); });
}

const CommandRegistration registration{20, add_fe_command};
const CommandRegistration bench_registration{21, add_bench_command};
}  // namespace

}  // namespace ringcrush::compare::cli
