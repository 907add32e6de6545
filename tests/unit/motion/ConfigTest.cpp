// Parameter access and axis configuration cycle by cycle (core/Config.h):
// which cycle Valid/Done/Error rise, the axis state and configuration they
// change, and the supervision errors the changed configuration trips.
#include <gtest/gtest.h>

#include <cmath>

#include "MotionSim.h"
#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"
#include "stdlib-motion//core/Config.h"

using namespace stc::motion;
using stc::motion::test::Sim;

namespace {

MoveInputs absolute(double pos, double v, double a, double d, double j = 0) {
  MoveInputs in;
  in.position = pos;
  in.velocity = v;
  in.acceleration = a;
  in.deceleration = d;
  in.jerk = j;
  in.direction = Direction::Positive;
  return in;
}

MoveInputs relative(double dist, double v, double a, double d) {
  MoveInputs in;
  in.distance = dist;
  in.velocity = v;
  in.acceleration = a;
  in.deceleration = d;
  return in;
}

// Runs a move to its Done; returns the cycle of the call that started it and the Done cycle.
std::pair<uint64_t, uint64_t> runMove(Sim& s, FbSlot& m, const MoveInputs& in, uint64_t maxCycles = 20000) {
  const uint64_t c0 = s.cycle;
  uint64_t doneCycle = 0;
  while (s.cycle < c0 + maxCycles && !doneCycle) {
    s.k.callMove(m, *s.ax, true, in, s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    if (m.out.done) doneCycle = c;
    EXPECT_FALSE(m.out.error) << "ErrorID " << sm3face::smcError(m.out.errorId);
  }
  s.k.callMove(m, *s.ax, false, in, s.ctx());
  s.endCycle();
  return {c0, doneCycle};
}

const int32_t kActPos = sdoParameterNumber(4, 0x6064, 0);

}  // namespace

// ---------------------------------------------------------------- MC_ReadParameter

TEST(MotionConfig, SdoNumberEncoding) {
  EXPECT_EQ(sdoParameterNumber(1, 0x6060, 0), -23093248);   // the spec's worked example
  SdoAddress a;
  ASSERT_TRUE(decodeSdo(-23093248, a));
  EXPECT_EQ(a.length, 1);
  EXPECT_EQ(a.index, 0x6060);
  EXPECT_EQ(a.sub, 0);
  ASSERT_TRUE(decodeSdo(sdoParameterNumber(4, 0x607D, 2), a));
  EXPECT_EQ(a.index, 0x607D);
  EXPECT_EQ(a.sub, 2);
  EXPECT_FALSE(decodeSdo(1000, a));
  EXPECT_FALSE(decodeSdo(sdoParameterNumber(3, 0x6064, 0), a));   // length 3
}

TEST(MotionConfig, ReadAxisParameterIsValidInTheCallAndFollowsTheAxis) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& r = s.slot(FbKind::Parameter);
  // c1: power_off (0), Valid and Busy in the call.
  callReadParameter(s.k, r, *s.ax, true, 1000, false, s.ctx());
  EXPECT_TRUE(r.out.busy);
  EXPECT_TRUE(parameterState(r).valid);
  EXPECT_FALSE(r.out.error);
  EXPECT_EQ(parameterState(r).value, 0.0);
  s.endCycle();
  // c2: MC_Power before the reader: standstill (3) in the same call.
  s.powerOn(p);
  callReadParameter(s.k, r, *s.ax, true, 1000, false, s.ctx());
  EXPECT_EQ(parameterState(r).value, 3.0);
  // Another number while enabled: read at once.
  callReadParameter(s.k, r, *s.ax, true, 1040, false, s.ctx());   // bVirtual
  EXPECT_EQ(parameterState(r).value, 1.0);
  callReadParameter(s.k, r, *s.ax, true, 1025, false, s.ctx());   // fTaskCycle
  EXPECT_DOUBLE_EQ(parameterState(r).value, 0.001);
  s.endCycle();
  // Enable FALSE: every output resets.
  callReadParameter(s.k, r, *s.ax, false, 1000, false, s.ctx());
  EXPECT_FALSE(r.out.busy);
  EXPECT_FALSE(parameterState(r).valid);
  EXPECT_EQ(parameterState(r).value, 0.0);
  s.endCycle();
  // Unknown numbers: 130 in the call, Busy and Valid FALSE; a known number clears it.
  for (int32_t n : {0, 17, 999, 1001, 99999}) {
    callReadParameter(s.k, r, *s.ax, true, n, false, s.ctx());
    EXPECT_TRUE(r.out.error) << n;
    EXPECT_EQ(r.out.errorId, Error::ReadParamUnknown) << n;
    EXPECT_FALSE(r.out.busy);
    EXPECT_FALSE(parameterState(r).valid);
  }
  callReadParameter(s.k, r, *s.ax, true, sdoParameterNumber(3, 0x6064, 0), false, s.ctx());   // bad SDO length
  EXPECT_EQ(r.out.errorId, Error::ReadParamUnknown);
  callReadParameter(s.k, r, *s.ax, true, 9, false, s.ctx());
  EXPECT_FALSE(r.out.error);
  EXPECT_TRUE(parameterState(r).valid);
}

