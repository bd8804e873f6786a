#include "fe/contact/self_contact_taper.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ringcrush::fe {

namespace {

// c_a(f), c_a'(f), c_a''(f) of the piece's cubic shape functions.
void shape(const PiecePolynomial& p, double f, double* c, double* dc, double* ddc) {
  for (int a = 0; a < p.count; ++a) {
    const double* q = p.a[a];
    c[a] = q[0] + f * (q[1] + f * (q[2] + f * q[3]));
    dc[a] = q[1] + f * (2 * q[2] + 3 * f * q[3]);
    ddc[a] = 2 * q[2] + 6 * f * q[3];
  }
}

}  // namespace

ArcTaper::ArcTaper(double start_rad, double band_rad) : start(start_rad), band(band_rad) {
  if (!(std::isfinite(start_rad) && start_rad >= 0))
    throw std::invalid_argument("ArcTaper: exclusion arc must be finite and ≥ 0 rad, got " + std::to_string(start_rad));
  if (!(std::isfinite(band_rad) && band_rad >= 0))
    throw std::invalid_argument("ArcTaper: taper band must be finite and ≥ 0 rad, got " + std::to_string(band_rad));
}

double ArcTaper::weight(double delta, double* slope) const {
  if (slope) *slope = 0;
  if (!(delta > start)) return 0;
  if (!(delta < start + band)) return 1;
  const double t = (delta - start) / band;
  if (slope) *slope = 6 * t * (1 - t) / band;
  return t * t * (3 - 2 * t);
}

std::array<double, 5> unwrapped_piece_angles(const std::array<double, 5>& piece_angle, int count) {
  const double two_pi = 2 * std::numbers::pi;
  std::array<double, 5> out{};
  for (int a = 0; a < count; ++a)
    out[static_cast<std::size_t>(a)] = std::remainder(piece_angle[static_cast<std::size_t>(a)] - piece_angle[0], two_pi);
  return out;
}

double arc_to_closest_point(const PiecePolynomial& piece, const std::array<double, 5>& piece_angle,
                            const std::array<double, 5>& unwrapped, double slave_angle, double f, double* slope) {
  const double two_pi = 2 * std::numbers::pi;
  double c[5], dc[5], ddc[5];
  shape(piece, f, c, dc, ddc);
  // Node angles unwrapped about the piece's first node, so that interpolating them is
  // meaningful across the 0/2π cut.
  const double first = std::remainder(piece_angle[0] - slave_angle, two_pi);
  double d = 0, dd = 0;
  for (int a = 0; a < piece.count; ++a) {
    const double angle = first + unwrapped[static_cast<std::size_t>(a)];
    d += c[a] * angle;
    dd += dc[a] * angle;
  }
  d = std::remainder(d, two_pi);
  if (slope) *slope = d < 0 ? -dd : dd;
  return std::abs(d);
}

double arc_to_closest_point(const PiecePolynomial& piece, const std::array<double, 5>& piece_angle,
                            double slave_angle, double f, double* slope) {
  return arc_to_closest_point(piece, piece_angle, unwrapped_piece_angles(piece_angle, piece.count), slave_angle, f,
                              slope);
}

double tapered_self_force(const PiecePolynomial& p, const double* xy, double k, double f, double gap,
                          const ArcTaper& taper, double slave_angle, const std::array<double, 5>& piece_angle,
                          double* force) {
  const int n = 2 + 2 * p.count;
  std::fill(force, force + n, 0.0);
  double darc = 0, dw = 0;
  const double w = taper.weight(arc_to_closest_point(p, piece_angle, slave_angle, f, &darc), &dw);
  if (!(gap < 0) || w == 0) return w;
  double c[5], dc[5], ddc[5];
  shape(p, f, c, dc, ddc);
  double pos[2] = {0, 0}, tan[2] = {0, 0}, curv[2] = {0, 0};
  for (int a = 0; a < p.count; ++a)
    for (int d = 0; d < 2; ++d) {
      pos[d] += c[a] * xy[2 + 2 * a + d];
      tan[d] += dc[a] * xy[2 + 2 * a + d];
      curv[d] += ddc[a] * xy[2 + 2 * a + d];
    }
  const double tl = std::hypot(tan[0], tan[1]);
  if (!(tl > 0)) return 0;
  const double nx = -tan[1] / tl, ny = tan[0] / tl;
  // Through g (as surface_force): ∂g/∂x_s = n, ∂g/∂x_a = −c_a n at the closest point.
  const double kg = w * k * gap;
  force[0] = kg * nx;
  force[1] = kg * ny;
  for (int a = 0; a < p.count; ++a) {
    force[2 + 2 * a] = -kg * c[a] * nx;
    force[3 + 2 * a] = -kg * c[a] * ny;
  }
  // Through w: ½ k g² w'(Δ) Δ'(f) ∂f/∂coords, where r(f) = (x(f) − x_s)·x'(f) = 0 gives
  // ∂f/∂x_s = x'/D and ∂f/∂x_a = −(c_a x' + c_a' (x − x_s))/D, D = ∂r/∂f = x'·x' + (x − x_s)·x''
  // (> 0 at a closest point; a degenerate D leaves the term out rather than divide by it).
  const double rx = pos[0] - xy[0], ry = pos[1] - xy[1];
  const double big_d = tan[0] * tan[0] + tan[1] * tan[1] + rx * curv[0] + ry * curv[1];
  if (dw == 0 || !(big_d > 1e-12 * tl * tl)) return w;
  const double e = 0.5 * k * gap * gap * dw * darc / big_d;
  force[0] += e * tan[0];
  force[1] += e * tan[1];
  for (int a = 0; a < p.count; ++a) {
    force[2 + 2 * a] -= e * (c[a] * tan[0] + dc[a] * rx);
    force[3 + 2 * a] -= e * (c[a] * tan[1] + dc[a] * ry);
  }
  return w;
}

}  // namespace ringcrush::fe
