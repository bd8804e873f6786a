#include "compare/fe_dynamic.hpp"

#include "compare/run_result_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "compare/fe_integration.hpp"
#include "compare/run_output.hpp"
#include "compare/svg_plot.hpp"
#include "fe/output/vtu_writer.hpp"

namespace ringcrush::compare {
namespace {

fe::JointKind joint_of(JointType j) {
  switch (j) {
    case JointType::Welded: return fe::JointKind::Welded;
    case JointType::Free: return fe::JointKind::Free;
    case JointType::Plates: return fe::JointKind::Plates;
  }
  return fe::JointKind::Free;
}

// The scenes the dynamic FE covers (issue 4): anything else is refused before a model is built.
void require_dynamic_fe_scene(const Scene& s) {
  if (s.analysis.type != AnalysisType::Dynamic)
    throw std::invalid_argument("fe dynamic: the scene's analysis is static (run it with the static FE)");
  if (s.fe.solver == FeSolver::Static)
    throw std::invalid_argument("fe dynamic: fe.solver = \"static\" cannot run an impact; use \"explicit\" or \"hht\"");
  if (s.rings.section != SectionState::PlaneStress)
    throw std::invalid_argument(
        "fe dynamic: CPS8 is a plane-stress element; set rings.section = \"plane_stress\"");
  if (s.fe.friction_coefficient != 0.0)
    throw std::invalid_argument(fmt::format(
        "fe dynamic: fe.friction_coefficient = {} but Coulomb friction is built for the static FE only "
        "(plates, fe/contact/plate_friction.hpp), not for the chain dynamics; use 0",
        s.fe.friction_coefficient));
  if (!s.impactor)
    throw std::invalid_argument("fe dynamic: the scene has no [impactor]");
}

// The same four classes as the Level 2 hinge runs (compare/hinge_run_2d.cpp), so that the two
// models' `mode` arrays compare word for word.
void check_finite(double v, const std::string& what) {
  if (!std::isfinite(v))
    throw std::runtime_error(fmt::format("fe dynamic result: non-finite {} (a failed run is not written)", what));
}

// A NaN anywhere in a result is a solver failure: refuse it before anything is derived from it.
void require_finite_result(const fe::DynamicResult& r, int rings) {
  if (r.history.empty()) throw std::runtime_error("fe dynamic result: empty history");
  for (std::size_t k = 0; k < r.history.size(); ++k) {
    const auto& h = r.history[k];
    const std::string at = fmt::format("at history row {} (t = {:g} s)", k, h.time_s);
    for (double v : {h.time_s, h.impactor_displacement_m, h.impactor_velocity_m_s, h.impactor_force_n, h.kinetic_j,
                     h.elastic_j, h.plastic_j, h.contact_j, h.numerical_j, h.external_work_j, h.bulk_viscous_j,
                     h.step_s})
      check_finite(v, "value " + at);
    if (static_cast<int>(h.ring_crush_m.size()) != rings)
      throw std::runtime_error(fmt::format("fe dynamic result: {} ring crushes {} for {} rings",
                                           h.ring_crush_m.size(), at, rings));
    for (double v : h.ring_crush_m) check_finite(v, "ring crush " + at);
  }
  for (Eigen::Index i = 0; i < r.final_displacement.size(); ++i)
    check_finite(r.final_displacement(i), fmt::format("final displacement (dof {})", i));
  for (double v : r.max_peeq_per_ring) check_finite(v, "max PEEQ");
  check_finite(r.energy_balance_error, "energy balance error");
  check_finite(r.numerical_dissipation, "numerical dissipation");
  check_finite(r.initial_kinetic_j, "initial kinetic energy");
}

}  // namespace

fe::ChainInput fe_chain_input(const Scene& s) {
  require_dynamic_fe_scene(s);
  fe::ChainInput in;
  in.rings = s.rings.count;
  in.ring.outer_radius_m = 0.5 * s.rings.outer_diameter_m;
  in.ring.inner_radius_m = in.ring.outer_radius_m - s.rings.wall_thickness_m;
  in.ring.width_m = s.rings.width_m;
  in.material.youngs_modulus_pa = s.rings.material.youngs_modulus_pa;
  in.material.poisson_ratio = s.rings.material.poisson_ratio;
  in.material.hardening.clear();
  for (const auto& p : s.rings.material.hardening) in.material.hardening.push_back({p.yield_stress_pa, p.plastic_strain});
  in.density_kg_m3 = s.rings.material.density_kg_m3;
  in.mesh.elements_around = s.fe.elements_around;
  in.mesh.elements_through = s.fe.elements_through;
  in.mesh.grading = s.fe.grading;
  in.mesh.half_ring = s.analysis.symmetry == Symmetry::Half;
  in.integration = fe_integration(s.fe.integration);
  in.contact.penalty_scale = s.fe.contact_penalty_scale;
  in.contact.smoothing = s.fe.contact_smoothing;
  in.contact.arrival_depth = s.fe.contact_arrival_depth;
  in.contact_penalty_step_fraction = s.fe.contact_penalty_step_fraction;
  in.pitch_m = s.rings.pitch_m;
  in.joints = joint_of(s.joints.type);
  in.plate_mass_kg = s.joints.plate_mass_kg;
  in.plate_thickness_m = s.joints.plate_thickness_m;
  // Physical (full) values: the ChainModel halves the mass itself for a half model.
  in.impactor_mass_kg = s.impactor->mass_kg;
  in.impactor_velocity_m_s = s.impactor->velocity_m_s;
  in.fixed_target = s.far_end == FarEnd::Fixed;
  // Bulk viscosity acts in the explicit driver only (the ChainModel forms it from the step
  // the explicit driver announces); HHT ignores it.
  in.bulk_viscosity = s.fe.bulk_viscosity;
  in.step_bound = s.fe.step_bound == ExplicitStepBound::Assembled ? fe::StepBound::Assembled : fe::StepBound::Element;
  // Mass scaling: explicit only (fe/dynamics/mass_scaling.hpp), refused with HHT by name.
  in.mass_scaling.target_step_s = s.fe.mass_scaling_dt;
  in.mass_scaling.factor = s.fe.mass_scaling_factor;
  in.mass_scaling.safety = s.fe.explicit_safety;
  if (s.fe.solver != FeSolver::Explicit && in.mass_scaling.active())
    throw std::invalid_argument(fmt::format(
        "fe dynamic: fe.mass_scaling_dt = {} s, fe.mass_scaling_factor = {} with fe.solver = \"hht\": mass scaling is "
        "for the explicit solver only (use --solver explicit, or remove the keys)",
        s.fe.mass_scaling_dt, s.fe.mass_scaling_factor));
  fe::validate(in);
  return in;
}

fe::DynamicSolverInput fe_dynamic_solver_input(const Scene& s) {
  require_dynamic_fe_scene(s);
  fe::DynamicSolverInput in;
  in.scheme = s.fe.solver == FeSolver::Hht ? fe::DynamicScheme::Hht : fe::DynamicScheme::Explicit;
  in.end_time_s = s.analysis.end_time_s;
  in.stop_at_rest = s.analysis.stop_at_rest;
  in.energy_error_limit = s.fe.energy_error_limit;
  in.safety = s.fe.explicit_safety;
  in.alpha = s.fe.hht_alpha;
  in.initial_step_s = s.fe.initial_step_s;
  in.max_step_s = std::max(in.max_step_s, in.initial_step_s);
  in.min_step_s = std::min(in.min_step_s, 1e-3 * in.initial_step_s);
  // HAFTOL and PTOL are forces on the model (the thesis's values were for its half model).
  in.haftol_n = s.fe.haftol_n;
  in.ptol_n = s.fe.ptol_n;
  in.max_iterations = s.fe.max_iterations;
  // History rows: about 1000 over the end time, never sparser than the driver's default.
  in.output_interval_s = std::min(in.output_interval_s, s.analysis.end_time_s / 1000.0);
  in.frames = s.outputs.fields ? s.outputs.frames : 0;
  return in;
}

fe::DynamicResult run_scene_dynamic(const Scene& scene, int threads) {
  fe::ChainInput chain = fe_chain_input(scene);
  chain.threads = threads;
  return fe::run_dynamic(chain, fe_dynamic_solver_input(scene));
}

std::vector<RingShape> outer_surface_shapes(const fe::ChainMesh& mesh, const Eigen::VectorXd& u) {
  if (u.size() < static_cast<Eigen::Index>(2 * mesh.nodes.size()))
    throw std::invalid_argument(fmt::format("outer_surface_shapes: {} displacement values for {} nodes", u.size(),
                                            mesh.nodes.size()));
  if (mesh.ring_outer_nodes.size() != mesh.ring_outer_theta.size())
    throw std::invalid_argument("outer_surface_shapes: outer nodes and angles differ in ring count");
  std::vector<RingShape> shapes(mesh.ring_outer_nodes.size());
  for (std::size_t r = 0; r < shapes.size(); ++r) {
    const auto& ids = mesh.ring_outer_nodes[r];
    if (ids.size() != mesh.ring_outer_theta[r].size())
      throw std::invalid_argument(fmt::format("outer_surface_shapes: ring {} has {} nodes and {} angles", r + 1,
                                              ids.size(), mesh.ring_outer_theta[r].size()));
    auto& shape = shapes[r];
    shape.half = mesh.half_ring;
    shape.surface_offset = 0.0;  // the points are on the outer surface
    shape.material_angle = mesh.ring_outer_theta[r];
    for (int id : ids) {
      const auto k = static_cast<Eigen::Index>(2 * id);
      shape.points.push_back(mesh.nodes[static_cast<std::size_t>(id)] + Eigen::Vector2d(u(k), u(k + 1)));
    }
  }
  return shapes;
}

RunResult fe_dynamic_run_result(const Scene& s, const fe::DynamicResult& r) {
  const int rings = s.rings.count;
  require_finite_result(r, rings);
  if (static_cast<int>(r.mesh.ring_outer_nodes.size()) != rings)
    throw std::runtime_error(fmt::format("fe dynamic result: the mesh has {} rings, the scene {}",
                                         r.mesh.ring_outer_nodes.size(), rings));
  RunResult out;
  out.model = "fe";
  out.scene = s.name;
  out.analysis = AnalysisType::Dynamic;
  out.ring_crush_m.assign(static_cast<std::size_t>(rings), {});
  for (const auto& h : r.history) {
    out.time_s.push_back(h.time_s);
    out.impactor_displacement_m.push_back(h.impactor_displacement_m);
    out.impactor_velocity_m_s.push_back(h.impactor_velocity_m_s);
    out.impactor_force_n.push_back(h.impactor_force_n);
    for (int i = 0; i < rings; ++i) out.ring_crush_m[static_cast<std::size_t>(i)].push_back(h.ring_crush_m[static_cast<std::size_t>(i)]);
    out.kinetic_j.push_back(h.kinetic_j);
    out.elastic_j.push_back(h.elastic_j);
    out.plastic_j.push_back(h.plastic_j);
    out.contact_j.push_back(h.contact_j);
    out.numerical_j.push_back(h.numerical_j);
    out.external_work_j.push_back(h.external_work_j);
  }
  // Bulk viscosity is an explicit-only damping (fe/element/bulk_viscosity.hpp): its column
  // appears only when it acted.
  if (s.fe.solver == FeSolver::Explicit && s.fe.bulk_viscosity > 0)
    for (const auto& h : r.history) out.bulk_viscous_j.push_back(h.bulk_viscous_j);

  // Final state per ring, measured once by compare/measures on the deformed outer surfaces
  // (THEORY §4.6): crush from the axial extent, wrap of ring i over ring i+1.
  const double d_outer = s.rings.outer_diameter_m, t = s.rings.wall_thickness_m;
  const double mean_radius = 0.5 * (d_outer - t);
  const auto shapes = outer_surface_shapes(r.mesh, r.final_displacement);
  std::vector<double> top_height, bottom_height;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const HalfHeights hh = half_heights(shapes[i], d_outer);
    top_height.push_back(hh.top);
    bottom_height.push_back(hh.bottom);
    const double c = crush_ratio(shapes[i], d_outer);
    const RingShape* lower = i + 1 < shapes.size() && s.joints.type != JointType::Plates ? &shapes[i + 1] : nullptr;
    const WrapMeasure w = measure_wrap(shapes[i], lower, mean_radius, t);
    out.crush_ratio.push_back(c);
    out.wrap_around.push_back(w.wrap_around);
    out.wrapped_angle_deg.push_back(w.wrapped_angle_deg);
    out.inverted_arc_m.push_back(w.inverted_arc_m);
    out.inverted_turning_deg.push_back(w.inverted_turning_deg);
    out.mode.push_back(deformation_mode(c, w.wrap_around));
  }
  // Final outlines for reports (outer surface, x ≥ 0 half of a half model).
  for (const auto& shape : shapes) {
    std::vector<std::array<double, 2>> outline;
    for (const auto& p : shape.points) outline.push_back({p.x(), p.y()});
    out.ring_outline_m.push_back(std::move(outline));
  }
  out.outline_half = r.mesh.half_ring;
  out.events.push_back({r.history.back().time_s, "run_ended", -1, r.end_reason});

