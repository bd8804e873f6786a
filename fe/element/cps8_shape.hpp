// CPS8: the 8-node serendipity quadrilateral of thesis §3.6.1.3 (Fig. 3.6.1-1).
// Node order: corners 1–4 counter-clockwise from (g, h) = (−1, −1), then the mid-side nodes
// 5 (edge 1–2), 6 (2–3), 7 (3–4), 8 (4–1), as in ABAQUS and the thesis decks.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace ringcrush::fe {

using ShapeVec = Eigen::Matrix<double, 8, 1>;
using ShapeGrad = Eigen::Matrix<double, 8, 2>;  // ∂N_a/∂(g, h) or ∂N_a/∂(X, Y)

// N_a(g, h) and ∂N_a/∂(g, h).
void cps8_shape(double g, double h, ShapeVec& n, ShapeGrad& dn);

// Natural coordinates of node a.
inline constexpr std::array<std::array<double, 2>, 8> cps8_node_coords{
    {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}}};

struct GaussPoint {
  double g, h, weight;
};
// n×n Gauss–Legendre rule on [−1, 1]², n = 2 or 3.
std::vector<GaussPoint> gauss_rule(int n);

struct GaussPoint1d {
  double x, weight;
};
// The n-point Gauss–Legendre rule on [−1, 1] that gauss_rule(n) is the tensor product of.
std::vector<GaussPoint1d> gauss_rule_1d(int n);

}  // namespace ringcrush::fe
