// The motion kernel cycle by cycle: which cycle each FB output rises and
// falls, the axis state, and set positions against closed-form values.
// A "cycle" here is what the controller does in one task slot: the FB calls
// of the program (call()), then the kernel step (endCycle()).
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <functional>

#include "MotionSim.h"

using namespace stc::motion;
using stc::motion::test::Sim;

namespace {

MoveInputs absolute(double pos, double v, double a, double d, BufferMode m = BufferMode::Aborting) {
  MoveInputs in;
  in.position = pos;
  in.velocity = v;
  in.acceleration = a;
  in.deceleration = d;
  in.bufferMode = m;
  return in;
}

}  // namespace

TEST(MotionKernel, VirtualAxisPowersOnInTheCallCycle) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  EXPECT_EQ(s.ax->state(), AxisState::PowerOff);
  s.powerOn(p);
  EXPECT_TRUE(p.out.status);
  EXPECT_TRUE(p.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
}

TEST(MotionKernel, ServoAxisNeedsTheCia402Handshake) {
  AxisConfig cfg;
  cfg.drive.kind = AxisKind::Servo;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  // c1: request; the drive steps SwitchOnDisabled -> ReadyToSwitchOn -> SwitchedOn -> OperationEnabled
  // one state per cycle; the axis is in standstill after the third step.
  std::vector<bool> status;
  for (int i = 0; i < 5; ++i) {
    s.k.callPower(p, *s.ax, true, true, true, s.ctx());
    status.push_back(p.out.status);
    s.endCycle();
  }
  EXPECT_EQ(status, (std::vector<bool>{false, false, false, true, true}));
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  EXPECT_EQ(s.ax->drive().statusword() & 0x6F, 0x27);
}

TEST(MotionKernel, MoveAbsoluteTakesTenPointOneSecondsAndDoneRisesAtTheTarget) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  const uint64_t c0 = s.cycle;
  s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  EXPECT_TRUE(m.out.busy);      // Busy in the cycle of the edge
  EXPECT_TRUE(m.out.active);
  EXPECT_FALSE(m.out.done);
  s.endCycle();
  EXPECT_EQ(s.ax->set().p, 0.0);   // the profile starts at the end of c0: no motion yet
  EXPECT_EQ(s.ax->state(), AxisState::DiscreteMotion);
  uint64_t doneCycle = 0;
  while (s.cycle < c0 + 12000 && !doneCycle) {
    s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    const double t = (c - c0) * 1e-3;
    if (m.out.done) {
      doneCycle = c;
      EXPECT_EQ(s.ax->set().p, 100.0);
      EXPECT_EQ(s.ax->set().v, 0.0);
      EXPECT_FALSE(m.out.busy);
    } else {
      // Closed form: accelerate 0.1 s, cruise, decelerate 0.1 s.
      const double expect = t <= 0.1 ? 50 * t * t : t <= 10.0 ? 0.5 + 10 * (t - 0.1) : 100 - 50 * (10.1 - t) * (10.1 - t);
      ASSERT_NEAR(s.ax->set().p, expect, 1e-9) << "cycle " << c;
      ASSERT_LT(s.ax->set().p, 100.0);
    }
  }
  EXPECT_EQ(doneCycle, c0 + 10100);   // 10.1 s after the edge
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
}

TEST(MotionKernel, DoneIsHeldWhileExecuteIsTrueAndResetsWithIt) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveRelative);
  s.powerOn(p);
  MoveInputs in = absolute(0, 10, 100, 100);
  in.distance = 0.01;   // 0.02 s triangle
  s.k.callMove(m, *s.ax, true, in, s.ctx());
  while (!m.out.done) {
    s.endCycle();
    s.k.callMove(m, *s.ax, true, in, s.ctx());
  }
  for (int i = 0; i < 5; ++i) {
    s.endCycle();
    s.k.callMove(m, *s.ax, true, in, s.ctx());
    EXPECT_TRUE(m.out.done);
  }
  s.k.callMove(m, *s.ax, false, in, s.ctx());
  EXPECT_FALSE(m.out.done);   // falls in the call that sees Execute FALSE
}

