// ringcrush formula — the DeRuntz–Hodge / Redwood load–deflection curves of one ring
// (thesis §4.1.2, THEORY.md §1), from a scene or from flags.
//
//   ringcrush formula data/scenes/thesis_static.toml -o results/formula
//   ringcrush formula --D 0.0508 --t 0.0016 --L 0.0125 --sigma0 273e6 --Ep 2.2e9 -o out
//
// Prints the reference values and the table; writes summary.json, history.csv and
// load_deflection.svg into the results directory.
#include <fmt/format.h>

#include <chrono>
#include <optional>

#include "compare/cli/commands.hpp"
#include "compare/formula.hpp"
#include "compare/results_dir.hpp"
#include "compare/svg_plot.hpp"
#include "compare/version.hpp"

namespace ringcrush::compare::cli {
namespace {

struct FormulaOptions {
  std::string scene;
  std::optional<double> D, t, L, sigma0, Ep, E, nu;
  std::vector<double> alphas{0.5, 1.0, 2.0};
  bool plane_strain = false;
  int points = 41;
  std::string output;
};

FormulaInput resolve(const FormulaOptions& o, std::string& scene_name) {
  FormulaInput in{};
  if (!o.scene.empty()) {
    const Scene s = load_scene(o.scene);
    scene_name = s.name;
    in = formula_input(s);
  } else {
    for (auto [v, name] : {std::pair{o.D, "--D"}, {o.t, "--t"}, {o.L, "--L"}, {o.sigma0, "--sigma0"}})
      if (!v) throw std::invalid_argument(fmt::format("{} is required without a scene", name));
    scene_name = "flags";
    in.yield_stress_pa = 0;
    in.hardening_modulus_pa = 0;
    in.youngs_modulus_pa = 202e9;
    in.poisson_ratio = 0.3;
  }
  // Flags override the scene.
  if (o.D) in.section.outer_diameter_m = *o.D;
  if (o.t) in.section.wall_thickness_m = *o.t;
  if (o.L) in.section.width_m = *o.L;
  if (o.sigma0) in.yield_stress_pa = *o.sigma0;
  if (o.Ep) in.hardening_modulus_pa = *o.Ep;
  if (o.E) in.youngs_modulus_pa = *o.E;
  if (o.nu) in.poisson_ratio = *o.nu;
  if (o.plane_strain) in.state = hinge::SectionState::PlaneStrain;
  in.alphas = o.alphas;
  const auto& s = in.section;
  if (!(s.outer_diameter_m > 0 && s.wall_thickness_m > 0 && s.width_m > 0))
    throw std::invalid_argument("D, t and L must be positive");
  if (!(s.wall_thickness_m < 0.5 * s.outer_diameter_m))
    throw std::invalid_argument("t must be less than D/2");
  if (!(in.yield_stress_pa > 0)) throw std::invalid_argument("sigma0 must be positive");
  if (!(in.hardening_modulus_pa >= 0)) throw std::invalid_argument("Ep must not be negative");
  for (double a : in.alphas)
    if (!(a > 0)) throw std::invalid_argument("every alpha must be positive");
  return in;
}

void run(const FormulaOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  std::string scene_name;
  const FormulaInput in = resolve(o, scene_name);
  const FormulaResult r = evaluate_formula(in, o.points);
  const double d = in.section.mean_diameter();
  const bool strain = in.state == hinge::SectionState::PlaneStrain;

  fmt::print("Ring: D = {:.2f} mm, t = {:.2f} mm, L = {:.2f} mm (d = {:.2f} mm), {}\n",
             in.section.outer_diameter_m * 1e3, in.section.wall_thickness_m * 1e3,
             in.section.width_m * 1e3, d * 1e3, strain ? "plane strain" : "plane stress");
  fmt::print("       sigma0 = {:.1f} MPa, E' = {:.3f} GPa\n", in.yield_stress_pa / 1e6,
             in.hardening_modulus_pa / 1e9);
  fmt::print("M0 = {:.5f} N m   P0 = 8 M0/d = {:.3f} N   k_el = {:.2f} N/mm   P_y = {:.2f} N\n",
             r.plastic_moment_nm, r.collapse_load_n, r.elastic_stiffness_n_m / 1e3, r.first_yield_load_n);
  fmt::print("lock-up at delta = d - t = {:.2f} mm: W_DH = {:.3f} J", r.lock_deflection_m * 1e3,
             r.dh_energy_to_lock_j);
  for (std::size_t i = 0; i < in.alphas.size(); ++i)
    fmt::print(", W_RW(alpha={:g}) = {:.3f} J", in.alphas[i], r.redwood_energy_to_lock_j[i]);
  fmt::print("\n\n{:>10} {:>8} {:>12}", "delta_mm", "delta/d", "P_DH_N");
  for (double a : in.alphas) fmt::print(" {:>12}", fmt::format("P_RW({:g})_N", a));
  fmt::print("\n");
  for (const auto& row : r.curves.rows) {
    fmt::print("{:10.3f} {:8.4f} {:12.2f}", row[0] * 1e3, row[1], row[2]);
    for (std::size_t i = 0; i < in.alphas.size(); ++i) fmt::print(" {:12.2f}", row[3 + i]);
    fmt::print("\n");
  }

  if (o.output.empty()) return;
  ResultsDir out(o.output);
  r.curves.write(out.file("history.csv"));

  SvgPlot plot(fmt::format("Load–deflection of one ring ({})", scene_name), "deflection δ (mm)",
               "load P (N)");
  const auto delta = r.curves.column("deflection_m");
  auto mm = delta;
  for (auto& v : mm) v *= 1e3;
  plot.add({"DeRuntz–Hodge", mm, r.curves.column("force_deruntz_hodge_N")});
  for (double a : in.alphas)
    plot.add({fmt::format("Redwood α = {:g}", a), mm,
              r.curves.column(fmt::format("force_redwood_alpha_{:g}_N", a)), true});
  plot.write(out.file("load_deflection.svg"));

  nlohmann::json summary = {
      {"model", "formula"},
      {"scene", scene_name},
      {"analysis", "static"},
      {"version", std::string(version())},
      {"steps", r.curves.rows.size()},
      {"section", strain ? "plane_strain" : "plane_stress"},
      {"M0_Nm", r.plastic_moment_nm},
      {"P0_N", r.collapse_load_n},
      {"elastic_stiffness_N_m", r.elastic_stiffness_n_m},
      {"first_yield_load_N", r.first_yield_load_n},
      {"lock_deflection_m", r.lock_deflection_m},
      {"final_deflection_m", r.lock_deflection_m},
      {"max_force_N", r.curves.rows.back()[2]},
      {"energy_to_lock_deruntz_hodge_J", r.dh_energy_to_lock_j},
      {"redwood_alpha", in.alphas},
      {"energy_to_lock_redwood_J", r.redwood_energy_to_lock_j},
  };
  summary["wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_json(out.file("summary.json"), summary);
  out.commit();
  fmt::print("\nwrote {}/{{summary.json, history.csv, load_deflection.svg}}\n", out.target().string());
}

}  // namespace

namespace {
void add_formula_command(CLI::App& app) {
  auto o = std::make_shared<FormulaOptions>();
  auto* cmd = app.add_subcommand(
      "formula", "DeRuntz–Hodge and Redwood load–deflection of one ring (thesis §4.1.2)");
  cmd->add_option("scene", o->scene, "Scene file (ring geometry and material)")->check(CLI::ExistingFile);
  cmd->add_option("--D", o->D, "Outer diameter (m)");
  cmd->add_option("--t", o->t, "Wall thickness (m)");
  cmd->add_option("--L", o->L, "Ring width / tube length (m)");
  cmd->add_option("--sigma0", o->sigma0, "Yield stress (Pa)");
  cmd->add_option("--Ep", o->Ep, "Linear hardening modulus E' (Pa)");
  cmd->add_option("--E", o->E, "Young's modulus (Pa), for the elastic stiffness");
  cmd->add_option("--nu", o->nu, "Poisson's ratio, for plane strain");
  cmd->add_option("--alpha", o->alphas, "Redwood hinge-length factors (default 0.5 1 2)");
  cmd->add_flag("--plane-strain", o->plane_strain, "Long tube: plane-strain M0 and stiffness");
  cmd->add_option("--points", o->points, "Rows from delta = 0 to lock-up")->check(CLI::Range(2, 100000));
  cmd->add_option("-o,--output", o->output, "Results directory (written completely or not at all)");
  cmd->callback([o] { run(*o); });
}

const CommandRegistration registration{10, add_formula_command};
}  // namespace

}  // namespace ringcrush::compare::cli
