// Verification (a) patch test and (b) rigid rotation of a pre-stressed element, plus the
// element tangent against finite differences (STYLE.md practice 10).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "fe/element/cps8_element.hpp"
#include "fe/kinematics.hpp"

using namespace ringcrush::fe;

namespace {

MaterialInput elastic_material() {
  MaterialInput m;
  m.youngs_modulus_pa = 200e9;
  m.poisson_ratio = 0.3;
  m.hardening = {{1e15, 0.0}};  // never yields
  return m;
}

const Integration rules[] = {Integration::Full, Integration::Reduced, Integration::Selective};
const char* name(Integration r) {
  return r == Integration::Full ? "full" : r == Integration::Reduced ? "reduced" : "selective";
}
int points(Integration r) { return r == Integration::Reduced ? 4 : 9; }

// A 2×2 patch of CPS8 on [0, 2]² with every interior node (and the mid-side nodes) moved:
// distorted, curved-edged elements.
struct Patch {
  std::vector<Eigen::Vector2d> x;
  std::vector<std::array<int, 8>> elements;
  std::vector<bool> boundary;
};

Patch distorted_patch() {
  Patch p;
  // 5×5 grid of node slots, serendipity (no slot with both indices odd).
  std::map<std::pair<int, int>, int> id;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) {
      if (i % 2 == 1 && j % 2 == 1) continue;
      double x = 0.5 * i, y = 0.5 * j;
      const bool edge = i == 0 || j == 0 || i == 4 || j == 4;
      if (!edge) {  // distort interior nodes
        x += 0.11 * std::sin(1.7 * i + 0.3 * j);
        y += 0.09 * std::cos(0.8 * i + 2.1 * j);
      }
      id[{i, j}] = static_cast<int>(p.x.size());
      p.x.emplace_back(x, y);
      p.boundary.push_back(edge);
    }
  for (int ej = 0; ej < 2; ++ej)
    for (int ei = 0; ei < 2; ++ei) {
      const int i = 2 * ei, j = 2 * ej;
      p.elements.push_back({id[{i, j}], id[{i + 2, j}], id[{i + 2, j + 2}], id[{i, j + 2}], id[{i + 1, j}],
                            id[{i + 2, j + 1}], id[{i + 1, j + 2}], id[{i, j + 1}]});
    }
  return p;
}

// Internal force and tangent of the patch for nodal displacements u (dense).
void assemble(const Patch& p, Integration rule, const J2PlaneStress& mat, const Eigen::VectorXd& u,
              Eigen::VectorXd& f, Eigen::MatrixXd& k, std::vector<Vec3>& stresses) {
  const int n = 2 * static_cast<int>(p.x.size());
  f.setZero(n);
  k.setZero(n, n);
  stresses.clear();
  for (const auto& e : p.elements) {
    ElementCoords xe;
    double ue[16];
    for (int a = 0; a < 8; ++a) {
      xe.row(a) = p.x[e[a]].transpose();
      ue[2 * a] = u(2 * e[a]);
      ue[2 * a + 1] = u(2 * e[a] + 1);
    }
    const Cps8Geometry g = cps8_geometry(xe, rule, 0.01);
    std::vector<PointState> committed(9), trial(9);
    Cps8Output o;
    cps8_evaluate(g, ue, committed.data(), trial.data(), mat, true, o);
    for (int a = 0; a < 16; ++a) {
      f(2 * e[a / 2] + a % 2) += o.force(a);
      for (int b = 0; b < 16; ++b) k(2 * e[a / 2] + a % 2, 2 * e[b / 2] + b % 2) += o.tangent(a, b);
    }
    for (int i = 0; i < points(rule); ++i) stresses.push_back(trial[i].stress);
  }
}

}  // namespace

