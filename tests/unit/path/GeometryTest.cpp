// Path geometry (stdlib-motion/path/Geometry.h): closed forms, arc-length
// parametrisation, degenerate input, G2 blends.
#include "stdlib-motion/path/Geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

using namespace stc::motion::path;

namespace {

constexpr double kPi = std::numbers::pi;

Vec V(double x, double y, double z = 0) {
  Vec v{};
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}
double dist3(const Vec& a, const Vec& b) { return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])); }

// The sum of chords over a fine sampling equals the length (arc-length parametrisation),
// and consecutive samples are exactly `h` apart (within the chord error of the curvature).
void checkArcLength(const Segment& s, double tol) {
  const int N = 4000;
  const double h = s.length() / N;
  double kmax = s.maxCurvature();
  for (int i = 0; i < N; ++i) {
    const double c = dist3(s.position(i * h), s.position((i + 1) * h));
    // chord of an arc of length h with curvature <= k: h - c <= k^2 h^3 / 24
    EXPECT_NEAR(c, h, kmax * kmax * h * h * h / 24 + tol * s.length()) << "at " << i;
  }
}

TEST(PathGeometry, LineHasExactEndsAndLength) {
  Segment s;
  ASSERT_EQ(Segment::line(V(0.1, 0.2), V(30.3, 40.7), 2, s), GeoStatus::Ok);
  EXPECT_DOUBLE_EQ(s.length(), std::hypot(30.2, 40.5));
  EXPECT_EQ(s.position(s.length()), V(30.3, 40.7));
  EXPECT_EQ(s.position(0), V(0.1, 0.2));
  PathPoint p;
  s.eval(1.0, p);
  EXPECT_NEAR(std::hypot(p.d1[0], p.d1[1]), 1.0, 1e-15);
  EXPECT_EQ(p.curvature, 0);
}

TEST(PathGeometry, AuxiliaryCoordinatesFollowThePathLength) {
  Vec a = V(0, 0), b = V(3, 4);
  a[3] = 10;
  b[3] = 20;   // A axis
  Segment s;
  ASSERT_EQ(Segment::line(a, b, 4, s), GeoStatus::Ok);
  EXPECT_DOUBLE_EQ(s.length(), 5.0);   // X/Y/Z carry the length
  EXPECT_NEAR(s.position(2.5)[3], 15.0, 1e-12);
  // an orientation-only move: the length is over all coordinates
  Vec c = a;
  c[3] = 13;
  ASSERT_EQ(Segment::line(a, c, 4, s), GeoStatus::Ok);
  EXPECT_FALSE(s.cartesianMetric());
  EXPECT_DOUBLE_EQ(s.length(), 3.0);
}

TEST(PathGeometry, BorderArcThroughThreePoints) {
  Segment s;
  const double r = 10;
  ASSERT_EQ(Segment::arcBorder(V(r, 0), V(r * std::cos(0.3), r * std::sin(0.3)), V(0, r), V(0, 0, 1), 2, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), r * kPi / 2, 1e-12);
  EXPECT_NEAR(s.radius(), r, 1e-12);
  for (int i = 0; i <= 100; ++i) {
    const Vec p = s.position(s.length() * i / 100);
    EXPECT_NEAR(std::hypot(p[0], p[1]), r, 1e-12);
  }
  EXPECT_EQ(s.position(s.length()), V(0, r));
  // the same arc the long way round: via a border point on the other side
  ASSERT_EQ(Segment::arcBorder(V(r, 0), V(-r, 0), V(0, r), V(0, 0, 1), 2, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), r * 1.5 * kPi, 1e-12);
  // 3-D: a quarter circle in a tilted plane
  ASSERT_EQ(Segment::arcBorder(V(1, 0, 0), V(std::sqrt(0.5), 0.5, 0.5), V(0, std::sqrt(0.5), std::sqrt(0.5)), V(0, 0, 0), 3, s),
            GeoStatus::Ok);
  EXPECT_NEAR(s.length(), kPi / 2, 1e-12);
  checkArcLength(s, 1e-12);
}