TEST(MotionKernel, DoneIsVisibleForExactlyOneCycleWhenExecuteFellBefore) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveRelative);
  s.powerOn(p);
  MoveInputs in = absolute(0, 10, 100, 100);
  in.distance = 0.01;
  s.k.callMove(m, *s.ax, true, in, s.ctx());   // a one-cycle Execute pulse
  s.endCycle();
  int doneCycles = 0;
  uint64_t rose = 0;
  for (int i = 0; i < 100; ++i) {
    s.k.callMove(m, *s.ax, false, in, s.ctx());
    if (m.out.done) ++doneCycles;          // seen by the program after its call
    s.endCycle();
    if (m.out.done && !rose) rose = s.cycle - 1;   // seen at the end of the cycle (trace)
  }
  EXPECT_GT(rose, 0u);
  EXPECT_EQ(doneCycles, 1);   // the program sees it in the cycle after the kernel raised it, then it is gone
  EXPECT_FALSE(m.out.done);
  EXPECT_FALSE(m.out.busy);
}

TEST(MotionKernel, AbortingMoveGivesTheFirstCommandAbortedInTheCycleItStarts) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& a = s.slot(FbKind::MoveAbsolute);
  FbSlot& b = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  s.k.callMove(a, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  for (int i = 0; i < 500; ++i) {
    s.endCycle();
    s.k.callMove(a, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  }
  const double v = s.ax->set().v;
  EXPECT_NEAR(v, 10, 1e-12);
  s.k.callMove(b, *s.ax, true, absolute(20, 5, 100, 100), s.ctx());
  EXPECT_TRUE(a.out.aborted);
  EXPECT_FALSE(a.out.busy);
  EXPECT_FALSE(a.out.active);
  EXPECT_TRUE(b.out.busy && b.out.active);
  // The new command starts from the state of this cycle: velocity is continuous.
  s.endCycle();
  EXPECT_NEAR(s.ax->set().v, 10 - 100 * 1e-3 * 0, 0.1 + 1e-9);
  s.k.callMove(a, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  EXPECT_TRUE(a.out.aborted);   // held while its Execute stays TRUE
  for (int i = 0; i < 5000 && !b.out.done; ++i) {
    s.k.callMove(a, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
    s.k.callMove(b, *s.ax, true, absolute(20, 5, 100, 100), s.ctx());
    s.endCycle();
  }
  EXPECT_TRUE(b.out.done);
  EXPECT_EQ(s.ax->set().p, 20.0);   // had to reverse: it was past 20 at 10 u/s
}

TEST(MotionKernel, BufferedSuccessorBecomesActiveInTheDoneCycleAndMovesFromTheNext) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& a = s.slot(FbKind::MoveAbsolute);
  FbSlot& b = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  s.k.callMove(a, *s.ax, true, absolute(1, 10, 100, 100), s.ctx());
  s.k.callMove(b, *s.ax, true, absolute(2, 10, 100, 100, BufferMode::Buffered), s.ctx());
  EXPECT_TRUE(b.out.busy);
  EXPECT_FALSE(b.out.active);
  for (int i = 0; i < 1000 && !a.out.done; ++i) {
    s.endCycle();
    if (a.out.done) break;
    s.k.callMove(a, *s.ax, true, absolute(1, 10, 100, 100), s.ctx());
    s.k.callMove(b, *s.ax, true, absolute(2, 10, 100, 100, BufferMode::Buffered), s.ctx());
  }
  ASSERT_TRUE(a.out.done);
  EXPECT_TRUE(b.out.active);          // Active in the cycle the predecessor is Done
  EXPECT_EQ(s.ax->set().p, 1.0);      // still at the predecessor's target in that cycle
  s.k.callMove(a, *s.ax, true, absolute(1, 10, 100, 100), s.ctx());
  s.k.callMove(b, *s.ax, true, absolute(2, 10, 100, 100, BufferMode::Buffered), s.ctx());
  s.endCycle();
  EXPECT_NEAR(s.ax->set().p, 1.0 + 50 * 1e-6, 1e-12);   // interpolation from the next cycle
}

TEST(MotionKernel, BlendingLowHandsOverAtTheLowerVelocity) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& a = s.slot(FbKind::MoveAbsolute);
  FbSlot& b = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  s.k.callMove(a, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  s.k.callMove(b, *s.ax, true, absolute(200, 5, 100, 100, BufferMode::BlendingLow), s.ctx());
  double minV = 1e9;
  bool handedOver = false;
  for (int i = 0; i < 40000 && !b.out.done; ++i) {
    s.endCycle();
    if (a.out.done && !handedOver) {
      handedOver = true;
      EXPECT_NEAR(s.ax->set().p, 100.0, 5e-3 + 1e-9);   // within one cycle at 5 u/s of the corner
      EXPECT_NEAR(s.ax->set().v, 5.0, 1e-9);            // min(10, 5)
      EXPECT_TRUE(b.out.active);
    }
    if (handedOver && !b.out.done) minV = std::min(minV, s.ax->set().v);
    s.k.callMove(a, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
    s.k.callMove(b, *s.ax, true, absolute(200, 5, 100, 100, BufferMode::BlendingLow), s.ctx());
  }
  EXPECT_TRUE(handedOver);
  EXPECT_TRUE(b.out.done);
  EXPECT_EQ(s.ax->set().p, 200.0);
  EXPECT_GT(minV, 0.0);   // never stopped between the two moves
}

TEST(MotionKernel, StopBlocksOtherCommandsWhileItsExecuteIsTrue) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& mv = s.slot(FbKind::MoveVelocity);
  FbSlot& st = s.slot(FbKind::Stop);
  FbSlot& mv2 = s.slot(FbKind::MoveVelocity);
  s.powerOn(p);
  MoveInputs v = absolute(0, 10, 100, 100);
  v.direction = Direction::Positive;
  s.k.callMove(mv, *s.ax, true, v, s.ctx());
  for (int i = 0; i < 200; ++i) {
    s.endCycle();
    s.k.callMove(mv, *s.ax, true, v, s.ctx());
  }
  EXPECT_TRUE(mv.out.inState);
  MoveInputs stop;
  stop.deceleration = 50;
  s.k.callStop(st, *s.ax, true, stop, s.ctx());
  EXPECT_TRUE(mv.out.aborted);
  EXPECT_FALSE(mv.out.inState);
  EXPECT_EQ(s.ax->state(), AxisState::Stopping);
  s.endCycle();
  s.k.callMove(mv2, *s.ax, true, v, s.ctx());
  EXPECT_TRUE(mv2.out.error);
  EXPECT_EQ(mv2.out.errorId, Error::NotReadyForMotion);
  // Braking 10 -> 0 at 50 u/s^2 takes 0.2 s: Done 200 cycles after the edge.
  uint64_t c0 = s.cycle - 1, doneAt = 0;
  for (int i = 0; i < 400; ++i) {
    s.k.callStop(st, *s.ax, true, stop, s.ctx());
    s.endCycle();
    if (st.out.done && !doneAt) doneAt = s.cycle - 1;
  }
  EXPECT_EQ(doneAt, c0 + 200);
  EXPECT_EQ(s.ax->state(), AxisState::Stopping);   // held while Execute is TRUE
  s.k.callMove(mv2, *s.ax, false, v, s.ctx());
  s.k.callMove(mv2, *s.ax, true, v, s.ctx());
  EXPECT_EQ(mv2.out.errorId, Error::BlockingStopWasntCalled);
  s.k.callStop(st, *s.ax, false, stop, s.ctx());
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  s.k.callMove(mv2, *s.ax, false, v, s.ctx());
  s.k.callMove(mv2, *s.ax, true, v, s.ctx());
  EXPECT_FALSE(mv2.out.error);
  EXPECT_TRUE(mv2.out.busy);
}

TEST(MotionKernel, BadInputsGiveTheDocumentedErrorIdInTheCallCycle) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  s.powerOn(p);
  struct Case { FbKind kind; MoveInputs in; Error expect; };
  MoveInputs ok = absolute(10, 10, 100, 100);
  auto with = [&](std::function<void(MoveInputs&)> f) { MoveInputs i = ok; f(i); return i; };
  const Case cases[] = {
      {FbKind::MoveAbsolute, with([](MoveInputs& i) { i.velocity = 0; }), Error::MaInvalidVelAcc},
      {FbKind::MoveAbsolute, with([](MoveInputs& i) { i.acceleration = -1; }), Error::MaInvalidVelAcc},
      {FbKind::MoveAbsolute, with([](MoveInputs& i) { i.deceleration = NAN; }), Error::MaInvalidVelAcc},
      {FbKind::MoveAbsolute, with([](MoveInputs& i) { i.position = INFINITY; }), Error::MaInvalidVelAcc},
      {FbKind::MoveAbsolute, with([](MoveInputs& i) { i.direction = static_cast<Direction>(7); }), Error::MaInvalidDirection},
      {FbKind::MoveRelative, with([](MoveInputs& i) { i.velocity = -5; }), Error::MrInvalidVelAcc},
      {FbKind::MoveAdditive, with([](MoveInputs& i) { i.acceleration = 0; }), Error::MadInvalidVelAcc},
      {FbKind::MoveSuperImposed, with([](MoveInputs& i) { i.deceleration = 0; }), Error::MsiInvalidVelAcc},
      {FbKind::MoveVelocity, with([](MoveInputs& i) { i.acceleration = 0; }), Error::MvInvalidAccDec},
      {FbKind::MoveVelocity, with([](MoveInputs& i) { i.direction = Direction::Shortest; }), Error::MvDirectionNotApplicable},
      {FbKind::MoveContinuousAbsolute, with([](MoveInputs& i) { i.direction = Direction::Fastest; }), Error::McaDirectionNotApplicable},
      {FbKind::MoveContinuousRelative, with([](MoveInputs& i) { i.velocity = 0; }), Error::McrInvalidVelAcc},
  };
  for (const Case& c : cases) {
    FbSlot& f = s.slot(c.kind);
    s.k.callMove(f, *s.ax, true, c.in, s.ctx());
    EXPECT_TRUE(f.out.error);
    EXPECT_FALSE(f.out.busy);
    EXPECT_EQ(f.out.errorId, c.expect) << "kind " << int(c.kind);
  }
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);   // FB errors leave the axis alone
  FbSlot& h = s.slot(FbKind::Halt);
  MoveInputs bad;
  bad.deceleration = 0;
  s.k.callHalt(h, *s.ax, true, bad, s.ctx());
  EXPECT_EQ(h.out.errorId, Error::StopInvalidAccDec);
}

