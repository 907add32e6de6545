// The cam library (core/Cam.h): XYVA pieces against closed forms, tables,
// lookups over random positions, motion-law peak coefficients (VDI 2143),
// tappets with hysteresis and the .CAM text format.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "stdlib-motion/core/Cam.h"

using namespace stc::motion;

namespace {

// A random quintic and its XYVA points: the cam must be the quintic itself.
struct Poly5 {
  double c[6];
  double y(double x) const { return c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * (c[4] + x * c[5])))); }
  double dy(double x) const { return c[1] + x * (2 * c[2] + x * (3 * c[3] + x * (4 * c[4] + x * 5 * c[5]))); }
  double ddy(double x) const { return 2 * c[2] + x * (6 * c[3] + x * (12 * c[4] + x * 20 * c[5])); }
};

}  // namespace

TEST(Cam, XyvaPiecesReproduceAQuinticExactly) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int trial = 0; trial < 1000; ++trial) {
    Poly5 p;
    for (double& c : p.c) c = d(rng);
    std::vector<CamXYVA> pts;
    const int n = 2 + trial % 7;
    for (int i = 0; i < n; ++i) {
      const double x = 2.0 * i / (n - 1);
      pts.push_back(CamXYVA{x, p.y(x), p.dy(x), p.ddy(x)});
    }
    Cam cam;
    std::string err;
    ASSERT_TRUE(Cam::xyva(pts, {}, cam, err)) << err;
    for (int k = 0; k <= 200; ++k) {
      const double x = 2.0 * k / 200;
      const CamSample s = cam.at(x);
      ASSERT_NEAR(s.y, p.y(x), 1e-12);
      ASSERT_NEAR(s.dy, p.dy(x), 1e-10);
      ASSERT_NEAR(s.ddy, p.ddy(x), 1e-8);
    }
  }
}

TEST(Cam, TablesInterpolateLinearly) {
  Cam t1, t2;
  std::string err;
  ASSERT_TRUE(Cam::table1D(0, 10, {0, 5, 20}, {}, t1, err)) << err;
  EXPECT_DOUBLE_EQ(t1.at(2.5).y, 2.5);
  EXPECT_DOUBLE_EQ(t1.at(7.5).y, 12.5);
  EXPECT_DOUBLE_EQ(t1.at(7.5).dy, 3.0);
  EXPECT_DOUBLE_EQ(t1.at(11).y, 20);   // clamped
  EXPECT_DOUBLE_EQ(t1.lift(), 20);
  ASSERT_TRUE(Cam::table2D({{0, 0}, {1, 10}, {4, 10}, {5, 0}}, {}, t2, err)) << err;
  EXPECT_DOUBLE_EQ(t2.at(0.5).y, 5);
  EXPECT_DOUBLE_EQ(t2.at(2).y, 10);
  EXPECT_DOUBLE_EQ(t2.at(4.5).y, 5);
  EXPECT_DOUBLE_EQ(t2.at(4.5).dy, -10);
  EXPECT_DOUBLE_EQ(t2.extremes().yMax, 10);
  EXPECT_DOUBLE_EQ(t2.extremes().dyMin, -10);
}

TEST(Cam, RefusesInvalidTables) {
  Cam c;
  std::string err;
  EXPECT_FALSE(Cam::xyva({{0, 0, 0, 0}}, {}, c, err));
  EXPECT_FALSE(Cam::xyva({{0, 0, 0, 0}, {0, 1, 0, 0}}, {}, c, err));           // x not increasing
  EXPECT_FALSE(Cam::xyva({{0, 0, 0, 0}, {1, NAN, 0, 0}}, {}, c, err));
  EXPECT_FALSE(Cam::xyva({{0, 0, 0, 0}, {1, 1e300, 0, 0}}, {}, c, err));       // absurd
  EXPECT_FALSE(Cam::table1D(5, 5, {0, 1}, {}, c, err));
  EXPECT_FALSE(Cam::table2D({{0, 0}, {2, 1}, {1, 2}}, {}, c, err));
  Tappet bad{0.5, 513, TappetAction::On, TappetAction::Off};
  EXPECT_FALSE(Cam::table1D(0, 1, {0, 1}, {bad}, c, err));
  bad.group = 1;
  bad.x = 2;   // outside the master range
  EXPECT_FALSE(Cam::table1D(0, 1, {0, 1}, {bad}, c, err));
}

