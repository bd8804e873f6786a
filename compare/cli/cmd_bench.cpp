// ringcrush bench [--quick] -o DIR — run time against error (issue 8 items 6 and 7).
//
//   ringcrush bench --quick -o results/bench_quick     # the test suite's version, ~7 s CPU
//   nice -n 5 ringcrush bench -o results/bench          # the README table, ~15 min CPU
//
// Work–precision (group "work_precision") on one impact scene (Test 30 welded by default):
//  - FE: meshes (elements per half ring) × integrators × step controls — HHT-α with the
//    half-step residual tolerance HAFTOL (thesis §3.5), explicit with the safety factor on the
//    stable step. Reference: the finest mesh with HHT at the tightest HAFTOL.
//  - Hinge: every registered level of 0, 1, 2, 3 × IDA / Odeint × relative tolerances.
//    Reference of each level: the same level on Odeint at its tightest tolerance. The model
//    error of each hinge run is taken against the FE reference (the finest FE run).
//  Errors: compare/work_precision.hpp (final crush ratio per ring, absorbed energy, peak force).
// "Only what a scene needs" (item 7): the FE run with all fields, frames, history and plots
//  written against none (group "outputs": time and bytes written), and the static thesis
//  crush on the half (symmetric) model against the full ring (group "symmetry").
// Times: median of --repeats runs (hinge and static rows; a run over 1 s CPU is not
// repeated) or --fe-repeats (FE dynamic rows), process CPU time beside wall time (the
// machine is shared), the FE on one thread.
// Writes DIR/bench.csv, work_precision.svg, model_error.svg, summary.json, atomically.
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>

#include "compare/bench_timing.hpp"
#include "compare/cli/commands.hpp"
#include "compare/fe_dynamic.hpp"
#include "compare/fe_static.hpp"
#include "compare/hinge_levels.hpp"
#include "compare/results_dir.hpp"
#include "compare/table_output.hpp"
#include "compare/work_precision.hpp"
#include "fe/time/static_driver.hpp"

