// ChainInput: everything the FE needs to run one ring chain under impact (issue 4, thesis
// §3.5, §4.2; seed/thesis_dynamic.inp), as plain data. compare/ builds it from a Scene.
// SI units. The chain axis is y: ring 1 on top, centred at y = 0, ring i at y = −(i−1)·pitch;
// the impactor comes down from +y onto ring 1, the target (if any) lies under the last ring.
#pragma once

#include "fe/dynamics/mass_scaling.hpp"
#include "fe/fe_input.hpp"

namespace ringcrush::fe {

enum class JointKind {
  Welded,  // neighbours share their touching node (the thesis's *MPC ties): exact constraint
  Free,    // contact only
  Plates,  // a rigid plate (one y dof, with mass) between each pair of neighbours
};

// The explicit stable step's ω_max (chain_model.hpp, stable_step): Element = the element
// eigenvalue inequality, a guaranteed upper bound (≈ 1.2× ω_max on the thesis chain);
// Assembled = a power-iteration estimate of the assembled system's ω_max² times
// step_bound_margin, never above the element bound (fe/dynamics/assembled_eigenvalue.hpp).
enum class StepBound { Element, Assembled };

struct ChainInput {
  int rings = 6;
  RingInput ring;            // every ring is the same (Reid & Reddy chains)
  MaterialInput material;
  double density_kg_m3 = 7850.0;
  MeshInput mesh;            // mesh.half_ring: the thesis's x = 0 symmetry model
  Integration integration = Integration::Reduced;
  ContactInput contact;      // penalty scale and smoothing also used ring↔ring and ring↔plate
  // Distance between neighbouring ring centres: 2·outer radius for welded and free chains
  // (touching), 2·outer radius + plate thickness for plates.
  double pitch_m = 0.0508;
  JointKind joints = JointKind::Welded;
  double plate_mass_kg = 0.0;        // plates only: physical (full) mass of one plate
  double plate_thickness_m = 0.0;    // plates only
  double impactor_mass_kg = 0.256;   // physical (full) mass; a half model carries half
  double impactor_velocity_m_s = 30; // toward the chain (> 0)
  bool fixed_target = true;          // rigid plane under the last ring; false: free far end
  // Linear bulk viscosity b1 (fe/element/bulk_viscosity.hpp): explicit driver only (HHT damps
  // the high modes itself), fraction of critical damping of each element's highest mode,
  // in [0, 1); 0 = none. The scene default is ABAQUS/Explicit's 0.06.
  double bulk_viscosity = 0.0;
  // Threads for the element loop (chain_model.cpp): 0 = automatic (two when the machine has
  // two idle cores and the chain at least 64 elements), 1 = one, 2 = two. The results are
  // bitwise the same either way.
  int threads = 0;
  // A penalty that does not shorten the explicit step (fe/contact/penalty_step_cap.hpp): > 0
  // lowers contact.penalty_scale, uniformly, until the stiffest contact spring costs at most
  // this fraction of the element step (in (0, 0.5]); 0 = off, the penalty scale as given.
  double contact_penalty_step_fraction = 0.0;
  StepBound step_bound = StepBound::Element;
  double step_bound_margin = 1.05;  // Assembled: ω² = margin · θ, in [1, 2]
  // Explicit only, off by default: fixed mass scaling (fe/dynamics/mass_scaling.hpp), a
  // change of the physics; run_dynamic refuses it with HHT.
  MassScaling mass_scaling;
};

// Throws std::invalid_argument naming the first inconsistent value.
void validate(const ChainInput& input);

}  // namespace ringcrush::fe
