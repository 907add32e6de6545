// Tool radius correction (ToolCorr.h; docs/cnc.md, "Tool radius correction").
#include "stdlib-motion/cnc/ToolCorr.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "stdlib-motion/cnc/Geometry.h"

namespace stc::cnc {

namespace {

using P2 = ToolCorrector::P2;
using Piece = ToolCorrector::Piece;

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2 * std::numbers::pi;
// In-plane moves up to this length count as "not moving in the plane" (a Z plunge).
constexpr double kStill = 1e-9;
constexpr double kMaxRadius = 1e9;

P2 operator+(P2 a, P2 b) { return {a.x + b.x, a.y + b.y}; }
P2 operator-(P2 a, P2 b) { return {a.x - b.x, a.y - b.y}; }
P2 operator*(double s, P2 a) { return {s * a.x, s * a.y}; }
double dot2(P2 a, P2 b) { return a.x * b.x + a.y * b.y; }
double cross2(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }
double len2(P2 a) { return std::hypot(a.x, a.y); }
P2 unit2(P2 a) {
  const double l = len2(a);
  return l > 0 && std::isfinite(l) ? P2{a.x / l, a.y / l} : P2{0, 0};
}
P2 rot90(P2 a) { return {-a.y, a.x}; }   // the left normal (seen from the plane normal)
double angleOf(P2 a) { return std::atan2(a.y, a.x); }
double sgn(double v) { return v < 0 ? -1.0 : 1.0; }

// The frame of a plane: in-plane axes (u, v) and the normal, right-handed as the decoder's bases.
void planeAxes(Plane p, int& u, int& v, int& n) {
  switch (p) {
    case Plane::ZX: u = AxZ, v = AxX, n = AxY; return;
    case Plane::YZ: u = AxY, v = AxZ, n = AxX; return;
    default: u = AxX, v = AxY, n = AxZ; return;
  }
}
Vec3 axisVector(int axis) {
  Vec3 e{0, 0, 0};
  e[static_cast<size_t>(axis)] = 1;
  return e;
}

// Unit tangent of a piece at its start / end (the direction of travel).
P2 startTangent2(const Piece& p) {
  if (!p.arc) return unit2(p.b - p.a);
  return sgn(p.phi) * rot90(unit2(p.a - p.c));
}
P2 endTangent2(const Piece& p) {
  if (!p.arc) return unit2(p.b - p.a);
  return sgn(p.phi) * rot90(unit2(p.b - p.c));
}

// Moves the end / start of a piece to X (a point on its line or circle), keeping the arc's
// direction: the sweep changes by the (short) angle between the old and the new point.
void setEnd(Piece& p, P2 x) {
  if (p.arc) p.phi += std::remainder(angleOf(x - p.c) - (p.angA + p.phi), kTwoPi);
  p.b = x;
}
void setStart(Piece& p, P2 x) {
  if (p.arc) {
    const double a = angleOf(x - p.c);
    p.phi -= std::remainder(a - p.angA, kTwoPi);
    p.angA = a;
  }
  p.a = x;
}

// The intersections of the full line or circle of two pieces (0, 1 or 2 points).
struct Curve {
  bool circle;
  P2 p, d;   // line: a point and the unit direction
  P2 c;      // circle: centre and radius
  double R;
};
int intersect(const Curve& A, const Curve& B, P2 out[2]) {
  if (!A.circle && !B.circle) {
    const double den = cross2(A.d, B.d);
    if (std::fabs(den) < 1e-15) return 0;
    out[0] = A.p + (cross2(B.p - A.p, B.d) / den) * A.d;
    return 1;
  }
  if (A.circle != B.circle) {
    const Curve& L = A.circle ? B : A;
    const Curve& C = A.circle ? A : B;
    const P2 f = L.p - C.c;
    const double b = dot2(f, L.d), cc = dot2(f, f) - C.R * C.R;
    double disc = b * b - cc;
    if (disc < 0) {
      if (disc < -1e-12 * C.R * C.R) return 0;
      disc = 0;
    }
    const double s = std::sqrt(disc);
    out[0] = L.p + (-b - s) * L.d;
    out[1] = L.p + (-b + s) * L.d;
    return 2;
  }
  const P2 dv = B.c - A.c;
  const double D = len2(dv);
  if (D < 1e-15) return 0;
  const double a = (A.R * A.R - B.R * B.R + D * D) / (2 * D);
  double h2 = A.R * A.R - a * a;
  if (h2 < 0) {
    if (h2 < -1e-12 * A.R * A.R) return 0;
    h2 = 0;
  }
  const P2 ud = (1 / D) * dv, base = A.c + a * ud, off = std::sqrt(h2) * rot90(ud);
  out[0] = base + off;
  out[1] = base - off;
  return 2;
}

bool samePos(const Pos& a, const Pos& b) {
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) return false;
  return true;
}

// Clears what belongs to a programmed block only (marks, switch points, M) from an element
// the corrector inserts.
void makeInserted(Element& e) {
  e.marks = 0;
  e.switchCount = 0;
  for (auto& s : e.switches) s = SwitchPoint{};
  e.m = 0;
  e.k = e.l = e.dwell = 0;
  e.velEnd = 0;
}

}  // namespace