TEST(MotionKernel, MotionCommandsWithoutPowerGiveError20) {
  Sim s;
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.k.callMove(m, *s.ax, true, absolute(10, 10, 100, 100), s.ctx());
  EXPECT_EQ(m.out.errorId, Error::RegulatorOrStartNotSet);
}

TEST(MotionKernel, AnFbNotCalledDuringMotionStopsTheAxisWithError30) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  FbSlot& q = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  s.k.callMove(q, *s.ax, true, absolute(50, 10, 100, 100, BufferMode::Buffered), s.ctx());
  s.endCycle();
  s.endCycle();   // m is not called in this cycle
  EXPECT_EQ(s.ax->state(), AxisState::ErrorStop);
  EXPECT_EQ(s.ax->error(), Error::FbWasntCalledDuringMotion);
  EXPECT_TRUE(m.out.error);
  EXPECT_EQ(m.out.errorId, Error::FbWasntCalledDuringMotion);
  EXPECT_TRUE(q.out.error);   // ErrorStop ends buffered commands with Error, not CommandAborted
  EXPECT_FALSE(q.out.aborted);
  // MC_Reset: refused while nothing... then ErrorStop -> Standstill once at rest.
  FbSlot& r = s.slot(FbKind::Reset);
  for (int i = 0; i < 100; ++i) s.endCycle();
  s.k.callReset(r, *s.ax, true, s.ctx());
  EXPECT_TRUE(r.out.done);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  FbSlot& r2 = s.slot(FbKind::Reset);
  s.k.callReset(r2, *s.ax, true, s.ctx());
  EXPECT_EQ(r2.out.errorId, Error::ResetNoErrorToReset);
}

