// The explicit step's speed-ups keep its results (issue 4 performance, README "Performance"):
//  - the force-only CPS8 kernel, arranged for the CPU (cps8_force.cpp), is bitwise its plain
//    point-by-point form, written out below from the public pieces;
//  - the bulk viscosity formed inside the force-only element kernel (BulkViscousLoad) is
//    bitwise the separate add_bulk_viscous_force();
//  - the chain's element pass (geometry re-derived lazily after a commit, bulk viscosity
//    inside the pass, both split over two threads) gives bitwise the same force and viscous
//    force on one thread or two, and the viscous force equals the element-by-element sum;
//  - the driver re-bounds only the contact springs when the contact activity changes, and
//    the full stable step keeps its schedule; the activity is a hash of the active set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "cps8_random_elements.hpp"
#include "dynamic_toy_systems.hpp"
#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/explicit_driver.hpp"
#include "fe/element/bulk_viscosity.hpp"
#include "fe/kinematics.hpp"
#include "threaded_chain_pass.hpp"

using namespace ringcrush::fe;

namespace {
// r_a += c A ∇N_a, node by node (the plain form of the kernel's nodal force).
void add_plain_nodal_force(const ShapeGrad& d, const Mat2& a, double c, ElementVector& force) {
  const double a00 = c * a(0, 0), a01 = c * a(0, 1), a10 = c * a(1, 0), a11 = c * a(1, 1);
  for (int k = 0; k < 8; ++k) {
    force(2 * k) += a00 * d(k, 0) + a01 * d(k, 1);
    force(2 * k + 1) += a10 * d(k, 0) + a11 * d(k, 1);
  }
}

// cps8_force() point by point: f, ΔE, bulk viscosity, selective correction, material, nodal
// force and trial state of one point after the other (cps8_element.hpp, bulk_viscosity.hpp).
struct PlainForce {
  ElementVector force = ElementVector::Zero(), viscous = ElementVector::Zero();
  double elastic = 0, plastic = 0;
  std::array<PointState, 9> trial{};
};
PlainForce plain_force(const Cps8Geometry& geo, const double* u, const PointState* committed,
                       const J2PlaneStress& material, double coefficient, double dt) {
  PlainForce out;
  const bool selective = geo.rule == Integration::Selective;
  std::array<Mat2, 4> f_r;
  std::array<double, 4> tr_r{}, q_r{};
  for (int r = 0; selective && r < 4; ++r) {
    f_r[r] = deformation_gradient(geo.dndx_reduced[r], u);
    const Eigen::Vector3d e = green_lagrange(f_r[r]);
    tr_r[r] = e(0) + e(1);
  }
  for (int i = 0; i < geo.points; ++i) {
    const Mat2 f = deformation_gradient(geo.dndx[i], u);
    Eigen::Vector3d e = green_lagrange(f);
    add_plain_nodal_force(geo.dndx[i], f, coefficient * (e(0) + e(1)) / dt * geo.weight[i], out.viscous);
    if (selective) {
      double tr_bar = 0;
      for (int r = 0; r < 4; ++r) tr_bar += geo.barlow(i, r) * tr_r[r];
      const double corr = 0.5 * (tr_bar - e(0) - e(1));
      e(0) += corr;
      e(1) += corr;
    }
    const J2Update up = material.update_stress(e, committed[i]);
    const double w = geo.weight[i] * committed[i].thickness_stretch;
    add_plain_nodal_force(geo.dndx[i], f * point_stress(up.stress, geo, i, w, q_r), w, out.force);
    out.elastic += w * up.elastic_energy;
    PointState& t = out.trial[i];
    const double l3 = std::sqrt(std::max(1e-12, 1.0 + 2.0 * up.strain33_increment));
    t.stress = cauchy_from_pk2(f, up.stress, l3);
    t.plastic_strain = committed[i].plastic_strain + up.plastic_increment;
    t.peeq = up.peeq;
    t.plastic_work = committed[i].plastic_work + w * up.dissipation;
    t.thickness_stretch = committed[i].thickness_stretch * l3;
    out.plastic += t.plastic_work;
  }
  for (int r = 0; selective && r < 4; ++r) add_plain_nodal_force(geo.dndx_reduced[r], f_r[r], q_r[r], out.force);
  return out;
}
}  // namespace

