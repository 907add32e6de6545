// Profile tables, direct set points, torque / controller mode and the
// master-first stepping, cycle by cycle (1 ms cycles; cycle c0 = the call that
// sees the edge, its kernel step follows in endCycle()).  Positions against
// closed forms (docs/motion-profiles.md).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "MotionSim.h"
#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"
#include "stdlib-motion//core/Profiles.h"

using namespace stc::motion;
using stc::motion::test::Sim;

namespace {

constexpr double kTol = 1e-9;

std::vector<RawPoint> table(std::vector<std::pair<double, double>> pts) {
  std::vector<RawPoint> r;
  for (auto& [dt, v] : pts) r.push_back(RawPoint{static_cast<int64_t>(std::llround(dt * 1e9)), v});
  return r;
}

double S(double s) { return s * s * (3 - 2 * s); }

struct ProfileRun {
  Sim& s;
  FbSlot& fb;
  TableKind kind;
  std::vector<RawPoint> pts;
  bool absolute = true;
  double scale = 1, offset = 0;
  void call(bool execute) {
    callProfile(s.k, fb, *s.ax, execute, kind, static_cast<int>(pts.size()), pts, absolute, scale, offset, s.ctx());
  }
};

MoveInputs absMove(double pos, double v, double a) {
  MoveInputs in;
  in.position = pos;
  in.velocity = v;
  in.acceleration = in.deceleration = a;
  return in;
}

// A servo axis (CiA402 handshake) with an inertia for torque control.
AxisConfig servo(double inertia) {
  AxisConfig cfg;
  cfg.drive.kind = AxisKind::Servo;
  cfg.drive.inertia = inertia;
  return cfg;
}
void powerServo(Sim& s, FbSlot& p) {
  for (int i = 0; i < 6 && !p.out.status; ++i) {
    s.k.callPower(p, *s.ax, true, true, true, s.ctx());
    s.endCycle();
  }
  ASSERT_TRUE(p.out.status);
}

}  // namespace

// ---------------------------------------------------------------- MC_PositionProfile

TEST(MotionProfiles, PositionProfileOnePointIsTheSmoothStepAndDoneAtTheLastPoint) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  s.powerOn(p);
  ProfileRun r{s, fb, TableKind::Position, table({{1.0, 10.0}})};
  const uint64_t c0 = s.cycle;
  r.call(true);
  EXPECT_TRUE(fb.out.busy);
  EXPECT_FALSE(fb.out.done);
  EXPECT_EQ(s.ax->state(), AxisState::DiscreteMotion);
  s.endCycle();
  EXPECT_EQ(s.ax->set().p, 0.0);     // the profile starts at the time of c0
  for (int k = 1; k <= 1000; ++k) {
    r.call(true);
    s.endCycle();
    const double x = k * 1e-3;
    ASSERT_NEAR(s.ax->set().p, 10 * S(x), kTol) << k;
    ASSERT_NEAR(s.ax->set().v, 60 * x * (1 - x), kTol) << k;
    ASSERT_EQ(fb.out.done, k == 1000) << k;   // Done in the kernel step of c0 + 1000
    ASSERT_EQ(fb.out.busy, k < 1000) << k;
  }
  EXPECT_EQ(s.cycle - 1, c0 + 1000);
  EXPECT_EQ(s.ax->set().p, 10.0);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  r.call(true);   // held while Execute
  EXPECT_TRUE(fb.out.done);
  s.endCycle();
  r.call(false);
  EXPECT_FALSE(fb.out.done);
}

TEST(MotionProfiles, PositionProfileRelativeTableIsExactAtEveryPointAndC2) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  s.powerOn(p);
  // The manual's PT example, in u: +10 in 1 s, +40 in 2 s, -10 in 1 s, -5 in 0.5 s.
  ProfileRun r{s, fb, TableKind::Position, table({{1, 10}, {2, 40}, {1, -10}, {0.5, -5}})};
  r.absolute = false;
  const uint64_t c0 = s.cycle;
  const std::vector<std::pair<uint64_t, double>> knots = {{1000, 10}, {3000, 50}, {4000, 40}, {4500, 35}};
  double lastV = 0;
  for (int k = 0; k <= 4500; ++k) {
    r.call(true);
    s.endCycle();
    for (auto& [kc, pos] : knots)
      if (static_cast<uint64_t>(k) == kc) { ASSERT_NEAR(s.ax->set().p, pos, kTol) << k; }
    ASSERT_LT(std::fabs(s.ax->set().v - lastV), 0.5) << k;   // continuous velocity
    lastV = s.ax->set().v;
    ASSERT_EQ(fb.out.done, k == 4500) << k;
  }
  (void)c0;
  EXPECT_EQ(s.ax->set().v, 0.0);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  // The generator itself: C2 at the inner points, clamped velocities 0 at both ends.
  std::vector<TablePoint> pts = {{1, 10}, {2, 40}, {1, -10}, {0.5, -5}};
  TableGenerator g(TableKind::Position, pts, false, Kinematic{0, 0, 0}, 0);
  for (double t : {1.0, 3.0, 4.0}) {
    EXPECT_NEAR(g.at(t - 1e-12).a, g.at(t + 1e-12).a, 1e-6) << t;
    EXPECT_NEAR(g.at(t - 1e-12).v, g.at(t + 1e-12).v, 1e-9) << t;
  }
  EXPECT_EQ(g.at(0).v, 0.0);
  EXPECT_NEAR(g.at(4.5).v, 0.0, kTol);
}

