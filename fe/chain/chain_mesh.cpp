#include "fe/chain/chain_mesh.hpp"

#include <algorithm>
#include <numbers>

namespace ringcrush::fe {

ChainTopology make_chain_topology(const ChainInput& input) {
  validate(input);
  ChainTopology t;
  t.ring = make_ring_mesh(input.ring, input.mesh);
  const RingMesh& r = t.ring;
  ChainMesh& m = t.mesh;
  m.half_ring = r.half_ring;
  const int local_nodes = static_cast<int>(r.nodes.size());
  const double radius = input.ring.outer_radius_m;
  const double pi = std::numbers::pi;
  std::vector<int> fixed_nodes;
  for (int i = 0; i < input.rings; ++i) {
    const double yc = -i * input.pitch_m;
    m.ring_centre_y.push_back(yc);
    std::vector<int> map(local_nodes, -1);
    for (int a = 0; a < local_nodes; ++a) {
      if (input.joints == JointKind::Welded && i > 0 && a == r.top_node) {
        // The weld: this ring's top outer point IS the previous ring's bottom outer point.
        map[a] = t.ring_node[i - 1][r.bottom_node];
        continue;
      }
      map[a] = static_cast<int>(m.nodes.size());
      m.nodes.emplace_back(r.nodes[a].x(), r.nodes[a].y() + yc);
    }
    for (const auto& e : r.elements) {
      std::array<int, 8> g{};
      for (int k = 0; k < 8; ++k) g[k] = map[e[k]];
      m.elements.push_back(g);
      m.element_ring.push_back(i);
    }
    for (int a : r.fixed_x) fixed_nodes.push_back(map[a]);
    // Outer nodes by θ = π − φ from the top apex: the mesher runs counter-clockwise in φ from
    // the bottom, so walk it backwards from the top node (and on round for a full ring).
    std::vector<std::pair<double, int>> outer;
    for (int a : r.outer_nodes) {
      double theta = pi - r.node_angle[a];
      if (theta < 0) theta += 2 * pi;
      if (theta >= 2 * pi) theta -= 2 * pi;
      outer.emplace_back(theta, map[a]);
    }
    std::sort(outer.begin(), outer.end());
    std::vector<int> ids;
    std::vector<double> theta;
    for (const auto& [th, id] : outer) {
      theta.push_back(th);
      ids.push_back(id);
    }
    m.ring_outer_nodes.push_back(ids);
    m.ring_outer_theta.push_back(theta);
    t.ring_node.push_back(std::move(map));
  }
  // Rigid bodies: x fixed, y carries the body.
  m.impactor_node = static_cast<int>(m.nodes.size());
  m.nodes.emplace_back(0.0, radius);
  fixed_nodes.push_back(m.impactor_node);
  if (input.joints == JointKind::Plates) {
    t.plate_half_thickness = 0.5 * input.plate_thickness_m;
    for (int k = 0; k + 1 < input.rings; ++k) {
      m.plate_nodes.push_back(static_cast<int>(m.nodes.size()));
      m.nodes.emplace_back(0.0, m.ring_centre_y[k] - radius - t.plate_half_thickness);
      fixed_nodes.push_back(m.plate_nodes.back());
    }
  }
  t.target_y = m.ring_centre_y.back() - radius;
  std::sort(fixed_nodes.begin(), fixed_nodes.end());
  fixed_nodes.erase(std::unique(fixed_nodes.begin(), fixed_nodes.end()), fixed_nodes.end());
  for (int n : fixed_nodes) t.fixed_dofs.push_back(2 * n);
  return t;
}

}  // namespace ringcrush::fe