// (a) A homogeneous deformation u = A X on the boundary of a distorted patch is reproduced
// inside to 1e-10 for every rule: solve for the interior nodes from a perturbed start.
TEST(Cps8, PatchTestEveryIntegrationRule) {
  const Patch p = distorted_patch();
  const J2PlaneStress mat(elastic_material());
  Eigen::Matrix2d a;
  a << 1.2e-3, -0.4e-3, 0.7e-3, -0.5e-3;
  for (Integration rule : rules) {
    const int n = 2 * static_cast<int>(p.x.size());
    Eigen::VectorXd exact(n), u(n), f;
    Eigen::MatrixXd k;
    std::vector<Vec3> s;
    for (std::size_t i = 0; i < p.x.size(); ++i) exact.segment<2>(2 * i) = a * p.x[i];
    u = exact;
    for (std::size_t i = 0; i < p.x.size(); ++i)
      if (!p.boundary[i]) u.segment<2>(2 * i) += Eigen::Vector2d(2e-4 * std::sin(3.0 * static_cast<double>(i)), -1e-4 * std::cos(static_cast<double>(i)));
    std::vector<int> free;
    for (std::size_t i = 0; i < p.x.size(); ++i)
      if (!p.boundary[i]) free.insert(free.end(), {2 * int(i), 2 * int(i) + 1});
    for (int it = 0; it < 12; ++it) {
      assemble(p, rule, mat, u, f, k, s);
      Eigen::VectorXd r(free.size());
      Eigen::MatrixXd kf(free.size(), free.size());
      for (std::size_t i = 0; i < free.size(); ++i) {
        r(i) = f(free[i]);
        for (std::size_t j = 0; j < free.size(); ++j) kf(i, j) = k(free[i], free[j]);
      }
      const Eigen::VectorXd du = kf.fullPivLu().solve(-r);
      for (std::size_t i = 0; i < free.size(); ++i) u(free[i]) += du(i);
      if (du.norm() < 1e-16) break;
    }
    EXPECT_LT((u - exact).cwiseAbs().maxCoeff(), 1e-10 * exact.cwiseAbs().maxCoeff()) << name(rule);
    // Constant stress at every point, equal to the exact one.
    assemble(p, rule, mat, exact, f, k, s);
    const Eigen::Matrix2d ff = Eigen::Matrix2d::Identity() + a;
    const Vec3 e = green_lagrange(ff);
    const Vec3 pk2 = mat.elastic_tangent() * e;
    const double l3 = std::sqrt(1 + 2 * (-0.3 / 200e9 * (pk2(0) + pk2(1))));
    const Vec3 sigma = cauchy_from_pk2(ff, pk2, l3);
    for (const auto& si : s) EXPECT_LT((si - sigma).norm(), 1e-10 * sigma.norm()) << name(rule);
  }
}

// Element tangent = derivative of the element force, for every rule, in a plastic state
// with large rotation (material + geometric stiffness consistent).
TEST(Cps8, TangentMatchesFiniteDifferences) {
  MaterialInput m;
  m.hardening = {{273e6, 0.0}, {320e6, 0.02113}};
  const J2PlaneStress mat(m);
  const Patch p = distorted_patch();
  ElementCoords xe;
  for (int a = 0; a < 8; ++a) xe.row(a) = p.x[p.elements[0][a]].transpose();
  for (Integration rule : rules) {
    const Cps8Geometry g = cps8_geometry(xe, rule, 0.0125);
    std::vector<PointState> committed(9), trial(9);
    for (auto& c : committed) {
      c.stress = Vec3(150e6, -60e6, 40e6);
      c.peeq = 0.004;
    }
    // Rotation by 0.3 rad plus a plastic stretch.
    double du[16];
    const Mat2 r = rotation(0.3);
    for (int a = 0; a < 8; ++a) {
      const Eigen::Vector2d x = xe.row(a).transpose();
      const Eigen::Vector2d d = r * (x + Eigen::Vector2d(4e-3 * x.x() + 1e-3 * x.y() * x.y(), -2e-3 * x.y())) - x;
      du[2 * a] = d.x();
      du[2 * a + 1] = d.y();
    }
    Cps8Output o, op, om;
    cps8_evaluate(g, du, committed.data(), trial.data(), mat, true, o);
    ElementMatrix fd;
    const double h = 1e-9;
    for (int j = 0; j < 16; ++j) {
      const double keep = du[j];
      du[j] = keep + h;
      cps8_evaluate(g, du, committed.data(), trial.data(), mat, false, op);
      du[j] = keep - h;
      cps8_evaluate(g, du, committed.data(), trial.data(), mat, false, om);
      du[j] = keep;
      fd.col(j) = (op.force - om.force) / (2 * h);
    }
    EXPECT_LT((fd - o.tangent).norm() / o.tangent.norm(), 1e-6) << name(rule);
    EXPECT_LT((o.tangent - o.tangent.transpose()).norm() / o.tangent.norm(), 1e-12) << name(rule);
  }
}

