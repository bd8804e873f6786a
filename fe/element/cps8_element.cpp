#include <Eigen/Dense>
#include "fe/element/cps8_element.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "fe/kinematics.hpp"

namespace ringcrush::fe {

namespace {

// ∂N/∂X from ∂N/∂(g,h) and the reference coordinates; returns det J₀.
double reference_gradients(const ElementCoords& x, double g, double h, ShapeVec& n, ShapeGrad& dndx) {
  ShapeGrad dn;
  cps8_shape(g, h, n, dn);
  const Mat2 j = dn.transpose() * x;  // J_ij = ∂X_j/∂ξ_i
  const double det = j.determinant();
  dndx = dn * j.inverse().transpose();
  return det;
}

// Strain-displacement row block of δE (Voigt) at a point with deformation gradient f.
inline void fill_b(const ShapeGrad& d, const Mat2& f, Eigen::Matrix<double, 3, 16>& b) {
  for (int a = 0; a < 8; ++a) {
    const double nx = d(a, 0), ny = d(a, 1);
    b(0, 2 * a) = f(0, 0) * nx;
    b(0, 2 * a + 1) = f(1, 0) * nx;
    b(1, 2 * a) = f(0, 1) * ny;
    b(1, 2 * a + 1) = f(1, 1) * ny;
    b(2, 2 * a) = f(0, 0) * ny + f(0, 1) * nx;
    b(2, 2 * a + 1) = f(1, 0) * ny + f(1, 1) * nx;
  }
}

// The tangent is symmetric (cps8_element.hpp), so the per-point sums below fill its upper
// triangle only and cps8_evaluate mirrors it once: the point loop is ~55 % of an HHT run
// on the thesis chain (callgrind), and half the products is most of that.

// Geometric stiffness c · (∇N_a · A ∇N_b) δ_ij: the node-pair scalars are summed over the
// points in an 8×8 matrix and spread onto the two displacement directions once per element.
using NodePairMatrix = Eigen::Matrix<double, 8, 8>;
inline void add_geometric(const ShapeGrad& d, const Mat2& a, double c, NodePairMatrix& g) {
  g.noalias() += (c * (d * a)).lazyProduct(d.transpose());
}
inline void spread_geometric_upper(const NodePairMatrix& g, ElementMatrix& k) {
  for (int q = 0; q < 8; ++q)
    for (int p = 0; p <= q; ++p) {
      k(2 * p, 2 * q) += g(p, q);
      k(2 * p + 1, 2 * q + 1) += g(p, q);
    }
}

// Adds bᵀ c to the upper triangle of the tangent (c = C b, so the product is symmetric).
inline void add_material_upper(const Eigen::Matrix<double, 3, 16>& b, const Eigen::Matrix<double, 3, 16>& cb,
                               ElementMatrix& k) {
  const Eigen::Matrix<double, 16, 3> bt = b.transpose();
  for (int q = 0; q < 16; ++q) {
    const double c0 = cb(0, q), c1 = cb(1, q), c2 = cb(2, q);
    for (int p = 0; p <= q; ++p) k(p, q) += bt(p, 0) * c0 + bt(p, 1) * c1 + bt(p, 2) * c2;
  }
}

}  // namespace

Cps8Geometry cps8_geometry(const ElementCoords& x, Integration rule, double thickness) {
  Cps8Geometry geo;
  geo.rule = rule;
  const auto pts = gauss_rule(rule == Integration::Reduced ? 2 : 3);
  geo.points = static_cast<int>(pts.size());
  for (int i = 0; i < geo.points; ++i) {
    const double det = reference_gradients(x, pts[i].g, pts[i].h, geo.n[i], geo.dndx[i]);
    if (!(det > 0))
      throw std::invalid_argument(fmt::format("CPS8 element inverted or degenerate (det J = {:g})", det));
    geo.weight[i] = pts[i].weight * det * thickness;
  }
  if (rule == Integration::Selective) {
    const auto red = gauss_rule(2);
    const double s3 = std::sqrt(3.0);
    for (int r = 0; r < 4; ++r) {
      ShapeVec n;
      reference_gradients(x, red[r].g, red[r].h, n, geo.dndx_reduced[r]);
      const double gr = red[r].g > 0 ? 1.0 : -1.0, hr = red[r].h > 0 ? 1.0 : -1.0;
      // Bilinear interpolant through the 2×2 points, evaluated at each 3×3 point.
      for (int i = 0; i < geo.points; ++i)
        geo.barlow(i, r) = 0.25 * (1 + s3 * pts[i].g * gr) * (1 + s3 * pts[i].h * hr);
    }
  }
  return geo;
}

void cps8_evaluate(const Cps8Geometry& geo, const double* u, const PointState* committed,
                   PointState* trial, const J2PlaneStress& material, bool want_tangent,
                   Cps8Output& out) {
  // Force only (explicit dynamics, residual-only evaluations): the B-free path of
  // cps8_force.cpp. Below is the reference path that forms B, used with the tangent.
  if (!want_tangent) {
    cps8_force(geo, u, committed, trial, material, out);
    return;
  }
  out.force.setZero();
  out.tangent.setZero();
  out.elastic_energy = 0;
  out.plastic_work = 0;
  const bool selective = geo.rule == Integration::Selective;

  // Selective: trace of E and its variation row at the 2×2 points.
  std::array<double, 4> tr_r{};
  std::array<Eigen::Matrix<double, 1, 16>, 4> btr_r;
  if (selective) {
    Eigen::Matrix<double, 3, 16> b;
    for (int r = 0; r < 4; ++r) {
      const Mat2 f = deformation_gradient(geo.dndx_reduced[r], u);
      const auto e = green_lagrange(f);
      tr_r[r] = e(0) + e(1);
      fill_b(geo.dndx_reduced[r], f, b);
      btr_r[r] = b.row(0) + b.row(1);
    }
  }
  std::array<double, 4> q_r{};  // Σ_points w p M_r: geometric weight of the reduced points
  NodePairMatrix geometric = NodePairMatrix::Zero();

  Eigen::Matrix<double, 3, 16> b;
  for (int i = 0; i < geo.points; ++i) {
    const ShapeGrad& d = geo.dndx[i];
    const Mat2 f = deformation_gradient(d, u);
    Eigen::Vector3d e = green_lagrange(f);
    fill_b(d, f, b);
    if (selective) {
      double tr_bar = 0;
      Eigen::Matrix<double, 1, 16> btr_bar = Eigen::Matrix<double, 1, 16>::Zero();
      for (int r = 0; r < 4; ++r) {
        tr_bar += geo.barlow(i, r) * tr_r[r];
        btr_bar += geo.barlow(i, r) * btr_r[r];
      }
      const double corr = 0.5 * (tr_bar - e(0) - e(1));
      e(0) += corr;
      e(1) += corr;
      const Eigen::Matrix<double, 1, 16> bcorr = 0.5 * (btr_bar - b.row(0) - b.row(1));
      b.row(0) += bcorr;
      b.row(1) += bcorr;
    }
    const J2Update up = material.update(e, committed[i]);
    const double w = geo.weight[i] * committed[i].thickness_stretch;
    out.force.noalias() += b.transpose().lazyProduct(w * up.stress);
    out.elastic_energy += w * up.elastic_energy;
    // Trial state: Cauchy stress at the end of the increment and the history variables.
    PointState& t = trial[i];
    const double l3 = std::sqrt(std::max(1e-12, 1.0 + 2.0 * up.strain33_increment));
    t.stress = cauchy_from_pk2(f, up.stress, l3);
    t.plastic_strain = committed[i].plastic_strain + up.plastic_increment;
    t.peeq = up.peeq;
    t.plastic_work = committed[i].plastic_work + w * up.dissipation;
    t.thickness_stretch = committed[i].thickness_stretch * l3;
    out.plastic_work += t.plastic_work;
    // Small fixed-size products: lazy (coefficient-wise) evaluation, no GEMM kernel.
    const Eigen::Matrix<double, 3, 16> cb = (w * up.tangent).lazyProduct(b);
    add_material_upper(b, cb, out.tangent);
    const Mat2 s = point_stress(up.stress, geo, i, w, q_r);  // geometric part: S : Δδ Ē
    add_geometric(d, s, w, geometric);
  }
  if (selective)
    for (int r = 0; r < 4; ++r) add_geometric(geo.dndx_reduced[r], Mat2::Identity(), q_r[r], geometric);
  spread_geometric_upper(geometric, out.tangent);
  out.tangent.triangularView<Eigen::StrictlyLower>() = out.tangent.transpose();
}

Cps8Fields cps8_fields(const PointState* states, int points) {
  Cps8Fields out;
  for (int i = 0; i < points; ++i) {
    out.mises += mises(states[i].stress);
    out.peeq += states[i].peeq;
    out.sxx += states[i].stress(0);
    out.syy += states[i].stress(1);
    out.sxy += states[i].stress(2);
  }
  out.mises /= points;
  out.peeq /= points;
  out.sxx /= points;
  out.syy /= points;
  out.sxy /= points;
  return out;
}

}  // namespace ringcrush::fe
