#include "compare/calculix_slab.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "compare/calculix_deck_parts.hpp"

namespace ringcrush::compare::calculix_parts {

int Slab::nodes() const {
  int c = 0;
  for (bool b : corner) c += b ? 1 : 0;
  return 2 * plane_nodes + c;
}

std::vector<int> Slab::through(const std::vector<int>& ids) const {
  std::vector<int> out;
  for (int n : ids) {
    out.push_back(front(n));
    out.push_back(back(n));
    if (corner.at(static_cast<std::size_t>(n - 1))) out.push_back(middle(n));
  }
  return out;
}

Slab make_slab(int plane_nodes, const std::vector<std::array<int, 8>>& elements, double thickness) {
  if (!(thickness > 0)) throw std::invalid_argument(fmt::format("calculix slab: thickness {} must be > 0", thickness));
  Slab s;
  s.plane_nodes = plane_nodes;
  s.thickness = thickness;
  s.corner.assign(static_cast<std::size_t>(plane_nodes), false);
  for (const auto& e : elements)
    for (int a = 0; a < 4; ++a) s.corner.at(static_cast<std::size_t>(e[static_cast<std::size_t>(a)])) = true;
  return s;
}

void write_slab_nodes(std::ostringstream& o, const Slab& slab, const std::vector<Eigen::Vector2d>& xy) {
  if (static_cast<int>(xy.size()) != slab.plane_nodes)
    throw std::invalid_argument(fmt::format("calculix slab: {} points for {} nodes", xy.size(), slab.plane_nodes));
  o << "*NODE, NSET=NALL\n";
  const std::string z_back = num(slab.thickness), z_mid = num(0.5 * slab.thickness);
  for (int n = 1; n <= slab.plane_nodes; ++n) {
    const auto& p = xy[static_cast<std::size_t>(n - 1)];
    o << fmt::format("{}, {}, {}, 0\n", slab.front(n), num(p.x()), num(p.y()));
  }
  for (int n = 1; n <= slab.plane_nodes; ++n) {
    const auto& p = xy[static_cast<std::size_t>(n - 1)];
    o << fmt::format("{}, {}, {}, {}\n", slab.back(n), num(p.x()), num(p.y()), z_back);
  }
  for (int n = 1; n <= slab.plane_nodes; ++n)
    if (slab.corner[static_cast<std::size_t>(n - 1)]) {
      const auto& p = xy[static_cast<std::size_t>(n - 1)];
      o << fmt::format("{}, {}, {}, {}\n", slab.middle(n), num(p.x()), num(p.y()), z_mid);
    }
}

void write_bricks(std::ostringstream& o, const std::string& elset, const std::string& type, const Slab& slab,
                  const std::vector<std::array<int, 8>>& elements, int first_element) {
  o << "*ELEMENT, TYPE=" << type << ", ELSET=" << elset << "\n";
  int id = first_element;
  for (const auto& q : elements) {
    std::array<int, 20> b{};
    for (int a = 0; a < 4; ++a) {
      const int n = q[static_cast<std::size_t>(a)] + 1, m = q[static_cast<std::size_t>(a + 4)] + 1;
      b[static_cast<std::size_t>(a)] = slab.front(n);
      b[static_cast<std::size_t>(a + 4)] = slab.back(n);
      b[static_cast<std::size_t>(a + 8)] = slab.front(m);
      b[static_cast<std::size_t>(a + 12)] = slab.back(m);
      b[static_cast<std::size_t>(a + 16)] = slab.middle(n);
    }
    o << id++;
    for (std::size_t a = 0; a < 20; ++a) o << (a == 15 ? ",\n" : ", ") << b[a];
    o << "\n";
  }
}

std::string brick_face(int cps8_face) {
  if (cps8_face < 1 || cps8_face > 4) throw std::invalid_argument(fmt::format("calculix slab: CPS8 face {}", cps8_face));
  return fmt::format("S{}", cps8_face + 2);
}

}  // namespace ringcrush::compare::calculix_parts
