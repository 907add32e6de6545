// Diagnostics, FB errors, touch probe and cam switch cycle by cycle
// (docs/motion-diag.md).  The axis runs at 100 u/s from cycle c0 with a one-cycle ramp
// (a = 1e5): the kernel step of cycle c0 + k (k >= 1) is at 0.05 + 0.1 (k - 1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "MotionSim.h"
#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"
#include "stdlib-motion/core/Diag.h"

using namespace stc::motion;
using namespace stc::motion::diag;
using stc::motion::test::Sim;

namespace {

MoveInputs velocity(double v) {
  MoveInputs in;
  in.velocity = v;
  in.acceleration = in.deceleration = 1e5;
  in.direction = v < 0 ? Direction::Negative : Direction::Positive;
  in.velocity = std::fabs(v);
  return in;
}

double posAt(int k) { return 0.05 + 0.1 * (k - 1); }   // step c0 + k, k >= 1

struct Runner {
  Sim& s;
  FbSlot& power;
  FbSlot& mv;
  MoveInputs in;
  bool moving = false;
  Runner(Sim& sim, double v) : s(sim), power(sim.slot(FbKind::Power)), mv(sim.slot(FbKind::MoveVelocity)), in(velocity(v)) {
    s.powerOn(power);
  }
  // The program's calls of one cycle (power, move), then `body`, then the kernel step.
  template <class F>
  void cycle(F body) {
    s.k.callPower(power, *s.ax, true, true, true, s.ctx());
    if (moving) s.k.callMove(mv, *s.ax, true, in, s.ctx());
    body();
    s.endCycle();
  }
  void cycle() { cycle([] {}); }
  void start() { moving = true; }
};

}  // namespace

// ---------------------------------------------------------------- touch probe (drive mode)

TEST(MotionDiag, TouchProbeLatchesTheHomeSwitchEdgeExactly) {
  AxisConfig cfg;
  cfg.drive.hasHomeSwitch = true;
  cfg.drive.homeSwitchLow = 3.0;
  cfg.drive.homeSwitchHigh = 4.0;
  Sim s(cfg);
  Runner r(s, 100);
  FbSlot& rise = s.slot(FbKind::Probe);
  FbSlot& fall = s.slot(FbKind::Probe);
  bool activeRise = false, activeFall = false;
  TriggerRef tRise{&activeRise, 0, true, nullptr, &activeRise};
  TriggerRef tFall{&activeFall, 1, true, nullptr, &activeFall};
  r.start();
  const uint64_t c0 = s.cycle;
  uint64_t doneRise = 0, doneFall = 0;
  for (int k = 0; k <= 45; ++k) {
    const uint64_t c = s.cycle;
    r.cycle([&] {
      callTouchProbe(s.k, rise, *s.ax, true, tRise, {}, s.ctx());
      callTouchProbe(s.k, fall, *s.ax, true, tFall, {}, s.ctx());
      if (c == c0) {
        EXPECT_TRUE(rise.out.busy);   // Busy in the call of the edge
        EXPECT_TRUE(activeRise);
      }
    });
    if (rise.out.done && !doneRise) doneRise = c;
    if (fall.out.done && !doneFall) doneFall = c;
  }
  // 3.0 lies between the steps k = 30 (2.95) and k = 31 (3.05); 4.0 is left between k = 40 and 41.
  EXPECT_EQ(doneRise, c0 + 31);
  EXPECT_EQ(doneFall, c0 + 41);
  EXPECT_EQ(recordedPosition(rise), 3.0);
  EXPECT_EQ(recordedPosition(fall), 4.0);
  EXPECT_FALSE(rise.out.busy);
  EXPECT_FALSE(activeRise);
  EXPECT_FALSE(activeFall);
}