TEST(MotionConfig, ReadParameterValuesAgainstTheAxis) {
  AxisConfig cfg;
  cfg.maxVelocity = 50;
  cfg.maxAcceleration = 500;
  cfg.maxDeceleration = 400;
  cfg.maxJerk = 9000;
  cfg.swLimitEnable = true;
  cfg.swLimitPositive = 1000;
  cfg.swLimitNegative = -20;
  cfg.period = 0;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  FbSlot& r = s.slot(FbKind::Parameter);
  s.powerOn(p);
  s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  for (int i = 0; i < 50; ++i) {
    s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
    s.endCycle();
  }
  // 50 steps, the first one in the edge's cycle without motion: 49 ms of a = 100, v = 4.9.
  auto read = [&](int32_t n) {
    callReadParameter(s.k, r, *s.ax, true, n, false, s.ctx());
    EXPECT_TRUE(parameterState(r).valid) << n;
    return parameterState(r).value;
  };
  EXPECT_NEAR(read(1), 100 * 0.049 * 0.049 / 2, 1e-12);
  EXPECT_NEAR(read(11), 4.9, 1e-12);
  EXPECT_NEAR(read(10), 4.9, 1e-12);        // ideal drive: actual = set
  EXPECT_EQ(read(1000), 4.0);               // discrete_motion
  for (int32_t n : {9, 1112, 8}) EXPECT_EQ(read(n), 50.0);
  for (int32_t n : {13, 1122, 12}) EXPECT_EQ(read(n), 500.0);
  for (int32_t n : {15, 1132, 14}) EXPECT_EQ(read(n), 400.0);
  for (int32_t n : {16, 1142}) EXPECT_EQ(read(n), 9000.0);
  for (int32_t n : {2, 1200}) EXPECT_EQ(read(n), 1000.0);
  for (int32_t n : {3, 1201}) EXPECT_EQ(read(n), -20.0);
  for (int32_t n : {4, 5, 1205, 1010, 1011, 1012, 1015, 1016, 1040}) EXPECT_EQ(read(n), 1.0) << n;
  for (int32_t n : {6, 1030, 1014, 1036}) EXPECT_EQ(read(n), 0.0) << n;
  // 1031 (the axis error as a number) needs a face: the core's faults have no numbers
  // (the SM3 face: tests/run/motion_param_error_id.st).
  callReadParameter(s.k, r, *s.ax, true, 1031, false, s.ctx());
  EXPECT_EQ(r.out.errorId, Error::ReadParamUnknown);
  EXPECT_EQ(read(1013), 100.0);
  EXPECT_EQ(read(1060), 1.0);               // linear
  EXPECT_EQ(read(1062), 0.0);               // trapez
  // The BOOL variant: BOOL parameters only, else 133.
  callReadParameter(s.k, r, *s.ax, true, 1205, true, s.ctx());
  EXPECT_TRUE(parameterState(r).valid);
  EXPECT_EQ(parameterState(r).value, 1.0);
  callReadParameter(s.k, r, *s.ax, true, 1112, true, s.ctx());
  EXPECT_TRUE(r.out.error);
  EXPECT_EQ(r.out.errorId, Error::ReadParamConversionError);
  EXPECT_FALSE(parameterState(r).valid);
}

TEST(MotionConfig, ReadDriveObjectBySdoIsValidInTheKernelStep) {
  AxisConfig cfg;
  cfg.drive.incrementsPerUnit = 1000;
  Sim s(cfg);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveRelative);
  FbSlot& r = s.slot(FbKind::Parameter);
  s.powerOn(p);
  runMove(s, m, relative(2.5, 10, 100, 100));
  // Call: Busy, not yet Valid (the request goes out with this cycle's bus exchange).
  callReadParameter(s.k, r, *s.ax, true, kActPos, false, s.ctx());
  EXPECT_TRUE(r.out.busy);
  EXPECT_FALSE(parameterState(r).valid);
  s.endCycle();
  EXPECT_TRUE(parameterState(r).valid);
  EXPECT_EQ(parameterState(r).value, 2500.0);    // increments
  // Held Enable: one request per call, the value follows the drive.
  FbSlot& sp = s.slot(FbKind::SetPosition);
  s.k.callSetPosition(sp, *s.ax, true, 7, false, s.ctx());
  callReadParameter(s.k, r, *s.ax, true, kActPos, false, s.ctx());
  EXPECT_TRUE(parameterState(r).valid);
  EXPECT_EQ(parameterState(r).value, 2500.0);    // the previous answer until this cycle's
  s.endCycle();
  EXPECT_EQ(parameterState(r).value, 7000.0);
  // Statusword (2 bytes): operation enabled.
  callReadParameter(s.k, r, *s.ax, true, sdoParameterNumber(2, 0x6041, 0), false, s.ctx());
  EXPECT_FALSE(parameterState(r).valid);          // new number: not valid until answered
  s.endCycle();
  EXPECT_EQ(static_cast<int>(parameterState(r).value) & 0x6F, 0x27);
  // A length that does not match the object, or no such object: 131 in the kernel step.
  callReadParameter(s.k, r, *s.ax, true, sdoParameterNumber(2, 0x6064, 0), false, s.ctx());
  EXPECT_FALSE(r.out.error);
  s.endCycle();
  EXPECT_TRUE(r.out.error);
  EXPECT_EQ(r.out.errorId, Error::ReadParamRequestingError);
  EXPECT_FALSE(r.out.busy);
  EXPECT_FALSE(parameterState(r).valid);
  callReadParameter(s.k, r, *s.ax, true, sdoParameterNumber(4, 0x2000, 1), false, s.ctx());
  s.endCycle();
  EXPECT_EQ(r.out.errorId, Error::ReadParamRequestingError);
  // BOOL variant over SDO: value <> 0.
  FbSlot& rb = s.slot(FbKind::Parameter);
  callReadParameter(s.k, rb, *s.ax, true, kActPos, true, s.ctx());
  s.endCycle();
  EXPECT_TRUE(parameterState(rb).valid);
  EXPECT_EQ(parameterState(rb).value, 1.0);
}

