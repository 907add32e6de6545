// Loop avoidance (AvoidLoop.h; docs/cnc.md, "Loop avoidance").
#include "stdlib-motion/cnc/AvoidLoop.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "stdlib-motion/cnc/Geometry.h"

namespace stc::cnc {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kEnds = 1e-9;   // crossings this close to an element's joint are the joint

bool isArc(const Element& e) { return e.type == MoveType::Clw || e.type == MoveType::Cclw; }

// Lines and arcs of the XY plane can be cut; a loop that holds anything else (a G0, an M
// function, a dwell, an arc of another plane) is left alone.
bool cuttable(const Element& e) {
  if (e.type == MoveType::Lin) return true;
  return isArc(e) && std::fabs(std::fabs(e.arc.normal[2]) - 1) < 1e-12;
}

struct X2 {
  double x, y;
};
X2 xy(const Pos& p) { return {p[AxX], p[AxY]}; }

// The parameter (0..1) of a point of the arc's circle along the arc, or -1 outside the arc.
double arcParam(const Element& e, X2 p) {
  const ArcGeo& g = e.arc;
  const Vec3 q{p.x - g.centre[0], p.y - g.centre[1], 0};
  double rel = std::remainder(std::atan2(dot(q, g.v), dot(q, g.u)) - g.startAngle, kTwoPi);
  if (g.sweep > 0 && rel < 0) rel += kTwoPi;
  if (g.sweep < 0 && rel > 0) rel -= kTwoPi;
  const double t = g.sweep != 0 ? rel / g.sweep : -1;
  return t >= 0 && t <= 1 ? t : -1;
}
double lineParam(const Element& e, X2 p) {
  const X2 a = xy(e.start), b = xy(e.end);
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  if (l2 == 0) return -1;
  const double t = ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2;
  return t >= -1e-12 && t <= 1 + 1e-12 ? std::clamp(t, 0.0, 1.0) : -1;
}
double paramOf(const Element& e, X2 p) { return isArc(e) ? arcParam(e, p) : lineParam(e, p); }

// The points where the XY curves of two elements cross, as parameters (ta on a, tb on b).
int crossings(const Element& a, const Element& b, double ta[2], double tb[2]) {
  X2 pts[2];
  int n = 0;
  if (!isArc(a) && !isArc(b)) {
    const X2 p = xy(a.start), r{a.end[AxX] - p.x, a.end[AxY] - p.y};
    const X2 q = xy(b.start), s{b.end[AxX] - q.x, b.end[AxY] - q.y};
    const double den = r.x * s.y - r.y * s.x;
    if (std::fabs(den) < 1e-15 * (std::hypot(r.x, r.y) * std::hypot(s.x, s.y) + 1e-300)) return 0;
    const double t = ((q.x - p.x) * s.y - (q.y - p.y) * s.x) / den;
    const double u = ((q.x - p.x) * r.y - (q.y - p.y) * r.x) / den;
    if (t < 0 || t > 1 || u < 0 || u > 1) return 0;
    ta[0] = t;
    tb[0] = u;
    return 1;
  }
  if (isArc(a) != isArc(b)) {
    const Element& L = isArc(a) ? b : a;
    const Element& C = isArc(a) ? a : b;
    const X2 p = xy(L.start);
    const double dx = L.end[AxX] - p.x, dy = L.end[AxY] - p.y, len = std::hypot(dx, dy);
    if (len == 0) return 0;
    const double ux = dx / len, uy = dy / len, fx = p.x - C.arc.centre[0], fy = p.y - C.arc.centre[1];
    // From the foot of the perpendicular from the centre: the discriminant bq^2 - |f|^2 + R^2
    // cancels catastrophically when the line starts far from the circle (|f| >> R), which put
    // the crossing (and the cut arc's start) off the circle.
    const double s0 = -(fx * ux + fy * uy);
    const double hx = fx + s0 * ux, hy = fy + s0 * uy;
    const double disc = C.arc.radius * C.arc.radius - (hx * hx + hy * hy);
    if (disc < 0) return 0;
    const double sq = std::sqrt(disc);
    for (double s : {s0 - sq, s0 + sq}) pts[n++] = {p.x + s * ux, p.y + s * uy};
  } else {
    const double dx = b.arc.centre[0] - a.arc.centre[0], dy = b.arc.centre[1] - a.arc.centre[1], D = std::hypot(dx, dy);
    if (D < 1e-15) return 0;
    const double R1 = a.arc.radius, R2 = b.arc.radius;
    const double m = (R1 * R1 - R2 * R2 + D * D) / (2 * D), h2 = R1 * R1 - m * m;
    if (h2 < 0) return 0;
    const double h = std::sqrt(h2), ux = dx / D, uy = dy / D;
    const double bx = a.arc.centre[0] + m * ux, by = a.arc.centre[1] + m * uy;
    pts[n++] = {bx - h * uy, by + h * ux};
    pts[n++] = {bx + h * uy, by - h * ux};
  }
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const double s = paramOf(a, pts[i]), t = paramOf(b, pts[i]);
    if (s < 0 || t < 0) continue;
    ta[k] = s;
    tb[k] = t;
    ++k;
  }
  return k;
}