TEST(MotionProfiles, PositionProfileAbsoluteScaleAndOffset) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  s.powerOn(p);
  ProfileRun r{s, fb, TableKind::Position, table({{0.5, 1}, {0.5, 20}})};
  r.scale = 2;
  r.offset = 1;    // points 3 and 41
  for (int k = 0; k <= 1000; ++k) {
    r.call(true);
    s.endCycle();
    if (k == 500) { EXPECT_NEAR(s.ax->set().p, 3, kTol); }
  }
  EXPECT_TRUE(fb.out.done);
  EXPECT_NEAR(s.ax->set().p, 41, kTol);
}

TEST(MotionProfiles, PositionProfileIsAbortedByAMove) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  ProfileRun r{s, fb, TableKind::Position, table({{1, 10}})};
  for (int k = 0; k < 100; ++k) {
    r.call(true);
    s.endCycle();
  }
  r.call(true);
  s.k.callMove(m, *s.ax, true, absMove(0, 10, 100), s.ctx());
  EXPECT_TRUE(fb.out.aborted);     // in the call that starts the move
  EXPECT_FALSE(fb.out.busy);
  EXPECT_TRUE(m.out.busy);
  s.endCycle();
  EXPECT_EQ(s.ax->state(), AxisState::DiscreteMotion);
  r.call(false);                   // held until Execute falls
  EXPECT_FALSE(fb.out.aborted);
}

TEST(MotionProfiles, SuperImposedIsRefusedDuringAProfile) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  FbSlot& sup = s.slot(FbKind::MoveSuperImposed);
  s.powerOn(p);
  ProfileRun r{s, fb, TableKind::Position, table({{1, 10}})};
  r.call(true);
  s.endCycle();
  r.call(true);
  MoveInputs in;
  in.distance = 1;
  in.velocity = in.acceleration = in.deceleration = 10;
  s.k.callMove(sup, *s.ax, true, in, s.ctx());
  EXPECT_TRUE(sup.out.error);
  EXPECT_EQ(sup.out.errorId, Error::NotReadyForMotion);
  EXPECT_TRUE(fb.out.busy);        // the profile runs on
  EXPECT_FALSE(fb.out.aborted);
}

TEST(MotionProfiles, ProfileInputErrors) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  const double nan = std::nan("");
  struct Case { TableKind kind; std::vector<RawPoint> pts; int n; double scale; Error e; };
  const std::vector<Case> cases = {
      {TableKind::Position, table({{1, 1}}), 0, 1, Error::PpArraySize},
      {TableKind::Position, table({{1, 1}}), 101, 1, Error::PpArraySize},
      {TableKind::Position, table({{1, 1}, {0, 2}}), 2, 1, Error::PpStep0ms},
      {TableKind::Position, table({{-1, 1}}), 1, 1, Error::PpStep0ms},
      {TableKind::Position, table({{1, nan}}), 1, 1, Error::PpArraySize},
      {TableKind::Position, table({{1, 1}}), 1, nan, Error::PpArraySize},
      {TableKind::Velocity, table({{1, 1}}), -1, 1, Error::VpArraySize},
      {TableKind::Velocity, table({{0, 1}}), 1, 1, Error::VpStep0ms},
      {TableKind::Acceleration, table({{1, 1}}), 200, 1, Error::ApArraySize},
      {TableKind::Acceleration, table({{1, 1}, {0, 1}}), 2, 1, Error::ApStep0ms},
  };
  // Power off: 20 once the table is valid.
  callProfile(s.k, fb, *s.ax, true, TableKind::Position, 1, table({{1, 1}}), true, 1, 0, s.ctx());
  EXPECT_TRUE(fb.out.error);
  EXPECT_EQ(fb.out.errorId, Error::RegulatorOrStartNotSet);
  callProfile(s.k, fb, *s.ax, false, TableKind::Position, 1, table({{1, 1}}), true, 1, 0, s.ctx());
  EXPECT_FALSE(fb.out.error);
  s.powerOn(p);
  for (const Case& c : cases) {
    callProfile(s.k, fb, *s.ax, true, c.kind, c.n, c.pts, true, c.scale, 0, s.ctx());
    EXPECT_TRUE(fb.out.error);
    EXPECT_FALSE(fb.out.busy);      // Busy never rises
    EXPECT_EQ(fb.out.errorId, c.e) << sm3face::smcError(c.e);
    s.endCycle();
    callProfile(s.k, fb, *s.ax, false, c.kind, c.n, c.pts, true, c.scale, 0, s.ctx());
    EXPECT_FALSE(fb.out.error);
    EXPECT_EQ(fb.out.errorId, Error::None);
    s.endCycle();
  }
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
}

