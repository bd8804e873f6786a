// Linear bulk viscosity of the CPS8 element (fe/element/bulk_viscosity.hpp) and of the chain
// in the explicit driver: no force for rigid motions, action = reaction, the force is q times
// the variation of the element's volumetric strain, it dissipates, it damps the element's
// highest (dilatational) mode at about ξ = b1, and the energy books close with its work as a
// named term.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <numbers>
#include <random>

#include "fe/dynamics/dynamic_run.hpp"
#include "fe/dynamics/element_eigenvalue.hpp"
#include "fe/dynamics/lumped_mass.hpp"
#include "fe/element/bulk_viscosity.hpp"
#include "fe/kinematics.hpp"

using namespace ringcrush::fe;

namespace {

// A thesis-sized wall element (3.3 mm along the wall, 1.6 mm through it), slightly curved.
ElementCoords wall_element() {
  ElementCoords x;
  const double hx = 1.66e-3, hy = 0.8e-3;
  for (int a = 0; a < 8; ++a) {
    const double g = cps8_node_coords[a][0], h = cps8_node_coords[a][1];
    x(a, 0) = hx * g + 0.05 * hy * h * h;
    x(a, 1) = hy * h + 0.1 * hy * g * g;
  }
  return x;
}

// Σ w tr ΔE (weights: null → geo.weight) and the point traces.
double volumetric(const Cps8Geometry& geo, const double* du, const double* weights = nullptr) {
  double v = 0;
  for (int i = 0; i < geo.points; ++i) {
    const Eigen::Vector3d e = green_lagrange(deformation_gradient(geo.dndx[i], du));
    v += (weights ? weights[i] : geo.weight[i]) * (e(0) + e(1));
  }
  return v;
}

}  // namespace

TEST(BulkViscosity, RigidMotionsGiveNoForce) {
  for (Integration rule : {Integration::Full, Integration::Reduced, Integration::Selective}) {
    const ElementCoords x = wall_element();
    const Cps8Geometry geo = cps8_geometry(x, rule, 12.5e-3);
    const Mat2 r = rotation(0.3);
    double du[16];
    for (int a = 0; a < 8; ++a) {
      const Eigen::Vector2d p = x.row(a).transpose();
      const Eigen::Vector2d d = r * p - p + Eigen::Vector2d(1e-3, -2e-3);
      du[2 * a] = d.x();
      du[2 * a + 1] = d.y();
    }
    ElementVector f = ElementVector::Zero();
    const double q = add_bulk_viscous_force(geo, du, 1e-7, 1e3, f);
    EXPECT_LT(std::abs(q), 1e-4);  // Pa, against 1e6 Pa for a 1e-4 strain in 1e-7 s
    EXPECT_LT(f.norm(), 1e-9);
  }
}

TEST(BulkViscosity, ForceIsThePressureTimesTheVolumeVariationAndActionEqualsReaction) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Cps8Geometry geo = cps8_geometry(wall_element(), Integration::Selective, 12.5e-3);
  for (int trial = 0; trial < 5; ++trial) {
    double du[16];
    for (double& d : du) d = 2e-6 * u(rng);
    ElementVector f = ElementVector::Zero();
    const double dt = 5e-8, c = 2e3;
    const double q = add_bulk_viscous_force(geo, du, dt, c, f);
    double volume = 0;
    for (int i = 0; i < geo.points; ++i) volume += geo.weight[i];
    EXPECT_NEAR(q, c * volumetric(geo, du) / (volume * dt), 1e-12 * c * std::abs(volumetric(geo, du)) / (volume * dt));
    // f = Σ_i q_i ∂(w_i tr ΔE_i)/∂Δu with q_i = c tr ΔE_i / Δt frozen, central differences.
    double qw[9];
    for (int i = 0; i < geo.points; ++i) {
      const Eigen::Vector3d e = green_lagrange(deformation_gradient(geo.dndx[i], du));
      qw[i] = c * (e(0) + e(1)) / dt * geo.weight[i];
    }
    for (int k = 0; k < 16; ++k) {
      double p[16], m[16];
      std::copy(du, du + 16, p);
      std::copy(du, du + 16, m);
      const double h = 1e-9;
      p[k] += h;
      m[k] -= h;
      const double fd = (volumetric(geo, p, qw) - volumetric(geo, m, qw)) / (2 * h);
      EXPECT_NEAR(f(k), fd, 1e-6 * f.norm()) << "dof " << k;
    }
    double fx = 0, fy = 0;
    for (int a = 0; a < 8; ++a) {
      fx += f(2 * a);
      fy += f(2 * a + 1);
    }
    EXPECT_LT(std::abs(fx) + std::abs(fy), 1e-10 * f.norm());
    // Dissipative: the work over the increment is Σ q_i w_i tr ΔE_i ≥ 0 (to first order).
    EXPECT_GT(f.dot(Eigen::Map<const ElementVector>(du)), 0.0);
  }
}

