// Tool radius correction (stdlib-motion/cnc/ToolCorr.h, docs/cnc.md "Tool radius
// correction"): closed-form corners, entry and exit per mode, the distance property on
// random contours, errors and degenerate input.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <random>
#include <sstream>

#include "CncTestUtil.h"
#include "stdlib-motion/cnc/ToolCorr.h"

namespace stc::cnc::test {
namespace {

std::vector<Element> corrected(const std::string& text, ToolCorrMode mode, ToolCorrError* err = nullptr,
                               double defaultRadius = 0) {
  Decoded d(text);
  EXPECT_EQ(d.errors(), 0u) << d.all();
  return correctAll(d.els, mode, defaultRadius, err);
}

// The elements are chained: each starts exactly where the previous ended.
void expectChained(const std::vector<Element>& els) {
  for (size_t i = 1; i < els.size(); ++i)
    for (int a = 0; a < kAxisCount; ++a)
      ASSERT_EQ(els[i].start[a], els[i - 1].end[a]) << "element " << i << " axis " << a;
}
// point(e, 1) is the end and the arc's start angle matches the start point.
void expectConsistent(const std::vector<Element>& els) {
  for (size_t i = 0; i < els.size(); ++i) {
    const Element& e = els[i];
    if (e.type != MoveType::Clw && e.type != MoveType::Cclw) continue;
    Vec3 s = e.arc.centre + (e.arc.radius * std::cos(e.arc.startAngle)) * e.arc.u +
             (e.arc.radius * std::sin(e.arc.startAngle)) * e.arc.v;
    expectVec(s, xyz(e.start), 1e-9);
    Vec3 q = e.arc.centre + (e.arc.radius * std::cos(e.arc.startAngle + e.arc.sweep)) * e.arc.u +
             (e.arc.radius * std::sin(e.arc.startAngle + e.arc.sweep)) * e.arc.v + e.arc.rise * e.arc.normal;
    expectVec(q, xyz(e.end), 1e-9);
    EXPECT_EQ(e.type == MoveType::Cclw, e.arc.sweep > 0) << "element " << i;
  }
}

struct Expect {
  MoveType type;
  double x, y;        // end point
  double cx = 0, cy = 0, sweep = 0;   // arcs: centre and sweep
};
void expectPath(const std::vector<Element>& els, const std::vector<Expect>& want) {
  ASSERT_EQ(els.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    SCOPED_TRACE("element " + std::to_string(i));
    EXPECT_EQ(els[i].type, want[i].type);
    EXPECT_NEAR(els[i].end[AxX], want[i].x, kTol);
    EXPECT_NEAR(els[i].end[AxY], want[i].y, kTol);
    if (want[i].type == MoveType::Clw || want[i].type == MoveType::Cclw) {
      EXPECT_NEAR(els[i].arc.centre[0], want[i].cx, kTol);
      EXPECT_NEAR(els[i].arc.centre[1], want[i].cy, kTol);
      EXPECT_NEAR(els[i].arc.sweep, want[i].sweep, kTol);
    }
  }
  expectChained(els);
  expectConsistent(els);
}

const MoveType L = MoveType::Lin, P = MoveType::LinPos, CW = MoveType::Clw, CCW = MoveType::Cclw;

// The square 0..10 travelled counter-clockwise from the origin.
std::string square(const char* g) {
  return std::string("N10 ") + g +
         " D1\nN20 G1 X10 Y0 F10\nN30 G1 X10 Y10\nN40 G1 X0 Y10\nN50 G1 X0 Y0\nN60 G40\nN70 G0 X-5 Y-5\n";
}

TEST(ToolCorr, SquareLeftInsideCornersAreCut) {
  // G41 on a counter-clockwise square: the tool is inside, the corners are cut at (9,1) ...
  auto els = corrected(square("G41"), ToolCorrMode::BlindPos);
  expectPath(els, {{P, 0, 1}, {L, 9, 1}, {L, 9, 9}, {L, 1, 9}, {L, 1, 0}, {P, -5, -5}});
}

TEST(ToolCorr, SquareRightOutsideCornersAreRounded) {
  // G42: the tool outside; quarter arcs of radius 1 about the programmed corners.
  auto els = corrected(square("G42"), ToolCorrMode::BlindPos);
  const double q = kPi / 2;
  expectPath(els, {{P, 0, -1},
                   {L, 10, -1},
                   {CCW, 11, 0, 10, 0, q},
                   {L, 11, 10},
                   {CCW, 10, 11, 10, 10, q},
                   {L, 0, 11},
                   {CCW, -1, 10, 0, 10, q},
                   {L, -1, 0},
                   {P, -5, -5}});
  for (const Element& e : els)
    if (e.type == CCW) {
      EXPECT_EQ(e.arc.radius, 1.0);
    }
}

TEST(ToolCorr, ClockwiseSquareLeftIsOutside) {
  auto els = corrected("N10 G41 D2\nN20 G1 X0 Y10 F10\nN30 G1 X10 Y10\nN40 G40\n", ToolCorrMode::BlindPos);
  // Up the Y axis with the tool on the left (x = -2), a right turn: outside corner about (0,10).
  expectPath(els, {{P, -2, 0}, {L, -2, 10}, {CW, 0, 12, 0, 10, -kPi / 2}, {L, 10, 12}, {P, 10, 10}});
}

TEST(ToolCorr, PositioningG0IsMovedToTheOffsetStart) {
  // TC_BLIND_POS with a G0 before the contour (the seed's example 2): no element is inserted,
  // the G0 ends at the offset start; the G0 after the contour leaves from the offset end.
  auto els = corrected("N00 G41 D1\nN10 G0 X3 Y0 F100\nN20 G1 X3 Y10\nN30 G1 X7 Y10\nN40 G0 X20 Y0\nN50 G40\n",
                       ToolCorrMode::BlindPos);
  expectPath(els, {{P, 2, 0}, {L, 2, 10}, {CW, 3, 11, 3, 10, -kPi / 2}, {L, 7, 11}, {P, 20, 0}});
}

TEST(ToolCorr, ZMovesGoWithTheTool) {
  // The seed's example 3: a plunge after the positioning is offset with the contour.
  auto els = corrected("N00 G41 D1 F100\nN10 G0 X3\nN20 G1 Z10\nN30 G1 X3 Y10\nN40 G1 X7 Y10\nN60 G1 Z0\nN70 G40\n"
                       "N80 G0 X20 Y0\n",
                       ToolCorrMode::BlindPos);
  ASSERT_EQ(els.size(), 7u);
  expectChained(els);
  expectPos(els[0].end, {2, 0, 0});
  expectPos(els[1].end, {2, 0, 10});
  expectPos(els[2].end, {2, 10, 10});
  EXPECT_EQ(els[3].type, CW);
  expectPos(els[4].end, {7, 11, 10});
  expectPos(els[5].end, {7, 11, 0});
  expectPos(els[6].end, {20, 0, 0});
}

// The Moons manual's TC_BLIND_IN program (left, radius 3) in the three modes.
const char* kMoonsBlindIn = "N000 G41 D3\nN010 G01 X3 Y10 F100 E1000 E-1000\nN020 G01 X7 Y10\nN030 G01 X10 Y0\nN040 G40\nN050 G01 X20\n";

TEST(ToolCorr, RampInKeepsTheStartAndCornersTheEntry) {
  auto els = corrected(kMoonsBlindIn, ToolCorrMode::RampIn);
  const double s = std::sqrt(109.0);
  const double n1x = -10 / s * 3, n1y = 3 / s * 3;   // left normal of the first line, times 3
  const double n3x = 10 / s * 3, n3y = 3 / s * 3;    // of the third
  const double a1 = std::atan2(3 / s, -10 / s), a3 = std::atan2(3 / s, 10 / s);
  expectPath(els, {{L, 3 + n1x, 10 + n1y},
                   {CW, 3, 13, 3, 10, std::remainder(kPi / 2 - a1, 2 * kPi)},
                   {L, 7, 13},
                   {CW, 7 + n3x, 10 + n3y, 7, 10, a3 - kPi / 2},
                   {L, 10 + n3x, n3y},
                   {L, 20, 0}});
  EXPECT_EQ(els[0].start[AxX], 0.0);   // the entry starts at the programmed point
  EXPECT_EQ(els[0].start[AxY], 0.0);
}

TEST(ToolCorr, BlindInReachesTheOffsetAtTheEndOfTheFirstElement) {
  auto els = corrected(kMoonsBlindIn, ToolCorrMode::BlindIn);
  const double s = std::sqrt(109.0);
  const double n3x = 10 / s * 3, n3y = 3 / s * 3;
  const double a3 = std::atan2(3 / s, 10 / s);
  // No corner element at the end of the first line: it goes straight to (3, 13).
  expectPath(els, {{L, 3, 13}, {L, 7, 13}, {CW, 7 + n3x, 10 + n3y, 7, 10, a3 - kPi / 2}, {L, 10 + n3x, n3y}, {L, 20, 0}});
}

TEST(ToolCorr, BlindPosInsertsPositioningAtBothEnds) {
  auto els = corrected(kMoonsBlindIn, ToolCorrMode::BlindPos);
  const double s = std::sqrt(109.0);
  ASSERT_EQ(els.size(), 8u);
  EXPECT_EQ(els[0].type, P);   // to the offset start of the first line
  EXPECT_NEAR(els[0].end[AxX], -30 / s, kTol);
  EXPECT_NEAR(els[0].end[AxY], 9 / s, kTol);
  EXPECT_EQ(els[6].type, P);   // back to the programmed end (10, 0), then the G1 after G40
  expectPos(els[6].end, {10, 0, 0});
  EXPECT_EQ(els[7].type, L);
  expectChained(els);
}

TEST(ToolCorr, BlindPosG0BetweenContourElementsKeepsTheNextElement) {
  // A G0 between two contour elements connects them (no corner).  The element after it was
  // once lost: it became the held element without being marked as held (found by
  // tests/fuzz/path_fuzz.cpp, path_regressions/tc-blindpos-g0-between-contours-kept-next.cnc).
  auto els = corrected("N10 G41 D1\nN20 G1 X10 Y0 F100\nN30 G0 X20 Y0\nN40 G1 X30 Y0\nN50 G40\n", ToolCorrMode::BlindPos);
  expectPath(els, {{P, 0, 1}, {L, 10, 1}, {P, 20, 1}, {L, 30, 1}, {P, 30, 0}});
  EXPECT_EQ(els[3].line, 4);
}

TEST(ToolCorr, RampModesG0RetractBetweenContourElementsKeepsTheOffset) {
  // In the ramp modes a G0 is part of the contour; one that does not move in the plane goes
  // with the tool like a G1 plunge.  It once went to its programmed point, so the corner arc
  // after it started at its own centre (found by tests/fuzz/path_fuzz.cpp,
  // path_regressions/tc-rampin-g0-retract-between-contours.cnc).
  for (ToolCorrMode m : {ToolCorrMode::RampIn, ToolCorrMode::BlindIn}) {
    SCOPED_TRACE(static_cast<int>(m));
    auto els = corrected("N10 G42 D1\nN20 G1 X10 Y0 F100\nN30 G0 Z5\nN40 G1 X10 Y10\nN50 G40\n", m);
    if (m == ToolCorrMode::RampIn) {
      expectPath(els, {{L, 10, -1}, {P, 10, -1}, {CCW, 11, 0, 10, 0, kPi / 2}, {L, 11, 10}});
    } else {
      // TC_BLIND_IN: the entry goes straight to the offset start of the second element.
      expectPath(els, {{L, 11, 0}, {P, 11, 0}, {L, 11, 10}});
    }
    ASSERT_GE(els.size(), 2u);
    EXPECT_EQ(els[1].end[AxZ], 5.0);
  }
}

TEST(ToolCorr, HelixEntryAtAnotherHeightReachesItsProgrammedEnd) {
  // TC_RAMP_IN: the G18 section leaves the tool 1 above the programmed Z; the G17 section
  // that follows enters from there.  Its helix kept the programmed rise (20), so the arc's
  // geometry ended at Z 21, not at its end point Z 20 (found by tests/fuzz/path_fuzz.cpp,
  // path_regressions/tc-helix-entry-from-other-plane.cnc).
  auto els = corrected("N10 G18\nN20 G42 D1\nN30 G1 X10 Z0 F100\nN40 G40\nN50 G17\nN60 G41 D1\n"
                       "N70 G3 X0 Y10 Z20 I-10 J0\nN80 G40\n",
                       ToolCorrMode::RampIn);
  ASSERT_EQ(els.size(), 2u);
  expectPos(els[0].end, {10, 0, 1});
  EXPECT_EQ(els[1].type, CCW);
  expectPos(els[1].end, {0, 9, 20});
  EXPECT_NEAR(els[1].arc.rise, 19, kTol);
  expectConsistent(els);
}

TEST(ToolCorr, ReversalGoesRoundTheEnd) {
  auto els = corrected("N10 G41 D1\nN20 G1 X10 F10\nN30 G1 X0\nN40 G40\n", ToolCorrMode::BlindPos);
  expectPath(els, {{P, 0, 1}, {L, 10, 1}, {CW, 10, -1, 10, 0, -kPi}, {L, 0, -1}, {P, 0, 0}});
}

TEST(ToolCorr, ArcsAreOffsetConcentrically) {
  // A counter-clockwise half circle of radius 5 about (5,0): left (inside) radius 4, right 6.
  auto left = corrected("N10 G41 D1\nN20 G3 X10 Y0 I5 J0 F10\nN30 G40\n", ToolCorrMode::BlindPos);
  expectPath(left, {{P, 1, 0}, {CCW, 9, 0, 5, 0, kPi}, {P, 10, 0}});
  EXPECT_NEAR(left[1].arc.radius, 4, kTol);
  auto right = corrected("N10 G42 D1\nN20 G3 X10 Y0 I5 J0 F10\nN30 G40\n", ToolCorrMode::BlindPos);
  expectPath(right, {{P, -1, 0}, {CCW, 11, 0, 5, 0, kPi}, {P, 10, 0}});
  EXPECT_NEAR(right[1].arc.radius, 6, kTol);
}

TEST(ToolCorr, LineArcInsideCornerIsCutAtTheIntersection) {
  // Along +X to (10,0), then a counter-clockwise quarter of radius 10 about (10,10): a tangent
  // join; then back along -X from (20,10): an inside corner for G41 with a closed form.
  auto els = corrected("N10 G41 D2\nN20 G1 X10 F10\nN30 G3 X20 Y10 I0 J10\nN40 G1 X10 Y10\nN50 G40\n",
                       ToolCorrMode::BlindPos);
  // Offsets: the line y = 2, the arc radius 8 about (10,10), the last line y = 8 (left of -X
  // is -Y).  The arc meets y = 8 at x = 10 + sqrt(64 - 4).
  const double x = 10 + std::sqrt(60.0);
  expectPath(els, {{P, 0, 2}, {L, 10, 2}, {CCW, x, 8, 10, 10, std::atan2(-2.0, x - 10) + kPi / 2}, {L, 10, 8}, {P, 10, 10}});
}

TEST(ToolCorr, ArcSmallerThanTheToolIsAnError) {
  ToolCorrError err{};
  auto els = corrected("N10 G41 D5\nN20 G1 X10 F10\nN30 G3 X10 Y4 I0 J2\nN40 G1 X0\nN50 G40\n", ToolCorrMode::BlindPos, &err);
  EXPECT_EQ(err, ToolCorrError::ArcSmallerThanTool);
  ASSERT_EQ(els.size(), 1u);   // the positioning; the line waited for its corner
  Decoded d("N10 G41 D5\nN20 G1 X10 F10\nN30 G3 X10 Y4 I0 J2\n");
  ToolCorrector tc(ToolCorrMode::BlindPos);
  for (const Element& e : d.els) tc.push(e);
  EXPECT_EQ(tc.errorLine(), 3);
  EXPECT_EQ(tc.errorMessage(), "line 3: the arc of radius 2 is smaller than the tool radius 5 on its concave side");
}

TEST(ToolCorr, RefusedElementsUnderCorrection) {
  ToolCorrError err{};
  corrected("N10 G41 D1\nN20 G1 X10 F10\nN30 G5 X20 Y5\nN40 G40\n", ToolCorrMode::BlindPos, &err);
  EXPECT_EQ(err, ToolCorrError::NotInPlane);
  corrected("N10 G41 D1\nN20 G1 X10 F10\nN30 G92 X0 Y0\nN40 G1 X5\n", ToolCorrMode::BlindPos, &err);
  EXPECT_EQ(err, ToolCorrError::NotInPlane);
  corrected("N10 G41 D1\nN20 G1 X10 F10\nN30 G18 G1 X20\n", ToolCorrMode::BlindPos, &err);
  EXPECT_EQ(err, ToolCorrError::NotInPlane);
  // G5 outside a section passes.
  auto els = corrected("N10 G1 X10 F10\nN30 G5 X20 Y5\n", ToolCorrMode::BlindPos, &err);
  EXPECT_EQ(err, ToolCorrError::None);
  EXPECT_EQ(els.size(), 2u);
}

TEST(ToolCorr, LookAheadIsBounded) {
  std::string text = "N1 G41 D1\nN2 G1 X10 F10\n";
  for (int i = 0; i < 70; ++i) text += "N" + std::to_string(10 + i) + " M" + std::to_string(10 + i) + "\n";
  text += "N100 G1 Y10\n";
  ToolCorrError err{};
  corrected(text, ToolCorrMode::BlindPos, &err);
  EXPECT_EQ(err, ToolCorrError::LookAheadExceeded);
}

// Radius 0 (D0 without a default) and programs without G41/G42 come out unchanged, bit for bit.
TEST(ToolCorr, RadiusZeroAndNoCorrectionPassThrough) {
  for (const char* text : {"N10 G41 D0\nN20 G1 X10 Y3 F10\nN30 G2 X20 Y3 R7\nN35 M5\nN40 G0 X1\nN50 G40\n",
                           "N10 G1 X10 Y3 F10\nN30 G2 X20 Y3 R7\nN35 G4 T1\nN40 G0 X1\nN45 G5 X4 Y4\nN50 G92 X0 Y0\n"}) {
    for (ToolCorrMode m : {ToolCorrMode::BlindPos, ToolCorrMode::BlindIn, ToolCorrMode::RampIn}) {
      Decoded d(text);
      ToolCorrError err{};
      auto els = correctAll(d.els, m, 0, &err);
      EXPECT_EQ(err, ToolCorrError::None);
      ASSERT_EQ(els.size(), d.els.size());
      for (size_t i = 0; i < els.size(); ++i) EXPECT_EQ(std::memcmp(&els[i], &d.els[i], sizeof(Element)), 0) << text << i;
    }
  }
}

TEST(ToolCorr, DefaultRadiusWhenDIsZero) {
  auto els = corrected(square("G41").replace(4, 6, "G41 D0"), ToolCorrMode::BlindPos, nullptr, 1.0);
  expectPath(els, {{P, 0, 1}, {L, 9, 1}, {L, 9, 9}, {L, 1, 9}, {L, 1, 0}, {P, -5, -5}});
  ToolCorrector tc;
  EXPECT_FALSE(tc.setDefaultRadius(-1));
  EXPECT_FALSE(tc.setDefaultRadius(std::nan("")));
  EXPECT_TRUE(tc.setDefaultRadius(2));
}

TEST(ToolCorr, ZxPlane) {
  // G18: the frame is (Z, X) with the normal +Y; left of travel along +Z is +X.
  auto els = corrected("N10 G18 G41 D1\nN20 G1 Z10 F10\nN30 G1 Z10 X10\nN40 G40\n", ToolCorrMode::BlindPos);
  // From +Z to +X is a left turn about +Y: an inside corner for G41, cut at X1 Z9.
  ASSERT_EQ(els.size(), 4u);
  expectPos(els[0].end, {1, 0, 0});
  expectPos(els[1].end, {1, 0, 9});
  expectPos(els[2].end, {10, 0, 9});
  expectPos(els[3].end, {10, 0, 10});
  expectChained(els);
  // G42: an outside corner, an arc about X0 Z10 in the ZX frame.
  els = corrected("N10 G18 G42 D1\nN20 G1 Z10 F10\nN30 G1 Z10 X10\nN40 G40\n", ToolCorrMode::BlindPos);
  ASSERT_EQ(els.size(), 5u);
  expectPos(els[1].end, {-1, 0, 10});
  EXPECT_EQ(els[2].type, CCW);   // the corner arc turns with the path
  EXPECT_EQ(els[2].plane, Plane::ZX);
  expectPos(els[2].end, {0, 0, 11});
  EXPECT_NEAR(els[2].arc.sweep, kPi / 2, kTol);
  expectChained(els);
  expectConsistent(els);
}

// ---- the distance property on random contours

double distToSegment(Vec3 p, Vec3 a, Vec3 b) {
  Vec3 d = b - a;
  double t = dot(p - a, d) / dot(d, d);
  t = std::clamp(t, 0.0, 1.0);
  return norm(p - (a + t * d));
}
double distToArc(Vec3 p, const Element& e) {
  const ArcGeo& g = e.arc;
  Vec3 q = p - g.centre;
  double ang = std::atan2(dot(q, g.v), dot(q, g.u));
  // Is ang inside the swept range?
  double rel = std::remainder(ang - g.startAngle, 2 * kPi);
  if (g.sweep > 0 && rel < 0) rel += 2 * kPi;
  if (g.sweep < 0 && rel > 0) rel -= 2 * kPi;
  if (std::fabs(rel) <= std::fabs(g.sweep)) return std::fabs(std::hypot(dot(q, g.u), dot(q, g.v)) - g.radius);
  return std::min(norm(p - xyz(e.start)), norm(p - xyz(e.end)));
}
double distToContour(Vec3 p, const std::vector<Element>& contour) {
  double best = 1e300;
  for (const Element& e : contour) {
    double d = e.type == MoveType::Lin ? distToSegment(p, xyz(e.start), xyz(e.end)) : distToArc(p, e);
    best = std::min(best, d);
  }
  return best;
}

// Corrects `program` (a closed contour under G41/G42 D r, TC_BLIND_POS) and checks every
// tool-centre sample is at r from the programmed contour; counts the samples.
void expectAtTheRadius(const std::string& program, double r, int& samples) {
  Decoded d(program);
  ASSERT_EQ(d.errors(), 0u) << d.all();
  std::vector<Element> contour;
  for (const Element& e : d.els)
    if (e.type == L || e.type == CW || e.type == CCW) contour.push_back(e);
  ToolCorrError err{};
  auto out = correctAll(d.els, ToolCorrMode::BlindPos, 0, &err);
  ASSERT_EQ(err, ToolCorrError::None) << program;
  expectChained(out);
  expectConsistent(out);
  for (const Element& e : out) {
    if (e.type == P) continue;
    for (int k = 0; k <= 10; ++k) {
      const Vec3 q = xyz(point(e, k / 10.0));
      ASSERT_NEAR(distToContour(q, contour), r, 1e-9) << program << " element line " << e.line << " u " << k / 10.0;
      ++samples;
    }
  }
}

TEST(ToolCorrProperty, ToolCentreStaysAtTheRadius) {
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> U(0, 1);
  int samples = 0;
  for (int prog = 0; prog < 200; ++prog) {
    const int n = 3 + static_cast<int>(U(rng) * 5);
    const double rad = 20 + 30 * U(rng);
    std::vector<std::pair<double, double>> pts;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * kPi * (i + 0.3 * (U(rng) - 0.5)) / n;
      pts.push_back({rad * std::cos(a), rad * std::sin(a)});
    }
    const bool left = U(rng) < 0.5;       // ccw contour: left = inside, right = outside
    const double r = std::round((left ? 0.05 + 0.9 * U(rng) : 0.1 + 5 * U(rng)) * 1e6) / 1e6;   // as written
    std::ostringstream g;
    g.precision(17);
    // The contour starts and ends in the middle of its first edge (a line), so that the
    // closing vertex is a corner like the others (entry and exit meet on a straight line).
    const double mx = (pts[0].first + pts[1].first) / 2, my = (pts[0].second + pts[1].second) / 2;
    g << std::fixed << std::setprecision(6) << "N1 G0 X" << mx << " Y" << my << "\n";
    g << "N2 " << (left ? "G41" : "G42") << " D" << r << "\n";
    g << "N3 G1 X" << pts[1].first << " Y" << pts[1].second << " F10\n";
    for (int i = 2; i <= n; ++i) {
      const auto& q = pts[static_cast<size_t>(i % n)];
      const auto& p0 = pts[static_cast<size_t>(i - 1)];
      const double chord = std::hypot(q.first - p0.first, q.second - p0.second);
      if (U(rng) < 0.5)
        g << "N" << 10 + i << " G1 X" << q.first << " Y" << q.second << " F10\n";
      else   // an outward bulge: counter-clockwise, radius 2..6 chords
        g << "N" << 10 + i << " G3 X" << q.first << " Y" << q.second << " R" << chord * (2 + 4 * U(rng)) << " F10\n";
    }
    g << "N80 G1 X" << mx << " Y" << my << "\n";
    g << "N90 G40\nN91 G0 X0 Y0\n";
    expectAtTheRadius(g.str(), r, samples);
  }
  EXPECT_GT(samples, 10000);
}

// Star-shaped contours of lines and arcs bulging either way: concave and convex corners
// alternate, so half the corners are inside ones (cut at the intersection of the offset
// elements) whichever side the tool is on.
// No gouge: every point of the tool centre's path stays exactly at the radius from the
// programmed contour (an inside corner cut too short or too long would come closer or leave).
TEST(ToolCorrProperty, StarContoursKeepTheRadiusAtInsideAndOutsideCorners) {
  std::mt19937 rng(61);
  std::uniform_real_distribution<double> U(0, 1);
  int samples = 0;
  for (int prog = 0; prog < 200; ++prog) {
    const int n = 5 + static_cast<int>(U(rng) * 5);   // star points
    const double outer = 20 + 30 * U(rng), inner = outer * (0.5 + 0.3 * U(rng));
    std::vector<std::pair<double, double>> pts;
    for (int i = 0; i < 2 * n; ++i) {
      const double a = kPi * (i + 0.2 * (U(rng) - 0.5)) / n;
      const double rr = i % 2 ? inner : outer;
      pts.push_back({rr * std::cos(a), rr * std::sin(a)});
    }
    // A radius small against every edge and against the inside corners' reach.
    double shortest = 1e300;
    for (size_t i = 0; i < pts.size(); ++i) {
      const auto& p0 = pts[i];
      const auto& p1 = pts[(i + 1) % pts.size()];
      shortest = std::min(shortest, std::hypot(p1.first - p0.first, p1.second - p0.second));
    }
    const bool left = U(rng) < 0.5;
    const double r = std::round((0.01 + 0.1 * U(rng)) * shortest * 1e6) / 1e6;
    std::ostringstream g;
    const double mx = (pts[0].first + pts[1].first) / 2, my = (pts[0].second + pts[1].second) / 2;
    g << std::fixed << std::setprecision(6) << "N1 G0 X" << mx << " Y" << my << "\n";
    g << "N2 " << (left ? "G41" : "G42") << " D" << r << "\n";
    for (size_t i = 1; i <= pts.size(); ++i) {
      const auto& q = pts[i % pts.size()];
      const auto& p0 = pts[i - 1];
      const double chord = std::hypot(q.first - p0.first, q.second - p0.second);
      const double pick = U(rng);
      // Lines, and arcs bulging outwards (G3) or inwards (G2) of radius 2..6 chords; the
      // first edge is a line, collinear with the closing one (start and end in its middle).
      if (i == 1 || i == pts.size() || pick < 0.5)
        g << "N" << 10 + i << " G1 X" << q.first << " Y" << q.second << " F10\n";
      else
        g << "N" << 10 + i << (pick < 0.75 ? " G3" : " G2") << " X" << q.first << " Y" << q.second << " R" << chord * (2 + 4 * U(rng))
          << " F10\n";
    }
    g << "N80 G1 X" << mx << " Y" << my << "\n";
    g << "N90 G40\nN91 G0 X0 Y0\n";
    expectAtTheRadius(g.str(), r, samples);
  }
  EXPECT_GT(samples, 10000);
}

}  // namespace
}  // namespace stc::cnc::test