TEST(MotionConfig, SdoFailsWithoutCommunication) {
  AxisConfig cfg;
  cfg.drive.kind = AxisKind::Servo;
  cfg.drive.faults.push_back(FaultEvent{2'000'000, FaultKind::CommunicationLost, 0});
  Sim s(cfg);
  FbSlot& r = s.slot(FbKind::Parameter);
  FbSlot& w = s.slot(FbKind::Parameter);
  const int32_t homeOffset = sdoParameterNumber(4, 0x607C, 0);
  callReadParameter(s.k, r, *s.ax, true, homeOffset, false, s.ctx());   // c1 at 0 ms
  s.endCycle();
  EXPECT_TRUE(parameterState(r).valid);
  callReadParameter(s.k, r, *s.ax, true, homeOffset, false, s.ctx());   // c2
  s.endCycle();
  EXPECT_TRUE(parameterState(r).valid);
  callReadParameter(s.k, r, *s.ax, true, homeOffset, false, s.ctx());   // c3: lost at 2 ms
  callWriteParameter(s.k, w, *s.ax, true, homeOffset, 5, false, s.ctx());
  EXPECT_TRUE(w.out.busy);
  s.endCycle();
  EXPECT_TRUE(r.out.error);
  EXPECT_EQ(r.out.errorId, Error::ReadParamRequestingError);
  EXPECT_TRUE(w.out.error);
  EXPECT_EQ(w.out.errorId, Error::WriteParamSendingError);
  EXPECT_FALSE(w.out.busy);
}

// ---------------------------------------------------------------- MC_WriteParameter

TEST(MotionConfig, WriteAxisParameterIsDoneInTheCallAndTheSupervisionUsesIt) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& w = s.slot(FbKind::Parameter);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  // fMaxVelocity := 5 while the axis stands: Done in the call, held while Execute.
  callWriteParameter(s.k, w, *s.ax, true, 1112, 5, false, s.ctx());
  EXPECT_TRUE(w.out.done);
  EXPECT_FALSE(w.out.busy);
  EXPECT_EQ(s.ax->config().maxVelocity, 5.0);
  s.endCycle();
  callWriteParameter(s.k, w, *s.ax, true, 1112, 5, false, s.ctx());
  EXPECT_TRUE(w.out.done);
  s.endCycle();
  callWriteParameter(s.k, w, *s.ax, false, 1112, 5, false, s.ctx());
  EXPECT_FALSE(w.out.done);
  // A move at 10 u/s, a = 100: the set velocity passes 5 in the 51st ms -> error 40 in that step.
  const uint64_t c0 = s.cycle;
  uint64_t errCycle = 0;
  for (int i = 0; i < 100 && !errCycle; ++i) {
    s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    if (m.out.error) errCycle = c;
  }
  EXPECT_EQ(errCycle, c0 + 51);
  EXPECT_EQ(m.out.errorId, Error::VdMaxVelocityExceeded);
  EXPECT_EQ(s.ax->state(), AxisState::ErrorStop);
  EXPECT_EQ(s.ax->error(), Error::VdMaxVelocityExceeded);
}

TEST(MotionConfig, WriteAxisParameterErrors) {
  AxisConfig cfg;
  cfg.period = 360;
  Sim s(cfg);
  FbSlot& w = s.slot(FbKind::Parameter);
  auto write = [&](int32_t n, double v, bool asBool = false) {
    callWriteParameter(s.k, w, *s.ax, true, n, v, asBool, s.ctx());
    const Error e = w.out.error ? w.out.errorId : Error::None;
    EXPECT_FALSE(w.out.busy);
    EXPECT_EQ(w.out.done, e == Error::None);
    callWriteParameter(s.k, w, *s.ax, false, n, v, asBool, s.ctx());
    EXPECT_FALSE(w.out.error);     // Execute FALSE clears the held output
    EXPECT_FALSE(w.out.done);
    return e;
  };
  EXPECT_EQ(write(99999, 1), Error::WriteParamInvalid);        // unknown
  EXPECT_EQ(write(1000, 3), Error::WriteParamInvalid);         // read-only
  EXPECT_EQ(write(1, 3), Error::WriteParamInvalid);
  EXPECT_EQ(write(1152, 3), Error::WriteParamInvalid);         // not simulated: read-only
  EXPECT_EQ(write(1112, std::nan("")), Error::WriteParamConversionError);
  EXPECT_EQ(write(1112, INFINITY), Error::WriteParamConversionError);
  EXPECT_EQ(write(1112, -1), Error::WriteParamInvalid);
  EXPECT_EQ(write(1205, 2), Error::WriteParamConversionError); // BOOL parameter: 0 or 1
  EXPECT_EQ(write(1112, 1, true), Error::WriteParamConversionError);   // BOOL variant, LREAL parameter
  EXPECT_EQ(write(1061, 0), Error::WriteParamInvalid);         // period must be > 0
  EXPECT_EQ(s.ax->config().maxVelocity, 0.0);
  // Accepted writes change the configuration.
  EXPECT_EQ(write(1205, 1, true), Error::None);
  EXPECT_TRUE(s.ax->config().swLimitEnable);
  EXPECT_EQ(write(4, 0), Error::None);
  EXPECT_FALSE(s.ax->config().swLimitEnable);
  EXPECT_EQ(write(2, 12.5), Error::None);
  EXPECT_EQ(s.ax->config().swLimitPositive, 12.5);
  EXPECT_EQ(write(1201, -3), Error::None);
  EXPECT_EQ(s.ax->config().swLimitNegative, -3.0);
  EXPECT_EQ(write(13, 250), Error::None);
  EXPECT_EQ(s.ax->config().maxAcceleration, 250.0);
  EXPECT_EQ(write(1132, 260), Error::None);
  EXPECT_EQ(s.ax->config().maxDeceleration, 260.0);
  EXPECT_EQ(write(16, 7000), Error::None);
  EXPECT_EQ(s.ax->config().maxJerk, 7000.0);
  EXPECT_EQ(write(7, 0.5), Error::None);
  EXPECT_EQ(s.ax->config().drive.followingErrorLimit, 0.5);
  EXPECT_EQ(write(1203, 50), Error::None);
  EXPECT_EQ(s.ax->config().swLimitDeceleration, 50.0);
  EXPECT_EQ(write(1250, 2), Error::None);
  EXPECT_EQ(s.ax->config().swErrorMaxDistance, 2.0);
  EXPECT_EQ(write(1061, 100), Error::None);
  EXPECT_EQ(s.ax->config().period, 100.0);
}

