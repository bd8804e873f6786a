// The explicit step's speed-ups keep its results (issue 4 performance, README "Performance"):
//  - the bulk viscosity formed inside the force-only element kernel (BulkViscousLoad) is
//    bitwise the separate add_bulk_viscous_force();
//  - the chain's element pass (geometry re-derived lazily after a commit, bulk viscosity
//    inside the pass, both split over two threads) gives bitwise the same force and viscous
//    force on one thread or two, and the viscous force equals the element-by-element sum;
//  - the driver re-bounds only the contact springs when the contact activity changes, and
//    the full stable step keeps its schedule; the activity is a hash of the active set.
#include <gtest/gtest.h>

#include <random>

#include "cps8_random_elements.hpp"
#include "dynamic_toy_systems.hpp"
#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/explicit_driver.hpp"
#include "fe/element/bulk_viscosity.hpp"

using namespace ringcrush::fe;

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
    in.threads = 1;
    ChainModel serial(in);
    in.threads = 2;
    ChainModel threaded(in);
    std::mt19937 gen(9);
    std::uniform_real_distribution<double> d(-2e-6, 2e-6);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(serial.dofs());
    for (int step = 0; step < 3; ++step) {
      for (int i = 0; i < serial.dofs(); ++i) u(i) += d(gen);
      for (int dof : serial.fixed_dofs()) u(dof) = 0;
      SystemEvaluation a, b;
      serial.set_increment_time(5e-8);
      threaded.set_increment_time(5e-8);
      serial.evaluate(u, false, a);
      threaded.evaluate(u, false, b);
      ASSERT_EQ(a.viscous_force.size(), serial.dofs());
      EXPECT_EQ(a.force, b.force);
      EXPECT_EQ(a.viscous_force, b.viscous_force);
      EXPECT_EQ(a.elastic_energy, b.elastic_energy);
      EXPECT_GT(a.viscous_force.norm(), 0.0);
      // Momentum: the viscous forces of every element sum to zero.
      double fx = 0, fy = 0;
      for (int n = 0; n < serial.dofs() / 2; ++n) {
        fx += a.viscous_force(2 * n);
        fy += a.viscous_force(2 * n + 1);
      }
      EXPECT_LT(std::abs(fx) + std::abs(fy), 1e-9 * a.viscous_force.lpNorm<Eigen::Infinity>());
      serial.commit(u);  // the next pass re-derives the geometry on this configuration
      threaded.commit(u);
    }
    // Zero increment time: no viscous force at all.
    serial.set_increment_time(0);
    SystemEvaluation c;
    serial.evaluate(u, false, c);
    EXPECT_EQ(c.viscous_force.size(), 0);
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