// ---------------------------------------------------------------- MC_VelocityProfile

TEST(MotionProfiles, VelocityProfileSCurvesAndTrapezoidPositions) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  s.powerOn(p);
  ProfileRun r{s, fb, TableKind::Velocity, table({{1, 10}, {2, 10}, {1, 0}})};
  r.call(true);
  EXPECT_TRUE(fb.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::ContinuousMotion);
  s.endCycle();
  for (int k = 1; k <= 4000; ++k) {
    r.call(true);
    s.endCycle();
    if (k == 500) {
      EXPECT_NEAR(s.ax->set().v, 5, kTol);
      EXPECT_NEAR(s.ax->set().p, 10 * (0.125 - 0.03125), kTol);
      EXPECT_NEAR(s.ax->set().a, 15, kTol);   // 10 * 6 s (1 - s) / 1 s
    }
    if (k == 1000) { EXPECT_NEAR(s.ax->set().p, 5, kTol); EXPECT_NEAR(s.ax->set().v, 10, kTol); }
    if (k == 3000) { EXPECT_NEAR(s.ax->set().p, 25, kTol); EXPECT_NEAR(s.ax->set().v, 10, kTol); }
    ASSERT_EQ(fb.out.done, k == 4000) << k;
    if (k < 4000) { ASSERT_EQ(s.ax->state(), AxisState::ContinuousMotion); }
  }
  EXPECT_NEAR(s.ax->set().p, 30, kTol);
  EXPECT_EQ(s.ax->set().v, 0.0);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
}

TEST(MotionProfiles, VelocityProfileEndsMovingAndARepeatedRunAddsVelocity) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  s.powerOn(p);
  // Relative, scaled and offset: raw +2, -1 -> 2*2+1 = 5, 2*-1+1 = -1: V = 5, then 4.
  ProfileRun r{s, fb, TableKind::Velocity, table({{1, 2}, {1, -1}})};
  r.absolute = false;
  r.scale = 2;
  r.offset = 1;
  for (int k = 0; k <= 2000; ++k) {
    r.call(true);
    s.endCycle();
  }
  EXPECT_TRUE(fb.out.done);
  EXPECT_NEAR(s.ax->set().v, 4, kTol);
  EXPECT_NEAR(s.ax->set().p, 2.5 + 4.5, kTol);
  EXPECT_EQ(s.ax->state(), AxisState::ContinuousMotion);   // keeps moving at the end velocity
  r.call(false);
  s.endCycle();
  EXPECT_NEAR(s.ax->set().p, 7 + 0.004, kTol);
  // Second run of the same table: v = 4 + V(t).
  for (int k = 0; k <= 2000; ++k) {
    r.call(true);
    s.endCycle();
  }
  EXPECT_TRUE(fb.out.done);
  EXPECT_NEAR(s.ax->set().v, 8, kTol);
  EXPECT_NEAR(s.ax->set().p, 7.008 + 4 * 2 + 7, kTol);   // starts one cycle later, at 7.008
}

// ---------------------------------------------------------------- MC_AccelerationProfile

