// Couplings cycle by cycle against closed forms (docs/motion-sync.md): gear
// ratio and ramp bounds, position gearing to the sync point, phasing, gear
// out, refused couplings.  The master is a second virtual axis of the Sim.
#include <gtest/gtest.h>

#include <cmath>

#include "MotionSim.h"
#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"
#include "stdlib-motion//core/Coupling.h"

using namespace stc::motion;
using stc::motion::test::Sim;

namespace {

// A Sim with a master (s.ax) and a slave, both powered, in task 0.
struct Pair {
  Sim s;
  Axis* master;
  Axis* slave;
  FbSlot* mv;
  explicit Pair(AxisConfig slaveCfg = {}, AxisConfig masterCfg = {}) : s(masterCfg) {
    master = s.ax;
    slave = &s.k.addAxis(slaveCfg);
    slave->task = 0;
    s.powerOn(s.slot(FbKind::Power));
    s.k.callPower(s.slot(FbKind::Power), *slave, true, true, true, s.ctx());
    mv = &s.slot(FbKind::MoveVelocity);
  }
  // The master runs at v (acceleration a) from this cycle on.
  void masterVelocity(double v, double a) {
    MoveInputs in;
    in.velocity = v;
    in.acceleration = in.deceleration = a;
    in.direction = Direction::Positive;
    s.k.callMove(*mv, *master, true, in, s.ctx());
  }
  void keepMaster() { s.k.callMove(*mv, *master, true, mv->in, s.ctx()); }
};

GearInputs gear(int64_t num, int64_t den, double acc, double dec) {
  GearInputs g;
  g.numerator = num;
  g.denominator = den;
  g.acceleration = acc;
  g.deceleration = dec;
  return g;
}

}  // namespace

// Gear 3:2: the slave ramps at 500 u/s^2 (never more) to 1.5 x the master velocity; from
// the cycle InGear rises, its velocity is exactly 1.5 x the master's and its distance 1.5 x.
TEST(Coupling, GearInThreeToTwo) {
  Pair p;
  FbSlot& g = p.s.slot(FbKind::GearIn);
  p.masterVelocity(100, 1000);   // master: 100 u/s after 0.1 s
  uint64_t inGearCycle = 0;
  double lastV = 0, lockM = 0, lockS = 0;
  for (int i = 0; i < 200; ++i) {   // the master runs at 100 u/s before the slave couples
    p.keepMaster();
    p.s.endCycle();
  }
  for (int i = 0; i < 1000; ++i) {
    p.keepMaster();
    callGearIn(p.s.k, g, *p.master, *p.slave, true, gear(3, 2, 500, 500), p.s.ctx());
    const uint64_t c = p.s.cycle;
    p.s.endCycle();
    ASSERT_TRUE(g.out.busy);
    ASSERT_FALSE(g.out.error);
    const double v = p.slave->set().v;
    if (!inGearCycle) {
      EXPECT_LE(std::fabs(v - lastV), 500 * 1e-3 * (1 + 1e-12)) << "ramp faster than Acceleration in cycle " << c;
      if (g.out.inState) {
        inGearCycle = c;
        lockM = p.master->set().p;
        lockS = p.slave->set().p;
      }
    } else {
      ASSERT_TRUE(g.out.inState);
      ASSERT_EQ(v, 1.5 * p.master->set().v) << "cycle " << c;
      ASSERT_NEAR(p.slave->set().p - lockS, 1.5 * (p.master->set().p - lockM), 1e-9) << "cycle " << c;
    }
    lastV = v;
  }
  // Execute in cycle 201; 0 -> 150 u/s at 500 u/s^2 takes 0.3 s: the step of cycle 501 locks.
  EXPECT_EQ(inGearCycle, 501u);
  EXPECT_EQ(p.slave->state(), AxisState::SynchronizedMotion);
}

// Master and slave at rest: the slave is in gear at once (no ramp needed) and then follows
// the master's acceleration x ratio.
TEST(Coupling, GearInAtRestIsInGearAtOnce) {
  Pair p;
  FbSlot& g = p.s.slot(FbKind::GearIn);
  callGearIn(p.s.k, g, *p.master, *p.slave, true, gear(3, 2, 500, 500), p.s.ctx());
  p.s.endCycle();
  EXPECT_TRUE(g.out.inState);
  for (int i = 0; i < 50; ++i) {
    if (i == 0) p.masterVelocity(100, 1000);
    else p.keepMaster();
    callGearIn(p.s.k, g, *p.master, *p.slave, true, gear(3, 2, 500, 500), p.s.ctx());
    p.s.endCycle();
    ASSERT_NEAR(p.slave->set().p, 1.5 * p.master->set().p, 1e-12);
  }
}

