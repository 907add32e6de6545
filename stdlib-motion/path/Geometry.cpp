// Path geometry (see Geometry.h and docs/path.md).
#include "stdlib-motion/path/Geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stc::motion::path {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = std::numbers::pi / 2;
constexpr double kTwoPi = 2 * std::numbers::pi;

// 8-point Gauss-Legendre on [-1, 1].
constexpr double kGx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr double kGw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

template <class F>
double gauss8(const F& f, double a, double b) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  double s = 0;
  for (int i = 0; i < 4; ++i) s += kGw[i] * (f(m - h * kGx[i]) + f(m + h * kGx[i]));
  return s * h;
}

// Adaptive table of the integral of f over [a, b]: an interval is kept when
// one 8-point rule and the sum over its halves agree to relTol of the total.
template <class F>
bool buildTable(const F& f, double a, double b, int initial, ArcTable& t) {
  constexpr double relTol = 1e-14;
  const double total = gauss8(f, a, b);
  if (!(total > 0) || !std::isfinite(total)) return false;
  struct Iv { double a, b; };
  Iv stack[64];
  int sp = 0;
  for (int i = initial - 1; i >= 0; --i) stack[sp++] = {a + (b - a) * i / initial, a + (b - a) * (i + 1) / initial};
  t.n = 1;
  t.u[0] = a;
  t.S[0] = 0;
  while (sp > 0) {
    const Iv iv = stack[--sp];
    const double m = 0.5 * (iv.a + iv.b);
    const double whole = gauss8(f, iv.a, iv.b);
    const double halves = gauss8(f, iv.a, m) + gauss8(f, m, iv.b);
    if (std::fabs(whole - halves) > relTol * total && sp + 2 <= 64 && iv.b - iv.a > 1e-9 * (b - a)) {
      stack[sp++] = {m, iv.b};
      stack[sp++] = {iv.a, m};
      continue;
    }
    if (std::fabs(whole - halves) > 1e-11 * total) return false;
    if (t.n >= ArcTable::kKnots) return false;
    t.u[t.n] = iv.b;
    t.S[t.n] = t.S[t.n - 1] + halves;
    ++t.n;
  }
  t.u[t.n - 1] = b;
  return true;
}

// Index i with S[i] <= s < S[i+1] (clamped to the table).
int findS(const ArcTable& t, double s) {
  int lo = 0, hi = t.n - 1;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (t.S[mid] <= s) lo = mid;
    else hi = mid;
  }
  return lo;
}
int findU(const ArcTable& t, double u) {
  int lo = 0, hi = t.n - 1;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (t.u[mid] <= u) lo = mid;
    else hi = mid;
  }
  return lo;
}

// Invert S(u) = s on the table with Newton steps safeguarded by the knot bracket.
template <class F>
double invertTable(const ArcTable& t, const F& speed, double s) {
  if (s <= 0) return t.u[0];
  if (s >= t.S[t.n - 1]) return t.u[t.n - 1];
  const int i = findS(t, s);
  double lo = t.u[i], hi = t.u[i + 1];
  const double target = s - t.S[i];
  double u = lo + (hi - lo) * target / (t.S[i + 1] - t.S[i]);
  for (int it = 0; it < 30; ++it) {
    const double f = gauss8(speed, t.u[i], u) - target;
    if (f > 0) hi = u;
    else lo = u;
    if (std::fabs(f) <= 1e-15 * t.S[t.n - 1]) break;
    const double d = speed(u);
    double next = d > 0 ? u - f / d : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == u) break;
    u = next;
  }
  return u;
}