TEST(BulkViscosity, DampsTheHighestElementModeAtAboutB1) {
  // One free thesis element, elastic, started in its highest mode (small amplitude) and
  // integrated by central difference at 0.5 of its stable step with b1 = 0.06 and
  // L_e = 2 c_d / ω_e, as ChainModel does. The amplitude decays as exp(−ξ ω t); ξ from the
  // energy after 20 periods. The highest mode of the wall element is mostly dilatational, so
  // ξ is close to b1 (the share of its strain energy in the volumetric part sets it).
  const ElementCoords x = wall_element();
  const double rho = 8410, width = 12.5e-3, b1 = 0.06;
  MaterialInput mi;
  mi.hardening = {{1e15, 0.0}};  // elastic
  const J2PlaneStress material(mi);
  const auto mass = hrz_lumped_mass(x, rho, width);
  const Cps8Geometry geo = cps8_geometry(x, Integration::Selective, width);
  std::array<PointState, 9> committed{}, trial{};
  Cps8Output out;
  const double zero[16] = {};
  cps8_evaluate(geo, zero, committed.data(), trial.data(), material, true, out);
  Eigen::Matrix<double, 16, 1> s;
  for (int k = 0; k < 16; ++k) s(k) = 1 / std::sqrt(mass[k / 2]);
  const ElementMatrix a = s.asDiagonal() * out.tangent * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<ElementMatrix> eig(0.5 * (a + a.transpose()));
  const double lambda = eig.eigenvalues()(15), omega = std::sqrt(lambda);
  EXPECT_NEAR(lambda, element_max_eigenvalue(x, mass, Integration::Selective, width, material), 1e-9 * lambda);
  const ElementVector mode = s.asDiagonal() * eig.eigenvectors().col(15);
  const double e = material.youngs_modulus(), nu = material.poisson_ratio();
  const double coefficient = 2 * b1 * e / ((1 - nu * nu) * omega);  // b1 ρ c_d L_e
  // Linear dynamics about the reference: K u + bulk viscous force, lumped mass.
  ElementVector u = 1e-9 * mode / mode.cwiseAbs().maxCoeff(), v = ElementVector::Zero(), acc;
  const double dt = 0.5 * 2 / omega;
  auto force = [&](const ElementVector& uu, const ElementVector& du_step) {
    ElementVector f = out.tangent * uu;
    add_bulk_viscous_force(geo, du_step.data(), dt, coefficient, f);
    return f;
  };
  auto energy = [&](const ElementVector& uu, const ElementVector& vv) {
    double ke = 0;
    for (int k = 0; k < 16; ++k) ke += 0.5 * mass[k / 2] * vv(k) * vv(k);
    return ke + 0.5 * uu.dot(out.tangent * uu);
  };
  for (int k = 0; k < 16; ++k) acc(k) = -(out.tangent * u)(k) / mass[k / 2];
  const double e0 = energy(u, v);
  const double periods = 20, t_end = periods * 2 * std::numbers::pi / omega;
  for (double t = 0; t < t_end; t += dt) {
    v += 0.5 * dt * acc;
    const ElementVector du = dt * v;
    u += du;
    const ElementVector f = force(u, du);
    for (int k = 0; k < 16; ++k) acc(k) = -f(k) / mass[k / 2];
    v += 0.5 * dt * acc;
  }
  // E ∝ exp(−2 ξ ω t).
  const double xi = -std::log(energy(u, v) / e0) / (2 * omega * t_end);
  EXPECT_GT(xi, 0.5 * b1);
  EXPECT_LT(xi, 1.5 * b1);
}

TEST(BulkViscosity, ChainImpactBooksItsDissipationAndTheBalanceCloses) {
  // Two welded rings (8 CPS8 per half ring, selective) hit by 0.128 kg at 30 m/s, 0.2 ms,
  // explicit with b1 = 0.06: W_v > 0 and small, the balance of the state energies against the
  // force work (which excludes W_v) and the numerical remainder both stay below 1 % of KE0.
  ChainInput in;
  in.rings = 2;
  in.mesh.elements_around = 8;
  in.integration = Integration::Selective;
  in.impactor_mass_kg = 0.256;
  in.impactor_velocity_m_s = 30;
  in.bulk_viscosity = 0.06;
  DynamicSolverInput s;
  s.scheme = DynamicScheme::Explicit;
  s.end_time_s = 2e-4;
  s.frames = 0;
  const DynamicResult r = run_dynamic(in, s);
  const auto& last = r.history.back();
  EXPECT_GT(last.bulk_viscous_j, 0.0);
  EXPECT_LT(last.bulk_viscous_j, 0.05 * r.initial_kinetic_j);
  EXPECT_LT(r.energy_balance_error, 0.01);
  EXPECT_LT(std::abs(r.numerical_dissipation), 0.01);
  const double books = last.kinetic_j + last.elastic_j + last.plastic_j + last.contact_j + last.numerical_j +
                       last.bulk_viscous_j;
  EXPECT_NEAR(books, r.initial_kinetic_j, 0.01 * r.initial_kinetic_j);
  // Bad input: b1 outside [0, 1).
  in.bulk_viscosity = -0.1;
  EXPECT_THROW(run_dynamic(in, s), std::invalid_argument);
  in.bulk_viscosity = 1.0;
  EXPECT_THROW(run_dynamic(in, s), std::invalid_argument);
}
