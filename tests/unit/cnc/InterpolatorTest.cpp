// cnc::Interpolator (the core of SMC_Interpolator, docs/cnc.md): set points on the
// elements to 1e-9, the feed at F between ramps, stops at corners, tangent junctions
// passed at speed, M handshake, dwell, H switches at exact positions, holds, override,
// a 10,000-block program through a small window.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

#include "CncTestUtil.h"
#include "stdlib-motion/cnc/Interpolator.h"
#include "stdlib-motion/cnc/Interpolator2Dir.h"
#include "stdlib-motion/cnc/PathSegment.h"

namespace stc::cnc::test {
namespace {

constexpr double kCycle = 0.001;

struct IpoRun {
  std::vector<Element> els;
  std::unique_ptr<Interpolator> ipo;
  size_t fed = 0, finished = 0;
  std::vector<IpoOutput> outs;
  IpoControls ctl;
  bool keep = true;   // keep every output (not for long runs)

  explicit IpoRun(const std::string& program, IpoSettings cfg = {}) {
    Decoded d(program);
    EXPECT_EQ(d.errors(), 0u);
    els = d.els;
    checkVelocities(els);
    cfg.cycle = kCycle;
    int16_t err = 0;
    ipo = std::make_unique<Interpolator>(cfg, err);
    EXPECT_EQ(err, 0);
  }
  const IpoOutput& step() {
    while (fed < els.size() && ipo->wantsMore()) EXPECT_EQ(ipo->feed(els[fed++]), 0);
    if (fed == els.size()) ipo->endOfList();
    const IpoOutput& o = ipo->step(ctl);
    finished += ipo->takeFinished();
    if (keep) outs.push_back(o);
    return o;
  }
  int runToEnd(int maxCycles = 1000000) {
    for (int i = 0; i < maxCycles; ++i)
      if (step().finished) return i + 1;
    return -1;
  }
};

TEST(Interpolator, LineTrapezoidClosedForm) {
  // 10 units at F 10 with E 100: 0.1 s ramps, 0.9 s at F: 1.1 s in all.
  IpoRun r("G1 X10 F10 E100 E-100\n");
  const int cycles = r.runToEnd();
  EXPECT_EQ(cycles, 1100);   // the cycle that reaches the end reports Finished
  double vmax = 0;
  for (const IpoOutput& o : r.outs) {
    EXPECT_EQ(o.pos[AxY], 0.0);
    vmax = std::max(vmax, o.vel);
  }
  EXPECT_NEAR(vmax, 10.0, 1e-9);
  EXPECT_EQ(r.outs.back().pos[AxX], 10.0);
  EXPECT_EQ(r.outs.back().status, IpoStatus::Finished);
  // at t = 0.05 s: x = 1/2 a t^2
  EXPECT_NEAR(r.outs[49].pos[AxX], 0.5 * 100 * 0.05 * 0.05, 1e-9);
  EXPECT_EQ(r.outs[49].status, IpoStatus::Accel);
  EXPECT_EQ(r.outs[500].status, IpoStatus::Constant);
  EXPECT_EQ(r.outs[1050].status, IpoStatus::Decel);
  EXPECT_EQ(r.finished, 1u);
}

TEST(Interpolator, SetPointsStayOnEveryElementType) {
  const char* prog =
      "G1 X10 F20 E200 E-200\n"
      "G3 X20 Y10 I0 J10\n"
      "G2 X30 Y20 R10\n"
      "G17 G2 X30 Y20 Z5 I5 J0\n"      // a full helix turn
      "G5 X40 Y25\nG5 X50 Y20\n"
      "G6 X60 Y20 I55 J25\n"
      "G8 X70 Y20 I65 J20 K0 R0.5\n"
      "G0 X0 Y0 Z0\n";
  IpoRun r(prog);
  ASSERT_GT(r.runToEnd(), 0);
  // every set point lies on one of the elements
  double worst = 0;
  for (const IpoOutput& o : r.outs) {
    // the element in control, or its neighbour at a junction
    double best = 1e300;
    for (int k = o.objNo - 2; k <= o.objNo; ++k)
      if (k >= 0 && k < int(r.els.size()) && isMotion(r.els[k].type)) best = std::min(best, distanceToElement(r.els[k], o.pos));
    worst = std::max(worst, best);
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_EQ(r.outs.back().pos[AxX], 0.0);
  EXPECT_EQ(r.finished, r.els.size());
}

TEST(Interpolator, StopsAtCornersRunsAtFeedBetween) {
  IpoRun r("G1 X10 F10 E100 E-100\nG1 Y10\nG1 X0\n");
  ASSERT_GT(r.runToEnd(), 0);
  int stops = 0;
  for (size_t i = 1; i < r.outs.size(); ++i)
    if (r.outs[i].vel == 0 && r.outs[i - 1].vel > 0) ++stops;
  EXPECT_EQ(stops, 3);   // two corners and the end
  // every corner is reached exactly
  bool sawCorner1 = false;
  for (const IpoOutput& o : r.outs) sawCorner1 |= (o.pos[AxX] == 10.0 && o.pos[AxY] == 0.0);
  EXPECT_TRUE(sawCorner1);
  for (const IpoOutput& o : r.outs) EXPECT_LE(o.vel, 10.0 + 1e-9);
}

TEST(Interpolator, TangentJunctionsPassedAtFeed) {
  // line, tangent quarter arc, tangent line: no stop in between
  IpoRun r("G1 X10 F10 E100 E-100\nG3 X20 Y10 I0 J10\nG1 Y20\n");
  ASSERT_GT(r.runToEnd(), 0);
  const double arcStart = 10, arcEnd = 10 + 10 * M_PI / 2;
  for (const IpoOutput& o : r.outs)
    if (o.wayPos > arcStart - 0.5 && o.wayPos < arcEnd + 0.5) {
      EXPECT_NEAR(o.vel, 10.0, 1e-9) << o.wayPos;
    }
}

// A chain of short tangent G5 splines behind a tighter one (the first spline after the
// line bends hard): each spline's curvature allows more than F, so the path runs at F
// there.  The path planner used to plan consecutive short trapezoidal slots as one run
// at the lowest cap in it and crept through the whole chain at the first spline's cap
// (57.5 u/s here: 5526 cycles instead of 1863).  Checked against SMC_Interpolator2Dir,
// which plans the same caps independently, and against every element's own cap.
TEST(Interpolator, ShortSplinesBehindATightCurveRegainTheFeed) {
  std::string prog = "G1 X0 Y10 F200 E2000 E-2000\n";
  char buf[80];
  for (int k = 1; k <= 30; ++k) {
    std::snprintf(buf, sizeof buf, "G5 X%.4f Y%.4f\n", 10.0 * k, 10.0 + 3.0 * std::sin(k * 0.9));
    prog += buf;
  }
  IpoRun r(prog);
  // Each element's cap: F, or sqrt(E / max curvature) on curves.
  std::vector<double> cap, end;
  double way = 0;
  for (const Element& e : r.els) {
    stc::motion::path::Segment seg;
    ASSERT_TRUE(buildPathSegment(e, seg));
    const double k = seg.maxCurvature();
    cap.push_back(k > 0 ? std::min(e.vel, std::sqrt(e.acc / k)) : e.vel);
    end.push_back(way += seg.length());
  }
  ASSERT_LT(cap[1], 100.0);   // the tight first spline
  for (size_t i = 2; i < cap.size(); ++i) ASSERT_EQ(cap[i], 200.0) << i;
  const int cycles = r.runToEnd();
  ASSERT_GT(cycles, 0);
  bool atFeed = false;
  for (const IpoOutput& o : r.outs) {
    const size_t i = std::lower_bound(end.begin(), end.end(), o.wayPos) - end.begin();
    if (i < cap.size()) {
      EXPECT_LE(o.vel, cap[i] * (1 + 1e-9)) << o.wayPos;
    }
    atFeed = atFeed || (o.wayPos > end[3] && o.wayPos < end[27] && std::fabs(o.vel - 200.0) < 1e-9);
  }
  EXPECT_TRUE(atFeed);
  // The independent plan of SMC_Interpolator2Dir over the same elements.
  Ipo2DirSettings c2;
  c2.ipo.cycle = kCycle;
  int16_t err = 0;
  Interpolator2Dir two(c2, err);
  ASSERT_EQ(err, 0);
  size_t fed = 0;
  int cycles2 = 0;
  for (; cycles2 < 1000000; ++cycles2) {
    while (fed < r.els.size() && two.wantsMore()) two.feed(r.els[fed++]);
    if (fed == r.els.size()) two.endOfList();
    const IpoOutput& o = two.step(IpoControls{});
    two.takeReleased();
    if (o.finished) break;
  }
  EXPECT_LE(std::abs(cycles - (cycles2 + 1)), 1) << cycles << " vs " << cycles2 + 1;
  EXPECT_LT(cycles, 2000);
}

TEST(Interpolator, MFunctionWaitsForAcknowledge) {
  IpoRun r("G1 X10 F10 E100 E-100\nM7 K2 L3\nG1 X20\n");
  int firstWait = -1;
  for (int i = 0; i < 3000; ++i) {
    const IpoOutput& o = r.step();
    if (o.m == 7 && firstWait < 0) firstWait = i;
  }
  ASSERT_GE(firstWait, 0);
  EXPECT_EQ(firstWait, 1100 - 1);   // wM in the cycle that reaches the stop (the 1100th)
  const IpoOutput& w = r.outs.back();
  EXPECT_EQ(w.m, 7);
  EXPECT_EQ(w.mK, 2.0);
  EXPECT_EQ(w.mL, 3.0);
  EXPECT_EQ(w.status, IpoStatus::Wait);
  EXPECT_EQ(w.pos[AxX], 10.0);
  r.ctl.acknM = true;
  const IpoOutput& a = r.step();
  EXPECT_EQ(a.m, 0);
  EXPECT_GT(a.pos[AxX], 10.0);   // moving again in the cycle of the acknowledgement
  r.ctl.acknM = false;
  EXPECT_GT(r.runToEnd(), 0);
  EXPECT_EQ(r.outs.back().pos[AxX], 20.0);
}

TEST(Interpolator, DwellHoldsAtLeastItsTime) {
  IpoRun r("G1 X10 F10 E100 E-100\nG4 T0.25\nG1 X20\n");
  ASSERT_GT(r.runToEnd(), 0);
  int standing = 0;
  bool after = false;
  for (const IpoOutput& o : r.outs) {
    if (o.pos[AxX] == 10.0) ++standing;
    after |= o.pos[AxX] > 10.0;
  }
  EXPECT_TRUE(after);
  EXPECT_GE(standing * kCycle, 0.25 - 1e-12);
  EXPECT_LE(standing * kCycle, 0.25 + 2 * kCycle);
}

TEST(Interpolator, SwitchPointsAtTheirPathPosition) {
  // H1 on 2 units after the start, H-1 off 3 units before the end (of 10)
  IpoRun r("G1 X10 F10 E100 E-100 H1 L2 H-1 L-3\n");
  ASSERT_GT(r.runToEnd(), 0);
  int onAt = -1, offAt = -1;
  for (size_t i = 0; i < r.outs.size(); ++i) {
    if (onAt < 0 && (r.outs[i].switches & 1)) onAt = int(i);
    if (onAt >= 0 && offAt < 0 && !(r.outs[i].switches & 1)) offAt = int(i);
  }
  ASSERT_GE(onAt, 0);
  ASSERT_GE(offAt, 0);
  EXPECT_GE(r.outs[onAt].pos[AxX], 2.0);
  EXPECT_LT(r.outs[onAt - 1].pos[AxX], 2.0);
  EXPECT_GE(r.outs[offAt].pos[AxX], 7.0);
  EXPECT_LT(r.outs[offAt - 1].pos[AxX], 7.0);
  EXPECT_EQ(r.outs[offAt].lastSwitch, -1);
}

TEST(Interpolator, SlowStopHoldsOnThePathAndResumes) {
  IpoRun r("G1 X100 F10 E100 E-100\n");
  for (int i = 0; i < 500; ++i) r.step();
  r.ctl.slowStop = true;
  double x = 0;
  for (int i = 0; i < 300; ++i) x = r.step().pos[AxX];
  EXPECT_EQ(r.outs.back().vel, 0.0);
  EXPECT_EQ(r.outs.back().status, IpoStatus::Wait);
  // braking from 10 at 100: 0.5 units after the request
  EXPECT_NEAR(x, r.outs[499].pos[AxX] + 0.5, 0.02);
  r.ctl.slowStop = false;
  ASSERT_GT(r.runToEnd(), 0);
  EXPECT_EQ(r.outs.back().pos[AxX], 100.0);
}

TEST(Interpolator, EmergencyStopFreezesAtOnce) {
  IpoRun r("G1 X100 F10 E100 E-100\n");
  for (int i = 0; i < 500; ++i) r.step();
  const double x = r.outs.back().pos[AxX];
  r.ctl.emergencyStop = true;
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(r.step().pos[AxX], x, 1e-12);
  EXPECT_EQ(r.outs.back().status, IpoStatus::Wait);
  r.ctl.emergencyStop = false;
  ASSERT_GT(r.runToEnd(), 0);
  EXPECT_EQ(r.outs.back().pos[AxX], 100.0);
}

TEST(Interpolator, OverrideScalesFeedWithinAcceleration) {
  IpoRun r("G1 X100 F10 E100 E-100\n");
  r.ctl.override = 0.5;
  for (int i = 0; i < 2000; ++i) r.step();
  EXPECT_NEAR(r.outs.back().vel, 5.0, 1e-9);
  r.ctl.override = 1.5;
  double prev = r.outs.back().vel, maxJump = 0;
  for (int i = 0; i < 500; ++i) {
    const double v = r.step().vel;
    maxJump = std::max(maxJump, std::fabs(v - prev));
    prev = v;
  }
  EXPECT_NEAR(prev, 15.0, 1e-9);
  EXPECT_LE(maxJump, 100 * kCycle * 1.5 * 1.5 + 1e-9);   // within E (time scaling: E x override^2)
  r.ctl.override = 7;   // beyond 0..2
  r.step();
  EXPECT_EQ(r.ipo->error(), kIpoInvalidParameter);
}

TEST(Interpolator, BadSettingsAndElements) {
  int16_t err = 0;
  IpoSettings s;
  s.cycle = 0;
  Interpolator a(s, err);
  EXPECT_EQ(err, kIpoIpoTimeZero);
  s.cycle = 0.001;
  s.mode = VelMode::Sigmoid;
  s.jerk = 0;
  Interpolator b(s, err);
  EXPECT_EQ(err, kIpoJerkNonPositive);
  s.mode = static_cast<VelMode>(9);
  Interpolator c(s, err);
  EXPECT_EQ(err, kIpoInvalidVelMode);
  // an element without F
  Decoded d("G1 X10\n");
  s.mode = VelMode::Trapezoid;
  Interpolator e(s, err);
  EXPECT_EQ(e.feed(d.els[0]), kIpoVelZero);
  EXPECT_EQ(e.error(), kIpoVelZero);
}

TEST(Interpolator, SigmoidHasJerkPhases) {
  IpoSettings s;
  s.mode = VelMode::Sigmoid;
  s.jerk = 1000;
  IpoRun r("G1 X10 F10 E100 E-100\n", s);
  ASSERT_GT(r.runToEnd(), 0);
  bool inc = false, dec = false, incD = false, decD = false;
  for (const IpoOutput& o : r.outs) {
    inc |= o.status == IpoStatus::IncreasingAccel;
    dec |= o.status == IpoStatus::DecreasingAccel;
    incD |= o.status == IpoStatus::IncreasingDecel;
    decD |= o.status == IpoStatus::DecreasingDecel;
  }
  EXPECT_TRUE(inc && dec && incD && decD);
  EXPECT_EQ(r.outs.back().pos[AxX], 10.0);
}

TEST(Interpolator, TenThousandBlocksThroughASmallWindow) {
  std::string prog = "G1 X0.5 F100 E1000 E-1000\n";
  for (int i = 1; i < 10000; ++i) prog += (i % 2 ? "G1 Y" : "G1 X") + std::to_string((i + 1) / 2 * 0.5 + 0.5) + "\n";
  IpoRun r(prog);
  r.keep = false;
  size_t maxInFlight = 0;
  int cycles = 0;
  for (; cycles < 10000000; ++cycles) {
    const IpoOutput& o = r.step();
    maxInFlight = std::max<size_t>(maxInFlight, r.ipo->inFlight());
    if (o.finished) break;
  }
  EXPECT_TRUE(r.ipo->output().finished);
  EXPECT_EQ(r.finished, 10000u);
  EXPECT_LE(maxInFlight, size_t(Interpolator::kMaxInFlight));
}

}  // namespace
}  // namespace stc::cnc::test