TEST(MotionConfig, WritePeriodOnlyOnAStandingModuloAxis) {
  Sim s;   // linear
  FbSlot& w = s.slot(FbKind::Parameter);
  callWriteParameter(s.k, w, *s.ax, true, 1061, 360, false, s.ctx());
  EXPECT_EQ(w.out.errorId, Error::WriteParamInvalid);
  EXPECT_EQ(s.ax->config().period, 0.0);
}

TEST(MotionConfig, WriteDriveObjectBySdoIsDoneInTheKernelStep) {
  Sim s;
  FbSlot& w = s.slot(FbKind::Parameter);
  FbSlot& r = s.slot(FbKind::Parameter);
  const int32_t homeOffset = sdoParameterNumber(4, 0x607C, 0);
  callWriteParameter(s.k, w, *s.ax, true, homeOffset, -1234, false, s.ctx());
  EXPECT_TRUE(w.out.busy);
  EXPECT_FALSE(w.out.done);
  int64_t v = 0;
  ASSERT_TRUE(s.ax->drive().readObject(0x607C, 0, v));
  EXPECT_EQ(v, 0);                   // not yet on the drive
  s.endCycle();
  EXPECT_TRUE(w.out.done);
  EXPECT_FALSE(w.out.busy);
  ASSERT_TRUE(s.ax->drive().readObject(0x607C, 0, v));
  EXPECT_EQ(v, -1234);
  // Done held while Execute is TRUE, cleared by the call that sees it FALSE.
  callWriteParameter(s.k, w, *s.ax, true, homeOffset, -1234, false, s.ctx());
  EXPECT_TRUE(w.out.done);
  s.endCycle();
  callWriteParameter(s.k, w, *s.ax, false, homeOffset, -1234, false, s.ctx());
  EXPECT_FALSE(w.out.done);
  // Read back by SDO.
  callReadParameter(s.k, r, *s.ax, true, homeOffset, false, s.ctx());
  s.endCycle();
  EXPECT_EQ(parameterState(r).value, -1234.0);
  // Errors in the kernel step: read-only object, no object, wrong length -> 141;
  // a value outside the object's type -> 143.
  auto write = [&](int32_t n, double value) {
    callWriteParameter(s.k, w, *s.ax, true, n, value, false, s.ctx());
    EXPECT_TRUE(w.out.busy);
    EXPECT_FALSE(w.out.error);
    s.endCycle();
    const Error e = w.out.error ? w.out.errorId : Error::None;
    EXPECT_FALSE(w.out.busy);
    callWriteParameter(s.k, w, *s.ax, false, n, value, false, s.ctx());
    s.endCycle();
    return e;
  };
  EXPECT_EQ(write(sdoParameterNumber(2, 0x6041, 0), 1), Error::WriteParamSendingError);
  EXPECT_EQ(write(sdoParameterNumber(4, 0x2000, 0), 1), Error::WriteParamSendingError);
  EXPECT_EQ(write(sdoParameterNumber(2, 0x607C, 0), 1), Error::WriteParamSendingError);
  EXPECT_EQ(write(sdoParameterNumber(1, 0x6060, 0), 128), Error::WriteParamConversionError);   // INT8
  EXPECT_EQ(write(sdoParameterNumber(2, 0x6072, 0), -1), Error::WriteParamConversionError);    // UINT16
  EXPECT_EQ(write(homeOffset, 0.5), Error::WriteParamConversionError);
  EXPECT_EQ(write(homeOffset, std::nan("")), Error::WriteParamConversionError);
  EXPECT_EQ(write(sdoParameterNumber(1, 0x6060, 0), 9), Error::None);    // CSV
  ASSERT_TRUE(s.ax->drive().readObject(0x6061, 0, v));
  EXPECT_EQ(v, 9);
  // A bad SDO length: 140 in the call.
  callWriteParameter(s.k, w, *s.ax, true, sdoParameterNumber(3, 0x607C, 0), 1, false, s.ctx());
  EXPECT_TRUE(w.out.error);
  EXPECT_EQ(w.out.errorId, Error::WriteParamInvalid);
  // The BOOL variant writes 0/1 with the encoded length.
  FbSlot& wb = s.slot(FbKind::Parameter);
  callWriteParameter(s.k, wb, *s.ax, true, sdoParameterNumber(4, 0x60FE, 1), 1, true, s.ctx());
  s.endCycle();
  EXPECT_TRUE(wb.out.done);
  ASSERT_TRUE(s.ax->drive().readObject(0x60FE, 1, v));
  EXPECT_EQ(v, 1);
}