// `w` ends at its parameter t.
void cutEnd(Element& w, double t) {
  const Pos p = point(w, t);
  if (isArc(w)) {
    w.arc.sweep *= t;
    w.arc.rise *= t;
  }
  w.end = p;
  w.length = pathLength(w);
}
// `e` starts at `from` (its point at parameter t in XY).
void cutStart(Element& e, double t, const Pos& from) {
  if (isArc(e)) {
    ArcGeo& g = e.arc;
    const double oldAt = g.startAngle + t * g.sweep;
    g.centre[2] = from[AxZ];
    const Vec3 q = xyz(from) - g.centre;
    const double a = std::atan2(dot(q, g.v), dot(q, g.u));
    g.sweep = g.sweep * (1 - t) + std::remainder(oldAt - a, kTwoPi);
    g.startAngle = a;
    g.rise = (e.end[AxZ] - from[AxZ]) * g.normal[2];
  }
  e.start = from;
  e.length = pathLength(e);
}

}  // namespace

bool LoopAvoider::cutLoop(Element& e) {
  const size_t n = window_.size();
  if (n < 2 || !cuttable(e)) return false;
  size_t bestI = n;
  double bestTw = 0, bestTe = 2;
  for (size_t i = 0; i + 1 < n && bestI == n; ++i) {   // the earliest element first: the whole loop
    const Element& w = window_[i];
    if (!cuttable(w)) continue;
    double tw[2], te[2];
    const int k = crossings(w, e, tw, te);
    for (int j = 0; j < k; ++j) {
      if (te[j] <= kEnds || te[j] >= 1 - kEnds) continue;        // at e's joints
      if (i + 2 == n && tw[j] >= 1 - kEnds) continue;            // the predecessor's start
      if (te[j] < bestTe) {
        bestI = i;
        bestTw = tw[j];
        bestTe = te[j];
      }
    }
  }
  if (bestI == n) return false;
  for (size_t j = bestI + 1; j < n; ++j)
    if (!cuttable(window_[j])) return false;   // an M function or a G0 in the loop: keep it
  Element& w = window_[bestI];
  cutEnd(w, bestTw);
  cutStart(e, bestTe, w.end);
  dropped_ += n - bestI - 1;
  ++loops_;
  window_.erase(window_.begin() + static_cast<std::ptrdiff_t>(bestI) + 1, window_.end());
  return true;
}

void LoopAvoider::flushWindow() {
  for (Element& w : window_) out_.push_back(w);
  window_.clear();
}

void LoopAvoider::push(const Element& e) {
  if (!e.loopAvoid) {
    flushWindow();
    out_.push_back(e);
    return;
  }
  Element x = e;
  cutLoop(x);
  window_.push_back(x);
  while (window_.size() > kWindow) {
    out_.push_back(window_.front());
    window_.pop_front();
  }
}

void LoopAvoider::finish() { flushWindow(); }

std::vector<Element> avoidLoopsAll(const std::vector<Element>& in) {
  LoopAvoider la;
  std::vector<Element> out;
  for (const Element& e : in) {
    la.push(e);
    while (la.hasOutput()) {
      out.push_back(la.front());
      la.pop();
    }
  }
  la.finish();
  while (la.hasOutput()) {
    out.push_back(la.front());
    la.pop();
  }
  return out;
}

}  // namespace stc::cnc