TEST(MotionProfiles, AccelerationProfileVelocityGainsTheMeanAcceleration) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Profile);
  s.powerOn(p);
  ProfileRun r{s, fb, TableKind::Acceleration, table({{0.5, 100}, {1, 100}, {0.5, 0}})};
  r.call(true);
  EXPECT_EQ(s.ax->state(), AxisState::DiscreteMotion);
  s.endCycle();
  for (int k = 1; k <= 2000; ++k) {
    r.call(true);
    s.endCycle();
    // velocity change of a segment A -> B = (A + B) / 2 * dt
    if (k == 500) { EXPECT_NEAR(s.ax->set().v, 25, kTol); EXPECT_NEAR(s.ax->set().p, 3.75, kTol); EXPECT_NEAR(s.ax->set().a, 100, kTol); }
    if (k == 1500) { EXPECT_NEAR(s.ax->set().v, 125, kTol); EXPECT_NEAR(s.ax->set().p, 78.75, kTol); }
    if (k == 250) { EXPECT_NEAR(s.ax->set().a, 50, kTol); }
    if (k < 2000) { ASSERT_EQ(s.ax->state(), AxisState::DiscreteMotion) << k; }
    ASSERT_EQ(fb.out.done, k == 2000) << k;
  }
  EXPECT_NEAR(s.ax->set().v, 150, kTol);
  EXPECT_NEAR(s.ax->set().p, 150, kTol);
  EXPECT_EQ(s.ax->state(), AxisState::ContinuousMotion);   // the axis keeps the end velocity
  r.call(false);
  s.endCycle();
  EXPECT_NEAR(s.ax->set().p, 150.15, kTol);
}

TEST(MotionProfiles, AccelerationProfileOnlyFromStandstillOrDiscreteMotion) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& mv = s.slot(FbKind::MoveVelocity);
  FbSlot& fb = s.slot(FbKind::Profile);
  s.powerOn(p);
  MoveInputs in;
  in.velocity = 10;
  in.acceleration = in.deceleration = 100;
  s.k.callMove(mv, *s.ax, true, in, s.ctx());
  s.endCycle();
  EXPECT_EQ(s.ax->state(), AxisState::ContinuousMotion);
  callProfile(s.k, fb, *s.ax, true, TableKind::Acceleration, 1, table({{1, 1}}), true, 1, 0, s.ctx());
  EXPECT_EQ(fb.out.errorId, Error::NotReadyForMotion);
  EXPECT_TRUE(mv.out.busy);    // the running command is untouched
  FbSlot& pp = s.slot(FbKind::Profile);
  callProfile(s.k, pp, *s.ax, true, TableKind::Position, 1, table({{1, 1}}), true, 1, 0, s.ctx());
  EXPECT_EQ(pp.out.errorId, Error::NotReadyForMotion);
  // A velocity table is accepted in continuous motion and adds to the velocity.
  FbSlot& vp = s.slot(FbKind::Profile);
  s.k.callMove(mv, *s.ax, true, in, s.ctx());
  callProfile(s.k, vp, *s.ax, true, TableKind::Velocity, 1, table({{0.1, 5}}), true, 1, 0, s.ctx());
  EXPECT_TRUE(vp.out.busy);
  EXPECT_TRUE(mv.out.aborted);
}

// ---------------------------------------------------------------- SMC_Follow*

TEST(MotionFollow, FollowPositionWritesTheSetPositionEveryCycle) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Follow);
  s.powerOn(p);
  FollowInputs in;
  in.mask = kFollowPosition;
  for (int k = 0; k < 10; ++k) {
    in.position = 0.5 * (k + 1);
    callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
    EXPECT_TRUE(fb.out.busy);
    EXPECT_EQ(s.ax->state(), AxisState::SynchronizedMotion);
    s.endCycle();
    EXPECT_EQ(s.ax->set().p, in.position);                  // this call's value in this cycle's step
    EXPECT_NEAR(s.ax->set().v, 500, kTol);                  // dp / cycle time
    EXPECT_NEAR(s.ax->set().a, k == 0 ? 500000 : 0, 1e-6);  // dv / cycle time
    EXPECT_EQ(s.ax->actPosition(), in.position);
  }
  // Execute FALSE does not end it (no Done output); another motion command does.
  in.position = 5.5;
  callFollow(s.k, fb, *s.ax, false, false, in, s.ctx());
  EXPECT_TRUE(fb.out.busy);
  s.endCycle();
  EXPECT_EQ(s.ax->set().p, 5.5);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  callFollow(s.k, fb, *s.ax, false, false, in, s.ctx());
  s.k.callMove(m, *s.ax, true, absMove(10, 1000, 1e6), s.ctx());
  EXPECT_TRUE(fb.out.aborted);
  EXPECT_FALSE(fb.out.busy);
  EXPECT_EQ(s.ax->state(), AxisState::DiscreteMotion);
  s.endCycle();
  EXPECT_NEAR(s.ax->set().p, 6.0, kTol);   // the move starts from the follow state at c0 (5.5 + 500 u/s * 1 ms)
  callFollow(s.k, fb, *s.ax, false, false, in, s.ctx());
  s.k.callMove(m, *s.ax, true, absMove(10, 1000, 1e6), s.ctx());
  s.endCycle();
  EXPECT_FALSE(fb.out.aborted);            // Execute was FALSE: visible for one cycle
}