TEST(MotionDiag, TouchProbeNegativeDirectionAndIndexPulseWithWindow) {
  AxisConfig cfg;
  cfg.drive.hasHomeSwitch = true;
  cfg.drive.homeSwitchLow = -4.0;
  cfg.drive.homeSwitchHigh = -3.0;
  cfg.drive.indexPeriod = 10;
  cfg.drive.indexOffset = 2.5;
  Sim s(cfg);
  Runner r(s, -100);
  FbSlot& rise = s.slot(FbKind::Probe);
  FbSlot& index = s.slot(FbKind::Probe);
  bool a1 = false, a2 = false;
  TriggerRef t1{&a1, 0, true, nullptr, &a1};
  TriggerRef t2{&a2, 2, true, nullptr, &a2};
  r.start();
  const uint64_t c0 = s.cycle;
  uint64_t done1 = 0, done2 = 0;
  for (int k = 0; k <= 200; ++k) {
    const uint64_t c = s.cycle;
    r.cycle([&] {
      callTouchProbe(s.k, rise, *s.ax, true, t1, {}, s.ctx());
      // Window [-20, -12]: the index marks -7.5 and -17.5 are passed; only -17.5 is inside.
      callTouchProbe(s.k, index, *s.ax, true, t2, {true, -20, -12}, s.ctx());
    });
    if (rise.out.done && !done1) done1 = c;
    if (index.out.done && !done2) done2 = c;
  }
  // Moving negative, the switch closes at its high end -3.0 (between -2.95 and -3.05).
  EXPECT_EQ(done1, c0 + 31);
  EXPECT_EQ(recordedPosition(rise), -3.0);
  // -17.5 between -17.45 (k = 175) and -17.55 (k = 176).
  EXPECT_EQ(done2, c0 + 176);
  EXPECT_EQ(recordedPosition(index), -17.5);
}

TEST(MotionDiag, TouchProbeControllerInputAndErrors) {
  Sim s;
  Runner r(s, 100);
  FbSlot& p = s.slot(FbKind::Probe);
  FbSlot& p2 = s.slot(FbKind::Probe);
  FbSlot& bad = s.slot(FbKind::Probe);
  FbSlot& abort = s.slot(FbKind::Probe);
  bool input = false, active = false, active2 = false;
  TriggerRef t{&input, -1, false, &input, &active};
  r.start();
  const uint64_t c0 = s.cycle;
  for (int k = 0; k <= 60; ++k) {
    const uint64_t c = s.cycle;
    input = c >= c0 + 50;
    r.cycle([&] {
      callTouchProbe(s.k, p, *s.ax, true, t, {}, s.ctx());
      if (c == c0 + 1) {
        // The same trigger again: 400.
        callTouchProbe(s.k, p2, *s.ax, true, t, {}, s.ctx());
        EXPECT_TRUE(p2.out.error);
        EXPECT_EQ(p2.out.errorId, Error::TpTriggerOccupied);
        // A drive channel that does not exist: 402; a window inside out: 401.
        TriggerRef t5{&active2, 5, true, nullptr, &active2};
        callTouchProbe(s.k, bad, *s.ax, true, t5, {}, s.ctx());
        EXPECT_EQ(bad.out.errorId, Error::TpCommError);
        callTouchProbe(s.k, bad, *s.ax, false, t5, {}, s.ctx());
        TriggerRef t0{&active2, 0, true, nullptr, &active2};
        callTouchProbe(s.k, bad, *s.ax, true, t0, {true, 5, 1}, s.ctx());
        EXPECT_EQ(bad.out.errorId, Error::TpCouldntSetWindow);
        EXPECT_FALSE(active2);
        // Nothing armed on t0: 410.
        callAbortTrigger(s.k, abort, *s.ax, true, t0, s.ctx());
        EXPECT_EQ(abort.out.errorId, Error::AtTriggerNotOccupied);
        callAbortTrigger(s.k, abort, *s.ax, false, t0, s.ctx());
      }
    });
    if (c == c0 + 50) {
      EXPECT_TRUE(p.out.done);   // Done in the kernel step of the cycle that set the input
      EXPECT_NEAR(recordedPosition(p), posAt(50), 1e-9);
      EXPECT_EQ(recordedPosition(p), s.ax->actPosition());
    } else if (c < c0 + 50) {
      EXPECT_FALSE(p.out.done);
      EXPECT_TRUE(p.out.busy);
    }
  }
  // The FB error record holds the latest refused call (MC_AbortTrigger, 410).
  EXPECT_TRUE(s.ax->fbError.set);
  EXPECT_EQ(s.ax->fbError.id, Error::AtTriggerNotOccupied);
  EXPECT_EQ(s.ax->fbError.instance, abort.instance);
}

