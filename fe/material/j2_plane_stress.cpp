#include <Eigen/Dense>
#include "fe/material/j2_plane_stress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ringcrush::fe {

HardeningTable::HardeningTable(std::vector<HardeningPoint> points) : points_(std::move(points)) {
  if (points_.empty()) throw std::invalid_argument("hardening table: at least one point");
  if (points_.front().plastic_strain != 0.0)
    throw std::invalid_argument("hardening table: the first point must be at plastic strain 0");
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!(points_[i].yield_stress_pa > 0))
      throw std::invalid_argument(fmt::format("hardening table: point {} has a non-positive yield stress", i));
    if (i > 0 && !(points_[i].plastic_strain > points_[i - 1].plastic_strain))
      throw std::invalid_argument("hardening table: plastic strains must increase");
  }
  min_yield_ = points_.front().yield_stress_pa;
  for (std::size_t i = 1; i < points_.size(); ++i) {
    const auto& p = points_[i - 1];
    const auto& q = points_[i];
    rise_.push_back(q.yield_stress_pa - p.yield_stress_pa);
    run_.push_back(q.plastic_strain - p.plastic_strain);
    slope_.push_back(rise_.back() / run_.back());
    min_yield_ = std::min(min_yield_, q.yield_stress_pa);
  }
}

// The segment formulas below are the ones of the first version of the table (rise · (ᾱ − ᾱ_i)
// / run, rise / run): the tabulated differences are the values it formed per call, so every
// result is bitwise unchanged (tests/fe/j2_return_map_bitwise_test.cpp).
double HardeningTable::yield_stress(double a) const {
  if (a <= 0.0) return points_.front().yield_stress_pa;
  for (std::size_t i = 1; i < points_.size(); ++i)
    if (a < points_[i].plastic_strain)
      return points_[i - 1].yield_stress_pa + rise_[i - 1] * (a - points_[i - 1].plastic_strain) / run_[i - 1];
  return points_.back().yield_stress_pa;
}

double HardeningTable::slope(double a) const {
  for (std::size_t i = 1; i < points_.size(); ++i)
    if (a < points_[i].plastic_strain) return slope_[i - 1];
  return 0.0;
}

void HardeningTable::yield_stress_and_slope(double a, double& sy, double& h) const {
  for (std::size_t i = 1; i < points_.size(); ++i)
    if (a < points_[i].plastic_strain) {
      sy = a <= 0.0 ? points_.front().yield_stress_pa
                    : points_[i - 1].yield_stress_pa + rise_[i - 1] * (a - points_[i - 1].plastic_strain) / run_[i - 1];
      h = slope_[i - 1];
      return;
    }
  sy = a <= 0.0 ? points_.front().yield_stress_pa : points_.back().yield_stress_pa;
  h = 0.0;
}

J2PlaneStress::J2PlaneStress(const MaterialInput& m)
    : e_(m.youngs_modulus_pa), nu_(m.poisson_ratio), g_(m.youngs_modulus_pa / (2.0 * (1.0 + m.poisson_ratio))),
      table_(m.hardening) {
  if (!(e_ > 0) || !(nu_ > -1.0 && nu_ < 0.5))
    throw std::invalid_argument("material: E must be positive and ν in (−1, 0.5)");
  const double f = e_ / (1.0 - nu_ * nu_);
  c_ << f, f * nu_, 0, f * nu_, f, 0, 0, 0, g_;
  c_inv_ = c_.inverse();
  p_ << 2.0 / 3.0, -1.0 / 3.0, 0, -1.0 / 3.0, 2.0 / 3.0, 0, 0, 0, 2.0;
  // 1/d1², 1/d2² at Δγ₀ = 1/(2G), with d1, d2 as return_map() forms them there.
  const double c1 = e_ / (3.0 * (1.0 - nu_)), c2 = 2.0 * g_, dg0 = 1.0 / c2;
  const double d1 = 1.0 + c1 * dg0, d2 = 1.0 + c2 * dg0;
  bracket_k1_ = 1.0 / (d1 * d1);
  bracket_k2_ = 1.0 / (d2 * d2);
}

