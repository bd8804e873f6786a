#include "compare/hinge_run_2d.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <stdexcept>

#include "compare/shape_output.hpp"

namespace ringcrush::compare {

namespace {

constexpr double pi = std::numbers::pi;

hinge::PolygonJoint joint_of(JointType j) {
  switch (j) {
    case JointType::Welded: return hinge::PolygonJoint::Welded;
    case JointType::Free: return hinge::PolygonJoint::Free;
    case JointType::Plates: return hinge::PolygonJoint::Plates;
  }
  return hinge::PolygonJoint::Free;
}

}  // namespace

Level2Settings level2_settings(const Scene& scene, HingeIntegrator integrator) {
  Level2Settings s;
  const bool cd = integrator == HingeIntegrator::CentralDifference;
  // The central difference: the implicit membrane unscaled with the penalties × 1/16 unless the
  // scene turns it off (then the 1/4 scales); IDA and Odeint: the unscaled model.
  s.central_difference_implicit_membrane = scene.hinge.level2_implicit_membrane.value_or(cd);
  const bool implicit = cd && s.central_difference_implicit_membrane;
  const double membrane_fallback = cd && !implicit ? kCentralDifferenceStiffTermScale : 1.0;
  const double penalty_fallback = !cd ? 1.0 : implicit ? kImplicitMembranePenaltyScale : kCentralDifferenceStiffTermScale;
  const double penalty = scene.hinge.level2_penalty_stiffness_scale.value_or(penalty_fallback);
  s.membrane_stiffness_scale = scene.hinge.level2_membrane_stiffness_scale.value_or(membrane_fallback);
  s.contact_stiffness_scale *= penalty;
  s.tie_stiffness_scale *= penalty;
  if (implicit) s.central_difference_safety = kImplicitMembraneSafety;
  s.membrane_damping_ratio = scene.hinge.membrane_damping_ratio.value_or(s.membrane_damping_ratio);
  s.hinge_damping_ratio = scene.hinge.hinge_damping_ratio.value_or(s.hinge_damping_ratio);
  s.hinge_damper_on_elastic_rate = scene.hinge.level2_hinge_damper == HingeSettings::Level2HingeDamper::Elastic;
  s.flow_d_per_s = scene.hinge.level2_flow_rate_per_s.value_or(s.flow_d_per_s);
  s.flow_q = scene.hinge.level2_flow_exponent.value_or(s.flow_q);
  return s;
}

hinge::PolygonChainInput polygon_input(const Scene& scene, const Level2Settings& s) {
  const auto& rings = scene.rings;
  const auto& mat = rings.material;
  hinge::PolygonChainInput in;
  in.rings = rings.count;
  in.outer_diameter_m = rings.outer_diameter_m;
  in.wall_thickness_m = rings.wall_thickness_m;
  in.width_m = rings.width_m;
  in.pitch_m = rings.pitch_m;
  // Section state (THEORY §1.2): plane strain uses E/(1 − ν²) and the yield 2σ0/√3.
  const bool strain = rings.section == SectionState::PlaneStrain;
  const double nu = mat.poisson_ratio;
  const double yield_factor = strain ? 2.0 / std::sqrt(3.0) : 1.0;
  in.youngs_modulus_pa = strain ? mat.youngs_modulus_pa / (1 - nu * nu) : mat.youngs_modulus_pa;
  in.yield_stress_pa = yield_factor * mat.initial_yield_stress();
  in.hardening_modulus_pa = yield_factor * mat.hardening_modulus();
  // The flat end of the hardening table caps the hinge moment.
  in.yield_cap_ratio = mat.hardening.size() > 1
                           ? mat.hardening.back().yield_stress_pa / mat.initial_yield_stress()
                           : 0.0;
  in.density_kg_m3 = mat.density_kg_m3;
  in.nodes_per_ring = scene.hinge.nodes_per_ring;
  in.half_symmetry = scene.analysis.symmetry == Symmetry::Half;
  in.redwood_alpha = scene.hinge.redwood_alpha;
  in.redwood_fitted_hardening = scene.hinge.hardening_length == HingeSettings::HardeningLength::RedwoodFit;
  in.cowper_symonds_d_per_s = s.flow_d_per_s;
  in.cowper_symonds_q = s.flow_q;
  in.joint = joint_of(scene.joints.type);
  in.plate_mass_kg = scene.joints.plate_mass_kg;
  in.plate_thickness_m = scene.joints.plate_thickness_m;
  in.tie_stiffness_scale = s.tie_stiffness_scale;
  in.contact_stiffness_scale = s.contact_stiffness_scale;
  in.membrane_stiffness_scale = s.membrane_stiffness_scale;
  in.contact_damping_s_per_m = s.contact_damping_s_per_m;
  in.membrane_damping_ratio = s.membrane_damping_ratio;
  in.hinge_damping_ratio = s.hinge_damping_ratio;
  in.hinge_damper_on_elastic_rate = s.hinge_damper_on_elastic_rate;
  in.fixed_target = scene.far_end == FarEnd::Fixed;
  if (scene.analysis.type == AnalysisType::Static) {
    in.driven_impactor = true;
    in.drive_speed_m_s = s.static_speed_m_s;
    in.drive_ramp_s = 0.02 * scene.analysis.crush_m / s.static_speed_m_s;
    in.mass_damping_per_s = s.static_mass_damping_per_s;
    in.impactor_mass_kg = 0.0;
  } else {
    if (!scene.impactor) throw std::invalid_argument("Level 2: a dynamic scene needs an [impactor]");
    in.impactor_mass_kg = scene.impactor->mass_kg;
    in.impactor_velocity_m_s = scene.impactor->velocity_m_s;
  }
  return in;
}

std::vector<RingShape> ring_shapes(const hinge::PolygonShape& shape, double wall_thickness) {
  std::vector<RingShape> out;
  for (const auto& nodes : shape.nodes) {
    RingShape r;
    const auto n = nodes.size();
    for (std::size_t k = 0; k < n; ++k) {
      r.points.emplace_back(nodes[k][0], nodes[k][1]);
      r.material_angle.push_back(2.0 * pi * static_cast<double>(k) / static_cast<double>(n));
    }
    r.half = false;
    r.surface_offset = wall_thickness;
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<RingHingeMap> hinge_map(const hinge::PolygonShape& shape,
                                    const std::vector<std::vector<double>>& first_yield,
                                    double peak_fraction) {
  std::vector<RingHingeMap> maps;
  for (std::size_t r = 0; r < shape.plastic_rotation.size(); ++r) {
    const auto& a = shape.plastic_rotation[r];
    const std::size_t n = a.size();
    RingHingeMap m;
    const double top = *std::max_element(a.begin(), a.end());
    // Peaks on the x ≥ 0 side (nodes 0…N/2; the other side mirrors it in a symmetric run).
    for (std::size_t k = 0; k <= n / 2; ++k) {
      const double prev = a[(k + n - 1) % n], next = a[(k + 1) % n];
      if (top > 0 && a[k] >= peak_fraction * top && a[k] >= prev && a[k] >= next &&
          (a[k] > prev || a[k] > next))
        m.peaks.push_back({360.0 * static_cast<double>(k) / static_cast<double>(n), a[k],
                           first_yield[r][k]});
    }
    for (std::size_t k = 0; k < n; ++k)
      if (first_yield[r][k] >= 0 && (m.first_yield_s < 0 || first_yield[r][k] < m.first_yield_s)) {
        m.first_yield_s = first_yield[r][k];
        const double deg = 360.0 * static_cast<double>(k) / static_cast<double>(n);
        m.first_yield_angle_deg = deg > 180.0 ? 360.0 - deg : deg;
      }
    maps.push_back(std::move(m));
  }
  return maps;
}

Level2Run run_level2(const Scene& scene, const HingeRunOptions& options, const Level2Settings& s) {
  Level2Run run;
  const auto in = polygon_input(scene, s);
  const bool is_static = scene.analysis.type == AnalysisType::Static;
  hinge::PolygonRunOptions po;
  po.integrator = options.integrator == HingeIntegrator::Ida      ? hinge::PolygonIntegrator::Ida
                  : options.integrator == HingeIntegrator::Odeint ? hinge::PolygonIntegrator::Odeint
                                                                  : hinge::PolygonIntegrator::CentralDifference;
  po.central_difference_safety = s.central_difference_safety;
  po.central_difference_implicit_dampers = s.central_difference_implicit_dampers;
  po.central_difference_implicit_membrane = s.central_difference_implicit_membrane;
  po.step_breakdown = s.step_breakdown;
  po.central_difference_power_bound = s.central_difference_power_bound;
  po.central_difference_landing_depth_m = s.central_difference_landing_depth_ratio * scene.rings.wall_thickness_m;
  if (po.integrator == hinge::PolygonIntegrator::CentralDifference)
    po.energy_error_limit = s.central_difference_energy_error_limit;
  run.relative_tolerance_used = options.relative_tolerance >= s.min_relative_tolerance
                                    ? options.relative_tolerance
                                    : s.default_relative_tolerance;
  po.relative_tolerance = run.relative_tolerance_used;
  po.absolute_scale = 1e-3 * run.relative_tolerance_used;  // × R, V, 1 rad, KE0
  po.velocity_tolerance_factor = s.velocity_tolerance_factor;
  po.plastic_tolerance_factor = s.plastic_tolerance_factor;
  po.ida_jacobian_reuse_steps = s.jacobian_reuse_steps;
  po.ida_klu_ordering = s.klu_ordering;
  po.ida_pattern_slack = s.pattern_slack;
  po.output_interval_s = s.output_interval_s;
  po.settle_time_s = s.settle_time_s;
  if (is_static) {
    // The cosine ramp of the plate speed covers half its duration in travel.
    po.end_time_s = 0.5 * in.drive_ramp_s + scene.analysis.crush_m / s.static_speed_m_s;
    po.stop_at_arrest = false;
    po.output_interval_s = po.end_time_s / 400.0;
  } else {
    po.end_time_s = scene.analysis.end_time_s;
    po.stop_at_arrest = scene.analysis.stop_at_rest;
  }
  run.raw = hinge::run_polygon_chain(in, po);
  const auto& raw = run.raw;
  const auto& h = raw.history;
  const double D = scene.rings.outer_diameter_m, t = scene.rings.wall_thickness_m;
  const double R = 0.5 * (D - t);
  const auto nsteps = h.time_s.size();

  RunResult& r = run.result;
  r.model = "hinge";
  r.scene = scene.name;
  r.analysis = scene.analysis.type;
  if (is_static) {
    r.deflection_m = h.impactor_displacement_m;
    r.force_n = h.impactor_force_n;
  }
  r.time_s = h.time_s;
  r.impactor_displacement_m = h.impactor_displacement_m;
  r.impactor_velocity_m_s = h.impactor_velocity_m_s;
  r.impactor_force_n = h.impactor_force_n;
  r.ring_crush_m.assign(static_cast<std::size_t>(scene.rings.count), std::vector<double>(nsteps));
  for (std::size_t i = 0; i < nsteps; ++i) {
    const auto shapes = ring_shapes(h.shapes[i], t);
    for (std::size_t ring = 0; ring < shapes.size(); ++ring) r.ring_crush_m[ring][i] = crush(shapes[ring], D);
  }
  r.kinetic_j = h.kinetic_j;
  r.elastic_j = h.elastic_j;
  r.plastic_j = h.plastic_j;
  r.contact_j.resize(nsteps);
  r.numerical_j = h.damping_j;
  for (std::size_t i = 0; i < nsteps; ++i) r.contact_j[i] = h.contact_j[i] + h.contact_damping_j[i];
  r.external_work_j = h.external_j;

  // Crush and inverted arc S on the final shapes; the wrapped angle W on the shapes at the
  // impactor's arrest (largest compaction): once unloaded, free rings spring apart by more
  // than the 0.1 t contact cap of W, although the wrapped shape stays.
  const auto final_shapes = ring_shapes(h.shapes.back(), t);
  std::size_t arrest_sample = nsteps - 1;
  if (raw.arrest_time_s >= 0)
    for (std::size_t i = 0; i < nsteps; ++i)
      if (h.time_s[i] >= raw.arrest_time_s) {
        arrest_sample = i;
        break;
      }
  const auto arrest_shapes = ring_shapes(h.shapes[arrest_sample], t);
  WrapThresholds thresholds;
  thresholds.min_inverted_arc_fraction = s.wrap_min_inverted_arc_fraction;
  std::vector<double> top_height, bottom_height;
  for (std::size_t ring = 0; ring < final_shapes.size(); ++ring) {
    const HalfHeights hh = half_heights(final_shapes[ring], D);
    top_height.push_back(hh.top);
    bottom_height.push_back(hh.bottom);
    const bool below = ring + 1 < final_shapes.size() && scene.joints.type != JointType::Plates;
    WrapMeasure w;
    const InvertedArc arc = inverted_arc(final_shapes[ring]);
    w.inverted_arc_m = arc.length_m;
    w.inverted_turning_deg = arc.turning_deg;
    if (below) w.wrapped_angle_deg = wrapped_angle_deg(arrest_shapes[ring], arrest_shapes[ring + 1], 1.1 * t);
    // Decided on S and T (compare/measures wrap_flag); in free chains the wrapped arc of ring
    // i bridges over the apex of ring i+1 (Test 30: a 4.5 mm gap on the axis, contact at
    // 37–45°), where W, contiguous from the apex, reads 0.
    w.wrap_around = below && wrap_flag(arc, R, thresholds);  // measures.hpp measure_wrap
    const double c = crush_ratio(final_shapes[ring], D);
    r.crush_ratio.push_back(c);
    r.wrap_around.push_back(w.wrap_around);
    r.wrapped_angle_deg.push_back(w.wrapped_angle_deg);
    r.inverted_arc_m.push_back(w.inverted_arc_m);
    r.inverted_turning_deg.push_back(w.inverted_turning_deg);
    r.mode.push_back(deformation_mode(c, w.wrap_around));
  }

  // Final outlines (mean line, closed) for reports; same chain frame as the FE (ring 1
  // centred at y = 0, rings below).
  for (const auto& shape : final_shapes) {
    std::vector<std::array<double, 2>> outline;
    for (const auto& p : shape.points) outline.push_back({p.x(), p.y()});
    if (!outline.empty()) outline.push_back(outline.front());
    r.ring_outline_m.push_back(std::move(outline));
  }
  r.outline_half = false;
  for (std::size_t i : frame_samples(h.shapes.size(), scene.outputs.fields ? scene.outputs.frames : 0)) {
    ShapeFrame f;
    f.time_s = h.time_s[i];
    f.rings = h.shapes[i].nodes;
    f.plastic_rotation = h.shapes[i].plastic_rotation;
    f.body_faces = h.shapes[i].body_faces;
    r.shape_frames.push_back(std::move(f));
  }

  run.hinge_map = hinge_map(h.shapes.back(), raw.first_yield_time_s);
  nlohmann::json maps = nlohmann::json::array();
  for (std::size_t ring = 0; ring < run.hinge_map.size(); ++ring) {
    const auto& m = run.hinge_map[ring];
    nlohmann::json peaks = nlohmann::json::array();
    for (const auto& p : m.peaks)
      peaks.push_back({{"angle_deg", p.angle_deg},
                       {"plastic_rotation_rad", p.plastic_rotation_rad},
                       {"first_yield_s", p.first_yield_s}});
    maps.push_back({{"ring", ring + 1},
                    {"first_yield_s", m.first_yield_s},
                    {"first_yield_angle_deg", m.first_yield_angle_deg},
                    {"peaks", peaks}});
    if (m.first_yield_s >= 0)
      r.events.push_back({m.first_yield_s, "hinge_formed", static_cast<int>(ring),
                          fmt::format("first yield at {:.1f} deg from the top", m.first_yield_angle_deg)});
  }
  std::sort(r.events.begin(), r.events.end(),
            [](const RunEvent& a, const RunEvent& b) { return a.time_s < b.time_s; });

  r.statistics.steps = raw.steps;
  r.statistics.rejected_steps = raw.rejected_steps;
  r.statistics.newton_iterations = raw.nonlinear_iterations;
  r.statistics.wall_time_s = raw.wall_time_s;
  r.extra = {
      {"level", "2"},
      {"integrator", hinge_integrator_name(options.integrator)},
      {"relative_tolerance_used", run.relative_tolerance_used},
      {"nodes_per_ring", in.nodes_per_ring},
      {"symmetry", in.half_symmetry ? "half" : "full"},
      {"joints", to_string(scene.joints.type)},
      {"ties", scene.joints.type == JointType::Welded ? "penalty springs" : "none"},
      {"arrest_time_s", raw.arrest_time_s >= 0 ? nlohmann::json(raw.arrest_time_s) : nlohmann::json()},
      {"end_time_s", raw.end_time_s},
      {"wrapped_angle_measured_at_s", h.time_s[arrest_sample]},
      {"model_energy_balance_error", raw.energy_balance_error},
      {"numerical_damping_J", h.damping_j.back()},
      {"contact_damping_J", h.contact_damping_j.back()},
      {"residual_evaluations", raw.rhs_evaluations},
      {"jacobian_setups", raw.jacobian_setups},
      {"inverted_arc_m", r.inverted_arc_m},
      {"top_height_ratio", top_height},
      {"bottom_height_ratio", bottom_height},
      {"hinge_map", maps},
      {"level2_settings",
       {{"flow_D_per_s", s.flow_d_per_s},
        {"flow_q", s.flow_q},
        {"contact_stiffness_scale", s.contact_stiffness_scale},
        {"contact_damping_s_per_m", s.contact_damping_s_per_m},
        {"tie_stiffness_scale", s.tie_stiffness_scale},
        {"membrane_stiffness_scale", s.membrane_stiffness_scale},
        {"membrane_damping_ratio", s.membrane_damping_ratio},
        {"hinge_damping_ratio", s.hinge_damping_ratio},
        {"velocity_tolerance_factor", s.velocity_tolerance_factor},
        {"plastic_tolerance_factor", s.plastic_tolerance_factor},
        {"central_difference_safety", s.central_difference_safety},
        {"central_difference_implicit_dampers", s.central_difference_implicit_dampers},
        {"central_difference_energy_error_limit", s.central_difference_energy_error_limit},
        {"wrap_min_inverted_arc_fraction", s.wrap_min_inverted_arc_fraction}}}};
  if (options.integrator == HingeIntegrator::CentralDifference)
    r.extra["central_difference"] = {{"min_step_s", raw.min_step_s},
                                     {"max_step_s", raw.max_step_s},
                                     {"min_flow_relaxation_s", raw.min_flow_relaxation_s}};
  // Echoed only when on, so that the default run's summary keeps its bytes.
  if (options.integrator == HingeIntegrator::CentralDifference && s.central_difference_implicit_membrane) {
    r.extra["level2_settings"]["central_difference_implicit_membrane"] = true;
    r.extra["central_difference"]["membrane_correction_work_j"] = raw.membrane_correction_work_j;
  }
  if (s.hinge_damper_on_elastic_rate) {  // likewise: "total" (the default) is not echoed
    r.extra["level2_settings"]["hinge_damper"] = "elastic";
    if (options.integrator == HingeIntegrator::CentralDifference)
      r.extra["central_difference"]["hinge_damper_plastic_work_j"] = raw.hinge_damper_plastic_work_j;
  }
  if (run.relative_tolerance_used != options.relative_tolerance)
    r.extra["note"] = fmt::format("requested rtol {:g} is below Level 2's floor {:g}; ran at {:g}",
                                  options.relative_tolerance, s.min_relative_tolerance,
                                  run.relative_tolerance_used);
  return run;
}

RunResult run_hinge_level2(const Scene& scene, const HingeRunOptions& options) {
  return run_level2(scene, options, level2_settings(scene, options.integrator)).result;
}

}  // namespace ringcrush::compare