TEST(MotionDiag, AbortTriggerAbortsAnArmedProbe) {
  Sim s;
  Runner r(s, 0.0 + 100);
  FbSlot& p = s.slot(FbKind::Probe);
  FbSlot& a = s.slot(FbKind::Probe);
  bool input = false, active = false;
  TriggerRef t{&input, -1, false, &input, &active};
  r.cycle([&] { callTouchProbe(s.k, p, *s.ax, true, t, {}, s.ctx()); });
  EXPECT_TRUE(active);
  r.cycle([&] {
    callTouchProbe(s.k, p, *s.ax, true, t, {}, s.ctx());
    callAbortTrigger(s.k, a, *s.ax, true, t, s.ctx());
    EXPECT_TRUE(a.out.done);
    EXPECT_TRUE(p.out.aborted);
    EXPECT_FALSE(p.out.busy);
    EXPECT_FALSE(active);
  });
  input = true;   // too late: nothing latched
  r.cycle([&] { callTouchProbe(s.k, p, *s.ax, true, t, {}, s.ctx()); });
  EXPECT_FALSE(p.out.done);
  EXPECT_TRUE(p.out.aborted);   // held while Execute is TRUE
}

TEST(MotionDiag, CommunicationLossEndsADriveProbeAndShowsInCheckAxisCommunication) {
  AxisConfig cfg;
  cfg.drive.kind = AxisKind::Servo;
  cfg.drive.faults.push_back({20'000'000, FaultKind::CommunicationLost, 0});
  Sim s(cfg);
  FbSlot& power = s.slot(FbKind::Power);
  FbSlot& p = s.slot(FbKind::Probe);
  bool active = false;
  TriggerRef t{&active, 2, true, nullptr, &active};
  for (int i = 0; i < 5; ++i) {
    s.k.callPower(power, *s.ax, true, true, true, s.ctx());
    s.endCycle();
  }
  EXPECT_TRUE(checkCommunication(*s.ax, true).operational);
  EXPECT_EQ(checkCommunication(*s.ax, true).state, ComState::Operational);
  EXPECT_FALSE(checkCommunication(*s.ax, false).valid);
  uint64_t errCycle = 0;
  while (s.now <= 25'000'000) {
    const uint64_t c = s.cycle;
    s.k.callPower(power, *s.ax, true, true, true, s.ctx());
    callTouchProbe(s.k, p, *s.ax, true, t, {}, s.ctx());
    s.endCycle();
    if (p.out.error && !errCycle) errCycle = c;
  }
  // The fault is due at 20 ms: the step of cycle 21 (cycle n at (n-1) ms).
  EXPECT_EQ(errCycle, 21u);
  EXPECT_EQ(p.out.errorId, Error::TpCommError);
  const ComOut o = checkCommunication(*s.ax, true);
  EXPECT_TRUE(o.valid);
  EXPECT_FALSE(o.operational);
  EXPECT_EQ(o.state, ComState::Error);
  // A new probe on a drive without communication: 402 in the call.
  FbSlot& p2 = s.slot(FbKind::Probe);
  bool a2 = false;
  callTouchProbe(s.k, p2, *s.ax, true, TriggerRef{&a2, 0, true, nullptr, &a2}, {}, s.ctx());
  EXPECT_EQ(p2.out.errorId, Error::TpCommError);
}

