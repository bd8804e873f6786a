// Level 3 wrap with a travelling hinge F placed by the shear-free condition (THEORY §4.5:
// "θ_F … located by the Owens–Symonds shear-free condition Q = 0"; thesis §4.2.3: the plastic
// zones nucleate at E and F and travel along the arcs).
//
// Configuration. One half of the lower quadrant, material arc length u from C (u = 0) to B
// (u = L = πR/2), tangent angle β(u), curvature κ = −dβ/du (1/R undeformed, β = −π/2 − u/R).
// C is the origin of the lower quadrant and the upper half is rigid in this mechanism.
//
// Instantaneous mechanism with F at u_F (θ_F = 90° + u_F/R), curvature-rate scale c = 1:
//   β̇(u) = ω_C                           u < u_F   (C–F turns rigidly about C)
//   β̇(u) = ω_C + ω_F + (u − u_F)          u > u_F   (hinge F, arc F–B bending, κ̇ = −1)
//   symmetry at B (tangent horizontal):   ω_C + ω_F + (L − u_F) = 0
//   B stays on the axis:                  ẋ_B = −∫ sin β β̇ du = 0
//   rise of B (the crush rate):           δ̇ = ẏ_B = ∫ cos β β̇ du
//   dissipation rate (both halves):       Ḋ = 2 M0 (|ω_C| + |ω_F| + (L − u_F))
// Two linear conditions on (ω_C, ω_F): one degree of freedom, load P(u_F) = Ḋ/δ̇ by virtual
// work (the chain's contact force does work P δ̇).
//
// Shear-free F. Let M(u) be a moment field in equilibrium with the loads, whose power is
// P δ̇, that is at yield on the mechanism: M = M0 sgn ω at C and F and on the arc F–B.
// Virtual power with that field holds for every compatible rate field, so for every u_F
//   (P/2) δ̇(u_F) = M_C ω_C(u_F) + M(u_F) ω_F(u_F) + ∫_{u_F}^{L} M du,
// while the kinematic load P_k(u_F) uses M0 in place of M. Differentiating both in u_F at the
// u_F* where the field is at yield (P_k = P there) and subtracting:
//   (δ̇/2) dP_k/du_F = −ω_F dM/du(u_F*) = ω_F Q(u_F*)     (dM/ds = −Q for the curved beam).
// So dP_k/du_F = 0 ⇔ Q = 0 at F: the shear-free hinge is the stationary point of the
// virtual-work load in the hinge position, the least of the upper bounds (Jones, Structural
// Impact, travelling hinges; the same argument fixes F once at the onset in
// level3_optimal_theta_f). A travelling F is therefore found, at every instant of the wrap,
// as the θ_F of least instantaneous load on the CURRENT configuration; material passes
// through the moving hinge and keeps the rotation it received (a spread kink).
// Caveat: the chain gives the contact's power as P δ̇ (resultant times the rise of B), exact
// for a point load at B; under a point load the moment is linear in position and cannot stay
// at M0 along a curved arc (that needs the next ring's pressure spread over F–B, p = −κN with
// Q = 0), so P_k is an upper bound, and F is placed where that bound is least. The statics
// check under point contacts (hinge/level3_statics.hpp) confirms it: 2.36 M0 at the wrap
// onset of Test 30 at 45 m/s, peaking at A, C and 146° on arc F–B.
//
// Tracing: midpoint rule in the curvature at B (c = 1: κ_B falls at unit rate while the arc
// reaches B), F re-placed at both stages; the closure x_B is restored after each step by a
// uniform bend of the quadrant of size O(step³) that is not counted as dissipation.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "level3_mechanism.hpp"