// MC_GearInPos 2:1: the master at 100 u/s enters the start distance (300) at t = 3.005 s
// (StartSync) and reaches MasterSyncPosition 500 at t = 5.005 s: in that very cycle InSync
// rises and the slave is at SlaveSyncPosition 300; afterwards slave = 300 + 2 (master - 500).
TEST(Coupling, GearInPosReachesTheSyncPointWithTheMaster) {
  Pair p;
  FbSlot& g = p.s.slot(FbKind::GearInPos);
  GearInPosInputs in;
  in.numerator = 2;
  in.masterSyncPosition = 500;
  in.slaveSyncPosition = 300;
  in.masterStartDistance = 200;
  p.masterVelocity(100, 10000);   // 100 u/s after 10 ms: master(t) = 100 (t - 0.005)
  uint64_t startCycle = 0, syncCycle = 0;
  double prevSlave = 0;
  for (int i = 0; i < 7000; ++i) {
    p.keepMaster();
    callGearInPos(p.s.k, g, *p.master, *p.slave, true, in, p.s.ctx());
    const uint64_t c = p.s.cycle;
    p.s.endCycle();
    ASSERT_FALSE(g.out.error) << sm3face::smcError(g.out.errorId);
    if (g.out.startSync && !startCycle) startCycle = c;
    if (!startCycle) {
      ASSERT_EQ(p.slave->set().p, 0.0);
    }
    if (g.out.inState && !syncCycle) {
      syncCycle = c;
      EXPECT_NEAR(p.master->set().p, 500, 1e-9);
      EXPECT_NEAR(p.slave->set().p, 300, 1e-9);
    }
    if (syncCycle) {
      ASSERT_NEAR(p.slave->set().p, 300 + 2 * (p.master->set().p - 500), 1e-9);
    }
    if (startCycle) {
      ASSERT_GE(p.slave->set().p, prevSlave - 1e-12);   // no reversal from rest
    }
    prevSlave = p.slave->set().p;
  }
  EXPECT_EQ(startCycle, 3006u);   // cycle n runs at (n - 1) ms
  EXPECT_EQ(syncCycle, 5006u);
  // The velocity is continuous at the sync point: 2 x 100.
  EXPECT_NEAR(p.slave->set().v, 200, 1e-9);
}

// MC_Phasing on a 1:1 gear: the slave sees the master shifted by 10 (it lags by 10) once Done.
TEST(Coupling, PhasingShiftsTheMasterTheSlaveSees) {
  Pair p;
  FbSlot& g = p.s.slot(FbKind::GearIn);
  FbSlot& ph = p.s.slot(FbKind::Phasing);
  p.masterVelocity(100, 1000);
  bool phased = false;
  uint64_t doneCycle = 0;
  double offsetBefore = 0;
  for (int i = 0; i < 3000; ++i) {
    p.keepMaster();
    callGearIn(p.s.k, g, *p.master, *p.slave, true, gear(1, 1, 1000, 1000), p.s.ctx());
    if (g.out.inState && !phased && i > 500) {
      offsetBefore = p.slave->set().p - p.master->set().p;
      callPhasing(p.s.k, ph, *p.master, *p.slave, true, PhasingInputs{10, 50, 500, 500, 0}, p.s.ctx());
      phased = true;
    } else if (phased) {
      callPhasing(p.s.k, ph, *p.master, *p.slave, true, PhasingInputs{10, 50, 500, 500, 0}, p.s.ctx());
    }
    const uint64_t c = p.s.cycle;
    p.s.endCycle();
    if (ph.out.done && !doneCycle) doneCycle = c;
  }
  ASSERT_TRUE(phased);
  ASSERT_NE(doneCycle, 0u);
  EXPECT_FALSE(ph.out.error);
  EXPECT_NEAR(p.slave->set().p - p.master->set().p, offsetBefore - 10, 1e-9);
  EXPECT_TRUE(g.out.inState);
}