const char* toString(ToolCorrError e) {
  switch (e) {
    case ToolCorrError::None: return "no error";
    case ToolCorrError::NotInPlane: return "element or plane the tool radius correction cannot offset";
    case ToolCorrError::ArcSmallerThanTool: return "arc smaller than the tool radius";
    case ToolCorrError::LookAheadExceeded: return "too many elements without a contour move";
    case ToolCorrError::BadRadius: return "invalid tool radius";
  }
  return "?";
}

ToolCorrector::ToolCorrector(ToolCorrMode mode, double defaultRadius) : mode_(mode), defaultRadius_(0) {
  setDefaultRadius(defaultRadius);
}

bool ToolCorrector::setDefaultRadius(double r) {
  if (!std::isfinite(r) || r < 0 || r > kMaxRadius) return false;
  defaultRadius_ = r;
  return true;
}

void ToolCorrector::fail(ToolCorrError e, const Element& at, std::string message) {
  error_ = e;
  errorLine_ = at.line;
  errorMessage_ = "line " + std::to_string(at.line) + ": " + std::move(message);
}

ToolCorrector::P2 ToolCorrector::in(const Pos& p) const { return {p[iu_], p[iv_]}; }
void ToolCorrector::setIn(Pos& p, P2 q) const {
  p[iu_] = q.x;
  p[iv_] = q.y;
}

bool ToolCorrector::inPlaneStill(const Element& e) const {
  if (e.type == MoveType::Lin || e.type == MoveType::LinPos) return len2(in(e.end) - in(e.start)) <= kStill;
  return !isMotion(e.type);
}

bool ToolCorrector::isContour(const Element& e) const {
  if (!isMotion(e.type) || inPlaneStill(e)) return false;
  return !(mode_ == ToolCorrMode::BlindPos && e.type == MoveType::LinPos);   // a G0 positions
}

ToolCorrector::Piece ToolCorrector::pieceOf(const Element& e) const {
  Piece p;
  p.a = in(e.start);
  p.b = in(e.end);
  if (e.type == MoveType::Clw || e.type == MoveType::Cclw) {
    p.arc = true;
    p.c = {e.arc.centre[static_cast<size_t>(iu_)], e.arc.centre[static_cast<size_t>(iv_)]};
    p.R = e.arc.radius;
    p.angA = angleOf(p.a - p.c);
    p.phi = e.arc.sweep * sgn(dot(e.arc.normal, axisVector(in_)));
  }
  return p;
}

