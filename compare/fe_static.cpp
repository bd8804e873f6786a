#include "compare/fe_static.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "compare/fe_integration.hpp"
#include "compare/formula.hpp"
#include "compare/svg_plot.hpp"
#include "compare/table_output.hpp"
#include "compare/version.hpp"
#include "fe/output/vtu_writer.hpp"
#include "hinge/ring_laws.hpp"

namespace ringcrush::compare {

fe::FeInput fe_static_input(const Scene& s) {
  if (s.analysis.type != AnalysisType::Static)
    throw std::invalid_argument("fe static: the scene's analysis is not static");
  if (s.rings.count != 1)
    throw std::invalid_argument(fmt::format("fe static: the static FE crush models one ring; the scene has {}",
                                            s.rings.count));
  if (s.rings.section != SectionState::PlaneStress)
    throw std::invalid_argument("fe static: CPS8 is a plane-stress element; set rings.section = \"plane_stress\"");
  // A static crush has no mass to scale: refuse the explicit-only option rather than ignore it.
  if (s.fe.mass_scaling_dt != 0.0 || s.fe.mass_scaling_factor != 1.0)
    throw std::invalid_argument(fmt::format(
        "fe static: fe.mass_scaling_dt = {} s, fe.mass_scaling_factor = {}: mass scaling is for the explicit dynamic "
        "solver only (a static run has no mass)",
        s.fe.mass_scaling_dt, s.fe.mass_scaling_factor));
  fe::FeInput in;
  in.ring.outer_radius_m = 0.5 * s.rings.outer_diameter_m;
  in.ring.inner_radius_m = in.ring.outer_radius_m - s.rings.wall_thickness_m;
  in.ring.width_m = s.rings.width_m;
  in.material.youngs_modulus_pa = s.rings.material.youngs_modulus_pa;
  in.material.poisson_ratio = s.rings.material.poisson_ratio;
  in.material.hardening.clear();
  for (const auto& p : s.rings.material.hardening) in.material.hardening.push_back({p.yield_stress_pa, p.plastic_strain});
  in.mesh.elements_around = s.fe.elements_around;
  in.mesh.elements_through = s.fe.elements_through;
  in.mesh.grading = s.fe.grading;
  in.mesh.half_ring = s.analysis.symmetry == Symmetry::Half;
  in.integration = fe_integration(s.fe.integration);
  in.contact.penalty_scale = s.fe.contact_penalty_scale;
  in.contact.smoothing = s.fe.contact_smoothing;
  // Coulomb friction at the plates (the inner wall against itself stays frictionless).
  in.contact.friction_coefficient = s.fe.friction_coefficient;
  in.contact.tangential_penalty_scale = s.fe.friction_penalty_scale;
  in.solver.crush_m = s.analysis.crush_m;
  in.solver.initial_increment = s.fe.initial_increment;
  in.solver.min_increment = s.fe.min_increment;
  in.solver.max_increment = s.fe.max_increment;
  in.solver.max_iterations = s.fe.max_iterations;
  // PTOL is a force on the model; the thesis's 6 N was for its half model.
  in.solver.force_tolerance_n = s.fe.ptol_n;
  in.solver.frames = s.outputs.fields ? s.outputs.frames : 0;
  fe::validate(in);
  return in;
}

RunResult fe_static_run_result(const Scene& s, const fe::StaticResult& r) {
  RunResult out;
  out.model = "fe";
  out.scene = s.name;
  out.analysis = AnalysisType::Static;
  out.ring_crush_m.resize(1);
  for (const auto& h : r.history) {
    out.deflection_m.push_back(h.deflection_m);
    out.force_n.push_back(h.force_n);
    out.ring_crush_m[0].push_back(h.deflection_m);
    out.kinetic_j.push_back(0.0);
    out.elastic_j.push_back(h.elastic_j);
    out.plastic_j.push_back(h.plastic_j);
    out.contact_j.push_back(h.contact_j);
    out.external_work_j.push_back(h.external_work_j);
    // Friction work is dissipated like plastic work; RunResult has no column of its own for
    // it, so it stays out of the numerical residue here and is reported in history.csv.
    out.numerical_j.push_back(h.external_work_j - h.elastic_j - h.plastic_j - h.contact_j - h.friction_j);
  }
  const double final_delta = r.history.back().deflection_m;
  out.crush_ratio = {final_delta / s.rings.outer_diameter_m};
  out.wrap_around = {false};
  out.wrapped_angle_deg = {0.0};
  out.mode = {"flattened"};
  bool touching = false;
  for (const auto& h : r.history) {
    if (!touching && h.self_contacts > 0)
      out.events.push_back({h.deflection_m, "contact_closed", 0, "inner wall touches itself (lock-up)"});
    if (touching && h.self_contacts == 0)
      out.events.push_back({h.deflection_m, "contact_opened", 0, "inner wall separates"});
    touching = h.self_contacts > 0;
  }
  out.statistics.steps = r.statistics.increments;
  out.statistics.rejected_steps = r.statistics.cutbacks;
  out.statistics.newton_iterations = r.statistics.newton_iterations;
  out.statistics.wall_time_s = r.statistics.wall_time_s;
  return out;
}

RedwoodFit fit_redwood(const Scene& s, const std::vector<double>& delta, const std::vector<double>& force,
                       double from, double to, double lo, double hi) {
  const FormulaInput fin = formula_input(s);
  const double d = fin.section.mean_diameter();
  const double m0 = hinge::plastic_moment(fin.section, fin.yield_stress_pa, fin.state);
  const double p0 = hinge::collapse_load(m0, d);
  std::vector<std::pair<double, double>> pts;
  for (std::size_t i = 0; i < delta.size(); ++i)
    if (delta[i] / d >= from && delta[i] / d <= to) pts.emplace_back(delta[i], force[i]);
  if (pts.empty()) throw std::invalid_argument("fit_redwood: no points in the deflection range");
  auto deviation = [&](double alpha, double& maxdev) {
    double sum = 0;
    maxdev = 0;
    for (auto [x, p] : pts) {
      const double pr = hinge::redwood_load(p0, fin.hardening_modulus_pa, fin.yield_stress_pa, alpha, x, d);
      const double e = (p - pr) / pr;
      sum += e * e;
      maxdev = std::max(maxdev, std::abs(e));
    }
    return std::sqrt(sum / static_cast<double>(pts.size()));
  };
  // Golden-section search in log α (the deviation is unimodal in α for a rising curve).
  double a = std::log(lo), b = std::log(hi), md;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double c = b - g * (b - a), e = a + g * (b - a);
  double fc = deviation(std::exp(c), md), fe_ = deviation(std::exp(e), md);
  for (int it = 0; it < 60; ++it) {
    if (fc < fe_) { b = e; e = c; fe_ = fc; c = b - g * (b - a); fc = deviation(std::exp(c), md); }
    else { a = c; c = e; fc = fe_; e = a + g * (b - a); fe_ = deviation(std::exp(e), md); }
  }
  RedwoodFit fit;
  fit.alpha = std::exp(0.5 * (a + b));
  fit.rms_relative_deviation = deviation(fit.alpha, fit.max_relative_deviation);
  fit.min_ratio_to_deruntz_hodge = 1e300;
  for (auto [x, p] : pts)
    fit.min_ratio_to_deruntz_hodge = std::min(fit.min_ratio_to_deruntz_hodge, p / hinge::deruntz_hodge_load(p0, x, d));
  return fit;
}

void write_fe_static_outputs(const Scene& s, const fe::StaticResult& r, const RunResult& run, ResultsDir& out) {
  if (s.outputs.history) {
    CsvTable t;
    t.columns = {"deflection_m", "force_N", "fixed_plate_force_N", "self_contact_force_N",
                 "elastic_energy_J", "plastic_dissipation_J", "contact_energy_J", "external_work_J",
                 "friction_dissipation_J", "energy_balance_error_J", "increment", "iterations"};
    for (const auto& h : r.history)
      t.add_row({h.deflection_m, h.force_n, h.fixed_force_n, h.self_contact_force_n, h.elastic_j, h.plastic_j,
                 h.contact_j, h.external_work_j, h.friction_j,
                 h.external_work_j - h.elastic_j - h.plastic_j - h.contact_j - h.friction_j,
                 h.increment, static_cast<double>(h.iterations)});
    t.write(out.file("history.csv"));
  }

  const FormulaInput fin = formula_input(s);
  const double d = fin.section.mean_diameter();
  const double m0 = hinge::plastic_moment(fin.section, fin.yield_stress_pa, fin.state);
  const double p0 = hinge::collapse_load(m0, d);
  const double final_delta = r.history.back().deflection_m;
  RedwoodFit fit{};
  const bool can_fit = final_delta / d >= 0.7;
  if (can_fit) fit = fit_redwood(s, run.deflection_m, run.force_n);

  if (s.outputs.plots) {
    SvgPlot plot(fmt::format("FE static crush of one ring ({})", s.name), "deflection δ (mm)", "load P (N)");
    std::vector<double> x, y;
    for (const auto& h : r.history) {
      x.push_back(h.deflection_m * 1e3);
      y.push_back(h.force_n);
    }
    plot.add({"FE (CPS8)", x, y});
    std::vector<double> xd, ydh, yrw;
    const double top = std::min(final_delta, 0.99 * d);
    const double alpha = can_fit ? fit.alpha : s.hinge.redwood_alpha;
    for (int i = 0; i <= 100; ++i) {
      const double dl = top * i / 100.0;
      xd.push_back(dl * 1e3);
      ydh.push_back(hinge::deruntz_hodge_load(p0, dl, d));
      yrw.push_back(hinge::redwood_load(p0, fin.hardening_modulus_pa, fin.yield_stress_pa, alpha, dl, d));
    }
    plot.add({"DeRuntz–Hodge", xd, ydh, true});
    plot.add({fmt::format("Redwood α = {:.2f}{}", alpha, can_fit ? " (best fit)" : ""), xd, yrw, true});
    plot.write(out.file("load_deflection.svg"));
  }

  if (s.outputs.fields && !r.frames.empty()) {
    std::vector<std::pair<double, std::string>> entries;
    for (std::size_t i = 0; i < r.frames.size(); ++i) {
      const std::string name = fmt::format("frames/frame_{:04d}.vtu", i);
      fe::write_vtu(out.file(name), r.mesh, r.frames[i]);
      entries.emplace_back(r.frames[i].deflection_m, name);
    }
    fe::write_pvd(out.file("series.pvd"), entries);
  }

  const auto& st = r.statistics;
  double max_force = 0, max_self = 0, first_self = -1, max_self_pen = 0, max_plate_pen = 0;
  for (const auto& h : r.history) {
    max_force = std::max(max_force, h.force_n);
    max_self = std::max(max_self, h.self_contact_force_n);
    max_self_pen = std::max(max_self_pen, h.max_self_penetration_m);
    max_plate_pen = std::max(max_plate_pen, h.max_plate_penetration_m);
    if (first_self < 0 && h.self_contacts > 0) first_self = h.deflection_m;
  }
  const auto& last = r.history.back();
  nlohmann::json summary = {
      {"model", "fe"},
      {"scene", s.name},
      {"analysis", "static"},
      {"version", std::string(version())},
      {"wall_time_s", st.wall_time_s},
      {"steps", st.increments},
      {"max_force_N", max_force},
      {"final_deflection_m", final_delta},
      {"final_force_N", last.force_n},
      {"increments", st.increments},
      {"cutbacks", st.cutbacks},
      {"newton_iterations", st.newton_iterations},
      {"iterations_per_increment", st.increments ? double(st.newton_iterations) / double(st.increments) : 0.0},
      {"time_per_iteration_s", st.newton_iterations ? st.wall_time_s / double(st.newton_iterations) : 0.0},
      {"line_searches", st.line_searches},
      {"residual_evaluations", st.residual_evaluations},
      {"pattern_analyses", st.pattern_analyses},
      {"factorizations", st.factorizations},
      {"mesh", {{"elements", r.mesh.elements.size()}, {"nodes", r.mesh.nodes.size()},
                {"half_ring", r.mesh.half_ring}}},
      {"initial_overlaps", r.initial_overlaps},
      {"max_initial_overlap_m", r.max_initial_overlap_m},
      {"max_equilibrium_error", r.max_equilibrium_error},
      {"energy_balance_error", last.external_work_j > 0
                                   ? (last.external_work_j - last.elastic_j - last.plastic_j - last.contact_j -
                                      last.friction_j) /
                                         last.external_work_j
                                   : 0.0},
      {"external_work_J", last.external_work_j},
      {"plastic_dissipation_J", last.plastic_j},
      {"friction_coefficient", s.fe.friction_coefficient},
      {"friction_dissipation_J", last.friction_j},
      {"P0_N", p0},
      {"max_self_contact_force_N", max_self},
      {"max_self_penetration_m", max_self_pen},
      {"max_plate_penetration_m", max_plate_pen},
      {"crush_ratio", run.crush_ratio},
  };
  summary["self_contact_first_deflection_m"] = first_self >= 0 ? nlohmann::json(first_self) : nlohmann::json(nullptr);
  if (can_fit)
    summary["redwood_fit"] = {{"alpha", fit.alpha},
                              {"max_relative_deviation", fit.max_relative_deviation},
                              {"rms_relative_deviation", fit.rms_relative_deviation},
                              {"min_ratio_to_deruntz_hodge", fit.min_ratio_to_deruntz_hodge},
                              {"range_delta_over_d", {0.1, 0.7}}};
  write_json(out.file("summary.json"), summary);
}

}  // namespace ringcrush::compare
