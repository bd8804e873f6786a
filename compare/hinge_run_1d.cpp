#include "compare/hinge_run_1d.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "compare/measures.hpp"
#include "hinge/ring_laws.hpp"

namespace ringcrush::compare {
namespace {

hinge::SectionState section_state(SectionState s) {
  return s == SectionState::PlaneStrain ? hinge::SectionState::PlaneStrain
                                        : hinge::SectionState::PlaneStress;
}

void require_dynamic(const Scene& s, const char* level) {
  if (s.analysis.type != AnalysisType::Dynamic || !s.impactor)
    throw std::invalid_argument(fmt::format(
        "scene {}: hinge level {} runs dynamic impact scenes only (for the static load of one "
        "ring use `ringcrush formula`)", s.name, level));
}

const char* integrator_name(HingeIntegrator i) { return hinge_integrator_name(i); }

std::string final_mode(double crush, const hinge::RingLaw& law) {
  if (crush >= 0.999 * law.lock_deflection()) return "locked";
  if (crush < 0.02 * law.outer_diameter_m) return "intact";
  return "flattened";
}

void fill_final_state(RunResult& r, const std::vector<double>& final_crush, const hinge::RingLaw& law) {
  for (double c : final_crush) {
    r.crush_ratio.push_back(c / law.outer_diameter_m);
    r.wrap_around.push_back(false);  // 1-D levels cannot wrap (THEORY §4.2)
    r.wrapped_angle_deg.push_back(0.0);
    r.inverted_arc_m.push_back(0.0);
    r.inverted_turning_deg.push_back(0.0);
    r.mode.push_back(final_mode(c, law));
  }
}

RunResult from_chain(const Scene& scene, const HingeRunOptions& o, const hinge::ChainResult& c,
                     const hinge::RingLaw& law, double wall) {
  RunResult r;
  r.model = "hinge";
  r.scene = scene.name;
  r.analysis = AnalysisType::Dynamic;
  const auto& h = c.history;
  r.time_s = h.time_s;
  r.impactor_displacement_m = h.impactor_displacement_m;
  r.impactor_velocity_m_s = h.impactor_velocity_m_s;
  r.impactor_force_n = h.impactor_force_n;
  r.ring_crush_m = h.ring_crush_m;
  r.kinetic_j = h.kinetic_j;
  r.elastic_j = h.elastic_j;
  r.plastic_j = h.plastic_j;
  r.contact_j = h.impact_loss_j;  // plastic impacts (first contact, lock-up)
  r.numerical_j.assign(h.time_s.size(), 0.0);
  r.external_work_j.assign(h.time_s.size(), 0.0);
  // Final crush: the permanent (plastic) crush, i.e. after elastic springback.
  fill_final_state(r, c.final_permanent_crush_m, law);
  for (const auto& e : c.events) r.events.push_back({e.time_s, e.kind, e.ring, e.detail});
  const auto& st = c.outcome.statistics;
  r.statistics.steps = st.steps;
  r.statistics.rejected_steps = st.rejected_steps;
  r.statistics.newton_iterations = st.nonlinear_iterations;
  r.statistics.wall_time_s = wall;
  std::vector<double> ring_plastic;
  for (const auto& w : h.ring_plastic_j) ring_plastic.push_back(w.back());
  r.extra = {{"level", o.level},
             {"integrator", integrator_name(o.integrator)},
             {"relative_tolerance", o.relative_tolerance},
             {"absolute_tolerance", o.absolute_tolerance},
             {"arrest_time_s", c.arrest_time_s >= 0.0 ? nlohmann::json(c.arrest_time_s) : nlohmann::json()},
             {"end_time_s", c.outcome.end_time},
             {"stopped_at_rest", c.outcome.stopped_by_model},
             {"events_located", st.events},
             {"restarts", st.restarts},
             {"function_evaluations", st.function_evaluations},
             {"jacobian_evaluations", st.jacobian_evaluations},
             {"plastic_energy_per_ring_J", ring_plastic},
             {"crush_ratio_basis", "permanent crush (elastic springback removed)"},
             {"final_total_crush_m", c.final_crush_m},
             {"impact_loss_J", h.impact_loss_j.back()},
             {"ring_collapse_load_N", law.collapse_load()},
             {"ring_mean_force_to_lock_N", law.mean_force_to_lock()},
             {"ring_lock_deflection_m", law.lock_deflection()},
             {"ring_mass_kg", law.mass_kg}};
  return r;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The shock model's prediction for the same scene, reported next to a chain result.
nlohmann::json shock_reference(const Scene& scene, const hinge::RingLaw& law) {
  const auto& imp = *scene.impactor;
  const auto far = scene.far_end == FarEnd::Free ? hinge::ChainFarEnd::Free : hinge::ChainFarEnd::Fixed;
  const auto in = hinge::ShockInput::from_ring(law, scene.rings.count, imp.mass_kg, imp.velocity_m_s, far);
  nlohmann::json j = {{"plateau_force_N", in.plateau_force_n},
                      {"locking_strain", in.locking_strain},
                      {"mass_per_length_kg_m", in.mass_per_length_kg_m}};
  if (far == hinge::ChainFarEnd::Fixed) {
    const auto c = hinge::shock_closed_form(in);
    std::vector<double> crush;
    for (int i = 0; i < scene.rings.count; ++i)
      crush.push_back(in.locking_strain * std::clamp(c.arrest_position_m - i * in.pitch_m, 0.0, in.pitch_m) /
                      law.outer_diameter_m);
    j["closed_form"] = {{"locked_rings", c.locked_rings},
                        {"arrest_time_s", c.arrest_time_s},
                        {"initial_load_N", c.initial_load_n},
                        {"characteristic_velocity_m_s", c.characteristic_velocity_m_s},
                        {"reaches_far_end", c.reaches_far_end},
                        {"crush_ratio", crush}};
    const auto d = hinge::discrete_shock(scene.rings.count, in.plateau_force_n, law.lock_deflection(),
                                         law.mass_kg, imp.mass_kg + 0.5 * law.mass_kg, imp.velocity_m_s);
    std::vector<double> dc;
    for (double x : d.crush_m) dc.push_back(x / law.outer_diameter_m);
    j["discrete_sequential"] = {{"crush_ratio", dc}, {"arrest_time_s", d.arrest_time_s},
                                {"initial_moving_mass_kg", imp.mass_kg + 0.5 * law.mass_kg}};
  }
  return j;
}

}  // namespace

hinge::RingLaw ring_law(const Scene& scene) {
  const auto& rg = scene.rings;
  const hinge::RingSection section{rg.outer_diameter_m, rg.wall_thickness_m, rg.width_m};
  const auto state = section_state(rg.section);
  hinge::RingLaw law;
  law.outer_diameter_m = rg.outer_diameter_m;
  law.wall_thickness_m = rg.wall_thickness_m;
  law.yield_stress_pa = rg.material.initial_yield_stress();
  law.plastic_moment_nm = hinge::plastic_moment(section, law.yield_stress_pa, state);
  law.hardening_modulus_pa = std::max(rg.material.hardening_modulus(), 0.0);
  law.redwood_alpha = scene.hinge.redwood_alpha;
  law.elastic_stiffness_n_m = hinge::elastic_stiffness(section, rg.material.youngs_modulus_pa,
                                                       rg.material.poisson_ratio, state);
  law.lock_stiffness_n_m = level0_lock_stiffness_scale * law.elastic_stiffness_n_m;
  law.mass_kg = hinge::ring_mass(section, rg.material.density_kg_m3);
  return law;
}

hinge::ChainInput chain_input(const Scene& scene) {
  hinge::ChainInput in;
  in.rings = scene.rings.count;
  in.ring = ring_law(scene);
  in.joint = scene.joints.type == JointType::Welded ? hinge::ChainJoint::Welded
             : scene.joints.type == JointType::Free ? hinge::ChainJoint::Free
                                                    : hinge::ChainJoint::Plates;
  in.plate_mass_kg = scene.joints.type == JointType::Plates ? scene.joints.plate_mass_kg : 0.0;
  in.far_end = scene.far_end == FarEnd::Free ? hinge::ChainFarEnd::Free : hinge::ChainFarEnd::Fixed;
  if (scene.impactor) {
    in.impactor_mass_kg = scene.impactor->mass_kg;
    in.impactor_velocity_m_s = scene.impactor->velocity_m_s;
  }
  return in;
}

hinge::HybridOptions hybrid_options(const Scene& scene, const HingeRunOptions& o) {
  hinge::HybridOptions h;
  if (o.integrator == HingeIntegrator::CentralDifference)
    throw std::invalid_argument(fmt::format(
        "scene {}: hinge level {}: the integrator \"central_difference\" is for level 2 only; use ida or odeint",
        scene.name, o.level));
  h.integrator = o.integrator == HingeIntegrator::Ida ? hinge::HybridIntegrator::Ida
                                                      : hinge::HybridIntegrator::Odeint;
  h.relative_tolerance = o.relative_tolerance;
  h.absolute_tolerance = o.absolute_tolerance;
  h.end_time = scene.analysis.end_time_s > 0 ? scene.analysis.end_time_s : 0.05;
  h.stop_when_finished = scene.analysis.stop_at_rest;
  return h;
}

RunResult run_hinge_level0(const Scene& scene, const HingeRunOptions& o) {
  require_dynamic(scene, "0");
  const auto start = std::chrono::steady_clock::now();
  const auto in = chain_input(scene);
  const auto c = hinge::simulate_level0(in, hybrid_options(scene, o));
  auto r = from_chain(scene, o, c, in.ring, seconds_since(start));
  r.extra["joints"] = to_string(scene.joints.type);
  r.extra["shock_model"] = shock_reference(scene, in.ring);
  return r;
}

RunResult run_hinge_level1(const Scene& scene, const HingeRunOptions& o) {
  require_dynamic(scene, "1");
  const auto start = std::chrono::steady_clock::now();
  auto in = chain_input(scene);
  const auto c = hinge::simulate_level1(in, hybrid_options(scene, o));
  auto r = from_chain(scene, o, c, in.ring, seconds_since(start));
  // Level 1 is a plated-chain model: welded and free joints are run as flat contacts
  // without plate mass (DeRuntz–Hodge kinematics need flat loading faces).
  r.extra["joints"] = to_string(scene.joints.type);
  if (scene.joints.type != JointType::Plates)
    r.extra["note"] = "Level 1 treats every joint as a massless flat contact (plated-chain kinematics)";
  r.extra["shock_model"] = shock_reference(scene, in.ring);
  return r;
}

RunResult run_hinge_shock(const Scene& scene, const HingeRunOptions& o) {
  require_dynamic(scene, "shock");
  const auto start = std::chrono::steady_clock::now();
  const auto law = ring_law(scene);
  const auto& imp = *scene.impactor;
  const auto far = scene.far_end == FarEnd::Free ? hinge::ChainFarEnd::Free : hinge::ChainFarEnd::Fixed;
  const auto in = hinge::ShockInput::from_ring(law, scene.rings.count, imp.mass_kg, imp.velocity_m_s, far);
  const auto s = hinge::integrate_shock(in, hybrid_options(scene, o));
  RunResult r;
  r.model = "hinge";
  r.scene = scene.name;
  r.analysis = AnalysisType::Dynamic;
  r.time_s = s.time_s;
  r.impactor_displacement_m = s.impactor_displacement_m;
  r.impactor_velocity_m_s = s.velocity_m_s;
  r.impactor_force_n = s.impactor_force_n;
  r.ring_crush_m.assign(scene.rings.count, {});
  for (std::size_t k = 0; k < s.time_s.size(); ++k)
    for (int i = 0; i < scene.rings.count; ++i)
      r.ring_crush_m[i].push_back(in.locking_strain *
                                  std::clamp(s.front_position_m[k] - i * in.pitch_m, 0.0, in.pitch_m));
  r.kinetic_j = s.kinetic_j;
  r.elastic_j.assign(s.time_s.size(), 0.0);
  r.plastic_j = s.plastic_j;
  r.contact_j = s.shock_loss_j;  // the shock (compaction-front) loss
  r.numerical_j.assign(s.time_s.size(), 0.0);
  r.external_work_j.assign(s.time_s.size(), 0.0);
  fill_final_state(r, s.final_crush_m, law);
  if (s.arrest_time_s >= 0) r.events.push_back({s.arrest_time_s, "impactor_arrested", -1, "v = v_f"});
  if (s.front_reached_far_end)
    r.events.push_back({s.time_s.back(), "front_at_far_end", -1, "every ring locked"});
  r.statistics.steps = s.outcome.statistics.steps;
  r.statistics.rejected_steps = s.outcome.statistics.rejected_steps;
  r.statistics.newton_iterations = s.outcome.statistics.nonlinear_iterations;
  r.statistics.wall_time_s = seconds_since(start);
  r.extra = {{"level", "shock"},
             {"integrator", integrator_name(o.integrator)},
             {"relative_tolerance", o.relative_tolerance},
             {"absolute_tolerance", o.absolute_tolerance},
             {"arrest_time_s", s.arrest_time_s >= 0 ? nlohmann::json(s.arrest_time_s) : nlohmann::json()},
             {"front_position_m", s.front_position_m.back()},
             {"locked_rings", s.front_position_m.back() / in.pitch_m},
             {"front_reached_far_end", s.front_reached_far_end},
             {"far_end_loss_J", s.far_end_loss_j},
             {"shock_model", shock_reference(scene, law)}};
  return r;
}

}  // namespace ringcrush::compare
