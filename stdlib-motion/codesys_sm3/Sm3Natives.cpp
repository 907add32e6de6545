// The CODESYS SoftMotion face: the AXIS_REF_SM3 binding and mirror, and the
// administration, motion and reader FBs of sm3_axis.st.  Each body copies the
// ST inputs into a kernel call and the FbOutputs back into the instance; the
// axis variable mirrors the kernel's axis after every call and cycle.
// Other instruction families live in Sm3<Family>.cpp next to this file.
#include <cmath>
#include <cstdint>
#include <vector>

#include "stdlib-motion/codesys_sm3/Sm3Face.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

// Saturating conversions without libm calls (the mirror runs for every axis in every cycle).
int32_t clampDint(double v) {
  if (!(v == v)) return 0;
  return v <= -2147483648.0 ? INT32_MIN : v >= 2147483647.0 ? INT32_MAX : static_cast<int32_t>(std::lrint(v));
}
int16_t clampInt(double v) {
  if (!(v == v)) return 0;
  return v <= -32768.0 ? INT16_MIN : v >= 32767.0 ? INT16_MAX : static_cast<int16_t>(std::lrint(v));
}

// What an FB call can change: state, errors, power, set/actual values, the limits.
void mirrorState(const Axis& ax, sm3::AXIS_REF_SM3& r) {
  r.nAxisState = static_cast<int16_t>(ax.state());
  r.bCommunication = ax.drive().communication();
  r.wCommunicationState = ax.drive().communication() ? 100 : 0;
  r.bVirtual = ax.config().drive.kind == AxisKind::Virtual;
  r.bRegulatorOn = ax.operational();
  r.bDriveStart = ax.driveStart();
  r.bError = ax.state() == AxisState::ErrorStop;
  r.nErrorID = static_cast<int16_t>(smcError(ax.error()));
  r.bFBErrorOccured = ax.state() == AxisState::ErrorStop || ax.fbError.set;
  const AxisConfig& c = ax.config();
  r.bSWLimitEnable = c.swLimitEnable;
  r.fSWLimitPositive = c.swLimitPositive;
  r.fSWLimitNegative = c.swLimitNegative;
  r.fPositionPeriod = c.period;
  r.fMaxVelocity = c.maxVelocity;
  r.fMaxAcceleration = c.maxAcceleration;
  r.fMaxDeceleration = c.maxDeceleration;
  r.fMaxJerk = c.maxJerk;
  r.fSetPosition = ax.reportPosition(ax.set().p);
  r.fSetVelocity = ax.set().v;
  r.fSetAcceleration = ax.set().a;
  r.fActPosition = ax.reportPosition(ax.actPosition());
  r.fActVelocity = ax.actVelocity();
  r.fActTorque = ax.actTorque();
  r.out.wControlWord = ax.drive().controlword();
  r.out.byModesOfOperation = ax.drive().modeOfOperation();   // 6 during drive-side homing
}

// Everything, with the drive's process data (once per cycle, after the kernel step).
void mirror(const Axis& ax, sm3::AXIS_REF_SM3& r) {
  mirrorState(ax, r);
  const double inc = ax.config().drive.incrementsPerUnit;
  r.in.wStatusWord = ax.drive().statusword();
  r.in.diActPosition = clampDint(ax.actPosition() * inc);
  r.in.diActVelocity = clampDint(ax.actVelocity() * inc);
  r.in.wActTorque = clampInt(ax.actTorque() * 10);
  r.in.wErrorCode = ax.drive().errorCode();
  r.in.dwDigitalInputs = ax.drive().digitalInputs();
  r.out.wSetTorque = clampInt(ax.drive().targetTorque() * 10);
  r.out.diSetPosition = clampDint(ax.set().p * inc);
  r.out.diSetVelocity = clampDint(ax.set().v * inc);
}

// An AXIS_REF_SM3 the project does not configure becomes a virtual axis
// configured from the values its initialiser gave.
AxisConfig configFromRef(const sm3::AXIS_REF_SM3& r) {
  AxisConfig c;
  c.drive.kind = AxisKind::Virtual;
  c.period = r.fPositionPeriod > 0 ? r.fPositionPeriod : 0;
  c.swLimitEnable = r.bSWLimitEnable;
  c.swLimitPositive = r.fSWLimitPositive;
  c.swLimitNegative = r.fSWLimitNegative;
  c.maxVelocity = r.fMaxVelocity;
  c.maxAcceleration = r.fMaxAcceleration;
  c.maxDeceleration = r.fMaxDeceleration;
  c.maxJerk = r.fMaxJerk;
  return c;
}

}  // namespace