bool finiteVec(const Vec& v, int dims) {
  for (int i = 0; i < dims; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
void cross3(const double* a, const double* b, double* o) {
  const double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
  o[0] = x;
  o[1] = y;
  o[2] = z;
}
double norm3(const double* a) { return std::sqrt(dot3(a, a)); }

// The Cartesian part (coordinates 0..min(dims,3)-1; the others 0).
void cart(const Vec& v, int dims, double* o) {
  for (int i = 0; i < 3; ++i) o[i] = i < dims ? v[i] : 0.0;
}

double cartDist(const Vec& a, const Vec& b, int dims) {
  double s = 0;
  for (int i = 0; i < std::min(dims, 3); ++i) s += (b[i] - a[i]) * (b[i] - a[i]);
  return std::sqrt(s);
}
double allDist(const Vec& a, const Vec& b, int dims) {
  double s = 0;
  for (int i = 0; i < dims; ++i) s += (b[i] - a[i]) * (b[i] - a[i]);
  return std::sqrt(s);
}

// Coordinates below this Cartesian length count as "no Cartesian extent".
constexpr double kCartEps = 1e-9;

double wrap2Pi(double a) {
  a = std::fmod(a, kTwoPi);
  if (a < 0) a += kTwoPi;
  return a;
}

}  // namespace

const char* toString(GeoStatus s) {
  switch (s) {
    case GeoStatus::Ok: return "ok";
    case GeoStatus::NonFinite: return "non-finite input";
    case GeoStatus::BadDims: return "bad number of coordinates";
    case GeoStatus::ZeroLength: return "zero length";
    case GeoStatus::Collinear: return "collinear border points";
    case GeoStatus::RadiusTooSmall: return "radius smaller than half the chord";
    case GeoStatus::NotOnCircle: return "end point not on the circle/ellipse";
    case GeoStatus::BadPlane: return "undefined plane";
    case GeoStatus::BadParameter: return "bad parameter";
    case GeoStatus::Quadrature: return "arc-length table did not converge";
    case GeoStatus::TooManyPoints: return "too many points";
  }
  return "?";
}

// ---------------------------------------------------------------- evaluation

void Segment::evalBase(double sg, PathPoint& o) const {
  const int n = dims_;
  o.pos = {};
  o.d1 = {};
  o.d2 = {};
  o.curvature = 0;
  switch (kind_) {
    case SegKind::Line: {
      const auto& L = g_.line;
      for (int i = 0; i < n; ++i) {
        o.pos[i] = base0_[i] + L.dir[i] * sg;
        o.d1[i] = L.dir[i];
      }
      return;
    }
    case SegKind::Arc: {
      const auto& A = g_.arc;
      const double th = sg / A.m;
      const double c = std::cos(th), s = std::sin(th);
      const double h = A.rise / A.sweep;   // rise per radian
      const double im = 1.0 / A.m;
      for (int i = 0; i < std::min(n, 3); ++i) {
        o.pos[i] = A.c[i] + A.r * (c * A.u[i] + s * A.v[i]) + h * th * A.n[i];
        o.d1[i] = (A.r * (-s * A.u[i] + c * A.v[i]) + h * A.n[i]) * im;
        o.d2[i] = A.r * (-c * A.u[i] - s * A.v[i]) * im * im;
      }
      for (int i = 3; i < n; ++i) {
        o.pos[i] = base0_[i] + A.auxDir[i] * sg;
        o.d1[i] = A.auxDir[i];
      }
      o.curvature = A.r * im * im;
      return;
    }
    case SegKind::Ellipse: {
      const auto& E = g_.ell;
      const double phi = ellipseInvG(E.G0 + E.dir * sg);
      const double c = std::cos(phi), s = std::sin(phi);
      double p1[3], p2[3];
      for (int i = 0; i < 3; ++i) {
        p1[i] = E.dir * (-E.A * s * E.e1[i] + E.B * c * E.e2[i]);   // dp/dt
        p2[i] = -E.A * c * E.e1[i] - E.B * s * E.e2[i];             // d2p/dt2
      }
      const double sig = norm3(p1);
      const double sigt = dot3(p1, p2) / sig;
      for (int i = 0; i < std::min(n, 3); ++i) {
        o.pos[i] = E.c[i] + E.A * c * E.e1[i] + E.B * s * E.e2[i];
        o.d1[i] = p1[i] / sig;
        o.d2[i] = (p2[i] - p1[i] * sigt / sig) / (sig * sig);
      }
      for (int i = 3; i < n; ++i) {
        o.pos[i] = base0_[i] + E.auxDir[i] * sg;
        o.d1[i] = E.auxDir[i];
      }
      double k2 = 0;
      for (int i = 0; i < std::min(n, 3); ++i) k2 += o.d2[i] * o.d2[i];
      o.curvature = std::sqrt(k2);
      return;
    }
    case SegKind::Poly: {
      const auto& P = g_.poly;
      const double u = polyInvS(sg);
      double q1[kMaxCoords], q2[kMaxCoords];
      for (int i = 0; i < n; ++i) {
        const double* c = P.c[i];
        o.pos[i] = c[0] + u * (c[1] + u * (c[2] + u * (c[3] + u * (c[4] + u * c[5]))));
        q1[i] = c[1] + u * (2 * c[2] + u * (3 * c[3] + u * (4 * c[4] + u * 5 * c[5])));
        q2[i] = 2 * c[2] + u * (6 * c[3] + u * (12 * c[4] + u * 20 * c[5]));
      }
      const int m = cartMetric_ ? std::min(n, 3) : n;
      double ss = 0, sd = 0;
      for (int i = 0; i < m; ++i) {
        ss += q1[i] * q1[i];
        sd += q1[i] * q2[i];
      }
      const double sig = std::sqrt(ss);
      const double sigt = sd / sig;
      double k2 = 0;
      for (int i = 0; i < n; ++i) {
        o.d1[i] = q1[i] / sig;
        o.d2[i] = (q2[i] - q1[i] * sigt / sig) / ss;
        if (i < m) k2 += o.d2[i] * o.d2[i];
      }
      o.curvature = std::sqrt(k2);
      return;
    }
  }
}

void Segment::eval(double s, PathPoint& o) const {
  if (!(s > 0)) s = 0;
  if (s >= len_) {
    evalBase(s0_ + len_, o);
    o.pos = p1_;
    return;
  }
  evalBase(s0_ + s, o);
  if (s == 0) o.pos = p0_;
}

Vec Segment::position(double s) const {
  PathPoint p;
  eval(s, p);
  return p.pos;
}

double Segment::ellipseG(double phi) const {
  const auto& E = g_.ell;
  const double k = std::floor(phi / kHalfPi);
  const double r = phi - k * kHalfPi;
  auto speed = [&](double x) {
    const double s = std::sin(x), c = std::cos(x);
    return std::sqrt(E.A * E.A * s * s + E.B * E.B * c * c);
  };
  auto Sq = [&](double x) {
    const int i = findU(E.tab, x);
    return E.tab.S[i] + gauss8(speed, E.tab.u[i], x);
  };
  const long long ki = static_cast<long long>(k);
  const double q = (ki % 2 != 0) ? E.Q - Sq(kHalfPi - r) : Sq(r);
  return k * E.Q + q;
}

double Segment::ellipseInvG(double g) const {
  const auto& E = g_.ell;
  const double k = std::floor(g / E.Q);
  const double rem = g - k * E.Q;
  auto speed = [&](double x) {
    const double s = std::sin(x), c = std::cos(x);
    return std::sqrt(E.A * E.A * s * s + E.B * E.B * c * c);
  };
  const long long ki = static_cast<long long>(k);
  const double r = (ki % 2 != 0) ? kHalfPi - invertTable(E.tab, speed, E.Q - rem) : invertTable(E.tab, speed, rem);
  return k * kHalfPi + r;
}

double Segment::polyS(double u) const {
  const auto& P = g_.poly;
  const int i = findU(P.tab, u);
  const int m = cartMetric_ ? std::min<int>(dims_, 3) : dims_;
  auto speed = [&](double x) {
    double ss = 0;
    for (int k = 0; k < m; ++k) {
      const double* c = P.c[k];
      const double d = c[1] + x * (2 * c[2] + x * (3 * c[3] + x * (4 * c[4] + x * 5 * c[5])));
      ss += d * d;
    }
    return std::sqrt(ss);
  };
  return P.tab.S[i] + gauss8(speed, P.tab.u[i], u);
}

double Segment::polyInvS(double s) const {
  const auto& P = g_.poly;
  const int m = cartMetric_ ? std::min<int>(dims_, 3) : dims_;
  auto speed = [&](double x) {
    double ss = 0;
    for (int k = 0; k < m; ++k) {
      const double* c = P.c[k];
      const double d = c[1] + x * (2 * c[2] + x * (3 * c[3] + x * (4 * c[4] + x * 5 * c[5])));
      ss += d * d;
    }
    return std::sqrt(ss);
  };
  return invertTable(P.tab, speed, s);
}

double Segment::polyCurvature(double u) const {
  const auto& P = g_.poly;
  const int m = cartMetric_ ? std::min<int>(dims_, 3) : dims_;
  double q1[kMaxCoords], q2[kMaxCoords], ss = 0, sd = 0;
  for (int i = 0; i < m; ++i) {
    const double* c = P.c[i];
    q1[i] = c[1] + u * (2 * c[2] + u * (3 * c[3] + u * (4 * c[4] + u * 5 * c[5])));
    q2[i] = 2 * c[2] + u * (6 * c[3] + u * (12 * c[4] + u * 20 * c[5]));
    ss += q1[i] * q1[i];
    sd += q1[i] * q2[i];
  }
  const double sig = std::sqrt(ss), sigt = sd / sig;
  double k2 = 0;
  for (int i = 0; i < m; ++i) {
    const double d2 = (q2[i] - q1[i] * sigt / sig) / ss;
    k2 += d2 * d2;
  }
  return std::sqrt(k2);
}

void Segment::finish() {
  s0_ = 0;
  len_ = baseLen_;
  p0_ = base0_;
  p1_ = base1_;
  // curvature bound
  switch (kind_) {
    case SegKind::Line: kappaMax_ = 0; break;
    case SegKind::Arc: kappaMax_ = g_.arc.r / (g_.arc.m * g_.arc.m); break;
    case SegKind::Poly: {
      // Curvature does not depend on the parameterisation: scan the polynomial's own
      // parameter (no arc-length inversion per sample), then refine around the largest.
      const auto& t = g_.poly.tab;
      const double u0 = t.u[0], u1 = t.u[t.n - 1];
      constexpr int N = 128;
      double best = 0;
      int bi = 0;
      for (int i = 0; i <= N; ++i) {
        const double k = polyCurvature(u0 + (u1 - u0) * i / N);
        if (k > best) {
          best = k;
          bi = i;
        }
      }
      double lo = u0 + (u1 - u0) * std::max(0, bi - 1) / N, hi = u0 + (u1 - u0) * std::min(N, bi + 1) / N;
      const double gr = 0.6180339887498949;
      for (int it = 0; it < 40; ++it) {
        const double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
        const double a = polyCurvature(x1), b = polyCurvature(x2);
        best = std::max({best, a, b});
        if (a > b) hi = x2;
        else lo = x1;
      }
      kappaMax_ = best * (1 + 1e-9);
      break;
    }
    default: {
      // dense samples, then a golden-section refinement around the largest one
      constexpr int N = 128;
      double best = 0;
      int bi = 0;
      PathPoint pp;
      for (int i = 0; i <= N; ++i) {
        evalBase(baseLen_ * i / N, pp);
        if (pp.curvature > best) {
          best = pp.curvature;
          bi = i;
        }
      }
      double lo = baseLen_ * std::max(0, bi - 1) / N, hi = baseLen_ * std::min(N, bi + 1) / N;
      const double gr = 0.6180339887498949;
      for (int it = 0; it < 40; ++it) {
        const double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
        PathPoint a, b;
        evalBase(x1, a);
        evalBase(x2, b);
        best = std::max({best, a.curvature, b.curvature});
        if (a.curvature > b.curvature) hi = x2;
        else lo = x1;
      }
      kappaMax_ = best * (1 + 1e-9);
    }
  }
}

GeoStatus Segment::trim(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return GeoStatus::NonFinite;
  if (!(a >= 0) || !(b > a) || b > len_ * (1 + 1e-12)) return GeoStatus::BadParameter;
  b = std::min(b, len_);
  PathPoint pa, pb;
  eval(a, pa);
  eval(b, pb);
  s0_ += a;
  len_ = b - a;
  p0_ = pa.pos;
  p1_ = pb.pos;
  return GeoStatus::Ok;
}

// ---------------------------------------------------------------- builders

GeoStatus Segment::line(const Vec& a, const Vec& b, int dims, Segment& out) {
  if (dims < 1 || dims > kMaxCoords) return GeoStatus::BadDims;
  if (!finiteVec(a, dims) || !finiteVec(b, dims)) return GeoStatus::NonFinite;
  Segment s;
  s.kind_ = SegKind::Line;
  s.dims_ = static_cast<uint8_t>(dims);
  const double lc = cartDist(a, b, dims);
  s.cartMetric_ = lc > kCartEps;
  s.baseLen_ = s.cartMetric_ ? lc : allDist(a, b, dims);
  if (!(s.baseLen_ > 0)) return GeoStatus::ZeroLength;
  if (!std::isfinite(s.baseLen_)) return GeoStatus::NonFinite;
  s.base0_ = a;
  s.base1_ = b;
  for (int i = dims; i < kMaxCoords; ++i) s.base0_[i] = s.base1_[i] = 0;
  for (int i = 0; i < dims; ++i) s.g_.line.dir[i] = (b[i] - a[i]) / s.baseLen_;
  s.finish();
  out = s;
  return GeoStatus::Ok;
}

GeoStatus Segment::arcCenter(const Vec& a, const Vec& centre, const Vec& b, const Vec& normal, bool ccw, int turns,
                             int dims, Segment& out) {
  if (dims < 2 || dims > kMaxCoords) return GeoStatus::BadDims;
  if (!finiteVec(a, dims) || !finiteVec(b, dims) || !finiteVec(centre, dims) || !finiteVec(normal, 3))
    return GeoStatus::NonFinite;
  if (turns < 0) return GeoStatus::BadParameter;
  double A[3], B[3], C[3], N[3];
  cart(a, dims, A);
  cart(b, dims, B);
  cart(centre, dims, C);
  for (int i = 0; i < 3; ++i) N[i] = normal[i];
  if (dims < 3) {   // a planar group: the XY plane, the normal's sign gives the sense
    N[0] = N[1] = 0;
    N[2] = normal[2] < 0 ? -1 : 1;
  }
  double nn = norm3(N);
  bool autoPlane = false;
  double ca[3], cb[3];
  for (int i = 0; i < 3; ++i) {
    ca[i] = A[i] - C[i];
    cb[i] = B[i] - C[i];
  }
  if (!(nn > 0)) {
    double x[3];
    cross3(ca, cb, x);
    const double xn = norm3(x);
    if (!(xn > 1e-12 * std::max(1.0, dot3(ca, ca)))) return GeoStatus::BadPlane;
    for (int i = 0; i < 3; ++i) N[i] = x[i] / xn;
    autoPlane = true;   // N gives the short arc counter-clockwise
  } else {
    for (int i = 0; i < 3; ++i) N[i] /= nn;
  }
  if (!ccw)   // clockwise about N = counter-clockwise about -N (auto plane: the long arc)
    for (int i = 0; i < 3; ++i) N[i] = -N[i];
  // project the centre into the plane through A, B into it as well (rise)
  const double cOff = dot3(ca, N);   // A - C along N
  double Cp[3];
  for (int i = 0; i < 3; ++i) Cp[i] = C[i] + cOff * N[i];
  double u[3], w[3];
  for (int i = 0; i < 3; ++i) u[i] = A[i] - Cp[i];
  const double r = norm3(u);
  if (!(r > 0)) return GeoStatus::ZeroLength;
  for (int i = 0; i < 3; ++i) u[i] /= r;
  double rel[3];
  for (int i = 0; i < 3; ++i) rel[i] = B[i] - A[i];
  const double rise = dot3(rel, N);
  for (int i = 0; i < 3; ++i) w[i] = B[i] - rise * N[i] - Cp[i];
  const double rb = norm3(w);
  if (std::fabs(rb - r) > 1e-6 * std::max(r, 1.0)) return GeoStatus::NotOnCircle;
  double v[3];
  cross3(N, u, v);
  double ang = std::atan2(dot3(w, v), dot3(w, u));
  if (ang < 0) ang += kTwoPi;
  if (ang * r < 1e-12 * std::max(1.0, r) || kTwoPi - ang < 1e-12) ang = kTwoPi;   // end == start: full turn
  (void)autoPlane;
  const double sweep = ang + kTwoPi * turns;
  return arcAssemble(a, b, Cp, u, N, r, sweep, rise, dims, out);
}

GeoStatus Segment::arcBorder(const Vec& a, const Vec& m, const Vec& b, const Vec& normal, int dims, Segment& out) {
  if (dims < 2 || dims > kMaxCoords) return GeoStatus::BadDims;
  if (!finiteVec(a, dims) || !finiteVec(b, dims) || !finiteVec(m, dims) || !finiteVec(normal, 3))
    return GeoStatus::NonFinite;
  double A[3], M[3], B[3];
  cart(a, dims, A);
  cart(m, dims, M);
  cart(b, dims, B);
  double am[3], ab[3];
  for (int i = 0; i < 3; ++i) {
    am[i] = M[i] - A[i];
    ab[i] = B[i] - A[i];
  }
  const double lam = norm3(am), lab = norm3(ab);
  if (!(lam > 0)) return GeoStatus::Collinear;
  if (lab <= 1e-12 * lam) {
    // full circle: m diametrically opposite
    double N[3] = {normal[0], normal[1], normal[2]};
    if (dims < 3) N[0] = N[1] = 0, N[2] = normal[2] < 0 ? -1 : 1;
    const double nn = norm3(N);
    if (!(nn > 0)) return GeoStatus::BadPlane;
    for (int i = 0; i < 3; ++i) N[i] /= nn;
    if (std::fabs(dot3(am, N)) > 1e-9 * lam) return GeoStatus::BadPlane;
    Vec c = a;
    for (int i = 0; i < std::min(dims, 3); ++i) c[i] = 0.5 * (A[i] + M[i]);
    Vec nv{};
    for (int i = 0; i < 3; ++i) nv[i] = N[i];
    return arcCenter(a, c, b, nv, true, 0, dims, out);
  }
  double x[3];
  cross3(am, ab, x);
  const double xn = norm3(x);
  if (!(xn > 1e-10 * lam * lab)) return GeoStatus::Collinear;
  double N[3];
  for (int i = 0; i < 3; ++i) N[i] = x[i] / xn;
  // circumcentre: C = A + (|ab|^2 (x × am)... ) standard formula
  double t1[3], t2[3], c[3];
  double xa[3], xb[3];
  cross3(x, am, xa);   // x × am
  cross3(ab, x, xb);   // ab × x
  const double k = 1.0 / (2 * xn * xn);
  for (int i = 0; i < 3; ++i) {
    t1[i] = dot3(ab, ab) * xa[i];
    t2[i] = dot3(am, am) * xb[i];
    c[i] = A[i] + (t1[i] + t2[i]) * k;
  }
  Vec cv = a, nv{};
  for (int i = 0; i < 3; ++i) {
    if (i < dims) cv[i] = c[i];
    nv[i] = N[i];
  }
  return arcCenter(a, cv, b, nv, true, 0, dims, out);
}

GeoStatus Segment::arcRadius(const Vec& a, const Vec& b, double r, const Vec& normal, bool ccw, bool longArc,
                             int turns, int dims, Segment& out) {
  if (dims < 2 || dims > kMaxCoords) return GeoStatus::BadDims;
  if (!finiteVec(a, dims) || !finiteVec(b, dims) || !finiteVec(normal, 3) || !std::isfinite(r))
    return GeoStatus::NonFinite;
  if (!(r > 0)) return GeoStatus::ZeroLength;
  double N[3] = {normal[0], normal[1], normal[2]};
  if (dims < 3) N[0] = N[1] = 0, N[2] = normal[2] < 0 ? -1 : 1;
  const double nn = norm3(N);
  if (!(nn > 0)) return GeoStatus::BadPlane;
  for (int i = 0; i < 3; ++i) N[i] /= nn;
  double A[3], B[3], d[3];
  cart(a, dims, A);
  cart(b, dims, B);
  for (int i = 0; i < 3; ++i) d[i] = B[i] - A[i];
  const double rise = dot3(d, N);
  for (int i = 0; i < 3; ++i) d[i] -= rise * N[i];
  const double chord = norm3(d);
  if (!(chord > 1e-12 * r)) return GeoStatus::ZeroLength;   // a full circle needs its centre
  if (r < 0.5 * chord * (1 - 1e-9)) return GeoStatus::RadiusTooSmall;
  const double half = 0.5 * chord;
  const double h = std::sqrt(std::max(0.0, r * r - half * half));
  double dh[3], w[3];
  for (int i = 0; i < 3; ++i) dh[i] = d[i] / chord;
  cross3(N, dh, w);   // left of the chord (seen from +N)
  const double sgn = (ccw != longArc) ? 1.0 : -1.0;
  Vec c = a;
  for (int i = 0; i < std::min(dims, 3); ++i) c[i] = A[i] + 0.5 * d[i] + sgn * h * w[i];
  Vec nv{};
  for (int i = 0; i < 3; ++i) nv[i] = N[i];
  return arcCenter(a, c, b, nv, ccw, turns, dims, out);
}


GeoStatus Segment::arcAssemble(const Vec& a, const Vec& b, const double* c, const double* u, const double* n,
                               double r, double sweep, double rise, int dims, Segment& out) {
  Segment s;
  s.kind_ = SegKind::Arc;
  s.dims_ = static_cast<uint8_t>(dims);
  s.cartMetric_ = true;
  auto& A = s.g_.arc;
  for (int i = 0; i < 3; ++i) {
    A.c[i] = c[i];
    A.u[i] = u[i];
    A.n[i] = n[i];
  }
  cross3(A.n, A.u, A.v);
  A.r = r;
  A.sweep = sweep;
  A.rise = rise;
  s.baseLen_ = std::sqrt(r * r * sweep * sweep + rise * rise);
  if (!(s.baseLen_ > 0) || !std::isfinite(s.baseLen_)) return GeoStatus::ZeroLength;
  A.m = s.baseLen_ / sweep;
  A.auxDir = {};
  for (int i = 3; i < dims; ++i) A.auxDir[i] = (b[i] - a[i]) / s.baseLen_;
  s.base0_ = a;
  s.base1_ = b;
  for (int i = dims; i < kMaxCoords; ++i) s.base0_[i] = s.base1_[i] = 0;
  s.finish();
  out = s;
  return GeoStatus::Ok;
}

GeoStatus Segment::ellipse(const Vec& a, const Vec& centre, const Vec& b, double majorAngle, double ratio,
                           const Vec& normal, bool ccw, int turns, int dims, Segment& out) {
  if (dims < 2 || dims > kMaxCoords) return GeoStatus::BadDims;
  if (!finiteVec(a, dims) || !finiteVec(b, dims) || !finiteVec(centre, dims) || !finiteVec(normal, 3) ||
      !std::isfinite(majorAngle) || !std::isfinite(ratio))
    return GeoStatus::NonFinite;
  if (!(ratio > 0) || turns < 0) return GeoStatus::BadParameter;
  double N[3] = {normal[0], normal[1], normal[2]};
  if (dims < 3 || !(norm3(N) > 0)) N[0] = N[1] = 0, N[2] = (dims < 3 && normal[2] < 0) ? -1 : 1;
  {
    const double nn = norm3(N);
    for (int i = 0; i < 3; ++i) N[i] /= nn;
  }
  // in-plane reference axis: X projected into the plane (Y if X is the normal)
  double ex[3] = {1, 0, 0};
  if (std::fabs(N[0]) > 0.9) ex[0] = 0, ex[1] = 1;
  const double d = dot3(ex, N);
  for (int i = 0; i < 3; ++i) ex[i] -= d * N[i];
  const double exn = norm3(ex);
  for (int i = 0; i < 3; ++i) ex[i] /= exn;
  double ey[3];
  cross3(N, ex, ey);
  Segment s;
  s.kind_ = SegKind::Ellipse;
  s.dims_ = static_cast<uint8_t>(dims);
  s.cartMetric_ = true;
  auto& E = s.g_.ell;
  const double ck = std::cos(majorAngle), sk = std::sin(majorAngle);
  for (int i = 0; i < 3; ++i) {
    E.e1[i] = ck * ex[i] + sk * ey[i];
    E.e2[i] = -sk * ex[i] + ck * ey[i];
  }
  double A3[3], B3[3], C3[3], ra[3], rb[3];
  cart(a, dims, A3);
  cart(b, dims, B3);
  cart(centre, dims, C3);
  for (int i = 0; i < 3; ++i) {
    ra[i] = A3[i] - C3[i];
    rb[i] = B3[i] - C3[i];
  }
  const double scale = std::max(1.0, norm3(ra));
  if (std::fabs(dot3(ra, N)) > 1e-9 * scale || std::fabs(dot3(rb, N)) > 1e-9 * scale) return GeoStatus::BadPlane;
  for (int i = 0; i < 3; ++i) E.c[i] = C3[i];
  const double xa = dot3(ra, E.e1), ya = dot3(ra, E.e2) / ratio;
  E.A = std::hypot(xa, ya);
  E.B = ratio * E.A;
  if (!(E.A > 0)) return GeoStatus::ZeroLength;
  const double xb = dot3(rb, E.e1), yb = dot3(rb, E.e2) / ratio;
  if (std::fabs(std::hypot(xb, yb) - E.A) > 1e-6 * std::max(1.0, E.A)) return GeoStatus::NotOnCircle;
  E.phi0 = std::atan2(ya, xa);
  const double phib = std::atan2(yb, xb);
  E.dir = ccw ? 1.0 : -1.0;
  double dphi = wrap2Pi(E.dir * (phib - E.phi0));
  if (dphi < 1e-12 || kTwoPi - dphi < 1e-12) dphi = kTwoPi;
  E.dphi = dphi + kTwoPi * turns;
  auto speed = [&](double x) {
    const double sn = std::sin(x), cs = std::cos(x);
    return std::sqrt(E.A * E.A * sn * sn + E.B * E.B * cs * cs);
  };
  if (!buildTable(speed, 0.0, kHalfPi, 4, E.tab)) return GeoStatus::Quadrature;
  E.Q = E.tab.S[E.tab.n - 1];
  E.G0 = 0;
  E.G0 = s.ellipseG(E.phi0);
  const double gEnd = s.ellipseG(E.phi0 + E.dir * E.dphi);
  s.baseLen_ = E.dir * (gEnd - E.G0);
  if (!(s.baseLen_ > 0)) return GeoStatus::ZeroLength;
  E.auxDir = {};
  for (int i = 3; i < dims; ++i) E.auxDir[i] = (b[i] - a[i]) / s.baseLen_;
  s.base0_ = a;
  s.base1_ = b;
  for (int i = dims; i < kMaxCoords; ++i) s.base0_[i] = s.base1_[i] = 0;
  s.finish();
  out = s;
  return GeoStatus::Ok;
}

GeoStatus Segment::poly(const double (&coef)[kMaxCoords][6], int dims, Segment& out) {
  if (dims < 1 || dims > kMaxCoords) return GeoStatus::BadDims;
  for (int i = 0; i < dims; ++i)
    for (int k = 0; k < 6; ++k)
      if (!std::isfinite(coef[i][k])) return GeoStatus::NonFinite;
  Segment s;
  s.kind_ = SegKind::Poly;
  s.dims_ = static_cast<uint8_t>(dims);
  auto& P = s.g_.poly;
  for (int i = 0; i < kMaxCoords; ++i)
    for (int k = 0; k < 6; ++k) P.c[i][k] = i < dims ? coef[i][k] : 0.0;
  // metric: X/Y/Z unless the piece has no Cartesian extent
  double cl = 0, al = 0;
  for (int i = 0; i < dims; ++i) {
    double e = 0;
    for (int k = 1; k < 6; ++k) e += std::fabs(coef[i][k]);
    if (i < 3) cl += e;
    al += e;
  }
  if (!(al > 0)) return GeoStatus::ZeroLength;
  s.cartMetric_ = cl > kCartEps;
  const int m = s.cartMetric_ ? std::min(dims, 3) : dims;
  auto speed = [&](double x) {
    double ss = 0;
    for (int k = 0; k < m; ++k) {
      const double* c = P.c[k];
      const double dd = c[1] + x * (2 * c[2] + x * (3 * c[3] + x * (4 * c[4] + x * 5 * c[5])));
      ss += dd * dd;
    }
    return std::sqrt(ss);
  };
  // a piece whose speed nearly vanishes (a cusp) has no usable arc-length parametrisation
  double smax = 0, smin = 1e300;
  for (int i = 0; i <= 64; ++i) {
    const double v = speed(i / 64.0);
    smax = std::max(smax, v);
    smin = std::min(smin, v);
  }
  if (!(smax > 0)) return GeoStatus::ZeroLength;
  if (smin < 1e-6 * smax) return GeoStatus::Quadrature;
  if (!buildTable(speed, 0.0, 1.0, 4, P.tab)) return GeoStatus::Quadrature;
  s.baseLen_ = P.tab.S[P.tab.n - 1];
  for (int i = 0; i < dims; ++i) {
    s.base0_[i] = coef[i][0];
    double e = 0;
    for (int k = 0; k < 6; ++k) e += coef[i][k];
    s.base1_[i] = e;
  }
  s.finish();
  out = s;
  return GeoStatus::Ok;
}

// ---------------------------------------------------------------- spline

GeoStatus splineThrough(const Vec& start, std::span<const Vec> pts, int dims, const Vec* startTangent,
                        const Vec* endTangent, std::span<Segment> out, SplineScratch& sc) {
  if (dims < 1 || dims > kMaxCoords) return GeoStatus::BadDims;
  const int n = static_cast<int>(pts.size());   // pieces
  if (n < 1) return GeoStatus::BadParameter;
  if (static_cast<int>(out.size()) < n) return GeoStatus::TooManyPoints;
  if (!finiteVec(start, dims)) return GeoStatus::NonFinite;
  for (const Vec& p : pts)
    if (!finiteVec(p, dims)) return GeoStatus::NonFinite;
  if ((startTangent && !finiteVec(*startTangent, dims)) || (endTangent && !finiteVec(*endTangent, dims)))
    return GeoStatus::NonFinite;
  auto P = [&](int i) -> const Vec& { return i == 0 ? start : pts[i - 1]; };
  if (sc.h.size() < static_cast<size_t>(n + 1)) {
    sc.h.resize(n + 1);
    sc.diag.resize(n + 1);
    sc.rhs.resize((n + 1) * kMaxCoords);
    sc.cprime.resize(n + 1);
  }
  for (int i = 0; i < n; ++i) {
    sc.h[i] = cartDist(P(i), P(i + 1), dims);
    if (!(sc.h[i] > kCartEps)) return GeoStatus::ZeroLength;
  }
  // tridiagonal system for the second derivatives M (per coordinate)
  // rows 0..n: a[i] M[i-1] + b[i] M[i] + c[i] M[i+1] = r[i]
  const int N = n + 1;
  auto row = [&](int i, double& a, double& b, double& c) {
    if (i == 0) {
      a = 0;
      if (startTangent) b = 2 * sc.h[0], c = sc.h[0];
      else b = 1, c = 0;
    } else if (i == n) {
      c = 0;
      if (endTangent) a = sc.h[n - 1], b = 2 * sc.h[n - 1];
      else a = 0, b = 1;
    } else {
      a = sc.h[i - 1];
      b = 2 * (sc.h[i - 1] + sc.h[i]);
      c = sc.h[i];
    }
  };
  for (int k = 0; k < dims; ++k) {
    for (int i = 0; i < N; ++i) {
      double r;
      if (i == 0) r = startTangent ? 6 * ((P(1)[k] - P(0)[k]) / sc.h[0] - (*startTangent)[k]) : 0;
      else if (i == n) r = endTangent ? 6 * ((*endTangent)[k] - (P(n)[k] - P(n - 1)[k]) / sc.h[n - 1]) : 0;
      else r = 6 * ((P(i + 1)[k] - P(i)[k]) / sc.h[i] - (P(i)[k] - P(i - 1)[k]) / sc.h[i - 1]);
      sc.rhs[i * kMaxCoords + k] = r;
    }
  }
  // Thomas algorithm (the matrix is diagonally dominant)
  for (int i = 0; i < N; ++i) {
    double a, b, c;
    row(i, a, b, c);
    const double denom = i == 0 ? b : b - a * sc.cprime[i - 1];
    sc.diag[i] = denom;
    sc.cprime[i] = c / denom;
    for (int k = 0; k < dims; ++k) {
      double& r = sc.rhs[i * kMaxCoords + k];
      r = (i == 0 ? r : r - a * sc.rhs[(i - 1) * kMaxCoords + k]) / denom;
    }
  }
  for (int i = N - 2; i >= 0; --i)
    for (int k = 0; k < dims; ++k) sc.rhs[i * kMaxCoords + k] -= sc.cprime[i] * sc.rhs[(i + 1) * kMaxCoords + k];
  for (int i = 0; i < n; ++i) {
    double coef[kMaxCoords][6] = {};
    const double h = sc.h[i];
    for (int k = 0; k < dims; ++k) {
      const double Mi = sc.rhs[i * kMaxCoords + k], Mj = sc.rhs[(i + 1) * kMaxCoords + k];
      const double yi = P(i)[k], yj = P(i + 1)[k];
      coef[k][0] = yi;
      coef[k][1] = yj - yi - h * h * (2 * Mi + Mj) / 6;
      coef[k][2] = Mi * h * h / 2;
      coef[k][3] = (Mj - Mi) * h * h / 6;
    }
    const GeoStatus st = Segment::poly(coef, dims, out[i]);
    if (st != GeoStatus::Ok) return st;
    Vec e0 = P(i), e1 = P(i + 1);
    for (int k = dims; k < kMaxCoords; ++k) e0[k] = e1[k] = 0;
    out[i].setExactEnds(e0, e1);
  }
  return GeoStatus::Ok;
}

// ---------------------------------------------------------------- blend

GeoStatus blendBetween(const Segment& A, double sA, const Segment& B, double sB, Segment& out) {
  if (A.dims() != B.dims()) return GeoStatus::BadDims;
  if (!A.cartesianMetric() || !B.cartesianMetric()) return GeoStatus::BadParameter;
  PathPoint f0, f1;
  A.eval(sA, f0);
  B.eval(sB, f1);
  const int dims = A.dims();
  const double lam = cartDist(f0.pos, f1.pos, dims);
  if (!(lam > kCartEps)) return GeoStatus::ZeroLength;
  double coef[kMaxCoords][6] = {};
  for (int i = 0; i < dims; ++i) {
    const double p0 = f0.pos[i], p1 = f1.pos[i];
    const double d0 = lam * f0.d1[i], d1 = lam * f1.d1[i];
    const double dd0 = lam * lam * f0.d2[i], dd1 = lam * lam * f1.d2[i];
    const double D = p1 - p0;
    coef[i][0] = p0;
    coef[i][1] = d0;
    coef[i][2] = 0.5 * dd0;
    coef[i][3] = 10 * D - 6 * d0 - 4 * d1 - 1.5 * dd0 + 0.5 * dd1;
    coef[i][4] = -15 * D + 8 * d0 + 7 * d1 + 1.5 * dd0 - dd1;
    coef[i][5] = 6 * D - 3 * d0 - 3 * d1 - 0.5 * dd0 + 0.5 * dd1;
  }
  Segment s;
  const GeoStatus st = Segment::poly(coef, dims, s);
  if (st != GeoStatus::Ok) return st;
  s.setExactEnds(f0.pos, f1.pos);
  out = s;
  return GeoStatus::Ok;
}

double cornerAngle(const Segment& A, const Segment& B) {
  PathPoint a, b;
  A.eval(A.length(), a);
  B.eval(0, b);
  const int m = (A.cartesianMetric() && B.cartesianMetric()) ? std::min(A.dims(), 3) : A.dims();
  double d = 0, na = 0, nb = 0;
  for (int i = 0; i < m; ++i) {
    d += a.d1[i] * b.d1[i];
    na += a.d1[i] * a.d1[i];
    nb += b.d1[i] * b.d1[i];
  }
  if (!(na > 0) || !(nb > 0)) return kPi;
  const double c = std::clamp(d / std::sqrt(na * nb), -1.0, 1.0);
  // acos loses precision near 0: use the cross-product magnitude there
  double x2 = 0;
  for (int i = 0; i < m; ++i)
    for (int j = i + 1; j < m; ++j) {
      const double x = a.d1[i] * b.d1[j] - a.d1[j] * b.d1[i];
      x2 += x * x;
    }
  return std::atan2(std::sqrt(x2 / (na * nb)), c);
}

}  // namespace stc::motion::path