TEST(PathGeometry, CentreArcDirectionsAndFullCircle) {
  Segment s;
  // quarter circle ccw, 3/4 circle cw
  ASSERT_EQ(Segment::arcCenter(V(10, 0), V(0, 0), V(0, 10), V(0, 0, 1), true, 0, 2, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), 5 * kPi, 1e-12);
  ASSERT_EQ(Segment::arcCenter(V(10, 0), V(0, 0), V(0, 10), V(0, 0, 1), false, 0, 2, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), 15 * kPi, 1e-12);
  EXPECT_LT(s.position(1.0)[1], 0);   // clockwise: y goes negative first
  // full circle (end == start), plus two extra turns
  ASSERT_EQ(Segment::arcCenter(V(10, 0), V(0, 0), V(10, 0), V(0, 0, 1), true, 0, 2, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), 20 * kPi, 1e-12);
  ASSERT_EQ(Segment::arcCenter(V(10, 0), V(0, 0), V(10, 0), V(0, 0, 1), true, 2, 2, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), 60 * kPi, 1e-11);
  EXPECT_EQ(s.position(s.length()), V(10, 0));
  // auto plane: ccw = the short arc, cw = the long arc
  ASSERT_EQ(Segment::arcCenter(V(1, 0, 0), V(0, 0, 0), V(0, 0, 1), V(0, 0, 0), true, 0, 3, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), kPi / 2, 1e-12);
  ASSERT_EQ(Segment::arcCenter(V(1, 0, 0), V(0, 0, 0), V(0, 0, 1), V(0, 0, 0), false, 0, 3, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), 1.5 * kPi, 1e-12);
}

TEST(PathGeometry, RadiusArcShortAndLong) {
  Segment s;
  const double r = 5;   // chord 10/sqrt2 ... quarter circle of radius 5 from (5,0) to (0,5)
  ASSERT_EQ(Segment::arcRadius(V(5, 0), V(0, 5), r, V(0, 0, 1), true, false, 0, 2, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), r * kPi / 2, 1e-12);
  EXPECT_NEAR(std::hypot(s.position(1)[0], s.position(1)[1]), r, 1e-12);   // centre at the origin
  ASSERT_EQ(Segment::arcRadius(V(5, 0), V(0, 5), r, V(0, 0, 1), true, true, 0, 2, s), GeoStatus::Ok);
  EXPECT_NEAR(s.length(), r * 1.5 * kPi, 1e-12);
  EXPECT_EQ(Segment::arcRadius(V(0, 0), V(10, 0), 4.9, V(0, 0, 1), true, false, 0, 2, s), GeoStatus::RadiusTooSmall);
  ASSERT_EQ(Segment::arcRadius(V(0, 0), V(10, 0), 5, V(0, 0, 1), true, false, 0, 2, s), GeoStatus::Ok);   // half circle
  EXPECT_NEAR(s.length(), 5 * kPi, 1e-9);
}

TEST(PathGeometry, HelixLengthAndRise) {
  Segment s;
  // two turns of radius 3 rising 8 along Z (centre mode, end above the start)
  ASSERT_EQ(Segment::arcCenter(V(3, 0, 0), V(0, 0, 0), V(3, 0, 8), V(0, 0, 1), true, 1, 3, s), GeoStatus::Ok);
  const double sweep = 4 * kPi;
  EXPECT_NEAR(s.length(), std::hypot(3 * sweep, 8), 1e-12);
  for (int i = 0; i <= 200; ++i) {
    const double t = i / 200.0;
    const Vec p = s.position(s.length() * t);
    EXPECT_NEAR(std::hypot(p[0], p[1]), 3, 1e-12);
    EXPECT_NEAR(p[2], 8 * t, 1e-12);
  }
  PathPoint pp;
  s.eval(1, pp);
  const double c = 8 / sweep;
  EXPECT_NEAR(pp.curvature, 3 / (9 + c * c), 1e-12);
  checkArcLength(s, 1e-12);
}

TEST(PathGeometry, EllipseOnCurveAndArcLength) {
  Segment s;
  // major axis 10 along X, ratio 0.5; from (10,0) ccw full turn
  ASSERT_EQ(Segment::ellipse(V(10, 0), V(0, 0), V(10, 0), 0, 0.5, V(0, 0, 1), true, 0, 2, s), GeoStatus::Ok);
  // circumference of a=10, b=5: 48.44224110273838 (complete elliptic integral, reference value)
  EXPECT_NEAR(s.length(), 48.44224110273838, 1e-9);
  for (int i = 0; i <= 500; ++i) {
    const Vec p = s.position(s.length() * i / 500);
    EXPECT_NEAR(p[0] * p[0] / 100 + p[1] * p[1] / 25, 1.0, 1e-12);
  }
  checkArcLength(s, 1e-12);
  // rotated by 30 degrees, a quarter, clockwise; the end must lie on it
  const double k = kPi / 6;
  const Vec a = V(10 * std::cos(k), 10 * std::sin(k));
  const Vec b = V(-2 * std::sin(k) * 1.0 * 1, 2 * std::cos(k));   // minor vertex of ratio 0.2
  ASSERT_EQ(Segment::ellipse(a, V(0, 0), b, k, 0.2, V(0, 0, 1), false, 0, 2, s), GeoStatus::Ok);
  checkArcLength(s, 1e-12);
  EXPECT_EQ(Segment::ellipse(a, V(0, 0), V(3, 3), k, 0.2, V(0, 0, 1), false, 0, 2, s), GeoStatus::NotOnCircle);
  EXPECT_EQ(Segment::ellipse(a, V(0, 0), b, k, 0.0, V(0, 0, 1), false, 0, 2, s), GeoStatus::BadParameter);
}