TEST(MotionFollow, FollowMustBeCalledEveryCycle) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Follow);
  s.powerOn(p);
  FollowInputs in;
  in.mask = kFollowPosition;
  callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
  s.endCycle();
  s.endCycle();   // not called
  EXPECT_EQ(s.ax->state(), AxisState::ErrorStop);
  EXPECT_TRUE(fb.out.error);
  EXPECT_EQ(fb.out.errorId, Error::FbWasntCalledDuringMotion);
}

TEST(MotionFollow, FollowPositionVelocityTakesBothValues) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Follow);
  s.powerOn(p);
  FollowInputs in;
  in.mask = kFollowPosition | kFollowVelocity;
  const double v[] = {7, 7, 9};
  for (int k = 0; k < 3; ++k) {
    in.position = 0.01 * (k + 1);
    in.velocity = v[k];
    callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
    s.endCycle();
    EXPECT_EQ(s.ax->set().p, in.position);
    EXPECT_EQ(s.ax->set().v, v[k]);      // as given, not derived
    EXPECT_NEAR(s.ax->set().a, (v[k] - (k ? v[k - 1] : 0)) / 1e-3, 1e-6);
  }
}

TEST(MotionFollow, FollowVelocityIntegratesThePosition) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Follow);
  s.powerOn(p);
  FollowInputs in;
  in.mask = kFollowVelocity;
  const double v[] = {100, 100, 200, -50};
  const double pos[] = {0.05, 0.15, 0.30, 0.375};   // trapezoids of the set velocities
  for (int k = 0; k < 4; ++k) {
    in.velocity = v[k];
    callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
    s.endCycle();
    EXPECT_EQ(s.ax->set().v, v[k]);       // changes act at once (unlike MC_MoveVelocity)
    EXPECT_NEAR(s.ax->set().p, pos[k], kTol);
    EXPECT_EQ(s.ax->state(), AxisState::SynchronizedMotion);
  }
}

TEST(MotionFollow, FollowSetValuesMaskAbortAndErrors) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Follow);
  FollowInputs in;
  in.mask = kFollowPosition;
  callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
  EXPECT_EQ(fb.out.errorId, Error::RegulatorOrStartNotSet);   // not enabled
  callFollow(s.k, fb, *s.ax, false, false, in, s.ctx());
  s.powerOn(p);
  in.mask = kFollowCurrent | kFollowPosition;                  // no current controller
  callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
  EXPECT_EQ(fb.out.errorId, Error::WrongControllerMode);
  EXPECT_FALSE(fb.out.busy);
  callFollow(s.k, fb, *s.ax, false, false, in, s.ctx());
  EXPECT_FALSE(fb.out.error);
  // Mask 7: position, velocity and acceleration as given.
  in.mask = kFollowPosition | kFollowVelocity | kFollowAcceleration;
  in.position = 1;
  in.velocity = 2;
  in.acceleration = 3;
  callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
  s.endCycle();
  EXPECT_EQ(s.ax->set().p, 1.0);
  EXPECT_EQ(s.ax->set().v, 2.0);
  EXPECT_EQ(s.ax->set().a, 3.0);
  // Mask 4: acceleration only; velocity and position integrate.
  in.mask = kFollowAcceleration;
  in.acceleration = 5;
  callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
  s.endCycle();
  EXPECT_NEAR(s.ax->set().v, 2 + 0.5 * (3 + 5) * 1e-3, kTol);
  EXPECT_NEAR(s.ax->set().p, 1 + 0.5 * (2 + 2.004) * 1e-3, kTol);
  // bAbort: CommandAborted, the axis keeps its last velocity in synchronized_motion.
  const Kinematic last = s.ax->set();
  callFollow(s.k, fb, *s.ax, true, true, in, s.ctx());
  EXPECT_TRUE(fb.out.aborted);
  EXPECT_FALSE(fb.out.busy);
  s.endCycle();
  EXPECT_NEAR(s.ax->set().p, last.p + last.v * 1e-3, kTol);
  EXPECT_EQ(s.ax->state(), AxisState::SynchronizedMotion);
  s.endCycle();   // not called: no controller, no error 30
  EXPECT_NE(s.ax->state(), AxisState::ErrorStop);
}

