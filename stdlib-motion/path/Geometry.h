// Path geometry of axis-group moves: segments in an N-dimensional coordinate
// space (N <= 11: X, Y, Z, A, B, C and up to five auxiliary axes; axis groups
// use up to 9, the CNC interpolator 11: X Y Z A B C P Q U V W), each
// parametrised by its path length s (docs/path.md, "Geometry").
//
//  - The Cartesian part X/Y/Z carries the geometry and defines the path length
//    (the "metric"); the other coordinates follow proportionally to s (lines,
//    arcs, helices, ellipses), along the same cubic (splines) or along the same
//    quintic (blends).  A move without Cartesian extent (only A..C/aux change)
//    uses all its coordinates as the metric.
//  - Lines, arcs and helices are parametrised exactly by arc length.  Ellipses
//    and polynomial pieces (spline pieces, blends) use an arc-length table built
//    with adaptive 8-point Gauss-Legendre quadrature and a Newton inversion; the
//    position at s is exact to <= 1e-9 of the segment's length (typically 1e-13).
//  - Every segment gives the position, dp/ds (a unit vector in the metric
//    coordinates) and d2p/ds2 (its length over the metric coordinates is the
//    curvature) at any s in [0, length()]; s is clamped to that range.  At
//    s = length() the position is the exact end point the segment was built with.
//  - Degenerate or non-finite input gives a GeoStatus, never a NaN.
//
// A Segment is a value of fixed size (no allocation); it may be restricted to a
// window [a, b] of its path length (trim), which is how blends shorten the
// segments they join.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace stc::motion::path {

constexpr int kMaxCoords = 11;   // X, Y, Z, A, B, C, aux1..aux5
using Vec = std::array<double, kMaxCoords>;

enum class GeoStatus : uint8_t {
  Ok,
  NonFinite,        // a coordinate, radius, angle or ratio is NaN or infinite
  BadDims,          // dims outside 1..11, or a circle/ellipse with fewer than 2 Cartesian coordinates
  ZeroLength,       // start and end coincide (a line), a zero radius, two equal spline points
  Collinear,        // border (three-point) arc through collinear points
  RadiusTooSmall,   // radius smaller than half the chord
  NotOnCircle,      // centre mode: end not at the start's distance from the centre (relative 1e-6);
                    // ellipse: end not on the ellipse through the start
  BadPlane,         // zero plane normal where one is needed, or the normal lies in the chord's line
  BadParameter,     // ellipse ratio <= 0, negative turns, spline without points ...
  Quadrature,       // the arc-length table did not reach its tolerance (a cusp or an extreme ellipse)
  TooManyPoints,    // more spline points than the caller's buffer
};
const char* toString(GeoStatus s);

// The geometry at one path length.
struct PathPoint {
  Vec pos{};        // all coordinates
  Vec d1{};         // dp/ds
  Vec d2{};         // d2p/ds2
  double curvature = 0;   // |d2p/ds2| over the metric coordinates
};

enum class SegKind : uint8_t { Line, Arc, Ellipse, Poly };

// Arc-length table of a curve parametrised by u: knots u[i] with the path
// length S[i] from u[0].  At most kKnots knots.
struct ArcTable {
  static constexpr int kKnots = 40;
  int n = 0;
  double u[kKnots] = {};
  double S[kKnots] = {};
};

class Segment {
public:
  SegKind kind() const { return kind_; }
  int dims() const { return dims_; }
  double length() const { return len_; }
  // TRUE if X/Y/Z define the path length (else all coordinates do).
  bool cartesianMetric() const { return cartMetric_; }
  // Exact end points of the (windowed) segment.
  const Vec& startPoint() const { return p0_; }
  const Vec& endPoint() const { return p1_; }

  void eval(double s, PathPoint& out) const;
  Vec position(double s) const;
  // Upper bound of the curvature over the segment (exact for lines, arcs, helices;
  // sampled densely and refined for ellipses and polynomial pieces).
  double maxCurvature() const { return kappaMax_; }
  // Radius / rise / sweep of an arc or helix (0 for other kinds).
  double radius() const { return kind_ == SegKind::Arc ? g_.arc.r : 0.0; }
  double sweep() const { return kind_ == SegKind::Arc ? g_.arc.sweep : 0.0; }

  // Restricts the segment to its part [a, b] (0 <= a < b <= length()).
  GeoStatus trim(double a, double b);