// The element of `orig` with the in-plane geometry `pc`, starting at the current position.
Element ToolCorrector::elementOf(const Element& orig, const Piece& pc) const {
  Element out = orig;
  out.start = cur_;
  setIn(out.end, pc.b);
  if (pc.arc) {
    const double sigma = sgn(dot(orig.arc.normal, axisVector(in_)));
    ArcGeo& g = out.arc;
    g.centre[static_cast<size_t>(iu_)] = pc.c.x;
    g.centre[static_cast<size_t>(iv_)] = pc.c.y;
    g.centre[static_cast<size_t>(in_)] = cur_[in_];
    g.radius = pc.R;
    const Vec3 d = xyz(out.start) - g.centre;
    g.startAngle = std::atan2(dot(d, g.v), dot(d, g.u));
    g.sweep = pc.phi * sigma;
    // The rise from where the tool is: the entry of a section can start at another height
    // along the normal than programmed (the offset of a section in another plane before it),
    // and the programmed rise then missed the programmed end.
    g.rise = (out.end[in_] - out.start[in_]) * sigma;
    out.type = g.sweep > 0 ? MoveType::Cclw : MoveType::Clw;
  } else if (orig.type == MoveType::Clw || orig.type == MoveType::Cclw) {
    out.type = MoveType::Lin;   // a ramp arc that could not be re-centred
    out.arc = ArcGeo{};
  }
  out.length = pathLength(out);
  return out;
}

void ToolCorrector::emit(Element e) {
  cur_ = e.end;
  haveCur_ = true;
  lastEmitted_ = e;
  out_.push_back(std::move(e));
}

void ToolCorrector::insertPositioning(const Element& like, const Pos& to) {
  if (samePos(cur_, to)) return;
  Element p = like;
  makeInserted(p);
  p.type = MoveType::LinPos;
  p.arc = ArcGeo{};
  p.start = cur_;
  p.end = to;
  p.length = pathLength(p);
  emit(std::move(p));
}

// Places the held elements that do not move in the plane where the tool is now.
void ToolCorrector::emitTail(const P2* lastG0Shift) {
  size_t lastG0 = tail_.size();
  if (lastG0Shift)
    for (size_t i = 0; i < tail_.size(); ++i)
      if (tail_[i].type == MoveType::LinPos) lastG0 = i;
  for (size_t i = 0; i < tail_.size(); ++i) {
    Element t = tail_[i];
    if (samePos(t.start, cur_) && i != lastG0) {
      emit(std::move(t));
      continue;
    }
    if (i == lastG0) {
      // The positioning before a contour element ends at its offset start.
      setIn(t.end, in(t.end) + *lastG0Shift);
      t.start = cur_;
    } else if ((t.type == MoveType::LinPos && (mode_ == ToolCorrMode::BlindPos || !inSection_)) ||
               t.type == MoveType::InitPos) {
      // A positioning goes to its programmed point.  Only in TC_BLIND_POS (where G0 positions)
      // or outside a section: in the ramp modes a G0 inside a section is part of the contour,
      // and one that does not move in the plane (a Z retract between two contour elements)
      // must keep the offset like any other such element; sent to its programmed point, it
      // left the tool on the programmed corner and the next element started there (a gouge,
      // and a corner arc whose start is its centre).
      t.start = cur_;
    } else {
      for (size_t k = 0; k < t.end.size(); ++k) t.end[k] = cur_[k] + (t.end[k] - t.start[k]);
      t.start = cur_;
    }
    t.length = pathLength(t);
    emit(std::move(t));
  }
  tail_.clear();
}

void ToolCorrector::emitHeld() {
  if (!hasHeld_) return;
  hasHeld_ = false;
  Piece pc = held_.off;
  if (held_.rampIn) {
    // Entry: from the programmed start (the current position) to the offset end.
    const P2 s = in(cur_);
    if (pc.arc) {
      // Keep the end and its tangent: the centre lies on the radius through the end,
      // as far from the start as from the end (LinuxCNC's entry arc).
      const P2 e = pc.b, u = unit2(pc.c - e), es = e - s;
      const double den = 2 * dot2(u, es);
      const double t = den != 0 ? -dot2(es, es) / den : 0;
      if (len2(es) <= kStill || std::fabs(den) <= 1e-12 * len2(es) || !std::isfinite(t) || std::fabs(t) > kMaxRadius * 10) {
        pc.arc = false;
      } else {
        const double dir = sgn(pc.phi);
        pc.c = e + t * u;
        pc.R = std::fabs(t);
        pc.angA = angleOf(s - pc.c);
        double sweep = std::remainder(angleOf(e - pc.c) - pc.angA, kTwoPi);
        if (dir > 0 && sweep <= 0) sweep += kTwoPi;
        if (dir < 0 && sweep >= 0) sweep -= kTwoPi;
        pc.phi = sweep;
      }
    }
    pc.a = s;
  }
  emit(elementOf(held_.orig, pc));
}

