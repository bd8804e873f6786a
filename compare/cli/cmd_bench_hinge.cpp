// ringcrush bench-hinge [SCENE] — speed against error of the 1-D hinge levels (README
// "Measured results"; issue "Hinge model I", Performance and verification f).
//
//   ringcrush bench-hinge                                  # Test 30 with plates
//   ringcrush bench-hinge data/scenes/test30_welded.toml -o results/bench_hinge --repeat 31
//
// 1. One run of the scene per level (0, 1) × integrator (ida, odeint) × tolerance: median
//    wall time of --repeat runs on one core (no history kept), steps, and the error of the
//    permanent crush per ring against a tight reference (Odeint, rtol 1e-12).
// 2. Work–precision: the same over rtol 1e-3 … 1e-11 (work_precision.csv, .svg).
// 3. A velocity × mass sweep (--sweep N: N × N scenes, Level 0 on Odeint at --sweep-rtol,
//    V 10–60 m/s, M 0.05–0.5 kg, on --threads cores): total wall and CPU time; sweep.csv
//    with the crush per ring (rtol 1e-5 by default: ~1e-5 relative crush error).
// Wall and thread-CPU times are both reported: on a loaded machine they differ.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <ctime>
#include <exception>
#include <thread>

#include "compare/bench_timing.hpp"
#include "compare/cli/commands.hpp"
#include "compare/hinge_run_1d.hpp"
#include "compare/results_dir.hpp"
#include "compare/svg_plot.hpp"
#include "compare/table_output.hpp"