  const auto& st = r.statistics;
  out.statistics.steps = st.steps;
  out.statistics.rejected_steps = st.rejected_steps;
  out.statistics.newton_iterations = st.newton_iterations;
  out.statistics.wall_time_s = st.wall_time_s;

  const double elements = static_cast<double>(r.mesh.elements.size());
  const double element_steps = elements * static_cast<double>(st.steps);
  const bool hht = s.fe.solver == FeSolver::Hht;
  // The driver's own balance (its numerical term is what closes the books; THEORY §3):
  // fe_dynamic_summary puts it in summary.json in place of run_output's recomputation, which
  // is zero by construction when numerical_j is the remainder.
  out.extra["energy_balance_error"] = r.energy_balance_error;
  out.extra["numerical_dissipation"] = r.numerical_dissipation;
  out.extra["end_reason"] = r.end_reason;
  out.extra["solver"] = hht ? "hht" : "explicit";
  out.extra["max_peeq_per_ring"] = r.max_peeq_per_ring;
  out.extra["top_height_ratio"] = top_height;
  out.extra["bottom_height_ratio"] = bottom_height;
  if (!hht) out.extra["explicit_safety"] = s.fe.explicit_safety;  // the scene's or --safety
  out.extra["step_limited_by"] = st.step_limited_by;
  out.extra["min_step_s"] = st.min_step_s;
  out.extra["max_step_s"] = st.max_step_s;
  out.extra["factorizations"] = st.factorizations;
  out.extra["contact_time_s"] = st.contact_time_s;
  out.extra["contact_share"] = st.wall_time_s > 0 ? st.contact_time_s / st.wall_time_s : 0.0;
  out.extra["time_per_element_step_s"] = element_steps > 0 ? st.wall_time_s / element_steps : 0.0;
  out.extra["model_initial_kinetic_energy_J"] = r.initial_kinetic_j;
  // The contact arrival rule acted (refused) or left a margin (admitted), fractions of the
  // through-wall element depth (fe/contact/contact_arrival.hpp).
  out.extra["contact_arrival"] = {{"arrival_depth", s.fe.contact_arrival_depth},
                                  {"refused", st.refused_contact_arrivals},
                                  {"deepest_refused", st.deepest_refused_arrival},
                                  {"deepest_refused_at", st.deepest_refused_arrival_at},
                                  {"admitted", st.admitted_contact_arrivals},
                                  {"deepest_admitted", st.deepest_admitted_arrival}};
  // The penalty the springs used (lowered by fe.contact_penalty_step_fraction when set) and
  // the deepest penetration it let through, over the accepted steps, in wall thicknesses.
  out.extra["contact_penalty"] = {{"scale", st.contact_penalty_scale},
                                  {"step_fraction", s.fe.contact_penalty_step_fraction},
                                  {"max_penetration_m", st.max_penetration_m},
                                  {"max_penetration_per_wall", st.max_penetration_m / s.rings.wall_thickness_m}};
  out.extra["mesh"] = {{"elements", r.mesh.elements.size()},
                       {"nodes", r.mesh.nodes.size()},
                       {"half_ring", r.mesh.half_ring},
                       {"elements_around", s.fe.elements_around},
                       {"elements_through", s.fe.elements_through}};
  const auto alt = alternation(out.crush_ratio);
  out.extra["alternates"] = alt.index > alternation_threshold;
  // Mass scaling changes the physics: what was added is reported with every scaled run
  // (whole chain; the impactor's mass for scale).
  if (r.mass_scaling.active) {
    const auto& ms = r.mass_scaling;
    const double impactor = s.impactor ? s.impactor->mass_kg : 0.0;
    out.extra["mass_scaling"] = {
        {"target_step_s", ms.target_step_s},
        {"factor", ms.factor},
        {"elements_scaled", ms.scaled_elements},
        {"elements", ms.elements},
        {"rings_mass_kg", ms.element_mass_kg},
        {"added_mass_kg", ms.added_mass_kg},
        {"added_mass_percent_of_rings", ms.element_mass_kg > 0 ? 100 * ms.added_mass_kg / ms.element_mass_kg : 0.0},
        {"added_mass_over_impactor_mass", impactor > 0 ? ms.added_mass_kg / impactor : 0.0},
        {"min_element_step_unscaled_s", ms.min_element_step_s},
        {"min_element_step_scaled_s", ms.min_scaled_element_step_s},
        {"steps_below_target", r.statistics.steps_below_mass_scaling_target}};
  }
  return out;
}

