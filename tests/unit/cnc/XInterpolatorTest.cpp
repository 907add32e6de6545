// cnc::XInterpolator (the core of SMC_XInterpolator, docs/cnc.md): the set point at a
// given X on lines and arcs against closed forms, before the start, at the end, steps
// without X extent, the negative direction, paths not unique in X, H switches.
#include <gtest/gtest.h>

#include <cmath>

#include "CncTestUtil.h"
#include "stdlib-motion/cnc/XInterpolator.h"

namespace stc::cnc::test {
namespace {

struct XRun {
  std::vector<Element> els;
  XInterpolator ipo;
  size_t fed = 0, finished = 0;

  XRun(const std::string& program, int dir) : ipo(dir) {
    Decoded d(program);
    EXPECT_EQ(d.errors(), 0u);
    els = d.els;
  }
  const IpoOutput& at(double x) {
    while (fed < els.size() && ipo.wantsMore())
      if (ipo.feed(els[fed++]) != 0) break;
    if (fed == els.size()) ipo.endOfList();
    const IpoOutput& o = ipo.step(x);
    finished += ipo.takeFinished();
    return o;
  }
};

TEST(XInterpolator, LineAndArcAtEveryX) {
  // from (0,0): line to (10,5), quarter arc about (10,15) to (20,15), line to (30,15)
  XRun r("G1 X10 Y5 F10\nG3 X20 Y15 I0 J10\nG1 X30\n", 1);
  EXPECT_EQ(r.at(-1).status, IpoStatus::Init);   // not on the path yet: its start
  expectPos(r.ipo.output().pos, {0, 0, 0});
  for (int k = 0; k <= 3000; ++k) {
    const double x = k * 0.01;
    const IpoOutput& o = r.at(x);
    ASSERT_EQ(r.ipo.error(), 0) << x;
    EXPECT_EQ(o.pos[AxX], x);
    double y;
    if (x <= 10) y = 0.5 * x;
    else if (x <= 20) y = 15 - std::sqrt(100 - (x - 10) * (x - 10));
    else y = 15;
    EXPECT_NEAR(o.pos[AxY], y, 1e-9) << x;
  }
  EXPECT_TRUE(r.ipo.output().finished);
  EXPECT_EQ(r.ipo.output().status, IpoStatus::Finished);
  EXPECT_EQ(r.finished, r.els.size());
  EXPECT_NEAR(r.ipo.output().wayPos, std::hypot(10, 5) + 10 * kPi / 2 + 10, 1e-9);
}

TEST(XInterpolator, JitterBackAndBeyondWhatIsKept) {
  XRun r("G1 X1 Y1\nG1 X2 Y0\nG1 X3 Y1\nG1 X4 Y0\nG1 X5 Y1\n", 1);
  r.at(3.5);
  EXPECT_NEAR(r.at(2.5).pos[AxY], 0.5, 1e-12);   // two elements back: kept
  EXPECT_EQ(r.ipo.error(), 0);
  r.at(4.5);
  r.at(1.5);   // three back from the fifth: released
  EXPECT_EQ(r.ipo.error(), kXIpoNoIntersection);
}

TEST(XInterpolator, StepWithoutXExtentIsJumped) {
  XRun r("G1 X10 F10\nG1 Y5\nG1 X20\n", 1);
  EXPECT_EQ(r.at(9.5).pos[AxY], 0.0);
  EXPECT_EQ(r.at(10).pos[AxY], 5.0);   // at X 10 the step is taken
  EXPECT_EQ(r.at(15).pos[AxY], 5.0);
}

TEST(XInterpolator, NegativeDirection) {
  XRun r("G0 X0 Y0\nG1 X-10 Y10 F10\n", -1);
  const IpoOutput& o = r.at(-4);
  EXPECT_EQ(o.pos[AxX], -4.0);
  EXPECT_NEAR(o.pos[AxY], 4.0, 1e-12);
  EXPECT_TRUE(r.at(-10).finished);
  XRun wrong("G1 X10 F10\n", -1);   // X grows along the path: not in the negative direction
  wrong.at(0);
  EXPECT_EQ(wrong.ipo.error(), kXIpoNoIntersection);
}

TEST(XInterpolator, PathNotUniqueInX) {
  XRun r("G1 X10 F10\nG2 X10 Y-10 I0 J-5\nG1 X20\n", 1);   // a half circle bulging to X 15 and back
  r.at(1);
  r.at(5);
  EXPECT_EQ(r.ipo.error(), kXIpoNoIntersection);
  EXPECT_EQ(XInterpolator(0).error(), kXIpoInvalidDirection);
}

TEST(XInterpolator, SwitchesFollowX) {
  XRun r("G1 X10 F10 H3 L4\n", 1);
  EXPECT_EQ(r.at(3.9).switches, 0u);
  EXPECT_EQ(r.at(4.1).switches, 4u);
  EXPECT_EQ(r.at(4.1).lastSwitch, 3);
  EXPECT_EQ(r.at(3.0).switches, 0u);   // back over it
  EXPECT_EQ(r.ipo.output().lastSwitch, -3);
  r.at(std::nan(""));
  EXPECT_EQ(r.ipo.error(), kIpoInvalidParameter);
}

}  // namespace
}  // namespace stc::cnc::test
