// From a deck to the ringcrush description of the same problem (issue 5 item 2): the ring
// geometry read off the generated nodes, the element counts, the material, the loading and
// the solver controls, so that compare/ can build a Scene and run the deck through the same
// FE path as the TOML scenes (data/scenes/thesis_*.toml). This is the seam for
// `ringcrush fe DECK.inp`.
//
// What is recognised (the thesis decks, Anexo I): every CPS8 element belongs to a ring; rings
// are found as groups of elements around a common centre; a rigid surface whose reference
// node carries a MASS element and an initial velocity is the impactor; one whose reference
// node is ENCASTRE'd is the fixed target; one whose reference node is driven by a step
// *BOUNDARY magnitude is the static crushing plate. Anything else is a std::invalid_argument
// naming what does not fit.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fe/deck/deck_model.hpp"

namespace ringcrush::fe::deck {

// One ring found in the mesh: its centre and radii, its elements.
struct DeckRing {
  Point centre{};
  double inner_radius = 0.0, outer_radius = 0.0;
  std::vector<int> elements;  // CPS8 labels
  std::vector<int> nodes;     // every node of those elements
};

struct DeckParameters {
  std::string heading;
  // Geometry (rings ordered from the impacted end: ring 1 has the highest centre y).
  std::vector<DeckRing> rings;
  double outer_radius_m = 0.0, inner_radius_m = 0.0;
  double width_m = 0.0;   // *SOLID SECTION thickness (plane stress)
  double pitch_m = 0.0;   // centre distance; 2·outer radius for a single ring
  bool half_model = false;  // all ring nodes on x ≥ centre x (the thesis's XSYMM model)
  int elements_around = 0;  // per modelled part of one ring (half ring for a half model)
  int elements_through = 0;
  double grading = 1.0;     // largest / smallest element angle around the ring
  // Ring 1's element boundaries around the ring, radians, measured counter-clockwise from the
  // bottom point (φ = 0 at −y, π/2 at +x, π at the top): the deck's exact grading, for a mesh
  // built from the parameters (the thesis static deck: blocks of 5.625° and 11.25°, which the
  // smooth grading law of fe/mesh only approximates).
  std::vector<double> boundary_angles;
  bool welded = false;      // *MPC ties between coincident nodes of neighbouring rings
  int ring_ties = 0, internal_ties = 0;  // MPCs between rings / within one ring
  // Material.
  double youngs_modulus_pa = 0.0, poisson_ratio = 0.0;
  std::optional<double> density_kg_m3;
  std::vector<HardeningPoint> hardening;
  // Contact.
  std::optional<double> contact_smoothing;  // SMOOTH of the slide lines (all equal)
  double friction_coefficient = 0.0;
  std::optional<double> softened_clearance_m, softened_pressure_pa;
  int slide_lines = 0, rigid_surfaces = 0;
  // Loading.
  bool dynamic = false;
  bool fixed_target = false;
  double crush_m = 0.0;                    // static: driven-plate travel
  std::optional<double> impactor_mass_kg;  // physical mass (×2 for a half model)
  std::optional<double> impactor_velocity_m_s;  // toward the chain, > 0
  // Solver controls (thesis §3.4, §3.5).
  std::optional<double> ptol_n, haftol_n, hht_alpha;
  double initial_increment = 0.0;  // static: fraction of the step; dynamic: seconds
  double period = 0.0;             // step time period (dynamic: end time, s)
  std::optional<double> min_increment, max_increment;  // as initial_increment
  std::optional<int> max_iterations, max_increments;   // CYCLE, INC
};

DeckParameters deck_parameters(const DeckModel& model);

}  // namespace ringcrush::fe::deck
