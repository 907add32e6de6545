// MC_TouchProbe and MC_AbortTrigger: a position latch armed on a drive touch
// probe channel (home switch / index pulse of the simulated drive, latched at
// the exact crossing position) or on a controller input (the actual position
// of the kernel step that first sees the rising edge).  docs/motion-diag.md.
#include <algorithm>
#include <cmath>

#include "stdlib-motion/core/Diag.h"

namespace stc::motion::diag {

namespace {

TouchProbe* probeOf(const FbSlot& fb) { return dynamic_cast<TouchProbe*>(fb.behaviour.get()); }

void stopObserving(Axis& ax, FbSlot& fb) {
  ax.observers.erase(std::remove(ax.observers.begin(), ax.observers.end(), &fb), ax.observers.end());
}

// The armed probe on `t` (any axis), if there is one.
FbSlot* armedOn(Kernel& k, const TriggerRef& t, Axis*& on) {
  for (size_t i = 0; i < k.axisCount(); ++i) {
    Axis* ax = k.axis(static_cast<uint32_t>(i));
    for (FbSlot* o : ax->observers) {
      TouchProbe* p = probeOf(*o);
      if (p && p->armed && (p->trig.id == t.id || (ax == on && p->sameTrigger(t)))) {
        on = ax;
        return o;
      }
    }
  }
  return nullptr;
}

bool inWindow(const Axis& ax, const ProbeIn& in, double reported) {
  if (!in.windowOnly) return true;
  if (ax.isModulo() && in.first > in.last) return reported >= in.first || reported <= in.last;
  return reported >= in.first && reported <= in.last;
}

void disarm(TouchProbe& p) {
  p.armed = false;
  if (p.trig.active) *p.trig.active = false;
}

}  // namespace

bool TouchProbe::sameTrigger(const TriggerRef& t) const {
  return trig.id == t.id || (trig.fast && t.fast && trig.number == t.number);
}

double recordedPosition(const FbSlot& fb) {
  const TouchProbe* p = probeOf(fb);
  return p ? p->recorded : 0;
}

void callTouchProbe(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const TriggerRef& trig, const ProbeIn& in, const CallCtx& c) {
  const bool rising = k.beginExecute(fb, execute, c);
  if (!fb.behaviour) fb.behaviour = std::make_unique<TouchProbe>();
  TouchProbe& p = *probeOf(fb);
  if (!p.armed && fb.axis) stopObserving(*fb.axis, fb);
  if (!rising || fb.out.busy) return;   // a new edge while armed is ignored
  fb.axis = &ax;
  if (trig.fast && (trig.number < 0 || trig.number > 3)) return k.fail(fb, Error::TpCommError, c);
  if (in.windowOnly && (!std::isfinite(in.first) || !std::isfinite(in.last) || (!ax.isModulo() && in.first > in.last)))
    return k.fail(fb, Error::TpCouldntSetWindow, c);
  if (trig.fast && !ax.drive().communication()) return k.fail(fb, Error::TpCommError, c);
  Axis* on = &ax;
  if (armedOn(k, trig, on)) return k.fail(fb, Error::TpTriggerOccupied, c);
  if (!trig.fast && !trig.input) return k.fail(fb, Error::TpCommError, c);
  p.trig = trig;
  p.in = in;
  p.armed = true;
  p.prevAct = ax.actPosition();
  p.prevInput = trig.input ? *trig.input : false;
  if (p.trig.active) *p.trig.active = true;
  fb.out.busy = true;
  if (std::find(ax.observers.begin(), ax.observers.end(), &fb) == ax.observers.end()) ax.observers.push_back(&fb);
  fb.sync();
}

void TouchProbe::afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t /*nowNs*/, uint64_t cycle) {
  // (Observers are removed in the next call, never during the kernel's loop over them.)
  if (!armed) return;
  if (trig.fast && !ax.drive().communication()) {
    disarm(*this);
    k.finish(fb, nullptr, cycle, false, false, Error::TpCommError);
    return;
  }
  const double from = prevAct, to = ax.actPosition();
  prevAct = to;
  // Candidate latch positions of this step, in the order the axis passed them.
  double cand[2];
  int n = 0;
  if (!trig.fast) {
    const bool cur = *trig.input;
    if (cur && !prevInput) cand[n++] = to;
    prevInput = cur;
  } else if (trig.number <= 1) {
    const DriveConfig& d = ax.drive().config();
    if (d.hasHomeSwitch && from != to) {
      const double lo = d.homeSwitchLow, hi = d.homeSwitchHigh;
      const bool rise = trig.number == 0;
      if (to > from) {
        if (rise && from < lo && lo <= to) cand[n++] = lo;
        if (!rise && from <= hi && hi < to) cand[n++] = hi;
      } else {
        if (rise && to <= hi && hi < from) cand[n++] = hi;
        if (!rise && to < lo && lo <= from) cand[n++] = lo;
      }
    }
  } else {
    double at = 0;
    if (ax.drive().indexPassed(at)) cand[n++] = at;
  }
  for (int i = 0; i < n; ++i) {
    const double r = ax.reportPosition(cand[i]);
    if (!inWindow(ax, in, r)) continue;
    recorded = r;
    disarm(*this);
    k.finish(fb, nullptr, cycle, true, false, Error::None);
    return;
  }
}

void callAbortTrigger(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const TriggerRef& trig, const CallCtx& c) {
  const bool rising = k.beginExecute(fb, execute, c);
  fb.axis = &ax;
  if (!rising) return;
  Axis* on = &ax;
  FbSlot* probe = armedOn(k, trig, on);
  if (!probe) return k.fail(fb, Error::AtTriggerNotOccupied, c);
  disarm(*probeOf(*probe));
  stopObserving(*on, *probe);
  k.finish(*probe, &c, c.cycle, false, true, Error::None);
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

}  // namespace stc::motion::diag