void ToolCorrector::emitRampOut(const Element& e) {
  if (samePos(e.start, cur_)) return emit(e);
  Element out = e;
  if (e.type == MoveType::Lin || e.type == MoveType::LinPos) {
    out.start = cur_;
    out.length = pathLength(out);
    return emit(std::move(out));
  }
  const bool arcInPlane = (e.type == MoveType::Clw || e.type == MoveType::Cclw) && e.plane == plane_ &&
                          std::fabs(std::fabs(dot(e.arc.normal, axisVector(in_))) - 1) < 1e-12;
  if (arcInPlane) {
    // Keep the end; the centre lies on the line from the new start towards the programmed
    // centre, as far from the new start as from the end (the start tangent is kept).
    Piece pc = pieceOf(e);
    const P2 s = in(cur_), u = unit2(pc.c - pc.a), se = s - pc.b;
    const double den = 2 * dot2(u, se);
    const double t = den != 0 ? -dot2(se, se) / den : 0;
    if (len2(se) > kStill && std::fabs(den) > 1e-12 * len2(se) && std::isfinite(t) && std::fabs(t) < kMaxRadius * 10) {
      const double dir = sgn(pc.phi);
      pc.c = s + t * u;
      pc.R = std::fabs(t);
      pc.a = s;
      pc.angA = angleOf(s - pc.c);
      double sweep = std::remainder(angleOf(pc.b - pc.c) - pc.angA, kTwoPi);
      if (dir > 0 && sweep <= 0) sweep += kTwoPi;
      if (dir < 0 && sweep >= 0) sweep -= kTwoPi;
      pc.phi = sweep;
      return emit(elementOf(e, pc));
    }
  }
  // Any other element: a straight line back to its programmed start, then the element.
  Element link = e;
  makeInserted(link);
  link.type = MoveType::Lin;
  link.arc = ArcGeo{};
  link.start = cur_;
  link.end = e.start;
  link.length = pathLength(link);
  emit(std::move(link));
  emit(e);
}

void ToolCorrector::startSection(const Element& e, double radius) {
  inSection_ = true;
  sectionHadContour_ = false;
  rampOutPending_ = false;   // a new entry starts wherever the tool is
  side_ = e.toolSide == ToolSide::Left ? 1.0 : -1.0;
  radius_ = radius;
  plane_ = e.plane;
  planeAxes(plane_, iu_, iv_, in_);
}

void ToolCorrector::closeSection(bool nextIsPositioning) {
  emitHeld();              // the last contour element ends at its own offset end
  emitTail(nullptr);
  if (mode_ == ToolCorrMode::BlindPos) {
    if (!nextIsPositioning) insertPositioning(lastEmitted_, lastProgrammed_);
  } else {
    rampOutPending_ = sectionHadContour_;
  }
  inSection_ = false;
}