// ---------------------------------------------------------------- cam switch

TEST(MotionDiag, CamSwitchOnModuloAxisWithCompensationAndCorruption) {
  AxisConfig cfg;
  cfg.period = 10;
  Sim s(cfg);
  Runner r(s, 100);
  FbSlot& cs = s.slot(FbKind::CamSwitch);
  bool outs[kTracks] = {};
  TrackOption opt[kTracks];
  opt[1].onCompensation = -0.01;   // track 2 switches on 10 ms early: 1 u at 100 u/s
  opt[2].onCompensation = 0.01;    // track 3: the window [2, 2.5] turns inside out at 100 u/s
  std::vector<CamSwitch> sw = {
      {1, 9.0, 1.0, 0, 0, 0},      // wraps around the period
      {2, 2.0, 5.0, 1, 0, 0},
      {3, 2.0, 2.5, 0, 0, 0},
      {4, 6.0, 8.0, -1, 0, 0},     // negative direction only
  };
  // Enabled at rest at 0: track 1 is on at once (0 <= 1).
  r.cycle([&] {
    CamSwitchOut o = callDigitalCamSwitch(s.k, cs, *s.ax, true, &sw, opt, outs, 0xFFFFFFFF, TappetMode::Auto, s.ctx());
    EXPECT_TRUE(o.inOperation);
    EXPECT_EQ(o.corrupted, -1);
  });
  EXPECT_TRUE(outs[0]);
  r.start();
  const uint64_t c0 = s.cycle;
  std::vector<int> on1, on2;
  int16_t corrupted = -1;
  for (int k = 0; k <= 100; ++k) {
    r.cycle([&] {
      CamSwitchOut o = callDigitalCamSwitch(s.k, cs, *s.ax, true, nullptr, nullptr, nullptr, 0xFFFFFFFF, TappetMode::Auto, s.ctx());
      if (k == 50) corrupted = o.corrupted;
    });
    if (outs[0]) on1.push_back(k);
    if (outs[1]) on2.push_back(k);
    EXPECT_FALSE(outs[3]);
    EXPECT_FALSE(outs[2]);
  }
  (void)c0;
  // Track 1: on at 0.05 .. 0.95 (k = 1..10), off from 1.05, on again from 9.05 (k = 91) to 10.95 (k = 100).
  std::vector<int> want1;
  for (int k = 0; k <= 10; ++k) want1.push_back(k);
  for (int k = 91; k <= 100; ++k) want1.push_back(k);
  EXPECT_EQ(on1, want1);
  // Track 2: window shifted to [1, 5] at 100 u/s: 1.05 (k = 11) .. 4.95 (k = 50).
  std::vector<int> want2;
  for (int k = 11; k <= 50; ++k) want2.push_back(k);
  EXPECT_EQ(on2, want2);
  EXPECT_EQ(corrupted, 3);
  // Enable FALSE clears the tracks it drives.
  r.cycle([&] { callDigitalCamSwitch(s.k, cs, *s.ax, false, nullptr, nullptr, nullptr, 0, TappetMode::Auto, s.ctx()); });
  EXPECT_FALSE(outs[0]);
}