namespace ringcrush::hinge {

using std::numbers::pi;

namespace {

// The instantaneous mechanism from the integrals of the configuration over the quadrant
// (S0 = ∫ sin β, C0 = ∫ cos β) and over the arc F–B (S_F, C_F, and the first moments G_s, G_c
// of sin β, cos β about u_F), unit curvature rate on the arc of length `arc`.
WrapRate mechanism_rate(double M0, double theta_f, double arc, double s0, double c0, double sf, double cf,
                        double gs, double gc) {
  WrapRate w;
  w.theta_f = theta_f;
  w.omega_c = (arc * sf - gs) / (s0 - sf);  // closure ẋ_B = 0 with symmetry eliminated
  w.omega_f = -arc - w.omega_c;             // symmetry at B
  w.crush_rate = w.omega_c * c0 + w.omega_f * cf + gc;
  const double dissipation = 2.0 * M0 * (std::abs(w.omega_c) + std::abs(w.omega_f) + arc);
  w.load = w.crush_rate > 0.0 ? dissipation / w.crush_rate : std::numeric_limits<double>::infinity();
  return w;
}

// Golden section of f over [a, b] (f returns a WrapRate, minimised in load).
template <class F>
WrapRate golden_least_load(F f, double a, double b, int iterations) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  WrapRate wc = f(c), wd = f(d);
  for (int it = 0; it < iterations; ++it) {
    if (wc.load < wd.load) { b = d; d = c; wd = wc; c = b - g * (b - a); wc = f(c); }
    else { a = c; c = d; wc = wd; d = a + g * (b - a); wd = f(d); }
  }
  return wc.load < wd.load ? wc : wd;
}

constexpr double kThetaLo = 91.0 * pi / 180.0, kThetaHi = 179.0 * pi / 180.0;

// A cell field β_k on cells [e_k, e_{k+1}] of the quadrant, with suffix sums so that the
// mechanism costs O(log n) for any u_F.
class QuadrantSums {
 public:
  QuadrantSums(double R, double M0, const std::vector<double>& edges, const std::vector<double>& beta)
      : R_(R), M0_(M0), e_(edges), n_(beta.size()) {
    ss_.assign(n_ + 1, 0.0);
    cs_.assign(n_ + 1, 0.0);
    sus_.assign(n_ + 1, 0.0);
    cus_.assign(n_ + 1, 0.0);
    sin_.resize(n_);
    cos_.resize(n_);
    for (std::size_t k = n_; k-- > 0;) {
      sin_[k] = std::sin(beta[k]);
      cos_[k] = std::cos(beta[k]);
      const double h = e_[k + 1] - e_[k], um = 0.5 * (e_[k] + e_[k + 1]);
      ss_[k] = ss_[k + 1] + sin_[k] * h;
      cs_[k] = cs_[k + 1] + cos_[k] * h;
      sus_[k] = sus_[k + 1] + sin_[k] * h * um;
      cus_[k] = cus_[k + 1] + cos_[k] * h * um;
    }
  }

  std::size_t cell_of(double u) const {
    const auto it = std::upper_bound(e_.begin(), e_.end(), u);
    const std::size_t k = it == e_.begin() ? 0 : static_cast<std::size_t>(it - e_.begin()) - 1;
    return std::min(k, n_ - 1);
  }

  WrapRate rate(double theta_f) const { return rate_in(cell_of(R_ * (theta_f - 0.5 * pi)), theta_f); }
  // F in cell m (u_F ∈ [e_m, e_{m+1}]).
  WrapRate rate_in(std::size_t m, double theta_f) const {
    const double uf = R_ * (theta_f - 0.5 * pi);
    const double b = e_[m + 1] - uf;  // part of cell m in the arc
    const double sf = ss_[m + 1] + sin_[m] * b, cf = cs_[m + 1] + cos_[m] * b;
    const double gs = sus_[m + 1] - uf * ss_[m + 1] + sin_[m] * 0.5 * b * b;
    const double gc = cus_[m + 1] - uf * cs_[m + 1] + cos_[m] * 0.5 * b * b;
    return mechanism_rate(M0_, theta_f, e_[n_] - uf, ss_[0], cs_[0], sf, cf, gs, gc);
  }

  // θ_F of least load: every cell edge in [91°, 179°], then a golden section within the
  // cells either side of the best edge.
  WrapRate shear_free() const {
    WrapRate best = rate(kThetaLo);
    std::size_t kb = cell_of(R_ * (kThetaLo - 0.5 * pi));
    for (std::size_t k = 1; k < n_; ++k) {
      const double th = 0.5 * pi + e_[k] / R_;
      if (th < kThetaLo || th > kThetaHi) continue;
      const WrapRate w = rate_in(k, th);
      if (w.load < best.load) { best = w; kb = k; }
    }
    const double a = std::max(kThetaLo, 0.5 * pi + e_[kb == 0 ? 0 : kb - 1] / R_);
    const double b = std::min(kThetaHi, 0.5 * pi + e_[std::min(kb + 1, n_)] / R_);
    const WrapRate w = golden_least_load([this](double th) { return rate(th); }, a, b, 24);
    return w.load < best.load ? w : best;
  }

