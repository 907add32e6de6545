// The axis-group blocks of the CODESYS SoftMotion face (sm3_group.st): binding
// an AXIS_GROUP_REF_SM3 to its kernel group, the administration FBs and the
// group readers.  The semantics live in stdlib-motion/group.
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include <algorithm>
#include <cmath>
#include <cstring>

#include "stdlib-motion/core/InputBounds.h"

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

// MC_MoveDirect*: SMC_POS_REF's v[i] is coordinate i of CoordSystem (GroupKinematics.h: with
// kinematics X..C and the additional axes, else the members); in TCS positions are relative
// to the pose at the start.
template <class T>
void moveDirect(T* self, const sm3::SMC_POS_REF& pos, bool relative) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    DirectInputs in;
    for (size_t i = 0; i < kMaxGroupAxes; ++i) in.position[i] = pos.v[i];
    in.relative = relative;
    in.coordSystem = self->CoordSystem;
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
  in.coordSystem = self->CoordSystem;
  in.orientationMode = self->OrientationMode;
  (void)g;
  return in;
}

// The number of coordinates a position in CoordSystem cs has for group g.
size_t coordsIn(const AxisGroup& g, int cs) {
  if (!validCoordSystem(cs)) return g.axes().size();
  return static_cast<size_t>(coordCount(g, cs == 5 ? CoordSystem::MCS : static_cast<CoordSystem>(cs)));
}
template <class T>
void moveLinear(T* self, const sm3::SMC_POS_REF& pos, bool relative) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    PathInputs in = pathInputs(self, g);
    in.spec.kind = path::MoveKind::Line;
    in.spec.relative = relative || self->CoordSystem == 5;   // TCS: relative to the start
    for (size_t i = 0; i < coordsIn(g, self->CoordSystem); ++i) in.spec.end[i] = pos.v[i];
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
    const size_t n = coordsIn(g, self->CoordSystem);
    for (size_t i = 0; i < n; ++i) in.spec.end[i] = self->EndPoint.v[i];
    in.spec.ccw = self->PathChoice == 1;
    switch (self->CircMode) {
      case 0:   // BORDER
        in.spec.kind = path::MoveKind::ArcBorder;
        for (size_t i = 0; i < n; ++i) in.spec.aux[i] = self->AuxPoint.v[i];
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

// Set and actual values in CoordSystem: the members' positions (velocities, accelerations)
// through the kinematics and frames.  Cartesian velocities and accelerations are the
// derivatives of the coordinates (A, B, C: of the angles), by central differences over h.
enum class Quantity { Position, Velocity, Acceleration };
bool groupVector(const Kernel& k, const AxisGroup& g, int cs, const Kinematic* q, Quantity what, double* out) {
  const size_t n = g.axes().size();
  if (!validCoordSystem(cs) || cs == 5) return false;
  const CoordSystem sys = static_cast<CoordSystem>(cs);
  double p[kMaxGroupAxes] = {};
  for (size_t i = 0; i < n; ++i) p[i] = q[i].p;
  if (what == Quantity::Position) return coordsOf(k, g, sys, p, out);
  if (sys == CoordSystem::ACS || (!g.kin && sys == CoordSystem::MCS)) {   // the members' own derivatives
    for (size_t i = 0; i < n; ++i) out[i] = what == Quantity::Velocity ? q[i].v : q[i].a;
    return true;
  }
  constexpr double h = 1e-4;
  double pp[kMaxGroupAxes] = {}, pm[kMaxGroupAxes] = {}, x0[kMaxGroupAxes] = {}, xp[kMaxGroupAxes] = {}, xm[kMaxGroupAxes] = {};
  for (size_t i = 0; i < n; ++i) {
    pp[i] = p[i] + h * q[i].v + 0.5 * h * h * q[i].a;
    pm[i] = p[i] - h * q[i].v + 0.5 * h * h * q[i].a;
  }
  if (!coordsOf(k, g, sys, p, x0) || !coordsOf(k, g, sys, pp, xp) || !coordsOf(k, g, sys, pm, xm)) return false;
  const int m = coordCount(g, sys);
  for (int i = 0; i < m; ++i) out[i] = what == Quantity::Velocity ? (xp[i] - xm[i]) / (2 * h) : (xp[i] - 2 * x0[i] + xm[i]) / (h * h);
  return true;
}

void setConfig(sm3::CONFIGDATA& out, const AxisGroup& g, const Kinematic* q) {
  out = sm3::CONFIGDATA{};
  if (!g.kin) return;
  double p[kMaxGroupAxes] = {};
  for (size_t i = 0; i < g.axes().size(); ++i) p[i] = q[i].p;
  const KinConfigData c = g.kin->configOf(p);
  out.iElbow = static_cast<int16_t>(c.elbow);
  out.iShoulder = static_cast<int16_t>(c.shoulder);
  out.iWrist = static_cast<int16_t>(c.wrist);
}

// A reader of set (actual) values: `state` gives member i's state.
template <class T, class F>
void groupValues(T* self, sm3::SMC_POS_REF& out, Quantity what, F state) {
  out = sm3::SMC_POS_REF{};
  groupReader(self, [&](AxisGroup& g) {
    Kinematic q[kMaxGroupAxes] = {};
    for (size_t i = 0; i < g.axes().size(); ++i) q[i] = state(*g.axes()[i]);
    if constexpr (requires { self->KinematicConfig; }) setConfig(self->KinematicConfig, g, q);
    if (!groupVector(kernel(), g, self->CoordSystem, q, what, out.v)) {
      out = sm3::SMC_POS_REF{};
      self->Valid = false;
      self->Error = true;
      self->ErrorID = static_cast<decltype(self->ErrorID)>(smcError(validCoordSystem(self->CoordSystem) && self->CoordSystem != 5
                                                                       ? Error::AgUnreachable : Error::AgInvalidCoordSystem));
    }
  });
}
Kinematic setState(const Axis& ax) { return Kinematic{ax.reportPosition(ax.set().p), ax.set().v, ax.set().a}; }
Kinematic actState(const Axis& ax) { return Kinematic{ax.reportPosition(ax.actPosition()), ax.actVelocity(), 0}; }

void SMC_GroupReadSetPosition(sm3::SMC_GroupReadSetPosition* self) { groupValues(self, self->Position, Quantity::Position, setState); }
void SMC_GroupReadSetVelocity(sm3::SMC_GroupReadSetVelocity* self) { groupValues(self, self->Velocity, Quantity::Velocity, setState); }
void SMC_GroupReadSetAcceleration(sm3::SMC_GroupReadSetAcceleration* self) {
  groupValues(self, self->Acceleration, Quantity::Acceleration, setState);
}
void MC_GroupReadActualPosition(sm3::MC_GroupReadActualPosition* self) { groupValues(self, self->Position, Quantity::Position, actState); }
void MC_GroupReadActualVelocity(sm3::MC_GroupReadActualVelocity* self) { groupValues(self, self->Velocity, Quantity::Velocity, actState); }

// In a Cartesian system the members' new positions come from the inverse kinematics (the
// configuration the members stand in); relative: added to the present coordinates.
void MC_GroupSetPosition(sm3::MC_GroupSetPosition* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    const int cs = self->CoordSystem;
    const bool relative = self->Relative || cs == 5;
    if (!validCoordSystem(cs)) return k.fail(fb, Error::AgInvalidCoordSystem, c);
    if (cs == 0 || (!g.kin && cs == 5)) return callGroupSetPosition(k, fb, g, self->Execute, self->Position.v, relative, c);
    if (!self->Execute || fb.execute) return callGroupSetPosition(k, fb, g, self->Execute, self->Position.v, relative, c);
    const CoordSystem sys = cs == 5 ? CoordSystem::MCS : static_cast<CoordSystem>(cs);
    double q[kMaxGroupAxes] = {}, x[kMaxGroupAxes] = {}, target[kMaxGroupAxes] = {};
    for (size_t i = 0; i < g.axes().size(); ++i) q[i] = g.axes()[i]->set().p;
    if (!coordsOf(k, g, sys, q, x)) return k.fail(fb, Error::AgInvalidCoordSystem, c);
    for (size_t i = 0; i < coordsIn(g, cs); ++i) x[i] = relative ? x[i] + self->Position.v[i] : self->Position.v[i];
    if (!jointsOf(k, g, sys, x, g.kin ? g.kin->configOf(q) : KinConfigData{}, q, target)) return k.fail(fb, Error::AgUnreachable, c);
    callGroupSetPosition(k, fb, g, self->Execute, target, false, c);
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

// Saved continue data goes into continueData once the save is complete (Done).
void SMC_GroupSaveContinueData(sm3::SMC_GroupSaveContinueData* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    callGroupSaveContinueData(k, fb, g, self->Execute, c);
    if (self->Done && self->continueData && savedContinueToken(g)) {
      self->continueData->__group = g.index() + 1;
      self->continueData->__token = savedContinueToken(g);
    }
  });
}