TEST(MotionConfig, SdoWriteWithExecuteAlreadyFalseShowsDoneForOneCycle) {
  Sim s;
  FbSlot& w = s.slot(FbKind::Parameter);
  const int32_t n = sdoParameterNumber(4, 0x607C, 0);
  callWriteParameter(s.k, w, *s.ax, true, n, 5, false, s.ctx());
  w.execute = false;   // stand-in: Execute already FALSE when the answer arrives
  s.endCycle();
  EXPECT_TRUE(w.out.done);
  callWriteParameter(s.k, w, *s.ax, false, n, 5, false, s.ctx());
  EXPECT_TRUE(w.out.done);          // visible in the next call
  s.endCycle();
  EXPECT_FALSE(w.out.done);         // cleared after one cycle
}

// ---------------------------------------------------------------- SMC_ChangeDynamicLimits

TEST(MotionConfig, ChangeDynamicLimits) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& f = s.slot(FbKind::Config);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  auto change = [&](double v, double a, double d, double j) {
    callChangeDynamicLimits(s.k, f, *s.ax, true, v, a, d, j, s.ctx());
    const Error e = f.out.error ? f.out.errorId : Error::None;
    EXPECT_FALSE(f.out.busy);
    callChangeDynamicLimits(s.k, f, *s.ax, false, v, a, d, j, s.ctx());
    return e;
  };
  const double nan = std::nan("");
  EXPECT_EQ(change(0, 1, 1, 1), Error::SdlInvalidVelocityValues);
  EXPECT_EQ(change(1, -1, 1, 1), Error::SdlInvalidVelocityValues);
  EXPECT_EQ(change(1, 1, nan, 1), Error::SdlInvalidVelocityValues);
  EXPECT_EQ(change(1, 1, 1, INFINITY), Error::SdlInvalidVelocityValues);
  EXPECT_EQ(change(1, 1, 1, 0), Error::SdlInvalidVelocityValues);
  EXPECT_EQ(change(20, 150, 100, 1e4), Error::None);    // power_off
  EXPECT_EQ(s.ax->config().maxVelocity, 20.0);
  EXPECT_EQ(s.ax->config().maxAcceleration, 150.0);
  EXPECT_EQ(s.ax->config().maxDeceleration, 100.0);
  EXPECT_EQ(s.ax->config().maxJerk, 1e4);
  s.powerOn(p);
  EXPECT_EQ(change(20, 100, 100, 1e4), Error::None);    // standstill
  // Not in discrete motion: 475, the limits stay.
  s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  s.endCycle();
  s.k.callMove(m, *s.ax, true, absolute(100, 10, 100, 100), s.ctx());
  EXPECT_EQ(change(30, 200, 200, 1e4), Error::SdlInvalidAxisState);
  EXPECT_EQ(s.ax->config().maxVelocity, 20.0);
  s.endCycle();
  // A move beyond the new acceleration limit: error 41 in the first step of motion.
  FbSlot& h = s.slot(FbKind::Halt);
  MoveInputs halt;
  halt.deceleration = 100;
  s.k.callHalt(h, *s.ax, true, halt, s.ctx());
  for (int i = 0; i < 200 && s.ax->state() != AxisState::Standstill; ++i) {
    s.k.callHalt(h, *s.ax, true, halt, s.ctx());
    s.endCycle();
  }
  ASSERT_EQ(s.ax->state(), AxisState::Standstill);
  FbSlot& m2 = s.slot(FbKind::MoveAbsolute);
  s.k.callMove(m2, *s.ax, true, absolute(0, 10, 200, 100), s.ctx());
  s.endCycle();
  EXPECT_FALSE(m2.out.error);       // the profile starts at the edge's cycle: no motion yet
  s.k.callMove(m2, *s.ax, true, absolute(0, 10, 200, 100), s.ctx());
  s.endCycle();
  EXPECT_TRUE(m2.out.error);
  EXPECT_EQ(m2.out.errorId, Error::VdMaxAccelerationExceeded);
}

// ---------------------------------------------------------------- SMC_SetRampType

TEST(MotionConfig, RampTypeChangesThePlannedProfile) {
  // 0 -> 100 at v = 10, a = d = 100, jerk 1000: trapez 10.1 s; quadratic 10 + v/a + a/j = 10.2 s;
  // sin² (peak acceleration a, ramp 2 v / a = 0.2 s) 10.2 s as well.
  struct Case { int ramp; double jerk; uint64_t cycles; double vAt50ms; };
  for (Case cs : {Case{0, 1000, 10100, 5.0}, Case{2, 1000, 10200, 1.25}, Case{3, 1000, 10200, 1.25},
                  Case{1, 0, 10200, 1.25}}) {
    Sim s;
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& rt = s.slot(FbKind::Config);
    FbSlot& m = s.slot(FbKind::MoveAbsolute);
    callSetRampType(s.k, rt, *s.ax, true, cs.ramp, s.ctx());     // power_off
    EXPECT_TRUE(rt.out.done) << cs.ramp;
    EXPECT_EQ(static_cast<int>(s.ax->config().ramp), cs.ramp);
    s.endCycle();
    callSetRampType(s.k, rt, *s.ax, false, cs.ramp, s.ctx());
    EXPECT_FALSE(rt.out.done);
    s.powerOn(p);
    const MoveInputs in = absolute(100, 10, 100, 100, cs.jerk);
    const uint64_t c0 = s.cycle;
    uint64_t doneCycle = 0;
    while (s.cycle < c0 + 11000 && !doneCycle) {
      s.k.callMove(m, *s.ax, true, in, s.ctx());
      const uint64_t c = s.cycle;
      s.endCycle();
      // 50 ms into the move: trapez v = a t; jerk-limited v = j t^2 / 2.
      if (c == c0 + 50) {
        EXPECT_NEAR(s.ax->set().v, cs.vAt50ms, 1e-9) << cs.ramp;
      }
      EXPECT_FALSE(m.out.error) << cs.ramp;
      if (m.out.done) doneCycle = c;
    }
    EXPECT_EQ(doneCycle, c0 + cs.cycles) << cs.ramp;
    EXPECT_NEAR(s.ax->set().p, 100.0, 1e-9);
  }
}

