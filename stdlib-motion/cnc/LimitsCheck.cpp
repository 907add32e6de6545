#include "stdlib-motion/cnc/LimitsCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stdlib-motion/cnc/Geometry.h"

namespace stc::cnc {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;

// Candidate parameters (u in (0, 1)) where one coordinate may have an extreme.
struct Candidates {
  double u[64];
  int n = 0;
  void add(double v) {
    if (v > 0 && v < 1 && n < 64) u[n++] = v;
  }
};

// Critical angles of f(t) = A cos t + B sin t + C t on the sweep from t0 over `sweep`:
// f(t) = R cos(t - phi) + C t with R = hypot(A, B), phi = atan2(B, A), so f'(t) = 0 <=>
// sin(t - phi) = C / R.  For C = 0
// every turn gives the same values, for C != 0 the extremes grow monotonically with the
// turn, so the first and the last root of each family in the sweep suffice.
void angleCandidates(double A, double B, double C, double t0, double sweep, Candidates& c) {
  const double R = std::hypot(A, B);
  if (!(R > 0) || sweep == 0 || std::fabs(C) > R) return;
  const double phi = std::atan2(B, A), delta = std::asin(std::clamp(C / R, -1.0, 1.0));
  const double lo = std::min(t0, t0 + sweep), hi = std::max(t0, t0 + sweep);
  for (double base : {phi + delta, phi + 3.14159265358979323846 - delta}) {
    const double kFirst = std::ceil((lo - base) / kTwoPi), kLast = std::floor((hi - base) / kTwoPi);
    if (kFirst > kLast) continue;
    for (double k : {kFirst, kFirst + 1, kLast - 1, kLast}) {
      if (k < kFirst || k > kLast) continue;
      c.add((base + k * kTwoPi - t0) / sweep);
    }
  }
}

// Roots in (0, 1) of a u^2 + b u + c.
void quadraticRoots(double a, double b, double c, Candidates& out) {
  const double scale = std::max({std::fabs(a), std::fabs(b), std::fabs(c)});
  if (!(scale > 0)) return;
  if (std::fabs(a) <= 1e-14 * scale) {
    if (b != 0) out.add(-c / b);
    return;
  }
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  if (q != 0) out.add(c / q);
  out.add(q / a);
}

}  // namespace

void elementBounds(const Element& e, Pos& lo, Pos& hi) {
  if (!isMotion(e.type)) {
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    return;
  }
  for (int k = 0; k < kAxisCount; ++k) {
    lo[k] = std::min(e.start[k], e.end[k]);
    hi[k] = std::max(e.start[k], e.end[k]);
  }
  Candidates c;
  const Vec3 p0 = xyz(e.start), p1 = xyz(e.end);
  switch (e.type) {
    case MoveType::Clw:
    case MoveType::Cclw: {
      // x_k(t) = centre_k + r cos t u_k + r sin t v_k + (t - t0) / sweep * rise * n_k
      const ArcGeo& g = e.arc;
      if (g.sweep == 0) break;
      for (int k = 0; k < 3; ++k)
        angleCandidates(g.radius * g.u[k], g.radius * g.v[k], g.rise * g.normal[k] / g.sweep, g.startAngle, g.sweep, c);
      break;
    }
    case MoveType::EllClw:
    case MoveType::EllCclw: {
      const EllipseGeo& g = e.ellipse;
      if (g.sweepPhi == 0) break;
      const Vec3 minor = cross(Vec3{0, 0, 1}, g.major);
      const Vec3 z{0, 0, 1};
      for (int k = 0; k < 3; ++k)
        angleCandidates(g.a * g.major[k], g.b * minor[k], g.rise * z[k] / g.sweepPhi, g.startPhi, g.sweepPhi, c);
      break;
    }
    case MoveType::Parabola: {
      // B'(u) = 2 (1-u) (ctrl - p0) + 2 u (p1 - ctrl) = 0 per coordinate (z is linear).
      for (int k = 0; k < 2; ++k) {
        const double a = e.parabola.control[k] - p0[k], b = p1[k] - e.parabola.control[k];
        if (a - b != 0) c.add(a / (a - b));
      }
      break;
    }
    case MoveType::Spline: {
      // Hermite: p'(u) = (6u^2 - 6u) p0 + (3u^2 - 4u + 1) m t0 + (-6u^2 + 6u) p1 + (3u^2 - 2u) m t1.
      const SplineGeo& g = e.spline;
      const int dims = g.dims == 2 ? 2 : 3;
      for (int k = 0; k < dims; ++k) {
        const double m0 = g.chord * g.t0[k], m1 = g.chord * g.t1[k];
        const double a = 6 * p0[k] + 3 * m0 - 6 * p1[k] + 3 * m1;
        const double b = -6 * p0[k] - 4 * m0 + 6 * p1[k] - 2 * m1;
        quadraticRoots(a, b, m0, c);
      }
      break;
    }
    default:
      break;   // lines: the end points
  }
  for (int i = 0; i < c.n; ++i) {
    const Pos p = point(e, c.u[i]);
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
}

uint16_t axesOutOfLimits(const Element& e, const Pos& min, const Pos& max, uint16_t axisMask) {
  if (!isMotion(e.type)) return 0;
  Pos lo, hi;
  elementBounds(e, lo, hi);
  uint16_t out = 0;
  for (int k = 0; k < kAxisCount; ++k) {
    if (!(axisMask & (1u << k))) continue;
    const double tolLo = 1e-9 * std::max(1.0, std::fabs(min[k])), tolHi = 1e-9 * std::max(1.0, std::fabs(max[k]));
    // NaN coordinates count as outside (!(x >= ...)).
    if (!(lo[k] >= min[k] - tolLo) || !(hi[k] <= max[k] + tolHi)) out |= uint16_t(1u << k);
  }
  return out;
}

}  // namespace stc::cnc
