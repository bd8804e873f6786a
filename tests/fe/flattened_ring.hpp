// Fixture of the inner wall's self-contact tests (self_contact_taper_test.cpp,
// side_point_contact_test.cpp; geometry as fold_contact_test.cpp): one 16-element half ring
// (Test 30, the matrix mesh) flattened by y → s·y, whose open side fold at C (φ = π/2) gives no
// contact by itself, and a point of its inner wall to press a node into.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "fe/chain/chain_mesh.hpp"
#include "fe/contact/ring_pair_contact.hpp"

namespace ringcrush::fe::fixture {

inline constexpr double kFlattening = 0.05;  // s

struct FlattenedRing {
  ChainTopology t;
  std::vector<Eigen::Vector2d> x;   // the flattened nodes
  std::vector<ContactPass> passes;  // the inner wall's self-contact passes
  double r = 0;                     // inner radius
  double k_scale = 0;               // penalty per unit tributary length
};

// two_pass = false: the one-sided pass (lower nodes on the upper wall), so a moved lower node
// is only a slave; true: the chain model's default, every inner node against the whole wall.
inline FlattenedRing make_flattened_ring(double taper_band, bool two_pass) {
  ChainInput in;
  in.rings = 1;
  in.mesh.elements_around = 16;
  in.mesh.half_ring = true;
  in.joints = JointKind::Free;
  FlattenedRing f{make_chain_topology(in), {}, {}, 0, 0};
  const RingMesh& ring = f.t.ring;
  f.k_scale = in.contact.penalty_scale * in.material.youngs_modulus_pa * in.ring.width_m / ring.element_depth;
  f.passes = inner_wall_passes(ring, f.t.ring_node[0], 0, f.k_scale, in.ring.width_m, in.contact.smoothing,
                               in.contact.self_contact_min_separation_rad, taper_band, two_pass);
  f.x = f.t.mesh.nodes;
  for (auto& p : f.x) p.y() *= kFlattening;
  f.r = ring.nodes[ring.inner_nodes.front()].norm();
  return f;
}

// A point a depth p inside the wall at parameter b of the flattened inner surface
// (r cos b, s r sin b): b > 0 on the upper leg (arc b past C), b < 0 on the lower leg; the
// ellipse's outward normal points into the wall's material.
inline Eigen::Vector2d inside_flattened_wall(double r, double b, double p) {
  const Eigen::Vector2d on_wall(r * std::cos(b), kFlattening * r * std::sin(b));
  const Eigen::Vector2d into(kFlattening * std::cos(b), std::sin(b));
  return on_wall + p * into.normalized();
}

}  // namespace ringcrush::fe::fixture