TEST(MotionDiag, CamSwitchRejectsBadTables) {
  Sim s;
  FbSlot& cs = s.slot(FbKind::CamSwitch);
  bool outs[kTracks] = {};
  TrackOption opt[kTracks];
  std::vector<CamSwitch> empty;
  auto call = [&](std::vector<CamSwitch> sw) {
    callDigitalCamSwitch(s.k, cs, *s.ax, false, nullptr, nullptr, nullptr, 0, TappetMode::Auto, s.ctx());
    return callDigitalCamSwitch(s.k, cs, *s.ax, true, &sw, opt, outs, 0xFFFFFFFF, TappetMode::Auto, s.ctx());
  };
  EXPECT_EQ(call({}).errorId, Error::CrNoTappetsInCam);
  EXPECT_EQ(call({{0, 1, 2, 0, 0, 0}}).errorId, kBadInput);                 // track 0
  EXPECT_EQ(call({{1, NAN, 2, 0, 0, 0}}).errorId, kBadInput);               // NaN
  EXPECT_EQ(call({{1, 3, 2, 0, 0, 0}}).errorId, kBadInput);                 // First > Last, linear axis
  EXPECT_EQ(call({{1, 1, 2, 5, 0, 0}}).errorId, kBadInput);                 // direction 5
  EXPECT_EQ(call({{1, 1, 2, 0, 1, 0}}).errorId, kBadInput);                 // time cam without Duration
  CamSwitchOut ok = call({{1, 1, 2, 0, 0, 0}});
  EXPECT_FALSE(ok.error);
  EXPECT_TRUE(ok.busy);
}

// ---------------------------------------------------------------- monitors

TEST(MotionDiag, InPositionTimeOutAndTrackingErrorWithALaggingDrive) {
  AxisConfig cfg;
  cfg.drive.model = DriveModel::Lag;
  Sim s(cfg);
  Runner r(s, 100);
  FbSlot& ip = s.slot(FbKind::Diagnostic);
  FbSlot& te = s.slot(FbKind::Diagnostic);
  FbSlot& te2 = s.slot(FbKind::Diagnostic);
  r.start();
  const uint64_t c0 = s.cycle;
  uint64_t timeoutCycle = 0;
  std::vector<double> sets;
  for (int k = 0; k <= 100; ++k) {
    const uint64_t c = s.cycle;
    r.cycle([&] {
      InPositionOut o = callInPosition(ip, s.ax, {true, 0.1, 1.0, 0.05}, s.ctx());
      EXPECT_TRUE(o.busy);
      if (k > 2) { EXPECT_FALSE(o.inPosition); }
      if (o.timeOut && !timeoutCycle) timeoutCycle = c;
      EXPECT_NEAR(o.distance, std::fabs(s.ax->set().p - s.ax->actPosition()), 0);
      sets.push_back(s.ax->set().p);
      TrackingOut t0 = callTrackingError(te, s.ax, true, 0, static_cast<uint32_t>(c), false);
      EXPECT_EQ(t0.actual, s.ax->set().p - s.ax->actPosition());
      TrackingOut t2 = callTrackingError(te2, s.ax, true, 2, static_cast<uint32_t>(c), false);
      const double delayed = sets[sets.size() >= 3 ? sets.size() - 3 : 0];
      EXPECT_EQ(t2.actual, delayed - s.ax->actPosition());
      EXPECT_GE(std::fabs(t0.max), std::fabs(t0.actual));
    });
  }
  EXPECT_EQ(timeoutCycle, c0 + 50);   // 50 ms after the enabling call
  // Bad inputs: 140.
  FbSlot& bad = s.slot(FbKind::Diagnostic);
  EXPECT_EQ(callInPosition(bad, s.ax, {true, NAN, 0, 0}, s.ctx()).errorId, kBadInput);
  EXPECT_EQ(callInPosition(bad, s.ax, {true, 1, -1, 0}, s.ctx()).errorId, kBadInput);
  EXPECT_EQ(callInPosition(bad, s.ax, {true, 0, 0, 0}, s.ctx()).errorId, kBadInput);
}

