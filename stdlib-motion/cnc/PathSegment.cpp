// Elements as path segments (PathSegment.h).
#include "stdlib-motion/cnc/PathSegment.h"

#include <algorithm>
#include <cmath>

namespace stc::cnc {

namespace {

constexpr int kDims = kPathDims;
constexpr double kTwoPi = 6.283185307179586;

// The full turns beyond the first partial one that a sweep of `sweep` rad makes: the path
// builders take "from a to b plus turns"; a whole number of turns ends where it started (a
// full circle plus the rest).
int extraTurns(double sweep) {
  const double k = std::fabs(sweep) / kTwoPi;
  const double whole = std::round(k);
  return (whole >= 1 && std::fabs(k - whole) < 1e-9) ? static_cast<int>(whole) - 1 : static_cast<int>(std::floor(k));
}

}  // namespace

bool buildPathSegment(const Element& e, path::Segment& out) {
  const path::Vec a = toPathVec(e.start), b = toPathVec(e.end);
  path::GeoStatus st = path::GeoStatus::BadParameter;
  switch (e.type) {
    case MoveType::Lin:
    case MoveType::LinPos: st = path::Segment::line(a, b, kDims, out); break;
    case MoveType::Clw:
    case MoveType::Cclw: {
      const ArcGeo& g = e.arc;
      const int turns = extraTurns(g.sweep);
      path::Vec c = a;
      for (int i = 0; i < 3; ++i) c[i] = g.centre[i];
      path::Vec n{};
      for (int i = 0; i < 3; ++i) n[i] = g.normal[i];
      st = path::Segment::arcCenter(a, c, b, n, g.sweep > 0, turns, kDims, out);
      if (st == path::GeoStatus::Ok && !(std::fabs(out.sweep() - std::fabs(g.sweep)) <= 1e-9 * std::max(1.0, std::fabs(g.sweep))))
        return false;
      break;
    }
    case MoveType::EllClw:
    case MoveType::EllCclw: {
      const EllipseGeo& g = e.ellipse;
      if (!(g.a > 0 && g.b > 0)) return false;
      const int turns = extraTurns(g.sweepPhi);
      path::Vec c = a;
      for (int i = 0; i < 3; ++i) c[i] = g.centre[i];
      path::Vec n{};
      n[2] = 1;
      st = path::Segment::ellipse(a, c, b, g.majorAngle, g.b / g.a, n, g.sweepPhi > 0, turns, kDims, out);
      break;
    }
    case MoveType::Spline:
    case MoveType::Parabola: {
      double coef[path::kMaxCoords][6] = {};
      for (int i = 0; i < kDims; ++i) {   // linear in u unless the curve says otherwise
        coef[i][0] = e.start[i];
        coef[i][1] = e.end[i] - e.start[i];
      }
      if (e.type == MoveType::Spline) {
        const SplineGeo& g = e.spline;
        const int dims = g.dims == 3 ? 3 : 2;
        for (int i = 0; i < dims; ++i) {
          const double p0 = e.start[i], p1 = e.end[i], m0 = g.chord * g.t0[i], m1 = g.chord * g.t1[i];
          coef[i][0] = p0;
          coef[i][1] = m0;
          coef[i][2] = -3 * p0 - 2 * m0 + 3 * p1 - m1;
          coef[i][3] = 2 * p0 + m0 - 2 * p1 + m1;
        }
      } else {
        const ParabolaGeo& g = e.parabola;
        for (int i = 0; i < 2; ++i) {
          const double p0 = e.start[i], p1 = e.end[i], c = g.control[i];
          coef[i][0] = p0;
          coef[i][1] = 2 * (c - p0);
          coef[i][2] = p0 - 2 * c + p1;
        }
      }
      st = path::Segment::poly(coef, kDims, out);
      break;
    }
    default: return false;
  }
  return st == path::GeoStatus::Ok;
}

}  // namespace stc::cnc