CsvTable rings_table(const Scene& s, const RunResult& run) {
  CsvTable t;
  t.columns = {"ring",           "crush_ratio",      "crush_m",         "wrapped_angle_deg", "inverted_arc_m",
               "wrap_around",    "top_height_ratio", "bottom_height_ratio", "max_peeq", "inverted_turning_deg"};
  auto per_ring = [&](const char* key) {
    return run.extra.contains(key) ? run.extra[key].get<std::vector<double>>() : std::vector<double>{};
  };
  const std::vector<double> peeq = per_ring("max_peeq_per_ring"), top = per_ring("top_height_ratio"),
                            bottom = per_ring("bottom_height_ratio");
  auto at = [](const std::vector<double>& v, std::size_t i) { return i < v.size() ? v[i] : 0.0; };
  for (std::size_t i = 0; i < run.crush_ratio.size(); ++i)
    t.add_row({static_cast<double>(i + 1), run.crush_ratio[i], run.crush_ratio[i] * s.rings.outer_diameter_m,
               run.wrapped_angle_deg[i], run.inverted_arc_m[i], run.wrap_around[i] ? 1.0 : 0.0, at(top, i),
               at(bottom, i), at(peeq, i), at(run.inverted_turning_deg, i)});
  return t;
}

namespace {
// Final crush ratio per ring as bars (one closed outline per bar, drawn as a line series),
// wrapped rings apart so the alternation and the wraps read at a glance.
void write_crush_bars(const Scene& s, const RunResult& run, ResultsDir& out) {
  SvgPlot p(fmt::format("Final crush per ring — {} (fe, {})", s.name,
                        run.extra.value("solver", std::string("?"))),
            "ring", "crush ratio δ/D");
  Series plain{"crushed / flattened / intact", {}, {}}, wrapped{"wrapped around the next ring", {}, {}};
  for (std::size_t i = 0; i < run.crush_ratio.size(); ++i) {
    auto& bar = run.wrap_around[i] ? wrapped : plain;
    const double x = static_cast<double>(i + 1), c = run.crush_ratio[i];
    for (auto [dx, y] : {std::pair{-0.35, 0.0}, {-0.35, c}, {0.35, c}, {0.35, 0.0}}) {
      bar.x.push_back(x + dx);
      bar.y.push_back(y);
    }
  }
  // A zero-height point per series keeps the axis at the full ring range.
  for (auto* series : {&plain, &wrapped}) {
    series->x.insert(series->x.begin(), 0.5);
    series->y.insert(series->y.begin(), 0.0);
    series->x.push_back(static_cast<double>(run.crush_ratio.size()) + 0.5);
    series->y.push_back(0.0);
    p.add(*series);
  }
  p.write(out.file("crush_per_ring.svg"));
}
}  // namespace

