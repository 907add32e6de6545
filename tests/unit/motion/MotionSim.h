// A controller stand-in for the kernel tests: one axis, one task, 1 ms
// cycles.  A "cycle" is what the controller does in one task slot: the FB
// calls of the program (k.callXxx(..., s.ctx())), then the kernel step
// (s.endCycle()).
#pragma once

#include <deque>

#include "stdlib-motion/core/Kernel.h"

namespace stc::motion::test {

struct Sim {
  Kernel k;
  uint64_t cycle = 1;            // the scheduler's cycles are 1-based, cycle n at (n-1) ms
  int64_t now = 0;
  static constexpr int64_t kDt = 1'000'000;
  Axis* ax;
  explicit Sim(AxisConfig cfg = {}) {
    k.reset();
    ax = &k.addAxis(cfg);
    ax->task = 0;
  }
  CallCtx ctx() const { return CallCtx{0, cycle, now, kDt}; }
  // Ends the current cycle (kernel step) and starts the next.
  void endCycle() {
    k.cycle(0, now, kDt, cycle);
    ++cycle;
    now += kDt;
  }
  FbSlot& slot(FbKind kind) {
    slots.push_back(0);
    return k.slot(slots.back(), &slots.back(), kind, nullptr);
  }
  std::deque<uint64_t> slots;    // stand-ins for the ST instances (their handles)
  void powerOn(FbSlot& p) {
    k.callPower(p, *ax, true, true, true, ctx());
  }
};

}  // namespace stc::motion::test