TEST(MotionConfig, RampTypeErrors) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& rt = s.slot(FbKind::Config);
  FbSlot& m = s.slot(FbKind::MoveVelocity);
  callSetRampType(s.k, rt, *s.ax, true, 4, s.ctx());
  EXPECT_TRUE(rt.out.error);
  EXPECT_EQ(rt.out.errorId, Error::SrtInvalidRampType);
  callSetRampType(s.k, rt, *s.ax, false, 4, s.ctx());
  callSetRampType(s.k, rt, *s.ax, true, -1, s.ctx());
  EXPECT_EQ(rt.out.errorId, Error::SrtInvalidRampType);
  callSetRampType(s.k, rt, *s.ax, false, 2, s.ctx());
  // Quadratic ramps need a jerk: a move without one is refused with 201.
  callSetRampType(s.k, rt, *s.ax, true, 2, s.ctx());
  EXPECT_TRUE(rt.out.done);
  callSetRampType(s.k, rt, *s.ax, false, 2, s.ctx());
  s.powerOn(p);
  FbSlot& a = s.slot(FbKind::MoveAbsolute);
  s.k.callMove(a, *s.ax, true, absolute(10, 10, 100, 100, 0), s.ctx());
  EXPECT_EQ(a.out.errorId, Error::MaInvalidVelAcc);
  // In continuous motion: 850, the ramp type stays.
  MoveInputs v;
  v.velocity = 5;
  v.acceleration = v.deceleration = 100;
  v.jerk = 1000;
  s.k.callMove(m, *s.ax, true, v, s.ctx());
  s.endCycle();
  s.k.callMove(m, *s.ax, true, v, s.ctx());
  callSetRampType(s.k, rt, *s.ax, true, 0, s.ctx());
  EXPECT_TRUE(rt.out.error);
  EXPECT_EQ(rt.out.errorId, Error::SrtNotStandstillOrPoweroff);
  EXPECT_EQ(s.ax->config().ramp, RampType::Quadratic);
  // SMC_SetCustomRampType: 850 in motion, 851 otherwise (user ramp objects are not run).
  FbSlot& cr = s.slot(FbKind::Config);
  callSetCustomRampType(s.k, cr, *s.ax, true, true, true, s.ctx());
  EXPECT_EQ(cr.out.errorId, Error::SrtNotStandstillOrPoweroff);
  callSetCustomRampType(s.k, cr, *s.ax, false, true, true, s.ctx());
  EXPECT_FALSE(cr.out.error);
  Sim s2;
  FbSlot& cr2 = s2.slot(FbKind::Config);
  callSetCustomRampType(s2.k, cr2, *s2.ax, true, true, true, s2.ctx());
  EXPECT_TRUE(cr2.out.error);
  EXPECT_FALSE(cr2.out.done);
  EXPECT_EQ(cr2.out.errorId, Error::SrtInvalidRampType);
  EXPECT_EQ(s2.ax->config().ramp, RampType::Trapez);
}

// ---------------------------------------------------------------- SMC_SetMovementType

TEST(MotionConfig, SetMovementTypeSwitchesBetweenLinearAndModulo) {
  Sim s;
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& mt = s.slot(FbKind::Config);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  auto set = [&](int type, double period) {
    callSetMovementType(s.k, mt, *s.ax, true, type, period, s.ctx());
    const Error e = mt.out.error ? mt.out.errorId : Error::None;
    EXPECT_EQ(mt.out.done, e == Error::None);
    callSetMovementType(s.k, mt, *s.ax, false, type, period, s.ctx());
    return e;
  };
  EXPECT_EQ(set(2, 360), Error::SmtInvalidMovementTypeOrPositionPeriod);
  EXPECT_EQ(set(0, 0), Error::SmtInvalidMovementTypeOrPositionPeriod);
  EXPECT_EQ(set(0, -1), Error::SmtInvalidMovementTypeOrPositionPeriod);
  EXPECT_EQ(set(0, std::nan("")), Error::SmtInvalidMovementTypeOrPositionPeriod);
  s.powerOn(p);
  runMove(s, m, absolute(370, 100, 1000, 1000));
  EXPECT_EQ(s.ax->set().p, 370.0);
  // Modulo 360: the position is reported (and kept) as 10.
  EXPECT_EQ(set(0, 360), Error::None);
  EXPECT_TRUE(s.ax->isModulo());
  EXPECT_EQ(s.ax->reportPosition(s.ax->set().p), 10.0);
  EXPECT_EQ(s.ax->set().p, 10.0);
  EXPECT_EQ(s.ax->actPosition(), 10.0);
  // MoveAbsolute 350 positive: +340 (a linear axis would move -20).
  FbSlot& m2 = s.slot(FbKind::MoveAbsolute);
  runMove(s, m2, absolute(350, 100, 1000, 1000));
  EXPECT_NEAR(s.ax->reportPosition(s.ax->set().p), 350.0, 1e-9);
  EXPECT_NEAR(s.ax->set().p - 10.0, 340.0, 1e-9);
  // Back to linear: the position stays 350.
  EXPECT_EQ(set(1, 1), Error::None);
  EXPECT_FALSE(s.ax->isModulo());
  EXPECT_NEAR(s.ax->set().p, 350.0, 1e-9);
  // While moving: 852.
  FbSlot& m3 = s.slot(FbKind::MoveAbsolute);
  s.k.callMove(m3, *s.ax, true, absolute(0, 100, 1000, 1000), s.ctx());
  s.endCycle();
  s.k.callMove(m3, *s.ax, true, absolute(0, 100, 1000, 1000), s.ctx());
  EXPECT_EQ(set(0, 360), Error::SmtNotStandstillOrPoweroff);
  EXPECT_FALSE(s.ax->isModulo());
  // Only virtual axes: 854.
  AxisConfig servo;
  servo.drive.kind = AxisKind::Servo;
  Sim s2(servo);
  FbSlot& mt2 = s2.slot(FbKind::Config);
  callSetMovementType(s2.k, mt2, *s2.ax, true, 0, 360, s2.ctx());
  EXPECT_EQ(mt2.out.errorId, Error::SmtAxisNotVirtual);
}