namespace ringcrush::compare::cli {
namespace {
namespace fs = std::filesystem;

struct BenchOptions {
  std::string scene = "data/scenes/test30_welded.toml";
  std::string static_scene = "data/scenes/thesis_static.toml";
  std::string output;
  bool quick = false;
  int repeats = 3;
  int fe_repeats = 1;
  double end_time_s = 0;  // > 0: overrides the impact scene's end time
};

// Hinge and static runs longer than this (Level 2 on six rings: ~15-30 s) run once.
constexpr double repeat_below_cpu_s = 1.0;

// The runs of one bench. Lists run from the loosest to the tightest; the FE reference is the
// last HHT mesh at the last HAFTOL, a hinge level's reference Odeint at reference_rtol.
struct HingeLevelPlan {
  std::string level;
  std::vector<double> rtols;
  double reference_rtol;
};

struct Plan {
  Scene impact;  // work–precision and "outputs" scene
  std::vector<int> hht_meshes;
  std::vector<double> haftols_n;
  std::vector<int> explicit_meshes;
  std::vector<double> safeties;
  int outputs_mesh = 0;
  std::vector<HingeLevelPlan> levels;
  Scene crush;  // static "outputs" and "symmetry" scene
  std::string why;
};

// Level 2 runs any rtol below Level2Settings::min_relative_tolerance (1e-6) at 1e-3 instead
// (compare/hinge_run_2d.hpp), so its ladder stops at 1e-6.
std::vector<HingeLevelPlan> hinge_levels(bool quick) {
  std::vector<HingeLevelPlan> out;
  const std::vector<double> smooth = quick ? std::vector<double>{1e-4, 1e-6, 1e-8}
                                           : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
  for (const char* level : {"0", "1", "2", "3"}) {
    if (!hinge_level_registry().count(level)) continue;
    if (std::string(level) == "2")
      out.push_back({level, quick ? std::vector<double>{1e-3, 1e-4} : std::vector<double>{1e-3, 1e-4, 1e-5}, 1e-6});
    else
      out.push_back({level, smooth, 1e-11});
  }
  return out;
}

Plan make_plan(const BenchOptions& o) {
  Plan p;
  p.impact = load_scene(o.scene);
  if (!p.impact.impactor) throw std::invalid_argument(fmt::format("bench: {} is not an impact scene", o.scene));
  p.impact.outputs = {false, false, 0, false};  // the work–precision runs write nothing
  p.crush = load_scene(o.static_scene);
  if (p.crush.analysis.type != AnalysisType::Static)
    throw std::invalid_argument(fmt::format("bench: {} is not a static scene", o.static_scene));
  p.levels = hinge_levels(o.quick);
  if (o.quick) {
    // Two rings for 1 ms: ring 1 crushes by ~0.3 D; each FE run well under a second, and the
    // mesh error (~5e-3 in crush ratio on 8 elements) stands well above the step-control error.
    p.impact.rings.count = 2;
    p.impact.analysis.end_time_s = std::min(p.impact.analysis.end_time_s, 1e-3);
    p.impact.hinge.nodes_per_ring = 24;
    p.hht_meshes = {8, 12, 16};
    p.haftols_n = {1e5, 1e4, 1e3};
    p.explicit_meshes = {8, 12};
    p.safeties = {0.8, 0.4};
    p.outputs_mesh = 8;
    p.crush.analysis.crush_m = std::min(p.crush.analysis.crush_m, 0.015);
    p.why = "quick: 2 rings, 1 ms, coarse meshes (the test suite)";
  } else {
    // The whole Test 30 impact to arrest (the hinge models' model error is only meaningful
    // on final crushes). HHT costs ~0.6-0.9 s CPU per element around (per half ring) to
    // arrest, so the ladder reaches the thesis's 48 (the reference); the explicit driver
    // costs ~1.5 s per element at safety 0.8 (its step is set by the wall thickness, not by
    // the mesh around), so it stops at 24 to keep the whole bench near 10-15 min CPU.
    p.hht_meshes = {12, 16, 24, 32, 48};
    p.haftols_n = {3e4, 1e4, 3e3};
    p.explicit_meshes = {12, 24};
    p.safeties = {0.8, 0.4};
    p.outputs_mesh = 24;
    p.why = "Test 30 to arrest; HHT meshes 12-48 per half ring, explicit 12-24";
  }
  if (o.end_time_s > 0) p.impact.analysis.end_time_s = o.end_time_s;
  return p;
}

std::string mesh_label(const Scene& s) {
  return fmt::format("{}x{} {}", s.fe.elements_around, s.fe.elements_through,
                     s.analysis.symmetry == Symmetry::Half ? "half" : "full");
}

Scene fe_variant(const Scene& base, FeSolver solver, int elements_around, double control) {
  Scene s = base;
  s.fe.solver = solver;
  s.fe.elements_around = elements_around;
  if (solver == FeSolver::Hht) s.fe.haftol_n = control;
  else s.fe.explicit_safety = control;
  return s;
}

// One FE impact on one thread (so that CPU time is comparable between runs).
fe::DynamicResult fe_dynamic(const Scene& s) { return run_scene_dynamic(s, 1); }

// Bytes of every file under `dir`.
double bytes_under(const fs::path& dir) {
  double n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) n += static_cast<double>(e.file_size());
  return n;
}

class Bench {
 public:
  Bench(const BenchOptions& o, Plan p) : o_(o), p_(std::move(p)) {
    scratch_ = fs::temp_directory_path() / fmt::format("ringcrush_bench_{}", ::getpid());
  }
  ~Bench() {
    std::error_code ignored;
    fs::remove_all(scratch_, ignored);
  }

  std::vector<BenchRow> rows;
  std::vector<std::string> failures;

