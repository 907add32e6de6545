// MC_DigitalCamSwitch: position and time cams on up to 32 output tracks,
// evaluated in the call of the Enable edge and after every kernel step.
// docs/motion-diag.md.
#include <algorithm>
#include <cmath>

#include "stdlib-motion/core/Diag.h"

namespace stc::motion::diag {

namespace {

DigitalCamSwitch* camOf(FbSlot& fb) { return dynamic_cast<DigitalCamSwitch*>(fb.behaviour.get()); }

void stopObserving(Axis& ax, FbSlot& fb) {
  ax.observers.erase(std::remove(ax.observers.begin(), ax.observers.end(), &fb), ax.observers.end());
}

bool negativeOnly(int16_t d) { return d == -1 || d == 2; }

Error validate(const std::vector<CamSwitch>& sw, const TrackOption* opt, const Axis& ax) {
  if (sw.empty()) return Error::None;   // checked by the caller (no switches)
  for (const CamSwitch& s : sw) {
    if (s.track < 1 || s.track > kTracks) return kBadInput;
    if (!std::isfinite(s.first) || (s.mode == 0 && !std::isfinite(s.last))) return kBadInput;
    if (s.direction != 0 && s.direction != 1 && !negativeOnly(s.direction)) return kBadInput;
    if (s.mode != 0 && s.mode != 1) return kBadInput;
    if (s.mode == 1 && s.durationNs <= 0) return kBadInput;
    if (s.mode == 0 && !ax.isModulo() && s.first > s.last) return kBadInput;
  }
  for (int t = 0; t < kTracks; ++t) {
    const TrackOption& o = opt[t];
    if (!std::isfinite(o.onCompensation) || !std::isfinite(o.offCompensation) || !std::isfinite(o.hysteresis) || o.hysteresis < 0)
      return kBadInput;
  }
  return Error::None;
}

}  // namespace

// One evaluation at the axis state of `nowNs`.  `first`: the enabling call (no crossing yet).
void DigitalCamSwitch::evaluate(Axis& ax, int64_t nowNs, bool first) {
  const bool actual = tappet == TappetMode::Actual;
  const double u = actual ? ax.actPosition() : ax.set().p;          // unwrapped
  const double v = actual ? ax.actVelocity() : ax.set().v;
  const double period = ax.isModulo() ? ax.config().period : 0;
  if (first) {
    prevPos = u;
    for (int t = 0; t < kTracks; ++t) {
      turnPos[t] = u;
      dir[t] = v > 0 ? 1 : v < 0 ? -1 : 0;
    }
    timedOffNs.assign(switches.size(), 0);
  }
  // Direction per track: it flips once the axis has moved back from its extreme by more than the hysteresis.
  for (int t = 0; t < kTracks; ++t) {
    const double h = options[t].hysteresis;
    if (dir[t] > 0) {
      if (u > turnPos[t]) turnPos[t] = u;
      else if (u < turnPos[t] - h) { dir[t] = -1; turnPos[t] = u; }
    } else if (dir[t] < 0) {
      if (u < turnPos[t]) turnPos[t] = u;
      else if (u > turnPos[t] + h) { dir[t] = 1; turnPos[t] = u; }
    } else if (u > turnPos[t] + h) { dir[t] = 1; turnPos[t] = u; }
    else if (u < turnPos[t] - h) { dir[t] = -1; turnPos[t] = u; }
  }
  const double from = prevPos;
  bool on[kTracks] = {};
  bool used[kTracks] = {};
  corrupted = -1;
  for (size_t i = 0; i < switches.size(); ++i) {
    const CamSwitch& s = switches[i];
    const int t = s.track - 1;
    used[t] = true;
    const TrackOption& o = options[t];
    const bool dirOk = s.direction == 0 || (s.direction == 1 && dir[t] > 0) || (negativeOnly(s.direction) && dir[t] < 0);
    if (s.mode == 0) {
      // The window in position space, shifted by the compensation times (a negative time switches earlier).
      double last = s.last;
      if (period > 0 && s.first > last) last += period;
      double lo, hi;
      if (v >= 0) { lo = s.first + v * o.onCompensation; hi = last + v * o.offCompensation; }
      else { lo = s.first + v * o.offCompensation; hi = last + v * o.onCompensation; }
      if (lo > hi) {   // the compensations turned the window inside out
        if (corrupted < 0) corrupted = static_cast<int16_t>(i + 1);
        continue;
      }
      bool inside;
      if (period > 0 && hi - lo >= period) inside = true;
      else if (period > 0) {
        double x = std::fmod(u - lo, period);
        if (x < 0) x += period;
        inside = x <= hi - lo;
      } else {
        inside = u >= lo && u <= hi;
      }
      if (inside && dirOk) on[t] = true;
    } else {
      // Time cam: ON when the (compensated) FirstOnPosition is passed, OFF Duration after that instant.
      if (!first && u != from && dirOk) {
        const double x = s.first + v * o.onCompensation;
        double hit = x;
        bool crossed;
        if (u > from) {
          if (period > 0) hit = x + (std::floor((from - x) / period) + 1) * period;
          crossed = hit > from && hit <= u;
        } else {
          if (period > 0) hit = x + (std::ceil((from - x) / period) - 1) * period;
          crossed = hit < from && hit >= u;
        }
        if (crossed) {
          const double after = (u - hit) / (u - from);   // share of the step after the crossing
          const int64_t at = nowNs - static_cast<int64_t>(std::llround(after * static_cast<double>(nowNs - lastNs)));
          timedOffNs[i] = at + s.durationNs;
        }
      }
      if (timedOffNs[i] > nowNs) on[t] = true;
      else timedOffNs[i] = 0;
    }
  }
  prevPos = u;
  lastNs = nowNs;
  if (outputs)
    for (int t = 0; t < kTracks; ++t)
      if (used[t]) outputs[t] = on[t] && ((mask >> t) & 1u);
}

void DigitalCamSwitch::afterStep(Kernel&, FbSlot&, Axis& ax, int64_t nowNs, uint64_t) {
  // (Observers are removed in the next call, never during the kernel's loop over them.)
  if (enabled) evaluate(ax, nowNs, false);
}

CamSwitchOut callDigitalCamSwitch(Kernel& k, FbSlot& fb, Axis& ax, bool enable, const std::vector<CamSwitch>* switches,
                                  const TrackOption* options, bool* outputs, uint32_t mask, TappetMode tappet, const CallCtx& c) {
  (void)k;
  CamSwitchOut o;
  if (!fb.behaviour) fb.behaviour = std::make_unique<DigitalCamSwitch>();
  DigitalCamSwitch& cs = *camOf(fb);
  const bool rising = enable && !fb.execute;
  fb.execute = enable;
  fb.lastCallCycle = c.cycle;
  fb.axis = &ax;
  if (!enable) {
    if (cs.enabled && cs.outputs)
      for (const CamSwitch& s : cs.switches) cs.outputs[s.track - 1] = false;
    cs.enabled = false;
    cs.error = Error::None;
    stopObserving(ax, fb);
    return o;
  }
  if (rising) {
    cs.enabled = false;
    cs.error = Error::None;
    stopObserving(ax, fb);
    if (static_cast<int>(tappet) > 2) cs.error = Error::InvalidTappetMode;
    else if (!switches || switches->empty()) cs.error = Error::CrNoTappetsInCam;
    else if (Error e = validate(*switches, options, ax); e != Error::None) cs.error = e;
    else {
      cs.switches = *switches;
      std::copy(options, options + kTracks, cs.options);
      cs.outputs = outputs;
      cs.tappet = tappet;
      cs.mask = mask;
      cs.enabled = true;
      cs.lastNs = c.nowNs - c.intervalNs;
      ax.observers.push_back(&fb);
      // The axis state the program sees (the latest kernel step).
      cs.evaluate(ax, c.nowNs - c.intervalNs, true);
    }
  }
  if (cs.error != Error::None) {
    o.error = true;
    o.errorId = cs.error;
    return o;
  }
  cs.mask = mask;          // EnableMask is an input: read in every call
  o.inOperation = o.busy = true;
  o.corrupted = cs.corrupted;
  return o;
}

}  // namespace stc::motion::diag
