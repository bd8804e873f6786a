// Elastic diametral stiffness of one half-model polygon ring (THEORY §1.1, §4.3), shared by the
// closed-form tests of the ring (polygon_ring_test) and of its membrane scale
// (polygon_stiff_term_scale_test).
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <vector>

#include "hinge/polygon_simulation.hpp"

namespace ringcrush::hinge::testing {

// The top node loaded, the bottom node held; K by finite differences of the generalised forces
// (perturbing away from the plates, which touch with zero gap), then K u = f. `in` is one ring.
inline double polygon_diametral_stiffness(const PolygonChainInput& in) {
  PolygonChain chain(in);
  const auto y = chain.initial_state();
  const int n = chain.independent_nodes();
  std::vector<std::size_t> dofs;
  for (int j = 0; j < n - 1; ++j) dofs.push_back(chain.node_offset(0, j) + 1);  // y, bottom held
  for (int j = 1; j < n - 1; ++j) dofs.push_back(chain.node_offset(0, j));      // x, off the axis
  const auto m = static_cast<Eigen::Index>(dofs.size());
  Eigen::MatrixXd K(m, m);
  std::vector<double> f0(chain.size()), f1(chain.size());
  chain.generalised_forces(0.0, y.data(), f0.data());
  const double h = -1e-9;
  for (Eigen::Index a = 0; a < m; ++a) {
    auto yy = y;
    yy[dofs[a]] += h;
    chain.generalised_forces(0.0, yy.data(), f1.data());
    for (Eigen::Index b = 0; b < m; ++b) K(b, a) = -(f1[dofs[b] + 2] - f0[dofs[b] + 2]) / h;
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m);
  f(0) = -0.5;  // half of a unit load: the half model carries half of everything on the axis
  const Eigen::VectorXd u = K.partialPivLu().solve(f);
  return 1.0 / -u(0);
}

}  // namespace ringcrush::hinge::testing