double mises(const Vec3& s) {
  return std::sqrt(std::max(0.0, s(0) * s(0) + s(1) * s(1) - s(0) * s(1) + 3.0 * s(2) * s(2)));
}

// Return mapping (Simo & Hughes, Computational Inelasticity §3.4; plane-stress projection).
// With P the plane-stress deviatoric projector (ξ = SᵀPS = ⅔ σ_mises²), the backward-Euler
// equations are
//   S = σ_n + C (ΔE − Δγ P S),   ᾱ = ᾱ_n + √(2/3) Δγ √ξ,   f = ½ξ − ⅓ σy(ᾱ)² = 0,
// with S_trial = σ_n + C ΔE.
// C and P share eigenvectors ((1,1,0), (1,−1,0), (0,0,1)), so S(Δγ) = Ξ(Δγ) C⁻¹ S_trial with
// Ξ = (C⁻¹ + Δγ P)⁻¹ is diagonal in that basis and ξ(Δγ) is the scalar function
//   ξ(Δγ) = (S11+S22)²/(6(1 + EΔγ/(3(1−ν)))²) + (½(S22−S11)² + 2 S12²)/(1 + 2GΔγ)²
// of the trial stress. f(Δγ) decreases monotonically, so a Newton iteration safeguarded by
// bisection always finds the root. Linearising the three equations gives the consistent
// tangent
//   C_alg = Ξ − N Nᵀ / (SᵀPΞPS + β),  N = ΞPS,  β = ⅔ H ξ / (1 − ⅔ H Δγ),
// with H = dσy/dᾱ on the active hardening segment.
J2Update J2PlaneStress::update(const Vec3& strain_increment, const PointState& committed) const {
  return return_map(strain_increment, committed, true);
}