TEST(MotionKernel, MoveVelocityReportsInVelocityWhenTheRampEnds) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveVelocity);
  s.powerOn(p);
  MoveInputs v = absolute(0, 10, 100, 100);
  v.direction = Direction::Negative;
  const uint64_t c0 = s.cycle;
  uint64_t inAt = 0;
  for (int i = 0; i < 300; ++i) {
    s.k.callMove(m, *s.ax, true, v, s.ctx());
    s.endCycle();
    if (m.out.inState && !inAt) inAt = s.cycle - 1;
  }
  EXPECT_EQ(inAt, c0 + 100);   // 10 u/s at 100 u/s^2: 0.1 s
  EXPECT_TRUE(m.out.busy);     // InVelocity does not end Busy
  EXPECT_EQ(s.ax->set().v, -10.0);
  EXPECT_EQ(s.ax->state(), AxisState::ContinuousMotion);
}

TEST(MotionKernel, SoftwareLimitPutsTheAxisIntoErrorStop) {
  AxisConfig cfg;
  cfg.swLimitEnable = true;
  cfg.swLimitPositive = 5;
  cfg.swLimitNegative = -5;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  for (int i = 0; i < 3000 && s.ax->state() != AxisState::ErrorStop; ++i) {
    s.k.callMove(m, *s.ax, true, absolute(10, 10, 100, 100), s.ctx());
    s.endCycle();
  }
  EXPECT_EQ(s.ax->state(), AxisState::ErrorStop);
  EXPECT_EQ(s.ax->error(), Error::SwLimitsExceeded);
  EXPECT_EQ(m.out.errorId, Error::SwLimitsExceeded);
  EXPECT_GT(s.ax->set().p, 5.0);
  EXPECT_LT(s.ax->set().p, 5.0 + 0.011);   // first cycle past the limit
}