  // β advanced by dτ along the mechanism w (cell averages: the cell holding F is split).
  void advance(const std::vector<double>& beta, const WrapRate& w, double dtau, std::vector<double>& out) const {
    const double uf = R_ * (w.theta_f - 0.5 * pi);
    for (std::size_t k = 0; k < n_; ++k) {
      const double u0 = e_[k], u1 = e_[k + 1];
      double rate = w.omega_c;
      if (u0 >= uf) rate += w.omega_f + (0.5 * (u0 + u1) - uf);
      else if (u1 > uf) {
        const double b = u1 - uf;
        rate += (b * w.omega_f + 0.5 * b * b) / (u1 - u0);
      }
      out[k] = beta[k] + dtau * rate;
    }
  }

  double x_b() const { return R_ + cs_[0]; }  // B's abscissa with C at (R, 0)
  double y_b() const { return ss_[0]; }
  // ∂x_B/∂ε for the closure correction β_k += ε (L − u_k)/L.
  double closure_gain() const {
    const double L = e_[n_];
    double s = 0.0;
    for (std::size_t k = 0; k < n_; ++k) s -= sin_[k] * (e_[k + 1] - e_[k]) * (L - 0.5 * (e_[k] + e_[k + 1])) / L;
    return s;
  }

 private:
  double R_, M0_;
  const std::vector<double>& e_;
  std::size_t n_;
  std::vector<double> ss_, cs_, sus_, cus_, sin_, cos_;
};

std::vector<double> uniform_edges(double L, int cells) {
  std::vector<double> e(static_cast<std::size_t>(cells) + 1);
  for (int k = 0; k <= cells; ++k) e[static_cast<std::size_t>(k)] = L * k / cells;
  return e;
}

}  // namespace

std::vector<double> level3_undeformed_tangent(const Level3Ring& r, int cells) {
  if (cells < 8) throw std::invalid_argument(fmt::format("wrap: cells = {} (need >= 8)", cells));
  const double R = r.mean_radius(), h = 0.5 * pi * R / cells;
  std::vector<double> beta(static_cast<std::size_t>(cells));
  for (int k = 0; k < cells; ++k) beta[static_cast<std::size_t>(k)] = -0.5 * pi - (k + 0.5) * h / R;
  return beta;
}

namespace {
std::vector<double> checked_edges(const Level3Ring& r, const std::vector<double>& tangent,
                                  const std::vector<double>& edges) {
  r.validate();
  if (tangent.size() < 8) throw std::invalid_argument(fmt::format("wrap: {} tangent cells (need >= 8)", tangent.size()));
  if (edges.empty()) return uniform_edges(0.5 * pi * r.mean_radius(), static_cast<int>(tangent.size()));
  if (edges.size() != tangent.size() + 1 || !std::is_sorted(edges.begin(), edges.end()))
    throw std::invalid_argument(fmt::format("wrap: {} cell edges for {} cells (need cells + 1, increasing)",
                                            edges.size(), tangent.size()));
  return edges;
}
}  // namespace

WrapRate level3_wrap_rate(const Level3Ring& r, const std::vector<double>& tangent, double theta_f,
                          const std::vector<double>& edges) {
  const auto e = checked_edges(r, tangent, edges);
  if (!(theta_f > 0.5 * pi && theta_f < pi))
    throw std::invalid_argument(fmt::format("wrap: theta_F = {} rad outside (90°, 180°)", theta_f));
  return QuadrantSums(r.mean_radius(), r.plastic_moment_nm, e, tangent).rate(theta_f);
}

WrapRate level3_shear_free_rate(const Level3Ring& r, const std::vector<double>& tangent,
                                const std::vector<double>& edges) {
  const auto e = checked_edges(r, tangent, edges);
  return QuadrantSums(r.mean_radius(), r.plastic_moment_nm, e, tangent).shear_free();
}

// The undeformed circle in closed form (β = −π/2 − φ, φ = u/R, a = u_F/R):
//   S0 = C0 = −R,  S_F = −R (1 − sin a),  C_F = −R cos a,
//   G_s = −R² (π/2 − a − cos a),  G_c = −R² (1 − sin a).
WrapRate level3_onset_shear_free_rate(const Level3Ring& r) {
  r.validate();
  const double R = r.mean_radius(), M0 = r.plastic_moment_nm;
  auto rate = [&](double theta_f) {
    const double a = theta_f - 0.5 * pi;
    return mechanism_rate(M0, theta_f, R * (0.5 * pi - a), -R, -R, -R * (1.0 - std::sin(a)), -R * std::cos(a),
                          -R * R * (0.5 * pi - a - std::cos(a)), -R * R * (1.0 - std::sin(a)));
  };
  return golden_least_load(rate, kThetaLo, kThetaHi, 60);
}