  // ---------------------------------------------------------------- builders
  // A straight line.
  static GeoStatus line(const Vec& a, const Vec& b, int dims, Segment& out);
  // Arc from a through the border point m to b (the plane of the three points).
  // b == a: a full circle with m diametrically opposite a, in the plane with
  // normal `normal` (then required).
  static GeoStatus arcBorder(const Vec& a, const Vec& m, const Vec& b, const Vec& normal, int dims, Segment& out);
  // Arc about `centre` from a to b, counter-clockwise about the plane normal
  // `normal` when ccw (right-hand rule), clockwise otherwise, plus `turns` extra
  // full turns; b == a (in the plane) is a full circle.  The centre is projected
  // into the plane through a; b's offset along the normal makes a helix (the
  // rise is linear in the angle).  normal == 0: the plane of a, centre, b, and
  // ccw selects the short arc, !ccw the long one.
  static GeoStatus arcCenter(const Vec& a, const Vec& centre, const Vec& b, const Vec& normal, bool ccw, int turns,
                             int dims, Segment& out);
  // Arc of radius r from a to b about the plane normal (required); longArc picks
  // the arc of more than half a turn.  b's offset along the normal makes a helix.
  static GeoStatus arcRadius(const Vec& a, const Vec& b, double r, const Vec& normal, bool ccw, bool longArc,
                             int turns, int dims, Segment& out);
  // Ellipse in the plane through `centre` with normal `normal` (0: Z): the major
  // axis at angle `majorAngle` (rad) from the plane's reference axis (the X axis
  // projected into the plane; for the XY plane: from +X towards +Y), minor/major
  // ratio `ratio` > 0; the size follows from the start a; b must lie on the same
  // ellipse; ccw about the normal, plus `turns` full turns (b == a: a full turn).
  static GeoStatus ellipse(const Vec& a, const Vec& centre, const Vec& b, double majorAngle, double ratio,
                           const Vec& normal, bool ccw, int turns, int dims, Segment& out);
  // A polynomial piece p(u) = sum c[k] u^k, u in [0, 1], degree <= 5, for every
  // coordinate (coef[i][k]); the metric is X/Y/Z.
  static GeoStatus poly(const double (&coef)[kMaxCoords][6], int dims, Segment& out);

private:
  struct LineData { Vec dir; };                 // (p1 - p0) / baseLen over every coordinate
  struct ArcData {
    double c[3], u[3], v[3], n[3];              // centre, start direction, in-plane normal, plane normal
    double r, sweep, rise, m;                   // radius, angle (rad, > 0), rise along n, baseLen / sweep
    Vec auxDir;                                 // aux coordinates: (end - start) / baseLen
  };
  struct EllipseData {
    double c[3], e1[3], e2[3];
    double A, B, phi0, dir, dphi, Q, G0;        // semi-axes, start angle, +-1, total angle, quarter length, G(phi0)
    Vec auxDir;
    ArcTable tab;                               // arc length over phi in [0, pi/2]
  };
  struct PolyData {
    double c[kMaxCoords][6];
    ArcTable tab;                               // arc length over u in [0, 1]
  };
  union Geo {
    LineData line;
    ArcData arc;
    EllipseData ell;
    PolyData poly;
    Geo() : line{} {}
  };

  friend GeoStatus splineThrough(const Vec&, std::span<const Vec>, int, const Vec*, const Vec*, std::span<Segment>,
                                 struct SplineScratch&);
  friend GeoStatus blendBetween(const Segment&, double, const Segment&, double, Segment&);
  void setExactEnds(const Vec& a, const Vec& b) { base0_ = p0_ = a; base1_ = p1_ = b; }
  static GeoStatus arcAssemble(const Vec& a, const Vec& b, const double* c, const double* u, const double* n,
                               double r, double sweep, double rise, int dims, Segment& out);
  void evalBase(double sigma, PathPoint& out) const;   // sigma: path length in the untrimmed segment
  double ellipseG(double phi) const;
  double ellipseInvG(double g) const;
  double polyS(double u) const;
  double polyInvS(double s) const;
  double polyCurvature(double u) const;   // the curvature at parameter u (as evalBase gives it)
  void finish();                                       // window = whole, end points, kappaMax

  SegKind kind_ = SegKind::Line;
  uint8_t dims_ = 0;
  bool cartMetric_ = true;
  double baseLen_ = 0;   // length of the untrimmed segment
  double s0_ = 0;        // window start in the untrimmed segment
  double len_ = 0;       // window length
  double kappaMax_ = 0;
  Vec p0_{}, p1_{};      // window end points (exact)
  Vec base0_{}, base1_{};   // untrimmed end points (exact)
  Geo g_;
};

// Cubic spline (C2) through the points pts[0..n-1] starting at `start`, with
// chord-length knots over X/Y/Z.  Natural ends, or clamped to the unit tangents
// startTangent / endTangent when given (not null; e.g. the tangent of the
// preceding segment for a smooth entry).  Writes n polynomial pieces to out
// (which must hold n); `scratch` is working memory the caller keeps (resized on
// first use to the number of points; keep it sized to avoid allocation).
struct SplineScratch {
  std::vector<double> h, diag, rhs, cprime;
};
GeoStatus splineThrough(const Vec& start, std::span<const Vec> pts, int dims, const Vec* startTangent,
                        const Vec* endTangent, std::span<Segment> out, SplineScratch& scratch);

// A curvature-continuous corner transition (quintic in X/Y/Z and every other
// coordinate) from the frame of A at sA to the frame of B at sB: position,
// tangent and curvature vector match at both ends (G2); the parametric
// derivative magnitude is the chord.  Requires both segments with a Cartesian
// metric.
GeoStatus blendBetween(const Segment& A, double sA, const Segment& B, double sB, Segment& out);

// Unit-tangent angle (rad) between the end of A and the start of B.
double cornerAngle(const Segment& A, const Segment& B);

}  // namespace stc::motion::path
