// Evaluation of decoded elements: the point at a parameter, tangents and
// path lengths (docs/cnc.md, "Elements").  The decoder uses these for spline
// tangents and lengths; plots and tests use them to walk an element.
//
// Every element is parametrised by u in [0, 1] from its start to its end;
// additional axes (A..W) move linearly in u.  point(e, 1) is exactly e.end.
#pragma once

#include <cmath>

#include "stdlib-motion/cnc/Element.h"

namespace stc::cnc {

// Small 3-vector helpers.
inline Vec3 xyz(const Pos& p) { return {p[AxX], p[AxY], p[AxZ]}; }
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
// a / |a|, or zero when |a| is zero (or not finite).
Vec3 normalized(const Vec3& a);

// The position at parameter u in [0, 1] (clamped).  Non-motion elements stay at
// their start.
Pos point(const Element& e, double u);
// dX/du, dY/du, dZ/du at u.
Vec3 derivative(const Element& e, double u);
// Unit tangent of the X/Y/Z path at the start (u = 0) / end (u = 1); zero when
// the element does not move X/Y/Z.
Vec3 startTangent(const Element& e);
Vec3 endTangent(const Element& e);
// The path length over X/Y/Z (closed form for lines and arcs, Gauss-Legendre
// quadrature elsewhere, relative error below 1e-10); for an element that moves
// only additional axes, the length over all axes.
double pathLength(const Element& e);

}  // namespace stc::cnc
