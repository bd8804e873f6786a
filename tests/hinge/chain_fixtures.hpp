// Test 30 ring chain (THEORY §3.1 Table 2, §5) as plain hinge inputs, shared by the tests.
#pragma once

#include "hinge/chain_1d.hpp"
#include "hinge/ring_laws.hpp"

namespace ringcrush::hinge::testing {

inline RingLaw test30_ring(double hardening_modulus = 2.2e9, double alpha = 2.0) {
  const RingSection s{0.0508, 0.0016, 0.0125};
  RingLaw r;
  r.outer_diameter_m = s.outer_diameter_m;
  r.wall_thickness_m = s.wall_thickness_m;
  r.plastic_moment_nm = plastic_moment(s, 273e6, SectionState::PlaneStress);
  r.hardening_modulus_pa = hardening_modulus;
  r.yield_stress_pa = 273e6;
  r.redwood_alpha = alpha;
  r.elastic_stiffness_n_m = elastic_stiffness(s, 202e9, 0.3, SectionState::PlaneStress);
  r.lock_stiffness_n_m = 50.0 * r.elastic_stiffness_n_m;
  r.mass_kg = ring_mass(s, 7850.0);
  return r;
}

inline ChainInput test30_chain(ChainJoint joint, ChainFarEnd end = ChainFarEnd::Fixed,
                               double hardening_modulus = 2.2e9) {
  ChainInput in;
  in.rings = 6;
  in.ring = test30_ring(hardening_modulus);
  in.joint = joint;
  in.plate_mass_kg = joint == ChainJoint::Plates ? 0.010 : 0.0;
  in.far_end = end;
  in.impactor_mass_kg = 0.257;
  in.impactor_velocity_m_s = 27.7;
  return in;
}

inline HybridOptions tight(HybridIntegrator integrator, double rtol = 1e-10, double atol = 1e-12) {
  HybridOptions o;
  o.integrator = integrator;
  o.relative_tolerance = rtol;
  o.absolute_tolerance = atol;
  o.end_time = 0.05;
  return o;
}

}  // namespace ringcrush::hinge::testing
