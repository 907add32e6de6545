// Homing cycle by cycle: MC_Home / LS_EtherCATAxis_HomeMove (CiA402 methods
// executed by the simulated drive), SMC_Homing (controller side, reference
// switch input from the program) and SMC_Home (Leadshine, the axis's own
// switches).  1 ms cycles; cycle c0 is the cycle of the rising edge, whose
// kernel step is at t = 0 of the homing (the drive samples its profile at
// t = (c - c0) ms).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "MotionSim.h"
#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"
#include "stdlib-motion//core/Homing.h"

using namespace stc::motion;
using stc::motion::test::Sim;

namespace {

// A virtual axis with a drive: limit switches at -10.0052 / +50, a home switch [5.3, 8.7],
// an index pulse every 2 u from 0.25.
AxisConfig homingAxis(AxisKind kind = AxisKind::Virtual) {
  AxisConfig cfg;
  cfg.drive.kind = kind;
  cfg.drive.hasLimitNegative = true;
  cfg.drive.limitNegative = -10.0052;
  cfg.drive.hasLimitPositive = true;
  cfg.drive.limitPositive = 50;
  cfg.drive.hasHomeSwitch = true;
  cfg.drive.homeSwitchLow = 5.3;
  cfg.drive.homeSwitchHigh = 8.7;
  cfg.drive.indexPeriod = 2;
  cfg.drive.indexOffset = 0.25;
  return cfg;
}

// 6098h and the speeds (1 increment per unit): fast 10 u/s, slow 1 u/s, 100 u/s^2.
void setMethod(Axis& ax, int method, int64_t fast = 10, int64_t slow = 1, int64_t acc = 100) {
  ax.drive().writeObject(0x6098, 0, method);
  ax.drive().writeObject(0x6099, 1, fast);
  ax.drive().writeObject(0x6099, 2, slow);
  ax.drive().writeObject(0x609A, 0, acc);
}

struct HomeRun {
  uint64_t c0 = 0, doneCycle = 0, errorCycle = 0;
  Error error = Error::None;
};

// Calls MC_Home (Execute TRUE) every cycle until it ends (at most `limit` cycles).
[[maybe_unused]] HomeRun runHome(Sim& s, FbSlot& h, double position, uint64_t limit = 20000) {
  HomeRun r;
  r.c0 = s.cycle;
  for (uint64_t i = 0; i < limit; ++i) {
    callHome(s.k, h, *s.ax, true, position, s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    if (h.out.done) {
      r.doneCycle = c;
      break;
    }
    if (h.out.error) {
      r.errorCycle = c;
      r.error = h.out.errorId;
      break;
    }
  }
  return r;
}

// The mechanical position (DriveConfig coordinates) the axis stands at.
double mechanical(const Axis& ax) { return ax.actPosition() - ax.drive().coordinateShift(); }

}  // namespace


// Puts the (ideal) axis at x without motion.
void placeAt(Sim& s, double x) {
  s.ax->holdAt(x);
  s.ax->drive().place(x);
}

// ================================================================ MC_Home: CiA402 methods in the drive

// Method 17 (negative limit switch at -10.0052, no index), fast 10 u/s, slow 1 u/s, 100 u/s^2,
// from 0.  Search: p(t) = -50 t^2 up to 0.1 s, then -0.5 - 10 (t - 0.1): the switch is closed
// from t = 1.05052 s, seen in the step of c0 + 1051 (p = -10.01); the drive reverses (v = -9.9 in
// the next step), brakes to -10.51 and comes back at 1 u/s: the switch opens at
// -10.51 + 0.005 + (tau - 0.11) > -10.0052, tau = 0.610 (step c0 + 1661, p = -10.005).  The
// reference is the switch edge: that point becomes Position (0), the set point jumps to
// +0.0002 and the drive returns to 0 (brake 0.01 s to 0.0052, back 0.0052 in a 14.42 ms
// triangle): Done in the step of c0 + 1686.
TEST(Homing, MethodSeventeenCycleByCycle) {
  Sim s(homingAxis());
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  setMethod(*s.ax, 17);
  const uint64_t c0 = s.cycle;
  callHome(s.k, h, *s.ax, true, 0, s.ctx());
  EXPECT_TRUE(h.out.busy);                       // Busy in the call of the edge
  EXPECT_EQ(s.ax->state(), AxisState::Homing);
  EXPECT_EQ(s.ax->drive().modeOfOperation(), 6);
  EXPECT_EQ(s.ax->drive().controlword() & 0x10, 0x10);
  s.endCycle();
  EXPECT_EQ(s.ax->set().p, 0.0);                 // t = 0 in the edge cycle
  uint64_t done = 0;
  for (int i = 0; i < 3000 && !done; ++i) {
    callHome(s.k, h, *s.ax, true, 0, s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    const double t = (c - c0) * 1e-3;
    if (c <= c0 + 1051) {
      const double x = t <= 0.1 ? -50 * t * t : -0.5 - 10 * (t - 0.1);
      ASSERT_NEAR(s.ax->set().p, x, 1e-9) << c;
      ASSERT_EQ(s.ax->state(), AxisState::Homing);
      ASSERT_TRUE(h.out.busy);
      ASSERT_EQ(s.ax->drive().statusword() & 0x3400, 0);   // homing in progress
    }
    if (c == c0 + 1051) { EXPECT_NEAR(s.ax->set().v, -10, 1e-9); }
    if (c == c0 + 1052) { EXPECT_NEAR(s.ax->set().v, -9.9, 1e-9); }   // the reversal
    if (c == c0 + 1660) { EXPECT_NEAR(s.ax->set().p, -10.006, 1e-9); }
    if (c == c0 + 1661) {
      EXPECT_NEAR(s.ax->set().p, 0.0002, 1e-9);   // the edge became 0
      EXPECT_NEAR(s.ax->set().v, 1, 1e-9);
    }
    if (h.out.done) done = c;
    else ASSERT_FALSE(h.out.error);
  }
  EXPECT_EQ(done, c0 + 1686);
  EXPECT_FALSE(h.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  EXPECT_EQ(s.ax->set().p, 0.0);
  EXPECT_EQ(s.ax->actPosition(), 0.0);
  EXPECT_NEAR(mechanical(*s.ax), -10.0052, 1e-9);
  EXPECT_EQ(s.ax->drive().modeOfOperation(), 8);
  EXPECT_EQ(s.ax->drive().statusword() & 0x8000, 0x8000);   // homed
  // Done is held while Execute is TRUE, cleared with it.
  callHome(s.k, h, *s.ax, true, 0, s.ctx());
  EXPECT_TRUE(h.out.done);
  s.endCycle();
  callHome(s.k, h, *s.ax, false, 0, s.ctx());
  EXPECT_FALSE(h.out.done);
}

// Every CiA402 method the drive runs, from 0, with Position 3: the axis ends at 3 exactly,
// standing at the configured switch edge or index mark (marks at 0.25 + 2k).
TEST(Homing, MethodTableFinalPositions) {
  struct Case { int method; double start; double mech; };
  const Case cases[] = {
      {1, 0, -9.75}, {2, 0, 48.25}, {3, 0, 4.25}, {4, 0, 6.25}, {5, 0, 10.25}, {6, 0, 8.25},
      {7, 0, 4.25}, {8, 0, 6.25}, {9, 0, 8.25}, {10, 0, 10.25}, {11, 0, 10.25}, {12, 0, 8.25}, {13, 0, 6.25}, {14, 0, 4.25},
      {17, 0, -10.0052}, {18, 0, 50}, {19, 0, 5.3}, {20, 0, 5.3}, {21, 0, 8.7}, {22, 0, 8.7},
      {23, 0, 5.3}, {24, 0, 5.3}, {25, 0, 8.7}, {26, 0, 8.7}, {27, 0, 8.7}, {28, 0, 8.7}, {29, 0, 5.3}, {30, 0, 5.3},
      {33, 0, -1.75}, {34, 0, 0.25}, {35, 0, 0}, {37, 0, 0},
      // Other starts: on the switch, above it (7 and 19 reverse at the positive limit), below the negative limit side.
      {19, 6, 5.3}, {21, 6, 8.7}, {7, 20, 4.25}, {19, 20, 5.3}, {3, 7, 4.25}, {10, 7, 10.25}, {13, -5, 6.25}, {34, 7.3, 8.25},
      {33, 7.3, 6.25}, {35, 7.3, 7.3}};
  for (const Case& k : cases) {
    Sim s(homingAxis());
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    placeAt(s, k.start);
    setMethod(*s.ax, k.method);
    HomeRun r = runHome(s, h, 3);
    EXPECT_TRUE(r.doneCycle) << "method " << k.method << " from " << k.start << " error " << sm3face::smcError(r.error);
    EXPECT_EQ(s.ax->set().p, 3.0) << "method " << k.method;
    EXPECT_EQ(s.ax->actPosition(), 3.0) << "method " << k.method;
    EXPECT_NEAR(mechanical(*s.ax), k.mech, 1e-9) << "method " << k.method << " from " << k.start;
    EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  }
}

// Method 35: the current position is the reference; Done in the kernel step of the edge cycle.
TEST(Homing, CurrentPositionMethodIsDoneInTheEdgeCycle) {
  Sim s(homingAxis());
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  placeAt(s, 4.5);
  callHome(s.k, h, *s.ax, true, 12, s.ctx());   // default method 35
  EXPECT_TRUE(h.out.busy);
  EXPECT_FALSE(h.out.done);
  EXPECT_EQ(s.ax->state(), AxisState::Homing);
  s.endCycle();
  EXPECT_TRUE(h.out.done);
  EXPECT_FALSE(h.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  EXPECT_EQ(s.ax->set().p, 12.0);
  EXPECT_EQ(s.ax->actPosition(), 12.0);
  int64_t off = 0;
  s.ax->drive().readObject(0x607C, 0, off);
  EXPECT_EQ(off, 12);
  // The sensors stay on the mechanics: the home switch [5.3, 8.7] is now at [12.8, 16.2].
  EXPECT_FALSE(s.ax->drive().homeSwitchActive());
  // Done rose with Execute TRUE: it is cleared in the call that sees Execute FALSE.
  callHome(s.k, h, *s.ax, false, 12, s.ctx());
  EXPECT_FALSE(h.out.done);
  // A new edge in standstill homes again (the position is already 12: nothing moves).
  s.endCycle();
  callHome(s.k, h, *s.ax, true, 12, s.ctx());
  EXPECT_TRUE(h.out.busy);
  s.endCycle();
  EXPECT_TRUE(h.out.done);
  EXPECT_EQ(s.ax->set().p, 12.0);
}

TEST(Homing, ServoAxisHomesAfterTheHandshake) {
  Sim s(homingAxis(AxisKind::Servo));
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  for (int i = 0; i < 4; ++i) {
    s.k.callPower(p, *s.ax, true, true, true, s.ctx());
    s.endCycle();
  }
  ASSERT_EQ(s.ax->state(), AxisState::Standstill);
  setMethod(*s.ax, 34);
  const uint64_t c0 = s.cycle;
  uint64_t done = 0;
  for (int i = 0; i < 1000 && !done; ++i) {
    s.k.callPower(p, *s.ax, true, true, true, s.ctx());
    callHome(s.k, h, *s.ax, true, -1, s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    if (h.out.done) done = c;
  }
  // Slow 1 u/s to the mark at 0.25 (0.005 u ramp, then 1 u/s): reached at t = 0.255; the drive
  // brakes (0.005 u) and returns 0.005 u (a 14.14 ms triangle): Done at t = 0.2792.
  EXPECT_EQ(done, c0 + 280);
  EXPECT_EQ(s.ax->set().p, -1.0);
  EXPECT_NEAR(mechanical(*s.ax), 0.25, 1e-9);
}

TEST(Homing, MCHomeErrors) {
  auto make = [](Sim& s, FbSlot*& h) {
    FbSlot& p = s.slot(FbKind::Power);
    h = &s.slot(FbKind::Home);
    s.powerOn(p);
  };
  {  // 170: not in standstill (a move is running); power off: 170 too.
    Sim s(homingAxis());
    FbSlot* h;
    make(s, h);
    FbSlot& m = s.slot(FbKind::MoveVelocity);
    MoveInputs in;
    in.velocity = 1;
    in.acceleration = in.deceleration = 10;
    s.k.callMove(m, *s.ax, true, in, s.ctx());
    callHome(s.k, *h, *s.ax, true, 0, s.ctx());
    EXPECT_TRUE(h->out.error);
    EXPECT_FALSE(h->out.busy);
    EXPECT_EQ(h->out.errorId, Error::HomeAxisWasntStandstill);
    EXPECT_TRUE(m.out.busy);   // the move is not disturbed
    Sim s2(homingAxis());
    FbSlot& h2 = s2.slot(FbKind::Home);
    callHome(s2.k, h2, *s2.ax, true, 0, s2.ctx());
    EXPECT_EQ(h2.out.errorId, Error::HomeAxisWasntStandstill);
  }
  {  // 174: errorstop
    Sim s(homingAxis());
    FbSlot* h;
    make(s, h);
    s.k.errorStop(*s.ax, Error::DriveError, s.now, s.cycle);
    callHome(s.k, *h, *s.ax, true, 0, s.ctx());
    EXPECT_EQ(h->out.errorId, Error::HomeAxisInErrorStop);
  }
  {  // 173: a method that moves with 609Ah = 0 (nothing to stop with)
    Sim s(homingAxis());
    FbSlot* h;
    make(s, h);
    setMethod(*s.ax, 17, 10, 1, 0);
    callHome(s.k, *h, *s.ax, true, 0, s.ctx());
    EXPECT_EQ(h->out.errorId, Error::HomeErrorWhenStopping);
    EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  }
  {  // 171: NaN Position (cannot become 607Ch)
    Sim s(homingAxis());
    FbSlot* h;
    make(s, h);
    callHome(s.k, *h, *s.ax, true, std::nan(""), s.ctx());
    EXPECT_EQ(h->out.errorId, Error::HomeAxisDidntStartHoming);
  }
  // 171: the drive does not start the method (unsupported method, missing sensor, zero speed):
  // Busy in the call, Error in the kernel step of the edge cycle, the axis back in standstill.
  struct Bad { int method; int64_t fast, slow; bool index, home; };
  const Bad bads[] = {{0, 10, 1, true, true}, {15, 10, 1, true, true}, {36, 10, 1, true, true}, {-1, 10, 1, true, true},
                      {1, 10, 1, false, true}, {19, 10, 1, true, false}, {17, 0, 1, true, true}, {33, 10, 0, true, true}};
  for (const Bad& b : bads) {
    AxisConfig cfg = homingAxis();
    if (!b.index) cfg.drive.indexPeriod = 0;
    cfg.drive.hasHomeSwitch = b.home;
    Sim s(cfg);
    FbSlot* h;
    make(s, h);
    setMethod(*s.ax, b.method, b.fast, b.slow);
    callHome(s.k, *h, *s.ax, true, 0, s.ctx());
    EXPECT_TRUE(h->out.busy) << b.method;
    s.endCycle();
    EXPECT_TRUE(h->out.error) << b.method;
    EXPECT_FALSE(h->out.busy);
    EXPECT_EQ(h->out.errorId, Error::HomeAxisDidntStartHoming) << b.method;
    EXPECT_EQ(s.ax->state(), AxisState::Standstill);
    EXPECT_EQ(s.ax->drive().modeOfOperation(), 8);
    EXPECT_EQ(s.ax->set().p, 0.0);
  }
}

// A method that cannot find its edge: home switch outside the limit switches.  The drive reverses
// at the positive limit, meets the negative one, stops (homing error, statusword bit 13) and
// MC_Home ends with 17 SMC_DI_HOMING_ERROR; the axis goes to errorstop.
TEST(Homing, EdgeNotFoundIsAHomingError) {
  AxisConfig cfg = homingAxis();
  cfg.drive.homeSwitchLow = 60;
  cfg.drive.homeSwitchHigh = 70;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  setMethod(*s.ax, 19);
  HomeRun r = runHome(s, h, 0);
  EXPECT_EQ(r.error, Error::DiHomingError);
  EXPECT_EQ(s.ax->state(), AxisState::ErrorStop);
  EXPECT_EQ(s.ax->error(), Error::DiHomingError);
  EXPECT_EQ(s.ax->set().v, 0.0);
  EXPECT_LE(mechanical(*s.ax), -10.0052);
  EXPECT_EQ(s.ax->drive().modeOfOperation(), 8);
}

// MC_Stop aborts MC_Home: CommandAborted in the call of the MC_Stop edge, the axis brakes from the
// drive's homing velocity (no jump), the drive is back in CSP.
TEST(Homing, StopAbortsHoming) {
  Sim s(homingAxis());
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  FbSlot& st = s.slot(FbKind::Stop);
  s.powerOn(p);
  setMethod(*s.ax, 17);
  for (int i = 0; i < 500; ++i) {
    callHome(s.k, h, *s.ax, true, 0, s.ctx());
    s.endCycle();
  }
  // Cycle c0 + 500: t = 0.499 at the last step: p = -0.5 - 10 * 0.399 = -4.49, v = -10.
  EXPECT_NEAR(s.ax->set().p, -4.49, 1e-9);
  callHome(s.k, h, *s.ax, true, 0, s.ctx());
  MoveInputs in;
  in.deceleration = 100;
  s.k.callStop(st, *s.ax, true, in, s.ctx());
  EXPECT_TRUE(h.out.aborted);
  EXPECT_FALSE(h.out.busy);
  EXPECT_TRUE(st.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::Stopping);
  s.endCycle();
  EXPECT_NEAR(s.ax->set().p, -4.5, 1e-9);   // the stop starts at t = 0.5 from p = -4.5, v = -10
  EXPECT_NEAR(s.ax->set().v, -10, 1e-9);
  EXPECT_EQ(s.ax->drive().modeOfOperation(), 8);
  s.k.callStop(st, *s.ax, true, in, s.ctx());
  s.endCycle();
  EXPECT_NEAR(s.ax->set().v, -9.9, 1e-9);
  for (int i = 0; i < 100; ++i) {
    s.k.callStop(st, *s.ax, true, in, s.ctx());
    callHome(s.k, h, *s.ax, true, 0, s.ctx());   // still called: no new homing (no edge)
    s.endCycle();
  }
  EXPECT_TRUE(st.out.done);
  EXPECT_NEAR(s.ax->set().p, -5.0, 1e-9);
  EXPECT_TRUE(h.out.aborted);
  EXPECT_FALSE(s.ax->drive().statusword() & 0x8000);
}

TEST(Homing, NotCalledDuringHomingIsError30) {
  Sim s(homingAxis());
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  setMethod(*s.ax, 17);
  callHome(s.k, h, *s.ax, true, 0, s.ctx());
  s.endCycle();
  s.endCycle();   // not called
  EXPECT_TRUE(h.out.error);
  EXPECT_EQ(h.out.errorId, Error::FbWasntCalledDuringMotion);
  EXPECT_EQ(s.ax->state(), AxisState::ErrorStop);
}

// ================================================================ LS_EtherCATAxis_HomeMove

// The defaults (method 21, 500 / 100 increments/s, 1000 increments/s^2) at 100 increments per
// unit: 5 u/s, 1 u/s, 10 u/s^2; home offset 250 increments = 2.5 u.
TEST(Homing, LsHomeMoveWritesTheObjectsAndHomes) {
  AxisConfig cfg = homingAxis();
  cfg.drive.incrementsPerUnit = 100;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  DriveHomeParams hp;
  hp.homePos = 250;
  callDriveHomeMove(s.k, h, *s.ax, true, hp, s.ctx());
  EXPECT_TRUE(h.out.busy);
  int64_t v = 0;
  s.ax->drive().readObject(0x6098, 0, v);
  EXPECT_EQ(v, 21);
  s.ax->drive().readObject(0x6099, 1, v);
  EXPECT_EQ(v, 500);
  s.ax->drive().readObject(0x6099, 2, v);
  EXPECT_EQ(v, 100);
  s.ax->drive().readObject(0x609A, 0, v);
  EXPECT_EQ(v, 1000);
  s.ax->drive().readObject(0x607C, 0, v);
  EXPECT_EQ(v, 250);
  s.endCycle();
  for (int i = 0; i < 20000 && !h.out.done; ++i) {
    ASSERT_FALSE(h.out.error);
    callDriveHomeMove(s.k, h, *s.ax, true, hp, s.ctx());
    s.endCycle();
  }
  EXPECT_TRUE(h.out.done);
  EXPECT_EQ(s.ax->set().p, 2.5);
  EXPECT_NEAR(mechanical(*s.ax), 8.7, 1e-9);   // method 21: the upper edge of the home switch
  // Home_Pos is a DWORD read as INT32: 16#FFFFFF9C = -100 increments = -1 u.
  hp.homePos = 0xFFFFFF9C;
  hp.method = 35;
  callDriveHomeMove(s.k, h, *s.ax, false, hp, s.ctx());
  s.endCycle();
  callDriveHomeMove(s.k, h, *s.ax, true, hp, s.ctx());
  s.endCycle();
  EXPECT_TRUE(h.out.done);
  EXPECT_EQ(s.ax->set().p, -1.0);
}

// Releasing the level-held bExecute interrupts homing: the drive brakes with 609Ah and
// CommandAborted rises (for one cycle) when it is at rest; standstill.
TEST(Homing, LsHomeMoveReleasedIsAborted) {
  Sim s(homingAxis());
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  DriveHomeParams hp;
  hp.method = 17;
  hp.fastVel = 10;
  hp.slowVel = 1;
  hp.acc = 100;
  for (int i = 0; i < 300; ++i) {
    callDriveHomeMove(s.k, h, *s.ax, true, hp, s.ctx());
    s.endCycle();
  }
  // t = 0.299: p = -0.5 - 10 * 0.199 = -2.49, v = -10; released: braking from t = 0.3 (drive sees bit 4 fall).
  EXPECT_NEAR(s.ax->set().p, -2.49, 1e-9);
  uint64_t aborted = 0;
  const uint64_t c1 = s.cycle;
  for (int i = 0; i < 200 && !aborted; ++i) {
    callDriveHomeMove(s.k, h, *s.ax, false, hp, s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    if (h.out.aborted) aborted = c;
    else ASSERT_TRUE(h.out.busy);
  }
  EXPECT_EQ(aborted, c1 + 100);   // 10 u/s at 100 u/s^2: 0.1 s
  EXPECT_NEAR(s.ax->set().p, -2.5 - 0.5, 1e-9);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  callDriveHomeMove(s.k, h, *s.ax, false, hp, s.ctx());
  s.endCycle();
  EXPECT_FALSE(h.out.aborted);
  // HomeAxisNo 1: no second axis on this drive answers.
  hp.axisNo = 1;
  callDriveHomeMove(s.k, h, *s.ax, true, hp, s.ctx());
  EXPECT_EQ(h.out.errorId, Error::HomeAxisDidntAnswer);
}

// ================================================================ SMC_Homing (controller side)

namespace {

SmcHomingInputs smcHoming(int mode, int direction = -1) {
  SmcHomingInputs in;
  in.velocityFast = 10;
  in.velocitySlow = 1;
  in.acceleration = in.deceleration = 100;
  in.direction = direction;
  in.mode = mode;
  return in;
}

// The program: bReferenceSwitch from the axis's actual position as the program sees it (the
// value after the previous cycle), the switch closed on [lo, hi]; calls SMC_Homing once per cycle.
struct HomingProgram {
  Sim& s;
  FbSlot& fb;
  SmcHomingInputs in;
  double lo = -1e9, hi = -4.0005;
  uint64_t doneCycle = 0;
  void cycle(bool execute = true) {
    const double x = s.ax->actPosition();
    in.referenceSwitch = !(x >= lo && x <= hi);
    callSmcHoming(s.k, fb, *s.ax, execute, in, s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    if (fb.out.done && !doneCycle) doneCycle = c;
  }
};

}  // namespace

// FAST_BSLOW_S_STOP, negative, switch closed below -4.0005: fast phase p(t) = -50 t^2, then
// -0.5 - 10 (t - 0.1): closed in the step of c0 + 451 (p = -4.01), seen by the program in c0 + 452,
// whose step starts the slow reverse from p = -4.02, v = -10 (v = -9.9 one step later); minimum
// -4.52, +1 u/s from -4.515: open in the step of tau = 0.625 (c0 + 1077, p = -4.0), seen in c0 + 1078:
// that position (-4.0) becomes fHomePosition (0) at once: set point -3.999 -> 0.001; stop
// (0.01 s, 0.005 u): Done in the step of c0 + 1088 at 0.006.
TEST(Homing, SmcHomingFastBslowSStopCycleByCycle) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  HomingProgram prog{s, h, smcHoming(0)};
  const uint64_t c0 = s.cycle;
  const double xStart = s.ax->actPosition();
  prog.in.referenceSwitch = !(xStart <= -4.0005);
  callSmcHoming(s.k, h, *s.ax, true, prog.in, s.ctx());
  EXPECT_TRUE(h.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::Homing);
  s.endCycle();
  for (int i = 0; i < 1200 && !prog.doneCycle; ++i) {
    const uint64_t c = s.cycle;
    prog.cycle();
    const double t = (c - c0) * 1e-3;
    if (c <= c0 + 451) {
      ASSERT_NEAR(s.ax->set().p, t <= 0.1 ? -50 * t * t : -0.5 - 10 * (t - 0.1), 1e-9) << c;
      ASSERT_EQ(s.ax->state(), AxisState::Homing);
    }
    if (c == c0 + 452) {
      EXPECT_NEAR(s.ax->set().p, -4.02, 1e-9);
      EXPECT_NEAR(s.ax->set().v, -10, 1e-9);
    }
    if (c == c0 + 453) { EXPECT_NEAR(s.ax->set().v, -9.9, 1e-9); }
    if (c == c0 + 552) { EXPECT_NEAR(s.ax->set().p, -4.52, 1e-9); }
    if (c == c0 + 1077) { EXPECT_NEAR(s.ax->set().p, -4.0, 1e-9); }
    if (c == c0 + 1078) { EXPECT_NEAR(s.ax->set().p, 0.001, 1e-9); }
    if (c < c0 + 1088) { ASSERT_TRUE(h.out.busy) << c; }
  }
  EXPECT_EQ(prog.doneCycle, c0 + 1088);
  EXPECT_FALSE(h.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  EXPECT_NEAR(s.ax->set().p, 0.006, 1e-9);
  EXPECT_NEAR(s.ax->actPosition(), 0.006, 1e-9);
}

// FAST_BSLOW_STOP_S: the same motion; the position is set when the axis has stopped.
TEST(Homing, SmcHomingStopThenSet) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  HomingProgram prog{s, h, smcHoming(1)};
  prog.in.homePosition = 100;
  const uint64_t c0 = s.cycle;
  for (int i = 0; i < 1200 && !prog.doneCycle; ++i) {
    const uint64_t c = s.cycle;
    prog.cycle();
    if (c == c0 + 1078) { EXPECT_NEAR(s.ax->set().p, -3.999, 1e-9); }
    if (c == c0 + 1087) { EXPECT_NEAR(s.ax->set().p, -3.99405, 1e-9); }
  }
  EXPECT_EQ(prog.doneCycle, c0 + 1088);
  EXPECT_NEAR(s.ax->set().p, 100.006, 1e-9);
}

// bReturnToZero: after the stop the axis moves to 0 (0.006 u at fVelocityFast and 100 u/s^2: a
// 15.5 ms triangle, peak 0.775 u/s);
// fSignalDelay = 2 ms moves the reference 0.002 u back along the slow direction.
TEST(Homing, SmcHomingReturnToZeroAndSignalDelay) {
  {
    Sim s;
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    HomingProgram prog{s, h, smcHoming(0)};
    prog.in.returnToZero = true;
    const uint64_t c0 = s.cycle;
    for (int i = 0; i < 1200 && !prog.doneCycle; ++i) {
      const uint64_t c = s.cycle;
      prog.cycle();
      if (c == c0 + 1088) { EXPECT_NEAR(s.ax->set().p, 0.006, 1e-9); }
    }
    EXPECT_EQ(prog.doneCycle, c0 + 1104);
    EXPECT_EQ(s.ax->set().p, 0.0);
    EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  }
  {
    Sim s;
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    HomingProgram prog{s, h, smcHoming(0)};
    prog.in.signalDelay = 0.002;
    for (int i = 0; i < 1200 && !prog.doneCycle; ++i) prog.cycle();
    EXPECT_NEAR(s.ax->set().p, 0.008, 1e-9);
  }
}

// FAST_BSLOW_I_S_STOP: bStartLatchingIndex once the switch is left; the application reports the
// index at -3.9 in cycle c0 + 1200 (the axis is at -3.877 then): -3.9 becomes 0, stop from 0.023.
TEST(Homing, SmcHomingIndexHandshake) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  HomingProgram prog{s, h, smcHoming(2)};
  const uint64_t c0 = s.cycle;
  for (int i = 0; i < 1300 && !prog.doneCycle; ++i) {
    const uint64_t c = s.cycle;
    prog.in.indexOccured = c >= c0 + 1200;
    prog.in.indexPosition = -3.9;
    prog.cycle();
    if (c < c0 + 1078) { ASSERT_FALSE(smcHomingLatching(h)) << c; }
    if (c >= c0 + 1078 && c < c0 + 1200) { ASSERT_TRUE(smcHomingLatching(h)) << c; }
    if (c == c0 + 1199) { EXPECT_NEAR(s.ax->set().p, -3.878, 1e-9); }
    if (c >= c0 + 1200) { ASSERT_FALSE(smcHomingLatching(h)); }
    if (c == c0 + 1200) { EXPECT_NEAR(s.ax->set().p, 0.023, 1e-9); }
  }
  EXPECT_EQ(prog.doneCycle, c0 + 1210);
  EXPECT_NEAR(s.ax->set().p, 0.028, 1e-9);
}

// FAST_SLOW_S_STOP: the slow phase goes on in nDirection (brake -10 -> -1 in 0.09 s) until the switch
// [-6, -4.0005] is left below -6: step of c0 + 452 + 1576 (p = -6.001), seen one cycle later.
// These modes need a hardware limit switch in nDirection (51 without it or with bIgnoreHWLimit).
TEST(Homing, SmcHomingSameDirectionNeedsALimitSwitch) {
  AxisConfig cfg;
  cfg.drive.hasLimitNegative = true;
  cfg.drive.limitNegative = -20;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  s.powerOn(p);
  HomingProgram prog{s, h, smcHoming(4)};
  prog.lo = -6;
  const uint64_t c0 = s.cycle;
  for (int i = 0; i < 2200 && !prog.doneCycle; ++i) {
    const uint64_t c = s.cycle;
    prog.cycle();
    if (c == c0 + 2028) { EXPECT_NEAR(s.ax->set().p, -6.001, 1e-9); }
    if (c == c0 + 2029) { EXPECT_NEAR(s.ax->set().p, -0.001, 1e-9); }
  }
  EXPECT_EQ(prog.doneCycle, c0 + 2039);
  EXPECT_NEAR(s.ax->set().p, -0.006, 1e-9);

  Sim s2;   // no limit switch
  FbSlot& p2 = s2.slot(FbKind::Power);
  FbSlot& h2 = s2.slot(FbKind::Home);
  s2.powerOn(p2);
  for (int mode : {4, 5, 6}) {
    callSmcHoming(s2.k, h2, *s2.ax, false, smcHoming(mode), s2.ctx());
    callSmcHoming(s2.k, h2, *s2.ax, true, smcHoming(mode), s2.ctx());
    EXPECT_EQ(h2.out.errorId, Error::HomingModeNeedsHwLimit) << mode;
  }
  Sim s3(cfg);
  FbSlot& p3 = s3.slot(FbKind::Power);
  FbSlot& h3 = s3.slot(FbKind::Home);
  s3.powerOn(p3);
  SmcHomingInputs ign = smcHoming(4);
  ign.ignoreHwLimit = true;
  callSmcHoming(s3.k, h3, *s3.ax, true, ign, s3.ctx());
  EXPECT_EQ(h3.out.errorId, Error::HomingModeNeedsHwLimit);
}

TEST(Homing, SmcHomingInputErrors) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  // Power off: 20.
  callSmcHoming(s.k, h, *s.ax, true, smcHoming(0), s.ctx());
  EXPECT_EQ(h.out.errorId, Error::RegulatorOrStartNotSet);
  s.powerOn(p);
  const double nan = std::nan("");
  std::vector<SmcHomingInputs> bad;
  for (double v : {0.0, -1.0, nan}) {
    SmcHomingInputs a = smcHoming(0);
    a.velocityFast = v;
    bad.push_back(a);
    a = smcHoming(0);
    a.velocitySlow = v;
    bad.push_back(a);
    a = smcHoming(0);
    a.acceleration = v;
    bad.push_back(a);
    a = smcHoming(0);
    a.deceleration = v;
    bad.push_back(a);
  }
  SmcHomingInputs a = smcHoming(3);   // no mode 3
  bad.push_back(a);
  a = smcHoming(0, 0);                // direction shortest
  bad.push_back(a);
  a = smcHoming(0);
  a.signalDelay = -0.001;
  bad.push_back(a);
  a = smcHoming(0);
  a.homePosition = nan;
  bad.push_back(a);
  for (const SmcHomingInputs& b : bad) {
    s.endCycle();
    callSmcHoming(s.k, h, *s.ax, false, b, s.ctx());
    callSmcHoming(s.k, h, *s.ax, true, b, s.ctx());
    EXPECT_TRUE(h.out.error);
    EXPECT_FALSE(h.out.busy);
    EXPECT_EQ(h.out.errorId, Error::HomingInvalidVelAcc);
    EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  }
  // Not in standstill: 34.
  FbSlot& m = s.slot(FbKind::MoveVelocity);
  MoveInputs in;
  in.velocity = 1;
  in.acceleration = in.deceleration = 10;
  s.k.callMove(m, *s.ax, true, in, s.ctx());
  callSmcHoming(s.k, h, *s.ax, false, smcHoming(0), s.ctx());
  callSmcHoming(s.k, h, *s.ax, true, smcHoming(0), s.ctx());
  EXPECT_EQ(h.out.errorId, Error::NotReadyForMotion);
  EXPECT_TRUE(m.out.busy);
}

// A hardware limit switch met during the search: error 11, errorstop; bIgnoreHWLimit passes it.
TEST(Homing, SmcHomingHardwareLimit) {
  for (bool ignore : {false, true}) {
    AxisConfig cfg;
    cfg.drive.hasLimitNegative = true;
    cfg.drive.limitNegative = -3.0005;   // closed in the step of c0 + 351 (p = -3.01)
    Sim s(cfg);
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    HomingProgram prog{s, h, smcHoming(0)};
    prog.in.ignoreHwLimit = ignore;
    const uint64_t c0 = s.cycle;
    uint64_t errorCycle = 0;
    for (int i = 0; i < 1200 && !prog.doneCycle && !errorCycle; ++i) {
      const uint64_t c = s.cycle;
      prog.cycle();
      if (h.out.error) errorCycle = c;
    }
    if (!ignore) {
      EXPECT_EQ(errorCycle, c0 + 352);
      EXPECT_EQ(h.out.errorId, Error::HwLimitsExceeded);
      EXPECT_EQ(s.ax->state(), AxisState::ErrorStop);
    } else {
      EXPECT_EQ(prog.doneCycle, c0 + 1088);
      EXPECT_NEAR(s.ax->set().p, 0.006, 1e-9);
    }
  }
}

TEST(Homing, SmcHomingAbortedByStop) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  FbSlot& st = s.slot(FbKind::Stop);
  s.powerOn(p);
  HomingProgram prog{s, h, smcHoming(0)};
  for (int i = 0; i < 300; ++i) prog.cycle();
  MoveInputs in;
  in.deceleration = 50;
  const double x = s.ax->actPosition();
  prog.in.referenceSwitch = !(x <= -4.0005);
  callSmcHoming(s.k, h, *s.ax, true, prog.in, s.ctx());
  s.k.callStop(st, *s.ax, true, in, s.ctx());
  EXPECT_TRUE(h.out.aborted);
  EXPECT_FALSE(h.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::Stopping);
  for (int i = 0; i < 250; ++i) {
    s.k.callStop(st, *s.ax, true, in, s.ctx());
    s.endCycle();
  }
  EXPECT_TRUE(st.out.done);
  // From t = 0.3 (p = -2.5, v = -10) at 50 u/s^2: 1 u further.
  EXPECT_NEAR(s.ax->set().p, -3.5, 1e-9);
}

// ================================================================ SMC_Home (Leadshine, the axis's own switches)

namespace {

AxisConfig pulseHomeAxis() {
  AxisConfig cfg = homingAxis();
  cfg.drive.homeSwitchLow = 5.3051;
  cfg.drive.indexOffset = 0.2504;
  return cfg;
}

SmcHomeInputs smcHome(int mode, int direction = 1) {
  SmcHomeInputs in;
  in.velocityFast = 10;
  in.velocitySlow = 1;
  in.acceleration = in.deceleration = 100;
  in.direction = direction;
  in.mode = mode;
  in.completeMode = 1;
  in.driverCounter = 0;
  return in;
}

uint64_t runSmcHome(Sim& s, FbSlot& h, const SmcHomeInputs& in, uint64_t limit = 5000) {
  for (uint64_t i = 0; i < limit; ++i) {
    callSmcHome(s.k, h, *s.ax, true, in, s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    if (h.out.done || h.out.error) return c;
  }
  return 0;
}

}  // namespace

// imode 0 (single search): fast +10 to the switch at 5.3051: closed in the step of c0 + 581
// (p = 5.31), seen in c0 + 582 (reference: 5.31, the position the controller read); stop from
// 5.32 (0.1 s, to 5.82), back to 5.31 at 1 u/s (0.52 s): Done in the step of c0 + 1202 and,
// with bHomeCompleteMode 1, that point is 0.  imode 6 latches the edge itself (5.3051).
TEST(Homing, SmcHomeSingleSearchAndLatch) {
  for (int mode : {0, 6}) {
    Sim s(pulseHomeAxis());
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    const uint64_t c0 = s.cycle;
    callSmcHome(s.k, h, *s.ax, true, smcHome(mode), s.ctx());
    EXPECT_TRUE(h.out.busy);
    EXPECT_EQ(s.ax->state(), AxisState::Homing);
    s.endCycle();
    uint64_t done = 0;
    for (int i = 0; i < 2000 && !done; ++i) {
      callSmcHome(s.k, h, *s.ax, true, smcHome(mode), s.ctx());
      const uint64_t c = s.cycle;
      s.endCycle();
      if (c == c0 + 581) { EXPECT_NEAR(s.ax->set().p, 5.31, 1e-9); }
      if (c == c0 + 582) { EXPECT_NEAR(s.ax->set().v, 10, 1e-9); }
      if (c == c0 + 583) { EXPECT_NEAR(s.ax->set().v, 9.9, 1e-9); }
      if (c == c0 + 682) { EXPECT_NEAR(s.ax->set().p, 5.82, 1e-9); }
      if (h.out.done) done = c;
      else ASSERT_TRUE(h.out.busy);
    }
    EXPECT_EQ(done, mode == 0 ? c0 + 1202 : c0 + 1207) << mode;
    EXPECT_EQ(s.ax->set().p, 0.0);
    EXPECT_NEAR(mechanical(*s.ax), mode == 0 ? 5.31 : 5.3051, 1e-9);
    EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  }
}

TEST(Homing, SmcHomeModesFinalPositions) {
  struct Case { int mode; int dir; double mech; };
  // 1: back off at 1 u/s until the switch opens (read at 5.305); 2 / 10: second approach at 1 u/s
  // (10 latched: 5.3051); 7: index after the switch, same direction (6.2504); 8: index only (0.2504);
  // 9: index after the switch, reverse (4.2504); negative direction 6: the upper edge 8.7 ... from 0
  // moving down: reversal at the negative limit first.
  const Case cases[] = {{1, 1, 5.305}, {2, 1, 5.306}, {10, 1, 5.3051}, {7, 1, 6.2504}, {8, 1, 0.2504}, {9, 1, 4.2504},
                        {8, -1, -1.7496}, {6, -1, 5.3051}};
  for (const Case& k : cases) {
    Sim s(pulseHomeAxis());
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    const uint64_t done = runSmcHome(s, h, smcHome(k.mode, k.dir), 20000);
    EXPECT_TRUE(done && h.out.done) << k.mode << " " << sm3face::smcError(h.out.errorId);
    EXPECT_EQ(s.ax->set().p, 0.0) << k.mode;
    EXPECT_NEAR(mechanical(*s.ax), k.mech, 1e-9) << k.mode << " dir " << k.dir;
  }
}

// imode 8 (EZ only), +1 u/s: the mark at 0.2504 passes in the step of c0 + 256, is seen in c0 + 257;
// stop (0.005 u), back 0.0066 u (16.25 ms): Done at c0 + 284.  bHomeCompleteMode 0 leaves the
// coordinates alone, 2 moves on by fHomePosition and makes that 0; iDriverCounter delays Done.
TEST(Homing, SmcHomeIndexOnlyAndCompleteModes) {
  struct Case { int complete; int64_t counter; uint64_t doneAfter; double pos, mech; };
  const Case cases[] = {{1, 0, 284, 0, 0.2504}, {0, 0, 284, 0.2504, 0.2504}, {1, 50, 284 + 50, 0, 0.2504},
                        {2, 0, 284 + 410, 0, 0.6504}};
  for (const Case& k : cases) {
    Sim s(pulseHomeAxis());
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    SmcHomeInputs in = smcHome(8);
    in.completeMode = k.complete;
    in.driverCounter = k.counter;
    in.homePosition = 0.4;
    const uint64_t c0 = s.cycle;
    const uint64_t done = runSmcHome(s, h, in);
    EXPECT_TRUE(h.out.done);
    EXPECT_EQ(done, c0 + k.doneAfter) << k.complete << " " << k.counter;
    EXPECT_NEAR(s.ax->set().p, k.pos, 1e-12);
    EXPECT_NEAR(mechanical(*s.ax), k.mech, 1e-9);
  }
}

// A limit switch in the search direction: emergency stop (bELStopMode FALSE: v = 0 at once) or
// braking (TRUE), then the search goes the other way; iHomeElEnable FALSE ignores the limits.
TEST(Homing, SmcHomeLimitReversal) {
  for (bool decelerate : {false, true}) {
    Sim s(pulseHomeAxis());
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    SmcHomeInputs in = smcHome(6, -1);
    in.limitDecelerate = decelerate;
    const uint64_t c0 = s.cycle;
    uint64_t done = 0;
    for (int i = 0; i < 5000 && !done; ++i) {
      callSmcHome(s.k, h, *s.ax, true, in, s.ctx());
      const uint64_t c = s.cycle;
      s.endCycle();
      // The limit (-10.0052) closes in the step of c0 + 1051 (p = -10.01), seen in c0 + 1052.
      if (c == c0 + 1052) {
        EXPECT_NEAR(s.ax->set().p, decelerate ? -10.02 : -10.02, 1e-9);
        EXPECT_NEAR(s.ax->set().v, decelerate ? -10 : 0, 1e-9);
      }
      if (c == c0 + 1053) { EXPECT_NEAR(s.ax->set().v, decelerate ? -9.9 : 0.1, 1e-9); }
      if (h.out.done) done = c;
    }
    EXPECT_TRUE(done);
    EXPECT_NEAR(mechanical(*s.ax), 5.3051, 1e-9);   // entered moving +: the lower edge
  }
}

TEST(Homing, SmcHomeStopAndRelease) {
  for (bool viaStop : {true, false}) {
    Sim s(pulseHomeAxis());
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& h = s.slot(FbKind::Home);
    s.powerOn(p);
    SmcHomeInputs in = smcHome(0);
    for (int i = 0; i < 300; ++i) {
      callSmcHome(s.k, h, *s.ax, true, in, s.ctx());
      s.endCycle();
    }
    // t = 0.299: p = 2.49, v = 10; the stop starts at t = 0.3 (2.5) and takes 0.1 s (0.5 u).
    EXPECT_NEAR(s.ax->set().p, 2.49, 1e-9);
    in.stop = viaStop;
    const uint64_t c1 = s.cycle;
    uint64_t aborted = 0;
    for (int i = 0; i < 200 && !aborted; ++i) {
      callSmcHome(s.k, h, *s.ax, viaStop, in, s.ctx());
      const uint64_t c = s.cycle;
      s.endCycle();
      if (h.out.aborted) aborted = c;
      else ASSERT_TRUE(h.out.busy);
    }
    EXPECT_EQ(aborted, c1 + 100);
    EXPECT_NEAR(s.ax->set().p, 3.0, 1e-9);
    EXPECT_EQ(s.ax->state(), AxisState::Standstill);
    callSmcHome(s.k, h, *s.ax, viaStop, in, s.ctx());
    s.endCycle();
    EXPECT_EQ(h.out.aborted, viaStop);   // held while bExecute is TRUE, else one cycle
  }
}

TEST(Homing, SmcHomeErrors) {
  Sim s(pulseHomeAxis());
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& h = s.slot(FbKind::Home);
  auto edge = [&](const SmcHomeInputs& in) {
    callSmcHome(s.k, h, *s.ax, false, in, s.ctx());
    callSmcHome(s.k, h, *s.ax, true, in, s.ctx());
    s.endCycle();
  };
  edge(smcHome(0));
  EXPECT_EQ(h.out.errorId, Error::HomeAxisWasntStandstill);   // power off
  s.powerOn(p);
  const double nan = std::nan("");
  for (double v : {0.0, -5.0, nan}) {
    SmcHomeInputs in = smcHome(0);
    in.velocityFast = v;
    edge(in);
    EXPECT_EQ(h.out.errorId, Error::HomingInvalidVelAcc);
    in = smcHome(0);
    in.deceleration = v;
    edge(in);
    EXPECT_EQ(h.out.errorId, Error::HomingInvalidVelAcc);
  }
  for (int mode : {3, 4, 5, 11, -1}) {
    edge(smcHome(mode));
    EXPECT_EQ(h.out.errorId, Error::HomingInvalidVelAcc) << mode;
  }
  SmcHomeInputs in = smcHome(0, 0);
  edge(in);
  EXPECT_EQ(h.out.errorId, Error::HomingInvalidVelAcc);
  in = smcHome(0);
  in.completeMode = 3;
  edge(in);
  EXPECT_EQ(h.out.errorId, Error::HomingInvalidVelAcc);
  EXPECT_FALSE(h.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  s.k.errorStop(*s.ax, Error::DriveError, s.now, s.cycle);
  edge(smcHome(0));
  EXPECT_EQ(h.out.errorId, Error::HomeAxisInErrorStop);
  // The mode's sensor is not there: 17.
  AxisConfig cfg = pulseHomeAxis();
  cfg.drive.hasHomeSwitch = false;
  cfg.drive.indexPeriod = 0;
  Sim s2(cfg);
  FbSlot& p2 = s2.slot(FbKind::Power);
  FbSlot& h2 = s2.slot(FbKind::Home);
  s2.powerOn(p2);
  callSmcHome(s2.k, h2, *s2.ax, true, smcHome(0), s2.ctx());
  EXPECT_EQ(h2.out.errorId, Error::DiHomingError);
  s2.endCycle();
  callSmcHome(s2.k, h2, *s2.ax, false, smcHome(8), s2.ctx());
  callSmcHome(s2.k, h2, *s2.ax, true, smcHome(8), s2.ctx());
  EXPECT_EQ(h2.out.errorId, Error::DiHomingError);
}
