// The dynamic half of compare/calculix_export.hpp: a ring chain under impact (issue 4, thesis
// §3.5, §4.2) as a CalculiX *DYNAMIC deck on the mesh of fe/chain/chain_mesh.
//
// ringcrush's rigid bodies are single nodes with analytic contact planes (impactor, joint
// plates, target); ccx needs meshed master surfaces, so each becomes a strip of CPS8 elements:
// the impactor and the joint plates as *RIGID BODY strips whose reference node carries the
// body's mass (*MASS) and, for the impactor, the impact velocity (*INITIAL CONDITIONS); the
// fixed target as a strip held in place. Welded joints need no *EQUATION: ringcrush itself
// makes the touching outer nodes of neighbours ONE node (the thesis's *MPC ties), and the deck
// carries that node. Free joints are node-to-surface contact pairs ring i ↔ ring i+1.
#include <fmt/format.h>

#include <sstream>
#include <stdexcept>

#include "compare/calculix_deck_parts.hpp"
#include "compare/calculix_export.hpp"
#include "compare/fe_dynamic.hpp"
#include "compare/version.hpp"
#include "fe/chain/chain_mesh.hpp"

namespace ringcrush::compare {
using namespace calculix_parts;

CalculixDeck calculix_chain_deck(const Scene& s, CalculixSection section) {
  // The same input (and the same refusals) as `ringcrush fe` on a dynamic scene.
  const fe::ChainInput in = fe_chain_input(s);
  const fe::DynamicSolverInput solver = fe_dynamic_solver_input(s);
  const fe::ChainTopology topo = fe::make_chain_topology(in);
  const fe::ChainMesh& mesh = topo.mesh;
  const bool half = in.mesh.half_ring;
  const double r_out = in.ring.outer_radius_m;
  const double diameter = 2 * r_out;
  const double wall = in.ring.outer_radius_m - in.ring.inner_radius_m;

  CalculixDeck out;
  out.symmetry_factor = half ? 2.0 : 1.0;
  out.section_thickness_m = section == CalculixSection::FullWidth ? in.ring.width_m : 0.1 * wall;
  out.load_factor = out.symmetry_factor * in.ring.width_m / out.section_thickness_m;
  // Masses of the model: a half model carries half, a slab of thickness s carries s/L of it.
  const double mass_factor = 1.0 / out.load_factor;
  // ringcrush's rigid-body nodes come after the ring nodes (chain_mesh.cpp); only the ring
  // nodes are written, the bodies become strips.
  out.ring_nodes = mesh.impactor_node;
  out.ring_elements = static_cast<int>(mesh.elements.size());
  const int per_ring = out.ring_elements / in.rings;

  const int strip_elements = half ? 8 : 16;
  const double x_lo = half ? 0.0 : -diameter;
  const double strip_thickness = 2 * wall;
  struct Body {
    std::string name;
    PlateStrip strip;
    int node0 = 0, elem0 = 0, ref = 0, rot = 0, mass_elem = 0;
    double mass_kg = 0;  // of the model
    bool rigid = true;
  };
  std::vector<Body> bodies;
  // Impactor: its lower face on ring 1's top (y = R), the strip above it.
  bodies.push_back({"IMPACTOR", make_plate_strip(x_lo, diameter, strip_elements, r_out, strip_thickness, true)});
  bodies.back().mass_kg = in.impactor_mass_kg * mass_factor;
  if (in.joints == fe::JointKind::Plates)
    for (int k = 0; k + 1 < in.rings; ++k) {
      // Plate k between rings k and k+1: upper face on ring k's bottom, thickness of the scene.
      bodies.push_back({fmt::format("PLATE{}", k + 1),
                        make_plate_strip(x_lo, diameter, strip_elements, mesh.ring_centre_y[static_cast<std::size_t>(k)] - r_out,
                                         in.plate_thickness_m, false)});
      bodies.back().mass_kg = in.plate_mass_kg * mass_factor;
    }
  if (in.fixed_target) {
    bodies.push_back({"TARGET", make_plate_strip(x_lo, diameter, strip_elements, topo.target_y, strip_thickness, false)});
    bodies.back().rigid = false;
  }
  int next_node = out.ring_nodes + 1, next_elem = out.ring_elements + 1;
  for (auto& b : bodies) {
    b.node0 = next_node;
    b.elem0 = next_elem;
    next_node += static_cast<int>(b.strip.nodes.size());
    next_elem += static_cast<int>(b.strip.elements.size());
  }
  for (auto& b : bodies)
    if (b.rigid) {
      b.ref = next_node++;  // ccx: reference and rotation nodes belong to no element
      b.rot = next_node++;
      b.mass_elem = next_elem++;
    }
  out.nodes = next_node - 1;
  out.elements = next_elem - 1;
  out.driven_reference_node = bodies.front().ref;

  const auto& mat = s.rings.material;
  const double penalty_slope = in.contact.penalty_scale * mat.youngs_modulus_pa / topo.ring.element_depth;
  const std::string type = element_type(s.fe.integration);

  if (s.fe.integration == Integration::Selective)
    out.approximations.push_back(
        "fe.integration = \"selective\" has no ccx element: written as CPS8 (full 3x3 integration)");
  out.approximations.push_back(fmt::format(
      "plane stress: ccx expands CPS8 into a one-layer C3D20 slab; {} (masses scale with the slab: every mass in "
      "the deck is the physical one / {:.6g})",
      section == CalculixSection::FullWidth ? "section thickness = ring width (near plane strain)"
                                            : fmt::format("thin slab s = t/10 = {:.6g} m", out.section_thickness_m),
      out.load_factor));
  out.approximations.push_back(
      "impactor and joint plates: *RIGID BODY strips of CPS8 (2 wall thicknesses thick; plates the scene's "
      "thickness) with the body's mass as *MASS on the reference node; their element density is negligible "
      "(1 kg/m^3); the target: a held strip");
  out.approximations.push_back(
      "welded joints: ringcrush merges the touching outer nodes of neighbouring rings into one node; the deck "
      "keeps that single node (no *EQUATION needed)");
  out.approximations.push_back(
      "inner-wall self contact and ring-to-ring contact away from the joint pairs are not written");
  out.approximations.push_back(fmt::format(
      "contact: node-to-surface penalty, pressure/overclosure = scale * E / h = {:.6g} Pa/m", penalty_slope));
  out.approximations.push_back(
      solver.scheme == fe::DynamicScheme::Hht
          ? fmt::format("time integration: ccx *DYNAMIC (alpha method, ALPHA = {:g}); ringcrush's HAFTOL/PTOL step "
                        "control is not mapped: ccx uses its own",
                        s.fe.hht_alpha)
          : "time integration: ccx *DYNAMIC, EXPLICIT with the scene's initial step; ringcrush's own stable-step "
            "control is not mapped");
  out.approximations.push_back(
      "end: ccx runs to analysis.end_time_s; ringcrush's stop-at-rest test is not mapped");

  std::ostringstream o;
  o << fmt::format("** CalculiX (ccx 2.20) deck of ringcrush scene {} -- written by ringcrush {}\n", s.name,
                   version());
  o << fmt::format("** Units SI. Impact of a chain of {} rings ({} joints). Forces of the chain = {} x the deck's.\n",
                   in.rings, to_string(s.joints.type), num(out.load_factor));
  o << "*HEADING\n" << fmt::format("ringcrush scene {}: {}\n", s.name, s.title);
  o << "*NODE, NSET=NALL\n";
  for (int n = 0; n < out.ring_nodes; ++n)
    o << fmt::format("{}, {}, {}\n", n + 1, num(mesh.nodes[static_cast<std::size_t>(n)].x()),
                     num(mesh.nodes[static_cast<std::size_t>(n)].y()));
  for (const auto& b : bodies) {
    int id = b.node0;
    for (const auto& p : b.strip.nodes) o << fmt::format("{}, {}, {}\n", id++, num(p.x()), num(p.y()));
  }
  for (const auto& b : bodies)
    if (b.rigid) {
      const auto& f = b.strip.nodes[static_cast<std::size_t>(b.strip.reference)];
      o << fmt::format("{}, {}, {}\n{}, {}, {}\n", b.ref, num(f.x()), num(f.y()), b.rot, num(f.x()), num(f.y()));
    }
  write_elements(o, "RINGS", type, mesh.elements, 1, 1);
  for (const auto& b : bodies) write_elements(o, b.name, "CPS8", b.strip.elements, b.elem0, b.node0);
  for (const auto& b : bodies)
    if (b.rigid) o << fmt::format("*ELEMENT, TYPE=MASS, ELSET={}_MASS\n{}, {}\n", b.name, b.mass_elem, b.ref);

  for (const auto& b : bodies) {
    o << fmt::format("*NSET, NSET={}_NODES\n", b.name);
    write_ids(o, id_range(b.node0, b.strip.nodes.size()));
    if (b.rigid) o << fmt::format("*NSET, NSET={}_REF\n{}\n*NSET, NSET={}_ROT\n{}\n", b.name, b.ref, b.name, b.rot);
  }
  std::vector<int> fixed;
  for (int dof : topo.fixed_dofs)
    if (dof / 2 < out.ring_nodes) fixed.push_back(dof / 2 + 1);
  o << (half ? "** x = 0 symmetry plane of the half rings\n" : "** u_x of the outer points on the chain axis\n");
  o << "*NSET, NSET=RING_FIXED_X\n";
  write_ids(o, fixed);

  // Outer surface of each ring: face 1 of its outer layer of elements (ring_mesh.cpp order).
  for (int i = 0; i < in.rings; ++i) {
    o << fmt::format("*SURFACE, NAME=RING{}_OUTER, TYPE=ELEMENT\n", i + 1);
    for (int e = 0; e < per_ring; e += in.mesh.elements_through) o << i * per_ring + e + 1 << ", S1\n";
  }
  for (const auto& b : bodies) {
    o << fmt::format("*SURFACE, NAME={}_FACE, TYPE=ELEMENT\n{}, S1\n", b.name, b.name);
    if (b.name.rfind("PLATE", 0) == 0) o << fmt::format("*SURFACE, NAME={}_BACK, TYPE=ELEMENT\n{}, S3\n", b.name, b.name);
  }

  o << "*MATERIAL, NAME=RING_MATERIAL\n*ELASTIC\n" << num(mat.youngs_modulus_pa) << ", " << num(mat.poisson_ratio)
    << "\n*PLASTIC\n";
  for (const auto& h : mat.hardening) o << num(h.yield_stress_pa) << ", " << num(h.plastic_strain) << "\n";
  o << "*DENSITY\n" << num(mat.density_kg_m3) << "\n";
  o << "** rigid strips: their mass is the *MASS of the reference node, the elements' is negligible\n";
  o << "*MATERIAL, NAME=STRIP_MATERIAL\n*ELASTIC\n" << num(mat.youngs_modulus_pa) << ", " << num(mat.poisson_ratio)
    << "\n*DENSITY\n1\n";
  o << "*SOLID SECTION, ELSET=RINGS, MATERIAL=RING_MATERIAL\n" << num(out.section_thickness_m) << "\n";
  for (const auto& b : bodies)
    o << fmt::format("*SOLID SECTION, ELSET={}, MATERIAL=STRIP_MATERIAL\n{}\n", b.name, num(out.section_thickness_m));
  for (const auto& b : bodies)
    if (b.rigid)
      o << fmt::format("*MASS, ELSET={}_MASS\n{}\n*RIGID BODY, NSET={}_NODES, REF NODE={}, ROT NODE={}\n", b.name,
                       num(b.mass_kg), b.name, b.ref, b.rot);

  o << "*SURFACE INTERACTION, NAME=PENALTY\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n" << num(penalty_slope)
    << "\n";
  auto pair = [&](const std::string& slave, const std::string& master) {
    o << "*CONTACT PAIR, INTERACTION=PENALTY, TYPE=NODE TO SURFACE\n" << slave << ", " << master << "\n";
  };
  pair("RING1_OUTER", "IMPACTOR_FACE");
  for (int k = 0; k + 1 < in.rings; ++k) {
    if (in.joints == fe::JointKind::Plates) {
      pair(fmt::format("RING{}_OUTER", k + 1), fmt::format("PLATE{}_FACE", k + 1));
      pair(fmt::format("RING{}_OUTER", k + 2), fmt::format("PLATE{}_BACK", k + 1));
    } else if (in.joints == fe::JointKind::Free) {
      pair(fmt::format("RING{}_OUTER", k + 2), fmt::format("RING{}_OUTER", k + 1));
    }
  }
  if (in.fixed_target) pair(fmt::format("RING{}_OUTER", in.rings), "TARGET_FACE");

  o << "*BOUNDARY\nRING_FIXED_X, 1, 1\n";
  for (const auto& b : bodies) {
    if (b.rigid) o << fmt::format("{}_REF, 1, 1\n{}_ROT, 1, 3\n", b.name, b.name);
    else o << fmt::format("{}_NODES, 1, 2\n", b.name);
  }
  o << "** the impactor (all its nodes and its reference node) moves toward the chain\n";
  o << "*INITIAL CONDITIONS, TYPE=VELOCITY\n"
    << fmt::format("IMPACTOR_NODES, 2, {}\nIMPACTOR_REF, 2, {}\n", num(-in.impactor_velocity_m_s),
                   num(-in.impactor_velocity_m_s));

  o << "*STEP, NLGEOM, INC=10000000\n";
  if (solver.scheme == fe::DynamicScheme::Hht)
    o << fmt::format("*DYNAMIC, ALPHA={}\n{}, {}, {}, {}\n", num(s.fe.hht_alpha), num(solver.initial_step_s),
                     num(solver.end_time_s), num(solver.min_step_s), num(solver.max_step_s));
  else
    o << fmt::format("*DYNAMIC, EXPLICIT\n{}, {}\n", num(solver.initial_step_s), num(solver.end_time_s));
  o << "*NODE PRINT, NSET=IMPACTOR_REF, FREQUENCY=10\nU, V\n";
  if (in.fixed_target) o << "*NODE PRINT, NSET=TARGET_NODES, TOTALS=ONLY, FREQUENCY=10\nRF\n";
  o << "*NODE FILE, FREQUENCY=100\nU, V\n*EL FILE, FREQUENCY=100\nS, PEEQ\n*END STEP\n";
  out.deck = o.str();

  std::ostringstream r;
  r << fmt::format("CalculiX deck of ringcrush scene {} ({})\n\n", s.name, s.title);
  r << fmt::format("Run:    ccx -i {}        (writes {}.dat, {}.frd)\n", s.name, s.name, s.name);
  r << fmt::format("Output: impactor reference node U, V (set IMPACTOR_REF){}; forces of the chain = {} x the "
                   "deck's.\n\n",
                   in.fixed_target ? ", target reaction (set TARGET_NODES, totals)" : "", num(out.load_factor));
  r << fmt::format("Mapped: {} nodes, {} elements ({} ring {} on the ringcrush chain mesh, {} rings x {} per half "
                   "ring x {} through); *DENSITY {} kg/m^3; impactor {} kg at {} m/s (physical)\n",
                   out.nodes, out.elements, out.ring_elements, type, in.rings, in.mesh.elements_around,
                   in.mesh.elements_through, num(mat.density_kg_m3), num(in.impactor_mass_kg),
                   num(in.impactor_velocity_m_s));
  r << "Approximations and what is not mapped:\n";
  for (const auto& a : out.approximations) r << "  - " << a << "\n";
  out.readme = r.str();
  return out;
}

}  // namespace ringcrush::compare