// The segment search agrees with a linear scan for every size (O(log n) lookups).
TEST(Cam, LookupFindsTheSegmentForRandomPositions) {
  std::mt19937_64 rng(11);
  for (int n : {2, 3, 17, 1000}) {
    std::vector<std::array<double, 2>> pts;
    double x = 0;
    std::uniform_real_distribution<double> step(0.01, 3);
    for (int i = 0; i < n; ++i, x += step(rng)) pts.push_back({x, std::sin(x)});
    Cam cam;
    std::string err;
    ASSERT_TRUE(Cam::table2D(pts, {}, cam, err));
    std::uniform_real_distribution<double> at(pts.front()[0], pts.back()[0]);
    for (int k = 0; k < 2000; ++k) {
      const double q = at(rng);
      size_t i = 0;
      while (i + 2 < pts.size() && pts[i + 1][0] <= q) ++i;
      const double expect = pts[i][1] + (pts[i + 1][1] - pts[i][1]) * (q - pts[i][0]) / (pts[i + 1][0] - pts[i][0]);
      ASSERT_NEAR(cam.at(q).y, expect, 1e-12);
    }
  }
}

// VDI 2143 laws: boundary values and the normalised peak coefficients.
TEST(Cam, MotionLawPeakCoefficients) {
  struct Case {
    MotionLaw law;
    double cv, ca;
  } cases[] = {{MotionLaw::Cycloid, 2.0, 2 * std::numbers::pi},
               {MotionLaw::ModifiedSine, 1.760, 5.528},
               {MotionLaw::Poly345, 1.875, 5.774},
               {MotionLaw::Harmonic, std::numbers::pi / 2, std::numbers::pi * std::numbers::pi / 2},
               {MotionLaw::ModifiedTrapezoid, 2.0, 4.888}};
  for (const Case& c : cases) {
    double cv = 0, ca = 0;
    for (int k = 0; k <= 100000; ++k) {
      const CamSample s = motionLaw(c.law, k / 100000.0);
      cv = std::max(cv, std::fabs(s.dy));
      ca = std::max(ca, std::fabs(s.ddy));
    }
    EXPECT_NEAR(cv, c.cv, 1e-3) << static_cast<int>(c.law);
    EXPECT_NEAR(ca, c.ca, 1e-3) << static_cast<int>(c.law);
    EXPECT_NEAR(motionLaw(c.law, 0).y, 0, 1e-12);
    EXPECT_NEAR(motionLaw(c.law, 1).y, 1, 1e-12);
    EXPECT_NEAR(motionLaw(c.law, 0).dy, 0, 1e-12);
    EXPECT_NEAR(motionLaw(c.law, 1).dy, 0, 1e-12);
    // Velocity is the integral of acceleration, position of velocity (central differences).
    for (double u : {0.1, 0.3, 0.5, 0.77, 0.9}) {
      const double h = 1e-6;
      EXPECT_NEAR((motionLaw(c.law, u + h).y - motionLaw(c.law, u - h).y) / (2 * h), motionLaw(c.law, u).dy, 1e-6);
      EXPECT_NEAR((motionLaw(c.law, u + h).dy - motionLaw(c.law, u - h).dy) / (2 * h), motionLaw(c.law, u).ddy, 1e-5);
    }
  }
}

// A cam generated from a law follows the law (1e-9 of the rise) and joins a synchronous zone smoothly.
TEST(Cam, MotionLawCamsFollowTheLaw) {
  std::vector<CamXYVA> pts;
  appendMotionLaw(MotionLaw::Linear, 0, 90, 0, 90, pts);
  appendMotionLaw(MotionLaw::ModifiedSine, 90, 360, 90, 300, pts, 1.0);
  Cam cam;
  std::string err;
  ASSERT_TRUE(Cam::xyva(pts, {}, cam, err)) << err;
  EXPECT_DOUBLE_EQ(cam.lift(), 300);
  for (int k = 0; k <= 3600; ++k) {
    const double x = k * 0.1;
    if (x <= 90) {
      ASSERT_NEAR(cam.at(x).y, x, 1e-12);
      ASSERT_NEAR(cam.at(x).dy, 1, 1e-12);
      continue;
    }
    const double u = (x - 90) / 270, R = 210 - 270;
    const CamSample s = motionLaw(MotionLaw::ModifiedSine, u);
    ASSERT_NEAR(cam.at(x).y, 90 + (x - 90) + R * s.y, 1e-9 * 300);
    ASSERT_NEAR(cam.at(x).dy, 1 + R / 270 * s.dy, 1e-7);
  }
}