TEST(ExplicitSpeed, ForceKernelIsBitwiseItsPointByPointForm) {
  std::mt19937 rng(17);
  const J2PlaneStress material(kernel_test::thesis_steel());
  int yielded = 0;
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective}) {
    for (int k = 0; k < 30; ++k) {
      const auto el = kernel_test::random_element(rng, k % 2 ? 1e-2 : 1e-4, k % 3 == 0);
      const Cps8Geometry geo = cps8_geometry(el.x, rule, 0.0125);
      const double coefficient = 3.7e3, dt = 5e-8;
      const PlainForce ref = plain_force(geo, el.du, el.committed.data(), material, coefficient, dt);
      std::array<PointState, 9> trial{};
      Cps8Output out;
      ElementVector viscous = ElementVector::Zero();
      const BulkViscousLoad load{coefficient, dt, &viscous};
      cps8_force(geo, el.du, el.committed.data(), trial.data(), material, out, &load);
      EXPECT_EQ(out.force, ref.force);
      EXPECT_EQ(viscous, ref.viscous);
      EXPECT_EQ(out.elastic_energy, ref.elastic);
      EXPECT_EQ(out.plastic_work, ref.plastic);
      for (int i = 0; i < geo.points; ++i) {
        EXPECT_EQ(trial[i].stress, ref.trial[i].stress);
        EXPECT_EQ(trial[i].plastic_strain, ref.trial[i].plastic_strain);
        EXPECT_EQ(trial[i].peeq, ref.trial[i].peeq);
        EXPECT_EQ(trial[i].thickness_stretch, ref.trial[i].thickness_stretch);
        if (trial[i].peeq > el.committed[i].peeq) ++yielded;
      }
    }
  }
  EXPECT_GT(yielded, 0);  // both material branches were compared
}

TEST(ExplicitSpeed, FusedBulkViscosityIsTheSeparateForce) {
  std::mt19937 rng(5);
  const J2PlaneStress material(kernel_test::thesis_steel());
  for (Integration rule : {Integration::Reduced, Integration::Full, Integration::Selective}) {
    for (int k = 0; k < 20; ++k) {
      const auto el = kernel_test::random_element(rng, k % 2 ? 1e-2 : 1e-4, k % 3 == 0);
      const Cps8Geometry geo = cps8_geometry(el.x, rule, 0.0125);
      std::array<PointState, 9> t1{}, t2{};
      Cps8Output plain, fused;
      cps8_force(geo, el.du, el.committed.data(), t1.data(), material, plain);
      ElementVector separate = ElementVector::Zero(), inside = ElementVector::Zero();
      const double coefficient = 3.7e3, dt = 5e-8;
      add_bulk_viscous_force(geo, el.du, dt, coefficient, separate);
      const BulkViscousLoad load{coefficient, dt, &inside};
      cps8_force(geo, el.du, el.committed.data(), t2.data(), material, fused, &load);
      EXPECT_EQ(inside, separate);
      EXPECT_EQ(fused.force, plain.force);  // the element force itself is untouched
      EXPECT_EQ(fused.elastic_energy, plain.elastic_energy);
      EXPECT_GT(separate.norm(), 0.0);
    }
  }
}

TEST(ExplicitSpeed, ChainPassWithViscosityIsThreadIndependent) {
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    ChainInput in;
    in.rings = 2;
    in.mesh.elements_around = 8;
    in.joints = JointKind::Free;
    in.integration = rule;
    in.bulk_viscosity = 0.06;
    test_support::ThreadedChainPass pass(in);
    pass.run(3, 9, [&](const SystemEvaluation& a) {
      // Momentum: the viscous forces of every element sum to zero.
      double fx = 0, fy = 0;
      for (int n = 0; n < pass.serial.dofs() / 2; ++n) {
        fx += a.viscous_force(2 * n);
        fy += a.viscous_force(2 * n + 1);
      }
      EXPECT_LT(std::abs(fx) + std::abs(fy), 1e-9 * a.viscous_force.lpNorm<Eigen::Infinity>());
    });
    // Zero increment time: no viscous force at all.
    pass.serial.set_increment_time(0);
    SystemEvaluation c;
    pass.serial.evaluate(pass.u, false, c);
    EXPECT_EQ(c.viscous_force.size(), 0);
  }
}

