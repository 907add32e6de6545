// Leadshine moves on the kernel: the start/creep-velocity trapezoid against
// closed forms and over random cases, LS_PositionToVelocity's hand-over and
// Halt/resume, the on-the-fly replan, cycle by cycle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "MotionSim.h"
#include "stdlib-motion/leadshine/LsMoves.h"

using namespace stc::motion;
using namespace stc::motion::leadshine;
using stc::motion::test::Sim;

TEST(JumpTrapezoid, ClosedFormWithCruise) {
  // 1000 u at 100, acc = dec 1000, start 20, creep 10: 0.08 + 9.9025 + 0.09 s.
  auto g = JumpTrapezoid::position(0, 1000, 20, 100, 10, 1000, 1000);
  EXPECT_NEAR(g->duration(), 10.0725, 1e-12);
  EXPECT_DOUBLE_EQ(g->at(0).v, 20);                       // the velocity jumps at the start
  EXPECT_NEAR(g->at(0.04).v, 60, 1e-12);
  EXPECT_NEAR(g->at(0.08).p, 4.8, 1e-12);
  EXPECT_NEAR(g->at(g->duration() - 1e-9).v, 10, 1e-5);   // arrives creeping ...
  EXPECT_EQ(g->at(g->duration()).v, 0);                    // ... and stops at the target
  EXPECT_DOUBLE_EQ(g->at(g->duration()).p, 1000);
}

TEST(JumpTrapezoid, ShortDistanceKeepsTheRates) {
  // 1 u, start 20, creep 10, vMax 100, acc = dec 1000: no cruise; the peak where both ramps meet.
  auto g = JumpTrapezoid::position(5, -1, 20, 100, 10, 1000, 1000);
  const double vp = std::sqrt((2 * 1000 * 1000 * 1.0 + 1000 * 400 + 1000 * 100) / 2000.0);
  EXPECT_NEAR(g->peakVelocity(), vp, 1e-12);
  EXPECT_NEAR(g->at(g->duration()).p, 4, 1e-12);
  EXPECT_LT(g->at(0).v, 0);
  // Too short for the ramp down from the start velocity: the arrival speed adapts.
  auto h = JumpTrapezoid::position(0, 0.01, 20, 100, 1, 1000, 1000);
  EXPECT_NEAR(h->at(h->duration()).p, 0.01, 1e-15);
  EXPECT_NEAR(h->at(h->duration() - 1e-12).v, std::sqrt(400 - 2 * 1000 * 0.01), 1e-6);
}

TEST(JumpTrapezoid, RandomCasesReachTheTargetWithinTheLimits) {
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 200000; ++i) {
    const double D = (u(rng) - 0.5) * 2000, vMax = 1 + u(rng) * 500, v0 = 0.001 + u(rng) * 100, ve = 0.001 + u(rng) * 100;
    const double a = u(rng) < 0.1 ? 0 : 1 + u(rng) * 5000, d = u(rng) < 0.1 ? 0 : 1 + u(rng) * 5000;
    auto g = JumpTrapezoid::position(1, D, v0, vMax, ve, a, d);
    const double T = g->duration();
    ASSERT_NEAR(g->at(T).p, 1 + D, 1e-9 * (1 + std::fabs(D))) << i;
    ASSERT_EQ(g->at(T).v, 0);
    for (int k = 0; k <= 20; ++k) {
      const Kinematic s = g->at(T * k / 20.0 * (1 - 1e-12));
      ASSERT_LE(std::fabs(s.v), vMax * (1 + 1e-9) + std::max(v0, ve)) << i;
      ASSERT_LE(std::fabs(s.a), std::max(a, d) * (1 + 1e-9)) << i;
      if (D != 0) {
        ASSERT_GE(s.v * D, 0) << i;   // never moves backwards
      }
    }
  }
}

TEST(LeadshineKernel, StartVelocityMoveTiming) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  s.powerOn(p);
  s.endCycle();
  FbSlot& m = s.slot(FbKind::Leadshine);
  StartVelInputs in;
  in.distance = 100;
  in.velocity = 100;
  in.acceleration = in.deceleration = 1000;
  in.startVel = in.endSecondVel = 20;
  // 100 u: 0.08 s ramps (4.8 u each), cruise 0.904 s: T = 1.064 s.
  const uint64_t c0 = s.cycle;
  callStartVelMove(s.k, m, *s.ax, true, FbKind::MoveRelative, in, s.ctx());
  EXPECT_TRUE(m.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::DiscreteMotion);
  while (!m.out.done) {
    callStartVelMove(s.k, m, *s.ax, true, FbKind::MoveRelative, in, s.ctx());
    s.endCycle();
    ASSERT_LT(s.cycle, c0 + 2000);
  }
  EXPECT_EQ(s.cycle - 1, c0 + 1064);   // the kernel step of the first cycle with t >= T
  EXPECT_DOUBLE_EQ(s.ax->set().p, 100);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
}

TEST(LeadshineKernel, BadStartVelocityAndDirection) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  s.powerOn(p);
  FbSlot& m = s.slot(FbKind::Leadshine);
  StartVelInputs in;
  in.velocity = 10;
  in.startVel = 0;   // must be >= 0.001
  callStartVelMove(s.k, m, *s.ax, true, FbKind::MoveAbsolute, in, s.ctx());
  EXPECT_TRUE(m.out.error);
  EXPECT_EQ(m.out.errorId, Error::MaInvalidVelAcc);
  FbSlot& v = s.slot(FbKind::Leadshine);
  in.startVel = 1;
  in.direction = Direction::Fastest;
  callStartVelMove(s.k, v, *s.ax, true, FbKind::MoveVelocity, in, s.ctx());
  EXPECT_EQ(v.out.errorId, Error::MvDirectionNotApplicable);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
}

TEST(LeadshineKernel, PositionToVelocityHandsOverWithoutStopping) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  s.powerOn(p);
  FbSlot& m = s.slot(FbKind::Leadshine);
  TwoSegmentInputs in;
  in.exec = true;
  in.ipoCycleUs = 1000;
  in.velocityMode = 0;
  in.endPos[0] = 10;
  in.endPos[1] = 30;
  in.velocity[0] = 5;
  in.velocity[1] = 20;
  in.acceleration[0] = in.deceleration[0] = 10;
  in.acceleration[1] = in.deceleration[1] = 20;
  TwoSegmentOutputs out;
  // Segment 0: 0.5 s ramp (1.25 u), cruise 1.75 s -> at 10 with 5 u/s at t = 2.25 s.
  callPositionToVelocity(s.k, m, *s.ax, in, out, s.ctx());
  for (int i = 0; i <= 2250; ++i) {   // kernel steps at t = 0 .. 2.25 s
    s.endCycle();
    callPositionToVelocity(s.k, m, *s.ax, in, out, s.ctx());
  }
  EXPECT_NEAR(s.ax->set().p, 10, 1e-9);
  EXPECT_NEAR(out.vel, 5, 1e-9);
  EXPECT_TRUE(m.out.busy);
  // Segment 1 from 10 at 5: 0.75 s to 20 (9.375 u), 1 s stop (10 u): cruise 0.03125 s; T1 = 1.78125 s.
  int n = 0;
  while (!m.out.done && n < 3000) {
    s.endCycle();
    callPositionToVelocity(s.k, m, *s.ax, in, out, s.ctx());
    ++n;
    ASSERT_GE(s.ax->set().v, 0);
  }
  EXPECT_EQ(n, 1782);
  EXPECT_DOUBLE_EQ(s.ax->set().p, 30);
}