TEST(MotionKernel, JogBusyEndsAtReleaseAndTheAxisStopsOnItsRamp) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& j = s.slot(FbKind::Jog);
  s.powerOn(p);
  MoveInputs in = absolute(0, 10, 100, 100);
  for (int i = 0; i < 200; ++i) {
    s.k.callJog(j, *s.ax, true, false, in, s.ctx());
    EXPECT_TRUE(j.out.busy);
    s.endCycle();
  }
  EXPECT_EQ(s.ax->set().v, 10.0);
  s.k.callJog(j, *s.ax, false, false, in, s.ctx());
  EXPECT_FALSE(j.out.busy);   // manual: Busy falls with the jog input
  // The ramp starts in the release cycle (t = 0 there): 10 -> 0 at 100 u/s^2 is 100 cycles.
  for (int i = 0; i < 100; ++i) {
    s.endCycle();
    s.k.callJog(j, *s.ax, false, false, in, s.ctx());
    EXPECT_GT(s.ax->set().v, 0.0);
  }
  s.endCycle();
  EXPECT_EQ(s.ax->set().v, 0.0);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
}

TEST(MotionKernel, ModuloAxisTakesTheShortestWay) {
  AxisConfig cfg;
  cfg.period = 360;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& set = s.slot(FbKind::SetPosition);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  s.k.callSetPosition(set, *s.ax, true, 350, false, s.ctx());
  EXPECT_TRUE(set.out.done);
  EXPECT_EQ(s.ax->reportPosition(s.ax->set().p), 350.0);
  MoveInputs in = absolute(10, 100, 1000, 1000);
  in.direction = Direction::Shortest;
  for (int i = 0; i < 2000 && !m.out.done; ++i) {
    s.k.callMove(m, *s.ax, true, in, s.ctx());
    s.endCycle();
    EXPECT_GE(s.ax->set().v, 0.0);   // forward through 360, not back through 180
  }
  EXPECT_TRUE(m.out.done);
  EXPECT_NEAR(s.ax->reportPosition(s.ax->set().p), 10.0, 1e-9);
}