void ToolCorrector::acceptContour(const Element& e) {
  const Piece prog = pieceOf(e);
  Piece off = prog;
  if (!prog.arc) {
    const P2 n = (side_ * radius_) * rot90(unit2(prog.b - prog.a));
    off.a = prog.a + n;
    off.b = prog.b + n;
  } else {
    off.R = prog.R - side_ * radius_ * sgn(prog.phi);
    if (!(off.R > kStill)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "the arc of radius %.9g is smaller than the tool radius %.9g on its concave side", prog.R,
                    radius_);
      return fail(ToolCorrError::ArcSmallerThanTool, e, buf);
    }
    off.a = prog.c + off.R * unit2(prog.a - prog.c);
    off.b = prog.c + off.R * unit2(prog.b - prog.c);
  }
  Held next{e, off, prog, false};

  if (!sectionHadContour_) {   // the entry
    sectionHadContour_ = true;
    if (mode_ == ToolCorrMode::BlindPos) {
      bool g0 = false;
      for (const Element& t : tail_) g0 = g0 || t.type == MoveType::LinPos;
      const P2 shift = off.a - prog.a;
      if (g0) {
        emitTail(&shift);
      } else {
        emitTail(nullptr);
        Pos to = e.start;
        setIn(to, off.a);
        insertPositioning(e, to);
      }
    } else {
      emitTail(nullptr);
      next.rampIn = true;
    }
    held_ = next;
    hasHeld_ = true;
    return;
  }

  if (mode_ == ToolCorrMode::BlindPos) {
    bool g0 = false;
    for (const Element& t : tail_) g0 = g0 || t.type == MoveType::LinPos;
    if (g0) {   // a positioning between two contour elements: no corner, it connects them
      emitHeld();
      const P2 shift = off.a - prog.a;
      emitTail(&shift);
      held_ = next;
      hasHeld_ = true;   // emitHeld() cleared it: without this the element was never emitted
      return;
    }
  }
  if (held_.rampIn && mode_ == ToolCorrMode::BlindIn) {
    held_.off.b = next.off.a;   // the entry ends at the offset start of the second element
    emitHeld();
    emitTail(nullptr);
    held_ = next;
    hasHeld_ = true;
    return;
  }

  // The corner between the held element A and this one (B) at the programmed point P.
  Piece& A = held_.off;
  Piece& B = next.off;
  const P2 P = held_.prog.b;
  const P2 tA = endTangent2(held_.prog), tB = startTangent2(prog);
  const double cr = cross2(tA, tB), dt = dot2(tA, tB);
  const double turn = std::atan2(cr, dt);
  enum class Join { Tangent, Arc, Cut, Link } join = Join::Tangent;
  double arcSweep = 0;
  if (std::fabs(turn) <= kTangentTurn || len2(A.b - B.a) <= 1e-12) {
    join = Join::Tangent;
  } else if (side_ * cr < 0 || std::fabs(turn) >= kPi - kTangentTurn) {
    join = Join::Arc;   // outside corner (a reversal too: the tool goes round the end)
    arcSweep = std::fabs(turn) >= kPi - kTangentTurn ? -side_ * kPi : turn;
  } else {
    Curve ca{A.arc, A.b, tA, A.c, A.R}, cb{B.arc, B.a, tB, B.c, B.R};
    P2 xs[2];
    const int n = intersect(ca, cb, xs);
    const P2 mid = 0.5 * (A.b + B.a);
    int best = -1;
    for (int i = 0; i < n; ++i)
      if (best < 0 || len2(xs[i] - mid) < len2(xs[best] - mid)) best = i;
    // An intersection far beyond both elements (a near-reversal inside) is no corner.
    const double reach = 10 * (len2(held_.prog.b - held_.prog.a) + len2(prog.b - prog.a) + radius_ +
                               (held_.prog.arc ? held_.prog.R : 0) + (prog.arc ? prog.R : 0));
    if (best >= 0 && std::isfinite(xs[best].x) && std::isfinite(xs[best].y) && len2(xs[best] - P) <= reach) {
      join = Join::Cut;
      setEnd(A, xs[best]);
      setStart(B, xs[best]);
    } else {
      join = Join::Link;
    }
  }
  if (join == Join::Tangent) setStart(B, A.b);
  emitHeld();
  emitTail(nullptr);
  if (join == Join::Arc || join == Join::Link) {
    Element c = e;
    makeInserted(c);
    c.start = cur_;
    c.end = cur_;
    setIn(c.end, B.a);
    if (join == Join::Arc) {
      ArcGeo& g = c.arc;
      g = ArcGeo{};
      g.u = axisVector(iu_);
      g.v = axisVector(iv_);
      g.normal = axisVector(in_);
      g.centre = xyz(cur_);
      g.centre[static_cast<size_t>(iu_)] = P.x;
      g.centre[static_cast<size_t>(iv_)] = P.y;
      g.radius = radius_;
      g.startAngle = angleOf(in(cur_) - P);
      g.sweep = arcSweep;
      g.rise = 0;
      c.type = arcSweep > 0 ? MoveType::Cclw : MoveType::Clw;
    } else {
      c.type = MoveType::Lin;
      c.arc = ArcGeo{};
    }
    c.length = pathLength(c);
    emit(std::move(c));
  }
  held_ = next;
  hasHeld_ = true;
}

