// The Test 30 ring as a rigid-perfectly-plastic Level 3 ring, and its uniformly crushed shape:
// shared by the statics-check tests with and without ring inertia, and their plated chain; and
// Test 30's six-ring chain with the hardening ring (the inertia tests).
#pragma once

#include "chain_fixtures.hpp"
#include "hinge/level3_mechanism.hpp"

namespace ringcrush::hinge::testing {

inline const Level3Ring kLevel3Ring{0.0508, 0.0016, 2.184, 0.0};  // Test 30 ring, no hardening

// A ring crushed uniformly (DeRuntz–Hodge) to quadrant angle φ, drawn with n points a quadrant.
inline Level3Shape uniform_shape(double phi, int n = 48) {
  Level3RingResult s;
  s.uniform_angle = phi;
  return level3_ring_shape(kLevel3Ring, WrapMechanism{}, s, 0.0, n);
}

// Three such rings between rigid plates, struck by Test 30's 0.257 kg at 20 m/s (massless rings
// unless the test sets `inertia`).
inline Level3Input plated_three_rings() {
  Level3Input in;
  in.rings = 3;
  in.ring = kLevel3Ring;
  in.plates = true;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = 20.0;
  return in;
}

// Test 30's chain (six rings, 0.257 kg) of the hardening ring of chain_fixtures.hpp (the same
// M0, k and mass) at `velocity`; the rings carry their mass when `inertia` is set.
inline Level3Input test30_level3_chain(double velocity, bool plates, bool inertia) {
  const RingLaw law = test30_ring();
  Level3Input in;
  in.rings = 6;
  in.ring = {law.outer_diameter_m, law.wall_thickness_m, law.plastic_moment_nm, law.hardening_k()};
  in.plates = plates;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = velocity;
  in.inertia = inertia;
  in.ring_mass_kg = inertia ? law.mass_kg : 0.0;
  return in;
}

}  // namespace ringcrush::hinge::testing