  void fe_work_precision() {
    const Scene ref_scene = fe_variant(p_.impact, FeSolver::Hht, p_.hht_meshes.back(), p_.haftols_n.back());
    fe_reference_ = fe_row(ref_scene, "hht", "haftol_N", p_.haftols_n.back(), nullptr);
    if (!fe_reference_) throw std::runtime_error("bench: the FE reference run failed: " + failures.back());
    rows.back().reference = true;
    for (int mesh : p_.hht_meshes)
      for (double haftol : p_.haftols_n)
        if (mesh != p_.hht_meshes.back() || haftol != p_.haftols_n.back())
          fe_row(fe_variant(p_.impact, FeSolver::Hht, mesh, haftol), "hht", "haftol_N", haftol, &*fe_reference_);
    for (int mesh : p_.explicit_meshes)
      for (double safety : p_.safeties)
        fe_row(fe_variant(p_.impact, FeSolver::Explicit, mesh, safety), "explicit", "safety", safety, &*fe_reference_);
  }

  void hinge_work_precision() {
    for (const auto& lp : p_.levels) {
      const auto& runner = hinge_level_registry().at(lp.level);
      auto options = [&](HingeIntegrator integ, double rtol) {
        HingeRunOptions h;
        h.level = lp.level;
        h.integrator = integ;
        h.relative_tolerance = rtol;
        h.absolute_tolerance = 1e-2 * rtol;
        return h;
      };
      RunResult reference;
      const Timing t = time_repeated(
          o_.repeats, [&] { return runner(p_.impact, options(HingeIntegrator::Odeint, lp.reference_rtol)); }, reference,
          repeat_below_cpu_s);
      add_hinge_row(lp.level, "odeint", lp.reference_rtol, t, reference, reference, true);
      for (auto integ : {HingeIntegrator::Ida, HingeIntegrator::Odeint})
        for (double rtol : lp.rtols) {
          RunResult run;
          try {
            const Timing ti = time_repeated(
                o_.repeats, [&] { return runner(p_.impact, options(integ, rtol)); }, run, repeat_below_cpu_s);
            add_hinge_row(lp.level, integ == HingeIntegrator::Ida ? "ida" : "odeint", rtol, ti, run, reference, false);
          } catch (const std::exception& e) {
            fail(fmt::format("hinge level {} {} rtol {:g}", lp.level, integ == HingeIntegrator::Ida ? "ida" : "odeint", rtol),
                 e.what());
          }
        }
    }
  }

  // Item 7: the same FE impact with every output asked for and with none.
  void outputs_saving() {
    Scene all = fe_variant(p_.impact, FeSolver::Hht, p_.outputs_mesh, p_.impact.fe.haftol_n);
    all.outputs = {true, true, 20, true};
    Scene none = all;
    none.outputs = {false, false, 0, false};
    std::optional<RunResult> reference;
    for (const Scene* s : {&all, &none}) {
      const std::string label = s->outputs.fields ? "all outputs" : "no outputs";
      try {
        RunResult run;
        double bytes = 0;
        const Timing t = time_repeated(o_.fe_repeats, [&] {
          const auto r = fe_dynamic(*s);
          RunResult rr = fe_dynamic_run_result(*s, r);
          ResultsDir out(scratch_ / "outputs");
          write_fe_dynamic_outputs(*s, r, rr, out);
          bytes = bytes_under(out.file("summary.json").parent_path());
          return rr;
        }, run);
        if (!reference) reference = run;
        rows.push_back(fe_dynamic_row("outputs", *s, "hht", label, {}, t, run, *reference));
        rows.back().bytes_written = bytes;
        rows.back().reference = s == &all;
        print_last();
      } catch (const std::exception& e) {
        fail("fe outputs " + label, e.what());
      }
    }
    // The static crush: all outputs against none, and the half model against the full ring.
    Scene half_all = p_.crush;
    half_all.outputs = {true, true, 20, true};
    Scene half_none = p_.crush;
    half_none.outputs = {false, false, 0, false};
    Scene full_none = half_none;
    full_none.analysis.symmetry = Symmetry::Full;
    static_row("outputs", half_all, "all outputs", true);
    static_row("outputs", half_none, "no outputs", false);
    static_row("symmetry", full_none, "full", true);
    static_row("symmetry", half_none, "half", false);
  }

