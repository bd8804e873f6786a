#include "compare/measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace ringcrush::compare {
namespace {
constexpr double pi = std::numbers::pi;

void require_shape(const RingShape& r) {
  if (r.points.size() < 3 || r.points.size() != r.material_angle.size())
    throw std::invalid_argument("ring shape needs >= 3 points and one material angle each");
}

double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

// Distance from p to a ring's polyline; a half ring is mirrored about x = 0 first.
double distance_to_ring(const Eigen::Vector2d& p, const RingShape& r) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = r.points.size();
  const bool closed = !r.half;
  for (int mirror = 0; mirror < (r.half ? 2 : 1); ++mirror) {
    const double sx = mirror ? -1.0 : 1.0;
    for (std::size_t j = 0; j + (closed ? 0 : 1) < n; ++j) {
      Eigen::Vector2d a = r.points[j], b = r.points[(j + 1) % n];
      a.x() *= sx;
      b.x() *= sx;
      best = std::min(best, point_segment_distance(p, a, b));
    }
  }
  return best;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
}  // namespace

double axial_extent(const RingShape& ring) {
  require_shape(ring);
  auto [lo, hi] = std::minmax_element(ring.points.begin(), ring.points.end(),
                                      [](const auto& a, const auto& b) { return a.y() < b.y(); });
  return hi->y() - lo->y() + ring.surface_offset;
}

double crush(const RingShape& ring, double outer_diameter) { return outer_diameter - axial_extent(ring); }

double crush_ratio(const RingShape& ring, double outer_diameter) {
  return crush(ring, outer_diameter) / outer_diameter;
}

double wrapped_angle_deg(const RingShape& upper, const RingShape& lower, double cap_distance) {
  require_shape(upper);
  require_shape(lower);
  // Walk away from the apex on each side while the points stay within the cap distance.
  const std::size_t n = lower.points.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  auto angle = [&](std::size_t i) {  // signed angle from the apex in (−π, π]
    double a = std::remainder(lower.material_angle[i], 2 * pi);
    return a;
  };
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return std::abs(angle(a)) < std::abs(angle(b)); });
  double extent_pos = 0.0, extent_neg = 0.0;
  bool open_pos = true, open_neg = true;
  for (std::size_t k : order) {
    const double a = angle(k);
    const bool wanted = (a >= 0 && open_pos) || (a <= 0 && open_neg);
    if (!wanted) {
      if (!open_pos && !open_neg) break;  // both sides closed: the rest cannot count
      continue;
    }
    const bool near = distance_to_ring(lower.points[k], upper) <= cap_distance;
    if (a >= 0 && open_pos) { if (near) extent_pos = std::max(extent_pos, a); else open_pos = false; }
    if (a <= 0 && open_neg) { if (near) extent_neg = std::max(extent_neg, -a); else open_neg = false; }
  }
  const double total = lower.half ? 2 * extent_pos : extent_pos + extent_neg;
  return std::min(360.0, total * 180.0 / pi);
}

InvertedArc inverted_arc(const RingShape& ring, double turning_tolerance) {
  require_shape(ring);
  const std::size_t n = ring.points.size();
  const bool closed = !ring.half;
  const double points_per_ring = ring.half ? 2.0 * static_cast<double>(n - 1) : static_cast<double>(n);
  if (turning_tolerance < 0) turning_tolerance = 0.1 * 2 * pi / points_per_ring;
  // Neighbours of point j. A half ring's end points A and B lie on the symmetry axis x = 0:
  // their missing neighbour is the mirror image of the one they have, so that B — the middle
  // of every wrap's inverted arc — turns as it does on the whole ring (it was skipped, which
  // read a wrapped FE half ring one outer-node spacing short).
  const auto mirrored = [](Eigen::Vector2d p) { p.x() = -p.x(); return p; };
  const auto previous = [&](std::size_t j) {
    return closed || j > 0 ? ring.points[(j + n - 1) % n] : mirrored(ring.points[1]);
  };
  const auto next = [&](std::size_t j) {
    return closed || j + 1 < n ? ring.points[(j + 1) % n] : mirrored(ring.points[n - 2]);
  };
  // On a half ring an end point stands once in the whole ring, an inner point twice.
  const auto share = [&](std::size_t j) { return !closed && (j == 0 || j + 1 == n) ? 0.5 : 1.0; };
  // Signed turning angle at each point; its sum gives the ring's orientation.
  std::vector<double> turning(n, 0.0);
  double total = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Vector2d a = ring.points[j] - previous(j);
    const Eigen::Vector2d b = next(j) - ring.points[j];
    turning[j] = std::atan2(cross(a, b), a.dot(b));
    total += share(j) * turning[j];
  }
  const double orientation = total >= 0 ? 1.0 : -1.0;
  double length = 0.0, turned = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double theta = std::abs(std::remainder(ring.material_angle[j], 2 * pi));
    if (theta < 0.5 * pi) continue;  // upper half
    if (orientation * turning[j] < -turning_tolerance) {
      const double before = (ring.points[j] - previous(j)).norm();
      const double after = (next(j) - ring.points[j]).norm();
      length += share(j) * 0.5 * (before + after);
      turned += share(j) * std::abs(turning[j]);
    }
  }
  const double whole = ring.half ? 2.0 : 1.0;
  return {whole * length, whole * turned * 180.0 / pi};
}

