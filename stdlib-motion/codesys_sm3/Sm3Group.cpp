// The axis-group blocks of the CODESYS SoftMotion face (sm3_group.st): binding
// an AXIS_GROUP_REF_SM3 to its kernel group, the administration FBs and the
// group readers.  The semantics live in stdlib-motion/group.
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include <algorithm>
#include <cmath>

#include "stdlib-motion/group/GroupMotion.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

// The group behind an AXIS_GROUP_REF_SM3, bound on first use to the calling task;
// null when another task owns it (every FB of a group runs in one task).
AxisGroup* bindGroup(sm3::AXIS_GROUP_REF_SM3* ref, const CallCtx& c) {
  if (!ref) return nullptr;
  MotionSession& s = MotionSession::current();
  Kernel& k = s.kernel;
  AxisGroup* g = k.group(ref->__stcGroup - 1u);
  // The binding is only trusted when the group is bound to this very variable.
  if (!g || g->index() >= s.groupVars.size() || s.groupVars[g->index()] != ref) {
    g = &k.addGroup();
    if (s.groupVars.size() <= g->index()) s.groupVars.resize(g->index() + 1);
    s.groupVars[g->index()] = ref;
    ref->__stcGroup = g->index() + 1;
  }
  if (g->task == UINT32_MAX) g->task = c.task;
  return g->task == c.task ? g : nullptr;
}

// The body of the group FBs with Execute: bind, call, mirror the member axes.
template <class T, class F>
void groupFb(T* self, F call) {
  CallCtx c = callContext();
  AxisGroup* g = bindGroup(self->AxisGroup, c);
  if (refuse(self, g)) return;
  call(kernel(), slotOf(self, FbKind::Group), *g, c);
  for (Axis* ax : g->axes()) mirrorCall(*ax);
}

// Group FBs that also take an axis (add / remove): both must belong to the calling task.
template <class T, class F>
void groupAxisFb(T* self, F call) {
  CallCtx c = callContext();
  AxisGroup* g = bindGroup(self->AxisGroup, c);
  Axis* ax = g ? bind(self->Axis, c) : nullptr;
  if (refuse(self, ax)) return;
  call(kernel(), slotOf(self, FbKind::Group), *g, *ax, c);
}

void MC_AddAxisToGroup(sm3::MC_AddAxisToGroup* self) {
  groupAxisFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, Axis& ax, const CallCtx& c) { callAddAxisToGroup(k, fb, g, ax, self->Execute, c); });
}
void MC_RemoveAxisFromGroup(sm3::MC_RemoveAxisFromGroup* self) {
  groupAxisFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, Axis& ax, const CallCtx& c) { callRemoveAxisFromGroup(k, fb, g, ax, self->Execute, c); });
}
void MC_UngroupAllAxes(sm3::MC_UngroupAllAxes* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) { callUngroupAllAxes(k, fb, g, self->Execute, c); });
}
void MC_GroupEnable(sm3::MC_GroupEnable* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) { callGroupEnable(k, fb, g, self->Execute, c); });
}
void MC_GroupDisable(sm3::MC_GroupDisable* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) { callGroupDisable(k, fb, g, self->Execute, c); });
}
void MC_GroupReset(sm3::MC_GroupReset* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) { callGroupReset(k, fb, g, self->Execute, c); });
}
void SMC_GroupPower(sm3::SMC_GroupPower* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    callGroupPower(k, fb, g, self->__members, self, self->Enable, self->bRegulatorOn, self->bDriveStart, c);
  });
}

// MC_MoveDirect*: SMC_POS_REF's v[i] is member i's coordinate in every coordinate system
// (without kinematics every system equals ACS, docs/motion-groups.md); in TCS positions
// are relative to the pose at the start.
template <class T>
void moveDirect(T* self, const sm3::SMC_POS_REF& pos, bool relative) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    DirectInputs in;
    for (size_t i = 0; i < kMaxGroupAxes; ++i) in.position[i] = pos.v[i];
    in.relative = relative || self->CoordSystem == 5;   // TCS
    in.pathInvariant = self->MovementType == 1;
    in.velFactor = self->VelFactor;
    in.accFactor = self->AccFactor;
    in.jerkFactor = self->JerkFactor;
    in.bufferMode = bufferModeOf(self->BufferMode);
    in.transitionMode = self->TransitionMode;
    callGroupMoveDirect(k, fb, g, self->Execute, in, c);
  });
}
void MC_MoveDirectAbsolute(sm3::MC_MoveDirectAbsolute* self) { moveDirect(self, self->Position, false); }
void MC_MoveDirectRelative(sm3::MC_MoveDirectRelative* self) { moveDirect(self, self->Distance, true); }