TEST(MotionFollow, FollowPositionOnAModuloAxisUnwraps) {
  AxisConfig cfg;
  cfg.period = 360;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& fb = s.slot(FbKind::Follow);
  s.powerOn(p);
  FollowInputs in;
  in.mask = kFollowPosition;
  const double in1[] = {358, 359.5, 1, 3};
  const double unwrapped[] = {-2, -0.5, 1, 3};   // nearest to the previous set position
  for (int k = 0; k < 4; ++k) {
    in.position = in1[k];
    callFollow(s.k, fb, *s.ax, true, false, in, s.ctx());
    s.endCycle();
    EXPECT_NEAR(s.ax->set().p, unwrapped[k], kTol);
    EXPECT_NEAR(s.ax->reportPosition(s.ax->set().p), in1[k], kTol);
  }
  EXPECT_NEAR(s.ax->set().v, 2000, 1e-6);
}

// ---------------------------------------------------------------- torque and controller mode

TEST(MotionTorque, SetControllerModeAndSetTorqueAccelerateTheInertia) {
  Sim s(servo(0.5));
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& mode = s.slot(FbKind::Config);
  FbSlot& tq = s.slot(FbKind::Torque);
  powerServo(s, p);
  // Not in torque mode: 75.
  callSetTorque(s.k, tq, *s.ax, true, 2, s.ctx());
  EXPECT_TRUE(tq.out.error);
  EXPECT_EQ(tq.out.errorId, Error::StWrongControllerMode);
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  s.endCycle();
  callSetTorque(s.k, tq, *s.ax, false, 2, s.ctx());
  EXPECT_FALSE(tq.out.error);
  // Switch to torque control: Busy in the call, Done in the kernel step of the edge cycle.
  callSetControllerMode(s.k, mode, *s.ax, true, static_cast<int16_t>(ControllerMode::Torque), s.ctx());
  EXPECT_TRUE(mode.out.busy);
  EXPECT_FALSE(mode.out.done);
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  s.endCycle();
  EXPECT_TRUE(mode.out.done);
  EXPECT_FALSE(mode.out.busy);
  EXPECT_EQ(s.ax->drive().modeOfOperation(), kModeCst);
  int64_t disp = 0;
  s.ax->drive().readObject(0x6061, 0, disp);
  EXPECT_EQ(disp, 10);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  // Moves are refused in torque control.
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.k.callMove(m, *s.ax, true, absMove(1, 1, 1), s.ctx());
  EXPECT_EQ(m.out.errorId, Error::WrongControllerMode);
  FbSlot& stop = s.slot(FbKind::Stop);
  MoveInputs dec;
  dec.deceleration = 10;
  s.k.callStop(stop, *s.ax, true, dec, s.ctx());
  EXPECT_EQ(stop.out.errorId, Error::WrongControllerMode);
  // Torque 2 on inertia 0.5: a = 4, v = 4 t, p = 2 t^2 (exact: constant acceleration).
  for (int k = 1; k <= 1000; ++k) {
    s.k.callPower(p, *s.ax, true, true, true, s.ctx());
    callSetControllerMode(s.k, mode, *s.ax, true, 1, s.ctx());
    callSetTorque(s.k, tq, *s.ax, true, 2, s.ctx());
    ASSERT_TRUE(tq.out.busy);
    s.endCycle();
    const double t = k * 1e-3;
    ASSERT_NEAR(s.ax->actVelocity(), 4 * t, kTol) << k;
    ASSERT_NEAR(s.ax->actPosition(), 2 * t * t, kTol) << k;
    ASSERT_EQ(s.ax->set().p, s.ax->actPosition());     // the set point follows the motor
    ASSERT_EQ(s.ax->set().v, s.ax->actVelocity());
    ASSERT_EQ(s.ax->actTorque(), 2.0);
    ASSERT_EQ(s.ax->state(), AxisState::ContinuousMotion);
  }
  int64_t target = 0;
  s.ax->drive().readObject(0x6071, 0, target);
  EXPECT_EQ(target, 20);
  // Enable FALSE: the torque drops to 0 and the load coasts at 4 u/s.
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  callSetTorque(s.k, tq, *s.ax, false, 2, s.ctx());
  EXPECT_FALSE(tq.out.busy);
  s.endCycle();
  EXPECT_EQ(s.ax->actTorque(), 0.0);
  EXPECT_NEAR(s.ax->actVelocity(), 4, kTol);
  EXPECT_NEAR(s.ax->actPosition(), 2 + 4e-3, kTol);
  // Back to position control: the axis holds where it is (standstill after the step).
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  callSetControllerMode(s.k, mode, *s.ax, false, 3, s.ctx());
  callSetControllerMode(s.k, mode, *s.ax, true, 3, s.ctx());
  const double at = s.ax->actPosition();
  s.endCycle();
  EXPECT_TRUE(mode.out.done);
  EXPECT_EQ(s.ax->drive().modeOfOperation(), kModeCsp);
  EXPECT_EQ(s.ax->set().v, 0.0);
  EXPECT_EQ(s.ax->set().p, at);
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
}

