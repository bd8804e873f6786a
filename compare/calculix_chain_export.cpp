// The dynamic half of compare/calculix_export.hpp: a ring chain under impact (issue 4, thesis
// §3.5, §4.2) as a CalculiX *DYNAMIC deck on the mesh of fe/chain/chain_mesh, written as one
// layer of 20-node bricks (compare/calculix_slab.hpp) because ccx 2.20's own CPS8 expansion
// loses initial velocities and rigid bodies (measured, see the header).
//
// ringcrush's rigid bodies are single nodes with analytic contact planes (impactor, joint
// plates, target); here each is a strip of bricks: the impactor and the joint plates *RIGID
// BODY strips whose reference node carries the body's mass (*MASS) and, for the impactor, the
// impact velocity (*INITIAL CONDITIONS on every node of the body); the fixed target a strip
// held in place. Their contact with the rings is ringcrush's own: a plane with a penalty
// spring per node, written as GAPUNI elements (see the gap block below for why). Welded joints need no *EQUATION:
// ringcrush itself makes the touching outer nodes of neighbours ONE node (the thesis's *MPC
// ties), and the deck carries that node (through the slab). Free joints are contact pairs
// ring i ↔ ring i+1.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "compare/calculix_deck_parts.hpp"
#include "compare/calculix_export.hpp"
#include "compare/calculix_slab.hpp"
#include "compare/fe_dynamic.hpp"
#include "compare/version.hpp"
#include "fe/chain/chain_mesh.hpp"

namespace ringcrush::compare {
using namespace calculix_parts;

namespace {

struct Body {
  std::string name;
  PlateStrip strip;
  int node0 = 0;  // 0-based index of the strip's first node in the 2-D node list
  int elem0 = 0;  // 1-based id of its first element
  int ref = 0, rot = 0, mass_elem = 0;
  double mass_kg = 0;  // of the model (deck)
  bool rigid = true;
};

std::vector<int> plane_ids(int first0, std::size_t count) { return id_range(first0 + 1, count); }

}  // namespace

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
  out.dynamic = true;
  out.symmetry_factor = half ? 2.0 : 1.0;
  out.section_thickness_m = section == CalculixSection::FullWidth ? in.ring.width_m : 0.1 * wall;
  out.load_factor = out.symmetry_factor * in.ring.width_m / out.section_thickness_m;
  // A half model carries half of every mass, a slab of thickness s carries s/L of it: the
  // ring's through *DENSITY, the rigid bodies through *MASS / load_factor.
  const double mass_factor = 1.0 / out.load_factor;
  // ringcrush's rigid-body nodes come after the ring nodes (chain_mesh.cpp); only the ring
  // nodes are written, the bodies become strips.
  const int ring_plane_nodes = mesh.impactor_node;
  out.ring_elements = static_cast<int>(mesh.elements.size());
  const int per_ring = out.ring_elements / in.rings;

  // Strips reach one diameter to each side of the axis (a flattened ring spreads over at
  // most π R / 2 ≈ 0.79 D on each side).
  const int strip_elements = half ? 8 : 16;
  const double x_lo = half ? 0.0 : -diameter;
  const double strip_thickness = 2 * wall;
  std::vector<Body> bodies;
  // Impactor: its lower face on ring 1's top (y = R, ringcrush's impactor node), the strip above.
  bodies.push_back({"IMPACTOR", make_plate_strip(x_lo, diameter, strip_elements, r_out, strip_thickness, true)});
  bodies.back().mass_kg = in.impactor_mass_kg * mass_factor;
  if (in.joints == fe::JointKind::Plates)
    for (int k = 0; k + 1 < in.rings; ++k) {
      // Plate k between rings k and k+1: its upper face on ring k's bottom, the scene's thickness.
      const double top_face = mesh.nodes[static_cast<std::size_t>(mesh.plate_nodes[static_cast<std::size_t>(k)])].y() +
                              topo.plate_half_thickness;
      bodies.push_back({fmt::format("PLATE{}", k + 1),
                        make_plate_strip(x_lo, diameter, strip_elements, top_face, 2 * topo.plate_half_thickness,
                                         false)});
      bodies.back().mass_kg = in.plate_mass_kg * mass_factor;
    }
  if (in.fixed_target) {
    bodies.push_back({"TARGET", make_plate_strip(x_lo, diameter, strip_elements, topo.target_y, strip_thickness, false)});
    bodies.back().rigid = false;
  }