// Path moves: the coordinates are the members' positions (v[i] of SMC_POS_REF: .c.X, .c.Y ...
// or .a.a0 ... in every coordinate system while the group has no kinematics).
template <class T>
PathInputs pathInputs(const T* self, const AxisGroup& g) {
  PathInputs in;
  in.spec.dyn = path::Dynamics{self->Velocity, self->Acceleration, self->Deceleration, self->Jerk};
  in.bufferMode = bufferModeOf(self->BufferMode);
  in.transitionMode = self->TransitionMode;
  in.spec.transitionParam = self->TransitionParameter[0];
  in.velFactor = self->VelFactor;
  in.accFactor = self->AccFactor;
  in.jerkFactor = self->JerkFactor;
  (void)g;
  return in;
}
template <class T>
void moveLinear(T* self, const sm3::SMC_POS_REF& pos, bool relative) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    PathInputs in = pathInputs(self, g);
    in.spec.kind = path::MoveKind::Line;
    in.spec.relative = relative || self->CoordSystem == 5;   // TCS: relative to the start
    for (size_t i = 0; i < g.axes().size(); ++i) in.spec.end[i] = pos.v[i];
    callGroupMovePath(k, fb, g, self->Execute, in, c);
  });
}
void MC_MoveLinearAbsolute(sm3::MC_MoveLinearAbsolute* self) { moveLinear(self, self->Position, false); }
void MC_MoveLinearRelative(sm3::MC_MoveLinearRelative* self) { moveLinear(self, self->Distance, true); }

// Circles in the X/Y plane of the first two members (plus helical / linear motion of the
// others): BORDER through AuxPoint; CENTER with AuxPoint[0..1] = the centre's offset from
// the start (manual: AuxPoint[1], [2] with 1-based numbering); RADIUS with AuxPoint[0] =
// the radius.  PathChoice 0 clockwise, 1 counter-clockwise (ignored by BORDER).
template <class T>
void moveCircular(T* self, bool relative) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    PathInputs in = pathInputs(self, g);
    const bool rel = relative || self->CoordSystem == 5;
    in.spec.relative = rel;
    for (size_t i = 0; i < g.axes().size(); ++i) in.spec.end[i] = self->EndPoint.v[i];
    in.spec.ccw = self->PathChoice == 1;
    switch (self->CircMode) {
      case 0:   // BORDER
        in.spec.kind = path::MoveKind::ArcBorder;
        for (size_t i = 0; i < g.axes().size(); ++i) in.spec.aux[i] = self->AuxPoint.v[i];
        break;
      case 1:   // CENTER: an offset from the start point, in both the absolute and relative FB
        in.spec.kind = path::MoveKind::ArcCenter;
        in.spec.aux = path::Vec{};
        in.spec.aux[0] = self->AuxPoint.v[0];
        in.spec.aux[1] = self->AuxPoint.v[1];
        in.spec.centerRelative = true;
        break;
      case 2:   // RADIUS
        in.spec.kind = path::MoveKind::ArcRadius;
        in.spec.radius = std::fabs(self->AuxPoint.v[0]);
        in.spec.longArc = self->AuxPoint.v[0] < 0;   // a negative radius: the arc of more than half a turn
        break;
      default:
        return k.fail(fb, Error::AgInvalidMoveInputs, c);
    }
    callGroupMovePath(k, fb, g, self->Execute, in, c);
  });
}
void MC_MoveCircularAbsolute(sm3::MC_MoveCircularAbsolute* self) { moveCircular(self, false); }
void MC_MoveCircularRelative(sm3::MC_MoveCircularRelative* self) { moveCircular(self, true); }

template <class T>
GroupStopInputs stopInputs(const T* self) {
  GroupStopInputs in;
  in.deceleration = self->Deceleration;
  in.jerk = self->Jerk;
  in.accFactor = self->AccFactor;
  in.jerkFactor = self->JerkFactor;
  return in;
}
void MC_GroupHalt(sm3::MC_GroupHalt* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) { callGroupHalt(k, fb, g, self->Execute, stopInputs(self), c); });
}
void MC_GroupStop(sm3::MC_GroupStop* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) { callGroupStop(k, fb, g, self->Execute, stopInputs(self), c); });
}

// Readers: Valid and Busy while Enable; refreshed at every call.
template <class T, class F>
void groupReader(T* self, F fill) {
  CallCtx c = callContext();
  readerOutputs(self, self->Enable ? bindGroup(self->AxisGroup, c) : nullptr, fill);
}

