// Two Test 30 rings of the Level 2 polygon chain (plane stress, N = 48, the thesis material's
// hardening and cap, near rate-independent flow), struck at 27.7 m/s: the small chain the
// polygon tests run; plates, when the joint has them, of 10 g and 2 mm.
#pragma once

#include <algorithm>
#include <cstddef>
#include <random>
#include <vector>

#include <Eigen/Dense>

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

// One Test 30 ring alone: no target, the impactor at rest (lift it off the ring, as the damper
// tests do, and the only velocity-dependent forces are the ring's Kelvin–Voigt dampers).
inline PolygonChainInput lone_ring(bool half) {
  PolygonChainInput in = input(PolygonJoint::Free);
  in.rings = 1;
  in.half_symmetry = half;
  in.fixed_target = false;
  in.impactor_velocity_m_s = 0.0;
  return in;
}

// Crush of ring `ring` of a polygon shape: outer diameter minus its extent along the chain
// axis (y) plus one wall (the shape holds the mean line).
inline double crush(const PolygonShape& s, int ring, const PolygonChainInput& in) {
  double lo = 1e300, hi = -1e300;
  for (const auto& p : s.nodes[ring]) {
    lo = std::min(lo, p[1]);
    hi = std::max(hi, p[1]);
  }
  return in.outer_diameter_m - (hi - lo + in.wall_thickness_m);
}

// Ring 1's node velocity rows of the state, the axis nodes' x left out (held at 0 by the
// symmetry plane in a half model): the rows the implicit damper and membrane solves act on.
inline std::vector<std::size_t> velocity_rows(const PolygonChain& chain) {
  std::vector<std::size_t> rows;
  const bool half = chain.input().half_symmetry;
  for (int j = 0; j < chain.independent_nodes(); ++j) {
    const auto o = chain.node_offset(0, j);
    if (!(half && (j == 0 || j == chain.independent_nodes() - 1))) rows.push_back(o + 2);
    rows.push_back(o + 3);
  }
  return rows;
}

// C read off the explicit damper forces: φ is linear in the node velocities through the
// dampers alone on a resting chain, so column m is −(φ(v = e_m) − φ(0)) on the velocity rows
// (the dense reference of the banded damper and membrane solves).
inline Eigen::MatrixXd damping_matrix(PolygonChain& chain, std::vector<double> y, const std::vector<std::size_t>& rows) {
  const auto n = static_cast<Eigen::Index>(rows.size());
  for (const auto i : rows) y[i] = 0.0;
  std::vector<double> phi0(y.size()), phi(y.size());
  chain.generalised_forces(0.0, y.data(), phi0.data());
  Eigen::MatrixXd C(n, n);
  for (Eigen::Index m = 0; m < n; ++m) {
    y[rows[static_cast<std::size_t>(m)]] = 1.0;
    chain.generalised_forces(0.0, y.data(), phi.data());
    y[rows[static_cast<std::size_t>(m)]] = 0.0;
    for (Eigen::Index i = 0; i < n; ++i)
      C(i, m) = -(phi[rows[static_cast<std::size_t>(i)]] - phi0[rows[static_cast<std::size_t>(i)]]);
  }
  return C;
}

// `rings` Test 30 rings two diameters apart, nothing touching (the impactor lifted 1 cm, no
// target): the only velocity-dependent forces are the rings' Kelvin–Voigt dampers (ratio 1).
inline PolygonChainInput apart(int rings, bool half) {
  PolygonChainInput in = input(PolygonJoint::Free);
  in.rings = rings;
  in.pitch_m = 2.0 * in.outer_diameter_m;
  in.half_symmetry = half;
  in.fixed_target = false;
  in.impactor_velocity_m_s = 0.0;
  return in;
}

// Every ring distorted at random (nodes moved by up to 0.3 ℓ0: all bar directions and hinge
// gradients differ) and moving at random (10 m/s); the axis nodes' x held.
inline std::vector<double> distorted(const PolygonChain& chain, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto y = chain.initial_state();
  y[chain.body_offset(0)] += 0.01;
  const bool half = chain.input().half_symmetry;
  for (int r = 0; r < chain.ring_count(); ++r)
    for (int j = 0; j < chain.independent_nodes(); ++j) {
      const auto o = chain.node_offset(r, j);
      const bool axis = half && (j == 0 || j == chain.independent_nodes() - 1);
      if (!axis) y[o] += 0.3 * chain.bar_length() * u(gen);
      y[o + 1] += 0.3 * chain.bar_length() * u(gen);
      y[o + 2] = axis ? 0.0 : 10.0 * u(gen);
      y[o + 3] = 10.0 * u(gen);
    }
  return y;
}

}  // namespace ringcrush::hinge::two_ring_chain
