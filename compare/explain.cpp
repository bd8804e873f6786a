#include "compare/explain.hpp"

#include <fmt/format.h>

#include "compare/fe_dynamic.hpp"
#include "compare/fe_static.hpp"
#include "compare/through_wall_section.hpp"

namespace ringcrush::compare {
namespace {

std::string rule_name(Integration i) {
  switch (i) {
    case Integration::Full: return "3x3 Gauss";
    case Integration::Reduced: return "2x2 Gauss";
    case Integration::Selective: return "selective (3x3, volumetric at 2x2)";
  }
  return "?";
}

void outputs(const Scene& s, int frames, std::vector<std::string>& e) {
  if (frames > 0)
    e.push_back(fmt::format("field frames: {} snapshots of displacement, Mises, PEEQ and contact pressure, "
                            "computed only at the snapshot times (outputs.fields = true, outputs.frames = {})",
                            frames, s.outputs.frames));
  else
    e.push_back("no field frames: stresses, PEEQ fields and contact pressures are never gathered "
                "(outputs.fields = false or outputs.frames = 0)");
  e.push_back(s.outputs.history ? "history.csv: one row per output step (outputs.history = true)"
                                : "no history.csv (outputs.history = false); summary.json is always written");
  e.push_back(s.outputs.plots ? "SVG plots (outputs.plots = true)" : "no SVG plots (outputs.plots = false)");
}

}  // namespace

std::vector<std::string> explain_fe(const Scene& s) {
  std::vector<std::string> e;
  const bool half = s.analysis.symmetry == Symmetry::Half;
  if (s.analysis.type == AnalysisType::Static) {
    const fe::FeInput in = fe_static_input(s);
    e.push_back(fmt::format("static crush of one ring to {:.2f} mm between rigid plates (analysis.type = \"static\")",
                            1e3 * in.solver.crush_m));
    e.push_back(fmt::format("{} model: {} CPS8 around x {} through, {} (analysis.symmetry = \"{}\")",
                            half ? "half-ring" : "full-ring", (half ? 1 : 2) * in.mesh.elements_around,
                            in.mesh.elements_through, rule_name(s.fe.integration), half ? "half" : "full"));
    e.push_back(through_wall_section_line(s));
    e.push_back("no mass matrix and no inertia: a static run assembles none");
    e.push_back("tangent stiffness and a sparse LDLT factorisation every Newton iteration; the pattern is analysed "
                "once and only again when contact couples new nodes");
    e.push_back("contact: both plates, and the inner wall against itself (lock-up)");
    outputs(s, in.solver.frames, e);
    return e;
  }
  const fe::ChainInput chain = fe_chain_input(s);
  const fe::DynamicSolverInput solver = fe_dynamic_solver_input(s);
  e.push_back(fmt::format("dynamic impact of {} rings by a {:.3f} kg impactor at {:.1f} m/s, until {} or {:.1f} ms",
                          chain.rings, chain.impactor_mass_kg, chain.impactor_velocity_m_s,
                          solver.stop_at_rest ? "the impactor stops and the rings are at rest" : "the end time",
                          1e3 * solver.end_time_s));
  e.push_back(fmt::format("{} model: {} CPS8 per ring ({} around x {} through), {} (analysis.symmetry = \"{}\")",
                          half ? "half-ring" : "full-ring",
                          (half ? 1 : 2) * chain.mesh.elements_around * chain.mesh.elements_through,
                          (half ? 1 : 2) * chain.mesh.elements_around, chain.mesh.elements_through,
                          rule_name(s.fe.integration), half ? "half" : "full"));
  e.push_back(through_wall_section_line(s));
  if (solver.scheme == fe::DynamicScheme::Explicit)
    e.push_back(fmt::format("explicit central difference: HRZ lumped mass, no tangent and no factorisation; the step "
                            "is {:g} x {} (fe.solver = \"explicit\", fe.step_bound = \"{}\")",
                            solver.safety,
                            chain.step_bound == fe::StepBound::Assembled
                                ? "the assembled power-iteration estimate of omega_max"
                                : "the element/contact stability bound",
                            chain.step_bound == fe::StepBound::Assembled ? "assembled" : "element"));
  if (chain.contact_penalty_step_fraction > 0)
    e.push_back(fmt::format("contact penalty lowered (fe.contact_penalty_step_fraction = {:g}): every contact spring "
                            "x one factor, so that the stiffest costs at most {:g} % of the element step; the scale "
                            "used and the deepest penetration are in summary.json (contact_penalty)",
                            chain.contact_penalty_step_fraction, 100 * chain.contact_penalty_step_fraction));
  if (solver.scheme == fe::DynamicScheme::Explicit && chain.mass_scaling.active())
    e.push_back(fmt::format("MASS SCALING, a change of the physics (fe.mass_scaling_dt = {:g} s, fe.mass_scaling_factor "
                            "= {:g}): every element's density x the factor, then every element whose own step "
                            "(safety included) is below the target x (target/step)^2; the added mass, the elements "
                            "scaled and the steps still below the target are reported",
                            chain.mass_scaling.target_step_s, chain.mass_scaling.factor));
  else
    e.push_back(fmt::format("implicit HHT-alpha (alpha = {:g}): lumped mass, tangent and sparse LDLT per Newton "
                            "iteration, half-step residual control with HAFTOL {:g} N (fe.solver = \"hht\")",
                            solver.alpha, solver.haftol_n));
  std::string joints;
  switch (chain.joints) {
    case fe::JointKind::Welded: joints = "welded: neighbours share their touching node (no contact needed there)"; break;
    case fe::JointKind::Free: joints = "free: neighbours touch through contact only"; break;
    case fe::JointKind::Plates:
      joints = fmt::format("plates: {} rigid plates of {:.3f} kg between the rings", chain.rings - 1, chain.plate_mass_kg);
      break;
  }
  e.push_back("joints " + joints + " (joints.type)");
  e.push_back(fmt::format("contact: impactor face, {}ring against ring where the broad phase finds candidates, every "
                          "ring's inner wall against itself",
                          chain.fixed_target ? "target plane, " : "no target (far_end = \"free\"), "));
  e.push_back(fmt::format("energy balance checked every step; a run stops when its error exceeds {:g} of the "
                          "initial kinetic energy (fe.energy_error_limit)",
                          solver.energy_error_limit));
  outputs(s, solver.frames, e);
  e.push_back("the hinge model is not built (ringcrush fe runs the FE only)");
  return e;
}

std::vector<std::string> explain_hinge(const Scene& s) {
  std::vector<std::string> e;
  e.push_back(fmt::format("hinge model level {} on {} (hinge.level, hinge.integrator), rtol {:g}", s.hinge.level,
                          s.hinge.integrator == HingeIntegrator::Ida      ? "SUNDIALS IDA"
                          : s.hinge.integrator == HingeIntegrator::Odeint ? "Boost.Odeint"
                                                                          : "explicit central difference",
                          s.hinge.relative_tolerance));
  if (s.hinge.level == "2")
    e.push_back(fmt::format("Level 2: {} bars per ring; ring shapes kept at output steps for the measures",
                            s.hinge.nodes_per_ring));
  else if (s.hinge.level == "3")
    e.push_back(s.hinge.level3_theta_f_deg >= 0
                    ? fmt::format("Level 3: wrap hinge F fixed at {:g}° (hinge.level3_theta_f_deg)", s.hinge.level3_theta_f_deg)
                    : s.hinge.level3_hinge_f == HingeSettings::Level3HingeF::ShearFree
                          ? std::string("Level 3: wrap hinge F placed by the shear-free condition at every step (hinge.level3_hinge_f)")
                          : std::string("Level 3: wrap hinge F fixed where the wrap starts at least load (hinge.level3_hinge_f)"));
  else if (s.hinge.level == "0" || s.hinge.level == "1" || s.hinge.level == "shock")
    e.push_back("no ring shapes: this level has a few degrees of freedom per ring, so the wrap flag comes from "
                "the crush alone (never set)");
  if (s.hinge.level == "3")
    e.push_back(s.hinge.level3_hinge_e == HingeSettings::Level3HingeE::ShearFree
                    ? std::string("Level 3: hinge E of a ring under a wrap at the least-load (shear-free) place beyond the held cap when the ring is reinforced, "
                                  "the E of its E-C-B; statics check |M| <= M0 per ring (hinge.level3_hinge_e)")
                    : std::string("Level 3: hinge E of a ring under a wrap fixed at 45° (the E of its E-C-B); statics check |M| <= M0 per "
                                  "ring (hinge.level3_hinge_e)"));
  if (s.hinge.level == "3")
    e.push_back(s.hinge.level3_ring_under == HingeSettings::Level3RingUnder::Bottom
                    ? std::string("Level 3: a ring under a wrap flows in the bottom mechanism only (hinge.level3_ring_under)")
                    : std::string("Level 3: a ring under a wrap flows in the least-load of bottom and E-C-B, E fixed where "
                                  "it forms (hinge.level3_ring_under)"));
  if (s.hinge.level == "3")
    e.push_back(s.hinge.level3_inertia
                    ? std::string("Level 3: rings with mass (centre mass, J(phi) in the uniform mode), a force per ring from the "
                                  "dynamics; no statics check (hinge.level3_inertia)")
                    : std::string("Level 3: massless chain, one force through every ring (hinge.level3_inertia)"));
  e.push_back("the FE model is not built by the hinge run");
  return e;
}

}  // namespace ringcrush::compare