namespace ringcrush::compare::cli {
namespace {

struct BenchOptions {
  std::string scene = "data/scenes/test30_plates.toml";  // relative to the repository root
  std::string output;
  int repeat = 21;
  int sweep = 100;
  double sweep_rtol = 1e-5;  // relative crush error ~1e-5 on Test 30 (work-precision table)
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
};

using Clock = std::chrono::steady_clock;

hinge::ChainResult simulate(int level, const hinge::ChainInput& in, const hinge::HybridOptions& o) {
  return level == 0 ? hinge::simulate_level0(in, o, false) : hinge::simulate_level1(in, o, false);
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

struct LevelTiming {
  Timing time;
  hinge::ChainResult last;
};

// Median wall and CPU time of `repeat` runs (compare/bench_timing.hpp).
LevelTiming time_runs(int level, const hinge::ChainInput& in, const hinge::HybridOptions& o, int repeat) {
  LevelTiming t;
  t.time = time_repeated(repeat, [&] { return simulate(level, in, o); }, t.last);
  return t;
}

void run(const BenchOptions& opt) {
  const Scene scene = load_scene(opt.scene);
  if (!scene.impactor) throw std::invalid_argument("bench-hinge needs a dynamic scene with an impactor");
  const hinge::ChainInput in = chain_input(scene);
  HingeRunOptions ro;
  hinge::HybridOptions base = hybrid_options(scene, ro);
  fmt::print("bench-hinge: scene {} ({} rings, {}), {}; one core; load average {:.2f}\n", scene.name,
             in.rings, to_string(scene.joints.type), cpu_model(), load_average());

  std::unique_ptr<ResultsDir> out;
  if (!opt.output.empty()) out = std::make_unique<ResultsDir>(opt.output);

  // 1 + 2. Single runs and work–precision.
  CsvTable wp;
  wp.columns = {"level", "integrator_ida", "relative_tolerance", "median_wall_s", "min_wall_s", "median_cpu_s", "steps",
                "function_evaluations", "events", "max_crush_error_m", "relative_crush_error",
                "energy_balance_error"};
  std::vector<Series> curves;
  fmt::print("\n{:>5} {:>7} {:>8} {:>11} {:>9} {:>9} {:>7} {:>7} {:>6} {:>12} {:>10}\n", "level", "integ", "rtol",
             "median_ms", "min_ms", "cpu_ms", "steps", "fevals", "events", "crush_err_mm", "rel_err");
  for (int level : {0, 1}) {
    auto ref_opt = base;
    ref_opt.integrator = hinge::HybridIntegrator::Odeint;
    ref_opt.relative_tolerance = 1e-12;
    ref_opt.absolute_tolerance = 1e-14;
    const auto reference = simulate(level, in, ref_opt).final_permanent_crush_m;
    const double scale = *std::max_element(reference.begin(), reference.end());
    for (auto integ : {hinge::HybridIntegrator::Ida, hinge::HybridIntegrator::Odeint}) {
      Series s{fmt::format("level {} {}", level, hinge::to_string(integ)), {}, {}, integ == hinge::HybridIntegrator::Ida, true};
      for (double rtol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11}) {
        auto o = base;
        o.integrator = integ;
        o.relative_tolerance = rtol;
        o.absolute_tolerance = rtol * 1e-2;
        const bool headline = rtol == 1e-6 || rtol == 1e-8;
        const auto t = time_runs(level, in, o, headline ? opt.repeat : std::max(3, opt.repeat / 4));
        const double err = max_abs_diff(t.last.final_permanent_crush_m, reference);
        const auto& st = t.last.outcome.statistics;
        wp.add_row({double(level), integ == hinge::HybridIntegrator::Ida ? 1.0 : 0.0, rtol, t.time.wall_s, t.time.min_wall_s,
                    t.time.cpu_s,
                    double(st.steps), double(st.function_evaluations), double(st.events), err, err / scale,
                    t.last.energy_balance_error()});
        s.x.push_back(t.time.wall_s * 1e3);
        s.y.push_back(std::max(err / scale, 1e-16));
        fmt::print("{:>5} {:>7} {:>8.0e} {:>11.3f} {:>9.3f} {:>9.3f} {:>7} {:>7} {:>6} {:>12.2e} {:>10.2e}{}\n", level,
                   hinge::to_string(integ), rtol, t.time.wall_s * 1e3, t.time.min_wall_s * 1e3, t.time.cpu_s * 1e3, st.steps,
                   st.function_evaluations, st.events, err * 1e3, err / scale, headline ? "  *" : "");
      }
      curves.push_back(std::move(s));
    }
  }
  fmt::print("(* median of {} runs; others of {})\n", opt.repeat, std::max(3, opt.repeat / 4));

  // 3. Velocity × mass sweep.
  CsvTable sweep;
  double sweep_wall = 0.0, sweep_cpu = 0.0;
  if (opt.sweep > 0) {
    sweep.columns = {"velocity_m_s", "mass_kg", "arrest_time_s", "plastic_J"};
    for (int i = 0; i < in.rings; ++i) sweep.columns.push_back(fmt::format("crush_ratio_ring_{}", i + 1));
    auto o = base;
    o.integrator = hinge::HybridIntegrator::Odeint;
    o.relative_tolerance = opt.sweep_rtol;
    o.absolute_tolerance = opt.sweep_rtol * 1e-2;
    const int n = opt.sweep;
    const int threads = std::max(1, opt.threads);
    const auto start = Clock::now();
    std::vector<std::vector<double>> rows(static_cast<std::size_t>(n) * n);
    std::vector<double> cpu(threads, 0.0);
    std::vector<std::exception_ptr> failures(threads);
    auto work = [&](int w) {
      try {
        const double c0 = thread_cpu_s();
        for (int idx = w; idx < n * n; idx += threads) {
          const int a = idx / n, b = idx % n;
          auto c = in;
          c.impactor_velocity_m_s = 10.0 + 50.0 * a / std::max(n - 1, 1);
          c.impactor_mass_kg = 0.05 + 0.45 * b / std::max(n - 1, 1);
          const auto r = hinge::simulate_level0(c, o, false);
          std::vector<double> row{c.impactor_velocity_m_s, c.impactor_mass_kg, r.arrest_time_s,
                                  r.history.plastic_j.back()};
          for (double x : r.final_permanent_crush_m) row.push_back(x / in.ring.outer_diameter_m);
          rows[idx] = std::move(row);
        }
        cpu[w] = thread_cpu_s() - c0;
      } catch (...) {
        failures[w] = std::current_exception();
      }
    };
    std::vector<std::thread> pool;
    for (int w = 1; w < threads; ++w) pool.emplace_back(work, w);
    work(0);
    for (auto& t : pool) t.join();
    for (auto& f : failures)
      if (f) std::rethrow_exception(f);
    for (auto& row : rows) sweep.add_row(std::move(row));
    for (double c : cpu) sweep_cpu += c;
    sweep_wall = std::chrono::duration<double>(Clock::now() - start).count();
    fmt::print("\nsweep: {} scenes (V 10-60 m/s x M 0.05-0.5 kg), Level 0, Odeint rtol {:g}, {} thread(s): "
               "wall {:.2f} s, cpu {:.2f} s ({:.3f} ms cpu per scene); load average {:.2f}\n", n * n,
               o.relative_tolerance, threads, sweep_wall, sweep_cpu, sweep_cpu / (n * n) * 1e3, load_average());
  }

  if (!out) return;
  wp.write(out->file("work_precision.csv"));
  SvgPlot plot(fmt::format("Work–precision, {} (final crush vs rtol 1e-12)", scene.name), "median wall time (ms)",
               "relative crush error");
  plot.set_log_axes(true, true);
  for (auto& s : curves) plot.add(s);
  plot.write(out->file("work_precision.svg"));
  if (opt.sweep > 0) sweep.write(out->file("sweep.csv"));
  nlohmann::json summary = {{"model", "hinge"}, {"scene", scene.name}, {"analysis", "dynamic"},
                            {"benchmark", "bench-hinge"}, {"cpu", cpu_model()}, {"repeat", opt.repeat},
                            {"sweep_scenes", opt.sweep * opt.sweep}, {"sweep_wall_s", sweep_wall}, {"sweep_cpu_s", sweep_cpu},
                            {"sweep_relative_tolerance", opt.sweep_rtol}, {"sweep_threads", opt.threads},
                            {"wall_time_s", sweep_wall}, {"steps", 0}};
  write_json(out->file("summary.json"), summary);
  out->commit();
  fmt::print("wrote {}/{{work_precision.csv, work_precision.svg, sweep.csv, summary.json}}\n", out->target().string());
}

void add_bench_hinge_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand("bench-hinge", "Speed against error of hinge levels 0 and 1; velocity x mass sweep");
  cmd->add_option("scene", o->scene, "Dynamic scene (default: Test 30 with plates)")->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Results directory");
  cmd->add_option("--repeat", o->repeat, "Runs per timing (median)")->check(CLI::Range(1, 10000));
  cmd->add_option("--sweep", o->sweep, "Sweep grid size N (N x N scenes; 0: no sweep)")->check(CLI::Range(0, 1000));
  cmd->add_option("--threads", o->threads, "Threads for the sweep (default: all cores)")->check(CLI::Range(1, 256));
  cmd->add_option("--sweep-rtol", o->sweep_rtol, "Relative tolerance of the sweep runs (default 1e-5)")
      ->check(CLI::Range(1e-12, 1e-1));
  cmd->callback([o] { run(*o); });
}

const CommandRegistration registration{61, add_bench_hinge_command};

}  // namespace
}  // namespace ringcrush::compare::cli
