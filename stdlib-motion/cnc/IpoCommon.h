// What the three interpolators (Interpolator, Interpolator2Dir, XInterpolator) share:
// the checks of their settings and of an element before it is run, and H switch points
// placed on the path and fired as the set point passes them (in either direction).
#pragma once

#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/Interpolator.h"

namespace stc::cnc {

// kIpoOk, or the error of unusable settings (cycle, velocity mode, jerk).
inline int16_t checkIpoSettings(const IpoSettings& s) {
  if (!(std::isfinite(s.cycle) && s.cycle > 0 && s.cycle <= 1.0)) return kIpoIpoTimeZero;
  if (s.mode != VelMode::Trapezoid && s.mode != VelMode::Sigmoid && s.mode != VelMode::Quadratic) return kIpoInvalidVelMode;
  if (s.mode != VelMode::Trapezoid && !(std::isfinite(s.jerk) && s.jerk > 0 && s.jerk <= 1e15)) return kIpoJerkNonPositive;
  return kIpoOk;
}

inline bool finitePos(const Pos& p) {
  for (double v : p)
    if (!std::isfinite(v)) return false;
  return true;
}

// kIpoOk, or why a time-based interpolator cannot run the element: positions not finite,
// F not > 0, E / E- not > 0, a dwell time not usable.
inline int16_t checkIpoElement(const Element& e) {
  if ((isMotion(e.type) || e.type == MoveType::InitPos) && (!finitePos(e.start) || !finitePos(e.end))) return kIpoPathExceeded;
  if (isMotion(e.type)) {
    if (!(e.vel > 0) || !std::isfinite(e.vel)) return kIpoVelZero;
    if (!(e.acc > 0 && e.dec > 0) || !std::isfinite(e.acc) || !std::isfinite(e.dec)) return kIpoVelAccDecZero;
  }
  if (e.type == MoveType::Dwell && !(std::isfinite(e.dwell) && e.dwell >= 0)) return kIpoPathExceeded;
  return kIpoOk;
}

// TRUE for the elements the path stops at: M functions not pre-acknowledged, dwells, G92, G75.
inline bool isIpoStop(const Element& e) {
  if (isMotion(e.type)) return false;
  return !(e.type == MoveType::MCommand && (e.marks & MarkMPreAcknowledged));
}

// Shows the M function e (wM, K, L) while the path waits on it; TRUE, with the outputs
// cleared, once it is acknowledged.
inline bool waitOnM(IpoOutput& out, const Element& e, bool acknM) {
  out.m = e.m;
  out.mK = e.k;
  out.mL = e.l;
  if (!acknM) return false;
  out.m = 0;
  out.mK = out.mL = 0;
  return true;
}

// Switch n on (+n) or off (-n) in the outputs (iLastSwitch, dwSwitches bits 0..31).
inline void applySwitch(IpoOutput& out, int16_t sw) {
  out.lastSwitch = sw;
  const int k = sw > 0 ? sw : -sw;
  if (k >= 1 && k <= 32) {
    const uint32_t bit = 1u << (k - 1);
    out.switches = sw > 0 ? (out.switches | bit) : (out.switches & ~bit);
  }
}

// The H switch points of one element at their path positions, in the order the path passes
// them, and how many lie behind the set point.
struct SwitchTrack {
  uint8_t n = 0, fired = 0;
  double way[kMaxSwitches] = {};
  int16_t code[kMaxSwitches] = {};

  // Places e's switches on the element that runs from path position wayStart over len.
  void place(const Element& e, double wayStart, double len) {
    n = fired = 0;
    for (int k = 0; k < e.switchCount && k < kMaxSwitches; ++k) {
      const SwitchPoint& sp = e.switches[k];
      if (sp.sw == 0) continue;
      const double d = sp.relative ? std::clamp(sp.pos, 0.0, 1.0) * len
                                   : sp.pos >= 0 ? std::min(sp.pos, len) : std::max(0.0, len + sp.pos);
      int j = n++;
      while (j > 0 && way[j - 1] > wayStart + d) {
        way[j] = way[j - 1];
        code[j] = code[j - 1];
        --j;
      }
      way[j] = wayStart + d;
      code[j] = sp.sw;
    }
  }
  // Fires the points up to path position `to` (forwards).
  void forwardTo(double to, double tol, IpoOutput& out) {
    while (fired < n && way[fired] <= to + tol) applySwitch(out, code[fired++]);
  }
  // Undoes the points beyond `to` (backwards: H+n clears n, H-n sets it).
  void backTo(double to, double tol, IpoOutput& out) {
    while (fired > 0 && way[fired - 1] > to + tol) applySwitch(out, static_cast<int16_t>(-code[--fired]));
  }
};

// Moves the switches of items from path position `from` to `to` (at(i) has .track, .wayStart,
// .wayEnd, in path order): forwards the items first..count-1 (those before `first` lie wholly
// behind `from`), backwards from the last item down to 0.
template <class At>
void moveSwitches(int first, int count, At at, double from, double to, IpoOutput& out) {
  if (to == from) return;
  const double tol = 1e-9 * std::max(1.0, std::fabs(to));
  if (to > from) {
    for (int i = std::max(first, 0); i < count; ++i) {
      auto& it = at(i);
      if (it.wayStart > to + tol) break;
      it.track.forwardTo(to, tol, out);
    }
  } else {
    for (int i = std::min(first, count - 1); i >= 0; --i) {
      auto& it = at(i);
      if (it.wayEnd < to - tol) break;
      it.track.backTo(to, tol, out);
    }
  }
}

}  // namespace stc::cnc