// Velocity override (time scaling): the same path at factor x the speed.
TEST(MotionKernel, OverrideScalesTheRunningMoveAlongItsPath) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  const uint64_t c0 = s.cycle;
  auto call = [&] { s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx()); };
  call();
  while (s.cycle < c0 + 5000) {   // kernel steps at t = 0 .. 4.999 s
    s.endCycle();
    call();
  }
  s.ax->setOverride(0.5, s.now);  // t = 5 s: at 49.5, 10 u/s
  s.endCycle();
  EXPECT_NEAR(s.ax->set().p, 49.5, 1e-9);
  EXPECT_NEAR(s.ax->set().v, 5, 1e-9);
  for (int i = 0; i < 2000; ++i) {   // 2 s at half speed: profile time 6 s -> 59.5
    call();
    s.endCycle();
  }
  EXPECT_NEAR(s.ax->set().p, 59.5, 1e-9);   // the last step at t = 7 s
  EXPECT_NEAR(s.ax->set().v, 5, 1e-9);
  // Override 0 holds the axis on its path (at profile time 6.0005 s: 59.505).
  s.ax->setOverride(0, s.now);
  call();
  s.endCycle();
  EXPECT_NEAR(s.ax->set().p, 59.505, 1e-9);
  for (int i = 0; i < 100; ++i) {
    call();
    s.endCycle();
    ASSERT_NEAR(s.ax->set().p, 59.505, 1e-9);
    ASSERT_EQ(s.ax->set().v, 0);
  }
  EXPECT_TRUE(m.out.busy);
  // Back to 1: the rest of the move (profile time 6.0005 .. 10.1 s) at full speed.
  s.ax->setOverride(1, s.now);
  uint64_t n = 0;
  while (!m.out.done && n < 10000) {
    call();
    s.endCycle();
    ++n;
  }
  EXPECT_EQ(n, 4101u);   // steps at profile times 6.0005, 6.0015 ...: 10.1 is passed in the 4101st
  EXPECT_EQ(s.ax->set().p, 100.0);
}

// The Leadshine profile (CODESYS rule): a released jog stays Busy until the axis has stopped.
TEST(MotionKernel, JogBusyUntilStandstillInTheLeadshineProfile) {
  Sim s;
  ASSERT_TRUE(VendorProfile::named("leadshine_pmc600", s.k.profile));
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& j = s.slot(FbKind::Jog);
  s.powerOn(p);
  MoveInputs in = absolute(0, 100, 1000, 1000);
  for (int i = 0; i < 500; ++i) {   // 0.1 s ramp, then at 100 u/s
    s.k.callJog(j, *s.ax, true, false, in, s.ctx());
    s.endCycle();
  }
  s.k.callJog(j, *s.ax, false, false, in, s.ctx());   // release: brake 0.1 s
  EXPECT_TRUE(j.out.busy);
  int n = 0;
  while (j.out.busy && n < 1000) {
    s.endCycle();
    s.k.callJog(j, *s.ax, false, false, in, s.ctx());
    ++n;
  }
  EXPECT_EQ(n, 101);   // the stop ends in the 101st step (t = 0 .. 0.1 s after the release)
  EXPECT_EQ(s.ax->set().v, 0);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  EXPECT_FALSE(j.out.aborted);
  EXPECT_FALSE(j.out.error);
}

// The lag drive model on a ramp of acceleration A: the motor follows the set point with the
// closed-form error A * lag_time / kv once the transient has died out (and never leads it).
TEST(MotionDrive, LagModelFollowingErrorOnARamp) {
  DriveConfig cfg;
  cfg.kind = AxisKind::Virtual;
  cfg.model = DriveModel::Lag;
  cfg.kv = 100;
  cfg.lagTime = 0.002;
  Drive d(cfg);
  d.setControlword(0x06);
  d.settle();
  d.setControlword(0x0F);
  d.settle();
  ASSERT_TRUE(d.operationEnabled());
  const double A = 1000, dt = 0.001;
  for (int k = 0; k <= 1000; ++k) {
    const double t = k * dt;
    d.cycle(A * t * t / 2, A * t, A, dt, static_cast<int64_t>(k) * 1'000'000);
    ASSERT_GE(A * t * t / 2 - d.actPosition(), -1e-12) << "cycle " << k;   // never ahead
  }
  EXPECT_NEAR(1000 * 0.5 - d.actPosition(), A * 0.002 / 100, 1e-6);     // 0.02
  EXPECT_NEAR(d.actVelocity(), A * 1.0, 1e-6);
}
