// A 2-D CPS8 mesh as one layer of 20-node bricks (C3D20 / C3D20R) through z ∈ [0, s], for the
// CalculiX dynamic deck (compare/calculix_export.hpp). ccx 2.20 expands CPS8 itself, but an
// *INITIAL CONDITIONS velocity on CPS8 nodes never reaches the expanded nodes and a *RIGID
// BODY of expanded elements diverges; written as explicit bricks both work (measured: a rigid
// C3D8 block at 30 m/s moves 3.000 mm in 0.1 ms).
//
// Numbering: the 2-D node with 1-based id n has the brick nodes n (front face, z = 0),
// n + N (back face, z = s) and, if it is a corner of some element, n + 2N (mid-plane,
// z = s/2), N being the number of 2-D nodes. A CPS8 (corners 1–4 counter-clockwise, midsides
// 5–8) becomes the C3D20 (1–4 front corners, 5–8 back corners, 9–12 front midsides, 13–16
// back midsides, 17–20 mid-plane corners): positive volume, and the CPS8 face k (edge k to
// k+1) is the brick's face S(k+2).
#pragma once

#include <Eigen/Core>
#include <array>
#include <sstream>
#include <string>
#include <vector>

namespace ringcrush::compare::calculix_parts {

struct Slab {
  int plane_nodes = 0;            // N: 2-D nodes (ids 1..N)
  double thickness = 0;           // s
  std::vector<bool> corner;       // per 2-D node (0-based): a corner of some element
  int nodes() const;              // brick nodes written: 2N + corners
  int front(int n) const { return n; }                       // 1-based 2-D id → brick ids
  int back(int n) const { return n + plane_nodes; }
  int middle(int n) const { return n + 2 * plane_nodes; }   // corners only
  // Every brick id of the 1-based 2-D node ids `ids` (front, back, and middle where it exists).
  std::vector<int> through(const std::vector<int>& ids) const;
};

// `elements` are 0-based CPS8 connectivities into the 2-D node list; id offsets already
// applied by the caller are not assumed: every list is global 0-based here.
Slab make_slab(int plane_nodes, const std::vector<std::array<int, 8>>& elements, double thickness);

// "*NODE, NSET=NALL" with every brick node of the 2-D points `xy` (global 0-based order).
void write_slab_nodes(std::ostringstream& o, const Slab& slab, const std::vector<Eigen::Vector2d>& xy);

// "*ELEMENT, TYPE=type, ELSET=elset" with the bricks of the CPS8 `elements` (global 0-based
// node ids), element ids from first_element; C3D20 lines are split after 15 node ids (ccx
// reads at most 16 entries per line; the element id is the first).
void write_bricks(std::ostringstream& o, const std::string& elset, const std::string& type, const Slab& slab,
                  const std::vector<std::array<int, 8>>& elements, int first_element);

// The brick face label of CPS8 face k (1..4): "S3".."S6".
std::string brick_face(int cps8_face);

}  // namespace ringcrush::compare::calculix_parts