TEST(MotionDiag, CheckLimitsMaxValuesAndMeasureDistanceOnAModuloAxis) {
  AxisConfig cfg;
  cfg.period = 0.1;
  Sim s(cfg);
  Runner r(s, 100);
  r.in.acceleration = 1000;   // ramp of 0.1 s: the step of c0 + k is at 500 t^2, v = 1000 t, t = k ms
  FbSlot& mv = s.slot(FbKind::Diagnostic);
  FbSlot& ma = s.slot(FbKind::Diagnostic);
  FbSlot& md = s.slot(FbKind::Diagnostic);
  r.cycle([&] { callMeasureDistance(md, *s.ax, true); });
  r.start();
  const uint64_t c0 = s.cycle;
  for (int k = 0; k <= 30; ++k) {
    const uint64_t c = s.cycle;
    r.cycle([&] {
      // The call of cycle c0 + k sees the step of c0 + k - 1: t = (k - 1) ms.
      const double t = k >= 1 ? (k - 1) * 1e-3 : 0;
      MaxOut v = callGetMax(mv, s.ax, MaxOf::Velocity, true, static_cast<uint32_t>(c), false);
      MaxOut a = callGetMax(ma, s.ax, MaxOf::AccDec, true, static_cast<uint32_t>(c), false);
      MeasureOut d = callMeasureDistance(md, *s.ax, true);
      CheckLimitsOut l = checkLimits(*s.ax, true, true, true, {10, 2000, 2000});
      CheckLimitsOut la = checkLimits(*s.ax, true, false, true, {10, 500, 2000});
      EXPECT_NEAR(v.max, 1000 * t, 1e-9) << k;
      EXPECT_EQ(v.timeAtMax, k >= 2 ? static_cast<uint32_t>(c) : 0u) << k;
      EXPECT_NEAR(d.distance, 500 * t * t, 1e-9) << k;
      EXPECT_EQ(l.exceeded, 1000 * t > 10 + 1e-9) << k;
      if (k >= 2) {
        EXPECT_EQ(a.max, 1000.0);
        EXPECT_EQ(a.timeAtMax, static_cast<uint32_t>(c0 + 2));
        EXPECT_TRUE(la.exceeded);   // 1000 > 500
      }
    });
  }
  EXPECT_LT(s.ax->reportPosition(s.ax->actPosition()), 0.1);
  EXPECT_GT(s.ax->actPosition(), 0.4);   // several periods
  EXPECT_EQ(checkLimits(*s.ax, true, true, false, {NAN, 0, 0}).errorId, kBadInput);
  EXPECT_FALSE(checkLimits(*s.ax, false, true, false, {NAN, 0, 0}).busy);
  // bResetMax restarts the maximum.
  EXPECT_EQ(callGetMax(mv, s.ax, MaxOf::Velocity, true, 7, true).timeAtMax, 7u);
}

TEST(MotionDiag, FbErrorRecordAndErrorString) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  MoveInputs in;
  in.position = 1;   // velocity 0: 201
  s.k.callMove(m, *s.ax, true, in, s.ctx());
  EXPECT_TRUE(m.out.error);
  FbErrorOut o = readFbError(*s.ax, true);
  EXPECT_TRUE(o.busy);
  EXPECT_TRUE(o.record.set);
  EXPECT_EQ(o.record.id, Error::MaInvalidVelAcc);
  EXPECT_EQ(o.record.instance, m.instance);
  EXPECT_EQ(o.record.atNs, s.now);
  EXPECT_TRUE(clearFbError(*s.ax));
  EXPECT_FALSE(readFbError(*s.ax, true).record.set);
  EXPECT_FALSE(readFbError(*s.ax, false).busy);
  EXPECT_EQ(sm3face::errorString(400), "SMC_TP_TRIGGEROCCUPIED: trigger already in use/active");
  EXPECT_EQ(sm3face::errorString(0), "SMC_NO_ERROR: no error");
  EXPECT_EQ(sm3face::errorString(9999), "unknown SMC_ERROR 9999");
  EXPECT_STREQ(sm3face::errorName(2101), "SMC_ADL_BUFFER_OVERRUN");
}

// ---------------------------------------------------------------- diagnostic log