void SMC_GroupEnableResumeAfterError(sm3::AXIS_GROUP_REF_SM3* group, sm3::SMC_AXIS_GROUP_CONTINUE_DATA* data, bool enable,
                                     bool* busy) {
  CallCtx c = callContext();
  AxisGroup* g = bindGroup(group, c);
  const bool on = g && setGroupResumeAfterError(*g, enable);
  if (busy) *busy = on;
  if (on && data && savedContinueToken(*g)) {
    data->__group = g->index() + 1;
    data->__token = savedContinueToken(*g);
  }
}

// The reference axes are read only (bound like masters: they may belong to another task).
void SMC_GroupJog(sm3::SMC_GroupJog* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    JogInputs in;
    in.coordSystem = self->CoordSystem;
    in.pcs = self->CoordSystemPCS;
    in.velFactor = self->VelFactor;
    in.accFactor = self->AccFactor;
    in.jerkFactor = self->JerkFactor;
    in.abcAsAcs = self->ABC_as_ACS;
    void* refs[6] = {self->AxisX, self->AxisY, self->AxisZ, self->AxisA, self->AxisB, self->AxisC};
    bool bad = false;
    for (int r = 0; r < 6; ++r) {
      if (!refs[r]) continue;
      in.ref[r] = bindMaster(static_cast<sm3::AXIS_REF_SM3*>(refs[r]), c);
      bad = bad || !in.ref[r];
    }
    if (bad && self->Execute && !fb.execute) {   // a reference that is not an axis: refused at the edge
      if (k.beginExecute(fb, true, c)) return k.fail(fb, Error::AgInvalidMoveInputs, c);
      return;
    }
    callGroupJog(k, fb, g, self->Execute, in, c);
  });
}