// Two threads deal the elements of a force-only pass (work_dealer.hpp): an element that fails
// on either thread (here an inverted one, its geometry re-derived after the commit) is an
// exception on the caller, as on one thread — not a thread waiting forever for the other.
TEST(ExplicitSpeed, DealtPassReportsAnInvertedElement) {
  ChainInput in;
  in.rings = 2;
  in.mesh.elements_around = 8;
  in.joints = JointKind::Free;
  in.integration = Integration::Selective;
  for (int threads : {1, 2}) {
    in.threads = threads;
    ChainModel model(in);
    const auto& mesh = model.mesh();
    for (int bad : {0, static_cast<int>(mesh.elements.size()) - 1}) {  // first and last: both halves
      ChainModel m(in);
      Eigen::VectorXd u = Eigen::VectorXd::Zero(m.dofs());
      // Mid-side node 5 (edge 1–2) pushed twice across the element, beyond node 7 (edge 3–4).
      const auto& conn = mesh.elements[bad];
      const Eigen::Vector2d push = 2.0 * (mesh.nodes[conn[6]] - mesh.nodes[conn[4]]);
      u(2 * conn[4]) = push.x();
      u(2 * conn[4] + 1) = push.y();
      SystemEvaluation out;
      m.evaluate(u, false, out);  // on the reference geometry: finite
      m.commit(u);
      EXPECT_THROW(m.evaluate(u, false, out), std::runtime_error) << threads << " threads, element " << bad;
    }
  }
}

namespace {
// The toy spring–mass chain, counting the stable-step calls the driver makes.
class CountingSystem final : public DynamicSystem {
 public:
  explicit CountingSystem(ringcrush::fe::testing::SpringMassSystem& s) : s_(s) {}
  int dofs() const override { return s_.dofs(); }
  const std::vector<int>& fixed_dofs() const override { return s_.fixed_dofs(); }
  const Eigen::VectorXd& lumped_mass() const override { return s_.lumped_mass(); }
  Eigen::VectorXd initial_velocity() const override { return s_.initial_velocity(); }
  void evaluate(const Eigen::VectorXd& u, bool t, SystemEvaluation& out) override { s_.evaluate(u, t, out); }
  void commit(const Eigen::VectorXd& u) override { s_.commit(u); }
  SparseSystem& tangent_system() override { return s_.tangent_system(); }
  StableStep stable_step(const Eigen::VectorXd& u) const override {
    ++full;
    return s_.stable_step(u);
  }
  StableStep contact_stable_step(const Eigen::VectorXd& u) const override {
    ++contact;
    return s_.stable_step(u);
  }
  mutable int full = 0, contact = 0;

 private:
  ringcrush::fe::testing::SpringMassSystem& s_;
};
}  // namespace

TEST(ExplicitSpeed, ContactChangeReboundsOnlyTheContactPart) {
  ringcrush::fe::testing::SpringMassSystem springs({1.0, 1.0}, {0.0, 1.0});
  springs.add_spring(0, -1, 100.0);
  springs.add_spring(1, -1, 100.0);
  CountingSystem sys(springs);
  ExplicitOptions o;
  o.stable_step_every = 10;
  ExplicitDriver d(sys, o);
  for (int k = 0; k < 5; ++k) d.step();
  EXPECT_EQ(sys.full, 1);  // the first step
  EXPECT_EQ(sys.contact, 0);
  d.request_contact_bound();
  d.step();
  EXPECT_EQ(sys.full, 1);
  EXPECT_EQ(sys.contact, 1);
  EXPECT_EQ(d.contact_bounds(), 1);
  for (int k = 0; k < 4; ++k) d.step();  // steps 7–10: no re-bound, the schedule is kept
  EXPECT_EQ(sys.full, 1);
  d.step();  // step 11: 10 steps since the full bound
  EXPECT_EQ(sys.full, 2);
  EXPECT_EQ(d.full_bounds(), 2);
  // A full bound due at the same step as a contact change covers both.
  for (int k = 0; k < 9; ++k) d.step();
  d.request_contact_bound();
  d.step();
  EXPECT_EQ(sys.full, 3);
  EXPECT_EQ(sys.contact, 1);
}

TEST(ExplicitSpeed, ActiveContactSetIsHashedDeterministically) {
  // run_dynamic re-bounds the explicit step when this hash changes (a set that changed at
  // the same count would slip past a comparison of counts).
  ChainInput in;
  in.rings = 2;
  in.mesh.elements_around = 8;
  in.joints = JointKind::Welded;
  in.fixed_target = true;
  ChainModel model(in);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
  SystemEvaluation ev;
  auto set_at = [&](double press) {
    u(model.impactor_dof()) = -press * 1.6e-3;
    model.evaluate(u, false, ev);
    return std::make_pair(model.contact_forces().active, model.contact_forces().active_set);
  };
  const auto light = set_at(0.05), again = set_at(0.05), deep = set_at(0.6);
  ASSERT_GT(light.first, 0);
  EXPECT_EQ(light, again);                 // the same contacts, the same hash
  EXPECT_GT(deep.first, light.first);      // more impactor nodes in contact
  EXPECT_NE(deep.second, light.second);
  EXPECT_NE(light.second, 0u);
}
