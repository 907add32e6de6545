// The axis-group state machine and its administration instructions
// (docs/motion-groups.md, "States").
#include "stdlib-motion/group/AxisGroup.h"

#include <algorithm>

#include "stdlib-motion/core/Kernel.h"
#include "stdlib-motion/group/GroupMotion.h"
#include "stdlib-motion/path/Planner.h"

namespace stc::motion {

AxisGroup::AxisGroup(uint32_t index) : index_(index) {}
AxisGroup::~AxisGroup() = default;

int AxisGroup::identOf(const Axis& ax) const {
  for (size_t i = 0; i < axes_.size(); ++i)
    if (axes_[i] == &ax) return static_cast<int>(i);
  return -1;
}

void AxisGroup::removeAxis(Axis& ax) { axes_.erase(std::remove(axes_.begin(), axes_.end(), &ax), axes_.end()); }

void AxisGroup::enterErrorStop(Error group, Error axis) {
  state_ = GroupState::ErrorStop;
  if (groupError_ == Error::None) groupError_ = group;
  if (axisError_ == Error::None) axisError_ = axis;
}

namespace {

void done(Kernel& k, FbSlot& fb, const CallCtx& c) { k.finish(fb, &c, c.cycle, true, false, Error::None); }

// The group of another enabled group that already holds `ax`, if any.
bool inOtherEnabledGroup(const Kernel& k, const AxisGroup& g, const Axis& ax) {
  for (size_t i = 0; i < k.groupCount(); ++i) {
    const AxisGroup* o = k.group(static_cast<uint32_t>(i));
    if (o && o != &g && o->enabled() && o->identOf(ax) >= 0) return true;
  }
  return false;
}

}  // namespace

void callAddAxisToGroup(Kernel& k, FbSlot& fb, AxisGroup& g, Axis& ax, bool execute, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  if (g.enabled()) return k.fail(fb, Error::AgNotDisabled, c);
  if (g.identOf(ax) >= 0) return k.fail(fb, Error::AgAxisAlreadyInGroup, c);
  if (g.axes().size() >= kMaxGroupAxes) return k.fail(fb, Error::AgTooManyAxes, c);
  g.addAxis(ax);
  g.planner.reset();   // planned for the old members
  g.dropSaved();
  done(k, fb, c);
}

void callRemoveAxisFromGroup(Kernel& k, FbSlot& fb, AxisGroup& g, Axis& ax, bool execute, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  if (g.enabled()) return k.fail(fb, Error::AgNotDisabled, c);
  if (g.identOf(ax) < 0) return k.fail(fb, Error::AgAxisNotInGroup, c);
  g.removeAxis(ax);
  g.planner.reset();
  g.dropSaved();
  done(k, fb, c);
}

void callUngroupAllAxes(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  if (g.enabled()) return k.fail(fb, Error::AgNotDisabled, c);
  g.clearAxes();
  g.planner.reset();
  g.dropSaved();
  done(k, fb, c);
}

namespace {

// MC_GroupEnable's checks: members, their kind, power and rest, other groups.
Error enableRefusal(const Kernel& k, const AxisGroup& g, bool allowPulse) {
  if (g.axes().empty()) return Error::AgNoAxes;
  for (const Axis* ax : g.axes()) {
    const AxisKind kind = ax->config().drive.kind;
    // Servo and virtual (servo) axes only (internal groups: pulse axes too); every member powered and at rest.
    if (kind != AxisKind::Servo && kind != AxisKind::Virtual && !(allowPulse && kind == AxisKind::Pulse)) return Error::AgAxisNotServo;
    if (!ax->ready() || ax->state() != AxisState::Standstill) return Error::AgAxisNotReady;
    if (inOtherEnabledGroup(k, g, *ax)) return Error::AgAxisInOtherGroup;
  }
  return Error::None;
}

}  // namespace

void callGroupEnable(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  if (g.enabled()) return done(k, fb, c);   // already enabled: nothing to do
  if (Error e = enableRefusal(k, g, false); e != Error::None) return k.fail(fb, e, c);
  g.clearErrors();
  for (Limits& a : g.anc) a = Limits{};
  g.ancPath = Limits{};
  g.ancImmediate = ++g.ancSerial;
  g.setState(GroupState::Standby);
  done(k, fb, c);
}

void disableGroup(Kernel& k, AxisGroup& g, const CallCtx& c) {
  abortGroupMotion(k, g, c);
  g.dropSaved();
  g.setState(GroupState::Disabled);
  g.clearErrors();
}

Error enableGroupWith(Kernel& k, AxisGroup& g, const std::vector<Axis*>& axes, bool allowPulse, const CallCtx& c) {
  if (axes.empty() || axes.size() > kMaxGroupAxes) return axes.empty() ? Error::AgNoAxes : Error::AgTooManyAxes;
  // The group starts afresh: enabled (also after its last move, in GroupErrorStop), it is
  // disabled first, its members let go where they stand.
  if (g.enabled()) disableGroup(k, g, c);
  if (g.axes() != axes) {
    g.clearAxes();
    for (Axis* ax : axes) g.addAxis(*ax);
    g.planner.reset();
    g.dropSaved();
  }
  // An idle internal group lets go of its members: all its commands ended (also in the
  // cycle after its last move, before the step returns it to GroupStandby).
  auto idle = [](const AxisGroup& o) {
    const bool standing = o.state() == GroupState::Standby || (o.state() == GroupState::Moving && o.ended);
    return o.internal && standing && !o.pending && !o.active && !o.interrupted && !o.interrupter && !o.pathInterrupted &&
           o.pathCommands.empty() && o.queue.empty();
  };
  for (size_t i = 0; i < k.groupCount(); ++i) {
    AxisGroup* o = k.group(static_cast<uint32_t>(i));
    if (!o || o == &g || !idle(*o)) continue;
    for (Axis* ax : axes)
      if (o->identOf(*ax) >= 0) {
        disableGroup(k, *o, c);
        break;
      }
  }
  if (Error e = enableRefusal(k, g, allowPulse); e != Error::None) return e;
  g.clearErrors();
  g.setState(GroupState::Standby);
  return Error::None;
}

void callGroupDisable(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  disableGroup(k, g, c);
  done(k, fb, c);
}

void callGroupReset(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  if (!g.enabled()) return k.fail(fb, Error::AgNotEnabled, c);
  if (g.state() != GroupState::ErrorStop) return done(k, fb, c);   // no error: nothing to reset
  // Not while the members still brake from the error.
  for (const Axis* ax : g.axes())
    if (ax->set().v != 0 || ax->set().a != 0) return k.fail(fb, Error::AgStillDecelerating, c);
  // The members' errors and faults are reset with the group's (an MC_Reset each).
  for (Axis* ax : g.axes())
    if (ax->state() == AxisState::ErrorStop) {
      ax->clearError();
      ax->setState(ax->operational() ? AxisState::Standstill : AxisState::PowerOff);
    }
  g.clearErrors();
  g.setState(GroupState::Standby);
  done(k, fb, c);
}

void callGroupPower(Kernel& k, FbSlot& fb, AxisGroup& g, uint64_t (&handles)[kMaxGroupAxes], void* instance, bool enable,
                    bool regulatorOn, bool driveStart, const CallCtx& c) {
  fb.execute = enable;
  fb.lastCallCycle = c.cycle;
  auto memberSlot = [&](size_t i) -> FbSlot& { return k.slot(handles[i], instance, FbKind::Power, nullptr); };
  FbOutputs o;
  if (enable) {
    o.status = !g.axes().empty();
    for (size_t i = 0; i < g.axes().size(); ++i) {
      Axis& ax = *g.axes()[i];
      FbSlot& s = memberSlot(i);
      // A slot that powered another axis before a membership change lets go of it.
      if (s.axis && s.axis != &ax && s.axis->power == &s) s.axis->power = nullptr;
      k.callPower(s, ax, true, regulatorOn, driveStart, c);
      o.status = o.status && s.out.status;
      o.busy = true;
      if (s.out.error && !o.error) {
        o.error = true;
        o.errorId = s.out.errorId;
      }
    }
  } else {
    for (size_t i = 0; i < kMaxGroupAxes; ++i)
      if (handles[i]) {
        FbSlot& s = memberSlot(i);
        if (s.axis) k.callPower(s, *s.axis, false, false, false, c);
      }
  }
  fb.out = o;
  fb.sync();
}

}  // namespace stc::motion
