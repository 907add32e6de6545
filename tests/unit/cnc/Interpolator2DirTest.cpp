// cnc::Interpolator2Dir (the core of SMC_Interpolator2Dir, docs/cnc.md): forwards the
// same closed-form timing as SMC_Interpolator; a negative override brakes, reverses and
// runs the path backwards on the elements to 1e-9, exactly back to the oldest element
// kept; M functions served once; H switches follow the position; bStartAtEnd; bounded memory.
#include <gtest/gtest.h>

#include <cmath>

#include "CncTestUtil.h"
#include "stdlib-motion/cnc/Interpolator2Dir.h"

namespace stc::cnc::test {
namespace {

constexpr double kCycle = 0.001;

struct Run2 {
  std::vector<Element> els;
  std::unique_ptr<Interpolator2Dir> ipo;
  size_t fed = 0, released = 0;
  std::vector<IpoOutput> outs;
  std::vector<int> dirs;
  IpoControls ctl;

  explicit Run2(const std::string& program, int history = 64, bool startAtEnd = false, IpoSettings ipoCfg = {}) {
    Decoded d(program);
    EXPECT_EQ(d.errors(), 0u);
    els = d.els;
    checkVelocities(els);
    Ipo2DirSettings cfg;
    cfg.ipo = ipoCfg;
    cfg.ipo.cycle = kCycle;
    cfg.history = history;
    cfg.startAtEnd = startAtEnd;
    cfg.pathCapacity = startAtEnd ? static_cast<int>(els.size()) + 1 : 0;
    int16_t err = 0;
    ipo = std::make_unique<Interpolator2Dir>(cfg, err);
    EXPECT_EQ(err, 0);
  }
  const IpoOutput& step() {
    while (fed < els.size() && ipo->wantsMore()) EXPECT_EQ(ipo->feed(els[fed++]), 0);
    if (fed == els.size()) ipo->endOfList();
    const IpoOutput& o = ipo->step(ctl);
    released += ipo->takeReleased();
    outs.push_back(o);
    dirs.push_back(ipo->direction());
    return o;
  }
  void steps(int n) {
    for (int i = 0; i < n; ++i) step();
  }
  int runToEnd(int maxCycles = 1000000) {
    for (int i = 0; i < maxCycles; ++i)
      if (step().finished) return i + 1;
    return -1;
  }
  // every set point so far lies on one of the elements
  double worstDistance() const {
    double worst = 0;
    for (const IpoOutput& o : outs) {
      double best = 1e300;
      for (const Element& e : els)
        if (isMotion(e.type)) best = std::min(best, distanceToElement(e, o.pos));
      worst = std::max(worst, best);
    }
    return worst;
  }
};

TEST(Interpolator2Dir, ForwardsLikeTheInterpolator) {
  // 10 units at F 10 with E 100: 0.1 s ramps, 0.9 s at F: 1.1 s in all (as SMC_Interpolator)
  Run2 r("G1 X10 F10 E100 E-100\n");
  EXPECT_EQ(r.runToEnd(), 1100);
  EXPECT_NEAR(r.outs[49].pos[AxX], 0.5 * 100 * 0.05 * 0.05, 1e-9);
  EXPECT_EQ(r.outs[49].status, IpoStatus::Accel);
  EXPECT_NEAR(r.outs[500].vel, 10.0, 1e-9);
  EXPECT_EQ(r.outs[500].status, IpoStatus::Constant);
  EXPECT_EQ(r.outs[1050].status, IpoStatus::Decel);
  EXPECT_EQ(r.outs.back().pos[AxX], 10.0);
  EXPECT_EQ(r.outs.back().status, IpoStatus::Finished);
  EXPECT_EQ(r.dirs[500], 1);
  EXPECT_EQ(r.dirs.back(), 0);
}

TEST(Interpolator2Dir, NegativeOverrideReversesToTheStart) {
  Run2 r("G1 X10 F10 E100 E-100\n");
  r.steps(600);   // t = 0.6 s: x = 0.5 + 10 x 0.5 = 5.5, at F
  EXPECT_NEAR(r.outs.back().pos[AxX], 5.5, 1e-9);
  r.ctl.override = -1;
  r.steps(100);   // brakes in 0.1 s over 0.5
  EXPECT_NEAR(r.outs.back().pos[AxX], 6.0, 1e-9);
  EXPECT_EQ(r.outs.back().vel, 0.0);
  r.steps(700);   // back over 6: 0.1 + 0.5 + 0.1 s
  EXPECT_EQ(r.outs.back().pos[AxX], 0.0);
  EXPECT_EQ(r.outs.back().vel, 0.0);
  EXPECT_NEAR(r.outs[r.outs.size() - 351].pos[AxX], 3.0, 1e-9);   // the middle, at F backwards
  EXPECT_NEAR(r.outs[r.outs.size() - 351].vel, 10.0, 1e-9);
  EXPECT_EQ(r.dirs[r.outs.size() - 351], -1);
  EXPECT_EQ(r.outs[r.outs.size() - 351].tangent[0], -1.0);   // the direction of motion
  r.step();
  EXPECT_EQ(r.outs.back().pos[AxX], 0.0);
  EXPECT_EQ(r.ipo->warning(), kIpoDataUnderrun);   // nothing kept further back
  EXPECT_FALSE(r.outs.back().finished);
  r.ctl.override = 1;   // and forwards again to the end
  EXPECT_EQ(r.runToEnd(), 1100);
  EXPECT_EQ(r.outs.back().pos[AxX], 10.0);
}

TEST(Interpolator2Dir, BackwardsOverCornersAndArcsOnThePath) {
  const char* prog =
      "G1 X10 F10 E100 E-100 H1 L5\n"
      "G3 X20 Y10 I0 J10\n"
      "G1 Y20\n"
      "G1 X0\n";
  Run2 r(prog);
  r.steps(4000);   // into the last line
  EXPECT_EQ(r.outs.back().switches, 1u);
  EXPECT_GT(r.outs.back().wayPos, 10 + 10 * kPi / 2 + 10);
  r.ctl.override = -2;
  r.steps(6000);
  EXPECT_EQ(r.outs.back().pos[AxX], 0.0);
  EXPECT_EQ(r.outs.back().pos[AxY], 0.0);
  EXPECT_EQ(r.outs.back().switches, 0u);      // H1 passed backwards: off again
  EXPECT_EQ(r.outs.back().lastSwitch, -1);
  EXPECT_LT(r.worstDistance(), 1e-9);
  // the tangent line-arc-line junctions are passed backwards at F x 2, the corner stops
  int cornerStops = 0;
  for (size_t i = 4001; i < r.outs.size(); ++i) {
    const IpoOutput& o = r.outs[i];
    if (o.pos[AxX] == 20.0 && o.pos[AxY] == 20.0 && o.vel == 0) ++cornerStops;
    if (o.wayPos > 9 && o.wayPos < 10 + 10 * kPi / 2 + 7.5 && r.dirs[i] < 0) {
      EXPECT_NEAR(o.vel, 20.0, 1e-9) << o.wayPos;
    }
  }
  EXPECT_GE(cornerStops, 1);
  for (const IpoOutput& o : r.outs) EXPECT_LE(o.vel, 20.0 + 1e-9);
}

TEST(Interpolator2Dir, HistoryLimitsHowFarBack) {
  // history 0: only inside the element in control; older ones are released
  Run2 r("G1 X10 F10 E100 E-100\nG1 Y10\nG1 X0\n", 0);
  r.steps(2600);   // on the third line (corners at 1.1 s and 2.2 s)
  EXPECT_EQ(r.released, 2u);
  EXPECT_EQ(r.ipo->kept(), 1);
  r.ctl.override = -1;
  r.steps(2000);
  EXPECT_EQ(r.outs.back().pos[AxX], 10.0);   // the start of the third line
  EXPECT_EQ(r.outs.back().pos[AxY], 10.0);
  EXPECT_EQ(r.ipo->warning(), kIpoDataUnderrun);
}

TEST(Interpolator2Dir, MFunctionServedOnceAndDwell) {
  Run2 r("G1 X10 F10 E100 E-100\nM7 K2 L3\nG1 X20\n");
  r.steps(1100);
  EXPECT_EQ(r.outs[1098].m, 0);
  EXPECT_EQ(r.outs[1099].m, 7);   // shown in the cycle that reaches it (the 1100th)
  EXPECT_EQ(r.outs.back().status, IpoStatus::Wait);
  r.ctl.acknM = true;
  r.steps(600);
  r.ctl.acknM = false;
  EXPECT_GT(r.outs.back().pos[AxX], 10.0);
  r.ctl.override = -1;   // back over the M (no wait) and forwards over it again (no wait)
  r.steps(1500);
  EXPECT_LT(r.outs.back().pos[AxX], 10.0);
  r.ctl.override = 1;
  for (int i = 0; i < 3000; ++i) EXPECT_EQ(r.step().m, 0);
  EXPECT_TRUE(r.outs.back().finished);
  EXPECT_EQ(r.outs.back().pos[AxX], 20.0);
}

TEST(Interpolator2Dir, StartAtEndRunsBackwards) {
  Run2 r("G1 X10 F10 E100 E-100\nG1 X20\n", 0, true);
  r.ctl.override = 0;
  r.step();
  EXPECT_EQ(r.outs.back().pos[AxX], 20.0);
  EXPECT_TRUE(r.outs.back().finished);   // standing at the end
  r.ctl.override = -1;
  r.steps(2500);
  EXPECT_EQ(r.outs.back().pos[AxX], 0.0);
  EXPECT_EQ(r.outs.back().vel, 0.0);
  EXPECT_LT(r.worstDistance(), 1e-9);
  // 20 units at F 10 (one tangent junction at F): 0.1 + 1.9 + 0.1 s
  int moving = 0;
  for (const IpoOutput& o : r.outs) moving += o.vel > 0;
  EXPECT_EQ(moving, 2099);
}

TEST(Interpolator2Dir, StopsAndBadOverride) {
  Run2 r("G1 X100 F10 E100 E-100\n");
  r.steps(300);
  r.ctl.override = 0;   // stands, direction 0
  r.steps(200);
  EXPECT_EQ(r.outs.back().vel, 0.0);
  EXPECT_EQ(r.dirs.back(), 0);
  r.ctl.override = 1;
  r.ctl.emergencyStop = true;
  r.steps(2);
  const double x = r.outs.back().pos[AxX];
  r.steps(5);
  EXPECT_EQ(r.outs.back().pos[AxX], x);
  r.ctl.emergencyStop = false;
  r.steps(300);
  r.ctl.override = std::nan("");
  r.steps(200);
  EXPECT_EQ(r.ipo->error(), kIpoInvalidParameter);
  EXPECT_EQ(r.outs.back().vel, 0.0);   // an error stop along the path (never a jump)
  for (size_t i = 1; i < r.outs.size(); ++i) EXPECT_LE(std::fabs(r.outs[i].pos[AxX] - r.outs[i - 1].pos[AxX]), 10 * kCycle + 1e-12);
}

TEST(Interpolator2Dir, SingleStepWaitAtNextStopQuickStop) {
  // two collinear lines: passed at F, except with bSingleStep (then a stop at X 10)
  Run2 r("G1 X10 F10 E100 E-100\nG1 X20\n");
  r.ctl.singleStep = true;
  r.ctl.waitAtNextStop = true;
  r.steps(1500);
  EXPECT_EQ(r.outs.back().pos[AxX], 10.0);   // 10 u from rest to rest: 1.1 s, then held
  EXPECT_EQ(r.outs[1099].pos[AxX], 10.0);
  EXPECT_GT(r.outs[1098].vel, 0.0);
  EXPECT_EQ(r.outs.back().status, IpoStatus::Wait);
  r.ctl.waitAtNextStop = false;
  r.ctl.singleStep = false;
  r.steps(300);   // at F after 0.1 s
  EXPECT_NEAR(r.outs.back().vel, 10.0, 1e-9);
  const double x0 = r.outs.back().pos[AxX];
  r.ctl.quickStop = true;
  r.ctl.quickDecel = 1000;   // 10 u/s to rest in 0.01 s over 0.05 u
  r.steps(50);
  EXPECT_EQ(r.outs.back().vel, 0.0);
  EXPECT_NEAR(r.outs.back().pos[AxX], x0 + 0.05, 1e-9);
  r.ctl.quickStop = false;
  EXPECT_GT(r.runToEnd(), 0);
  EXPECT_EQ(r.outs.back().pos[AxX], 20.0);
}

TEST(Interpolator2Dir, JerkLimitedBothWays) {
  IpoSettings s;
  s.mode = VelMode::Sigmoid;
  s.jerk = 2000;
  Run2 r("G1 X10 F10 E100 E-100\n", 64, false, s);
  r.steps(500);
  r.ctl.override = -1;
  r.steps(1500);
  EXPECT_EQ(r.outs.back().pos[AxX], 0.0);
  EXPECT_EQ(r.outs.back().vel, 0.0);
  bool sawIncreasing = false;
  for (size_t i = 1; i < r.outs.size(); ++i) {
    const double dv = r.outs[i].vel - r.outs[i - 1].vel;
    EXPECT_LE(std::fabs(dv), 100 * kCycle + 1e-9);   // |a| <= 100 (speed change per cycle)
    sawIncreasing |= r.outs[i].status == IpoStatus::IncreasingAccel;
  }
  EXPECT_TRUE(sawIncreasing);
}

TEST(Interpolator2Dir, LimitsHoldOnASmoothPath) {
  // tangent splines, arcs and helices: |dv| <= E per second, |v| <= F, v^2 / r <= E on arcs,
  // every step of the set point within the distance the speed allows, forwards and back
  const char* prog =
      "G1 X0 Y10 F200 E2000 E-2000\nG5 X10 Y12.35\nG5 X20 Y12.92\nG5 X30 Y11.28\nG5 X40 Y9.37\n"
      "G1 X50 Y9.37\nG2 X60 Y-0.63 Z1 I0 J-10\nG3 X70 Y-10.63 I10 J0\nG1 X70 Y-20\n";
  Run2 r(prog);
  r.steps(1500);
  r.ctl.override = -1;
  r.steps(1500);
  for (size_t i = 1; i < r.outs.size(); ++i) {
    const IpoOutput& a = r.outs[i - 1];
    const IpoOutput& b = r.outs[i];
    EXPECT_LE(std::fabs(b.vel - a.vel), 2000 * kCycle * (1 + 1e-9)) << i;
    EXPECT_LE(b.vel, 200 + 1e-9);
    double d = 0;
    for (int k = 0; k < 3; ++k) d += (b.pos[k] - a.pos[k]) * (b.pos[k] - a.pos[k]);
    // (the path segments' arc-length tables on splines are exact to a few 0.1 %)
    EXPECT_LE(std::sqrt(d), std::max(a.vel, b.vel) * kCycle * 1.01 + 1e-9) << i;
    // v^2 x curvature <= E: the helix (radius 10, rise 1 over a quarter turn), the arc (radius 10)
    const double c = 1 / (kPi / 2);
    const double kappa = b.sourceLine == 6 ? 10 / (100 + c * c) : b.sourceLine == 7 ? 0.1 : 0.0;
    EXPECT_LE(b.vel * b.vel * kappa, 2000 * (1 + 1e-9)) << i;
  }
  EXPECT_LT(r.worstDistance(), 1e-9);
}

TEST(Interpolator2Dir, LongProgramBoundedWindow) {
  std::string prog = "G1 X0 Y1 F1000 E100000 E-100000\n";
  for (int i = 0; i < 10000; ++i) prog += (i % 2 ? "G1 X0 Y" : "G1 X1 Y") + std::to_string(i + 2) + "\n";
  Run2 r(prog, 13);
  int maxKept = 0;
  for (int i = 0; i < 2000000 && !r.step().finished; ++i) maxKept = std::max(maxKept, r.ipo->kept());
  ASSERT_TRUE(r.outs.back().finished);
  EXPECT_LE(maxKept, 13 + 1 + Interpolator2Dir::kLookAhead);
  EXPECT_EQ(r.outs.back().pos[AxY], 10001.0);
}

}  // namespace
}  // namespace stc::cnc::test