void MC_GroupReadStatus(sm3::MC_GroupReadStatus* self) {
  self->GroupMoving = self->GroupHoming = self->GroupErrorStop = self->GroupStandby = self->GroupStopping = self->GroupDisabled =
      self->TrackingDynamicCS = self->InSync = false;
  self->ActiveMovementId = 0;
  groupReader(self, [&](AxisGroup& g) {
    switch (g.state()) {
      case GroupState::Disabled: self->GroupDisabled = true; break;
      case GroupState::Standby: self->GroupStandby = true; break;
      case GroupState::Moving: self->GroupMoving = true; break;
      case GroupState::Homing: self->GroupHoming = true; break;
      case GroupState::Stopping: self->GroupStopping = true; break;
      case GroupState::ErrorStop: self->GroupErrorStop = true; break;
    }
    self->ActiveMovementId = static_cast<uint32_t>(g.activeMovementId);
    // Not moving along a path: in sync when every member stands at its set point.
    bool still = true;
    for (const Axis* ax : g.axes()) still = still && ax->set().v == 0;
    self->InSync = g.enabled() && g.state() != GroupState::ErrorStop && still;
  });
}

// Set and actual values of the members: v[i] = member i (every coordinate system while the
// group has no kinematics); the rest of the union is 0.
template <class T, class F>
void groupValues(T* self, sm3::SMC_POS_REF& out, F value) {
  out = sm3::SMC_POS_REF{};
  groupReader(self, [&](AxisGroup& g) {
    for (size_t i = 0; i < g.axes().size(); ++i) out.v[i] = value(*g.axes()[i]);
  });
}
void SMC_GroupReadSetPosition(sm3::SMC_GroupReadSetPosition* self) {
  self->KinematicConfig = sm3::CONFIGDATA{};
  groupValues(self, self->Position, [](const Axis& ax) { return ax.reportPosition(ax.set().p); });
}
void SMC_GroupReadSetVelocity(sm3::SMC_GroupReadSetVelocity* self) {
  groupValues(self, self->Velocity, [](const Axis& ax) { return ax.set().v; });
}
void SMC_GroupReadSetAcceleration(sm3::SMC_GroupReadSetAcceleration* self) {
  groupValues(self, self->Acceleration, [](const Axis& ax) { return ax.set().a; });
}
void MC_GroupReadActualPosition(sm3::MC_GroupReadActualPosition* self) {
  self->KinematicConfig = sm3::CONFIGDATA{};
  groupValues(self, self->Position, [](const Axis& ax) { return ax.reportPosition(ax.actPosition()); });
}
void MC_GroupReadActualVelocity(sm3::MC_GroupReadActualVelocity* self) {
  groupValues(self, self->Velocity, [](const Axis& ax) { return ax.actVelocity(); });
}

void MC_GroupSetPosition(sm3::MC_GroupSetPosition* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    callGroupSetPosition(k, fb, g, self->Execute, self->Position.v, self->Relative || self->CoordSystem == 5, c);
  });
}

void MC_GroupSetOverride(sm3::MC_GroupSetOverride* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    OverrideInputs in{self->VelFactor, self->AccFactor, self->JerkFactor, self->PathVelFactor, self->PathAccFactor, self->PathJerkFactor};
    callGroupSetOverride(k, fb, g, self->Enable, in, c);
  });
  if (!self->Error) self->Enabled = self->Busy;
}

// The interruption's token goes into continueData when the interrupt is Done (CODESYS: the
// continue data is written once Done is TRUE).
void MC_GroupInterrupt(sm3::MC_GroupInterrupt* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    callGroupInterrupt(k, fb, g, self->Execute, self->__token, self->mvtIdInterruptPosition, c);
    if (self->Done && self->continueData) {
      self->continueData->__group = g.index() + 1;
      self->continueData->__token = self->__token;
    }
  });
}

void MC_GroupContinue(sm3::MC_GroupContinue* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    const bool same = self->continueData && self->continueData->__group == g.index() + 1;
    callGroupContinue(k, fb, g, self->Execute, same ? self->continueData->__token : 0, c);
  });
}