  // The 2-D node and element lists of everything (rings first, as ringcrush numbers them).
  std::vector<Eigen::Vector2d> xy(mesh.nodes.begin(), mesh.nodes.begin() + ring_plane_nodes);
  std::vector<std::array<int, 8>> all_elements(mesh.elements);
  int next_elem = out.ring_elements + 1;
  for (auto& b : bodies) {
    b.node0 = static_cast<int>(xy.size());
    b.elem0 = next_elem;
    xy.insert(xy.end(), b.strip.nodes.begin(), b.strip.nodes.end());
    for (auto e : b.strip.elements) {
      for (int& n : e) n += b.node0;
      all_elements.push_back(e);
    }
    next_elem += static_cast<int>(b.strip.elements.size());
  }
  const Slab slab = make_slab(static_cast<int>(xy.size()), all_elements, out.section_thickness_m);
  {
    const Slab ring_slab = make_slab(ring_plane_nodes, mesh.elements, out.section_thickness_m);
    out.ring_nodes = ring_slab.nodes();
  }
  int next_node = 3 * slab.plane_nodes + 1;  // after the highest brick id
  int extra_nodes = 0;
  for (auto& b : bodies) {
    b.ref = next_node++;  // ccx: reference and rotation nodes belong to no element
    ++extra_nodes;
    if (b.rigid) {
      b.rot = next_node++;
      ++extra_nodes;
      b.mass_elem = next_elem++;
    }
  }
  out.nodes = slab.nodes() + extra_nodes;
  out.driven_reference_node = bodies.front().ref;
  out.impactor_mass_kg = bodies.front().mass_kg;
  out.impactor_velocity_m_s = in.impactor_velocity_m_s;

  const auto& mat = s.rings.material;
  const double penalty_slope = in.contact.penalty_scale * mat.youngs_modulus_pa / topo.ring.element_depth;
  const std::string type = s.fe.integration == Integration::Reduced ? "C3D20R" : "C3D20";
  out.ring_element_type = type;

