// A scene as a CalculiX (ccx 2.20) input deck (issue 5 item 3), so a user can cross-check
// ringcrush's FE with another code on the SAME mesh: `ringcrush export-calculix SCENE -o DIR`
// writes DIR/<scene>.inp and DIR/README.txt (what was mapped, what was approximated).
//
// Static scenes (one ring between rigid plates, thesis Anexo I): the ring mesh of
// fe/mesh/ring_mesh (CPS8; section thickness below), *MATERIAL with *ELASTIC and the
// scene's *PLASTIC table, each rigid plate a strip of CPS8 elements every node of which
// carries the plate's motion (bottom: held; top: the crush as *BOUNDARY in a *STATIC,
// NLGEOM step), the outer ring surface against each plate face and the inner wall near the
// bottom against the inner wall near the top (lock-up) as surface-to-surface *CONTACT PAIRs
// (node-to-surface diverged at the onset of the inner-wall contact) with a linear penalty of
// the same stiffness per unit area ringcrush uses
// (fe_input.hpp ContactInput: k = scale · E · w L / h per node ⇒ pressure / overclosure =
// scale · E / h), the x = 0 symmetry of a half model, and *NODE PRINT of the driven plate's
// total reaction (RF, TOTALS=ONLY) and of its reference node's U.
//
// Plane stress: ccx has no σ_zz = 0 element; it expands a CPS8 into a one-layer C3D20 slab
// as thick as the section. A slab as wide as the ring (L = 12.5 mm ≈ 8 wall thicknesses for
// the thesis ring) bends like a wide plate, toward plane strain (measured with ccx 2.20 on
// the thesis ring, 22x1 mesh: elastic stiffness 426.9 N/mm against 390.3 N/mm for a thin
// slab and 389.1 N/mm in closed form, load at δ/d = 0.3 +18 % against the thin slab). The
// plane-stress model of the thesis (§3.6.1) and of ringcrush is therefore written as a thin
// slab, s = t/10, and the ring's load is L/s times the slab's (CalculixDeck::load_factor);
// CalculixSection::FullWidth writes s = L instead (the 3-D wide-ring response).
// CalculixPlates::RigidBodies writes the plates as *RIGID BODY strips, the deck in 20-node
// bricks (calculix_slab.hpp): ccx prints no reaction at a rigid body of CPS8.
//
// Dynamic scenes (a chain hit by an impactor, thesis §3.5, §4.2) go to calculix_chain_deck
// (compare/calculix_chain_export.cpp): ccx 2.20 cannot carry them as CPS8 (a rigid impactor of
// 2-D elements, *RIGID BODY or *EQUATION-tied to a *MASS node, made *DYNAMIC diverge at its
// second increment, and an *INITIAL CONDITIONS velocity on CPS8 nodes is reported but never
// moves them: ccx expands them to 3-D and the velocity stays on the 2-D nodes), so the chain is
// written as one layer of C3D20(R) bricks through the same thin slab (compare/calculix_slab.hpp),
// u_z = 0 on one face, the impactor a *RIGID BODY strip of bricks with its mass on the reference
// node and the impact velocity on every node of the body.
#pragma once

#include <string>
#include <vector>

#include "compare/scene.hpp"

namespace ringcrush::compare {

enum class CalculixSection {
  PlaneStressSlab,  // section thickness t/10: the slab is in plane stress (default)
  FullWidth,        // section thickness = ring width: ccx's 3-D slab of the real ring
};

enum class CalculixPlates {
  Strips,       // CPS8 strips every node of which carries the plate's motion (default)
  RigidBodies,  // the whole deck in 20-node bricks, each plate a *RIGID BODY driven at its reference node
};

struct CalculixDeck {
  std::string deck;    // the .inp text
  std::string readme;  // README.txt: the command, what is mapped, what is approximated
  int nodes = 0;       // all nodes (ring + plates)
  int elements = 0;    // all elements (ring + plates)
  int ring_nodes = 0, ring_elements = 0;
  int driven_reference_node = -1;  // 1-based node id of the driven plate's reference node
  std::string reaction_set;        // static: the node set whose total RF is the plate's load
  double symmetry_factor = 1.0;    // 2 for a half model
  double section_thickness_m = 0;  // the *SOLID SECTION thickness written
  // Whole-ring load = load_factor × the driven plate's total reaction printed by ccx
  // (symmetry_factor × ring width / section thickness).
  double load_factor = 1.0;
  std::vector<std::string> approximations;  // also listed in the README
  // Brick decks (dynamic chains, static --rigid-plates):
  bool dynamic = false;
  std::string ring_element_type;            // C3D20R (reduced) or C3D20
  double impactor_mass_kg = 0;              // the deck's (physical / load_factor)
  double impactor_velocity_m_s = 0;         // physical, toward the chain
  int gap_elements = 0;                     // all GAPUNI elements (contact, see calculix_chain_export.cpp)
  int ring_ring_gaps = 0, inner_wall_gaps = 0;  // of which ring↔ring and inner wall
};

// Throws std::invalid_argument naming the scene feature the deck cannot carry (the same
// refusals as `ringcrush fe`: plane strain, friction, a static chain). A dynamic scene is
// written by calculix_chain_deck.
CalculixDeck calculix_deck(const Scene& scene, CalculixSection section = CalculixSection::PlaneStressSlab,
                           CalculixPlates plates = CalculixPlates::Strips);

// A dynamic scene (ring chain, welded / free / plated joints) as a ccx *DYNAMIC deck of 20-node
// bricks; the same refusals as `ringcrush fe` on the scene. nodes / elements count the bricks
// (ring elements = ringcrush's CPS8 count; ring nodes = 2 × 2-D nodes + corner nodes).
CalculixDeck calculix_chain_deck(const Scene& scene, CalculixSection section = CalculixSection::PlaneStressSlab);

// Total reaction force (fx, fy) of the node set `nset` at each time printed in a ccx .dat
// file ("total force (fx,fy,fz) for set NSET and time T" blocks of *NODE PRINT, TOTALS=ONLY).
struct CcxTotalForce {
  double time, fx, fy;
};
std::vector<CcxTotalForce> parse_ccx_total_forces(const std::string& dat_text, const std::string& nset);

// The vector of the first node of set `nset` at each time printed in a ccx .dat file, for
// `quantity` "displacements" or "velocities" ("<quantity> (vx,vy,vz) for set NSET and time T"
// blocks of *NODE PRINT, U or V); the dynamic deck prints the impactor's at IMPACTOR_REF.
struct CcxNodeVector {
  double time, x, y, z;
};
std::vector<CcxNodeVector> parse_ccx_node_vectors(const std::string& dat_text, const std::string& quantity,
                                                  const std::string& nset);

}  // namespace ringcrush::compare