void SMC_GroupTargetPosition(sm3::SMC_GroupTargetPosition* self) {
  self->Stable = false;
  self->KinematicConfig = sm3::CONFIGDATA{};
  self->Position = sm3::SMC_POS_REF{};
  groupReader(self, [&](AxisGroup& g) {
    const bool moving = g.state() == GroupState::Moving || g.state() == GroupState::Stopping;
    if (!g.targetValid && !moving) {   // after a halt or stop, or nothing commanded yet: where the group stands
      for (size_t i = 0; i < g.axes().size(); ++i) g.target[i] = g.axes()[i]->set().p;
      g.targetValid = g.enabled();
    }
    self->Valid = g.targetValid;
    self->Stable = g.targetValid && !moving;
    if (g.targetValid)
      for (size_t i = 0; i < g.axes().size(); ++i) self->Position.v[i] = g.axes()[i]->reportPosition(g.target[i]);
  });
}

void MC_GroupReadActualAcceleration(sm3::MC_GroupReadActualAcceleration* self) {
  const int64_t now = callContext().nowNs;
  double vel[kMaxGroupAxes] = {};
  bool read = false;
  groupValues(self, self->Acceleration, [&](const Axis&) { return 0.0; });
  groupReader(self, [&](AxisGroup& g) {
    read = true;
    for (size_t i = 0; i < g.axes().size(); ++i) vel[i] = g.axes()[i]->actVelocity();
    const double dt = static_cast<double>(now - self->__prevNs) * 1e-9;
    for (size_t i = 0; i < g.axes().size(); ++i)
      self->Acceleration.v[i] = self->__prevNs >= 0 && dt > 0 ? (vel[i] - self->__prevVel[i]) / dt : 0.0;
  });
  if (!read) {
    self->__prevNs = -1;   // the next enabled call starts over
    return;
  }
  std::copy(vel, vel + kMaxGroupAxes, self->__prevVel);
  self->__prevNs = now;
}

void SMC_SetDynamicLimitFactors(sm3::SMC_SetDynamicLimitFactors* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    AxisGroup::LimitFactors f[kMaxGroupAxes];
    for (size_t i = 0; i < kMaxGroupAxes; ++i) f[i] = {self->VelFactors[i], self->AccFactors[i], self->DecFactors[i], self->JerkFactors[i]};
    callSetDynamicLimitFactors(k, fb, g, self->Execute, f, c);
  });
}

template <class T>
void ancillary(T* self, bool path) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    Limits lim[kMaxGroupAxes];
    for (size_t i = 0; i < kMaxGroupAxes; ++i)
      lim[i] = Limits{self->Limits[i].fVelocity, self->Limits[i].fAcceleration, self->Limits[i].fDeceleration, self->Limits[i].fJerk};
    if (self->ExecutionMode != 0 && self->ExecutionMode != 1) return k.fail(fb, Error::AgInvalidMoveInputs, c);
    callSetAncillaryLimits(k, fb, g, self->Execute, path, self->ExecutionMode == 0, lim, c);
  });
}
void SMC_GroupSetAncillaryAxisLimits(sm3::SMC_GroupSetAncillaryAxisLimits* self) { ancillary(self, false); }
void SMC_GroupSetAncillaryPathLimits(sm3::SMC_GroupSetAncillaryPathLimits* self) { ancillary(self, true); }

// Done in the call of the edge with the position the interrupted motion stands at (ACS: the
// members' coordinates), or Error SMC_AG_NOT_INTERRUPTED.
void SMC_GroupGetContinuePosition(sm3::SMC_GroupGetContinuePosition* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    if (!k.beginExecute(fb, self->Execute, c)) return fb.sync();
    fb.axis = nullptr;
    const bool same = self->continueData && self->continueData->__group == g.index() + 1;
    double pos[kMaxGroupAxes] = {};
    if (!continuePosition(g, same ? self->continueData->__token : 0, pos)) return k.fail(fb, Error::AgNotInterrupted, c);
    self->Position = sm3::SMC_POS_REF{};
    for (size_t i = 0; i < kMaxGroupAxes; ++i) self->Position.v[i] = pos[i];
    self->CoordSystem = 0;   // ACS
    k.finish(fb, &c, c.cycle, true, false, Error::None);
  });
}

void SMC_GroupWait(sm3::SMC_GroupWait* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) { callGroupWait(k, fb, g, self->Execute, self->WaitTime, c); });
}

void MC_GroupReadError(sm3::MC_GroupReadError* self) {
  self->GroupErrorID = 0;
  groupReader(self, [&](AxisGroup& g) {
    self->ErrorID = static_cast<decltype(self->ErrorID)>(smcError(g.axisError()));
    self->GroupErrorID = static_cast<decltype(self->GroupErrorID)>(smcError(g.groupError()));
  });
}

