// Two Test 30 rings of the Level 2 polygon chain (plane stress, N = 48, the thesis material's
// hardening and cap, near rate-independent flow), struck at 27.7 m/s: the small chain the
// polygon tests run; plates, when the joint has them, of 10 g and 2 mm.
#pragma once

#include "hinge/polygon_chain.hpp"

namespace ringcrush::hinge::two_ring_chain {

inline PolygonChainInput input(PolygonJoint joint) {
  PolygonChainInput in;
  in.rings = 2;
  in.nodes_per_ring = 48;
  in.joint = joint;
  in.plate_mass_kg = 0.01;
  in.plate_thickness_m = 0.002;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = 27.7;
  in.hardening_modulus_pa = 2.2e9;
  in.yield_cap_ratio = 320.0 / 273.0;
  in.redwood_alpha = 2.0;
  in.cowper_symonds_d_per_s = 1e4;
  in.cowper_symonds_q = 1.0;
  in.membrane_damping_ratio = 1.0;
  in.hinge_damping_ratio = 1.0;
  return in;
}

}  // namespace ringcrush::hinge::two_ring_chain
