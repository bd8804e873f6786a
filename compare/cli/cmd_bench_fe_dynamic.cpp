// ringcrush bench-fe-dynamic [--quick] [--matrix] -o DIR — the performance, agreement and
// stability benchmark of the FE impact (issue 4 "Performance", verification e, f and g).
//
//   ringcrush bench-fe-dynamic -o results/bench_fe_dynamic            # thesis scene, both drivers
//   ringcrush bench-fe-dynamic --matrix --elements-around 16 --jobs 2 -o results/matrix
//   ringcrush bench-fe-dynamic --matrix --elements-through 2 --no-thesis -o results/matrix_x2
//   ringcrush bench-fe-dynamic --matrix --filter 'explicit/welded/v30/' -o results/m30
//   ringcrush bench-fe-dynamic --matrix --no-thesis --step-bound assembled --safety 0.9 -o DIR
//
// (i) The thesis dynamic scene (or SCENE) to arrest with the explicit and the HHT-α driver,
//     and its `plates` variant with the scene's driver (verification e: no wrap, no
//     alternation): wall time, steps, time per element-step,
//     contact share, energy balance error, numerical dissipation, final crush per ring, wrap
//     flags and alternation index, and the HHT-vs-explicit crush difference per ring
//     (verification f: |c_hht − c_explicit| ≤ 10 % of c_explicit, or ≤ 0.01 for rings that
//     stay nearly intact, where a relative difference means nothing) → thesis.csv,
//     agreement.csv, printed tables.
// (ii) --matrix (verification g): speeds 5, 15, 30, 50, 100, 150 m/s × impactor mass ×0.25,
//     ×1, ×4 × t/D 0.02, 0.03, 0.06 × both drivers × welded / free / plates chains (the Test 30
//     scenes beside SCENE as the base). Every case ends at rest, at its end time, or with a named diagnosis
//     (a SolveFailure or a refused non-finite result is caught and recorded); → matrix.csv.
// --step-bound / --safety set the explicit step of every run (both parts) in place of the
// scenes' fe.step_bound / fe.explicit_safety, so the matrix can be run at another setting
// (the session-12 choice of the defaults, README "FE dynamics"); HHT runs ignore them.
// --elements-through N: elements through the wall of every run. The matrix keeps 1 without it
// — the mesh it was recorded on in issue 4 (16 × 1) — although its base scenes now carry 2
// (through_wall_section.hpp); part (i) keeps the scene's.
// --quick shrinks both parts to two rings on a coarse mesh and a short time (the test suite).
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <mutex>
#include <regex>
#include <thread>

#include "compare/cli/commands.hpp"
#include "compare/cli/fe_dynamic_terminal.hpp"
#include "compare/fe_dynamic.hpp"
#include "compare/measures.hpp"
#include "compare/results_dir.hpp"
#include "fe/time/static_driver.hpp"