J2Update J2PlaneStress::return_map(const Vec3& strain_increment, const PointState& committed,
                                   bool want_tangent) const {
  J2Update out;
  out.peeq = committed.peeq;
  const Vec3 trial = committed.stress + c_ * strain_increment;
  const double sy_n = table_.yield_stress(committed.peeq);
  const double xi_trial = trial.dot(p_ * trial);
  const double f_trial = 0.5 * xi_trial - sy_n * sy_n / 3.0;
  if (f_trial <= 1e-12 * sy_n * sy_n) {
    out.stress = trial;
    if (want_tangent) out.tangent = c_;
    else out.tangent.setZero();  // not computed
    out.elastic_energy = 0.5 * trial.dot(c_inv_ * trial);
    out.strain33_increment = -nu_ / e_ * (trial(0) + trial(1) - committed.stress(0) - committed.stress(1));
    return out;
  }

  const double a1 = (trial(0) + trial(1)) * (trial(0) + trial(1)) / 6.0;
  const double a2 = 0.5 * (trial(1) - trial(0)) * (trial(1) - trial(0)) + 2.0 * trial(2) * trial(2);
  const double c1 = e_ / (3.0 * (1.0 - nu_));
  const double c2 = 2.0 * g_;
  const double sq23 = std::sqrt(2.0 / 3.0);
  auto xi_of = [&](double dg, double& dxi) {
    const double d1 = 1.0 + c1 * dg, d2 = 1.0 + c2 * dg;
    dxi = -2.0 * a1 * c1 / (d1 * d1 * d1) - 2.0 * a2 * c2 / (d2 * d2 * d2);
    return a1 / (d1 * d1) + a2 / (d2 * d2);
  };
  auto residual = [&](double dg, double& df) {
    double dxi;
    const double xi = xi_of(dg, dxi);
    const double sxi = std::sqrt(xi);
    const double alpha = committed.peeq + sq23 * dg * sxi;
    const double dalpha = sq23 * (sxi + dg * dxi / (2.0 * sxi));
    double sy, h;
    table_.yield_stress_and_slope(alpha, sy, h);
    df = 0.5 * dxi - 2.0 / 3.0 * sy * h * dalpha;
    return 0.5 * xi - sy * sy / 3.0;
  };

  // Bracket [lo, hi] with f(lo) > 0 > f(hi). f(1/c2) need not be evaluated where a bound shows
  // it negative: ξ(1/c2) = k1 a1 + k2 a2 (to rounding) and σy ≥ its table minimum, so with a
  // margin far above rounding (1e-9 relative) the evaluated f(1/c2) is negative and the loop
  // below would have stopped at once, hi unchanged (and its df is overwritten below).
  double lo = 0.0, hi = 1.0 / c2, df = 0.0;
  const double sy_min = table_.min_yield_stress();
  if (!(0.5 * (bracket_k1_ * a1 + bracket_k2_ * a2) * (1.0 + 1e-9) < sy_min * sy_min / 3.0 * (1.0 - 1e-9)))
    while (residual(hi, df) > 0.0) hi *= 2.0;
  double dg = 0.0;
  double f = f_trial;
  // f′(0), as residual(0) forms it: at Δγ = 0, d1 = d2 = 1 exactly, ᾱ = ᾱ_n (σy = sy_n) and
  // dᾱ/dΔγ = √(2/3) √ξ_0 (the Δγ ξ′ term is a signed zero), so only the slope is looked up.
  {
    const double dxi0 = -2.0 * a1 * c1 - 2.0 * a2 * c2;
    const double dalpha0 = sq23 * std::sqrt(a1 + a2);
    df = 0.5 * dxi0 - 2.0 / 3.0 * sy_n * table_.slope(committed.peeq) * dalpha0;
  }
  const double ftol = 1e-14 * sy_n * sy_n;
  for (int it = 0; it < 200; ++it) {
    double next = dg - f / df;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    dg = next;
    f = residual(dg, df);
    if (f > 0.0) lo = dg; else hi = dg;
    if (std::abs(f) <= ftol || hi - lo <= 1e-15 * hi) break;
  }

  Mat3 xi_mat = (c_inv_ + dg * p_).inverse();
  const Vec3 s = xi_mat * (c_inv_ * trial);
  const Vec3 ps = p_ * s;
  const double xi = s.dot(ps);
  const double alpha = committed.peeq + sq23 * dg * std::sqrt(xi);
  out.stress = s;
  if (want_tangent) {
    const double h = table_.slope(alpha);
    const Vec3 n = xi_mat * ps;
    const double beta = 2.0 / 3.0 * h * xi / (1.0 - 2.0 / 3.0 * h * dg);
    out.tangent = xi_mat - n * n.transpose() / (ps.dot(n) + beta);
  } else {
    out.tangent.setZero();  // not computed
  }
  out.plastic = true;
  out.plastic_increment = dg * ps;
  out.peeq = alpha;
  // Plastic work of the increment by the trapezoidal rule, ½ (S_n + S_{n+1}) : ΔEp — the
  // quadrature of the drivers' force work (energy_balance.hpp), so that Δψ + ΔD equals
  // ½ (S_n + S_{n+1}) : ΔE exactly. It is ≥ 0: |S_n|_P ≤ |S_{n+1}|_P (the yield surface only
  // grows; up to the O(ΔE) push-forward of the committed stress) and Cauchy–Schwarz in the
  // P inner product. The backward-Euler value S_{n+1} : ΔEp
  // is larger by ½ ΔS : ΔEp ≥ 0 per step, an O(Δ) error that a stress chattering across the
  // yield surface at the step rate (an undamped high mode of explicit integration) accumulates
  // without bound: 19.7 % of KE0 on the selective explicit thesis run (README, "Explicit").
  out.dissipation = 0.5 * (s + committed.stress).dot(out.plastic_increment);
  out.elastic_energy = 0.5 * s.dot(c_inv_ * s);
  // Plastic flow is isochoric: ΔEp33 = −(ΔEp11 + ΔEp22).
  out.strain33_increment = -nu_ / e_ * (s(0) + s(1) - committed.stress(0) - committed.stress(1)) -
                           out.plastic_increment(0) - out.plastic_increment(1);
  return out;
}

}  // namespace ringcrush::fe