void SMC_GroupTargetPosition(sm3::SMC_GroupTargetPosition* self) {
  self->Stable = false;
  self->KinematicConfig = sm3::CONFIGDATA{};
  self->Position = sm3::SMC_POS_REF{};
  groupReader(self, [&](AxisGroup& g) {
    const Kernel& k = kernel();
    const bool moving = g.state() == GroupState::Moving || g.state() == GroupState::Stopping;
    if (!g.targetValid && !moving) {   // after a halt or stop, or nothing commanded yet: where the group stands
      for (size_t i = 0; i < g.axes().size(); ++i) g.target[i] = g.axes()[i]->set().p;
      g.targetCs = CoordSystem::ACS;
      g.targetValid = g.enabled();
    }
    self->Valid = g.targetValid;
    self->Stable = g.targetValid && !moving;
    if (!g.targetValid) return;
    // The target in ACS (by the inverse kinematics near the members' set positions), then in CoordSystem.
    double near[kMaxGroupAxes] = {}, q[kMaxGroupAxes] = {}, out[kMaxGroupAxes] = {};
    for (size_t i = 0; i < g.axes().size(); ++i) near[i] = g.axes()[i]->set().p;
    const bool ok = jointsOf(k, g, g.targetCs, g.target, g.kinConfig, near, q) && validCoordSystem(self->CoordSystem) &&
                    self->CoordSystem != 5 && coordsOf(k, g, static_cast<CoordSystem>(self->CoordSystem), q, out);
    if (!ok) {
      self->Valid = self->Stable = false;
      self->Error = true;
      self->ErrorID = static_cast<decltype(self->ErrorID)>(smcError(Error::AgInvalidCoordSystem));
      return;
    }
    const size_t n = coordsIn(g, self->CoordSystem);
    for (size_t i = 0; i < n; ++i) self->Position.v[i] = out[i];
    if (self->CoordSystem == 0)
      for (size_t i = 0; i < g.axes().size(); ++i) self->Position.v[i] = g.axes()[i]->reportPosition(out[i]);
    Kinematic kq[kMaxGroupAxes] = {};
    for (size_t i = 0; i < g.axes().size(); ++i) kq[i].p = q[i];
    setConfig(self->KinematicConfig, g, kq);
  });
}