namespace stc::motion::sm3face {

void mirrorVar(const Axis& ax, void* var) { mirror(ax, *static_cast<sm3::AXIS_REF_SM3*>(var)); }
void boundVar(void* var, const Axis& ax) { static_cast<sm3::AXIS_REF_SM3*>(var)->__stcAxis = ax.index() + 1; }

void mirrorAll(Axis& ax) { MotionSession::current().mirror(ax); }

void mirrorCall(Axis& ax) {
  MotionSession& s = MotionSession::current();
  if (s.mirrorsRead && ax.index() < s.axisVars.size() && s.axisVars[ax.index()].var)
    mirrorState(ax, *static_cast<sm3::AXIS_REF_SM3*>(s.axisVars[ax.index()].var));
}

Axis* bindMaster(sm3::AXIS_REF_SM3* ref, const CallCtx& c) {
  if (!ref) return nullptr;
  MotionSession& s = MotionSession::current();
  const uint64_t i = ref->__stcAxis - 1u;
  if (i < s.axisVars.size() && s.axisVars[i].var == ref) return s.axisVars[i].axis;
  return bind(ref, c);   // first use: bound (and owned) here
}

Axis* bind(sm3::AXIS_REF_SM3* ref, const CallCtx& c) {
  if (!ref) return nullptr;
  MotionSession& s = MotionSession::current();
  if (Axis* fast = s.boundAxis(ref->__stcAxis - 1, ref, c.task)) return fast;
  Kernel& k = s.kernel;
  Axis* ax = ref->__stcAxis ? k.axis(ref->__stcAxis - 1) : nullptr;
  // The binding is only trusted when the axis is bound to this very variable.
  if (!ax || ax->index() >= s.axisVars.size() || s.axisVars[ax->index()].var != ref) {
    ax = &k.addAxis(configFromRef(*ref));
    s.bindVar(*ax, ref, &mirrorVar);
    boundVar(ref, *ax);
  }
  if (!k.claim(*ax, c)) return nullptr;
  s.axisVars[ax->index()].task = ax->task;
  return ax;
}

}  // namespace stc::motion::sm3face

namespace {

void MC_Power(sm3::MC_Power* self) {
  CallCtx c = callContext();
  Axis* ax = bind(self->Axis, c);
  if (refuse(self, ax) || rewired(self, *ax, c)) return;
  FbSlot& fb = slotOf(self, FbKind::Power);
  // A call with the inputs of the previous one changes nothing the cycle's mirror does not show.
  const bool changed = fb.execute != static_cast<bool>(self->Enable) || ax->power != &fb ||
                       (self->Enable && (ax->powerRequested() != static_cast<bool>(self->bRegulatorOn) ||
                                         ax->driveStart() != static_cast<bool>(self->bDriveStart)));
  // Unchanged inputs on a settled axis (power as requested, no error): nothing to request;
  // the step's power follow-up (Kernel::updatePower) keeps the outputs current.
  if (!changed && self->Enable && fb.lastCallCycle + 1 >= c.cycle && ax->operational() == static_cast<bool>(self->bRegulatorOn) &&
      ax->state() != AxisState::ErrorStop && !ax->drive().faulted()) {
    fb.lastCallCycle = c.cycle;
    return;
  }
  kernel().callPower(fb, *ax, self->Enable, self->bRegulatorOn, self->bDriveStart, c);
  if (changed) mirrorCall(*ax);
}

void MC_Reset(sm3::MC_Reset* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) { k.callReset(slotOf(self, FbKind::Reset), ax, self->Execute, c); });
}

void MC_Halt(sm3::MC_Halt* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) { k.callHalt(slotOf(self, FbKind::Halt), ax, self->Execute, moveInputs(self), c); });
}

void MC_Stop(sm3::MC_Stop* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) { k.callStop(slotOf(self, FbKind::Stop), ax, self->Execute, moveInputs(self), c); });
}

void MC_Jog(sm3::MC_Jog* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) { k.callJog(slotOf(self, FbKind::Jog), ax, self->JogForward, self->JogBackward, moveInputs(self), c); });
}

void SMC_Inch(sm3::SMC_Inch* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) { k.callInch(slotOf(self, FbKind::Inch), ax, self->InchForward, self->InchBackward, moveInputs(self), c); });
}

void MC_SetPosition(sm3::MC_SetPosition* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) { k.callSetPosition(slotOf(self, FbKind::SetPosition), ax, self->Execute, self->Position, self->Mode, c); });
}