TEST(MotionTorque, LeavingTorqueModeAbortsSetTorque) {
  Sim s(servo(1));
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& mode = s.slot(FbKind::Config);
  FbSlot& tq = s.slot(FbKind::Torque);
  powerServo(s, p);
  callSetControllerMode(s.k, mode, *s.ax, true, 1, s.ctx());
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  s.endCycle();
  callSetControllerMode(s.k, mode, *s.ax, false, 1, s.ctx());
  callSetTorque(s.k, tq, *s.ax, true, 1, s.ctx());
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  s.endCycle();
  callSetTorque(s.k, tq, *s.ax, true, 1, s.ctx());
  callSetControllerMode(s.k, mode, *s.ax, true, 2, s.ctx());   // velocity control
  EXPECT_TRUE(tq.out.aborted);
  EXPECT_FALSE(tq.out.busy);
  EXPECT_EQ(s.ax->drive().targetTorque(), 0.0);
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  s.endCycle();
  EXPECT_TRUE(mode.out.done);
  EXPECT_EQ(s.ax->drive().modeOfOperation(), kModeCsv);
  callSetTorque(s.k, tq, *s.ax, true, 1, s.ctx());
  EXPECT_TRUE(tq.out.aborted);      // held while Enable
  callSetTorque(s.k, tq, *s.ax, false, 1, s.ctx());
  EXPECT_FALSE(tq.out.aborted);
}

TEST(MotionTorque, VelocityModeFollowsTheSetVelocity) {
  Sim s(servo(0));
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& mode = s.slot(FbKind::Config);
  FbSlot& mv = s.slot(FbKind::MoveVelocity);
  powerServo(s, p);
  callSetControllerMode(s.k, mode, *s.ax, true, 2, s.ctx());
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  s.endCycle();
  ASSERT_TRUE(mode.out.done);
  MoveInputs in;
  in.velocity = 10;
  in.acceleration = in.deceleration = 100;
  for (int k = 0; k <= 200; ++k) {
    s.k.callPower(p, *s.ax, true, true, true, s.ctx());
    s.k.callMove(mv, *s.ax, true, in, s.ctx());
    s.endCycle();
    ASSERT_EQ(s.ax->actVelocity(), s.ax->set().v) << k;
    // ramp aligned with the cycles: the trapezoid integral is the exact position
    ASSERT_NEAR(s.ax->actPosition(), s.ax->set().p, kTol) << k;
  }
  EXPECT_TRUE(mv.out.inState);
  EXPECT_NEAR(s.ax->set().p, 0.5 + 10 * 0.1, kTol);
}

