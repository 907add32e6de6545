#include "stdlib-motion/cnc/SmoothPath.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/Geometry.h"
#include "stdlib-motion/cnc/VelocityCheck.h"

namespace stc::cnc {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180;
// Corners turning by less than this are tangent joins: nothing to smooth.
constexpr double kMinTurnRad = 1e-9;
// Corners turning by more than pi minus this are reversals: a spline or arc there
// would have a cusp or a vanishing radius, so they stay (the velocity check stops there).
constexpr double kMaxTurnMarginRad = 1e-6;
// Pieces shorter than this (units of the program) are dropped after a cut.
constexpr double kMinPieceLength = 1e-9;

bool cuttable(const Element& e, Smoothing mode) {
  if (e.smoothing == Smoothing::Off) return false;
  if (e.type == MoveType::Lin) return true;
  return mode == Smoothing::Smooth && (e.type == MoveType::Clw || e.type == MoveType::Cclw);
}

bool finitePos(const Pos& p) {
  return std::all_of(p.begin(), p.end(), [](double v) { return std::isfinite(v); });
}

// The distance of a switch point from the start of `e` (length L), clamped to [0, L].
double switchDistance(const SwitchPoint& s, double L) {
  double d = s.relative ? s.pos * L : s.pos >= 0 ? s.pos : L + s.pos;
  return std::clamp(std::isfinite(d) ? d : 0.0, 0.0, L);
}

// Writes the switch at distance `d` from the start of a piece of length L, in the
// switch's own kind (relative, from the start, from the end).
SwitchPoint placeSwitch(const SwitchPoint& s, double d, double L) {
  SwitchPoint o = s;
  if (s.relative) {
    o.pos = L > 0 ? d / L : 0;
  } else if (s.pos >= 0) {
    o.pos = d;
  } else if (d < L) {
    o.pos = d - L;   // from the end, still negative
  } else {
    // At the very end: -0 would read as "0 from the start", so say "fraction 1".
    o.relative = true;
    o.pos = 1;
  }
  return o;
}

Vec3 planeNormal(Plane p, Vec3& u, Vec3& v) {
  switch (p) {
    case Plane::ZX: u = {0, 0, 1}, v = {1, 0, 0}; return {0, 1, 0};
    case Plane::YZ: u = {0, 1, 0}, v = {0, 0, 1}; return {1, 0, 0};
    default: u = {1, 0, 0}, v = {0, 1, 0}; return {0, 0, 1};
  }
}

}  // namespace

bool validOptions(const SmoothOptions& o) {
  return std::isfinite(o.edgeDistance) && o.edgeDistance >= 0 && o.edgeDistance <= 1e9 && std::isfinite(o.angleTolDeg) &&
         o.angleTolDeg >= 0 && o.angleTolDeg <= 180;
}

Element subElement(const Element& e, double u0, double u1) {
  u0 = std::clamp(u0, 0.0, 1.0);
  u1 = std::clamp(u1, u0, 1.0);
  Element p = e;
  p.start = point(e, u0);
  p.end = point(e, u1);
  if (e.type == MoveType::Clw || e.type == MoveType::Cclw) {
    p.arc.startAngle = e.arc.startAngle + u0 * e.arc.sweep;
    p.arc.sweep = (u1 - u0) * e.arc.sweep;
    p.arc.rise = (u1 - u0) * e.arc.rise;
    p.arc.centre = e.arc.centre + (u0 * e.arc.rise) * e.arc.normal;   // in the plane through the new start
  }
  p.length = pathLength(p);
  // Switch points keep their place on the path; those outside the piece move to its nearer end.
  const double L = pathLength(e), s0 = u0 * L, s1 = u1 * L;
  for (uint8_t i = 0; i < p.switchCount && i < kMaxSwitches; ++i) {
    const double d = std::clamp(switchDistance(e.switches[i], L), s0, s1) - s0;
    p.switches[i] = placeSwitch(e.switches[i], d, p.length);
  }
  // The mark bits belong to the first piece (they mean "from this element on").
  if (u0 > 0) p.marks = 0;
  return p;
}

void PathSmoother::emit(Element e, std::vector<Element>& out) {
  e.objNo = nextObjNo_++;
  out.push_back(e);
}

