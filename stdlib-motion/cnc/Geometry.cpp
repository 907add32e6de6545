#include "stdlib-motion/cnc/Geometry.h"

#include <algorithm>

namespace stc::cnc {

namespace {

constexpr Vec3 kZ{0, 0, 1};

// Cubic Hermite basis at u.
void hermite(double u, double& h00, double& h10, double& h01, double& h11) {
  double u2 = u * u, u3 = u2 * u;
  h00 = 2 * u3 - 3 * u2 + 1;
  h10 = u3 - 2 * u2 + u;
  h01 = -2 * u3 + 3 * u2;
  h11 = u3 - u2;
}
void hermiteD(double u, double& h00, double& h10, double& h01, double& h11) {
  double u2 = u * u;
  h00 = 6 * u2 - 6 * u;
  h10 = 3 * u2 - 4 * u + 1;
  h01 = -6 * u2 + 6 * u;
  h11 = 3 * u2 - 2 * u;
}

Vec3 ellipseMinor(const EllipseGeo& g) { return cross(kZ, g.major); }

// The X/Y/Z point of the curved types at u (0 < u < 1).
Vec3 curvePoint(const Element& e, double u) {
  Vec3 p0 = xyz(e.start), p1 = xyz(e.end);
  switch (e.type) {
    case MoveType::Clw:
    case MoveType::Cclw: {
      const ArcGeo& g = e.arc;
      double th = g.startAngle + u * g.sweep;
      return g.centre + (g.radius * std::cos(th)) * g.u + (g.radius * std::sin(th)) * g.v + (u * g.rise) * g.normal;
    }
    case MoveType::EllClw:
    case MoveType::EllCclw: {
      const EllipseGeo& g = e.ellipse;
      double ph = g.startPhi + u * g.sweepPhi;
      return g.centre + (g.a * std::cos(ph)) * g.major + (g.b * std::sin(ph)) * ellipseMinor(g) + (u * g.rise) * kZ;
    }
    case MoveType::Parabola: {
      const ParabolaGeo& g = e.parabola;
      double w = 1 - u;
      Vec3 q = (w * w) * p0 + (2 * u * w) * g.control + (u * u) * p1;
      q[2] = p0[2] + u * (p1[2] - p0[2]);
      return q;
    }
    case MoveType::Spline: {
      const SplineGeo& g = e.spline;
      double h00, h10, h01, h11;
      hermite(u, h00, h10, h01, h11);
      Vec3 q = h00 * p0 + (h10 * g.chord) * g.t0 + h01 * p1 + (h11 * g.chord) * g.t1;
      if (g.dims == 2) q[2] = p0[2] + u * (p1[2] - p0[2]);
      return q;
    }
    default:
      return p0 + u * (p1 - p0);
  }
}

// 8-point Gauss-Legendre on [a, b].
template <class F>
double gauss8(const F& f, double a, double b) {
  static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  double m = 0.5 * (a + b), h = 0.5 * (b - a), s = 0;
  for (int i = 0; i < 4; ++i) s += w[i] * (f(m - h * x[i]) + f(m + h * x[i]));
  return s * h;
}

// Adaptive quadrature: halves an interval until both halves agree with the
// whole to a relative 1e-13, within a depth limit and a budget of evaluations
// (only near-cusps of extreme ellipses reach either).
template <class F>
double adapt(const F& f, double a, double b, double whole, int depth, int& budget) {
  double m = 0.5 * (a + b);
  double l = gauss8(f, a, m), r = gauss8(f, m, b);
  budget -= 2;
  double sum = l + r;
  if (!std::isfinite(sum) || depth <= 0 || budget <= 0 || std::fabs(sum - whole) <= 1e-13 * std::fabs(sum)) return sum;
  return adapt(f, a, m, l, depth - 1, budget) + adapt(f, m, b, r, depth - 1, budget);
}

}  // namespace

Vec3 normalized(const Vec3& a) {
  double n = norm(a);
  if (!(n > 0) || !std::isfinite(n)) return {0, 0, 0};
  return (1.0 / n) * a;
}

Pos point(const Element& e, double u) {
  if (!isMotion(e.type) && e.type != MoveType::InitPos) return e.start;
  if (!(u > 0)) return e.start;
  if (u >= 1) return e.end;
  Pos p;
  for (int i = 0; i < kAxisCount; ++i) p[i] = e.start[i] + u * (e.end[i] - e.start[i]);
  Vec3 q = curvePoint(e, u);
  p[AxX] = q[0];
  p[AxY] = q[1];
  p[AxZ] = q[2];
  return p;
}

Vec3 derivative(const Element& e, double u) {
  u = std::clamp(u, 0.0, 1.0);
  Vec3 p0 = xyz(e.start), p1 = xyz(e.end);
  switch (e.type) {
    case MoveType::Clw:
    case MoveType::Cclw: {
      const ArcGeo& g = e.arc;
      double th = g.startAngle + u * g.sweep;
      return (g.sweep * g.radius) * ((-std::sin(th)) * g.u + std::cos(th) * g.v) + g.rise * g.normal;
    }
    case MoveType::EllClw:
    case MoveType::EllCclw: {
      const EllipseGeo& g = e.ellipse;
      double ph = g.startPhi + u * g.sweepPhi;
      return g.sweepPhi * ((-g.a * std::sin(ph)) * g.major + (g.b * std::cos(ph)) * ellipseMinor(g)) + g.rise * kZ;
    }
    case MoveType::Parabola: {
      const ParabolaGeo& g = e.parabola;
      Vec3 d = (2 * (1 - u)) * (g.control - p0) + (2 * u) * (p1 - g.control);
      d[2] = p1[2] - p0[2];
      return d;
    }
    case MoveType::Spline: {
      const SplineGeo& g = e.spline;
      double h00, h10, h01, h11;
      hermiteD(u, h00, h10, h01, h11);
      Vec3 d = h00 * p0 + (h10 * g.chord) * g.t0 + h01 * p1 + (h11 * g.chord) * g.t1;
      if (g.dims == 2) d[2] = p1[2] - p0[2];
      return d;
    }
    case MoveType::Lin:
    case MoveType::LinPos:
      return p1 - p0;
    default:
      return {0, 0, 0};
  }
}

Vec3 startTangent(const Element& e) { return normalized(derivative(e, 0)); }
Vec3 endTangent(const Element& e) { return normalized(derivative(e, 1)); }

double pathLength(const Element& e) {
  switch (e.type) {
    case MoveType::Lin:
    case MoveType::LinPos: {
      double l = norm(xyz(e.end) - xyz(e.start));
      if (l > 0) return l;
      double s = 0;
      for (int i = 0; i < kAxisCount; ++i) s += (e.end[i] - e.start[i]) * (e.end[i] - e.start[i]);
      return std::sqrt(s);
    }
    case MoveType::Clw:
    case MoveType::Cclw:
      return std::hypot(e.arc.radius * e.arc.sweep, e.arc.rise);
    case MoveType::EllClw:
    case MoveType::EllCclw:
    case MoveType::Parabola:
    case MoveType::Spline: {
      auto speed = [&](double u) { return norm(derivative(e, u)); };
      // Four starting pieces so that a quarter-turn feature is never missed.
      double total = 0;
      int budget = 4000;
      for (int i = 0; i < 4; ++i) {
        double a = i / 4.0, b = (i + 1) / 4.0;
        total += adapt(speed, a, b, gauss8(speed, a, b), 30, budget);
      }
      return total;
    }
    default:
      return 0;
  }
}

}  // namespace stc::cnc
