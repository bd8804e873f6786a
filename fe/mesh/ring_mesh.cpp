#include "fe/mesh/ring_mesh.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

namespace ringcrush::fe {

std::vector<double> graded_angles(int elements, double span, double grading) {
  // Element size h(φ) ∝ 1 + (g − 1) sin²(2φ): finest at φ = 0, π/2, π, … (contacts and
  // sides), g times coarser half-way. Corners at equal increments of s(φ) = ∫ dφ / h.
  const int samples = 4000 * std::max(1, elements / 8);
  std::vector<double> s(samples + 1, 0.0);
  auto inv_h = [&](double phi) {
    const double v = std::sin(2 * phi);
    return 1.0 / (1.0 + (grading - 1.0) * v * v);
  };
  const double dphi = span / samples;
  for (int k = 0; k < samples; ++k)
    s[k + 1] = s[k] + 0.5 * dphi * (inv_h(k * dphi) + inv_h((k + 1) * dphi));
  std::vector<double> out(elements + 1);
  out[0] = 0;
  out[elements] = span;
  int k = 0;
  for (int i = 1; i < elements; ++i) {
    const double target = s[samples] * i / elements;
    while (s[k + 1] < target) ++k;
    out[i] = (k + (target - s[k]) / (s[k + 1] - s[k])) * dphi;
  }
  return out;
}

RingMesh make_ring_mesh(const RingInput& ring, const MeshInput& in) {
  if (in.elements_around < 2 || in.elements_around % 2 != 0)
    throw std::invalid_argument("mesh: elements_around (per half ring) must be even and ≥ 2");
  if (in.elements_through < 1) throw std::invalid_argument("mesh: elements_through must be ≥ 1");
  if (!(in.grading >= 1.0)) throw std::invalid_argument("mesh: grading must be ≥ 1");
  if (!(ring.inner_radius_m > 0 && ring.outer_radius_m > ring.inner_radius_m))
    throw std::invalid_argument("mesh: need 0 < inner radius < outer radius");

  RingMesh m;
  m.half_ring = in.half_ring;
  const double pi = std::numbers::pi;
  const int ne = in.half_ring ? in.elements_around : 2 * in.elements_around;
  const int nt = in.elements_through;
  const std::vector<double> half = graded_angles(in.elements_around, pi, in.grading);
  std::vector<double> corner(half);
  if (!in.half_ring)
    for (int i = 1; i <= in.elements_around; ++i) corner.push_back(pi + half[i]);
  // Node columns: 2 per element around (corner, mid-side); a full ring wraps around.
  const int columns = in.half_ring ? 2 * ne + 1 : 2 * ne;
  const int rows = 2 * nt + 1;  // row 0 outer surface, row 2 nt inner surface
  auto column_angle = [&](int c) {
    const int i = c / 2;
    return c % 2 == 0 ? corner[i] : 0.5 * (corner[i] + corner[i + 1]);
  };
  const double thick = ring.outer_radius_m - ring.inner_radius_m;
  std::map<std::pair<int, int>, int> id;
  for (int c = 0; c < columns; ++c)
    for (int r = 0; r < rows; ++r) {
      if (c % 2 == 1 && r % 2 == 1) continue;  // serendipity: no centre node
      const double phi = column_angle(c);
      const double rad = ring.outer_radius_m - thick * r / (2.0 * nt);
      id[{c, r}] = static_cast<int>(m.nodes.size());
      // Nodes on the axis get x exactly 0 (symmetry plane).
      const double x = (std::abs(phi) < 1e-14 || std::abs(phi - pi) < 1e-14) ? 0.0 : rad * std::sin(phi);
      m.nodes.emplace_back(x, -rad * std::cos(phi));
      m.node_angle.push_back(phi);
    }
  auto node = [&](int c, int r) { return id.at({c % columns, r}); };
  for (int i = 0; i < ne; ++i)
    for (int j = 0; j < nt; ++j) {
      const int c0 = 2 * i, r0 = 2 * j;
      // g along φ, h from the outer toward the inner face (counter-clockwise, deck order).
      m.elements.push_back({node(c0, r0), node(c0 + 2, r0), node(c0 + 2, r0 + 2), node(c0, r0 + 2),
                            node(c0 + 1, r0), node(c0 + 2, r0 + 1), node(c0 + 1, r0 + 2), node(c0, r0 + 1)});
    }
  m.element_depth = thick / nt;

  // Surfaces with consistent tributary lengths ∫ N_a ds (1/6, 2/3, 1/6 of an arc edge).
  auto arc = [&](double rad, int i) { return rad * (corner[i + 1] - corner[i]); };
  for (int c = 0; c < columns; ++c) {
    m.outer_nodes.push_back(node(c, 0));
    m.inner_nodes.push_back(node(c, rows - 1));
  }
  m.outer_weight.assign(columns, 0.0);
  m.inner_weight.assign(columns, 0.0);
  for (int i = 0; i < ne; ++i) {
    for (auto [rad, w] : {std::pair{ring.outer_radius_m, &m.outer_weight}, {ring.inner_radius_m, &m.inner_weight}}) {
      const double l = arc(rad, i);
      (*w)[(2 * i) % columns] += l / 6;
      (*w)[(2 * i + 1) % columns] += 2 * l / 3;
      (*w)[(2 * i + 2) % columns] += l / 6;
    }
    // Inner face of the element of the last layer (element index i * nt + nt − 1).
    m.inner_segments.push_back({{node(2 * i, rows - 1), node(2 * i + 1, rows - 1), node(2 * i + 2, rows - 1)},
                                i * nt + nt - 1});
  }
  m.bottom_node = node(0, 0);
  m.top_node = node(2 * in.elements_around, 0);
  if (in.half_ring) {
    for (int r = 0; r < rows; ++r) {
      m.fixed_x.push_back(node(0, r));
      m.fixed_x.push_back(node(columns - 1, r));
    }
  } else {
    // Frictionless plates leave the horizontal translation and the rotation of a full ring
    // free: hold u_x of the two outer points on the loading axis (zero reaction by symmetry).
    m.fixed_x = {m.bottom_node, m.top_node};
  }
  return m;
}

}  // namespace ringcrush::fe
