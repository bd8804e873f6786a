// The discrete ring model: mesh, CPS8 elements, material, contact and the sparse system.
// evaluate() is the one system interface the drivers step (STYLE.md practice 5): given the
// nodal displacements and the driven-plate position it returns the residual (internal +
// contact force), optionally the tangent, and the energies; it writes only trial point
// states. commit() makes the trial states the committed ones (the driver calls it after a
// converged increment; a cut-back simply evaluates again from the committed states).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "fe/assembly/sparse_system.hpp"
#include "fe/contact/ring_contact.hpp"
#include "fe/element/cps8_element.hpp"
#include "fe/fe_input.hpp"
#include "fe/material/j2_plane_stress.hpp"
#include "fe/mesh/ring_mesh.hpp"

namespace ringcrush::fe {

struct ModelEvaluation {
  Eigen::VectorXd residual;  // all 2·nodes dofs (fixed dofs carry their reactions)
  ContactState contact;
  double elastic_energy = 0;
  double plastic_work = 0;
};

class RingModel {
 public:
  explicit RingModel(const FeInput& input);

  const FeInput& input() const { return input_; }
  const RingMesh& mesh() const { return mesh_; }
  SparseSystem& system() { return *system_; }
  const SparseSystem& system() const { return *system_; }
  int dofs() const { return 2 * static_cast<int>(mesh_.nodes.size()); }
  double plate_top_initial() const { return input_.ring.outer_radius_m; }
  double plate_bottom() const { return -input_.ring.outer_radius_m; }
  // Forces and energies of the whole ring = symmetry_factor × those of the model.
  double symmetry_factor() const { return mesh_.half_ring ? 2.0 : 1.0; }

  void evaluate(const Eigen::VectorXd& u, double y_top, bool want_tangent, bool want_pressure,
                ModelEvaluation& out);
  // Makes the trial states committed and u the start of the next increment (the element
  // geometry is re-derived on the new configuration). Throws std::runtime_error if an
  // element is inverted there.
  void commit(const Eigen::VectorXd& u);
  const Eigen::VectorXd& committed_displacement() const { return u_n_; }
  // Plate friction on (friction_coefficient > 0): the tangent is then not symmetric.
  bool frictional() const { return contact_.frictional(); }
  const RingContact& contact() const { return contact_; }

  // Point-averaged Mises (Cauchy) and PEEQ per element, committed states.
  std::vector<Cps8Fields> element_fields() const;

 private:
  FeInput input_;
  RingMesh mesh_;
  J2PlaneStress material_;
  std::vector<Cps8Geometry> geometry_;
  int points_per_element_;
  std::vector<PointState> committed_, trial_;
  RingContact contact_;
  std::unique_ptr<SparseSystem> system_;
  std::vector<ContactContribution> contributions_;
  std::vector<Eigen::Vector2d> x_;
  Eigen::VectorXd u_n_;
  void build_geometry();
};

}  // namespace ringcrush::fe