// The difference quotient of the actual velocity in CoordSystem between two calls.
void MC_GroupReadActualAcceleration(sm3::MC_GroupReadActualAcceleration* self) {
  const int64_t now = callContext().nowNs;
  sm3::SMC_POS_REF vel{};
  groupValues(self, vel, Quantity::Velocity, actState);
  self->Acceleration = sm3::SMC_POS_REF{};
  if (!self->Valid) {
    self->__prevNs = -1;   // the next enabled call starts over
    return;
  }
  const double dt = static_cast<double>(now - self->__prevNs) * 1e-9;
  for (size_t i = 0; i < kMaxGroupAxes; ++i)
    self->Acceleration.v[i] = self->__prevNs >= 0 && dt > 0 ? (vel.v[i] - self->__prevVel[i]) / dt : 0.0;
  std::copy(vel.v, vel.v + kMaxGroupAxes, self->__prevVel);
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

// ---- kinematics and coordinate systems

// The kinematics behind a TRAFO.MC_KIN_REF_SM3: one of the TRAFO.Kin_* blocks, recognised by
// the vtable its interface value carries (the instance's own vptr must be that vtable too);
// null for anything else or rejected parameters.
std::shared_ptr<const GroupKinematics> kinematicsOf(const stc_interface& itf) {
  if (!itf.self || !itf.itable) return nullptr;
  const void* vtable = *static_cast<const void* const*>(itf.itable);
  if (!vtable || *static_cast<const void* const*>(itf.self) != vtable) return nullptr;
  const char* name = static_cast<const char*>(*static_cast<const void* const*>(vtable));
  auto is = [&](const char* n) { return name && std::strcmp(name, n) == 0; };
  KinSpec spec;
  double* p = spec.param;
  if (is(sm3::Kin_Gantry2_typename)) {
    const auto* f = static_cast<const sm3::Kin_Gantry2*>(itf.self);
    spec.model = KinModel::Gantry2;
    p[0] = f->dOffsetX, p[1] = f->dOffsetY;
  } else if (is(sm3::Kin_Gantry3_typename)) {
    const auto* f = static_cast<const sm3::Kin_Gantry3*>(itf.self);
    spec.model = KinModel::Gantry3;
    p[0] = f->dOffsetX, p[1] = f->dOffsetY, p[2] = f->dOffsetZ;
  } else if (is(sm3::Kin_Scara2_Z_typename)) {
    const auto* f = static_cast<const sm3::Kin_Scara2_Z*>(itf.self);
    spec.model = KinModel::Scara2Z;
    p[0] = f->dArmLength1, p[1] = f->dArmLength2, p[2] = f->dOffsetA0, p[3] = f->dOffsetA1, p[4] = f->dOffsetA2;
  } else if (is(sm3::Kin_Tripod_Rotary_typename)) {
    const auto* f = static_cast<const sm3::Kin_Tripod_Rotary*>(itf.self);
    spec.model = KinModel::TripodRotary;
    p[0] = f->dOuterRadius, p[1] = f->dInnerRadius, p[2] = f->dLengthOuter, p[3] = f->dLengthInner, p[4] = f->dRotationOffset;
    p[5] = f->dOffsetA0, p[6] = f->dOffsetA1, p[7] = f->dOffsetA2;
  } else if (is(sm3::Kin_Tripod_Lin_typename)) {
    const auto* f = static_cast<const sm3::Kin_Tripod_Lin*>(itf.self);
    spec.model = KinModel::TripodLinear;
    p[0] = f->dOuterRadius, p[1] = f->dInnerRadius, p[2] = f->dLength, p[3] = f->dAxisAngle, p[4] = f->dRotationOffset;
    p[5] = f->dOffsetA0, p[6] = f->dOffsetA1, p[7] = f->dOffsetA2;
  } else if (is(sm3::Kin_Scara3_Z_typename)) {
    const auto* f = static_cast<const sm3::Kin_Scara3_Z*>(itf.self);
    spec.model = KinModel::Scara3Z;
    p[0] = f->dArmLength1, p[1] = f->dArmLength2, p[2] = f->dArmLength3;
    p[3] = f->dOffsetA0, p[4] = f->dOffsetA1, p[5] = f->dOffsetA2, p[6] = f->dOffsetA3;
  } else if (is(sm3::Kin_ArticulatedRobot_6DOF_typename)) {
    const auto* f = static_cast<const sm3::Kin_ArticulatedRobot_6DOF*>(itf.self);
    spec.model = KinModel::Articulated6;
    p[0] = f->d1, p[1] = f->a1, p[2] = f->a2, p[3] = f->d3, p[4] = f->a3, p[5] = f->d4, p[6] = f->d6;
    p[7] = f->dOffsetA0, p[8] = f->dOffsetA1, p[9] = f->dOffsetA2, p[10] = f->dOffsetA3, p[11] = f->dOffsetA4, p[12] = f->dOffsetA5;
  } else {
    return nullptr;
  }
  return GroupKinematics::make(spec);
}

void MC_SetKinTransform(sm3::MC_SetKinTransform* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    // Read on the rising edge only; a kinematics with more joints than members is invalid.
    std::shared_ptr<const GroupKinematics> kin;
    if (self->Execute && !fb.execute) {
      kin = kinematicsOf(self->KinTransform);
      if (kin && static_cast<size_t>(kin->joints()) > g.axes().size()) kin.reset();
    }
    callSetKinTransform(k, fb, g, self->Execute, std::move(kin), c);
  });
}