bool PathSmoother::smoothCorner(const Element& next, std::vector<Element>& out) {
  const Smoothing mode = next.smoothing;
  if (!cuttable(hold_, mode) || !cuttable(next, mode)) return false;
  if (!finitePos(hold_.end) || !finitePos(next.start) || !finitePos(next.end)) return false;
  // The elements must meet (in every axis): a gap is not a corner.
  for (int k = 0; k < kAxisCount; ++k)
    if (std::fabs(next.start[k] - hold_.end[k]) > 1e-9 * std::max(1.0, std::fabs(hold_.end[k]))) return false;
  const double d = opts_.edgeDistance + std::min(hold_.smoothDist, next.smoothDist);
  if (!(d > 0) || !std::isfinite(d)) return false;
  const double turnDeg = turnAngleDeg(hold_, next);
  if (turnDeg < 0) return false;
  const double turn = turnDeg * kDegToRad;
  if (turn <= std::max(opts_.angleTolDeg * kDegToRad, kMinTurnRad) || turn > kPi - kMaxTurnMarginRad) return false;

  const double L1 = pathLength(hold_), L2 = pathLength(next);
  if (!(L1 > 0) || !(L2 > 0) || !std::isfinite(L1) || !std::isfinite(L2)) return false;
  double d1 = std::min({d, holdOrigLength_ / 2, L1}), d2 = std::min(d, L2 / 2);
  if (opts_.symmetric || mode == Smoothing::Round) d1 = d2 = std::min(d1, d2);
  if (!(d1 > kMinPieceLength) || !(d2 > kMinPieceLength)) return false;

  const double u1 = d1 >= L1 ? 0.0 : 1 - d1 / L1, u2 = d2 / L2;
  Element first = subElement(hold_, 0, u1);
  Element second = subElement(next, u2, 1);

  // The corner piece: the block of `next` (the corner is where it starts, so its marks
  // go there), no switch points.
  Element c = next;
  c.switchCount = 0;
  c.velEnd = 0;
  c.vel = std::min(hold_.vel, next.vel);
  c.plane = hold_.plane;
  c.start = first.end;
  c.end = second.start;
  if (mode == Smoothing::Smooth) {
    c.type = MoveType::Spline;
    c.spline = SplineGeo{normalized(derivative(hold_, u1)), normalized(derivative(next, u2)), 3 * std::min(d1, d2), 3};
    ++splines_;
  } else {
    // The arc tangent to both lines: the tangent points are d from the corner, so the
    // radius is d / tan(turn / 2) and the centre lies on the inner normal of the first line.
    const Vec3 a = endTangent(hold_), b = startTangent(next);
    const double r = d1 / std::tan(turn / 2);
    const Vec3 p0 = xyz(c.start);
    const Vec3 centre = p0 + r * normalized(b - dot(a, b) * a);
    const Vec3 normal = normalized(cross(a, b));
    ArcGeo g{};
    g.centre = centre;
    g.radius = r;
    g.rise = 0;
    Vec3 pu, pv;
    const Vec3 pn = planeNormal(hold_.plane, pu, pv);
    if (hold_.plane != Plane::Free && std::fabs(dot(normal, pn)) > 1 - 1e-12) {
      // In the element's plane: the decoder's basis, so the arc reads like a G2/G3.
      g.u = pu, g.v = pv, g.normal = pn;
      g.startAngle = std::atan2(dot(p0 - centre, pv), dot(p0 - centre, pu));
      g.sweep = dot(normal, pn) > 0 ? turn : -turn;
    } else {
      c.plane = Plane::Free;
      g.normal = normal;
      g.u = normalized(p0 - centre);
      g.v = cross(normal, g.u);
      g.startAngle = 0;
      g.sweep = turn;
    }
    c.type = g.sweep > 0 ? MoveType::Cclw : MoveType::Clw;
    c.arc = g;
    ++arcs_;
  }
  c.length = pathLength(c);

  if (first.length > kMinPieceLength) {
    emit(first, out);
  } else {
    // The element is used up by its two corners: its switch points go to the corner piece's start.
    for (uint8_t i = 0; i < first.switchCount && c.switchCount < kMaxSwitches; ++i) {
      SwitchPoint s = first.switches[i];
      s.relative = true;
      s.pos = 0;
      c.switches[c.switchCount++] = s;
    }
    c.marks |= first.marks;
  }
  emit(c, out);
  hold_ = second;
  holdOrigLength_ = L2;
  return true;
}

void PathSmoother::push(const Element& e, std::vector<Element>& out) {
  if (held_) {
    if (smoothCorner(e, out)) return;
    emit(hold_, out);
    held_ = false;
  }
  if (isToolPath(e.type) && cuttable(e, Smoothing::Smooth)) {
    hold_ = e;
    holdOrigLength_ = pathLength(e);
    held_ = true;
  } else {
    emit(e, out);
  }
}

void PathSmoother::finish(std::vector<Element>& out) {
  if (held_) emit(hold_, out);
  held_ = false;
}

}  // namespace stc::cnc