// (b) A pre-stressed element turned rigidly by 90° in 10 increments: the Cauchy stress
// turns with the body, its invariants stay to 1e-8, and the increments agree with the
// thesis's Hughes–Winget rotation.
TEST(Cps8, RigidRotationOfPrestressedElement) {
  const J2PlaneStress mat(elastic_material());
  const Patch p = distorted_patch();
  for (Integration rule : rules) {
    std::vector<Eigen::Vector2d> x(8);
    for (int a = 0; a < 8; ++a) x[a] = p.x[p.elements[3][a]];
    auto geometry = [&] {
      ElementCoords xe;
      for (int a = 0; a < 8; ++a) xe.row(a) = x[a].transpose();
      return cps8_geometry(xe, rule, 0.01);
    };
    std::vector<PointState> committed(9), trial(9);
    // Pre-stress: a homogeneous stretch and shear.
    Eigen::Matrix2d a;
    a << 1.0e-3, 0.6e-3, 0.2e-3, -0.4e-3;
    double du[16];
    Cps8Output o;
    {
      const Cps8Geometry g = geometry();
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector2d d = a * x[k];
        du[2 * k] = d.x();
        du[2 * k + 1] = d.y();
        x[k] += d;
      }
      cps8_evaluate(g, du, committed.data(), trial.data(), mat, false, o);
      committed = trial;
    }
    const int np = points(rule);
    std::vector<Vec3> sigma0;
    for (int i = 0; i < np; ++i) sigma0.push_back(committed[i].stress);
    const double step = std::numbers::pi / 20;  // 10 × 9°
    const Mat2 r = rotation(step);
    for (int inc = 0; inc < 10; ++inc) {
      const Cps8Geometry g = geometry();
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector2d d = r * x[k] - x[k];
        du[2 * k] = d.x();
        du[2 * k + 1] = d.y();
      }
      // Hughes–Winget ΔR from ∂Δu/∂x at the mid-increment configuration equals R.
      ElementCoords mid;
      for (int k = 0; k < 8; ++k) mid.row(k) = (0.5 * (x[k] + r * x[k])).transpose();
      const Cps8Geometry gm = cps8_geometry(mid, Integration::Full, 0.01);
      Mat2 l = Mat2::Zero();
      for (int k = 0; k < 8; ++k) {
        l(0, 0) += du[2 * k] * gm.dndx[4](k, 0);
        l(0, 1) += du[2 * k] * gm.dndx[4](k, 1);
        l(1, 0) += du[2 * k + 1] * gm.dndx[4](k, 0);
        l(1, 1) += du[2 * k + 1] * gm.dndx[4](k, 1);
      }
      EXPECT_LT((hughes_winget_rotation(l) - r).norm(), 1e-12);
      cps8_evaluate(g, du, committed.data(), trial.data(), mat, false, o);
      committed = trial;
      for (int k = 0; k < 8; ++k) x[k] = r * x[k];
    }
    const Mat2 r90 = rotation(std::numbers::pi / 2);
    for (int i = 0; i < np; ++i) {
      Mat2 s;
      s << sigma0[i](0), sigma0[i](2), sigma0[i](2), sigma0[i](1);
      const Mat2 expect = r90 * s * r90.transpose();
      const Vec3& got = committed[i].stress;
      const double scale = sigma0[i].norm();
      EXPECT_LT(std::abs(got(0) - expect(0, 0)), 1e-8 * scale) << name(rule);
      EXPECT_LT(std::abs(got(1) - expect(1, 1)), 1e-8 * scale) << name(rule);
      EXPECT_LT(std::abs(got(2) - expect(0, 1)), 1e-8 * scale) << name(rule);
      EXPECT_NEAR(got(0) + got(1), sigma0[i](0) + sigma0[i](1), 1e-8 * scale);
      EXPECT_NEAR(got(0) * got(1) - got(2) * got(2),
                  sigma0[i](0) * sigma0[i](1) - sigma0[i](2) * sigma0[i](2), 1e-8 * scale * scale);
      EXPECT_NEAR(mises(got), mises(sigma0[i]), 1e-8 * scale);
    }
  }
}