  // Rigid faces as ringcrush models them: a plane with a penalty spring per outer node
  // (fe/chain/chain_model.cpp, k = scale·E·w·L/h). ccx's meshed-surface contact does not run
  // here (node-to-surface: "too many cutbacks" at the second increment, its impact rules
  // halving the increment below 1e-10 s; surface-to-surface: increments of ~1e-8 s), so each
  // face is a set of GAPUNI elements, one per brick node of the facing outer nodes, to the
  // body's reference node along the face normal: clearance = the node's distance to the plane,
  // stiffness = the node's share of the penalty (in-plane weight w of ring_mesh × the slab
  // layer's weight: 1/6, 2/3, 1/6 at a corner's front, middle, back nodes, 1/2, 1/2 at a
  // midside's) × scale·E·s/h. A node shares the plane's rigid motion exactly (frictionless).
  struct Gap {
    int node, other, id;  // brick node ids: the ring node, and the body's reference node or the facing node
    double clearance, normal_y, stiffness;
  };
  std::vector<Gap> gaps;
  // The brick nodes of 2-D node n with their share of the node's contact area (the layer
  // weights of a quadratic edge through the slab: 1/6, 2/3, 1/6; a linear one: 1/2, 1/2).
  auto layers = [&](int n) {
    return slab.corner[static_cast<std::size_t>(n - 1)]
               ? std::vector<std::pair<int, double>>{{slab.front(n), 1.0 / 6}, {slab.middle(n), 2.0 / 3},
                                                     {slab.back(n), 1.0 / 6}}
               : std::vector<std::pair<int, double>>{{slab.front(n), 0.5}, {slab.back(n), 0.5}};
  };
  auto global = [&](int ring, int local) {
    return topo.ring_node[static_cast<std::size_t>(ring)][static_cast<std::size_t>(local)] + 1;
  };
  auto face_gaps = [&](int ring, int body, double face_y, double normal_y) {
    // normal_y: from the ring toward the body (+1: the body is above the ring)
    const double yc = mesh.ring_centre_y[static_cast<std::size_t>(ring)];
    for (std::size_t j = 0; j < topo.ring.outer_nodes.size(); ++j) {
      const int n = global(ring, topo.ring.outer_nodes[j]);
      const double y = xy[static_cast<std::size_t>(n - 1)].y();
      if ((y - yc) * normal_y < 0) continue;  // the half of the ring facing the body
      const double k = penalty_slope * topo.ring.outer_weight[j] * slab.thickness;
      const double clearance = std::max(0.0, (face_y - y) * normal_y);
      for (const auto& [id, share] : layers(n))
        gaps.push_back({id, bodies[static_cast<std::size_t>(body)].ref, 0, clearance, normal_y, k * share});
    }
  };
  face_gaps(0, 0, r_out, 1.0);
  for (std::size_t bi = 1; bi < bodies.size(); ++bi) {
    const Body& b = bodies[bi];
    const double top_face = b.strip.nodes[static_cast<std::size_t>(b.strip.reference)].y();
    const int body = static_cast<int>(bi);
    if (b.name == "TARGET") {
      face_gaps(in.rings - 1, body, top_face, -1.0);
    } else {  // PLATEk between rings k-1 and k (0-based): upper face top_face, lower face − thickness
      const int k = static_cast<int>(bi) - 1;
      face_gaps(k, body, top_face, -1.0);
      face_gaps(k + 1, body, top_face - 2 * topo.plate_half_thickness, 1.0);
    }
  }
  // Ring↔ring (free and welded joints) and inner wall (lock-up) as node-to-node gaps between
  // mirror nodes: the node at reference angle φ (φ = 0 at the bottom, ring_mesh.cpp) and the
  // node at π − φ face each other across the joint plane (of neighbours) or across the ring's
  // horizontal diameter (inner wall), at the same x. Within π/3 of the joint / of the flats
  // (ringcrush pairs inner points down to 0.2 rad of arc, ContactInput::
  // self_contact_min_separation_rad, which also closes side folds; mirror gaps cannot follow a
  // fold, whose two legs slide along each other). Valid while the two
  // nodes slide little along each other, which the symmetry of the two sides keeps small;
  // ccx's *CONTACT PAIRs would slide freely but stall the integration as soon as they close
  // (node-to-surface at a free joint's initial touch: "too many cutbacks" at 0.5 us).
  const double pi = std::numbers::pi;
  auto mirror = [&](const std::vector<int>& nodes, std::size_t j) -> std::ptrdiff_t {
    const double phi = topo.ring.node_angle[static_cast<std::size_t>(nodes[j])];
    double m = pi - phi;
    if (m < 0) m += 2 * pi;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (std::abs(topo.ring.node_angle[static_cast<std::size_t>(nodes[i])] - m) < 1e-9) return static_cast<std::ptrdiff_t>(i);
    return -1;
  };
  auto near_bottom = [&](int local) {
    const double phi = topo.ring.node_angle[static_cast<std::size_t>(local)];
    return std::min(phi, 2 * pi - phi) < pi / 3;
  };
  auto pair_gaps = [&](int ring_a, int ring_b, const std::vector<int>& nodes, const std::vector<double>& weight) {
    // ring_a's nodes near its bottom against their mirrors in ring_b (ring_b's top), direction −y... +y for the
    // inner wall (ring_a == ring_b: the bottom node looks up at the top node)
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (!near_bottom(nodes[j])) continue;
      const std::ptrdiff_t m = mirror(nodes, j);
      if (m < 0) continue;
      const int a = global(ring_a, nodes[j]), b = global(ring_b, nodes[static_cast<std::size_t>(m)]);
      if (a == b) continue;  // a welded joint's shared node
      const double dy = xy[static_cast<std::size_t>(b - 1)].y() - xy[static_cast<std::size_t>(a - 1)].y();
      const double k = penalty_slope * weight[j] * slab.thickness;
      const auto la = layers(a), lb = layers(b);
      for (std::size_t l = 0; l < la.size() && l < lb.size(); ++l)
        gaps.push_back({la[l].first, lb[l].first, 0, std::abs(dy), dy < 0 ? -1.0 : 1.0, k * la[l].second});
    }
  };
  const std::size_t before_rings = gaps.size();
  if (in.joints != fe::JointKind::Plates)
    for (int k = 0; k + 1 < in.rings; ++k) pair_gaps(k, k + 1, topo.ring.outer_nodes, topo.ring.outer_weight);
  const std::size_t before_inner = gaps.size();
  if (in.contact.self_contact)
    for (int i = 0; i < in.rings; ++i) pair_gaps(i, i, topo.ring.inner_nodes, topo.ring.inner_weight);
  out.ring_ring_gaps = static_cast<int>(before_inner - before_rings);
  out.inner_wall_gaps = static_cast<int>(gaps.size() - before_inner);
  for (auto& g : gaps) g.id = next_elem++;
  out.elements = next_elem - 1;
  out.gap_elements = static_cast<int>(gaps.size());

  if (s.fe.integration == Integration::Selective)
    out.approximations.push_back(
        "fe.integration = \"selective\" has no ccx element: written as C3D20 (full 3x3x3 integration)");
  out.approximations.push_back(fmt::format(
      "plane stress: one layer of {} bricks through a slab {} (u_z = 0 on the face z = 0, the other face free; "
      "written as bricks because ccx 2.20's own CPS8 expansion drops initial velocities); every mass and force in "
      "the deck is the physical one / {:.6g}, displacements and velocities are physical",
      type,
      section == CalculixSection::FullWidth ? "as thick as the ring (near plane strain)"
                                            : fmt::format("s = t/10 = {:.6g} m thick", out.section_thickness_m),
      out.load_factor));
  out.approximations.push_back(
      "impactor and joint plates: *RIGID BODY strips of C3D20R bricks (impactor two wall thicknesses thick, plates "
      "the scene's thickness) whose reference node carries the body's mass (*MASS); their element density is "
      "negligible (1 kg/m^3); the target: a strip held in place");
  if (in.joints == fe::JointKind::Welded)
    out.approximations.push_back(
        "welded joints: ringcrush merges the touching outer nodes of neighbouring rings into one node; the deck "
        "keeps that node (through the slab), no *EQUATION needed");
  out.approximations.push_back(fmt::format(
      "contact: all of it as GAPUNI elements (frictionless penalty, the node's share of ringcrush's "
      "scale * E * w * s / h with scale * E / h = {:.6g} Pa/m): rigid faces (impactor on ring 1, plates on their "
      "two rings, target under the last ring) one per brick node of the facing half ring to the body's reference "
      "node, clearance = distance to the plane; ring to ring ({}) and inner wall ({}) between mirror nodes within "
      "60 deg of the joint / of the flats, valid while they slide little along each other. ccx 2.20's *CONTACT "
      "PAIRs stall the *DYNAMIC step as soon as they close (node-to-surface: its impact rules halve the increment "
      "to 1e-10 s, \"too many cutbacks\", at the 2nd increment; surface-to-surface: increments of ~1e-8 s). "
      "ringcrush meets every face and ring with every ring and smooths its master segments (no counterpart); the "
      "element surfaces RINGi_OUTER, RINGi_INNER_BOTTOM/TOP are in the deck for a user's own *CONTACT PAIR",
      penalty_slope, out.ring_ring_gaps, out.inner_wall_gaps));
  // ccx's explicit *DYNAMIC is no use here: on the thin slab its stable increment is 7e-9 s and
  // each increment with the rigid bodies' MPCs costs ~0.2 s CPU (measured with ccx 2.20 on two
  // free rings: 298 increments, 2.1 µs of impact, in 67 s), so every scene gets the implicit
  // α-method with the scene's initial step; an explicit scene's α is the scene's fe.hht_alpha.
  out.approximations.push_back(fmt::format(
      "time integration: ccx *DYNAMIC, implicit alpha method, ALPHA = {:g}, from the scene's initial step {:g} s "
      "(ccx's own increment control; ringcrush's HAFTOL/PTOL or stable-step control is not mapped){}",
      s.fe.hht_alpha, solver.initial_step_s,
      solver.scheme == fe::DynamicScheme::Hht
          ? ""
          : "; the scene's explicit scheme is not used: ccx's explicit step on the thin slab is 7e-9 s at ~0.2 s CPU "
            "each (2.1 us of impact in 67 s CPU on two rings)"));
  out.approximations.push_back("end: ccx runs to analysis.end_time_s; ringcrush's stop-at-rest test is not mapped");

  std::ostringstream o;
  o << fmt::format("** CalculiX (ccx 2.20) deck of ringcrush scene {} -- written by ringcrush {}\n", s.name,
                   version());
  o << fmt::format("** Units SI. Impact of a chain of {} ring(s) ({} joints). Forces and masses of the chain = {:.6g} x "
                   "the deck's.\n",
                   in.rings, to_string(s.joints.type), out.load_factor);
  o << "*HEADING\n" << fmt::format("ringcrush scene {}: {}\n", s.name, s.title);
  o << fmt::format("** Rings: the chain mesh of fe/chain/chain_mesh (2-D nodes 1..{}), then the strips; brick "
                   "nodes n (z = 0), n + {} (z = s), n + {} (z = s/2)\n",
                   ring_plane_nodes, slab.plane_nodes, 2 * slab.plane_nodes);
  write_slab_nodes(o, slab, xy);
  for (const auto& b : bodies) {
    const auto& f = b.strip.nodes[static_cast<std::size_t>(b.strip.reference)];
    o << fmt::format("{}, {}, {}, {}\n", b.ref, num(f.x()), num(f.y()), num(0.5 * slab.thickness));
    if (b.rigid) o << fmt::format("{}, {}, {}, {}\n", b.rot, num(f.x()), num(f.y()), num(0.5 * slab.thickness));
  }
  write_bricks(o, "RINGS", type, slab, mesh.elements, 1);
  for (const auto& b : bodies) {
    std::vector<std::array<int, 8>> es(all_elements.begin() + (b.elem0 - 1),
                                       all_elements.begin() + (b.elem0 - 1) + static_cast<long>(b.strip.elements.size()));
    write_bricks(o, b.name, "C3D20R", slab, es, b.elem0);
  }
  for (const auto& b : bodies)
    if (b.rigid) o << fmt::format("*ELEMENT, TYPE=MASS, ELSET={}_MASS\n{}, {}\n", b.name, b.mass_elem, b.ref);
  o << "** rigid faces: one GAPUNI per facing ring node to the body's reference node (see *GAP below)\n";
  for (const auto& g : gaps)
    o << fmt::format("*ELEMENT, TYPE=GAPUNI, ELSET=GAP{}\n{}, {}, {}\n", g.id, g.id, g.node, g.other);

  for (const auto& b : bodies) {
    o << fmt::format("*NSET, NSET={}_NODES\n", b.name);
    write_ids(o, slab.through(plane_ids(b.node0, b.strip.nodes.size())));
    o << fmt::format("*NSET, NSET={}_REF\n{}\n", b.name, b.ref);
    if (b.rigid) o << fmt::format("*NSET, NSET={}_ROT\n{}\n", b.name, b.rot);
  }
  std::vector<int> fixed;
  for (int dof : topo.fixed_dofs)
    if (dof / 2 < ring_plane_nodes) fixed.push_back(dof / 2 + 1);
  o << (half ? "** x = 0 symmetry plane of the half rings\n" : "** u_x of the outer points on the chain axis\n");
  o << "*NSET, NSET=RING_FIXED_X\n";
  write_ids(o, slab.through(fixed));
  o << "** the face z = 0 of the slab: u_z = 0 (mid-plane symmetry of a slab 2s thick, plane stress)\n";
  o << "*NSET, NSET=RING_FRONT\n";
  write_ids(o, plane_ids(0, static_cast<std::size_t>(ring_plane_nodes)));

  // Outer surface of each ring: CPS8 face 1 of its outer layer of elements (ring_mesh.cpp
  // order), brick face S3; inner wall: CPS8 face 3 of its inner layer, brick face S5, split
  // by the reference angle φ of the face's middle node into the part near the ring's top
  // (φ within π/3 of π) and near its bottom (within π/3 of 0), as the static deck.
  const int through = in.mesh.elements_through;
  for (int i = 0; i < in.rings; ++i) {
    o << fmt::format("*SURFACE, NAME=RING{}_OUTER, TYPE=ELEMENT\n", i + 1);
    for (int e = 0; e < per_ring; e += through) o << i * per_ring + e + 1 << ", " << brick_face(1) << "\n";
    std::vector<int> bottom, top;
    for (int e = through - 1; e < per_ring; e += through) {
      const double phi = topo.ring.node_angle[static_cast<std::size_t>(topo.ring.elements[static_cast<std::size_t>(e)][6])];
      if (std::min(phi, 2 * pi - phi) < pi / 3) bottom.push_back(i * per_ring + e + 1);
      if (std::abs(phi - pi) < pi / 3) top.push_back(i * per_ring + e + 1);
    }
    o << fmt::format("*SURFACE, NAME=RING{}_INNER_BOTTOM, TYPE=ELEMENT\n", i + 1);
    for (int e : bottom) o << e << ", " << brick_face(3) << "\n";
    o << fmt::format("*SURFACE, NAME=RING{}_INNER_TOP, TYPE=ELEMENT\n", i + 1);
    for (int e : top) o << e << ", " << brick_face(3) << "\n";
  }

  o << "*MATERIAL, NAME=RING_MATERIAL\n*ELASTIC\n" << num(mat.youngs_modulus_pa) << ", " << num(mat.poisson_ratio)
    << "\n*PLASTIC\n";
  for (const auto& h : mat.hardening) o << num(h.yield_stress_pa) << ", " << num(h.plastic_strain) << "\n";
  o << "*DENSITY\n" << num(mat.density_kg_m3) << "\n";
  o << "** strips: a rigid body's mass is the *MASS of its reference node, the elements' is negligible\n";
  o << "*MATERIAL, NAME=STRIP_MATERIAL\n*ELASTIC\n" << num(mat.youngs_modulus_pa) << ", " << num(mat.poisson_ratio)
    << "\n*DENSITY\n1\n";
  o << "*SOLID SECTION, ELSET=RINGS, MATERIAL=RING_MATERIAL\n";
  for (const auto& b : bodies) o << fmt::format("*SOLID SECTION, ELSET={}, MATERIAL=STRIP_MATERIAL\n", b.name);
  for (const auto& b : bodies)
    if (b.rigid)
      o << fmt::format("*MASS, ELSET={}_MASS\n{}\n*RIGID BODY, NSET={}_NODES, REF NODE={}, ROT NODE={}\n", b.name,
                       num(b.mass_kg), b.name, b.ref, b.rot);

  o << "** gap: clearance, direction (ring node toward the body), -, stiffness\n";
  for (const auto& g : gaps)
    o << fmt::format("*GAP, ELSET=GAP{}\n{}, 0, {}, 0, , {}\n", g.id, num(g.clearance), num(g.normal_y),
                     num(g.stiffness));
  o << "*BOUNDARY\nRING_FIXED_X, 1, 1\nRING_FRONT, 3, 3\n";
  for (const auto& b : bodies) {
    if (b.rigid) o << fmt::format("{}_REF, 1, 1\n{}_REF, 3, 3\n{}_ROT, 1, 3\n", b.name, b.name, b.name);
    else o << fmt::format("{}_NODES, 1, 3\n{}_REF, 1, 3\n", b.name, b.name);
  }
  o << "** the impactor (every node of the body and its reference node) moves toward the chain\n";
  o << "*INITIAL CONDITIONS, TYPE=VELOCITY\n"
    << fmt::format("IMPACTOR_NODES, 2, {}\nIMPACTOR_REF, 2, {}\n", num(-in.impactor_velocity_m_s),
                   num(-in.impactor_velocity_m_s));

  o << "*STEP, NLGEOM, INC=10000000\n";
  o << fmt::format("*DYNAMIC, ALPHA={}\n{}, {}, {}, {}\n", num(s.fe.hht_alpha), num(solver.initial_step_s),
                   num(solver.end_time_s), num(solver.min_step_s), num(solver.max_step_s));
  o << "*NODE PRINT, NSET=IMPACTOR_REF\nU, V\n";
  // The target's gaps end on its reference node: its reaction is the chain's force on the target.
  if (in.fixed_target) o << "*NODE PRINT, NSET=TARGET_REF\nRF\n";
  o << "*NODE FILE, FREQUENCY=100\nU, V\n*EL FILE, FREQUENCY=100\nS, PEEQ\n*END STEP\n";
  out.deck = o.str();

  std::ostringstream r;
  r << fmt::format("CalculiX deck of ringcrush scene {} ({})\n\n", s.name, s.title);
  r << fmt::format("Run:    ccx -i {}        (writes {}.dat, {}.frd)\n", s.name, s.name, s.name);
  r << fmt::format("Output: impactor reference node U, V (set IMPACTOR_REF, physical){}; forces of the chain = {:.6g} x "
                   "the deck's.\n\n",
                   in.fixed_target ? ", target reaction RF (set TARGET_REF)" : "", out.load_factor);
  r << fmt::format("Mapped: {} nodes, {} elements ({} ring {} on the ringcrush chain mesh, {} ring(s) x {} per half "
                   "ring x {} through); *DENSITY {} kg/m^3; impactor {} kg at {} m/s (physical; {:.6g} kg in the deck)\n",
                   out.nodes, out.elements, out.ring_elements, type, in.rings, in.mesh.elements_around,
                   in.mesh.elements_through, num(mat.density_kg_m3), num(in.impactor_mass_kg),
                   num(in.impactor_velocity_m_s), out.impactor_mass_kg);
  r << fmt::format("Contact: {} GAPUNI elements ({} rigid faces, {} ring to ring, {} inner wall)\n", out.gap_elements,
                   out.gap_elements - out.ring_ring_gaps - out.inner_wall_gaps, out.ring_ring_gaps,
                   out.inner_wall_gaps);
  r << "Approximations and what is not mapped:\n";
  for (const auto& a : out.approximations) r << "  - " << a << "\n";
  out.readme = r.str();
  return out;
}

}  // namespace ringcrush::compare
