#include "fe/deck/deck_summary.hpp"

#include <fmt/format.h>

namespace ringcrush::fe::deck {

namespace {
const char* procedure_name(Procedure p) {
  switch (p) {
    case Procedure::Static: return "*STATIC";
    case Procedure::Dynamic: return "*DYNAMIC";
    case Procedure::None: return "(none)";
  }
  return "?";
}

std::string opt(const std::optional<double>& v) { return v ? fmt::format("{:g}", *v) : "-"; }

void list_outputs(std::string& out, const std::vector<OutputRequest>& outputs, const char* indent) {
  for (const OutputRequest& o : outputs) {
    std::string vars;
    for (const auto& v : o.variables) vars += (vars.empty() ? "" : ",") + v;
    out += fmt::format("{}line {:>4}  *{:<13} {:<12} {} — {}\n", indent, o.line, o.keyword, vars,
                       o.mapped_to.empty() ? "ignored" : "mapped to " + o.mapped_to, o.reason);
  }
}
}  // namespace

std::string describe(const DeckModel& m) {
  std::string out;
  if (!m.heading.empty()) out += fmt::format("heading: {}\n", m.heading);
  std::map<ElementType, int> by_type;
  for (const auto& [label, e] : m.elements) ++by_type[e.type];
  out += fmt::format("nodes: {}\nelements: {}", m.nodes.size(), m.elements.size());
  std::string types;
  for (const auto& [t, n] : by_type) types += fmt::format("{}{} {}", types.empty() ? "" : ", ", n, to_string(t));
  out += fmt::format(" ({})\n", types);
  out += fmt::format("node sets ({}):", m.nsets.size());
  for (const auto& [name, s] : m.nsets) out += fmt::format(" {}[{}]", name, s.labels.size());
  out += fmt::format("\nelement sets ({}):", m.elsets.size());
  for (const auto& [name, s] : m.elsets) out += fmt::format(" {}[{}]", name, s.labels.size());
  out += "\n";
  for (const auto& [name, mat] : m.materials) {
    out += fmt::format("material {}: E = {} Pa, nu = {}, density = {}, plastic table {} points\n", name,
                       opt(mat.youngs_modulus), opt(mat.poisson_ratio), opt(mat.density), mat.plastic.size());
  }
  for (const SolidSection& s : m.sections)
    out += fmt::format("solid section: elset {}, material {}, thickness {:g} m\n", s.elset, s.material, s.thickness);
  for (const RigidSurface& r : m.rigid_surfaces)
    out += fmt::format("rigid surface {}: {} segments\n", r.elset, r.segments.size() - 1);
  for (const Interface& i : m.interfaces)
    out += fmt::format("interface {}: thickness {:g} m, friction {}, softened contact {}\n", i.elset, i.thickness,
                       opt(i.friction),
                       i.softened_clearance ? fmt::format("c0 = {:g} m, p0 = {:g} Pa", *i.softened_clearance,
                                                          *i.softened_pressure)
                                            : "no");
  for (const SlideLine& s : m.slide_lines)
    out += fmt::format("slide line {}: {} nodes, {}, smooth {:g}\n", s.elset, s.nodes.size(), s.type, s.smooth);
  out += fmt::format("MPCs: {}; boundary conditions: {} dof ranges; initial velocities: {}; point masses: {}\n",
                     m.mpcs.size(), m.boundaries.size(), m.initial_velocities.size(), m.masses.size());
  if (!m.outputs.empty()) {
    out += "model output requests:\n";
    list_outputs(out, m.outputs, "  ");
  }
  for (std::size_t k = 0; k < m.steps.size(); ++k) {
    const Step& s = m.steps[k];
    out += fmt::format("step {} (line {}): {}{}, INC {}, CYCLE {}\n", k + 1, s.line, procedure_name(s.procedure),
                       s.nlgeom ? ", NLGEOM" : "", s.max_increments ? std::to_string(*s.max_increments) : "-",
                       s.max_iterations ? std::to_string(*s.max_iterations) : "-");
    out += fmt::format("  increments: initial {}, period {}, min {}, max {}; PTOL {}, HAFTOL {}, ALPHA {}\n",
                       opt(s.initial_increment), opt(s.period), opt(s.min_increment), opt(s.max_increment),
                       opt(s.ptol), opt(s.haftol), opt(s.alpha));
    out += fmt::format("  boundary conditions in the step: {} dof ranges\n", s.boundaries.size());
    list_outputs(out, s.outputs, "  ");
  }
  return out;
}

std::string describe(const DeckParameters& p) {
  std::string out;
  out += fmt::format("rings: {} ({} model), centres", p.rings.size(), p.half_model ? "half" : "full");
  for (const DeckRing& r : p.rings) out += fmt::format(" ({:g}, {:g})", r.centre[0], r.centre[1]);
  out += fmt::format("\n  inner radius {:.9g} m, outer radius {:.9g} m, width {:g} m, pitch {:.9g} m\n",
                     p.inner_radius_m, p.outer_radius_m, p.width_m, p.pitch_m);
  out += fmt::format("  mesh: {} elements around × {} through per ring, grading {:.6g}\n", p.elements_around,
                     p.elements_through, p.grading);
  out += fmt::format("  joints: {} ({} ring-to-ring ties, {} ties inside a ring)\n", p.welded ? "welded" : "free",
                     p.ring_ties, p.internal_ties);
  out += fmt::format("material: E = {:g} Pa, nu = {:g}, density {}, hardening", p.youngs_modulus_pa, p.poisson_ratio,
                     opt(p.density_kg_m3));
  for (const auto& h : p.hardening) out += fmt::format(" ({:g} Pa, {:g})", h.yield_stress, h.plastic_strain);
  out += fmt::format("\ncontact: {} rigid surfaces, {} slide lines, smoothing {}, friction {:g}", p.rigid_surfaces,
                     p.slide_lines, opt(p.contact_smoothing), p.friction_coefficient);
  if (p.softened_clearance_m)
    out += fmt::format(", softened c0 = {:g} m p0 = {:g} Pa", *p.softened_clearance_m, *p.softened_pressure_pa);
  out += "\n";
  if (p.dynamic)
    out += fmt::format("analysis: dynamic to {:g} s, impactor {:g} kg (physical) at {:g} m/s, {} target\n", p.period,
                       *p.impactor_mass_kg, *p.impactor_velocity_m_s, p.fixed_target ? "fixed" : "no");
  else
    out += fmt::format("analysis: static crush {:g} m, {} target\n", p.crush_m, p.fixed_target ? "fixed" : "no");
  out += fmt::format("solver: PTOL {}, HAFTOL {}, alpha {}, initial increment {:g}, min {}, max {}\n", opt(p.ptol_n),
                     opt(p.haftol_n), opt(p.hht_alpha), p.initial_increment, opt(p.min_increment),
                     opt(p.max_increment));
  return out;
}

}  // namespace ringcrush::fe::deck
