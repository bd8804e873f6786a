#include "compare/calculix_export.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "compare/calculix_deck_parts.hpp"
#include "compare/calculix_slab.hpp"
#include "compare/fe_static.hpp"
#include "compare/version.hpp"
#include "fe/mesh/ring_mesh.hpp"

namespace ringcrush::compare {
using namespace calculix_parts;

CalculixDeck calculix_deck(const Scene& s, CalculixSection section, CalculixPlates plates) {
  if (s.analysis.type != AnalysisType::Static) return calculix_chain_deck(s, section);
  // Rigid-body plates need the deck in bricks: ccx 2.20 moves a *RIGID BODY of CPS8 but prints
  // RF = 0 at its reference node (its own 2-D expansion), so the load could not be read.
  const bool bricks = plates == CalculixPlates::RigidBodies;
  // The same FE input (and the same refusals: chains, plane strain, friction) as `ringcrush fe`.
  const fe::FeInput in = fe_static_input(s);
  const fe::RingMesh mesh = fe::make_ring_mesh(in.ring, in.mesh);

  CalculixDeck out;
  const double r_out = in.ring.outer_radius_m;
  const double diameter = 2 * r_out;
  const bool half = in.mesh.half_ring;
  out.symmetry_factor = half ? 2.0 : 1.0;
  // See the header: with a slab one tenth of the wall thick the elastic ring stiffness is
  // within 0.3 % of plane stress's (measured with ccx 2.20 on the thesis ring).
  const double wall = in.ring.outer_radius_m - in.ring.inner_radius_m;
  out.section_thickness_m = section == CalculixSection::FullWidth ? in.ring.width_m : 0.1 * wall;
  out.load_factor = out.symmetry_factor * in.ring.width_m / out.section_thickness_m;
  out.ring_nodes = static_cast<int>(mesh.nodes.size());
  out.ring_elements = static_cast<int>(mesh.elements.size());

  // Plates reach one diameter to each side of the axis: a flattened half ring spreads its
  // outer surface over at most π R / 2 ≈ 0.79 D on each plate.
  const int plate_elements = half ? 8 : 16;
  const double plate_thickness = 2 * wall;
  const double x_lo = half ? 0.0 : -diameter;
  const PlateStrip bottom = make_plate_strip(x_lo, diameter, plate_elements, -r_out, plate_thickness, false);
  const PlateStrip top = make_plate_strip(x_lo, diameter, plate_elements, r_out, plate_thickness, true);

  const int bottom_node0 = out.ring_nodes + 1;  // 1-based first ids
  const int top_node0 = bottom_node0 + static_cast<int>(bottom.nodes.size());
  const int bottom_elem0 = out.ring_elements + 1;
  const int top_elem0 = bottom_elem0 + static_cast<int>(bottom.elements.size());
  out.nodes = top_node0 - 1 + static_cast<int>(top.nodes.size());
  out.elements = top_elem0 - 1 + static_cast<int>(top.elements.size());
  out.driven_reference_node = top_node0 + top.reference;
  out.reaction_set = "PLATE_TOP_NODES";
  // Bricks: every 2-D node through the slab (calculix_slab.hpp), then each plate's reference
  // and rotation node (they belong to no element, as ccx requires).
  std::vector<Eigen::Vector2d> xy(mesh.nodes);
  xy.insert(xy.end(), bottom.nodes.begin(), bottom.nodes.end());
  xy.insert(xy.end(), top.nodes.begin(), top.nodes.end());
  std::vector<std::array<int, 8>> all(mesh.elements);
  for (auto e : bottom.elements) {
    for (int& n : e) n += bottom_node0 - 1;
    all.push_back(e);
  }
  for (auto e : top.elements) {
    for (int& n : e) n += top_node0 - 1;
    all.push_back(e);
  }
  const Slab slab = make_slab(static_cast<int>(xy.size()), all, out.section_thickness_m);
  const int top_ref = 3 * slab.plane_nodes + 1, top_rot = top_ref + 1, bottom_ref = top_ref + 2,
            bottom_rot = top_ref + 3;
  if (bricks) {
    out.ring_nodes = make_slab(out.ring_nodes, mesh.elements, out.section_thickness_m).nodes();
    out.nodes = slab.nodes() + 4;
    out.driven_reference_node = top_ref;
    out.reaction_set = "PLATE_TOP_REF";
    out.ring_element_type = s.fe.integration == Integration::Reduced ? "C3D20R" : "C3D20";
  }
  auto through = [&](const std::vector<int>& ids) { return bricks ? slab.through(ids) : ids; };
  const std::string outer_face = bricks ? brick_face(1) : "S1", inner_face = bricks ? brick_face(3) : "S3";

  const auto& mat = s.rings.material;
  // Penalty per unit contact area: ringcrush's node stiffness scale · E · (w L) / h divided by
  // the node's tributary area w L (fe/contact/ring_contact.cpp).
  const double penalty_slope = in.contact.penalty_scale * mat.youngs_modulus_pa / mesh.element_depth;
  const std::string type = bricks ? out.ring_element_type : element_type(s.fe.integration);
  if (s.fe.integration == Integration::Selective)
    out.approximations.push_back(
        std::string("fe.integration = \"selective\" (volumetric strain at the 2x2 points) has no ccx element: "
                    "written as ") +
        (bricks ? "C3D20 (full 3x3x3 integration)" : "CPS8 (full 3x3 integration)"));
  if (bricks)
    out.approximations.push_back(
        "rigid plates: *RIGID BODY strips of C3D20R bricks, the ring one layer of 20-node bricks through the slab "
        "(u_z = 0 on its face z = 0); the bottom plate's reference node held, the top one's driven; the load is the "
        "reaction RF of the driven reference node");
  else
    out.approximations.push_back(
        "rigid plates: strips of CPS8 elements every node of which carries the plate's motion (bottom held, top "
        "driven), i.e. kinematically rigid; the load is the total reaction RF over the driven plate's nodes");
  out.approximations.push_back(
      "inner-wall self contact (lock-up, thesis 3.6.3): the inner faces within 60 deg of the bottom against those "
      "within 60 deg of the top (ringcrush pairs any inner points more than 60 deg of arc apart on opposite "
      "halves, with Hermite-smoothed master segments)");
  out.approximations.push_back(fmt::format(
      "contact: surface-to-surface penalty (ccx's node-to-surface diverged at the onset of the inner-wall contact), "
      "linear pressure-overclosure of slope scale * E / h = {:.6g} Pa/m "
      "(ringcrush's per-node penalty divided by the node's tributary area); ringcrush's Hermite smoothing of the "
      "inner-wall master segments (fe.contact_smoothing) has no ccx counterpart",
      penalty_slope));
  if (section == CalculixSection::FullWidth)
    out.approximations.push_back(fmt::format(
        "section thickness = ring width {:.6g} m: ccx expands CPS8 into a one-layer C3D20 slab that thick, which "
        "bends like a wide plate (near plane strain), not in the plane stress of ringcrush's CPS8",
        in.ring.width_m));
  else
    out.approximations.push_back(fmt::format(
        "plane stress: ccx expands CPS8 into a one-layer C3D20 slab of the section thickness; a slab as wide as the "
        "ring bends near plane strain, so the section is a thin slab s = t/10 = {:.6g} m (elastic ring stiffness "
        "within 0.3 % of plane stress's) and forces scale by L/s = {:.6g}",
        out.section_thickness_m, in.ring.width_m / out.section_thickness_m));
  if (half)
    out.approximations.push_back("half model (x >= 0, u_x = 0 on x = 0): the whole ring carries twice the half's load");
  out.approximations.push_back(fmt::format(
      "the ring's load = {:.6g} x |fy| of the total force of set {} printed in the .dat file", out.load_factor,
      out.reaction_set));

  std::ostringstream o;
  o << fmt::format("** CalculiX (ccx 2.20) deck of ringcrush scene {} -- written by ringcrush {}\n", s.name,
                   version());
  o << "** Units SI (m, N, Pa). Static crush of one ring between rigid plates (thesis Anexo I).\n";
  o << fmt::format("** The ring's load = {:.6g} x |fy| of the total force of {} (.dat)\n", out.load_factor,
                   out.reaction_set);
  o << "*HEADING\n" << fmt::format("ringcrush scene {}: {}\n", s.name, s.title);

  o << "** Ring: the mesh of fe/mesh/ring_mesh (nodes 1.." << out.ring_nodes << "), then the plates.\n";
  if (bricks) {
    write_slab_nodes(o, slab, xy);
    for (int n : {top_ref, top_rot}) o << fmt::format("{}, 0, {}, 0\n", n, num(r_out));
    for (int n : {bottom_ref, bottom_rot}) o << fmt::format("{}, 0, {}, 0\n", n, num(-r_out));
    const auto part = [&](std::size_t first, std::size_t count) {
      return std::vector<std::array<int, 8>>(all.begin() + static_cast<long>(first),
                                             all.begin() + static_cast<long>(first + count));
    };
    write_bricks(o, "RING", type, slab, mesh.elements, 1);
    write_bricks(o, "PLATE_BOTTOM", "C3D20R", slab, part(mesh.elements.size(), bottom.elements.size()), bottom_elem0);
    write_bricks(o, "PLATE_TOP", "C3D20R", slab,
                 part(mesh.elements.size() + bottom.elements.size(), top.elements.size()), top_elem0);
  } else {
    o << "*NODE, NSET=NALL\n";
    int id = 1;
    for (const auto& p : xy) o << fmt::format("{}, {}, {}\n", id++, num(p.x()), num(p.y()));
    write_elements(o, "RING", type, mesh.elements, 1, 1);
    write_elements(o, "PLATE_BOTTOM", "CPS8", bottom.elements, bottom_elem0, bottom_node0);
    write_elements(o, "PLATE_TOP", "CPS8", top.elements, top_elem0, top_node0);
  }

  std::vector<int> ids;

  o << "*NSET, NSET=PLATE_BOTTOM_NODES\n";
  write_ids(o, through(id_range(bottom_node0, bottom.nodes.size())));
  o << "*NSET, NSET=PLATE_TOP_NODES\n";
  write_ids(o, through(id_range(top_node0, top.nodes.size())));
  o << "*NSET, NSET=DRIVEN_REF\n" << out.driven_reference_node << "\n";
  if (bricks) {
    o << fmt::format("*NSET, NSET=PLATE_TOP_REF\n{}\n*NSET, NSET=PLATE_BOTTOM_REF\n{}\n", top_ref, bottom_ref);
    o << "** the face z = 0 of the slab: u_z = 0 (mid-plane symmetry of a slab 2s thick, plane stress)\n";
    o << "*NSET, NSET=RING_FRONT\n";
    write_ids(o, id_range(1, mesh.nodes.size()));
  }
  ids.clear();
  for (int n : mesh.fixed_x) ids.push_back(n + 1);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  o << (half ? "** x = 0 symmetry plane of the half ring (XSYMM)\n"
             : "** u_x of the two outer points on the loading axis (frictionless plates leave x free)\n");
  o << "*NSET, NSET=RING_FIXED_X\n";
  write_ids(o, through(ids));

  // Outer surface: face 1 (nodes 1-5-2) of the outer layer of elements (ring_mesh.cpp order).
  o << "*SURFACE, NAME=RING_OUTER, TYPE=ELEMENT\n";
  for (int e = 0; e < out.ring_elements; e += in.mesh.elements_through) o << e + 1 << ", " << outer_face << "\n";
  // Inner surface for the lock-up (thesis §3.6.3): face 3 (nodes 3-7-4) of the inner layer,
  // split by the reference angle φ of the face's middle node into the part near the bottom
  // plate (φ within π/3 of 0) and near the top (within π/3 of π). Faces nearer the sides are
  // left out: at lock-up of a single ring the walls meet at the flats (ringcrush itself pairs
  // inner points down to ContactInput::self_contact_min_separation_rad = 0.2 rad of arc, for
  // the side folds of chains; the static crush to 46 mm never closes them).
  const double pi = std::numbers::pi;
  std::vector<int> inner_bottom, inner_top;
  for (int e = in.mesh.elements_through - 1; e < out.ring_elements; e += in.mesh.elements_through) {
    const double phi = mesh.node_angle[static_cast<std::size_t>(mesh.elements[static_cast<std::size_t>(e)][6])];
    if (std::min(phi, 2 * pi - phi) < pi / 3) inner_bottom.push_back(e + 1);
    if (std::abs(phi - pi) < pi / 3) inner_top.push_back(e + 1);
  }
  o << "*SURFACE, NAME=RING_INNER_BOTTOM, TYPE=ELEMENT\n";
  for (int e : inner_bottom) o << e << ", " << inner_face << "\n";
  o << "*SURFACE, NAME=RING_INNER_TOP, TYPE=ELEMENT\n";
  for (int e : inner_top) o << e << ", " << inner_face << "\n";
  o << "*SURFACE, NAME=PLATE_BOTTOM_FACE, TYPE=ELEMENT\nPLATE_BOTTOM, " << outer_face << "\n";
  o << "*SURFACE, NAME=PLATE_TOP_FACE, TYPE=ELEMENT\nPLATE_TOP, " << outer_face << "\n";

  o << "*MATERIAL, NAME=RING_MATERIAL\n*ELASTIC\n"
    << num(mat.youngs_modulus_pa) << ", " << num(mat.poisson_ratio) << "\n";
  o << "** isotropic hardening, flat after the last point (scene rings.material.hardening)\n*PLASTIC\n";
  for (const auto& h : mat.hardening) o << num(h.yield_stress_pa) << ", " << num(h.plastic_strain) << "\n";
  o << "** the plates only carry prescribed motion; their material never matters\n";
  o << "*MATERIAL, NAME=PLATE_MATERIAL\n*ELASTIC\n" << num(mat.youngs_modulus_pa) << ", "
    << num(mat.poisson_ratio) << "\n";
  // Bricks carry the slab thickness in their z coordinates; a 2-D section gives it.
  const std::string thickness = bricks ? "" : num(out.section_thickness_m) + "\n";
  o << "*SOLID SECTION, ELSET=RING, MATERIAL=RING_MATERIAL\n" << thickness;
  o << "*SOLID SECTION, ELSET=PLATE_BOTTOM, MATERIAL=PLATE_MATERIAL\n" << thickness;
  o << "*SOLID SECTION, ELSET=PLATE_TOP, MATERIAL=PLATE_MATERIAL\n" << thickness;
  if (bricks)
    o << fmt::format("*RIGID BODY, NSET=PLATE_TOP_NODES, REF NODE={}, ROT NODE={}\n"
                     "*RIGID BODY, NSET=PLATE_BOTTOM_NODES, REF NODE={}, ROT NODE={}\n",
                     top_ref, top_rot, bottom_ref, bottom_rot);

  o << "** frictionless penalty contact, pressure = K * overclosure (K = scale * E / h)\n";
  o << "*SURFACE INTERACTION, NAME=RING_PLATE\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
    << num(penalty_slope) << "\n";
  o << "*CONTACT PAIR, INTERACTION=RING_PLATE, TYPE=SURFACE TO SURFACE\nRING_OUTER, PLATE_BOTTOM_FACE\n";
  o << "*CONTACT PAIR, INTERACTION=RING_PLATE, TYPE=SURFACE TO SURFACE\nRING_OUTER, PLATE_TOP_FACE\n";
  o << "** inner wall against itself (surface-to-surface contact is symmetric in ccx)\n";
  o << "*CONTACT PAIR, INTERACTION=RING_PLATE, TYPE=SURFACE TO SURFACE\nRING_INNER_BOTTOM, RING_INNER_TOP\n";

  if (bricks)
    o << fmt::format("*BOUNDARY\nRING_FIXED_X, 1, 1\nRING_FRONT, 3, 3\n{0}, 1, 3\n{1}, 1, 3\n{2}, 1, 1\n{2}, 3, 3\n"
                     "{3}, 1, 3\n",
                     bottom_ref, bottom_rot, top_ref, top_rot);
  else
    o << "*BOUNDARY\nRING_FIXED_X, 1, 1\nPLATE_BOTTOM_NODES, 1, 2\nPLATE_TOP_NODES, 1, 1\n";

  // ccx's default *CONTROLS: they converge on the thesis ring with one or two cut-backs in the
  // first increment only; more iterations and cut-backs (TIME INCREMENTATION
  // 8,10,9,20,10,4,0,10) changed nothing (the same 279 iterations with node-to-surface
  // pairs), so no *CONTROLS card is written.
  o << fmt::format("*STEP, NLGEOM, INC={}\n", in.solver.max_increments);
  o << "** initial, total, minimum, maximum increment as fractions of the crush (scene fe.*_increment)\n";
  o << "*STATIC\n"
    << num(in.solver.initial_increment) << ", 1.0, " << num(in.solver.min_increment) << ", "
    << num(in.solver.max_increment) << "\n";
  o << "** the driven plate travels analysis.crush_m toward the ring\n";
  o << "*BOUNDARY\n" << (bricks ? std::to_string(top_ref) : std::string("PLATE_TOP_NODES")) << ", 2, 2, "
    << num(-in.solver.crush_m) << "\n";
  o << "*NODE PRINT, NSET=" << out.reaction_set << ", TOTALS=ONLY\nRF\n";
  o << "*NODE PRINT, NSET=DRIVEN_REF\nU\n";
  o << "*NODE FILE\nU, RF\n*EL FILE\nS, PEEQ\n*END STEP\n";
  out.deck = o.str();

  std::ostringstream r;
  r << fmt::format("CalculiX deck of ringcrush scene {} ({})\n\n", s.name, s.title);
  r << fmt::format("Run:    ccx -i {}        (writes {}.dat, {}.frd)\n", s.name, s.name, s.name);
  r << fmt::format(
      "Load:   the total force of set {} in {}.dat (\"total force (fx,fy,fz)\"); the ring's load is "
      "{:.6g} x |fy| at time t, deflection t x {} m.\n\n",
      out.reaction_set, s.name, out.load_factor, num(in.solver.crush_m));
  r << fmt::format("Mapped: {} nodes, {} elements ({} ring {} on the ringcrush mesh: {} per half ring x {} through, "
                   "grading {}; {} + {} plate {})\n",
                   out.nodes, out.elements, out.ring_elements, type, in.mesh.elements_around,
                   in.mesh.elements_through, in.mesh.grading, bottom.elements.size(), top.elements.size(),
                   bricks ? "C3D20R *RIGID BODY" : "CPS8");
  r << "        *SOLID SECTION (thickness: see below); *ELASTIC, *PLASTIC (hardening table); *CONTACT PAIR\n"
       "        ring outer surface to each plate face; *BOUNDARY symmetry / plate motion; *STATIC, NLGEOM step\n"
       "        with the scene's increments; *NODE PRINT of the driven plate's RF (totals) and reference node U.\n";
  r << "Approximations and what is not mapped:\n";
  for (const auto& a : out.approximations) r << "  - " << a << "\n";
  out.readme = r.str();
  return out;
}

std::vector<CcxTotalForce> parse_ccx_total_forces(const std::string& text, const std::string& nset) {
  std::vector<CcxTotalForce> out;
  std::string upper = nset;
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
  const std::string head = "total force (fx,fy,fz) for set " + upper + " and time";
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find(head);
    if (at == std::string::npos) continue;
    CcxTotalForce f{};
    std::istringstream t(line.substr(at + head.size()));
    if (!(t >> f.time)) throw std::runtime_error("ccx .dat: no time after \"" + head + "\"");
    std::string values;
    while (std::getline(in, values) && values.find_first_not_of(" \t\r") == std::string::npos) {
    }
    std::istringstream v(values);
    double fz = 0;
    if (!(v >> f.fx >> f.fy >> fz)) throw std::runtime_error("ccx .dat: no force values after \"" + line + "\"");
    out.push_back(f);
  }
  return out;
}

std::vector<CcxNodeVector> parse_ccx_node_vectors(const std::string& text, const std::string& quantity,
                                                  const std::string& nset) {
  std::vector<CcxNodeVector> out;
  std::string upper = nset;
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
  const std::string head = " " + quantity + " (vx,vy,vz) for set " + upper + " and time";
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find(head);
    if (at == std::string::npos) continue;
    CcxNodeVector v{};
    std::istringstream t(line.substr(at + head.size()));
    if (!(t >> v.time)) throw std::runtime_error("ccx .dat: no time after \"" + head + "\"");
    std::string values;
    while (std::getline(in, values) && values.find_first_not_of(" \t\r") == std::string::npos) {
    }
    std::istringstream r(values);
    int node = 0;
    if (!(r >> node >> v.x >> v.y >> v.z)) throw std::runtime_error("ccx .dat: no node values after \"" + line + "\"");
    out.push_back(v);
  }
  return out;
}

}  // namespace ringcrush::compare