void SMC_SetKinConfiguration(sm3::SMC_SetKinConfiguration* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    const KinConfigData cfg{self->ConfigData.iElbow == 0 ? 1 : self->ConfigData.iElbow, self->ConfigData.iShoulder == 0 ? 1 : self->ConfigData.iShoulder,
                            self->ConfigData.iWrist == 0 ? 1 : self->ConfigData.iWrist};
    callSetKinConfiguration(k, fb, g, self->Execute, cfg, c);
  });
}

void coordArray(const sm3::MC_COORD_REF& r, double* x) {
  x[0] = r.X, x[1] = r.Y, x[2] = r.Z, x[3] = r.A, x[4] = r.B, x[5] = r.C;
}

void MC_SetCoordinateTransform(sm3::MC_SetCoordinateTransform* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    double x[6];
    coordArray(self->CoordTransform, x);
    callSetCoordinateTransform(k, fb, g, self->Execute, x, self->CoordSystem, nullptr, c);
  });
}

void MC_SetDynCoordTransform(sm3::MC_SetDynCoordTransform* self) {
  groupFb(self, [&](Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
    // The master may belong to another task: it is only read (bound without claiming it).
    AxisGroup* master = nullptr;
    if (self->MasterAxisGroup) {
      const uint32_t i = self->MasterAxisGroup->__stcGroup - 1u;
      MotionSession& s = MotionSession::current();
      master = k.group(i);
      if (master && (i >= s.groupVars.size() || s.groupVars[i] != self->MasterAxisGroup)) master = nullptr;
      if (!master) master = bindGroup(self->MasterAxisGroup, c);
    }
    double x[6];
    coordArray(self->CoordTransform, x);
    if (self->Execute && !fb.execute && !master) {
      k.beginExecute(fb, self->Execute, c);
      return k.fail(fb, Error::AgInvalidCoordSystem, c);
    }
    callSetCoordinateTransform(k, fb, g, self->Execute, x, self->CoordSystem, master ? master : &g, c);
  });
}

