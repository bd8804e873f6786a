// Parametric ring mesher (DESIGN.md "Mesh"): CPS8 elements around and through the wall,
// graded toward the hinge locations, full ring or the thesis's half ring (x ≥ 0, symmetric
// about x = 0). Angle φ runs counter-clockwise from the bottom contact point:
// X = r sin φ, Y = −r cos φ (φ = 0 bottom plate, φ = π/2 side, φ = π top plate).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "fe/fe_input.hpp"

namespace ringcrush::fe {

struct SurfaceSegment {
  std::array<int, 3> nodes;  // quadratic edge in counter-clockwise order (end, middle, end)
  int element;
};

struct RingMesh {
  std::vector<Eigen::Vector2d> nodes;       // reference coordinates
  std::vector<double> node_angle;           // φ of each node (reference)
  std::vector<std::array<int, 8>> elements; // CPS8 connectivity (thesis node order)
  std::vector<int> outer_nodes;             // outer surface, counter-clockwise
  std::vector<double> outer_weight;         // ∫ N_a ds of each outer node (tributary length)
  std::vector<SurfaceSegment> inner_segments;  // inner surface, counter-clockwise
  std::vector<int> inner_nodes;
  std::vector<double> inner_weight;         // per inner_nodes entry
  std::vector<int> fixed_x;                 // nodes with u_x = 0 (symmetry / rigid-body restraint)
  double element_depth = 0;                 // element size through the wall, t / elements_through
  bool half_ring = true;
  int top_node = -1, bottom_node = -1;      // outer nodes on the loading axis
};

// Corner angles of the elements around (size ∝ 1 + (g − 1) sin²2φ, g = grading).
std::vector<double> graded_angles(int elements, double span, double grading);

RingMesh make_ring_mesh(const RingInput& ring, const MeshInput& mesh);

}  // namespace ringcrush::fe
