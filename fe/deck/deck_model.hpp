// DeckModel: what an ABAQUS 4.8 deck (the thesis's Anexo I) defines, after every generation
// command (*NGEN, *NCOPY, *ELGEN, *ELCOPY) has been carried out: plain data, labels as in the
// deck, SI units as in the deck. Built by read_deck() (deck_reader.hpp); turned into ringcrush
// parameters by deck_parameters.hpp.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace ringcrush::fe::deck {

using Point = std::array<double, 3>;  // x, y, z; z = 0 for the plane decks

struct Node {
  Point x{};
  int line = 0;  // the line that defined or generated it
};

enum class ElementType { Cps8, Irs22, Isl22, Mass };
std::string to_string(ElementType);
// Nodes per element as written in the deck: CPS8 8; IRS22 3 on the deformable surface + the
// rigid-surface reference node; ISL22 3 (one quadratic slide-line segment); MASS 1.
int node_count(ElementType);

struct Element {
  ElementType type = ElementType::Cps8;
  std::vector<int> nodes;
  int line = 0;
};

// An ordered label set (*NSET, *ELSET, NSET=/ELSET= on generation keywords).
struct LabelSet {
  std::vector<int> labels;  // in the order first added, each once
  int line = 0;             // where the set was first defined
  std::set<int> members;    // the same labels, for membership tests
};

struct SolidSection {
  std::string elset, material;
  double thickness = 1.0;  // plane-stress thickness (the ring width)
  int line = 0;
};

struct HardeningPoint {
  double yield_stress = 0.0;
  double plastic_strain = 0.0;
};

struct Material {
  std::optional<double> youngs_modulus, poisson_ratio, density;
  std::vector<HardeningPoint> plastic;  // *PLASTIC table, flat after the last point
  int line = 0;
};

// *RIGID SURFACE, TYPE=SEGMENTS: a polyline (LINE) / arc (CIRCL) profile in the plane.
struct RigidSegment {
  std::string kind;     // "START", "LINE", "CIRCL"
  double x = 0, y = 0;  // end point
  double xc = 0, yc = 0;  // CIRCL centre
};
struct RigidSurface {
  std::string elset;  // the IRS22 elements that see this surface
  std::vector<RigidSegment> segments;
  int line = 0;
};

// *INTERFACE with its sub-options *FRICTION and *SURFACE CONTACT (softened contact: the
// pressure grows from 0 at clearance c0 to p0 at zero clearance; thesis §4.2 used it for the
// plates to damp chatter).
struct Interface {
  std::string elset;
  double thickness = 1.0;
  std::optional<double> friction;
  std::optional<double> softened_clearance, softened_pressure;
  int line = 0;
};

// *SLIDE LINE: the node line (ISL22's partner) and the Hermite junction smoothing (§3.6.3).
struct SlideLine {
  std::string elset;      // the ISL22 elements on the other surface
  std::string type;       // LINEAR or PARABOLIC
  double smooth = 0.2;    // ABAQUS default
  std::vector<int> nodes;
  int line = 0;
};

// *MPC: type as written ("5" is a numbered user MPC in ABAQUS 4.8; names such as TIE are
// built-in types) and the node list.
struct Mpc {
  std::string type;
  std::vector<int> nodes;
  int line = 0;
};

// One degree-of-freedom constraint from *BOUNDARY, set names and symmetry names expanded:
// dofs first..last (1, 2 translations; 6 the in-plane rotation of a rigid-surface reference
// node) held at `value` (0 unless a magnitude is given).
struct Constraint {
  int node = 0;
  int first_dof = 0, last_dof = 0;
  double value = 0.0;
  std::string written;  // the symbolic type as written (XSYMM, ENCASTRE...) or ""
  int line = 0;
};

struct InitialVelocity {
  int node = 0, dof = 0;
  double value = 0.0;
  int line = 0;
};

struct PointMass {
  std::string elset;  // MASS elements
  double mass = 0.0;
  int line = 0;
};

// An output request, kept with what ringcrush does with it (see deck_outputs.cpp).
struct OutputRequest {
  std::string keyword;                 // e.g. "NODE PRINT"
  std::vector<std::string> variables;  // data-line entries, e.g. U, RF
  std::string mapped_to;               // the ringcrush output, "" if ignored
  std::string reason;                  // why it maps or why it is ignored
  int line = 0;
};

enum class Procedure { None, Static, Dynamic };

struct Step {
  int line = 0;
  bool nlgeom = false;
  std::optional<int> max_increments;  // INC
  std::optional<int> max_iterations;  // CYCLE (equilibrium iterations per increment)
  bool submax = false;
  Procedure procedure = Procedure::None;
  int procedure_line = 0;
  // *STATIC: initial increment, step period, minimum, maximum increment.
  // *DYNAMIC: initial time step, time period, minimum, maximum step.
  std::optional<double> initial_increment, period, min_increment, max_increment;
  std::optional<double> ptol, haftol, alpha;
  std::optional<int> max_contact_changes;   // *CONTROL INTERFACES, MAXCHP
  std::optional<double> contact_error;      // *CONTROL INTERFACES, UERRMX
  std::vector<Constraint> boundaries;       // *BOUNDARY inside the step
  std::vector<OutputRequest> outputs;
  bool ended = false;
};

struct DeckModel {
  std::string heading;
  std::map<int, Node> nodes;
  std::map<int, Element> elements;
  std::map<std::string, LabelSet> nsets, elsets;
  std::vector<SolidSection> sections;
  std::map<std::string, Material> materials;
  std::vector<RigidSurface> rigid_surfaces;
  std::vector<Interface> interfaces;
  std::vector<SlideLine> slide_lines;
  std::vector<Mpc> mpcs;
  std::vector<Constraint> boundaries;  // model data (before the first *STEP)
  std::vector<InitialVelocity> initial_velocities;
  std::vector<PointMass> masses;
  std::vector<OutputRequest> outputs;  // model-level requests (*PLOT, *RESTART...)
  std::vector<Step> steps;
};

}  // namespace ringcrush::fe::deck