// ---------------------------------------------------------------- SMC_SetSoftwareLimits

namespace {

// MoveVelocity 10 u/s with a = 1000 from 0 until the axis errors; the cycle of the error.
uint64_t runIntoLimit(Sim& s, FbSlot& m) {
  MoveInputs v;
  v.velocity = 10;
  v.acceleration = v.deceleration = 1000;
  v.direction = Direction::Positive;
  for (int i = 0; i < 2000; ++i) {
    s.k.callMove(m, *s.ax, true, v, s.ctx());
    const uint64_t c = s.cycle;
    s.endCycle();
    if (m.out.error) return c;
  }
  return 0;
}

void runToRest(Sim& s) {
  for (int i = 0; i < 2000 && !s.ax->atRest(); ++i) s.endCycle();
}

}  // namespace

TEST(MotionConfig, SoftwareLimitsTripErrorTenAndBrakeAsConfigured) {
  // Positive limit 5.0005: the set position (0.05 after the 10 ms ramp, then 10 u/s)
  // passes it in the 506th ms of motion at 5.01.
  struct Case { bool decelerate; double dec, maxDist, stopAt; };
  for (Case cs : {Case{true, 100, 0, 5.01 + 0.5}, Case{true, 100, 0.25, 5.01 + 0.25}, Case{false, 0, 0, 5.01}}) {
    Sim s;
    FbSlot& p = s.slot(FbKind::Power);
    FbSlot& sl = s.slot(FbKind::Config);
    FbSlot& m = s.slot(FbKind::MoveVelocity);
    SoftwareLimits l;
    l.activated = true;
    l.positive = 5.0005;
    l.negative = -1;
    l.decelerate = cs.decelerate;
    l.deceleration = cs.dec;
    l.maxDistance = cs.maxDist;
    callSetSoftwareLimits(s.k, sl, *s.ax, true, l, s.ctx());
    EXPECT_TRUE(sl.out.done);
    EXPECT_TRUE(s.ax->config().swLimitEnable);
    callSetSoftwareLimits(s.k, sl, *s.ax, false, l, s.ctx());
    s.powerOn(p);
    const uint64_t c0 = s.cycle;
    const uint64_t err = runIntoLimit(s, m);
    EXPECT_EQ(err, c0 + 506);
    EXPECT_EQ(m.out.errorId, Error::SwLimitsExceeded);
    EXPECT_EQ(s.ax->state(), AxisState::ErrorStop);
    EXPECT_NEAR(s.ax->set().p, 5.01, 1e-9);
    runToRest(s);
    EXPECT_NEAR(s.ax->set().p, cs.stopAt, 1e-9) << cs.decelerate << " " << cs.maxDist;
  }
}

TEST(MotionConfig, SoftwareLimitsInputErrorsAndDeactivation) {
  Sim s;
  FbSlot& sl = s.slot(FbKind::Config);
  auto set = [&](const SoftwareLimits& l) {
    callSetSoftwareLimits(s.k, sl, *s.ax, true, l, s.ctx());
    const Error e = sl.out.error ? sl.out.errorId : Error::None;
    callSetSoftwareLimits(s.k, sl, *s.ax, false, l, s.ctx());
    return e;
  };
  SoftwareLimits l;
  l.activated = true;
  l.positive = -1;
  l.negative = 1;
  EXPECT_EQ(set(l), Error::WriteParamInvalid);          // negative above positive
  l.positive = std::nan("");
  l.negative = 0;
  EXPECT_EQ(set(l), Error::WriteParamInvalid);
  l.positive = 10;
  l.deceleration = -1;
  EXPECT_EQ(set(l), Error::WriteParamInvalid);
  l.deceleration = 0;
  l.maxDistance = INFINITY;
  EXPECT_EQ(set(l), Error::WriteParamInvalid);
  EXPECT_FALSE(s.ax->config().swLimitEnable);
  l.maxDistance = 0;
  EXPECT_EQ(set(l), Error::None);
  EXPECT_TRUE(s.ax->config().swLimitEnable);
  EXPECT_EQ(s.ax->config().swLimitPositive, 10.0);
  // Deactivated: the limits are not checked (the order of the values does not matter then).
  l.activated = false;
  l.positive = -5;
  EXPECT_EQ(set(l), Error::None);
  EXPECT_FALSE(s.ax->config().swLimitEnable);
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& m = s.slot(FbKind::MoveAbsolute);
  s.powerOn(p);
  runMove(s, m, absolute(20, 100, 1000, 1000));
  EXPECT_EQ(s.ax->state(), AxisState::Standstill);
  EXPECT_EQ(s.ax->set().p, 20.0);
}