nlohmann::json fe_dynamic_summary(const Scene& s, const RunResult& run) {
  nlohmann::json j = summary_json(run, s);
  if (run.extra.contains("energy_balance_error")) j["energy_balance_error"] = run.extra["energy_balance_error"];
  return j;
}

void write_fe_dynamic_outputs(const Scene& s, const fe::DynamicResult& r, const RunResult& run, ResultsDir& out) {
  write_json(out.file("summary.json"), fe_dynamic_summary(s, run));
  write_json(out.file("run_result.json"), run_result_to_json(run));  // compare/, scripts, cache
  if (s.outputs.history) history_table(run).write(out.file("history.csv"));
  rings_table(s, run).write(out.file("rings.csv"));
  if (s.outputs.plots) {
    write_run_plots(run, s, out);
    write_crush_bars(s, run, out);
  }
  if (s.outputs.fields && !r.frames.empty()) {
    std::vector<std::pair<double, std::string>> entries;
    for (std::size_t i = 0; i < r.frames.size(); ++i) {
      const std::string name = fmt::format("frames/frame_{:04d}.vtu", i);
      fe::write_vtu(out.file(name), r.mesh, r.frames[i]);
      entries.emplace_back(r.frames[i].time_s, name);
    }
    fe::write_pvd(out.file("series.pvd"), entries);
  }
}

}  // namespace ringcrush::compare