TEST(MotionTorque, ControllerModeErrors) {
  {
    Sim s;   // virtual axis: no drive modes
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& mode = s.slot(FbKind::Config);
    s.powerOn(p);
    callSetControllerMode(s.k, mode, *s.ax, true, 1, s.ctx());
    EXPECT_EQ(mode.out.errorId, Error::ScmNotSupported);
    EXPECT_FALSE(mode.out.busy);
  }
  Sim s(servo(1));
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& mode = s.slot(FbKind::Config);
  FbSlot& tq = s.slot(FbKind::Torque);
  FbSlot& st = s.slot(FbKind::Stop);
  callSetTorque(s.k, tq, *s.ax, true, 1, s.ctx());
  EXPECT_EQ(tq.out.errorId, Error::RegulatorOrStartNotSet);
  callSetTorque(s.k, tq, *s.ax, false, 1, s.ctx());
  powerServo(s, p);
  for (int16_t m : {0, 4, 7, -1}) {   // no control, current, unknown
    callSetControllerMode(s.k, mode, *s.ax, true, m, s.ctx());
    EXPECT_EQ(mode.out.errorId, Error::ScmNotSupported) << m;
    callSetControllerMode(s.k, mode, *s.ax, false, m, s.ctx());
    EXPECT_FALSE(mode.out.error);
  }
  // Stopping: 71.
  MoveInputs halt;
  halt.deceleration = 10;
  s.k.callStop(st, *s.ax, true, halt, s.ctx());
  EXPECT_EQ(s.ax->state(), AxisState::Stopping);
  callSetControllerMode(s.k, mode, *s.ax, true, 1, s.ctx());
  EXPECT_EQ(mode.out.errorId, Error::ScmAxisInWrongState);
  callSetControllerMode(s.k, mode, *s.ax, false, 1, s.ctx());
  s.k.callPower(p, *s.ax, true, true, true, s.ctx());
  s.endCycle();
  s.k.callStop(st, *s.ax, false, halt, s.ctx());
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  // A drive fault in the step of the edge cycle interrupts the switch: 72, mode restored.
  AxisConfig cfg = servo(1);
  cfg.drive.faults.push_back(FaultEvent{7'000'000, FaultKind::DriveError, 0x5530});
  Sim f(cfg);
  FbSlot& p2 = f.slot(FbKind::Power);
  FbSlot& mode2 = f.slot(FbKind::Config);
  powerServo(f, p2);
  while (f.now < 7'000'000) {
    f.k.callPower(p2, *f.ax, true, true, true, f.ctx());
    f.endCycle();
  }
  callSetControllerMode(f.k, mode2, *f.ax, true, 1, f.ctx());
  EXPECT_TRUE(mode2.out.busy);
  f.k.callPower(p2, *f.ax, true, true, true, f.ctx());
  f.endCycle();
  EXPECT_EQ(f.ax->state(), AxisState::ErrorStop);
  EXPECT_TRUE(mode2.out.error);
  EXPECT_EQ(mode2.out.errorId, Error::ScmInterrupted);
  EXPECT_EQ(f.ax->drive().modeOfOperation(), kModeCsp);
  // Errorstop: 71.
  callSetControllerMode(f.k, mode2, *f.ax, false, 1, f.ctx());
  f.endCycle();
  callSetControllerMode(f.k, mode2, *f.ax, true, 1, f.ctx());
  EXPECT_EQ(mode2.out.errorId, Error::ScmAxisInWrongState);
}

// ---------------------------------------------------------------- master / slave stepping

namespace {
// A coupling for the test: slave set point = 2 x master set point of the same cycle.
class DoubleCoupling : public FbBehaviour {
public:
  Axis* master = nullptr;
  bool hook = true;
  std::shared_ptr<DirectGenerator> gen;
  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    gen = std::make_shared<DirectGenerator>();
    gen->state = ax.set();
    ax.startExternal(gen, nowNs);
    ax.setState(AxisState::SynchronizedMotion);
    if (hook) ax.master = master;   // as every coupling does when it takes control
  }
  void beforeStep(Kernel&, FbSlot&, Axis& ax, int64_t nowNs, uint64_t) override {
    const Kinematic& m = master->set();
    gen->state = Kinematic{2 * m.p, 2 * m.v, 2 * m.a};
    gen->tSet = ax.movement().t(nowNs);
  }
};

// Slave added first (index 0), master second: the kernel must still step the master first.
double maxCouplingError(bool hook) {
  Sim s;
  Axis& slave = *s.ax;
  Axis& master = s.k.addAxis(AxisConfig{});
  master.task = 0;
  FbSlot& ps = s.slot(FbKind::Power);
  FbSlot& pm = s.slot(FbKind::Power);
  FbSlot& cpl = s.slot(FbKind::Other);
  FbSlot& mv = s.slot(FbKind::MoveAbsolute);
  s.k.callPower(ps, slave, true, true, true, s.ctx());
  s.k.callPower(pm, master, true, true, true, s.ctx());
  auto b = std::make_unique<DoubleCoupling>();
  b->master = &master;
  b->hook = hook;
  cpl.behaviour = std::move(b);
  double worst = 0;
  for (int k = 0; k < 300; ++k) {
    if (k == 0) s.k.accept(cpl, slave, s.ctx());
    if (k == 0) { EXPECT_EQ(slave.state(), AxisState::SynchronizedMotion); }
    cpl.lastCallCycle = s.cycle;
    s.k.callMove(mv, master, true, absMove(1, 10, 100), s.ctx());
    s.endCycle();
    worst = std::max(worst, std::fabs(slave.set().p - 2 * master.set().p));
    if (hook) { EXPECT_EQ(slave.set().v, 2 * master.set().v); }
  }
  EXPECT_TRUE(cpl.out.busy);
  EXPECT_EQ(slave.state(), AxisState::SynchronizedMotion);
  EXPECT_NEAR(master.set().p, 1.0, kTol);
  return worst;
}
}  // namespace

TEST(MotionCoupling, SlaveIsSteppedAfterItsMasterWhateverTheOrder) {
  EXPECT_EQ(maxCouplingError(true), 0.0);
  // Without the hook the slave (added first) reads the master of the previous cycle.
  EXPECT_GT(maxCouplingError(false), 1e-3);
}