TEST(Cam, TappetsFireOncePerPassWithHysteresis) {
  Cam cam;
  std::string err;
  std::vector<Tappet> ts{{10, 1, TappetAction::On, TappetAction::Off}, {20, 1, TappetAction::Off, TappetAction::On},
                         {15, 2, TappetAction::Invert, TappetAction::None}};
  ASSERT_TRUE(Cam::table1D(0, 100, {0, 100}, ts, cam, err)) << err;
  TappetTracker t;
  t.reset(cam.tappets(), 0, 1.0);
  auto g1 = [&] { return TappetTracker::value(t.groups()[1], false); };
  auto g2 = [&] { return TappetTracker::value(t.groups()[2], false); };
  EXPECT_FALSE(t.move(9.99));
  EXPECT_TRUE(t.move(10.0));   // passing x = 10 forwards (position exactly on x counts)
  EXPECT_TRUE(g1());
  // Jitter within the hysteresis: nothing fires.
  for (double x : {9.5, 10.4, 9.2, 10.9, 9.1})
    EXPECT_FALSE(t.move(x)) << x;
  EXPECT_TRUE(g1());
  // Beyond the hysteresis on the far side, the backward pass fires ON→OFF.
  EXPECT_FALSE(t.move(11.2));
  EXPECT_TRUE(t.move(9.5));
  EXPECT_FALSE(g1());
  EXPECT_FALSE(t.move(9.5 + 0.4));   // back within the hysteresis: the forward pass is not re-armed
  EXPECT_FALSE(t.move(10.8));
  EXPECT_FALSE(g1());
  EXPECT_FALSE(t.move(8.5));    // now beyond it
  EXPECT_TRUE(t.move(16));      // 10 (ON) then 15 (INVERT) in one step, in that order
  EXPECT_TRUE(g1());
  EXPECT_TRUE(g2());
  EXPECT_TRUE(t.move(25));      // 20: OFF
  EXPECT_FALSE(g1());
  t.wrap(0);                    // next period: the tappets fire again
  EXPECT_TRUE(t.move(16));
  EXPECT_TRUE(g1());
  EXPECT_FALSE(g2());           // inverted twice
}

TEST(Cam, TextFormatRoundTrips) {
  std::vector<CamXYVA> pts;
  appendMotionLaw(MotionLaw::Cycloid, 0, 360, 0, 100, pts);
  Cam cam, back;
  std::string err, name, detail;
  ASSERT_TRUE(Cam::xyva(pts, {{12.5, 3, TappetAction::On, TappetAction::Invert}}, cam, err));
  const std::string text = writeCamText(cam, "lift");
  ASSERT_EQ(readCamText(text, back, name, detail), CamFileError::None) << detail;
  EXPECT_EQ(name, "lift");
  ASSERT_EQ(back.points().size(), cam.points().size());
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(back.points()[i].x, cam.points()[i].x);   // shortest round-trip form: bit-exact
    EXPECT_EQ(back.points()[i].y, cam.points()[i].y);
    EXPECT_EQ(back.points()[i].v, cam.points()[i].v);
    EXPECT_EQ(back.points()[i].a, cam.points()[i].a);
  }
  ASSERT_EQ(back.tappets().size(), 1u);
  EXPECT_EQ(back.tappets()[0].group, 3);
  EXPECT_EQ(back.tappets()[0].negative, TappetAction::Invert);
  // Damaged files: each with its own error.
  EXPECT_EQ(readCamText("hello\n", back, name, detail), CamFileError::WrongType);
  EXPECT_EQ(readCamText("STC-CAM 2\n", back, name, detail), CamFileError::WrongVersion);
  EXPECT_EQ(readCamText(text.substr(0, text.size() / 2), back, name, detail), CamFileError::UnexpectedEnd);
  EXPECT_EQ(readCamText("STC-CAM 1\ntype xyva\npoints 99999999\n", back, name, detail), CamFileError::TooMuchData);
  EXPECT_EQ(readCamText("STC-CAM 1\ntype xyva\npoints 2\n0 0 0 0\n1 nan 0 0\ntappets 0\nend\n", back, name, detail),
            CamFileError::UnexpectedEnd);
}