  const std::vector<BenchRow>& all_rows() const { return rows; }

 private:
  void fail(const std::string& what, const std::string& why) {
    failures.push_back(what + ": " + why);
    fmt::print("  FAILED {}: {}\n", what, why);
    std::fflush(stdout);
  }

  void print_last() {
    const auto& r = rows.back();
    fmt::print("  {:<8} {:<6} {:<11} {:<8} {:<11} {:>8} cpu {:9.3f} s  err {:9.2e}{}\n", r.group.substr(0, 8), r.model,
               r.level_or_mesh, r.integrator, r.control, r.tolerance ? fmt::format("{:g}", *r.tolerance) : "",
               r.cpu_s, r.error.crush,
               r.model_error ? fmt::format("  model err {:.3f}", r.model_error->crush) : std::string());
    std::fflush(stdout);
  }

  // A timed run's row: what was run, its cost, its error against `reference` and its measures.
  static BenchRow timed_row(const std::string& group, const std::string& model, const std::string& scene,
                            const std::string& level_or_mesh, const std::string& integ, const std::string& control,
                            std::optional<double> tol, const Timing& t, const RunResult& run,
                            const RunResult& reference) {
    BenchRow r;
    r.group = group;
    r.model = model;
    r.scene = scene;
    r.level_or_mesh = level_or_mesh;
    r.integrator = integ;
    r.control = control;
    r.tolerance = tol;
    r.repeats = t.repeats;
    r.wall_s = t.wall_s;
    r.cpu_s = t.cpu_s;
    r.error = run_errors(run, reference);
    r.measures = run_measures(run);
    return r;
  }

  BenchRow fe_dynamic_row(const std::string& group, const Scene& s, const std::string& integ,
                          const std::string& control, std::optional<double> tol, const Timing& t, const RunResult& run,
                          const RunResult& reference) {
    return timed_row(group, "fe", s.name, mesh_label(s), integ, control, tol, t, run, reference);
  }

  std::optional<RunResult> fe_row(const Scene& s, const std::string& integ, const std::string& control, double value,
                                  const RunResult* reference) {
    try {
      RunResult run;
      const Timing t = time_repeated(o_.fe_repeats, [&] { return fe_dynamic_run_result(s, fe_dynamic(s)); }, run);
      rows.push_back(fe_dynamic_row("work_precision", s, integ, control, value, t, run, reference ? *reference : run));
      print_last();
      return run;
    } catch (const std::exception& e) {
      fail(fmt::format("fe {} {} {} {:g}", mesh_label(s), integ, control, value), e.what());
      return std::nullopt;
    }
  }

  void add_hinge_row(const std::string& level, const std::string& integ, double rtol, const Timing& t,
                     const RunResult& run, const RunResult& reference, bool is_reference) {
    BenchRow r = timed_row("work_precision", "hinge", p_.impact.name, "level " + level, integ, "rtol", rtol, t, run,
                           reference);
    r.reference = is_reference;
    if (fe_reference_) r.model_error = run_errors(run, *fe_reference_);
    rows.push_back(r);
    print_last();
  }

  void static_row(const std::string& group, const Scene& s, const std::string& control, bool is_reference) {
    try {
      RunResult run;
      double bytes = 0;
      const Timing t = time_repeated(o_.repeats, [&] {
        const auto r = fe::run_static(fe_static_input(s));
        RunResult rr = fe_static_run_result(s, r);
        ResultsDir out(scratch_ / "static");
        write_fe_static_outputs(s, r, rr, out);
        bytes = bytes_under(out.file("summary.json").parent_path());
        return rr;
      }, run, repeat_below_cpu_s);
      if (is_reference) static_reference_ = run;
      BenchRow r = timed_row(group, "fe", s.name, mesh_label(s), "static", control, std::nullopt, t, run,
                             static_reference_ ? *static_reference_ : run);
      r.reference = is_reference;
      r.bytes_written = bytes;
      rows.push_back(r);
      print_last();
    } catch (const std::exception& e) {
      fail(fmt::format("fe static {} {}", mesh_label(s), control), e.what());
    }
  }