TEST(PathGeometry, SplineIsC2ThroughItsPoints) {
  std::vector<Vec> pts = {V(1, 1, 0), V(2, 0, 1), V(4, 2, 1), V(5, -1, 0)};
  std::vector<Segment> out(pts.size());
  SplineScratch sc;
  ASSERT_EQ(splineThrough(V(0, 0, 0), pts, 3, nullptr, nullptr, out, sc), GeoStatus::Ok);
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(out[i].endPoint(), pts[i]);
    checkArcLength(out[i], 1e-12);
    if (i + 1 < pts.size()) {
      PathPoint a, b;
      out[i].eval(out[i].length(), a);
      out[i + 1].eval(0, b);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(a.d1[k], b.d1[k], 1e-12);
        EXPECT_NEAR(a.d2[k], b.d2[k], 1e-9);
      }
    }
  }
  // clamped start tangent
  const Vec t = V(1, 0, 0);
  ASSERT_EQ(splineThrough(V(0, 0, 0), pts, 3, &t, nullptr, out, sc), GeoStatus::Ok);
  PathPoint p;
  out[0].eval(0, p);
  EXPECT_NEAR(p.d1[0], 1, 1e-12);
}

TEST(PathGeometry, DegenerateInputGivesAStatusNeverNaN) {
  Segment s;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Segment::line(V(1, 2), V(1, 2), 2, s), GeoStatus::ZeroLength);
  EXPECT_EQ(Segment::line(V(1, nan), V(1, 2), 2, s), GeoStatus::NonFinite);
  EXPECT_EQ(Segment::line(V(1, 0), V(inf, 2), 2, s), GeoStatus::NonFinite);
  EXPECT_EQ(Segment::arcBorder(V(0, 0), V(1, 1), V(2, 2), V(0, 0, 1), 2, s), GeoStatus::Collinear);
  EXPECT_EQ(Segment::arcCenter(V(10, 0), V(0, 0), V(0, 11), V(0, 0, 1), true, 0, 2, s), GeoStatus::NotOnCircle);
  EXPECT_EQ(Segment::arcCenter(V(0, 0), V(0, 0), V(0, 0), V(0, 0, 1), true, 0, 2, s), GeoStatus::ZeroLength);
  EXPECT_EQ(Segment::arcRadius(V(0, 0), V(1, 0), nan, V(0, 0, 1), true, false, 0, 2, s), GeoStatus::NonFinite);
  EXPECT_EQ(Segment::arcRadius(V(0, 0), V(0, 0), 1, V(0, 0, 1), true, false, 0, 2, s), GeoStatus::ZeroLength);
  EXPECT_EQ(Segment::line(V(0, 0), V(1, 0), kMaxCoords + 1, s), GeoStatus::BadDims);
  std::vector<Vec> pts = {V(1, 1), V(1, 1)};
  std::vector<Segment> out(2);
  SplineScratch sc;
  EXPECT_EQ(splineThrough(V(0, 0), pts, 2, nullptr, nullptr, out, sc), GeoStatus::ZeroLength);
}

TEST(PathGeometry, BlendIsG2AndInsideItsCornerBall) {
  for (double deg : {5.0, 30.0, 90.0, 135.0, 170.0}) {
    const double a = deg * kPi / 180;
    Segment A, B, bl;
    ASSERT_EQ(Segment::line(V(-10, 0), V(0, 0), 2, A), GeoStatus::Ok);
    ASSERT_EQ(Segment::line(V(0, 0), V(10 * std::cos(a), 10 * std::sin(a)), 2, B), GeoStatus::Ok);
    const double d = 2;
    ASSERT_EQ(blendBetween(A, A.length() - d, B, d, bl), GeoStatus::Ok);
    PathPoint p0, p1, q0, q1;
    A.eval(A.length() - d, p0);
    B.eval(d, p1);
    bl.eval(0, q0);
    bl.eval(bl.length(), q1);
    EXPECT_EQ(q0.pos, p0.pos);
    EXPECT_EQ(q1.pos, p1.pos);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(q0.d1[k], p0.d1[k], 1e-12);
      EXPECT_NEAR(q1.d1[k], p1.d1[k], 1e-12);
    }
    EXPECT_NEAR(q0.curvature, 0, 1e-9);
    EXPECT_NEAR(q1.curvature, 0, 1e-9);
    for (int i = 0; i <= 1000; ++i) EXPECT_LE(dist3(bl.position(bl.length() * i / 1000), V(0, 0)), d * (1 + 1e-12));
    checkArcLength(bl, 1e-12);
  }
}

}  // namespace