double inverted_arc_length(const RingShape& ring, double turning_tolerance) {
  return inverted_arc(ring, turning_tolerance).length_m;
}

WrapMeasure measure_wrap(const RingShape& ring, const RingShape* lower, double mean_radius,
                         double wall_thickness, const WrapThresholds& th) {
  WrapMeasure m;
  const InvertedArc arc = inverted_arc(ring);
  m.inverted_arc_m = arc.length_m;
  m.inverted_turning_deg = arc.turning_deg;
  if (!lower) return m;  // nothing to wrap around (measures.hpp)
  m.wrapped_angle_deg = wrapped_angle_deg(ring, *lower, 1.1 * wall_thickness);
  m.wrap_around = wrap_flag(arc, mean_radius, th);
  return m;
}

bool wrap_flag(const InvertedArc& arc, double mean_radius, const WrapThresholds& th) {
  return arc.length_m > th.min_inverted_arc_fraction * pi * mean_radius ||
         arc.turning_deg > th.min_inverted_turning_deg;
}

Alternation alternation(const std::vector<double>& c, double tol) {
  Alternation a;
  const std::size_t n = c.size();
  if (n < 3) return a;
  // Linear fit over rings 1 … N−1 (the target-end ring is left out of the trend).
  const std::size_t m = n - 1;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const double x = static_cast<double>(i);
    sx += x; sy += c[i]; sxx += x * x; sxy += x * c[i];
  }
  const double md = static_cast<double>(m);
  const double denom = md * sxx - sx * sx;
  const double slope = denom != 0 ? (md * sxy - sx * sy) / denom : 0.0;
  const double icpt = (sy - slope * sx) / md;
  std::vector<double> r(m);
  for (std::size_t i = 0; i < m; ++i) r[i] = c[i] - (icpt + slope * static_cast<double>(i));
  double num = 0, den = 0;
  for (std::size_t i = 0; i < m; ++i) {
    den += r[i] * r[i];
    if (i + 1 < m) num += r[i] * r[i + 1];
  }
  a.lag1 = den > 1e-12 ? -num / den : 0.0;

  int changes = 0, last_sign = 0;
  double amp = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double d = c[i + 1] - c[i];
    amp += std::abs(d);
    if (std::abs(d) < tol) continue;
    const int s = d > 0 ? 1 : -1;
    if (last_sign != 0 && s != last_sign) ++changes;
    last_sign = s;
  }
  a.amplitude = amp / static_cast<double>(n - 1);
  a.sign_change_fraction = static_cast<double>(changes) / static_cast<double>(n - 2);
  a.index = std::max(0.0, a.lag1) * a.sign_change_fraction;
  return a;
}

namespace {
// y of the ring at material angle `theta`, linear between the two points that bracket it
// (material angles are taken modulo 2π; a point exactly at θ is used as is).
double y_at_material_angle(const RingShape& ring, double theta) {
  const std::size_t n = ring.points.size();
  double below = -std::numeric_limits<double>::infinity(), above = std::numeric_limits<double>::infinity();
  std::size_t i_below = n, i_above = n;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = std::remainder(ring.material_angle[i] - theta, 2 * pi);
    if (d <= 0 && d > below) { below = d; i_below = i; }
    if (d >= 0 && d < above) { above = d; i_above = i; }
  }
  if (i_below == n || i_above == n)
    throw std::invalid_argument("half_heights: the shape has no points on both sides of the side point C");
  if (above - below <= 0) return ring.points[i_below].y();
  const double s = -below / (above - below);
  return (1 - s) * ring.points[i_below].y() + s * ring.points[i_above].y();
}
}  // namespace

HalfHeights half_heights(const RingShape& ring, double outer_diameter) {
  require_shape(ring);
  if (!(outer_diameter > 0)) throw std::invalid_argument("half_heights: outer diameter must be > 0");
  const double y_side = ring.half ? y_at_material_angle(ring, 0.5 * pi)
                                  : 0.5 * (y_at_material_angle(ring, 0.5 * pi) + y_at_material_angle(ring, 1.5 * pi));
  auto [lo, hi] = std::minmax_element(ring.points.begin(), ring.points.end(),
                                      [](const auto& a, const auto& b) { return a.y() < b.y(); });
  const double r_outer = 0.5 * outer_diameter, offset = 0.5 * ring.surface_offset;
  return {(hi->y() - y_side + offset) / r_outer, (y_side - lo->y() + offset) / r_outer};
}

std::string deformation_mode(double crush_ratio, bool wrap_around) {
  if (wrap_around) return "wrapped";
  if (crush_ratio >= 0.5) return "flattened";
  if (crush_ratio >= 0.1) return "crushed";
  return "intact";
}

}  // namespace ringcrush::compare
