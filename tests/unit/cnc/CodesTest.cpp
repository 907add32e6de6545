// Each G/M/H code of the dialect decodes to the documented geometry
// (docs/cnc.md), checked against closed-form values.
#include <cmath>

#include "CncTestUtil.h"

namespace stc::cnc::test {
namespace {

TEST(CncCodes, G1LineWithFeedAndBlockNumber) {
  Decoded r("N010 G01 X1000 Y2000 Z500 F10 E150 E-150\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 1u);
  const Element& e = r.els[0];
  EXPECT_EQ(e.type, MoveType::Lin);
  EXPECT_EQ(e.objNo, 1);
  EXPECT_EQ(e.line, 1);
  EXPECT_EQ(e.column, 6);
  EXPECT_EQ(e.blockNo, 10);
  expectPos(e.start, {0, 0, 0});
  expectPos(e.end, {1000, 2000, 500});
  EXPECT_EQ(e.vel, 10);
  EXPECT_EQ(e.acc, 150);
  EXPECT_EQ(e.dec, 150);
  EXPECT_NEAR(e.length, std::sqrt(1000.0 * 1000 + 2000.0 * 2000 + 500.0 * 500), 1e-9);
}

TEST(CncCodes, ModalFeedAndCoordinatesCarryOver) {
  // The seed's modal example: N020 uses N010's F/E, N040 keeps N030's Y.
  Decoded r("N010 G01 X1.5 Y3 F1 E0.5 E-0.5\n"
        "N020 G01 X3 Y1.5\n"
        "N030 X9 Y4\n"
        "N040 G01 X10\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 4u);
  for (const Element& e : r.els) {
    EXPECT_EQ(e.type, MoveType::Lin);
    EXPECT_EQ(e.vel, 1);
    EXPECT_EQ(e.acc, 0.5);
    EXPECT_EQ(e.dec, 0.5);
  }
  expectPos(r.els[2].end, {9, 4, 0});   // N030: no G word, the modal G1
  expectPos(r.els[3].end, {10, 4, 0});
  expectPos(r.els[3].start, {9, 4, 0});
}

TEST(CncCodes, AdditionalAxesMoveWithTheBlock) {
  Decoded r("N020 G01 X941 Y475 Z804 A8 B30 C20 P12 Q1 F5\nN030 G1 U4\n");
  ASSERT_EQ(r.errors(), 1u) << r.all();   // U after A in one program (1207)
  ASSERT_EQ(r.els.size(), 1u);
  expectPos(r.els[0].end, {941, 475, 804, 8, 30, 20, 12, 1, 0, 0, 0});
  EXPECT_EQ(r.els[0].axesUsed, (1 << AxX) | (1 << AxY) | (1 << AxZ) | (1 << AxA) | (1 << AxB) | (1 << AxC) |
                                   (1 << AxP) | (1 << AxQ));
  Decoded u("G1 X1 U4 V5 W6 F1\n");
  ASSERT_EQ(u.errors(), 0u) << u.all();
  expectPos(u.els[0].end, {1, 0, 0, 0, 0, 0, 0, 0, 4, 5, 6});
  // Only the additional axes move: the length is measured over them.
  Decoded a("G1 A3 P4 F1\n");
  EXPECT_NEAR(a.els[0].length, 5, 1e-12);
}

TEST(CncCodes, G0PositioningUsesFFandEFwhenSet) {
  Decoded r("N0 G0 X10 Y20 Z5 F100 E1000 E-2000\nN1 G0 X0 FF500 EF300 EF-400\nN2 G1 X5\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 3u);
  EXPECT_EQ(r.els[0].type, MoveType::LinPos);
  EXPECT_EQ(r.els[0].vel, 100);   // no FF yet: F/E/E-
  EXPECT_EQ(r.els[0].acc, 1000);
  EXPECT_EQ(r.els[0].dec, 2000);
  EXPECT_EQ(r.els[1].vel, 500);
  EXPECT_EQ(r.els[1].acc, 300);
  EXPECT_EQ(r.els[1].dec, 400);
  EXPECT_EQ(r.els[2].type, MoveType::Lin);
  EXPECT_EQ(r.els[2].vel, 100);   // G1 keeps F
  DecoderOptions o;
  o.defaultRapidVel = 50;
  o.defaultVel = 7;
  Decoded d("G0 X1\nG1 X2\n", o);
  EXPECT_EQ(d.els[0].vel, 50);
  EXPECT_EQ(d.els[1].vel, 7);
}

TEST(CncCodes, G2G3ByRadiusSignSelectsShortOrLongArc) {
  const double h = std::sqrt(75.0);
  struct Case {
    const char* text;
    MoveType type;
    double cy, sweep;
  } cases[] = {
      {"G2 X10 Y0 R10 F1", MoveType::Clw, -h, -kPi / 3},        // short CW: centre right of the chord
      {"G2 X10 Y0 R-10 F1", MoveType::Clw, h, -5 * kPi / 3},    // long CW
      {"G3 X10 Y0 R10 F1", MoveType::Cclw, h, kPi / 3},         // short CCW: centre left of the chord
      {"G3 X10 Y0 R-10 F1", MoveType::Cclw, -h, 5 * kPi / 3},   // long CCW
      {"G2 X10 Y0 R5 F1", MoveType::Clw, 0, -kPi},              // semicircle: R = half the chord
  };
  for (const Case& c : cases) {
    Decoded r(c.text);
    ASSERT_EQ(r.errors(), 0u) << c.text << r.all();
    ASSERT_EQ(r.els.size(), 1u);
    const Element& e = r.els[0];
    EXPECT_EQ(e.type, c.type) << c.text;
    expectVec(e.arc.centre, {5, c.cy, 0});
    EXPECT_NEAR(e.arc.radius, c.cy == 0 ? 5 : 10, 1e-12) << c.text;
    EXPECT_NEAR(e.arc.sweep, c.sweep, 1e-12) << c.text;
    expectVec(e.arc.normal, {0, 0, 1});
    expectPos(point(e, 1), {10, 0, 0});
    EXPECT_NEAR(e.length, e.arc.radius * std::fabs(c.sweep), 1e-9);
    // Every point on the circle.
    for (double u : {0.1, 0.37, 0.5, 0.81}) EXPECT_NEAR(norm(xyz(point(e, u)) - e.arc.centre), e.arc.radius, 1e-9);
  }
}

TEST(CncCodes, G2G3ByCentreRelativeAndAbsolute) {
  Decoded rel("G0 X2 Y3\nG2 X12 Y3 I5 J0 F1\n");            // G99 (default): I/J from the start
  Decoded abs("G0 X2 Y3\nG98 G2 X12 Y3 I7 J3 F1\n");        // G98: I/J absolute
  for (Decoded* r : {&rel, &abs}) {
    ASSERT_EQ(r->errors(), 0u) << r->all();
    const Element& e = r->els[1];
    EXPECT_EQ(e.type, MoveType::Clw);
    expectVec(e.arc.centre, {7, 3, 0});
    EXPECT_NEAR(e.arc.radius, 5, 1e-12);
    EXPECT_NEAR(e.arc.startAngle, kPi, 1e-12);
    EXPECT_NEAR(e.arc.sweep, -kPi, 1e-12);
    // Clockwise from (2,3) over the top: the midpoint is (7, 8).
    expectPos(point(e, 0.5), {7, 8, 0});
  }
  Decoded ccw("G0 X2 Y3\nG3 X12 Y3 I5 J0 F1\n");
  expectPos(point(ccw.els[1], 0.5), {7, -2, 0});
  EXPECT_NEAR(ccw.els[1].arc.sweep, kPi, 1e-12);
}

TEST(CncCodes, G2FullCircleAndHelixPitch) {
  Decoded full("G0 X10\nG2 I-10 F1\n");
  ASSERT_EQ(full.errors(), 0u) << full.all();
  const Element& c = full.els[1];
  expectVec(c.arc.centre, {0, 0, 0});
  EXPECT_NEAR(c.arc.sweep, -2 * kPi, 1e-12);
  expectPos(c.end, {10, 0, 0});
  EXPECT_NEAR(c.length, 2 * kPi * 10, 1e-9);

  // Half a turn rising 6: pitch 12.
  Decoded helix("G3 X10 Y0 Z6 I5 J0 F1\n");
  const Element& h = helix.els[0];
  EXPECT_NEAR(h.arc.rise, 6, 1e-12);
  EXPECT_NEAR(h.arc.rise / (std::fabs(h.arc.sweep) / (2 * kPi)), 12, 1e-12);
  EXPECT_NEAR(h.length, std::hypot(5 * kPi, 6.0), 1e-9);
  expectPos(point(h, 0.5), {5, -5, 3});

  // Two full turns by the sweep T: pitch 5.
  Decoded turns("G3 I5 J0 T720 Z10 F1\n");
  ASSERT_EQ(turns.errors(), 0u) << turns.all();
  const Element& t = turns.els[0];
  EXPECT_NEAR(t.arc.sweep, 4 * kPi, 1e-12);
  EXPECT_NEAR(t.arc.rise / (t.arc.sweep / (2 * kPi)), 5, 1e-12);
  expectPos(t.end, {0, 0, 10});
}

TEST(CncCodes, G3ByCentreAndSweepT) {
  Decoded r("G3 I5 J0 T90 F1\nG2 I0 J5 T45\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  // CCW from angle 180 deg about (5,0) by 90 deg: (5,-5).
  expectPos(r.els[0].end, {5, -5, 0});
  EXPECT_NEAR(r.els[0].arc.sweep, kPi / 2, 1e-12);
  // CW about (5,0) from angle -90 deg by 45 deg: angle -135 deg.
  const double s = 5 / std::sqrt(2.0);
  expectPos(r.els[1].end, {5 - s, -s, 0});
}

TEST(CncCodes, ArcCentreWithinTenPercentIsCorrected) {
  // r0 = 5.2, r1 = 4.8 (7.7%): the centre moves onto the chord's bisector.
  Decoded r("G2 X10 Y0 I5.2 J0 F1\n");
  EXPECT_EQ(r.errors(), 0u) << r.all();
  EXPECT_EQ(r.warnings(), 1u);
  expectVec(r.els[0].arc.centre, {5, 0, 0});
  EXPECT_NEAR(r.els[0].arc.radius, 5, 1e-12);
  // The seed's G03 X6 Y2.8 I0.06 J3.8 from (3, 1.5): 1.5% off, corrected; the
  // end point stays exact and both ends are on the circle.
  Decoded seed("G1 X3 Y1.5 F1\nN030 G03 X6 Y2.8 I0.06 J3.8\n");
  ASSERT_EQ(seed.errors(), 0u) << seed.all();
  const Element& e = seed.els[1];
  expectPos(e.end, {6, 2.8, 0});
  EXPECT_NEAR(norm(xyz(e.start) - e.arc.centre), e.arc.radius, 1e-12);
  EXPECT_NEAR(norm(xyz(e.end) - e.arc.centre), e.arc.radius, 1e-12);
}

TEST(CncCodes, PlanesG17G18G19) {
  // G18: the ZX plane, normal +Y; clockwise seen from +Y passes z = -5.
  Decoded zx("G18 G2 X10 I5 K0 F1\n");
  ASSERT_EQ(zx.errors(), 0u) << zx.all();
  const Element& a = zx.els[0];
  EXPECT_EQ(a.plane, Plane::ZX);
  expectVec(a.arc.normal, {0, 1, 0});
  expectPos(point(a, 0.5), {5, 0, -5});
  // G19: the YZ plane, normal +X; counter-clockwise from (0,0,0) to (0,10,0).
  Decoded yz("G19 G3 Y10 J5 K0 F1\n");
  const Element& b = yz.els[0];
  EXPECT_EQ(b.plane, Plane::YZ);
  expectVec(b.arc.normal, {1, 0, 0});
  expectPos(point(b, 0.5), {0, 5, -5});
  // G17 returns to XY; a helix in G18 rises along Y.
  Decoded back("G18\nG17 G2 X10 I5 F1\nG18 G3 X10 Y4 I5 K0\n");
  ASSERT_EQ(back.errors(), 0u) << back.all();
  EXPECT_EQ(back.els[0].plane, Plane::XY);
  expectPos(point(back.els[0], 0.5), {5, 5, 0});
  EXPECT_NEAR(back.els[1].arc.rise, 4, 1e-12);
}

TEST(CncCodes, G16PlaneFromNormal) {
  // A plane tilted 45 degrees about X: normal (0, -1, 1)/sqrt2.
  Decoded r("G16 I0 J-1 K1\nG3 X10 I5 F1\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  const Element& e = r.els[0];
  EXPECT_EQ(e.plane, Plane::Free);
  const double s = 1 / std::sqrt(2.0);
  expectVec(e.arc.normal, {0, -s, s});
  expectVec(e.arc.centre, {5, 0, 0});
  for (double u : {0.25, 0.5, 0.75}) {
    Vec3 p = xyz(point(e, u));
    EXPECT_NEAR(dot(p, e.arc.normal), 0, 1e-12);   // in the plane through the start
    EXPECT_NEAR(norm(p - e.arc.centre), 5, 1e-12);
  }
  // G16 without I/J/K keeps the plane.
  Decoded k("G16 I1 J0 K0\nG16 F100\nG2 Y10 J5\n");
  ASSERT_EQ(k.errors(), 0u) << k.all();
  expectVec(k.els[0].arc.normal, {1, 0, 0});
}

TEST(CncCodes, G4DwellAndG75Sync) {
  Decoded r("N5 G1 X1 F1\nN6 G4 T1.5\nN7 G75\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 3u);
  EXPECT_EQ(r.els[1].type, MoveType::Dwell);
  EXPECT_EQ(r.els[1].dwell, 1.5);
  EXPECT_EQ(r.els[1].blockNo, 6);
  expectPos(r.els[1].start, {1, 0, 0});
  EXPECT_EQ(r.els[2].type, MoveType::Sync);
  EXPECT_EQ(r.els[2].m, 65534);
}

TEST(CncCodes, G5SplineThroughStaircaseTangents) {
  // The seed's staircase: chord tangent after G0, intermediate tangents
  // parallel to the neighbours' line, chord tangent at the end.
  Decoded r("N0 G0 X0 Y0 Z0 F100 (start)\nN10 G5 X20 Y0\nN20 G5 X20 Y20\nN30 G5 X40 Y20\nN40 G5 X40 Y40\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  auto sp = r.of(MoveType::Spline);
  ASSERT_EQ(sp.size(), 4u);
  const double s = 1 / std::sqrt(2.0);
  expectVec(sp[0].spline.t0, {1, 0, 0});
  for (int i = 0; i < 3; ++i) {
    expectVec(sp[i].spline.t1, {s, s, 0});
    expectVec(sp[i + 1].spline.t0, {s, s, 0});
  }
  expectVec(sp[3].spline.t1, {0, 1, 0});
  for (const Element& e : sp) {
    EXPECT_EQ(e.spline.dims, 2);
    expectPos(point(e, 1), {e.end[0], e.end[1], 0});
    expectVec(startTangent(e), e.spline.t0);
    expectVec(endTangent(e), e.spline.t1);
    EXPECT_GT(e.length, norm(xyz(e.end) - xyz(e.start)) - 1e-12);
  }
  // objNo stays in order although each piece waits for its successor.
  for (size_t i = 0; i < r.els.size(); ++i) EXPECT_EQ(r.els[i].objNo, static_cast<int>(i + 1));
}

TEST(CncCodes, G5SplineJoinsNeighbouringToolPathElements) {
  Decoded r("G1 X10 F1\nG5 X20 Y10\nG2 X30 Y0 I0 J-10\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  auto sp = r.of(MoveType::Spline);
  ASSERT_EQ(sp.size(), 1u);
  expectVec(sp[0].spline.t0, {1, 0, 0});            // the line's end tangent
  expectVec(sp[0].spline.t1, startTangent(r.els[2]));   // the arc's start tangent
  expectVec(sp[0].spline.t1, {1, 0, 0});
  // An M function after the spline: chord tangent.
  Decoded m("G1 X10 F1\nG5 X20 Y10\nM7\n");
  const double s = 1 / std::sqrt(2.0);
  expectVec(m.of(MoveType::Spline)[0].spline.t1, {s, s, 0});
}

TEST(CncCodes, G10SplineIn3D) {
  Decoded r("G0 X0\nG10 X10 Y0 Z10 F1\nG10 X20 Y10 Z10\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  auto sp = r.of(MoveType::Spline);
  ASSERT_EQ(sp.size(), 2u);
  EXPECT_EQ(sp[0].spline.dims, 3);
  const double s = 1 / std::sqrt(2.0);
  expectVec(sp[0].spline.t0, {s, 0, s});   // chord after G0
  expectVec(sp[0].spline.t1, normalized(Vec3{20, 10, 10}));
  expectPos(point(sp[1], 1), {20, 10, 10});
}

TEST(CncCodes, G6ParabolaVertex) {
  Decoded r("N020 G06 X500 Y400 Z20 I100 J80 F5\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  const Element& e = r.els[0];
  EXPECT_EQ(e.type, MoveType::Parabola);
  expectVec(e.parabola.vertex, {100, 80, 10});
  expectVec(e.parabola.control, {-50, -40, 10});
  expectPos(point(e, 0.5), {100, 80, 10});
  // At the vertex the tangent is parallel to the chord.
  Vec3 d = derivative(e, 0.5);
  EXPECT_NEAR(d[0] * 400 - d[1] * 500, 0, 1e-9);
  expectPos(point(e, 1), {500, 400, 20});
  Decoded abs("G0 X100 Y100\nG98 G6 X200 Y100 I150 J150 F1\n");
  expectVec(abs.els[1].parabola.vertex, {150, 150, 0});
}

TEST(CncCodes, G8G9EllipseFromEndPointsCentreAndAxis) {
  // Centre (0,0), a = 10, b = 5, main axis along X.
  Decoded r("G0 X10 Y0\nG98 G9 X0 Y5 I0 J0 K0 F1\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  const Element& e = r.els[1];
  EXPECT_EQ(e.type, MoveType::EllCclw);
  EXPECT_NEAR(e.ellipse.a, 10, 1e-9);
  EXPECT_NEAR(e.ellipse.b, 5, 1e-9);
  EXPECT_NEAR(e.ellipse.startPhi, 0, 1e-12);
  EXPECT_NEAR(e.ellipse.sweepPhi, kPi / 2, 1e-12);
  expectPos(point(e, 0.5), {10 * std::cos(kPi / 4), 5 * std::sin(kPi / 4), 0});
  // A quarter of the ellipse's perimeter (Ramanujan's series is exact enough
  // to 1e-6 here; the quadrature itself agrees with the G8 complement).
  Decoded cw("G0 X10 Y0\nG98 G8 X0 Y5 I0 J0 K0 F1\n");
  EXPECT_NEAR(cw.els[1].ellipse.sweepPhi, -3 * kPi / 2, 1e-12);
  EXPECT_NEAR(cw.els[1].length + e.length, 48.44224110273838, 1e-9);

  // Rotated by K = 30 deg about (1, 2): points at phi 20 deg and 100 deg.
  const double phi = 30 * kPi / 180, a = 8, b = 3;
  auto at = [&](double t) {
    return Vec3{1 + a * std::cos(t) * std::cos(phi) - b * std::sin(t) * std::sin(phi),
                2 + a * std::cos(t) * std::sin(phi) + b * std::sin(t) * std::cos(phi), 0};
  };
  Vec3 s = at(20 * kPi / 180), t = at(100 * kPi / 180);
  std::string prog = "G0 X" + formatNumber(s[0]) + " Y" + formatNumber(s[1]) + "\nG98 G9 X" + formatNumber(t[0]) +
                     " Y" + formatNumber(t[1]) + " I1 J2 K30 F1\n";
  Decoded rot(prog);
  ASSERT_EQ(rot.errors(), 0u) << rot.all();
  const Element& q = rot.els[1];
  EXPECT_NEAR(q.ellipse.a, a, 1e-9);
  EXPECT_NEAR(q.ellipse.b, b, 1e-9);
  EXPECT_NEAR(q.ellipse.majorAngle, phi, 1e-12);
  EXPECT_NEAR(q.ellipse.sweepPhi, 80 * kPi / 180, 1e-9);
  Vec3 mid = xyz(point(q, 0.5));
  expectVec(mid, at(60 * kPi / 180), 1e-9);
}

TEST(CncCodes, G8EllipseNeedsRWhenSymmetricAndLineWhenNoEllipseFits) {
  // Points at phi 30 and 150 degrees: equally far from both axes, R decides.
  const double a = 10, b = 5;
  double x = a * std::cos(kPi / 6), y = b * std::sin(kPi / 6);
  std::string start = "G0 X" + formatNumber(x) + " Y" + formatNumber(y) + "\n";
  Decoded withR(start + "G98 G9 X" + formatNumber(-x) + " Y" + formatNumber(y) + " I0 J0 K0 R0.5 F1\n");
  ASSERT_EQ(withR.errors(), 0u) << withR.all();
  EXPECT_NEAR(withR.els[1].ellipse.a, 10, 1e-9);
  EXPECT_NEAR(withR.els[1].ellipse.b, 5, 1e-9);
  EXPECT_NEAR(withR.els[1].ellipse.sweepPhi, 2 * kPi / 3, 1e-9);
  Decoded noR(start + "G98 G9 X" + formatNumber(-x) + " Y" + formatNumber(y) + " I0 J0 K0 F1\n");
  EXPECT_EQ(noR.errors(), 1u);
  // (10, 3) and (5, 3) are equally far from the main axis but not from the
  // second one: no ellipse, a line (with a warning), as the spec says.
  Decoded line("G0 X10 Y3\nG98 G8 X5 Y3 I0 J0 F1\n");
  EXPECT_EQ(line.errors(), 0u);
  EXPECT_EQ(line.warnings(), 1u);
  EXPECT_EQ(line.els[1].type, MoveType::Lin);
  expectPos(line.els[1].end, {5, 3, 0});
}

TEST(CncCodes, SeedsG8ExampleUsesRForSymmetricPoints) {
  // N030 G98 / N040 G8 X200 Y100 I150 J100 K25 R0.5 from (100, 100): both
  // points are equally far from the 25-degree main axis, so R decides.
  Decoded r("N020 G0 X100 Y100\nN030 G98\nN040 G8 X200 Y100 I150 J100 K25 R0.5 F10\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  const Element& e = r.els[1];
  EXPECT_EQ(e.type, MoveType::EllClw);
  EXPECT_EQ(e.blockNo, 40);
  expectVec(e.ellipse.centre, {150, 100, 0});
  EXPECT_NEAR(e.ellipse.b / e.ellipse.a, 0.5, 1e-12);
  EXPECT_NEAR(e.ellipse.majorAngle, 25 * kPi / 180, 1e-12);
  EXPECT_NEAR(e.ellipse.sweepPhi, -kPi, 1e-12);
  for (double u : {0.0, 0.3, 0.5, 1.0}) {
    Vec3 d = xyz(point(e, u)) - e.ellipse.centre;
    double x = dot(d, e.ellipse.major), y = dot(d, cross(Vec3{0, 0, 1}, e.ellipse.major));
    EXPECT_NEAR(x * x / (e.ellipse.a * e.ellipse.a) + y * y / (e.ellipse.b * e.ellipse.b), 1, 1e-12);
  }
  expectPos(point(e, 1), {200, 100, 0});
}

TEST(CncCodes, G53GoesWithATravelCommand) {
  Decoded r("G54 X10\nG1 X0 F1\nG53 G1 X0\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  expectPos(r.els[0].end, {10, 0, 0});
  expectPos(r.els[1].end, {0, 0, 0});
}

TEST(CncCodes, MFunctionWithParameters) {
  Decoded r("N040 G1 X5 F1\nN050 M10 K87.6 L120.5\nN060 G1 X6 M11\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 4u);
  const Element& m = r.els[1];
  EXPECT_EQ(m.type, MoveType::MCommand);
  EXPECT_EQ(static_cast<int>(m.type), 120);
  EXPECT_EQ(m.m, 10);
  EXPECT_EQ(m.k, 87.6);
  EXPECT_EQ(m.l, 120.5);
  EXPECT_EQ(m.blockNo, 50);
  expectPos(m.start, {5, 0, 0});
  // An M in a moving block comes after the move.
  EXPECT_EQ(r.els[2].type, MoveType::Lin);
  EXPECT_EQ(r.els[3].type, MoveType::MCommand);
  EXPECT_EQ(r.els[3].m, 11);
  expectPos(r.els[3].start, {6, 0, 0});
}

TEST(CncCodes, HSwitchPointsSeveralPerBlock) {
  Decoded r("N90 G1 X20 F1\nN100 G1 X100 H2 L20 H-2 L-10\nN110 G1 Y20 H-3 O0.25 H4\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  const Element& a = r.els[1];
  ASSERT_EQ(a.switchCount, 2);
  EXPECT_EQ(a.switches[0].sw, 2);
  EXPECT_FALSE(a.switches[0].relative);
  EXPECT_EQ(a.switches[0].pos, 20);
  EXPECT_EQ(a.switches[1].sw, -2);
  EXPECT_EQ(a.switches[1].pos, -10);
  const Element& b = r.els[2];
  ASSERT_EQ(b.switchCount, 2);
  EXPECT_EQ(b.switches[0].sw, -3);
  EXPECT_TRUE(b.switches[0].relative);
  EXPECT_EQ(b.switches[0].pos, 0.25);
  EXPECT_EQ(b.switches[1].sw, 4);   // no L/O: at the start
  EXPECT_EQ(b.switches[1].pos, 0);
}

TEST(CncCodes, G41G42G40ToolCorrectionMarks) {
  Decoded r("N00 G0 X10 Y-10 F100 E100 E-100\nN10 G41 D10\nN20 G1 X20 Y-10\nN30 G1 X30\nN40 G40\nN50 G1 X40\n"
        "N60 G42 D2.5\nN70 G0 X50\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 5u);
  EXPECT_EQ(r.els[0].marks, 0);
  EXPECT_EQ(r.els[1].marks, MarkToolCorrLeft);
  EXPECT_EQ(r.els[1].toolSide, ToolSide::Left);
  EXPECT_EQ(r.els[1].toolRadius, 10);
  EXPECT_EQ(r.els[2].marks, 0);
  EXPECT_EQ(r.els[2].toolSide, ToolSide::Left);
  EXPECT_EQ(r.els[3].marks, MarkToolCorrEnd);
  EXPECT_EQ(r.els[3].toolSide, ToolSide::Off);
  EXPECT_EQ(r.els[4].marks, MarkToolCorrRight);
  EXPECT_EQ(r.els[4].toolRadius, 2.5);
  // G41 while G42 is on: not allowed (no nesting, no overlap).
  Decoded bad("G41 D1\nG1 X1 F1\nG42 D1\n");
  ASSERT_EQ(bad.errors(), 1u);
  EXPECT_EQ(bad.heads()[0],
            "prog.cnc:3:1: error: tool radius correction is already on; end it with G40 before G42 [gcode-conflict]");
}

TEST(CncCodes, G50G51G52SmoothingAndG60G61LoopMarks) {
  Decoded r("N000 G01 X10 Y0 F100\nN010 G51 D2 G61\nN020 G01 X10 Y20\nN030 G52 D1.5\nN035 G1 X20\n"
        "N040 G50 G60\nN050 G01 X30\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 4u);
  EXPECT_EQ(r.els[1].marks, MarkSmoothStart | MarkLoopAvoidStart);
  EXPECT_EQ(r.els[1].smoothing, Smoothing::Smooth);
  EXPECT_EQ(r.els[1].smoothDist, 2);
  EXPECT_TRUE(r.els[1].loopAvoid);
  EXPECT_EQ(r.els[2].marks, MarkRoundStart);
  EXPECT_EQ(r.els[2].smoothing, Smoothing::Round);
  EXPECT_EQ(r.els[2].smoothDist, 1.5);
  EXPECT_EQ(r.els[3].marks, MarkSmoothEnd | MarkLoopAvoidEnd);
  EXPECT_EQ(r.els[3].smoothing, Smoothing::Off);
  EXPECT_FALSE(r.els[3].loopAvoid);
}

TEST(CncCodes, G53G54G55G56Offsets) {
  Decoded r("G54 X10 Y20\n"          // offset (10, 20)
        "G1 X0 Y0 F1\n"          // machine (10, 20)
        "G55 X5\n"               // offset (15, 20)
        "G1 X1 Y1\n"             // machine (16, 21)
        "G56 X0 Y0\n"            // offset (16, 21): the current point is (0, 0)
        "G1 X1 Y1\n"             // machine (17, 22)
        "G53\n"
        "G1 X1 Y1\n"             // machine (1, 1)
        "G54 Z3\n"               // X/Y offsets back to 0
        "G1 X2\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 5u);
  expectPos(r.els[0].end, {10, 20, 0});
  expectPos(r.els[1].end, {16, 21, 0});
  expectPos(r.els[2].end, {17, 22, 0});
  expectPos(r.els[3].end, {1, 1, 0});
  expectPos(r.els[4].end, {2, 1, 0});   // Z keeps its position (not programmed)
  // Offsets apply to absolute centres (G98) and in G91 not at all.
  Decoded c("G54 X100\nG0 X0\nG98 G2 X10 Y0 I5 J0 F1\nG91 G1 X1\n");
  ASSERT_EQ(c.errors(), 0u) << c.all();
  expectVec(c.els[1].arc.centre, {105, 0, 0});
  expectPos(c.els[2].end, {111, 0, 0});
}

TEST(CncCodes, G90G91AbsoluteAndIncremental) {
  Decoded r("G91\nG1 X10 Y10 F1\nG1 X10 Y10\nG90 G1 X5\nG91 G2 X10 Y0 I5 J0\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  expectPos(r.els[0].end, {10, 10, 0});
  expectPos(r.els[1].end, {20, 20, 0});
  expectPos(r.els[2].end, {5, 20, 0});
  expectPos(r.els[3].end, {15, 20, 0});
  expectVec(r.els[3].arc.centre, {10, 20, 0});
}

TEST(CncCodes, G92SetsThePosition) {
  Decoded r("G1 X10 Y5 F1\nG92 X0 Y0\nG1 X5\nG54 X100\nG92 X0\nG1 X1\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 5u);
  EXPECT_EQ(r.els[1].type, MoveType::InitPos);
  expectPos(r.els[1].start, {10, 5, 0});
  expectPos(r.els[1].end, {0, 0, 0});
  expectPos(r.els[2].start, {0, 0, 0});
  expectPos(r.els[2].end, {5, 0, 0});
  expectPos(r.els[3].end, {100, 0, 0});   // G92 coordinates are program coordinates
  expectPos(r.els[4].end, {101, 0, 0});
}

TEST(CncCodes, G98G99CentreModes) {
  Decoded r("G0 X10 Y10\nG98\nG2 X20 Y10 I15 J10 F1\nG99\nG2 X30 Y10 I5 J0\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  expectVec(r.els[1].arc.centre, {15, 10, 0});
  expectVec(r.els[2].arc.centre, {25, 10, 0});
}

TEST(CncCodes, G20JumpLoopWithTheInternalCounter) {
  // SoftMotion's example: ten relative lines make a line to (100, 100).
  Decoded r("N00 G36 D10          (set counter to 10)\n"
        "N10 G91              (relative mode)\n"
        "N20 G01 X10 Y10 F100 (movement by distance 10/10)\n"
        "N30 G37 D-1          (decrement counter)\n"
        "N40 G20 L20          (jump, if counter != 0)\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 10u);
  expectPos(r.els.back().end, {100, 100, 0});
  EXPECT_EQ(r.els.back().line, 3);
  EXPECT_EQ(r.els.back().objNo, 10);
}

TEST(CncCodes, G25IsTheSeedsJumpCodeAndG36G37WriteVariables) {
  MapVars v;
  v.values["g_i"] = 0;
  Decoded r("N1000 G36 O$g_i$ D5\nN1010 G1 X100 F100 E100 E-100\nN1020 G1 X0\nN1030 G37 O$g_i$ D-1\n"
        "N1040 G25 L1010 K$g_i$\n",
        {}, &v);
  ASSERT_EQ(r.errors(), 0u) << r.all();
  EXPECT_EQ(r.els.size(), 10u);   // lines 1010 and 1020 travelled five times
  EXPECT_EQ(v.values["g_i"], 0);
}

TEST(CncCodes, G20JumpsForwardToLabels) {
  Decoded r("N0 G16 F100 E100 E-100\nN10 G20 L?4\nN15 G1 X60\nN20 G1 X10 L!4\nN30 G20 L50 K0\nN40 G1 X20\nN50 G1 X30\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 3u);   // N15 skipped; K0: no jump from N30
  expectPos(r.els[0].end, {10, 0, 0});
  expectPos(r.els[1].end, {20, 0, 0});
  expectPos(r.els[2].end, {30, 0, 0});
}

TEST(CncCodes, BlockSkipSlash) {
  std::string prog = "N10 G1 X1 F1\n/N20 G1 X2\nN30 G1 X3\n";
  Decoded skip(prog);
  EXPECT_EQ(skip.els.size(), 2u);
  DecoderOptions o;
  o.skipSlashBlocks = false;
  Decoded keep(prog, o);
  EXPECT_EQ(keep.els.size(), 3u);
}

TEST(CncCodes, CommentsHeaderCaseAndLeadingZeros) {
  Decoded r("% MyProgram\n(a whole-line comment)\nn010 g01 x010.50 y-0.5 f100 ; to the end of the line\n"
        "N020 G01 X3 // the seed's comments\n\nN030 g0001 X.5\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 3u);
  expectPos(r.els[0].end, {10.5, -0.5, 0});
  expectPos(r.els[2].end, {0.5, -0.5, 0});
  EXPECT_EQ(r.els[2].line, 6);
}

TEST(CncCodes, PercentLinesOpenAndCloseTheProgram) {
  Decoded r("%\n(CAM output)\nG90 G17\nG0 Z5.\nG1 X10. F300.\nM30\n%\n");
  ASSERT_EQ(r.errors(), 0u) << r.all();
  EXPECT_EQ(r.warnings(), 0u) << r.all();
  ASSERT_EQ(r.els.size(), 3u);
  EXPECT_EQ(r.els[2].type, MoveType::MCommand);   // M30 has no predefined meaning
  EXPECT_EQ(r.els[2].m, 30);
}

TEST(CncCodes, VariablesInCoordinatesAndMH) {
  MapVars v;
  v.values = {{"x_pos", 12.5}, {"y_pos", -3}, {"M_cmd", 7}, {"H_cmd", -4}, {"P_X", 1}};
  Decoded r("N080 G01 X$x_pos$ Y$y_pos$ F8 E130 E-130\nn20 g10 X-$P_X$ Y0 M$M_cmd$ H$H_cmd$\n", {}, &v);
  ASSERT_EQ(r.errors(), 0u) << r.all();
  expectPos(r.els[0].end, {12.5, -3, 0});
  EXPECT_EQ(r.els[1].type, MoveType::Spline);
  expectPos(r.els[1].end, {-1, 0, 0});
  EXPECT_EQ(r.els[1].switches[0].sw, -4);
  EXPECT_EQ(r.els[2].m, 7);
}

TEST(CncCodes, LeadshineRequiresBlockNumbersAndExclusiveAxes) {
  DecoderOptions o;
  o.requireBlockNumbers = true;
  Decoded r("N10 G1 X1 U2 F1\nG1 X2\nN30 G1 A1\n", o);
  auto h = r.heads();
  ASSERT_EQ(h.size(), 2u) << r.all();
  EXPECT_EQ(h[0], "prog.cnc:2:1: error: every block needs a block number N in this dialect [gcode-missing-word]");
  EXPECT_EQ(h[1], "prog.cnc:3:8: error: axes A and U cannot be used in one program (they share an interpolator "
                  "channel) [gcode-exclusive-axes]");
}

}  // namespace
}  // namespace stc::cnc::test
