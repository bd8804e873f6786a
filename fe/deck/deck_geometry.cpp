#include "fe/deck/deck_geometry.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ringcrush::fe::deck {

namespace {
Point sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point add(const Point& a, const Point& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Point scale(const Point& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Point& a) { return std::sqrt(dot(a, a)); }

Point unit(const Point& a, const char* what) {
  const double n = norm(a);
  if (!(n > 0.0) || !std::isfinite(n)) throw std::invalid_argument(std::string(what) + " has zero length");
  return scale(a, 1.0 / n);
}
}  // namespace

Point straight_point(const Point& a, const Point& b, double t) { return add(a, scale(sub(b, a), t)); }

Point arc_point(const Point& a, const Point& b, const Point& centre, const Point& normal, double t) {
  const Point n = unit(normal, "arc normal direction");
  const Point ra = sub(a, centre), rb = sub(b, centre);
  const double ha = dot(ra, n), hb = dot(rb, n);           // offsets along the normal
  const Point pa = sub(ra, scale(n, ha)), pb = sub(rb, scale(n, hb));  // in-plane radii
  const double r_a = norm(pa), r_b = norm(pb);
  if (!(r_a > 0.0) || !(r_b > 0.0))
    throw std::invalid_argument("arc end node lies on the arc centre (zero radius)");
  const Point e1 = scale(pa, 1.0 / r_a);
  const Point e2 = cross(n, e1);
  double angle = std::atan2(dot(cross(pa, pb), n), dot(pa, pb));
  if (angle <= 0.0) angle += 2.0 * std::numbers::pi;  // counter-clockwise about n, in (0, 2π]
  const double phi = t * angle;
  const double r = r_a + t * (r_b - r_a);
  const double h = ha + t * (hb - ha);
  return add(centre, add(scale(n, h), add(scale(e1, r * std::cos(phi)), scale(e2, r * std::sin(phi)))));
}

Point shift_rotate(const Point& p, const Point& shift, const Point& axis_a, const Point& axis_b,
                   double angle_deg) {
  const Point q = add(p, shift);
  if (angle_deg == 0.0) return q;
  // Rodrigues: v' = v cos θ + (k × v) sin θ + k (k·v)(1 − cos θ), v measured from the axis.
  const Point k = unit(sub(axis_b, axis_a), "rotation axis");
  const double th = angle_deg * std::numbers::pi / 180.0;
  const Point v = sub(q, axis_a);
  const Point rotated = add(add(scale(v, std::cos(th)), scale(cross(k, v), std::sin(th))),
                            scale(k, dot(k, v) * (1.0 - std::cos(th))));
  return add(axis_a, rotated);
}

Point reflect_line(const Point& p, const Point& a, const Point& b) {
  const Point d = unit(sub(b, a), "reflection line");
  const Point v = sub(p, a);
  const Point foot = add(a, scale(d, dot(v, d)));  // nearest point of the line
  return sub(scale(foot, 2.0), p);
}

}  // namespace ringcrush::fe::deck
