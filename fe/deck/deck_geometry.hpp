// Node-generation geometry of ABAQUS 4.8 (*NGEN, *NCOPY): pure functions of points, tested
// alone (tests/fe/deck_geometry_test.cpp). Each throws std::invalid_argument on degenerate
// input (zero-length axis, end node on the arc centre...).
#pragma once

#include "fe/deck/deck_model.hpp"

namespace ringcrush::fe::deck {

// *NGEN (LINE=L): the point a fraction t of the way from a to b.
Point straight_point(const Point& a, const Point& b, double t);

// *NGEN, LINE=C: the point a fraction t along the circular arc from a to b about `centre`,
// turning counter-clockwise about `normal` (right-hand rule, as ABAQUS does): the angle runs
// over (0, 2π], so two ends opposite each other give the half circle on the left of the
// normal. The radius and the offset along the normal are interpolated linearly (both equal
// for the thesis decks, which then lie exactly on a circle).
Point arc_point(const Point& a, const Point& b, const Point& centre, const Point& normal, double t);

// *NCOPY, SHIFT: translate by `shift`, then rotate by `angle_deg` about the axis from
// `axis_a` to `axis_b` (right-hand rule).
Point shift_rotate(const Point& p, const Point& shift, const Point& axis_a, const Point& axis_b,
                   double angle_deg);

// *NCOPY, REFLECT=LINE: mirror image of p in the line through a and b (in the plane of the
// line and p; for plane decks, the mirror about that line).
Point reflect_line(const Point& p, const Point& a, const Point& b);

}  // namespace ringcrush::fe::deck