WrapMechanism level3_travelling_wrap_mechanism(const Level3Ring& r, int samples, int cells) {
  r.validate();
  if (samples < 4) throw std::invalid_argument(fmt::format("wrap: samples = {} (need >= 4)", samples));
  if (cells < 8) throw std::invalid_argument(fmt::format("wrap: cells = {} (need >= 8)", cells));
  const double R = r.mean_radius(), t = r.wall_thickness_m, M0 = r.plastic_moment_nm, L = 0.5 * pi * R;
  const double k0 = 1.0 / R, k1 = -1.0 / (R + t);
  const double dtau = (k0 - k1) / samples;
  // Cells: a polygon prefers its own vertices as hinge sites, so the onset F (closed form,
  // level3_onset_shear_free_rate) is made a cell edge, cells of near-equal length either side.
  const double uf0 = R * (level3_onset_shear_free_rate(r).theta_f - 0.5 * pi);
  const int n1 = std::clamp(static_cast<int>(std::lround(cells * uf0 / L)), 1, cells - 1);
  std::vector<double> edges(static_cast<std::size_t>(cells) + 1), beta(static_cast<std::size_t>(cells));
  for (int k = 0; k <= cells; ++k)
    edges[static_cast<std::size_t>(k)] = k <= n1 ? uf0 * k / n1 : uf0 + (L - uf0) * (k - n1) / (cells - n1);
  for (std::size_t k = 0; k < beta.size(); ++k) {  // the chord of each cell of the circle
    const double a = edges[k] / R, b = edges[k + 1] / R;
    beta[k] = -0.5 * pi - 0.5 * (a + b);
  }
  std::vector<double> mid(beta.size()), next(beta.size());
  WrapMechanism w;
  w.cell_edges = edges;
  double D = 0.0, rot_c = 0.0, rot_f = 0.0, y0 = 0.0, x0 = 0.0;
  for (int j = 0; j <= samples; ++j) {
    const QuadrantSums now(R, M0, edges, beta);
    const WrapRate r1 = now.shear_free();
    if (j == 0) {
      y0 = now.y_b();
      x0 = now.x_b();
      w.theta_f = r1.theta_f;
    }
    const double q = now.y_b() - y0;
    if (!std::isfinite(r1.load) || (j > 0 && !(q > w.crush.back()))) {  // B stops rising
      if (j < 3) throw std::runtime_error("travelling wrap: no travel");
      break;
    }
    w.curvature.push_back(k0 - j * dtau);
    w.crush.push_back(q);
    w.dissipation.push_back(D);
    w.load.push_back(r1.load);
    w.chord_angle.push_back(rot_c);
    w.hinge_f.push_back(r1.theta_f);
    w.rotation_c.push_back(rot_c);
    w.rotation_f.push_back(rot_f);
    w.tangent.push_back(beta);
    if (j == samples) break;
    now.advance(beta, r1, 0.5 * dtau, mid);
    const WrapRate r2 = QuadrantSums(R, M0, edges, mid).shear_free();
    if (!std::isfinite(r2.load)) break;
    now.advance(beta, r2, dtau, next);
    D += dtau * 2.0 * M0 * (std::abs(r2.omega_c) + std::abs(r2.omega_f) + R * (pi - r2.theta_f));
    rot_c += dtau * r2.omega_c;
    rot_f += dtau * std::abs(r2.omega_f);
    // Closure: the midpoint rule lets x_B drift by O(dτ³) a step; the drift found at this
    // node is taken out with the step by a small uniform bend, zero at B, so it never
    // accumulates beyond one step's worth.
    const double eps = (x0 - now.x_b()) / now.closure_gain();
    for (std::size_t k = 0; k < next.size(); ++k) next[k] += eps * (L - 0.5 * (edges[k] + edges[k + 1])) / L;
    beta.swap(next);
  }
  if (w.crush.size() < 3) throw std::runtime_error("travelling wrap: fewer than 3 nodes");
  return w;
}

double WrapMechanism::theta_f_at(double q) const {
  if (hinge_f.empty()) return theta_f;
  const auto it = std::upper_bound(crush.begin(), crush.end(), q);
  if (it == crush.begin()) return hinge_f.front();
  if (it == crush.end()) return hinge_f.back();
  const std::size_t k = static_cast<std::size_t>(it - crush.begin());
  const double f = (q - crush[k - 1]) / (crush[k] - crush[k - 1]);
  return hinge_f[k - 1] + f * (hinge_f[k] - hinge_f[k - 1]);
}

std::string to_string(Level3HingeF h) {
  switch (h) {
    case Level3HingeF::LeastOnsetLoad: return "least_onset_load";
    case Level3HingeF::ShearFree: return "shear_free";
  }
  return "?";
}

}  // namespace ringcrush::hinge