// ---------------------------------------------------------------- SMC_ChangeGearingRatio

TEST(MotionConfig, ChangeGearingRatioKeepsTheIncrementsAndRescalesMotion) {
  Sim s;    // 1 increment per unit
  FbSlot& p = s.slot(FbKind::Power);
  FbSlot& g = s.slot(FbKind::Config);
  FbSlot& m = s.slot(FbKind::MoveRelative);
  s.powerOn(p);
  runMove(s, m, relative(10, 100, 1000, 1000));
  int64_t inc = 0;
  ASSERT_TRUE(s.ax->drive().readObject(0x6064, 0, inc));
  EXPECT_EQ(inc, 10);
  // Powered: 91 in the call.
  callChangeGearingRatio(s.k, g, *s.ax, true, 1310720, 10, 0, 1, s.ctx());
  EXPECT_TRUE(g.out.error);
  EXPECT_EQ(g.out.errorId, Error::CgrDrivePowered);
  callChangeGearingRatio(s.k, g, *s.ax, false, 1310720, 10, 0, 1, s.ctx());
  s.k.callPower(p, *s.ax, true, false, false, s.ctx());
  ASSERT_EQ(s.ax->state(), AxisState::PowerOff);
  s.endCycle();
  // 17-bit encoder, 10:1 gearbox, 10 mm lead: 1310720 increments = 10 mm.
  s.k.callPower(p, *s.ax, true, false, false, s.ctx());
  callChangeGearingRatio(s.k, g, *s.ax, true, 1310720, 10, 0, 1, s.ctx());
  EXPECT_TRUE(g.out.busy);
  EXPECT_FALSE(g.out.done);
  EXPECT_EQ(s.ax->config().drive.incrementsPerUnit, 1.0);
  s.endCycle();
  EXPECT_TRUE(g.out.done);          // applied in the kernel step
  EXPECT_FALSE(g.out.busy);
  EXPECT_EQ(s.ax->config().drive.incrementsPerUnit, 131072.0);
  ASSERT_TRUE(s.ax->drive().readObject(0x6064, 0, inc));
  EXPECT_EQ(inc, 10);               // the encoder count stays ...
  EXPECT_DOUBLE_EQ(s.ax->actPosition(), 10.0 / 131072);   // ... in the new unit
  callChangeGearingRatio(s.k, g, *s.ax, false, 1310720, 10, 0, 1, s.ctx());
  EXPECT_FALSE(g.out.done);
  // +1 unit is now 131072 increments.
  s.powerOn(p);
  FbSlot& m2 = s.slot(FbKind::MoveRelative);
  runMove(s, m2, relative(1, 100, 1000, 1000));
  ASSERT_TRUE(s.ax->drive().readObject(0x6064, 0, inc));
  EXPECT_EQ(inc, 10 + 131072);
}

TEST(MotionConfig, ChangeGearingRatioErrorsAndModulo) {
  Sim s;
  FbSlot& g = s.slot(FbKind::Config);
  auto change = [&](uint32_t denom, int32_t num, double period, int type) {
    callChangeGearingRatio(s.k, g, *s.ax, true, denom, num, period, type, s.ctx());
    Error e = g.out.error ? g.out.errorId : Error::None;
    if (e == Error::None) {
      EXPECT_TRUE(g.out.busy);
      s.endCycle();
      e = g.out.error ? g.out.errorId : Error::None;
    }
    callChangeGearingRatio(s.k, g, *s.ax, false, denom, num, period, type, s.ctx());
    s.endCycle();
    return e;
  };
  EXPECT_EQ(change(0, 1, 0, 1), Error::CgrZeroValues);
  EXPECT_EQ(change(1, 0, 0, 1), Error::CgrZeroValues);
  EXPECT_EQ(change(1, -1, 0, 1), Error::CgrZeroValues);
  EXPECT_EQ(change(1, 1, 0, 7), Error::CgrZeroValues);
  EXPECT_EQ(change(1, 1, 0, 0), Error::CgrInvalidPosPeriod);
  EXPECT_EQ(change(1, 1, -360, 0), Error::CgrInvalidPosPeriod);
  EXPECT_EQ(change(1, 1, std::nan(""), 0), Error::CgrInvalidPosPeriod);
  EXPECT_EQ(change(3, 1, 0.5, 0), Error::CgrPosPeriodNotIntegral);   // 1.5 increments
  EXPECT_FALSE(s.ax->isModulo());
  EXPECT_EQ(change(3600, 1, 360, 0), Error::None);
  EXPECT_EQ(s.ax->config().period, 360.0);
  EXPECT_EQ(s.ax->config().drive.incrementsPerUnit, 3600.0);
  EXPECT_EQ(change(1000, 1, 0, 1), Error::None);
  EXPECT_FALSE(s.ax->isModulo());
  // Powered between the call and the kernel step: 91 there.
  FbSlot& p = s.slot(FbKind::Power);
  callChangeGearingRatio(s.k, g, *s.ax, true, 10, 1, 0, 1, s.ctx());
  EXPECT_TRUE(g.out.busy);
  s.powerOn(p);
  s.endCycle();
  EXPECT_TRUE(g.out.error);
  EXPECT_EQ(g.out.errorId, Error::CgrDrivePowered);
  EXPECT_EQ(s.ax->config().drive.incrementsPerUnit, 1000.0);
}
