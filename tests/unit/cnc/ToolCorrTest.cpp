// Tool radius correction (stdlib-motion/cnc/ToolCorr.h, docs/cnc.md "Tool radius
// correction"): closed-form corners, entry and exit per mode, the distance property on
// random contours, errors and degenerate input.
#include <cmath>
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

}  // namespace
}  // namespace stc::cnc::test