void MC_ReadActualPosition(sm3::MC_ReadActualPosition* self) {
  reader(self, [&](Axis& ax) { self->Position = ax.reportPosition(ax.actPosition()); });
}
void MC_ReadActualVelocity(sm3::MC_ReadActualVelocity* self) {
  reader(self, [&](Axis& ax) { self->Velocity = ax.actVelocity(); });
}
void MC_ReadActualTorque(sm3::MC_ReadActualTorque* self) {
  reader(self, [&](Axis& ax) { self->Torque = ax.actTorque(); });
}
void SMC_ReadSetPosition(sm3::SMC_ReadSetPosition* self) {
  reader(self, [&](Axis& ax) { self->Position = ax.reportPosition(ax.set().p); });
}
void MC_ReadStatus(sm3::MC_ReadStatus* self) {
  const bool on = self->Enable;
  self->Disabled = self->Errorstop = self->Stopping = self->StandStill = self->DiscreteMotion = self->ContinuousMotion =
      self->SynchronizedMotion = self->Homing = self->ConstantVelocity = self->Accelerating = self->Decelerating =
          self->FBErrorOccured = false;
  if (!on) return reader(self, [](Axis&) {});
  reader(self, [&](Axis& ax) {
    switch (ax.state()) {
      case AxisState::PowerOff: self->Disabled = true; break;
      case AxisState::ErrorStop: self->Errorstop = true; break;
      case AxisState::Stopping: self->Stopping = true; break;
      case AxisState::Standstill: self->StandStill = true; break;
      case AxisState::DiscreteMotion: self->DiscreteMotion = true; break;
      case AxisState::ContinuousMotion: self->ContinuousMotion = true; break;
      case AxisState::SynchronizedMotion: self->SynchronizedMotion = true; break;
      case AxisState::Homing: self->Homing = true; break;
    }
    const Kinematic& s = ax.set();
    const bool moving = s.v != 0;
    self->ConstantVelocity = moving && s.a == 0;
    self->Accelerating = moving && s.a * s.v > 0;
    self->Decelerating = moving && s.a * s.v < 0;
    self->FBErrorOccured = ax.state() == AxisState::ErrorStop;
  });
}
void MC_ReadAxisError(sm3::MC_ReadAxisError* self) {
  self->AxisError = self->SWEndSwitchActive = false;
  self->AxisErrorID = 0;
  reader(self, [&](Axis& ax) {
    self->AxisError = ax.state() == AxisState::ErrorStop;
    self->AxisErrorID = ax.drive().errorCode() ? ax.drive().errorCode() : smcError(ax.error());
    const AxisConfig& c = ax.config();
    self->SWEndSwitchActive = c.swLimitEnable && (ax.set().p >= c.swLimitPositive || ax.set().p <= c.swLimitNegative);
  });
}

}  // namespace

namespace stc::motion {

void registerSm3Natives(MotionLibrary& lib) {
  registerLeadshineNatives(lib);
  registerSm3ConfigNatives(lib);
  registerSm3DiagNatives(lib);
  registerSm3FileNatives(lib);
  registerSm3NcNatives(lib);
  registerSm3InterpolatorNatives(lib);
  registerSm3Interpolator2DirNatives(lib);
  registerSm3XInterpolatorNatives(lib);
  registerSm3ControlAxisNatives(lib);
  registerSm3PreprocessNatives(lib);
  registerSm3ToolCorrNatives(lib);
  registerSm3ProfilesNatives(lib);
  registerSm3HomingNatives(lib);
  registerSm3SyncNatives(lib);
  registerSm3CamNatives(lib);
  registerSm3GroupNatives(lib);
  registerSm3TrafoNatives(lib);
  registerLsFollowNatives(lib);
  registerLsInterpolationNatives(lib);
  registerLsGCodeNatives(lib);
  STC_SM3_NATIVE(MC_Power, MC_Power)
  STC_SM3_NATIVE(MC_Reset, MC_Reset)
  STC_SM3_NATIVE(MC_MoveAbsolute, moveBody<sm3::MC_MoveAbsolute, FbKind::MoveAbsolute>)
  STC_SM3_NATIVE(MC_MoveRelative, moveBody<sm3::MC_MoveRelative, FbKind::MoveRelative>)
  STC_SM3_NATIVE(MC_MoveAdditive, moveBody<sm3::MC_MoveAdditive, FbKind::MoveAdditive>)
  STC_SM3_NATIVE(MC_MoveSuperImposed, moveBody<sm3::MC_MoveSuperImposed, FbKind::MoveSuperImposed>)
  STC_SM3_NATIVE(MC_MoveVelocity, moveBody<sm3::MC_MoveVelocity, FbKind::MoveVelocity>)
  STC_SM3_NATIVE(SMC_MoveContinuousAbsolute, moveBody<sm3::SMC_MoveContinuousAbsolute, FbKind::MoveContinuousAbsolute>)
  STC_SM3_NATIVE(SMC_MoveContinuousRelative, moveBody<sm3::SMC_MoveContinuousRelative, FbKind::MoveContinuousRelative>)
  STC_SM3_NATIVE(MC_Halt, MC_Halt)
  STC_SM3_NATIVE(MC_Stop, MC_Stop)
  STC_SM3_NATIVE(MC_Jog, MC_Jog)
  STC_SM3_NATIVE(SMC_Inch, SMC_Inch)
  STC_SM3_NATIVE(MC_SetPosition, MC_SetPosition)
  STC_SM3_NATIVE(MC_ReadActualPosition, MC_ReadActualPosition)
  STC_SM3_NATIVE(MC_ReadActualVelocity, MC_ReadActualVelocity)
  STC_SM3_NATIVE(MC_ReadActualTorque, MC_ReadActualTorque)
  STC_SM3_NATIVE(SMC_ReadSetPosition, SMC_ReadSetPosition)
  STC_SM3_NATIVE(MC_ReadStatus, MC_ReadStatus)
  STC_SM3_NATIVE(MC_ReadAxisError, MC_ReadAxisError)
  lib.addAxisFace({"AXIS_REF_SM3", &mirrorVar, &boundVar});
}

}  // namespace stc::motion
