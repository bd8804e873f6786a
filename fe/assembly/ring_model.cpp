#include "fe/assembly/ring_model.hpp"

#include <stdexcept>
#include <string>

namespace ringcrush::fe {

namespace {
std::vector<int> fixed_dofs(const RingMesh& m) {
  std::vector<int> d;
  for (int n : m.fixed_x) d.push_back(2 * n);
  return d;
}
}  // namespace

RingModel::RingModel(const FeInput& input)
    : input_(input),
      mesh_(make_ring_mesh(input.ring, input.mesh)),
      material_(input.material),
      points_per_element_(input.integration == Integration::Reduced ? 4 : 9),
      contact_(mesh_, input.contact, input.material.youngs_modulus_pa, input.ring.width_m) {
  u_n_ = Eigen::VectorXd::Zero(dofs());
  build_geometry();
  committed_.assign(mesh_.elements.size() * points_per_element_, PointState{});
  trial_ = committed_;
  system_ = std::make_unique<SparseSystem>(static_cast<int>(mesh_.nodes.size()), fixed_dofs(mesh_), mesh_.elements);
  x_.resize(mesh_.nodes.size());
}

void RingModel::build_geometry() {
  geometry_.resize(mesh_.elements.size());
  for (std::size_t e = 0; e < mesh_.elements.size(); ++e) {
    ElementCoords x;
    for (int a = 0; a < 8; ++a) {
      const int n = mesh_.elements[e][a];
      x(a, 0) = mesh_.nodes[n].x() + u_n_(2 * n);
      x(a, 1) = mesh_.nodes[n].y() + u_n_(2 * n + 1);
    }
    try {
      geometry_[e] = cps8_geometry(x, input_.integration, input_.ring.width_m);
    } catch (const std::invalid_argument& err) {
      throw std::runtime_error("element " + std::to_string(e + 1) + ": " + err.what());
    }
  }
}

void RingModel::commit(const Eigen::VectorXd& u) {
  committed_ = trial_;
  contact_.commit();
  u_n_ = u;
  build_geometry();
}

void RingModel::evaluate(const Eigen::VectorXd& u, double y_top, bool want_tangent, bool want_pressure,
                         ModelEvaluation& out) {
  const std::size_t nn = mesh_.nodes.size();
  for (std::size_t i = 0; i < nn; ++i) x_[i] = mesh_.nodes[i] + Eigen::Vector2d(u(2 * i), u(2 * i + 1));
  contributions_.clear();
  contact_.evaluate(x_, y_top, plate_bottom(), want_tangent, want_pressure, contributions_, out.contact);
  if (want_tangent) {
    // New contact couplings grow the pattern before anything is written into it.
    for (const auto& c : contributions_)
      if (c.count > 1) system_->ensure_coupled(c.nodes.data(), c.count);
    system_->zero();
  }
  out.residual.setZero(dofs());
  out.elastic_energy = 0;
  out.plastic_work = 0;
  Cps8Output eo;
  double ue[16];
  for (std::size_t e = 0; e < mesh_.elements.size(); ++e) {
    const auto& conn = mesh_.elements[e];
    for (int a = 0; a < 8; ++a) {
      ue[2 * a] = u(2 * conn[a]) - u_n_(2 * conn[a]);
      ue[2 * a + 1] = u(2 * conn[a] + 1) - u_n_(2 * conn[a] + 1);
    }
    const std::size_t p0 = e * points_per_element_;
    cps8_evaluate(geometry_[e], ue, &committed_[p0], &trial_[p0], material_, want_tangent, eo);
    for (int a = 0; a < 8; ++a) {
      out.residual(2 * conn[a]) += eo.force(2 * a);
      out.residual(2 * conn[a] + 1) += eo.force(2 * a + 1);
    }
    out.elastic_energy += eo.elastic_energy;
    out.plastic_work += eo.plastic_work;
    if (want_tangent) system_->add_element(static_cast<int>(e), eo.tangent.data());
  }
  for (const auto& c : contributions_) {
    for (int a = 0; a < c.count; ++a) {
      out.residual(2 * c.nodes[a]) += c.force(2 * a);
      out.residual(2 * c.nodes[a] + 1) += c.force(2 * a + 1);
    }
    if (want_tangent) system_->add_nodes(c.nodes.data(), c.count, c.tangent.data(), 12);
  }
}

std::vector<Cps8Fields> RingModel::element_fields() const {
  std::vector<Cps8Fields> out;
  for (std::size_t e = 0; e < mesh_.elements.size(); ++e)
    out.push_back(cps8_fields(&committed_[e * points_per_element_], points_per_element_));
  return out;
}

}  // namespace ringcrush::fe