bool ToolCorrector::push(const Element& e) {
  if (error_ != ToolCorrError::None || finished_) return false;
  if (!haveCur_) {
    cur_ = e.start;
    lastProgrammed_ = e.start;
    haveCur_ = true;
  }
  // Section boundaries: G40 (side off), G41/G42 (a mark or a new side).
  const bool sideOn = e.toolSide != ToolSide::Off;
  const double sideSign = e.toolSide == ToolSide::Left ? 1.0 : -1.0;
  const bool marked = (e.marks & (MarkToolCorrLeft | MarkToolCorrRight)) != 0;
  const bool newSection = sideOn && (marked || !inSection_ || sideSign != side_);
  if (inSection_ && (!sideOn || newSection)) closeSection(e.type == MoveType::LinPos);
  if (newSection) {
    const double r = e.toolRadius > 0 ? e.toolRadius : defaultRadius_;
    if (!std::isfinite(r) || r < 0 || r > kMaxRadius) {
      fail(ToolCorrError::BadRadius, e, "invalid tool radius");
      return false;
    }
    if (r > 0) {
      if (e.plane == Plane::Free) {
        fail(ToolCorrError::NotInPlane, e, "tool radius correction needs the plane G17, G18 or G19, not G16");
        return false;
      }
      startSection(e, r);
    }
  }
  const Pos programmedBefore = lastProgrammed_;
  lastProgrammed_ = isMotion(e.type) || e.type == MoveType::InitPos ? e.end : programmedBefore;

  if (!inSection_) {
    const bool moving = isMotion(e.type) && !inPlaneStill(e);
    if (rampOutPending_ && moving) {
      emitTail(nullptr);
      rampOutPending_ = false;
      emitRampOut(e);
      return true;
    }
    if (!moving || (mode_ == ToolCorrMode::BlindPos && e.type == MoveType::LinPos)) {
      tail_.push_back(e);
      if (mode_ != ToolCorrMode::BlindPos || tail_.size() > kMaxLookAhead) emitTail(nullptr);
      return true;
    }
    emitTail(nullptr);
    emit(e);
    return true;
  }

  switch (e.type) {
    case MoveType::Spline:
    case MoveType::Parabola:
    case MoveType::EllClw:
    case MoveType::EllCclw:
      fail(ToolCorrError::NotInPlane, e,
           std::string("a ") + toString(e.type) + " cannot be offset: only lines and arcs under tool radius correction");
      return false;
    case MoveType::InitPos:
      fail(ToolCorrError::NotInPlane, e, "G92 inside tool radius correction");
      return false;
    default: break;
  }
  if (e.plane != plane_) {
    fail(ToolCorrError::NotInPlane, e, "the plane changes inside tool radius correction");
    return false;
  }
  if ((e.type == MoveType::Clw || e.type == MoveType::Cclw) &&
      !(std::fabs(std::fabs(dot(e.arc.normal, axisVector(in_))) - 1) < 1e-12)) {
    fail(ToolCorrError::NotInPlane, e, "an arc outside the correction plane");
    return false;
  }
  if (isContour(e)) {
    acceptContour(e);
    return error_ == ToolCorrError::None;
  }
  tail_.push_back(e);
  if (tail_.size() > kMaxLookAhead) {
    fail(ToolCorrError::LookAheadExceeded, e, "more than 64 elements without a contour move inside tool radius correction");
    return false;
  }
  return true;
}

void ToolCorrector::finish() {
  if (error_ != ToolCorrError::None || finished_) return;
  if (inSection_) closeSection(false);
  emitTail(nullptr);
  finished_ = true;
}

std::vector<Element> correctAll(const std::vector<Element>& in, ToolCorrMode mode, double defaultRadius, ToolCorrError* error) {
  ToolCorrector tc(mode, defaultRadius);
  std::vector<Element> out;
  for (const Element& e : in) {
    if (!tc.push(e)) break;
    while (tc.hasOutput()) {
      out.push_back(tc.front());
      tc.pop();
    }
  }
  tc.finish();
  while (tc.hasOutput()) {
    out.push_back(tc.front());
    tc.pop();
  }
  if (error) *error = tc.error();
  return out;
}

}  // namespace stc::cnc