namespace ringcrush::compare::cli {
namespace {

struct BenchOptions {
  std::string scene = "data/scenes/thesis_dynamic.toml";
  std::string output;
  bool quick = false;
  bool matrix = false;
  bool thesis = true;
  int elements_around = 0;  // 0: the scene's (thesis part) / 16 (matrix)
  int elements_through = 0;  // with elements_through_given; else the scene's (thesis part) / 1 (matrix)
  bool elements_through_given = false;
  std::string filter;       // matrix: regex on the case name
  int jobs = 1;
  double end_time_s = 0;    // > 0: overrides the scenes' end time
  std::string step_bound;   // "element" | "assembled": overrides the scenes' fe.step_bound
  double safety = 0;        // with safety_given: overrides the scenes' fe.explicit_safety, in (0, 1]
  bool safety_given = false;
};

// One run of one case, as a table row. A run that fails keeps its diagnosis.
struct CaseOutcome {
  std::string name, status = "ok", reason;
  fe::DynamicResult result;
  RunResult run;
  bool has_result = false;
};

// threads: the element-loop threads of the chain (0 automatic; 1 when cases run in parallel).
CaseOutcome run_case(const std::string& name, const Scene& s, int threads = 0) {
  CaseOutcome o;
  o.name = name;
  try {
    o.result = run_scene_dynamic(s, threads);
    o.run = fe_dynamic_run_result(s, o.result);  // refuses a non-finite result
    o.has_result = true;
    o.reason = o.result.end_reason;
  } catch (const fe::SolveFailure& e) {
    o.status = "diagnosis";
    o.reason = e.what();
  } catch (const std::exception& e) {
    o.status = "error";
    o.reason = e.what();
  }
  return o;
}

std::string csv_text(std::string s) {
  for (char& c : s)
    if (c == '"' || c == '\n') c = '\'';
  return "\"" + s + "\"";
}

Scene quick_scene(Scene s) {
  s.rings.count = 2;
  s.fe.elements_around = 8;
  s.analysis.end_time_s = std::min(s.analysis.end_time_s, 2e-4);
  return s;
}

// default_elements, default_through: the part's own mesh when no flag sets it (0: the scene's).
Scene prepared(Scene s, const BenchOptions& o, int default_elements, int default_through) {
  s.outputs.fields = false;
  s.outputs.frames = 0;
  if (o.quick) s = quick_scene(s);
  else if (o.elements_around > 0) s.fe.elements_around = o.elements_around;
  else if (default_elements > 0) s.fe.elements_around = default_elements;
  if (o.elements_through_given) s.fe.elements_through = o.elements_through;
  else if (default_through > 0) s.fe.elements_through = default_through;
  if (o.end_time_s > 0) s.analysis.end_time_s = o.end_time_s;
  if (o.step_bound == "element") s.fe.step_bound = ExplicitStepBound::Element;
  if (o.step_bound == "assembled") s.fe.step_bound = ExplicitStepBound::Assembled;
  if (o.safety_given) s.fe.explicit_safety = o.safety;
  return s;
}

// ---- (i) the thesis scene with both drivers -------------------------------------------

void thesis_part(const BenchOptions& o, ResultsDir& out) {
  const Scene base = prepared(load_scene(o.scene), o, 0, 0);
  std::vector<CaseOutcome> runs;
  fmt::print("bench-fe-dynamic: {} ({} rings, {} x {} elements per half ring, end {:g} ms)\n", base.name,
             base.rings.count, base.fe.elements_around, base.fe.elements_through, 1e3 * base.analysis.end_time_s);
  fmt::print("{:>9} {:>8} {:>8} {:>9} {:>9} {:>10} {:>8} {:>9} {:>9} {:>7}  {}\n", "run", "steps", "rejected",
             "newton", "wall_s", "ns/el-step", "contact", "E_err_%", "E_num_%", "altern", "end");
  std::ofstream csv(out.file("thesis.csv"));
  csv << "scene,run,status,end_reason,steps,rejected_steps,newton_iterations,wall_time_s,"
         "time_per_element_step_s,contact_share,energy_balance_error,numerical_dissipation,alternation_index";
  for (int i = 0; i < base.rings.count; ++i) csv << fmt::format(",crush_ratio_ring_{},wrap_ring_{}", i + 1, i + 1);
  csv << '\n';
  // Explicit, HHT, and (verification e) the same chain with plates between the rings with
  // the scene's own driver: plates as in the Test 30 plated scene (10 g, 2 mm; assumed there too).
  for (int variant = 0; variant < 3; ++variant) {
    Scene s = base;
    s.fe.solver = variant == 0 ? FeSolver::Explicit : variant == 1 ? FeSolver::Hht : base.fe.solver;
    if (variant == 2) {
      s.joints = {JointType::Plates, 0.010, 0.002};
      s.rings.pitch_m = s.rings.outer_diameter_m + s.joints.plate_thickness_m;
    }
    const std::string driver = variant == 0 ? "explicit" : variant == 1 ? "hht" : "plates";
    runs.push_back(run_case(driver, s));
    const auto& c = runs.back();
    csv << fmt::format("{},{},{},{}", s.name, driver, c.status, csv_text(c.reason));
    if (!c.has_result) {
      fmt::print("{:>9} failed: {}\n", driver, c.reason);
      csv << '\n';
      continue;
    }
    const auto& st = c.result.statistics;
    const auto& x = c.run.extra;
    const double alt = alternation(c.run.crush_ratio).index;
    fmt::print("{:>9} {:>8} {:>8} {:>9} {:>9.3f} {:>10.1f} {:>7.0f}% {:>9.3f} {:>9.3f} {:>7.3f}  {}\n", driver,
               st.steps, st.rejected_steps, st.newton_iterations, st.wall_time_s,
               1e9 * x["time_per_element_step_s"].get<double>(), 100 * x["contact_share"].get<double>(),
               100 * c.result.energy_balance_error, 100 * c.result.numerical_dissipation, alt, c.reason);
    csv << fmt::format(",{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}", st.steps, st.rejected_steps,
                       st.newton_iterations, st.wall_time_s, x["time_per_element_step_s"].get<double>(),
                       x["contact_share"].get<double>(), c.result.energy_balance_error,
                       c.result.numerical_dissipation, alt);
    for (std::size_t i = 0; i < c.run.crush_ratio.size(); ++i)
      csv << fmt::format(",{:.6g},{}", c.run.crush_ratio[i], c.run.wrap_around[i] ? 1 : 0);
    csv << '\n';
    fmt::print("          crush ratio per ring:");
    for (std::size_t i = 0; i < c.run.crush_ratio.size(); ++i)
      fmt::print(" {:.3f}{}", c.run.crush_ratio[i], c.run.wrap_around[i] ? "w" : "");
    fmt::print("   (w: wraps around the next ring)\n");
  }
  // Verification e (thesis §4.2.1): with the scene's driver, ring 1 wraps around ring 2 and
  // the crush alternates; with plates, neither.
  const auto& own = runs[base.fe.solver == FeSolver::Hht ? 1 : 0];
  if (own.has_result && runs[2].has_result) {
    const double a_own = alternation(own.run.crush_ratio).index;
    const double a_plates = alternation(runs[2].run.crush_ratio).index;
    const bool plates_wrap = std::find(runs[2].run.wrap_around.begin(), runs[2].run.wrap_around.end(), true) !=
                             runs[2].run.wrap_around.end();
    const bool holds = own.run.wrap_around[0] && a_own > alternation_threshold && !plates_wrap &&
                       a_plates <= alternation_threshold;
    fmt::print("verification e ({}): ring 1 wraps {} (W = {:.0f} deg, S = {:.1f} mm), alternation {:.3f}; "
               "plates: a wrap {}, alternation {:.3f} (threshold {:g}) -> {}\n",
               own.name, own.run.wrap_around[0] ? "yes" : "no", own.run.wrapped_angle_deg[0],
               1e3 * own.run.inverted_arc_m[0], a_own, plates_wrap ? "yes" : "no", a_plates, alternation_threshold,
               holds ? "holds" : "DOES NOT HOLD");
  }
  if (!runs[0].has_result || !runs[1].has_result) return;
  // Verification f: HHT against explicit, ring by ring.
  std::ofstream agree(out.file("agreement.csv"));
  agree << "ring,crush_ratio_explicit,crush_ratio_hht,difference,relative_difference,within_target\n";
  fmt::print("HHT vs explicit (target: within 10 %, or 0.01 for nearly intact rings):\n{:>5} {:>9} {:>9} {:>9} {:>5}\n",
             "ring", "explicit", "hht", "rel_diff", "ok");
  int within = 0;
  const auto& ce = runs[0].run.crush_ratio;
  const auto& ch = runs[1].run.crush_ratio;
  for (std::size_t i = 0; i < ce.size(); ++i) {
    const double diff = ch[i] - ce[i];
    const double rel = ce[i] > 0.01 ? diff / ce[i] : 0.0;
    const bool ok = std::abs(diff) <= std::max(0.10 * std::abs(ce[i]), 0.01);
    within += ok;
    agree << fmt::format("{},{:.6g},{:.6g},{:.6g},{:.6g},{}\n", i + 1, ce[i], ch[i], diff, rel, ok ? 1 : 0);
    fmt::print("{:>5} {:>9.3f} {:>9.3f} {:>8.1f}% {:>5}\n", i + 1, ce[i], ch[i], 100 * rel, ok ? "yes" : "NO");
  }
  fmt::print("{} of {} rings within the target\n", within, ce.size());
}

// ---- (ii) the stability matrix ----------------------------------------------------------

struct MatrixCase {
  std::string name;
  Scene scene;
};

std::vector<MatrixCase> matrix_cases(const BenchOptions& o) {
  const std::vector<double> speeds = o.quick ? std::vector<double>{30} : std::vector<double>{5, 15, 30, 50, 100, 150};
  const std::vector<double> masses = o.quick ? std::vector<double>{1} : std::vector<double>{0.25, 1, 4};
  const std::vector<double> t_over_d = o.quick ? std::vector<double>{0.03} : std::vector<double>{0.02, 0.03, 0.06};
  const std::regex filter(o.filter.empty() ? ".*" : o.filter);
  std::vector<MatrixCase> cases;
  for (FeSolver solver : {FeSolver::Explicit, FeSolver::Hht})
    for (const char* joints : {"welded", "free", "plates"}) {
      const auto file = std::filesystem::path(o.scene).parent_path() / fmt::format("test30_{}.toml", joints);
      const Scene base = prepared(load_scene(file), o, 16, 1);
      for (double v : speeds)
        for (double m : masses)
          for (double td : t_over_d) {
            const std::string name = fmt::format("{}/{}/v{:g}/m{:g}/tD{:g}", solver == FeSolver::Hht ? "hht" : "explicit",
                                                 joints, v, m, td);
            if (!std::regex_search(name, filter)) continue;
            Scene s = base;
            s.fe.solver = solver;
            s.impactor->velocity_m_s = v;
            s.impactor->mass_kg = m * base.impactor->mass_kg;
            s.rings.wall_thickness_m = td * s.rings.outer_diameter_m;
            cases.push_back({name, s});
          }
    }
  return cases;
}

void matrix_part(const BenchOptions& o, ResultsDir& out) {
  const auto cases = matrix_cases(o);
  fmt::print("\nstability matrix: {} cases on {} thread(s)", cases.size(), o.jobs);
  if (!cases.empty())
    fmt::print(", {} x {} elements per half ring", cases.front().scene.fe.elements_around,
               cases.front().scene.fe.elements_through);
  if (!cases.empty())
    fmt::print(", explicit step: {} bound, safety {:g}",
               cases.front().scene.fe.step_bound == ExplicitStepBound::Assembled ? "assembled" : "element",
               cases.front().scene.fe.explicit_safety);
  fmt::print("\n");
  std::vector<CaseOutcome> outcomes(cases.size());
  std::atomic<std::size_t> next{0};
  std::mutex print_mutex;
  auto worker = [&] {
    for (std::size_t k = next++; k < cases.size(); k = next++) {
      outcomes[k] = run_case(cases[k].name, cases[k].scene, o.jobs > 1 ? 1 : 0);
      const auto& c = outcomes[k];
      std::lock_guard lock(print_mutex);
      if (c.has_result)
        fmt::print("{:>36} {:>9} steps {:>9.2f} s  E_err {:7.3f} %  {}\n", c.name, c.result.statistics.steps,
                   c.result.statistics.wall_time_s, 100 * c.result.energy_balance_error, c.reason);
      else
        fmt::print("{:>36} {}: {}\n", c.name, c.status, c.reason);
      std::fflush(stdout);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < o.jobs; ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();

  std::ofstream csv(out.file("matrix.csv"));
  csv << "case,driver,joints,speed_m_s,mass_kg,t_over_D,status,end_reason,steps,rejected_steps,wall_time_s,"
         "energy_balance_error,numerical_dissipation,impactor_final_velocity_m_s,max_crush_ratio,alternation_index,"
         "step_bound,explicit_safety";
  // The crush of every ring, so two settings can be compared ring by ring (all cases share
  // the base scenes' ring count).
  const int rings = cases.empty() ? 0 : cases.front().scene.rings.count;
  for (int i = 0; i < rings; ++i) csv << fmt::format(",crush_ratio_ring_{}", i + 1);
  csv << '\n';
  int at_rest = 0, end_time = 0, diagnosed = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto& s = cases[k].scene;
    const auto& c = outcomes[k];
    csv << fmt::format("{},{},{},{:g},{:g},{:g},{},{}", c.name, s.fe.solver == FeSolver::Hht ? "hht" : "explicit",
                       to_string(s.joints.type), s.impactor->velocity_m_s, s.impactor->mass_kg,
                       s.rings.wall_thickness_m / s.rings.outer_diameter_m, c.status, csv_text(c.reason));
    // The explicit step's setting; empty for HHT, whose step control does not use it.
    const std::string step =
        s.fe.solver == FeSolver::Hht
            ? std::string(",,")
            : fmt::format(",{},{:g}", s.fe.step_bound == ExplicitStepBound::Assembled ? "assembled" : "element",
                          s.fe.explicit_safety);
    if (!c.has_result) {
      ++diagnosed;
      csv << ",,,,,,,," << step << std::string(static_cast<std::size_t>(rings), ',') << '\n';
      continue;
    }
    (c.reason == "end_time" ? end_time : at_rest) += 1;
    const auto& st = c.result.statistics;
    csv << fmt::format(",{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}", st.steps, st.rejected_steps,
                       st.wall_time_s, c.result.energy_balance_error, c.result.numerical_dissipation,
                       c.run.impactor_velocity_m_s.back(),
                       *std::max_element(c.run.crush_ratio.begin(), c.run.crush_ratio.end()),
                       alternation(c.run.crush_ratio).index)
        << step;
    for (int i = 0; i < rings; ++i)
      csv << ','
          << (static_cast<std::size_t>(i) < c.run.crush_ratio.size() ? fmt::format("{:.6g}", c.run.crush_ratio[i])
                                                                       : std::string());
    csv << '\n';
  }
  fmt::print("matrix: {} ended by the driver's own reason (rest, energy limit...), {} at the end time, "
             "{} with a diagnosis\n",
             at_rest, end_time, diagnosed);
}

void run_bench(const BenchOptions& o) {
  if (o.output.empty()) throw std::invalid_argument("bench-fe-dynamic: -o DIR is required");
  if (o.safety_given && !(o.safety > 0 && o.safety <= 1))
    throw std::invalid_argument(fmt::format("bench-fe-dynamic: --safety {} must lie in (0, 1]", o.safety));
  if (o.elements_through_given && !(o.elements_through >= 1 && o.elements_through <= 16))
    throw std::invalid_argument(
        fmt::format("bench-fe-dynamic: --elements-through {} must lie in [1, 16] (the scene's fe.elements_through range)",
                    o.elements_through));
  if (o.elements_around % 2 != 0)
    throw std::invalid_argument(fmt::format("bench-fe-dynamic: --elements-around {} must be even", o.elements_around));
  ResultsDir out(o.output);
  if (o.thesis) thesis_part(o, out);
  if (o.matrix || o.quick) matrix_part(o, out);
  out.commit();
  fmt::print("wrote {}\n", out.target().string());
}

void add_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand("bench-fe-dynamic",
                                 "Benchmark the FE impact: thesis scene with both drivers, stability matrix");
  cmd->add_option("scene", o->scene, "Dynamic scene of part (i) (default data/scenes/thesis_dynamic.toml)")
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Results directory for the CSV tables")->required();
  cmd->add_flag("--quick", o->quick, "Two rings, 8 elements, 0.2 ms, a 6-case matrix (the test suite)");
  cmd->add_flag("--matrix", o->matrix, "Also run the stability matrix (verification g; long)");
  cmd->add_flag("!--no-thesis", o->thesis, "Skip part (i), the scene with both drivers");
  cmd->add_option("--elements-around", o->elements_around,
                  "Elements per half ring (default: the scene's for part (i), 16 for the matrix)")
      ->check(CLI::Range(8, 4096));
  auto* through = cmd->add_option(
      "--elements-through", o->elements_through,
      "Elements through the wall of every run (default: the scene's for part (i), 1 for the matrix, its recorded mesh)");
  cmd->add_option("--filter", o->filter, "Matrix: only cases whose name (driver/joints/vV/mM/tDX) matches");
  cmd->add_option("--jobs", o->jobs, "Matrix: cases run in parallel")->check(CLI::Range(1, 64));
  cmd->add_option("--end-time", o->end_time_s, "Override the end time of every run (s)")->check(CLI::PositiveNumber);
  cmd->add_option("--step-bound", o->step_bound,
                  "Explicit runs: stable-step omega_max from the element bound or the assembled estimate "
                  "(overrides the scenes' fe.step_bound)")
      ->check(CLI::IsMember({"element", "assembled"}));
  auto* safety = cmd->add_option("--safety", o->safety,
                                 "Explicit runs: fraction of the stable step, in (0, 1] (overrides the scenes' "
                                 "fe.explicit_safety)");
  cmd->callback([o, safety, through] {
    o->safety_given = safety->count() > 0;
    o->elements_through_given = through->count() > 0;
    run_bench(*o);
  });
}

const CommandRegistration registration{22, add_command};
}  // namespace

}  // namespace ringcrush::compare::cli
