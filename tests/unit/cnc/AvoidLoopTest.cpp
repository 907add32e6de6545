// Loop avoidance (stdlib-motion/cnc/AvoidLoop.h, docs/cnc.md "Loop avoidance"): a bow-tie
// of lines, a tool-corrected notch narrower than the tool, the window and G60.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "CncTestUtil.h"
#include "stdlib-motion/cnc/AvoidLoop.h"
#include "stdlib-motion/cnc/ToolCorr.h"

namespace stc::cnc::test {
namespace {

void expectChained(const std::vector<Element>& els) {
  for (size_t i = 1; i < els.size(); ++i)
    for (int a = 0; a < kAxisCount; ++a) ASSERT_EQ(els[i].start[a], els[i - 1].end[a]) << "element " << i;
}

TEST(AvoidLoop, BowTieIsCutAtTheCrossing) {
  // (0,0)->(10,0)->(10,5)->(5,-5)->(5,-10): the third line crosses the first at (7.5, 0).
  Decoded d("N1 G61\nN2 G1 X10 Y0 F10\nN3 G1 X10 Y5\nN4 G1 X5 Y-5\nN5 G1 X5 Y-10\nN6 G60\nN7 G1 X0 Y-10\n");
  ASSERT_EQ(d.els.size(), 5u);
  LoopAvoider la;
  std::vector<Element> out;
  for (const Element& e : d.els) la.push(e);
  la.finish();
  while (la.hasOutput()) {
    out.push_back(la.front());
    la.pop();
  }
  ASSERT_EQ(out.size(), 4u);
  expectPos(out[0].end, {7.5, 0, 0});
  expectPos(out[1].start, {7.5, 0, 0});
  expectPos(out[1].end, {5, -5, 0});
  expectPos(out[2].end, {5, -10, 0});
  expectPos(out[3].end, {0, -10, 0});
  EXPECT_NEAR(out[0].length, 7.5, kTol);
  EXPECT_NEAR(out[1].length, std::hypot(2.5, 5), kTol);
  EXPECT_EQ(la.loopsRemoved(), 1u);
  EXPECT_EQ(la.elementsDropped(), 1u);
  expectChained(out);
}

TEST(AvoidLoop, LineFarFromTheArcCrossesItOnTheCircle) {
  // The line comes from x = 1e8: the crossing with the circle of radius sqrt(21.25) about
  // (33,-4) once had an error of ~0.1 (the discriminant cancelled), so the cut arc started
  // off its circle (found by tests/fuzz/path_fuzz.cpp,
  // path_regressions/loop-line-far-from-arc.cnc).
  Decoded d("N1 G61\nN2 G0 X100000000\nN3 G1 X30 Y0 F10\nN4 G1 Y-0.5\nN5 G2 X30 Y-0.5 I3 J-3.5\n");
  ASSERT_EQ(d.els.size(), 4u);
  auto out = avoidLoopsAll(d.els);
  ASSERT_EQ(out.size(), 3u);   // the short line is the loop's
  // The cut point comes from the line's parameter: 1e-15 of its 1e8 length is ~1e-7.
  constexpr double kLong = 1e-7;
  const double x = 33 - std::sqrt(5.25);
  expectPos(out[1].end, {x, 0, 0}, kLong);
  const Element& arc = out[2];
  ASSERT_EQ(arc.type, MoveType::Clw);
  expectPos(arc.start, {x, 0, 0}, kLong);
  expectPos(arc.end, {30, -0.5, 0});
  const Vec3 s = arc.arc.centre + (arc.arc.radius * std::cos(arc.arc.startAngle)) * arc.arc.u +
                 (arc.arc.radius * std::sin(arc.arc.startAngle)) * arc.arc.v;
  expectVec(s, xyz(arc.start), kLong);   // before: 0.1 off
  expectChained(out);
}

TEST(AvoidLoop, OffWithoutG61) {
  Decoded d("N2 G1 X10 Y0 F10\nN3 G1 X10 Y5\nN4 G1 X5 Y-5\nN5 G1 X5 Y-10\n");
  auto out = avoidLoopsAll(d.els);
  ASSERT_EQ(out.size(), d.els.size());
  for (size_t i = 0; i < out.size(); ++i) EXPECT_EQ(std::memcmp(&out[i], &d.els[i], sizeof(Element)), 0);
}

TEST(AvoidLoop, MFunctionInTheLoopKeepsIt) {
  Decoded d("N1 G61\nN2 G1 X10 Y0 F10\nN3 G1 X10 Y5 M7\nN4 G1 X5 Y-5\nN5 G1 X5 Y-10\n");
  auto out = avoidLoopsAll(d.els);
  EXPECT_EQ(out.size(), d.els.size());
}

TEST(AvoidLoop, NotchNarrowerThanTheToolAfterToolCorr) {
  // A notch 1 wide and 1 deep under a tool of radius 2: ToolCorr's path loops inside it;
  // after AvoidLoop the two corner arcs meet at (10.5, sqrt(3.75)) and the tool centre stays
  // 2 from the contour everywhere.
  Decoded d("N1 G61\nN2 G41 D2\nN3 G1 X10 Y0 F10\nN4 G1 X10 Y-1\nN5 G1 X11 Y-1\nN6 G1 X11 Y0\nN7 G1 X20 Y0\nN8 G40\n");
  ASSERT_EQ(d.errors(), 0u);
  ToolCorrError err{};
  auto corr = correctAll(d.els, ToolCorrMode::BlindPos, 0, &err);
  ASSERT_EQ(err, ToolCorrError::None);
  auto out = avoidLoopsAll(corr);
  ASSERT_EQ(out.size(), 6u);
  const double y = std::sqrt(3.75);
  EXPECT_EQ(out[0].type, MoveType::LinPos);
  expectPos(out[1].end, {10, 2, 0});
  EXPECT_EQ(out[2].type, MoveType::Clw);
  expectPos(out[2].end, {10.5, y, 0});
  EXPECT_EQ(out[3].type, MoveType::Clw);
  expectPos(out[3].start, {10.5, y, 0});
  expectPos(out[3].end, {11, 2, 0});
  expectPos(out[4].end, {20, 2, 0});
  expectChained(out);
  for (const Element& e : out) {
    if (e.type == MoveType::LinPos) continue;
    for (int k = 0; k <= 20; ++k) {
      const Vec3 q = xyz(point(e, k / 20.0));
      double best = 1e300;
      for (const Element& c : d.els) {
        if (c.type != MoveType::Lin) continue;
        const Vec3 a = xyz(c.start), b = xyz(c.end), dd = b - a;
        const double t = std::clamp(dot(q - a, dd) / dot(dd, dd), 0.0, 1.0);
        best = std::min(best, norm(q - (a + t * dd)));
      }
      EXPECT_NEAR(best, 2, kTol) << "line " << e.line << " u " << k / 20.0;
    }
    if (e.type == MoveType::Clw) {   // the cut arcs are consistent
      Vec3 s = e.arc.centre + (e.arc.radius * std::cos(e.arc.startAngle)) * e.arc.u +
               (e.arc.radius * std::sin(e.arc.startAngle)) * e.arc.v;
      expectVec(s, xyz(e.start));
      expectVec(xyz(point(e, 1 - 1e-15)), xyz(e.end), 1e-9);
    }
  }
}

TEST(AvoidLoop, LoopsLongerThanTheWindowStay) {
  // The crossing line comes 40 elements after the line it crosses: beyond the window of 32.
  std::string t = "N1 G61\nN2 G1 X10 Y0 F10\n";
  for (int i = 0; i < 40; ++i) t += "N" + std::to_string(10 + i) + " G1 X10 Y" + std::to_string(i + 1) + "\n";
  t += "N90 G1 X5 Y-5\n";
  Decoded d(t);
  auto out = avoidLoopsAll(d.els);
  EXPECT_EQ(out.size(), d.els.size());
}

}  // namespace
}  // namespace stc::cnc::test