void MC_GroupReadConfiguration(sm3::MC_GroupReadConfiguration* self) {
  self->pAxis = nullptr;
  self->NumAxes = 0;
  groupReader(self, [&](AxisGroup& g) {
    self->NumAxes = static_cast<uint32_t>(g.axes().size());
    MotionSession& s = MotionSession::current();
    if (self->IdentInGroup >= g.axes().size()) {   // no such member: an error, not a dangling pointer
      self->Valid = false;
      self->Error = true;
      self->ErrorID = static_cast<decltype(self->ErrorID)>(smcError(Error::AgAxisNotInGroup));
      return;
    }
    const Axis* ax = g.axes()[self->IdentInGroup];
    self->pAxis = static_cast<sm3::AXIS_REF_SM3*>(s.axisVars[ax->index()].var);
  });
}

}  // namespace

namespace stc::motion {

void registerSm3GroupNatives(MotionLibrary& lib) {
  lib.addGroupFace({"AXIS_GROUP_REF_SM3", [](void* var, uint32_t index) { static_cast<sm3::AXIS_GROUP_REF_SM3*>(var)->__stcGroup = index + 1; }});
  STC_SM3_NATIVE(MC_AddAxisToGroup, MC_AddAxisToGroup)
  STC_SM3_NATIVE(MC_RemoveAxisFromGroup, MC_RemoveAxisFromGroup)
  STC_SM3_NATIVE(MC_UngroupAllAxes, MC_UngroupAllAxes)
  STC_SM3_NATIVE(MC_GroupEnable, MC_GroupEnable)
  STC_SM3_NATIVE(MC_GroupDisable, MC_GroupDisable)
  STC_SM3_NATIVE(MC_GroupReset, MC_GroupReset)
  STC_SM3_NATIVE(SMC_GroupPower, SMC_GroupPower)
  STC_SM3_NATIVE(MC_GroupReadStatus, MC_GroupReadStatus)
  STC_SM3_NATIVE(MC_GroupReadError, MC_GroupReadError)
  STC_SM3_NATIVE(MC_GroupReadConfiguration, MC_GroupReadConfiguration)
  STC_SM3_NATIVE(MC_MoveDirectAbsolute, MC_MoveDirectAbsolute)
  STC_SM3_NATIVE(MC_MoveDirectRelative, MC_MoveDirectRelative)
  STC_SM3_NATIVE(MC_GroupHalt, MC_GroupHalt)
  STC_SM3_NATIVE(SMC_GroupReadSetPosition, SMC_GroupReadSetPosition)
  STC_SM3_NATIVE(SMC_GroupReadSetVelocity, SMC_GroupReadSetVelocity)
  STC_SM3_NATIVE(SMC_GroupReadSetAcceleration, SMC_GroupReadSetAcceleration)
  STC_SM3_NATIVE(MC_GroupReadActualPosition, MC_GroupReadActualPosition)
  STC_SM3_NATIVE(MC_GroupReadActualVelocity, MC_GroupReadActualVelocity)
  STC_SM3_NATIVE(SMC_GroupWait, SMC_GroupWait)
  STC_SM3_NATIVE(SMC_GroupGetContinuePosition, SMC_GroupGetContinuePosition)
  STC_SM3_NATIVE(SMC_GroupTargetPosition, SMC_GroupTargetPosition)
  STC_SM3_NATIVE(MC_GroupReadActualAcceleration, MC_GroupReadActualAcceleration)
  STC_SM3_NATIVE(SMC_SetDynamicLimitFactors, SMC_SetDynamicLimitFactors)
  STC_SM3_NATIVE(SMC_GroupSetAncillaryAxisLimits, SMC_GroupSetAncillaryAxisLimits)
  STC_SM3_NATIVE(SMC_GroupSetAncillaryPathLimits, SMC_GroupSetAncillaryPathLimits)
  STC_SM3_NATIVE(MC_GroupSetPosition, MC_GroupSetPosition)
  STC_SM3_NATIVE(MC_GroupSetOverride, MC_GroupSetOverride)
  STC_SM3_NATIVE(MC_GroupInterrupt, MC_GroupInterrupt)
  STC_SM3_NATIVE(MC_GroupContinue, MC_GroupContinue)
  STC_SM3_NATIVE(MC_MoveLinearAbsolute, MC_MoveLinearAbsolute)
  STC_SM3_NATIVE(MC_MoveLinearRelative, MC_MoveLinearRelative)
  STC_SM3_NATIVE(MC_MoveCircularAbsolute, MC_MoveCircularAbsolute)
  STC_SM3_NATIVE(MC_MoveCircularRelative, MC_MoveCircularRelative)
  STC_SM3_NATIVE(MC_GroupStop, MC_GroupStop)
}

}  // namespace stc::motion