// MC_GearOut: the gear ends with CommandAborted, Done in the call; the slave keeps its velocity.
TEST(Coupling, GearOutLeavesTheSlaveMoving) {
  Pair p;
  FbSlot& g = p.s.slot(FbKind::GearIn);
  FbSlot& out = p.s.slot(FbKind::Other);
  p.masterVelocity(100, 1000);
  for (int i = 0; i < 500; ++i) {
    p.keepMaster();
    callGearIn(p.s.k, g, *p.master, *p.slave, true, gear(2, 1, 1000, 1000), p.s.ctx());
    p.s.endCycle();
  }
  ASSERT_TRUE(g.out.inState);
  callCouplingOut(p.s.k, out, *p.slave, true, false, p.s.ctx());
  EXPECT_TRUE(out.out.done);
  EXPECT_TRUE(g.out.aborted);
  EXPECT_EQ(p.slave->state(), AxisState::ContinuousMotion);
  const double p0 = p.slave->set().p;
  for (int i = 0; i < 100; ++i) {
    p.keepMaster();
    p.s.endCycle();
  }
  EXPECT_NEAR(p.slave->set().v, 200, 1e-9);
  EXPECT_NEAR(p.slave->set().p - p0, 200 * 0.1, 1e-9);
  // A second GearOut finds no gear: error.
  FbSlot& out2 = p.s.slot(FbKind::Other);
  callCouplingOut(p.s.k, out2, *p.slave, true, false, p.s.ctx());
  EXPECT_TRUE(out2.out.error);
}

// Refused couplings: a slave that is its own master, a loop of couplings, bad ratio and ramps.
TEST(Coupling, RefusedCouplings) {
  Pair p;
  FbSlot& self = p.s.slot(FbKind::GearIn);
  callGearIn(p.s.k, self, *p.slave, *p.slave, true, gear(1, 1, 10, 10), p.s.ctx());
  EXPECT_EQ(self.out.errorId, Error::NotReadyForMotion);
  FbSlot& ab = p.s.slot(FbKind::GearIn);
  callGearIn(p.s.k, ab, *p.master, *p.slave, true, gear(1, 1, 10, 10), p.s.ctx());
  ASSERT_TRUE(ab.out.busy);
  FbSlot& ba = p.s.slot(FbKind::GearIn);
  callGearIn(p.s.k, ba, *p.slave, *p.master, true, gear(1, 1, 10, 10), p.s.ctx());
  EXPECT_EQ(ba.out.errorId, Error::NotReadyForMotion);   // master <- slave <- master: a loop
  FbSlot& d0 = p.s.slot(FbKind::GearIn);
  callGearIn(p.s.k, d0, *p.master, *p.slave, true, gear(1, 0, 10, 10), p.s.ctx());
  EXPECT_EQ(d0.out.errorId, Error::GiRatioDenom);
  FbSlot& a0 = p.s.slot(FbKind::GearIn);
  callGearIn(p.s.k, a0, *p.master, *p.slave, true, gear(1, 1, 1e308, 10), p.s.ctx());
  EXPECT_EQ(a0.out.errorId, Error::GiInvalidAcc);
  FbSlot& dd = p.s.slot(FbKind::GearIn);
  callGearIn(p.s.k, dd, *p.master, *p.slave, true, gear(1, 1, 10, 0), p.s.ctx());
  EXPECT_EQ(dd.out.errorId, Error::GiInvalidDec);
  FbSlot& rev = p.s.slot(FbKind::GearInPos);
  GearInPosInputs in;
  in.avoidReversal = true;   // a linear slave
  callGearInPos(p.s.k, rev, *p.master, *p.slave, true, in, p.s.ctx());
  EXPECT_EQ(rev.out.errorId, Error::GipAvoidReversalForFiniteAxis);
}

// Another command on the slave aborts the gear (CommandAborted) and ends the coupling.
TEST(Coupling, AnotherCommandAbortsTheGear) {
  Pair p;
  FbSlot& g = p.s.slot(FbKind::GearIn);
  p.masterVelocity(100, 1000);
  for (int i = 0; i < 10; ++i) {
    p.keepMaster();
    callGearIn(p.s.k, g, *p.master, *p.slave, true, gear(1, 1, 1000, 1000), p.s.ctx());
    p.s.endCycle();
  }
  FbSlot& halt = p.s.slot(FbKind::Halt);
  MoveInputs h;
  h.deceleration = 1000;
  p.s.k.callHalt(halt, *p.slave, true, h, p.s.ctx());
  EXPECT_TRUE(g.out.aborted);
  EXPECT_EQ(p.slave->master, nullptr);
}
