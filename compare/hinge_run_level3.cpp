#include "compare/hinge_run_level3.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "compare/hinge_run_1d.hpp"
#include "compare/measures.hpp"
#include "compare/shape_output.hpp"

namespace ringcrush::compare {

hinge::Level3Input level3_input(const Scene& scene, const Level3RunOptions& extra) {
  if (scene.analysis.type != AnalysisType::Dynamic || !scene.impactor)
    throw std::invalid_argument(fmt::format("scene {}: hinge level 3 runs dynamic impact scenes only", scene.name));
  const auto law = ring_law(scene);
  hinge::Level3Input in;
  in.rings = scene.rings.count;
  in.ring.outer_diameter_m = law.outer_diameter_m;
  in.ring.wall_thickness_m = law.wall_thickness_m;
  in.ring.plastic_moment_nm = law.plastic_moment_nm;
  in.ring.hardening_k = law.hardening_k();
  in.plates = scene.joints.type == JointType::Plates;
  in.impactor_mass_kg = scene.impactor->mass_kg;
  in.impactor_velocity_m_s = scene.impactor->velocity_m_s;
  // F: fixed at a given θ_F (the run option, else the scene's [hinge] level3_theta_f_deg),
  // else placed by [hinge] level3_hinge_f (least onset load, or travelling shear-free).
  const double theta_f_deg = extra.theta_f_deg >= 0 ? extra.theta_f_deg : scene.hinge.level3_theta_f_deg;
  in.hinge_f = scene.hinge.level3_hinge_f == HingeSettings::Level3HingeF::ShearFree ? hinge::Level3HingeF::ShearFree
                                                                                    : hinge::Level3HingeF::LeastOnsetLoad;
  if (theta_f_deg >= 0) {
    in.theta_f = theta_f_deg * std::numbers::pi / 180.0;
    in.hinge_f = hinge::Level3HingeF::LeastOnsetLoad;  // a given θ_F overrides the placement
  }
  in.hinge_e = scene.hinge.level3_hinge_e == HingeSettings::Level3HingeE::ShearFree ? hinge::Level3HingeE::ShearFree
                                                                                    : hinge::Level3HingeE::Fixed;
  in.ring_under = scene.hinge.level3_ring_under == HingeSettings::Level3RingUnder::Bottom
                      ? hinge::Level3RingUnder::Bottom
                      : hinge::Level3RingUnder::LeastLoad;
  in.inertia = scene.hinge.level3_inertia;
  in.ring_mass_kg = law.mass_kg;
  return in;
}

namespace {

RingShape to_ring_shape(const hinge::Level3Shape& s, double wall) {
  RingShape r;
  for (const auto& p : s.points) r.points.emplace_back(p[0], p[1]);
  r.material_angle = s.theta;
  r.half = true;
  r.surface_offset = wall;
  return r;
}

// Half-ring mean lines of the chain in one state, stacked from ring 1's top at top_y: each
// next ring's top a wall thickness below the previous ring's bottom (mean lines t apart
// where the rings touch; Level 3 has no plate thickness).
std::vector<hinge::Level3Shape> chain_shapes(const hinge::Level3Ring& ring, const hinge::WrapMechanism& wrap,
                                             const std::vector<hinge::Level3RingResult>& states, double top_y) {
  std::vector<hinge::Level3Shape> shapes;
  double top = top_y;
  for (const auto& rr : states) {
    shapes.push_back(hinge::level3_ring_shape(ring, wrap, rr, top));
    top = shapes.back().bottom_y - ring.wall_thickness_m;
  }
  return shapes;
}

// The full mean line (mirrored about x = 0), open: the writers close it.
std::vector<std::array<double, 2>> full_mean_line(const hinge::Level3Shape& s) {
  std::vector<std::array<double, 2>> p = s.points;
  for (std::size_t k = s.points.size() - 1; k-- > 1;) p.push_back({-s.points[k][0], s.points[k][1]});
  return p;
}

// θ_F at the end of the run: of the first ring that wrapped (travelling F moves on), else
// the onset value.
double theta_f_final(const hinge::Level3Result& res) {
  for (const auto& rr : res.rings)
    if (rr.wrap_started) return rr.wrap_theta_f;
  return res.theta_f;
}

}  // namespace

RunResult run_hinge_level3(const Scene& scene, const HingeRunOptions& o, const Level3RunOptions& extra) {
  const auto start = std::chrono::steady_clock::now();
  const auto in = level3_input(scene, extra);
  const auto opts = hybrid_options(scene, o);
  const auto res = hinge::simulate_level3(in, opts, extra.record_history);
  const auto& h = res.history;

  RunResult r;
  r.model = "hinge";
  r.scene = scene.name;
  r.analysis = AnalysisType::Dynamic;
  r.time_s = h.time_s;
  r.impactor_displacement_m = h.impactor_displacement_m;
  r.impactor_velocity_m_s = h.impactor_velocity_m_s;
  r.impactor_force_n = h.force_n;
  r.ring_crush_m = h.ring_crush_m;
  r.kinetic_j = h.kinetic_j;
  r.plastic_j = h.plastic_j;
  const std::size_t n = h.time_s.size();
  r.elastic_j.assign(n, 0.0);
  r.contact_j.assign(n, 0.0);
  if (n > 0) r.contact_j.back() = res.lock_loss_j;  // kinetic energy lost if the chain locks
  // With ring inertia: the kinetic energy lost in plastic impacts (first contact, locks).
  for (std::size_t k = 0; k < n && k < h.impact_loss_j.size(); ++k) r.contact_j[k] += h.impact_loss_j[k];
  r.numerical_j.assign(n, 0.0);
  r.external_work_j.assign(n, 0.0);

  // Shapes stacked along the chain, mean lines t apart at each contact; measures. Chain
  // frame as Level 2 and the FE: ring 1 centred at y = 0 before the impact, the target fixed,
  // so ring 1's top is at R − (impactor travel) (the massless chain: travel = Σ crush).
  const auto& ring = in.ring;
  const auto& wrap = res.wrap;
  const double final_travel = h.impactor_displacement_m.empty() ? 0.0 : h.impactor_displacement_m.back();
  const auto final_shapes = chain_shapes(ring, wrap, res.rings, ring.mean_radius() - final_travel);
  std::vector<RingShape> shapes;
  for (const auto& s : final_shapes) {
    shapes.push_back(to_ring_shape(s, ring.wall_thickness_m));
    r.ring_outline_m.push_back(full_mean_line(s));
    r.ring_outline_m.back().push_back(r.ring_outline_m.back().front());
  }
  r.outline_half = false;
  const double t = ring.wall_thickness_m;
  for (std::size_t i : frame_samples(h.ring_state.size(), scene.outputs.fields ? scene.outputs.frames : 0)) {
    const auto at = chain_shapes(ring, wrap, h.ring_state[i], ring.mean_radius() - h.impactor_displacement_m[i]);
    ShapeFrame f;
    f.time_s = h.time_s[i];
    for (const auto& s : at) f.rings.push_back(full_mean_line(s));
    f.body_faces = {ring.mean_radius() - h.impactor_displacement_m[i] + 0.5 * t, at.back().bottom_y - 0.5 * t};
    r.shape_frames.push_back(std::move(f));
  }
  nlohmann::json hinge_map = nlohmann::json::array();
  nlohmann::json mech = nlohmann::json::array();
  nlohmann::json moment_ratio = nlohmann::json::array();
  for (std::size_t i = 0; i < res.rings.size(); ++i) {
    const auto& rr = res.rings[i];
    const auto m = measure_wrap(shapes[i], i + 1 < shapes.size() ? &shapes[i + 1] : nullptr, ring.mean_radius(),
                                ring.wall_thickness_m);
    r.crush_ratio.push_back(rr.crush_m / ring.outer_diameter_m);
    r.wrap_around.push_back(m.wrap_around);
    r.wrapped_angle_deg.push_back(m.wrapped_angle_deg);
    r.inverted_arc_m.push_back(m.inverted_arc_m);
    r.inverted_turning_deg.push_back(m.inverted_turning_deg);
    r.mode.push_back(rr.crush_m < 0.02 * ring.outer_diameter_m ? "intact" : hinge::to_string(rr.mode));
    nlohmann::json hs = nlohmann::json::array();
    for (const auto& hg : rr.hinges)
      hs.push_back({{"hinge", hg.name}, {"angle_deg", hg.angle_deg},
                    {"first_yield_s", hg.first_yield_s >= 0 ? nlohmann::json(hg.first_yield_s) : nlohmann::json()},
                    {"rotation_rad", hg.rotation_rad}});
    hinge_map.push_back({{"ring", i + 1}, {"hinges", hs}});
    mech.push_back({{"ring", i + 1}, {"mechanism", hinge::to_string(rr.mode)}, {"wrap_selected", rr.wrap_started},
                    {"under_wrap", rr.reinforced}, {"uniform_crush_m", rr.uniform_crush_m},
                    {"wrap_crush_m", rr.wrap_crush_m}, {"bottom_crush_m", rr.bottom_crush_m},
                    {"ecb_crush_m", rr.ecb_crush_m},
                    {"plastic_work_J", rr.plastic_work_j},
                    // statics check (hinge/level3_statics.hpp): > 1 means another hinge needed
                    {"moment_ratio_max", rr.peak_moment_ratio},
                    {"moment_ratio_max_angles_deg", rr.peak_moment_angles_deg},
                    {"moment_ratio_max_time_s", rr.peak_moment_time_s}});
    if (rr.reinforced && rr.e_onset_load_n > 0.0) {  // E reported in bottom states (hinge/level3_travelling_e.hpp)
      mech.back()["held_cap_deg"] = rr.held_cap * 180.0 / std::numbers::pi;
      mech.back()["theta_E_deg"] = rr.theta_e * 180.0 / std::numbers::pi;
      mech.back()["E_mechanism_load_N"] = rr.e_mechanism_load_n;
      mech.back()["bottom_load_N"] = rr.bottom_load_n;
      mech.back()["onset"] = {{"held_cap_deg", rr.held_cap_onset * 180.0 / std::numbers::pi},
                              {"theta_E_deg", rr.theta_e_onset * 180.0 / std::numbers::pi},
                              {"E_mechanism_load_N", rr.e_onset_load_n},
                              {"bottom_load_N", rr.bottom_onset_load_n}};
      mech.back()["E_cheaper_states"] = rr.e_cheaper_states;
      mech.back()["E_cheaper_from_s"] = rr.e_cheaper_time_s >= 0 ? nlohmann::json(rr.e_cheaper_time_s) : nlohmann::json();
    }
    if (rr.ecb_started) {  // the E–C–B the chain switched into (hinge/level3_ecb.hpp)
      mech.back()["ecb"] = {{"theta_E_deg", rr.ecb_theta_e * 180.0 / std::numbers::pi},
                              {"psi_at_switch_deg", rr.ecb_psi * 180.0 / std::numbers::pi},
                              {"rotation_E_rad", rr.ecb_rotation_e},
                              {"rotation_CB_rad", rr.ecb_rotation_cb}};
    }
    moment_ratio.push_back(rr.peak_moment_ratio);
  }
  for (const auto& e : res.events) r.events.push_back({e.time_s, e.kind, e.ring, e.detail});
  r.statistics.steps = res.outcome.statistics.steps;
  r.statistics.rejected_steps = res.outcome.statistics.rejected_steps;
  r.statistics.newton_iterations = res.outcome.statistics.nonlinear_iterations;
  r.statistics.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto alt = alternation(r.crush_ratio);
  const double arrest = [&] {
    for (const auto& e : res.events) if (e.kind == "impactor_arrested") return e.time_s;
    return -1.0;
  }();
  r.extra = {{"level", "3"},
             {"integrator", hinge_integrator_name(o.integrator)},
             {"relative_tolerance", o.relative_tolerance},
             {"absolute_tolerance", o.absolute_tolerance},
             {"theta_F_deg", res.theta_f * 180.0 / std::numbers::pi},
             {"hinge_F", in.theta_f >= 0 ? "fixed" : hinge::to_string(in.hinge_f)},
             {"theta_F_final_deg", theta_f_final(res) * 180.0 / std::numbers::pi},
             {"hinge_E", hinge::to_string(in.hinge_e)},
             {"ring_inertia", in.inertia},
             {"impact_loss_J", res.impact_loss_j},
             {"ring_under", hinge::to_string(in.ring_under)},
             {"moment_ratio_max", moment_ratio},
             {"collapse_load_N", ring.collapse_load()},
             {"wrap_onset_load_N", wrap.load.front()},
             {"wrap_min_load_N", *std::min_element(wrap.load.begin(), wrap.load.end())},
             {"alternation_index", alt.index},
             {"alternation_lag1", alt.lag1},
             {"energy_balance_error", res.energy_balance_error()},
             {"arrest_time_s", arrest >= 0 ? nlohmann::json(arrest) : nlohmann::json()},
             {"mechanisms", mech},
             {"hinge_map", hinge_map},
             {"note", in.inertia ? "rigid-plastic chain with ring inertia (a force per ring); mode = least-load admissible "
                                   "mechanism per ring"
                                 : "massless rigid-plastic chain (ring inertia neglected); mode = least-load admissible mechanism"}};
  if (in.inertia) {  // the largest force each ring carried (against the wrap onset load)
    nlohmann::json peaks = nlohmann::json::array();
    for (const auto& f : h.ring_force_n) peaks.push_back(f.empty() ? 0.0 : *std::max_element(f.begin(), f.end()));
    r.extra["ring_force_peak_N"] = peaks;
  }
  return r;
}

}  // namespace ringcrush::compare