TEST(MotionDiag, DiagnosticLogWritesOneLinePerCycle) {
  Sim s;
  Runner r(s, 100);
  FbSlot& lg = s.slot(FbKind::Diagnostic);
  const std::string file = ::testing::TempDir() + "stc_diag_log_test.txt";
  LogConfig cfg;
  cfg.fileName = file;
  cfg.setPosition = cfg.actPosition = cfg.setVelocity = cfg.setAcceleration = true;
  cfg.separator = ';';
  cfg.recordEnd = "\n";
  r.start();
  const uint64_t c0 = s.cycle;
  uint64_t doneCycle = 0;
  for (int k = 0; k <= 30; ++k) {
    const uint64_t c = s.cycle;
    r.cycle([&] {
      callDiagnosticLog(s.k, lg, *s.ax, true, k >= 20, cfg, s.ctx());
      if (k == 0) { EXPECT_TRUE(lg.out.busy); }
      if (k % 5 == 0) writeToFile(lg);
    });
    if (lg.out.done && !doneCycle) doneCycle = c;
  }
  EXPECT_EQ(doneCycle, c0 + 20);   // closed by the WriteToFile of cycle c0 + 20, Done in its step
  std::ifstream f(file);
  std::string line;
  int k = 0;
  while (std::getline(f, line)) {
    std::vector<double> v;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ';')) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 4u) << line;
    // Records from the step of the edge (k = 0: at rest, the ramp starts) to the step before bCloseFile.
    const double p = k == 0 ? 0 : posAt(k);
    EXPECT_NEAR(v[0], p, 1e-9) << k;
    EXPECT_NEAR(v[1], p, 1e-9) << k;
    EXPECT_EQ(v[2], k == 0 ? 0 : 100.0) << k;
    EXPECT_EQ(v[3], 0.0) << k;   // the one-cycle ramp ends exactly at the step: a = 0 at every sample
    ++k;
  }
  EXPECT_EQ(k, 20);
  std::remove(file.c_str());
}

TEST(MotionDiag, DiagnosticLogErrors) {
  Sim s;
  Runner r(s, 100);
  FbSlot& bad = s.slot(FbKind::Diagnostic);
  FbSlot& over = s.slot(FbKind::Diagnostic);
  FbSlot& noName = s.slot(FbKind::Diagnostic);
  LogConfig badCfg;
  badCfg.fileName = "/nonexistent-dir/stc/x.log";
  badCfg.setPosition = true;
  LogConfig overCfg;
  overCfg.fileName = ::testing::TempDir() + "stc_diag_over.txt";
  overCfg.mode = LogMode::AtClose;
  overCfg.setPosition = overCfg.actPosition = overCfg.setVelocity = overCfg.actVelocity = true;
  r.start();
  size_t records = 0;
  uint64_t overCycle = 0, badCycle = 0;
  for (int k = 0; k < 1000 && !overCycle; ++k) {
    const uint64_t c = s.cycle;
    r.cycle([&] {
      callDiagnosticLog(s.k, bad, *s.ax, true, false, badCfg, s.ctx());
      callDiagnosticLog(s.k, over, *s.ax, true, false, overCfg, s.ctx());
      if (k == 3) writeToFile(bad);
      writeToFile(over);   // LOG_AT_CLOSE: nothing written before bCloseFile
    });
    if (bad.out.error && !badCycle) badCycle = c;
    if (over.out.error) overCycle = c;
    else records = static_cast<DiagnosticLog*>(over.behaviour.get())->buffer.size();
  }
  EXPECT_EQ(bad.out.errorId, Error::AdlFileCannotBeOpened);
  EXPECT_GT(badCycle, 0u);
  EXPECT_EQ(over.out.errorId, Error::AdlBufferOverrun);
  EXPECT_LE(records, DiagnosticLog::kBufferSize);
  EXPECT_GT(records, DiagnosticLog::kBufferSize - 100);
  callDiagnosticLog(s.k, noName, *s.ax, true, false, LogConfig{}, s.ctx());
  EXPECT_EQ(noName.out.errorId, Error::AdlFileCannotBeOpened);
  std::FILE* f = std::fopen(overCfg.fileName.c_str(), "rb");
  EXPECT_EQ(f, nullptr);   // never closed: never written
  if (f) std::fclose(f);
}
