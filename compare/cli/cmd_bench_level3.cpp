// ringcrush bench-level3 [SCENE] — wall time of hinge Level 3 (issue 7, Performance: < 5 ms)
//
//   ringcrush bench-level3                                   # Test 30 welded, 27.7 m/s
//   ringcrush bench-level3 data/scenes/test30_welded.toml --repeat 51 --rtol 1e-8
//   ringcrush bench-level3 --velocity 50 --shear-free         # travelling F, wrap selected
//   /usr/bin/time ringcrush bench-level3 SCENE --only ida --repeat 201   # CPU per IDA run
//   ringcrush bench-level3 SCENE --velocity 45 --rtol 1e-7 --repeat 1 --accuracy   # error bought
//
// Median (and min/max) wall time of --repeat runs per integrator, no history kept, one core.
// --accuracy: each integrator's run against Odeint at rtol 1e-12 (atol 1e-14), untimed: the
// largest difference of any mechanism's crush over d, whether the events (kind, ring) are the
// same in the same order, the largest event-time difference, and the energy balance.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "compare/cli/commands.hpp"
#include "compare/hinge_run_1d.hpp"
#include "compare/hinge_run_level3.hpp"

namespace ringcrush::compare::cli {
namespace {

struct BenchLevel3Options {
  std::string scene = "data/scenes/test30_welded.toml";
  int repeat = 21;
  double rtol = 1e-8;
  double velocity = -1.0;
  bool shear_free = false;  // travelling F (the shear-free trace is part of every run)
  std::string only;         // "ida" or "odeint": that integrator alone (CPU time per run under load)
  bool accuracy = false;    // each run against Odeint at rtol 1e-12
};

// The run's accuracy against a reference run of the same model (README "Hinge models", h52).
struct Level3Accuracy {
  double crush_error_d = 0.0;      // largest |Δ| of a mechanism's or a ring's crush / d
  bool same_events = true;         // the same (kind, ring) in the same order
  double event_time_error_s = 0.0; // largest |Δt| of corresponding events
};

Level3Accuracy level3_accuracy(const hinge::Level3Result& run, const hinge::Level3Result& ref, double d) {
  Level3Accuracy a;
  for (std::size_t i = 0; i < run.rings.size() && i < ref.rings.size(); ++i) {
    const auto &x = run.rings[i], &y = ref.rings[i];
    for (double e : {x.uniform_crush_m - y.uniform_crush_m, x.wrap_crush_m - y.wrap_crush_m,
                     x.bottom_crush_m - y.bottom_crush_m, x.ecb_crush_m - y.ecb_crush_m, x.crush_m - y.crush_m})
      a.crush_error_d = std::max(a.crush_error_d, std::abs(e) / d);
  }
  a.same_events = run.rings.size() == ref.rings.size() && run.events.size() == ref.events.size();
  for (std::size_t e = 0; a.same_events && e < ref.events.size(); ++e) {
    a.same_events = run.events[e].kind == ref.events[e].kind && run.events[e].ring == ref.events[e].ring;
    a.event_time_error_s = std::max(a.event_time_error_s, std::abs(run.events[e].time_s - ref.events[e].time_s));
  }
  return a;
}

void run(const BenchLevel3Options& opt) {
  auto scene = load_scene(opt.scene);
  if (opt.velocity > 0 && scene.impactor) scene.impactor->velocity_m_s = opt.velocity;
  if (opt.shear_free) scene.hinge.level3_hinge_f = HingeSettings::Level3HingeF::ShearFree;
  fmt::print("bench-level3: {} ({} m/s), rtol {:g}, {} runs each, hinge F {}\n", scene.name,
             scene.impactor ? scene.impactor->velocity_m_s : 0.0, opt.rtol, opt.repeat,
             opt.shear_free ? "shear_free" : "from the scene");
  fmt::print("{:>8} {:>12} {:>10} {:>10} {:>8} {:>8}\n", "path", "median_ms", "min_ms", "max_ms", "steps", "ring1");
  for (auto integ : {HingeIntegrator::Ida, HingeIntegrator::Odeint}) {
    if (!opt.only.empty() && opt.only != (integ == HingeIntegrator::Ida ? "ida" : "odeint")) continue;
    HingeRunOptions o;
    o.level = "3";
    o.integrator = integ;
    o.relative_tolerance = opt.rtol;
    o.absolute_tolerance = opt.rtol * 1e-2;
    Level3RunOptions extra;
    extra.record_history = false;
    std::vector<double> ms;
    RunResult last;
    for (int k = 0; k < opt.repeat; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      last = run_hinge_level3(scene, o, extra);
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(ms.begin(), ms.end());
    fmt::print("{:>8} {:>12.3f} {:>10.3f} {:>10.3f} {:>8} {:>8}\n", integ == HingeIntegrator::Ida ? "ida" : "odeint",
               ms[ms.size() / 2], ms.front(), ms.back(), last.statistics.steps, last.mode.empty() ? "" : last.mode[0]);
    if (opt.accuracy) {
      const auto in = level3_input(scene);
      HingeRunOptions ref_o = o;
      ref_o.integrator = HingeIntegrator::Odeint;
      ref_o.relative_tolerance = 1e-12;
      ref_o.absolute_tolerance = 1e-14;
      const auto run = hinge::simulate_level3(in, hybrid_options(scene, o), false);
      const auto ref = hinge::simulate_level3(in, hybrid_options(scene, ref_o), false);
      const auto a = level3_accuracy(run, ref, in.ring.mean_diameter());
      fmt::print("{:>8} crush error {:.2e} d, events {} ({} / {}), event times within {:.1e} s, energy balance {:.1e} "
                 "(reference {:.1e}), steps {} + {} rejected\n",
                 "", a.crush_error_d, a.same_events ? "the same" : "DIFFERENT", run.events.size(), ref.events.size(),
                 a.event_time_error_s, run.energy_balance_error(), ref.energy_balance_error(),
                 run.outcome.statistics.steps, run.outcome.statistics.rejected_steps);
    }
  }
}

void add_command(CLI::App& app) {
  auto o = std::make_shared<BenchLevel3Options>();
  auto* cmd = app.add_subcommand("bench-level3", "Wall time of hinge Level 3 (median of repeated runs)");
  cmd->add_option("scene", o->scene, "Dynamic scene (default: Test 30 welded)")->check(CLI::ExistingFile);
  cmd->add_option("--repeat", o->repeat, "Runs per integrator (median)")->check(CLI::Range(1, 100000));
  cmd->add_option("--rtol", o->rtol, "Relative tolerance (atol = rtol/100)")->check(CLI::Range(1e-12, 1e-2));
  cmd->add_option("--velocity", o->velocity, "Override the impact speed (m/s)");
  cmd->add_flag("--shear-free", o->shear_free, "Hinge F travelling by the shear-free condition");
  cmd->add_option("--only", o->only, "One integrator only (ida | odeint), e.g. to time its CPU with /usr/bin/time")
      ->check(CLI::IsMember({"ida", "odeint"}));
  cmd->add_flag("--accuracy", o->accuracy, "Each run against Odeint at rtol 1e-12: crush error, events, energy");
  cmd->callback([o] { run(*o); });
}

const CommandRegistration registration{62, add_command};

}  // namespace
}  // namespace ringcrush::compare::cli