// Enable FB: converts at every call.
void SMC_GroupConvertPosition(sm3::SMC_GroupConvertPosition* self) {
  self->PositionOut = sm3::SMC_POS_REF{};
  groupReader(self, [&](AxisGroup& g) {
    const Kernel& k = kernel();
    auto fail = [&](Error e) {
      self->PositionOut = sm3::SMC_POS_REF{};
      self->Valid = false;
      self->Error = true;
      self->ErrorID = static_cast<decltype(self->ErrorID)>(smcError(e));
    };
    const int in = self->CoordSystemIn, out = self->CoordSystemOut;
    if (!validCoordSystem(in) || !validCoordSystem(out) || in == 5 || out == 5) return fail(Error::AgInvalidCoordSystem);
    if (!self->PositionIn) return fail(Error::AgInvalidMoveInputs);
    double x[kMaxGroupAxes] = {}, q[kMaxGroupAxes] = {}, r[kMaxGroupAxes] = {}, tool[6] = {};
    const size_t nIn = coordsIn(g, in);
    for (size_t i = 0; i < nIn; ++i) x[i] = static_cast<const sm3::SMC_POS_REF*>(self->PositionIn)->v[i];
    for (size_t i = 0; i < nIn; ++i)
      if (!bounds::position(x[i])) return fail(Error::AgInvalidMoveInputs);
    const double* aRef = &self->aRef.a0;
    for (size_t i = 0; i < g.axes().size(); ++i) r[i] = aRef[i];
    coordArray(self->ToolOffset, tool);
    const bool useTool = self->UseToolOffsetParameter && g.kin;
    Frame toolFrame;
    if (useTool && !Frame::fromCoords(tool, toolFrame)) return fail(Error::AgInvalidMoveInputs);
    // Through ACS: the tool point's coordinates -> the flange's -> joints -> the target system.
    const CoordSystem sIn = static_cast<CoordSystem>(in), sOut = static_cast<CoordSystem>(out);
    if (useTool && sIn != CoordSystem::ACS) {   // tool point -> flange (the flange's orientation is the position's A, B, C)
      Frame pose;
      Frame::fromCoords(x, pose);
      Frame flange = pose * toolFrame.inverse();
      flange.toCoords(x, x + 3);
    }
    const KinConfigData cfg{self->config.iElbow == 0 ? 1 : self->config.iElbow, self->config.iShoulder == 0 ? 1 : self->config.iShoulder,
                            self->config.iWrist == 0 ? 1 : self->config.iWrist};
    if (!jointsOf(k, g, sIn, x, cfg, r, q)) return fail(Error::AgUnreachable);
    double y[kMaxGroupAxes] = {};
    if (!coordsOf(k, g, sOut, q, y)) return fail(Error::AgUnreachable);
    if (useTool && sOut != CoordSystem::ACS) {
      Frame pose;
      Frame::fromCoords(y, pose);
      (pose * toolFrame).toCoords(y, y + 3);
    }
    const size_t nOut = coordsIn(g, out);
    for (size_t i = 0; i < nOut; ++i) self->PositionOut.v[i] = y[i];
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
  STC_SM3_NATIVE(MC_SetKinTransform, MC_SetKinTransform)
  STC_SM3_NATIVE(SMC_SetKinConfiguration, SMC_SetKinConfiguration)
  STC_SM3_NATIVE(MC_SetCoordinateTransform, MC_SetCoordinateTransform)
  STC_SM3_NATIVE(MC_SetDynCoordTransform, MC_SetDynCoordTransform)
  STC_SM3_NATIVE(SMC_GroupConvertPosition, SMC_GroupConvertPosition)
  STC_SM3_NATIVE(SMC_GroupSaveContinueData, SMC_GroupSaveContinueData)
  STC_SM3_NATIVE(SMC_GroupEnableResumeAfterError, SMC_GroupEnableResumeAfterError)
  STC_SM3_NATIVE(SMC_GroupJog, SMC_GroupJog)
}

}  // namespace stc::motion
