#include "compare/cli/fe_dynamic_terminal.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>

#include "compare/measures.hpp"
#include "compare/run_output.hpp"

namespace ringcrush::compare::cli {
namespace {

const char* integration_name(fe::Integration i) {
  switch (i) {
    case fe::Integration::Full: return "full 3x3";
    case fe::Integration::Reduced: return "reduced 2x2";
    case fe::Integration::Selective: return "selective (3x3, volumetric at 2x2)";
  }
  return "?";
}

const char* joint_name(fe::JointKind j) {
  switch (j) {
    case fe::JointKind::Welded: return "welded (neighbours share their touching node)";
    case fe::JointKind::Free: return "free (contact only)";
    case fe::JointKind::Plates: return "plates (rigid plates between the rings)";
  }
  return "?";
}

}  // namespace

const char* scheme_name(fe::DynamicScheme s) { return s == fe::DynamicScheme::Hht ? "hht" : "explicit"; }

void echo_dynamic(const Scene& s, const fe::ChainInput& c, const fe::DynamicSolverInput& d) {
  const double share = c.mesh.half_ring ? 0.5 : 1.0;  // a half model carries half of every mass
  fmt::print("scene {}: {}\n", s.name, s.title);
  fmt::print("  chain: {} rings, D = {:.2f} mm, t = {:.2f} mm (t/D = {:.4f}), L = {:.2f} mm, pitch {:.2f} mm\n",
             c.rings, 2e3 * c.ring.outer_radius_m, 1e3 * (c.ring.outer_radius_m - c.ring.inner_radius_m),
             (c.ring.outer_radius_m - c.ring.inner_radius_m) / (2 * c.ring.outer_radius_m), 1e3 * c.ring.width_m,
             1e3 * c.pitch_m);
  fmt::print("  material: E = {:.0f} GPa, nu = {:.2f}, rho = {:.0f} kg/m3, {} hardening points\n",
             c.material.youngs_modulus_pa / 1e9, c.material.poisson_ratio, c.density_kg_m3,
             c.material.hardening.size());
  fmt::print("  joints: {}", joint_name(c.joints));
  if (c.joints == fe::JointKind::Plates)
    fmt::print("; plate {:.4f} kg (model {:.4f} kg), {:.2f} mm thick", c.plate_mass_kg, share * c.plate_mass_kg,
               1e3 * c.plate_thickness_m);
  fmt::print("; far end {}\n", c.fixed_target ? "on a fixed rigid target" : "free");
  fmt::print("  impactor: {:.4f} kg (model {:.4f} kg) at {:.2f} m/s, KE0 = {:.3f} J\n", c.impactor_mass_kg,
             share * c.impactor_mass_kg, c.impactor_velocity_m_s,
             0.5 * c.impactor_mass_kg * c.impactor_velocity_m_s * c.impactor_velocity_m_s);
  fmt::print("  mesh: {} rings, {} CPS8 around (per half) x {} through, grading {:g}; integration {}\n",
             c.mesh.half_ring ? "half" : "full", c.mesh.elements_around, c.mesh.elements_through, c.mesh.grading,
             integration_name(c.integration));
  fmt::print("  contact: penalty scale {:g}, smoothing {:g}, ring-ring, impactor, target, plates and inner walls\n",
             c.contact.penalty_scale, c.contact.smoothing);
  if (d.scheme == fe::DynamicScheme::Hht)
    fmt::print("  integrator: HHT-alpha, alpha = {:g}; half-step residual control (thesis 3.5): HAFTOL {:g} N, "
               "PTOL {:g} N, {} iterations; step initial {:.3g} s, bounds [{:.3g}, {:.3g}] s\n",
               d.alpha, d.haftol_n, d.ptol_n, d.max_iterations, d.initial_step_s, d.min_step_s, d.max_step_s);
  else
    fmt::print("  integrator: explicit central difference, lumped (HRZ) mass; dt = {:g} x 2/omega_max ({}), "
               "re-bounded every {} steps; linear bulk viscosity b1 = {:g}\n",
               d.safety,
               c.step_bound == fe::StepBound::Assembled ? "assembled power-iteration estimate"
                                                        : "element + contact bound",
               d.stable_step_every, c.bulk_viscosity);
  if (c.mass_scaling.active())
    fmt::print("  MASS SCALING (changes the physics): target step {:.4g} s (elements below it scaled up to it), "
               "uniform factor {:g}\n",
               c.mass_scaling.target_step_s, c.mass_scaling.factor);
  fmt::print("  end: at rest (KE < {:g} of KE0 and the impactor stopped){} or at {:g} ms; energy error limit {:g}; "
             "{} frames\n",
             d.rest_kinetic_fraction, d.stop_at_rest ? "" : " [disabled]", 1e3 * d.end_time_s,
             d.energy_error_limit, d.frames);
}

fe::DynamicCallbacks dynamic_terminal_callbacks(bool quiet) {
  fe::DynamicCallbacks cb;
  if (quiet) return cb;
  cb.log = [](const std::string& m) { fmt::print(stderr, "{}\n", m); };
  if (isatty(fileno(stderr)) == 0) return cb;
  // The drivers report every step; the terminal gets a line at most every 0.1 s.
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  cb.progress = [last](const fe::DynamicProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (now - *last < std::chrono::milliseconds(100)) return;
    *last = now;
    fmt::print(stderr, "\r  t {:8.4f} / {:.2f} ms  step {:8d}  dt {:.2e} s  impactor {:8.3f} m/s  KE {:5.1f} %  ",
               1e3 * p.time_s, 1e3 * p.end_time_s, p.step, p.step_s, p.impactor_velocity_m_s,
               100 * p.kinetic_fraction);
  };
  return cb;
}

void print_dynamic_result(const Scene& s, const fe::DynamicResult& r, const RunResult& run) {
  const auto& st = r.statistics;
  const auto& x = run.extra;
  if (isatty(fileno(stderr)) != 0) fmt::print(stderr, "\n");
  fmt::print("end: {} at t = {:.4f} ms; impactor {:.3f} m/s\n", r.end_reason, 1e3 * r.history.back().time_s,
             r.history.back().impactor_velocity_m_s);
  fmt::print("statistics: {} steps, {} rejected, {} Newton iterations, {} factorizations; wall {:.3f} s, "
             "{:.1f} ns per element-step, contact {:.0f} %\n",
             st.steps, st.rejected_steps, st.newton_iterations, st.factorizations, st.wall_time_s,
             1e9 * x.value("time_per_element_step_s", 0.0), 100 * x.value("contact_share", 0.0));
  fmt::print("step: {:.3g} .. {:.3g} s{}\n", st.min_step_s, st.max_step_s,
             st.step_limited_by.empty() ? "" : "; stable step limited by " + st.step_limited_by);
  fmt::print("energy: balance error {:.3f} % of KE0 ({:.3f} J), numerical dissipation {:.3f} %\n",
             100 * r.energy_balance_error, r.initial_kinetic_j, 100 * r.numerical_dissipation);
  if (r.mass_scaling.active) {
    const auto& ms = r.mass_scaling;
    const double impactor = s.impactor ? s.impactor->mass_kg : 0.0;
    fmt::print("mass scaling: {} of {} elements scaled (target {:.4g} s, factor {:g}; smallest element step {:.4g} -> "
               "{:.4g} s); added {:.4g} kg = {:.1f} % of the rings' {:.4g} kg = {:.2f} x the impactor's {:.4g} kg; "
               "{} steps below the target\n",
               ms.scaled_elements, ms.elements, ms.target_step_s, ms.factor, ms.min_element_step_s,
               ms.min_scaled_element_step_s, ms.added_mass_kg,
               ms.element_mass_kg > 0 ? 100 * ms.added_mass_kg / ms.element_mass_kg : 0.0, ms.element_mass_kg,
               impactor > 0 ? ms.added_mass_kg / impactor : 0.0, impactor, st.steps_below_mass_scaling_target);
  }
  fmt::print("{:>5} {:>8} {:>9} {:>11} {:>11} {:>12} {:>5} {:>10} {:>9}\n", "ring", "c=d/D", "crush_mm", "wrapped_deg",
             "inv_arc_mm", "inv_turn_deg", "wrap", "mode", "max_PEEQ");
  for (std::size_t i = 0; i < run.crush_ratio.size(); ++i)
    fmt::print("{:>5} {:>8.3f} {:>9.2f} {:>11.1f} {:>11.2f} {:>12.1f} {:>5} {:>10} {:>9.3f}\n", i + 1, run.crush_ratio[i],
               1e3 * run.crush_ratio[i] * s.rings.outer_diameter_m, run.wrapped_angle_deg[i], 1e3 * run.inverted_arc_m[i],
               run.inverted_turning_deg[i], run.wrap_around[i] ? "yes" : "no", run.mode[i],
               i < r.max_peeq_per_ring.size() ? r.max_peeq_per_ring[i] : 0.0);
  const auto alt = alternation(run.crush_ratio);
  fmt::print("alternation index {:.3f} (A1 {:.3f}, sign changes {:.2f}; threshold {:g}: {})\n", alt.index, alt.lag1,
             alt.sign_change_fraction, alternation_threshold,
             alt.index > alternation_threshold ? "alternates" : "does not alternate");
}

}  // namespace ringcrush::compare::cli
