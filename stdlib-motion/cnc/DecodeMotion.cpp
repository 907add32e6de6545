// The decoder's travel commands: the geometry of lines, arcs and helices,
// ellipses, parabolas and spline pieces (docs/cnc.md, "The codes"), and the
// output side that holds a spline piece back until its successor is known.
#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/cnc/DecoderInternal.h"
#include "stdlib-motion/cnc/Geometry.h"

namespace stc::cnc {

using namespace detail;

// ---------------------------------------------------------------- motion

// The centre word of coordinate k (I, J, K): absolute (G98, with the offset) or relative to `from` (G99).
bool Decoder::centreWord(const Block& b, int k, double from, double& out) {
  const char l = "IJK"[k];
  double v;
  if (!wordValue(b, l, v)) return false;
  if (std::fabs(v) > kMaxCoord) {
    rep_.error(b.word(l).begin, b.word(l).end, std::string(1, l) + " is out of range (magnitude above 1e9)", "gcode-range");
    return false;
  }
  out = centreAbsolute_ ? v + offsetVec_[k] : from + v;
  return true;
}

bool Decoder::centreOf(const Block& b, Vec3& c, bool& any) {
  Vec3 s = xyz(pos_);
  c = s;
  any = false;
  for (int k = 0; k < 3; ++k) {
    if (!b.has("IJK"[k])) continue;
    if (!centreWord(b, k, s[k], c[k])) return false;
    any = true;
  }
  return true;
}

bool Decoder::buildArc(const Block& b, const Cmd& cmd, const Pos& tgtIn, Element& e) {
  const int code = cmd.code;
  const bool ccw = code == 3;
  const uint32_t cmdAt = cmdBegin(b, cmd), cmdEnd = cmdStop(b, cmd);
  const bool hasR = b.has('R'), hasT = b.has('T'), hasC = b.present & kIJK;
  if (hasR && (hasC || hasT)) {
    const Word& w = b.word('R');
    rep_.error(w.begin, w.end, hasC ? "the radius R and the centre I/J/K cannot both describe an arc"
                                    : "the radius R and the sweep T cannot both describe an arc",
               "gcode-conflict");
    return false;
  }
  if (!hasR && !hasC) {
    if (hasT) {
      const Word& w = b.word('T');
      rep_.error(w.begin, w.end, "the sweep T needs the arc's centre I/J/K", "gcode-missing-word");
    } else {
      rep_.error(cmdAt, cmdEnd,
                 gName(code) + " needs the centre (I/J/K), the radius R, or the centre and the sweep T",
                 "gcode-missing-word");
    }
    return false;
  }
  Pos tgt = tgtIn;
  const Vec3 S = xyz(pos_), n = n_, u = u_, v = v_;
  Vec3 T3 = xyz(tgt);
  double sweepDeg = 0;
  if (hasT) {
    uint32_t inPlane = plane_ == Plane::XY   ? B('X') | B('Y')
                       : plane_ == Plane::ZX ? B('Z') | B('X')
                       : plane_ == Plane::YZ ? B('Y') | B('Z')
                                             : B('X') | B('Y') | B('Z');
    if (b.present & inPlane) {
      const Word& w = b.words[b.at[lowestBit(b.present & inPlane)]];
      rep_.error(w.begin, w.end, "with a sweep T the end point follows from the centre and T; '" + slotName(w.slot) +
                                     "' cannot be given",
                 "gcode-conflict");
      return false;
    }
    if (!wordValue(b, 'T', sweepDeg)) return false;
    if (!(sweepDeg > 0) || sweepDeg > kMaxSweep) {
      const Word& w = b.word('T');
      rep_.error(w.begin, w.end, "the sweep T must be > 0 and at most 36000 degrees (is " + formatNumber(sweepDeg) + ")",
                 "gcode-range");
      return false;
    }
  }
  const double rise = dot(T3 - S, n);
  Vec3 Ep = T3 - rise * n;
  Vec3 C;
  if (hasR) {
    double r;
    if (!wordValue(b, 'R', r)) return false;
    const Word& rw = b.word('R');
    if (r == 0 || std::fabs(r) > kMaxCoord) {
      rep_.error(rw.begin, rw.end, "the radius R must not be 0 and at most 1e9 in magnitude", "gcode-range");
      return false;
    }
    Vec3 chord = Ep - S;
    double d = norm(chord), rr = std::fabs(r), half = 0.5 * d;
    if (d <= 1e-12 * std::max(1.0, rr)) {
      rep_.error(rw.begin, rw.end, "a full circle cannot be given by its radius; program the centre with I/J/K",
                 "gcode-arc");
      return false;
    }
    double h = 0;
    if (rr < half) {
      if (half - rr > 1e-9 * std::max(1.0, half)) {
        rep_.error(rw.begin, rw.end, "the radius " + formatNumber(rr) + " is smaller than half the chord (" +
                                         formatApprox(half) + "): no arc of this radius joins the points",
                   "gcode-arc");
        return false;
      }
    } else {
      h = std::sqrt(rr * rr - half * half);
    }
    Vec3 w = normalized(cross(n, chord));
    bool shortArc = r > 0;
    double sgn = (ccw == shortArc) ? 1.0 : -1.0;
    C = S + 0.5 * chord + (sgn * h) * w;
  } else {
    bool any;
    if (!centreOf(b, C, any)) return false;
    C = C - dot(C - S, n) * n;   // into the plane through the start
  }
  Vec3 s0 = S - C;
  double r0 = norm(s0);
  if (!(r0 > 1e-12)) {
    rep_.error(cmdAt, cmdEnd, "the arc's centre is its start point (radius 0)", "gcode-arc");
    return false;
  }
  double a0 = std::atan2(dot(s0, v), dot(s0, u));
  double sweep;
  if (hasT) {
    sweep = (ccw ? 1 : -1) * sweepDeg * kPi / 180;
    double a1 = a0 + sweep;
    Vec3 E = C + (r0 * std::cos(a1)) * u + (r0 * std::sin(a1)) * v + rise * n;
    tgt[AxX] = E[0];
    tgt[AxY] = E[1];
    tgt[AxZ] = E[2];
  } else {
    bool full = norm(Ep - S) <= 1e-9 * std::max(1.0, r0);
    if (!full && !hasR) {
      double r1 = norm(Ep - C);
      double diff = std::fabs(r0 - r1), rel = diff / std::max(r0, r1);
      if (rel > 0.1) {
        rep_.error(cmdAt, cmdEnd,
                   "the end point is not on the arc: it is " + formatApprox(r1) + " from the centre, the start " +
                       formatApprox(r0) + " (the decoder corrects differences up to 10%)",
                   "gcode-arc");
        return false;
      }
      if (diff > 1e-12 * std::max(r0, r1)) {
        // Move the centre onto the chord's perpendicular bisector.
        Vec3 chord = Ep - S, M = S + 0.5 * chord;
        Vec3 w = normalized(cross(n, chord));
        Vec3 C2 = M + dot(C - M, w) * w;
        if (rel > 1e-3)
          rep_.warning(cmdAt, cmdEnd,
                       "arc centre moved by " + formatApprox(norm(C2 - C)) +
                           " to fit the end point (start and end radii differ by " + formatApprox(rel * 100) + "%)",
                       "gcode-arc-centre");
        C = C2;
        s0 = S - C;
        r0 = norm(s0);
        a0 = std::atan2(dot(s0, v), dot(s0, u));
      }
    }
    if (full) {
      sweep = ccw ? 2 * kPi : -2 * kPi;
    } else {
      Vec3 e1 = Ep - C;
      double a1 = std::atan2(dot(e1, v), dot(e1, u));
      sweep = sweepOf(a1 - a0, ccw);
    }
  }
  e.type = ccw ? MoveType::Cclw : MoveType::Clw;
  e.end = tgt;
  e.arc = ArcGeo{C, u, v, n, r0, a0, sweep, rise};
  return true;
}

bool Decoder::buildEllipse(const Block& b, const Cmd& cmd, const Pos& tgt, Element& e, bool& asLine) {
  const int code = cmd.code;
  const bool ccw = code == 9;
  const uint32_t cmdAt = cmdBegin(b, cmd), cmdEnd = cmdStop(b, cmd);
  asLine = false;
  if (!b.has('I') && !b.has('J')) {
    rep_.error(cmdAt, cmdEnd, gName(code) + " needs the ellipse's centre I/J", "gcode-missing-word");
    return false;
  }
  const Vec3 S = xyz(pos_), T3 = xyz(tgt);
  double c[2] = {S[0], S[1]};
  for (int k = 0; k < 2; ++k)   // (K is the main axis' direction here, not a centre word)
    if (b.has("IJ"[k]) && !centreWord(b, k, S[k], c[k])) return false;
  double kdeg = 0;
  if (b.has('K')) {
    if (!wordValue(b, 'K', kdeg)) return false;
    if (std::fabs(kdeg) > kMaxSweep) {
      rep_.error(b.word('K').begin, b.word('K').end, "the main axis direction K is out of range (|K| <= 36000 degrees)",
                 "gcode-range");
      return false;
    }
  }
  double ratio = 0;
  if (b.has('R')) {
    if (!wordValue(b, 'R', ratio)) return false;
    if (!(ratio > 0) || ratio > 1) {
      rep_.error(b.word('R').begin, b.word('R').end,
                 "the axis ratio R must be in (0, 1] (is " + formatNumber(ratio) + ")", "gcode-range");
      return false;
    }
  }
  double phi = kdeg * kPi / 180;
  Vec3 e1{std::cos(phi), std::sin(phi), 0}, e2{-std::sin(phi), std::cos(phi), 0};
  Vec3 C{c[0], c[1], S[2]};
  Vec3 s = S - C, t = T3 - C;
  t[2] = 0;
  double x0 = dot(s, e1), y0 = dot(s, e2), x1 = dot(t, e1), y1 = dot(t, e2);
  double scale = std::max(x0 * x0 + y0 * y0, x1 * x1 + y1 * y1);
  if (!(scale > 1e-24)) {
    rep_.error(cmdAt, cmdEnd, "the ellipse's start and end are its centre", "gcode-arc");
    return false;
  }
  double tol = 1e-9 * scale, a = 0, bb = 0;
  if (std::fabs(y0 * y0 - y1 * y1) <= tol) {
    // Both points equally far from the main axis: only R decides (if they
    // are also equally far from the second axis).
    if (std::fabs(x0 * x0 - x1 * x1) <= tol) {
      if (!(ratio > 0)) {
        rep_.error(cmdAt, cmdEnd,
                   "the ellipse is not defined by its end points, centre and axis direction: give the axis ratio R",
                   "gcode-missing-word");
        return false;
      }
      a = std::sqrt(x0 * x0 + (y0 * y0) / (ratio * ratio));
      bb = ratio * a;
    }
  } else {
    double det = x0 * x0 * y1 * y1 - x1 * x1 * y0 * y0;
    double p = (y1 * y1 - y0 * y0) / det, q = (x0 * x0 - x1 * x1) / det;
    if (p > 0 && q > 0 && std::isfinite(p) && std::isfinite(q)) {
      a = 1 / std::sqrt(p);
      bb = 1 / std::sqrt(q);
    }
  }
  if (!(a > 0 && bb > 0) || !std::isfinite(a) || !std::isfinite(bb) || a > kMaxPosition || bb > kMaxPosition) {
    rep_.warning(cmdAt, cmdEnd,
                 "no ellipse with this centre and axis direction passes through both points; the move is a line",
                 "gcode-ellipse-line");
    asLine = true;
    return true;
  }
  double p0 = std::atan2(y0 / bb, x0 / a), p1 = std::atan2(y1 / bb, x1 / a);
  bool full = std::hypot(T3[0] - S[0], T3[1] - S[1]) <= 1e-9 * std::sqrt(scale);
  double sweep = full ? (ccw ? 2 * kPi : -2 * kPi) : sweepOf(p1 - p0, ccw);
  e.type = ccw ? MoveType::EllCclw : MoveType::EllClw;
  e.end = tgt;
  e.ellipse = EllipseGeo{C, e1, a, bb, phi, p0, sweep, T3[2] - S[2]};
  return true;
}

bool Decoder::buildParabola(const Block& b, const Cmd& cmd, const Pos& tgt, Element& e) {
  const uint32_t cmdAt = cmdBegin(b, cmd), cmdEnd = cmdStop(b, cmd);
  if (!b.has('I') && !b.has('J')) {
    rep_.error(cmdAt, cmdEnd, "G6 needs the parabola's vertex I/J", "gcode-missing-word");
    return false;
  }
  const Vec3 S = xyz(pos_), T3 = xyz(tgt);
  Vec3 V = S;
  for (int k = 0; k < 2; ++k) {
    char l = "IJ"[k];
    if (!b.has(l)) continue;
    double v;
    if (!wordValue(b, l, v)) return false;
    if (std::fabs(v) > kMaxCoord) {
      rep_.error(b.word(l).begin, b.word(l).end, std::string(1, l) + " is out of range (magnitude above 1e9)",
                 "gcode-range");
      return false;
    }
    V[k] = centreAbsolute_ ? v + offsetVec_[k] : S[k] + v;
  }
  V[2] = 0.5 * (S[2] + T3[2]);
  if (std::hypot(T3[0] - S[0], T3[1] - S[1]) <= 1e-12 * std::max(1.0, norm(S))) {
    rep_.error(cmdAt, cmdEnd, "a parabola needs different start and end points in X/Y", "gcode-arc");
    return false;
  }
  Vec3 ctrl = 2.0 * V - 0.5 * (S + T3);
  ctrl[2] = V[2];
  e.type = MoveType::Parabola;
  e.end = tgt;
  e.parabola = ParabolaGeo{V, ctrl};
  return true;
}

bool Decoder::decodeMotion(const Block& b, const Cmd& cmd, ElementQueue& out, bool& produced) {
  const int code = cmd.code;
  produced = false;
  if ((code == 5 || code == 6 || code == 8 || code == 9) && plane_ != Plane::XY) {
    rep_.error(cmdBegin(b, cmd), cmdStop(b, cmd),
               gName(code) + " works in the XY plane only (G17); the active plane is " + toString(plane_),
               "gcode-plane", SmcError::ObjectNot3D);
    return false;
  }
  Pos tgt;
  if (!target(b, incremental_, tgt)) return false;
  Element e;
  startElement(b, cmd, code == 0 ? MoveType::LinPos : MoveType::Lin, e);
  e.end = tgt;
  switch (code) {
    case 2:
    case 3:
      if (!buildArc(b, cmd, tgt, e)) return false;
      break;
    case 6:
      if (!buildParabola(b, cmd, tgt, e)) return false;
      break;
    case 8:
    case 9: {
      bool asLine;
      if (!buildEllipse(b, cmd, tgt, e, asLine)) return false;
      break;
    }
    case 5:
    case 10: {
      uint8_t dims = code == 5 ? 2 : 3;
      Vec3 S = xyz(pos_), T3 = xyz(tgt);
      Vec3 ch = T3 - S;
      if (dims == 2) ch[2] = 0;
      double L = norm(ch);
      if (!(L > 0)) {
        if (tgt == pos_) return true;   // no move
        rep_.error(cmdBegin(b, cmd), cmdStop(b, cmd),
                   dims == 2 ? "a G5 spline needs a move in X/Y (G10 is the 3D spline)" : "a spline needs a move in X/Y/Z",
                   "gcode-arc");
        return false;
      }
      Vec3 t0{0, 0, 0};
      if (havePending_) t0 = T3 - xyz(pending_.start);
      else if (lastTangentValid_) t0 = lastTangent_;
      if (dims == 2) t0[2] = 0;
      t0 = normalized(t0);
      Vec3 cd = normalized(ch);
      if (norm(t0) == 0) t0 = cd;
      e.type = MoveType::Spline;
      e.spline = SplineGeo{t0, cd, L, dims};
      break;
    }
    default:   // 0, 1: lines
      if (tgt == pos_) return true;   // no move, no element
      break;
  }
  if (e.type != MoveType::LinPos && e.vel == 0 && !feedWarned_) {
    feedWarned_ = true;
    rep_.warning(cmdBegin(b, cmd), cmdStop(b, cmd), "no path velocity: F is not programmed yet and the decoder has no default velocity",
                 "gcode-no-feed");
  }
  if (!switchPoints(b, e)) return false;
  e.marks = marks_;
  marks_ = 0;
  if (e.type != MoveType::Spline) e.length = pathLength(e);
  pos_ = e.end;
  emit(out, e);
  produced = true;
  return true;
}

// ---------------------------------------------------------------- output

void Decoder::emit(ElementQueue& out, const Element& e) {
  if (e.type == MoveType::Spline) {
    if (havePending_) flushPending(out, &e);
    pending_ = e;
    havePending_ = true;
    return;
  }
  if (havePending_) flushPending(out, &e);
  Element& slot = out.push();
  slot = e;
  slot.objNo = static_cast<int32_t>(++objNo_);   // wraps after 2^31 elements (loops)
  if (isToolPath(e.type)) {
    lastTangent_ = endTangent(slot);
    lastTangentValid_ = norm(lastTangent_) > 0;
  } else {
    lastTangentValid_ = false;
  }
}

void Decoder::flushPending(ElementQueue& out, const Element* next) {
  Element& p = pending_;
  Vec3 chord = xyz(p.end) - xyz(p.start);
  if (p.spline.dims == 2) chord[2] = 0;
  Vec3 t = normalized(chord);
  if (next) {
    Vec3 c{0, 0, 0};
    if (next->type == MoveType::Spline) c = xyz(next->end) - xyz(p.start);
    else if (isToolPath(next->type)) c = startTangent(*next);
    if (p.spline.dims == 2) c[2] = 0;
    Vec3 tn = normalized(c);
    if (norm(tn) > 0) t = tn;
  }
  p.spline.t1 = t;
  p.length = pathLength(p);
  Element& slot = out.push();
  slot = p;
  slot.objNo = static_cast<int32_t>(++objNo_);   // wraps after 2^31 elements (loops)
  lastTangent_ = endTangent(slot);
  lastTangentValid_ = norm(lastTangent_) > 0;
  havePending_ = false;
}

}  // namespace stc::cnc