  const BenchOptions& o_;
  Plan p_;
  fs::path scratch_;
  std::optional<RunResult> fe_reference_, static_reference_;
};

void run_bench(const BenchOptions& o) {
  if (o.output.empty()) throw std::invalid_argument("bench: -o DIR is required");
  const Plan plan = make_plan(o);
  const double load0 = load_average();
  const double cpu0 = process_cpu_s();
  fmt::print("bench: {} ({}); {} x {} logical CPUs, load average {:.2f}\n", plan.impact.name, plan.why, cpu_model(),
             cpu_count(), load0);
  fmt::print("  hinge and static rows: median of {} runs; FE impact rows: {} run(s); FE on one thread\n", o.repeats,
             o.fe_repeats);
  ResultsDir out(o.output);
  Bench bench(o, plan);
  bench.fe_work_precision();
  bench.hinge_work_precision();
  bench.outputs_saving();
  const auto& rows = bench.all_rows();

  write_bench_csv(out.file("bench.csv"), rows);
  const std::string title = fmt::format("Run time against error, {} ({})", plan.impact.name, o.quick ? "quick" : "full");
  std::ofstream(out.file("work_precision.svg")) << render_work_precision(rows, title, false);
  std::ofstream(out.file("model_error.svg")) << render_work_precision(rows, title + ": hinge against the finest FE", true);
  const double total_cpu = process_cpu_s() - cpu0;
  nlohmann::json summary = {{"benchmark", "bench"},
                            {"scene", plan.impact.name},
                            {"static_scene", plan.crush.name},
                            {"quick", o.quick},
                            {"plan", plan.why},
                            {"cpu", cpu_model()},
                            {"logical_cpus", cpu_count()},
                            {"load_average_start", load0},
                            {"load_average_end", load_average()},
                            {"repeats", o.repeats},
                            {"fe_repeats", o.fe_repeats},
                            {"rows", rows.size()},
                            {"total_cpu_s", total_cpu},
                            {"failures", bench.failures}};
  write_json(out.file("summary.json"), summary);
  out.commit();
  fmt::print("\n{}", bench_table(rows));
  fmt::print("errors: crush = max |crush ratio - reference| over the rings; E, F relative (absorbed energy, peak force)\n"
             "references (*): FE finest mesh at the tightest HAFTOL; each hinge level on Odeint at its tightest rtol;\n"
             "model_err: hinge against the FE reference. {} runs, {} failed, {:.1f} s CPU in all\n",
             rows.size(), bench.failures.size(), total_cpu);
  fmt::print("wrote {}/{{bench.csv, work_precision.svg, model_error.svg, summary.json}}\n", out.target().string());
}

void add_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand("bench", "Run time against error: FE meshes x integrators x step controls, hinge "
                                          "levels x tolerances x IDA/Odeint, outputs and symmetry savings");
  cmd->add_option("scene", o->scene, "Impact scene (default data/scenes/test30_welded.toml)")->check(CLI::ExistingFile);
  cmd->add_option("--static-scene", o->static_scene, "Static scene of the symmetry and outputs rows")
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Results directory (written completely or not at all)")->required();
  cmd->add_flag("--quick", o->quick, "Two rings, 1 ms, coarse meshes, short tolerance ladders (the test suite)");
  cmd->add_option("--repeats", o->repeats, "Runs per hinge and static timing (median; default 3)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--fe-repeats", o->fe_repeats, "Runs per FE impact timing (median; default 1)")
      ->check(CLI::Range(1, 100));
  cmd->add_option("--end-time", o->end_time_s, "Override the impact scene's end time (s)")
      ->check(CLI::PositiveNumber);
  cmd->callback([o] { run_bench(*o); });
}

const CommandRegistration registration{23, add_command};

}  // namespace
}  // namespace ringcrush::compare::cli
