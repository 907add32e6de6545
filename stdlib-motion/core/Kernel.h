// The motion kernel: every simulated axis, every motion FB slot, the
// instruction semantics (what a call of each FB does) and the per-cycle step
// that runs after the programs of the task owning the axes.
//
// One kernel per controller (held by its MotionSession, stdlib-motion/MotionNatives.h).  The vendor
// faces (stdlib-motion/<set>/) are thin: they copy the ST inputs into the
// calls below and the FbOutputs back into the ST instance.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "stdlib-motion/core/Axis.h"
#include "stdlib-motion/core/Fb.h"
#include "stdlib-motion/group/AxisGroup.h"

namespace stc::motion {

// Vendor differences are data (docs/motion.md, "Vendor profiles").
struct VendorProfile {
  // MC_Jog: Busy falls with the jog input (AMC1600C manual) rather than when the axis
  // has stopped (CODESYS SoftMotion, used where a manual is silent).
  bool jogBusyEndsAtRelease = true;
  // Motion commands accepted while the axis is synchronized (aborting the coupling).
  bool movesAbortSynchronized = true;
  // Commands an axis holds behind the running one (SoftMotion: 16; Hollysys FIFOs: 64).
  size_t queueCapacity = 16;
  // The profile of an instruction set by its name: "amc1600c", "leadshine_pmc600"; false if unknown.
  static bool named(std::string_view name, VendorProfile& out);
};

// Where and when an FB is being called.
struct CallCtx {
  uint32_t task = 0;
  uint64_t cycle = 0;          // the task's cycle number (1-based)
  int64_t nowNs = 0;           // simulated time of the cycle
  int64_t intervalNs = 1000000;
};

class Kernel {
public:
  void reset();

  // ---- axes
  Axis& addAxis(const AxisConfig& cfg);
  Axis* axis(uint32_t index) { return index < axes_.size() ? axes_[index].get() : nullptr; }
  size_t axisCount() const { return axes_.size(); }
  // Binds `axis` to the calling task if it has no owner yet; false if another task owns it.
  bool claim(Axis& axis, const CallCtx& c) {   // inline: every FB call claims its axis
    if (axis.task == UINT32_MAX) axis.task = c.task;
    return axis.task == c.task;
  }

  // ---- axis groups (stdlib-motion/group/AxisGroup.h), stepped after their member axes
  AxisGroup& addGroup();
  AxisGroup* group(uint32_t index) { return index < groups_.size() ? groups_[index].get() : nullptr; }
  const AxisGroup* group(uint32_t index) const { return index < groups_.size() ? groups_[index].get() : nullptr; }
  size_t groupCount() const { return groups_.size(); }

  // ---- FB slots: `handle` lives in the ST instance (0 = none yet).
  FbSlot& slot(uint64_t& handle, void* instance, FbKind kind, PublishFn publish) {   // inline fast path: a known instance
    if (handle >= 1 && handle <= slots_.size() && slots_[handle - 1]->instance == instance) return *slots_[handle - 1];
    return newSlot(handle, instance, kind, publish);
  }
  FbSlot& newSlot(uint64_t& handle, void* instance, FbKind kind, PublishFn publish);

  // An FB (by its handle) called with another axis than the one its command runs on:
  // while Busy it reports error 32 and its command ends (the first axis, left without
  // its commanding FB, stops in ErrorStop 32); true then, and the call goes no further.
  bool axisChanged(uint64_t handle, const void* instance, Axis& ax, const CallCtx& c) {
    if (handle - 1 >= slots_.size()) return false;   // no slot yet (handle 0 wraps)
    FbSlot& fb = *slots_[handle - 1];
    if (!fb.axis || fb.axis == &ax || fb.instance != instance) return false;
    return axisChangedSlow(fb, ax, c);
  }

  // ---- instruction semantics (called from the FB bodies)
  void callPower(FbSlot& fb, Axis& ax, bool enable, bool regulatorOn, bool driveStart, const CallCtx& c);
  void callReset(FbSlot& fb, Axis& ax, bool execute, const CallCtx& c);
  void callMove(FbSlot& fb, Axis& ax, bool execute, const MoveInputs& in, const CallCtx& c);
  void callHalt(FbSlot& fb, Axis& ax, bool execute, const MoveInputs& in, const CallCtx& c);
  void callStop(FbSlot& fb, Axis& ax, bool execute, const MoveInputs& in, const CallCtx& c);
  void callJog(FbSlot& fb, Axis& ax, bool forward, bool backward, const MoveInputs& in, const CallCtx& c);
  void callInch(FbSlot& fb, Axis& ax, bool forward, bool backward, const MoveInputs& in, const CallCtx& c);
  void callSetPosition(FbSlot& fb, Axis& ax, bool execute, double position, bool relative, const CallCtx& c);

  // ---- the cycle: steps every axis owned by `task`.
  void cycle(uint32_t task, int64_t nowNs, int64_t intervalNs, uint64_t cycle);

  VendorProfile profile;
  uint64_t callCounter = 0;

  // ---- output rules and command handling, for the instruction modules
  // (homing, profiles, probes ...) that attach an FbBehaviour to their slot.
  bool beginExecute(FbSlot& fb, bool execute, const CallCtx& c);   // true on a rising edge
  // Ends fb's command: Done / CommandAborted / Error e (held or one cycle, per the output rules).
  void finish(FbSlot& fb, const CallCtx* c, uint64_t cycle, bool done, bool aborted, Error e);
  // Stores e as the axis's latest FB error (SMC_ReadFBError); fail() and finish() do it.
  void noteFbError(FbSlot& fb, Error e, int64_t nowNs);
  int64_t stepNowNs() const { return stepNowNs_; }   // time of the latest kernel step
  // Refuses a command: Error with e, nothing started.
  void fail(FbSlot& fb, Error e, const CallCtx& c);
  // The error a motion command gets in the axis's current state (None: may start).
  Error motionStateError(const Axis& ax) const;
  void abortController(Axis& ax, uint64_t cycle, Error e = Error::None);
  // Starts fb now (Aborting) or queues it behind the running command (buffer modes).
  void accept(FbSlot& fb, Axis& ax, const CallCtx& c);
  void startCommand(FbSlot& fb, Axis& ax, int64_t nowNs, double frac);
  void errorStop(Axis& ax, Error e, int64_t nowNs, uint64_t cycle);
  // The command in control ended normally at this cycle: Done, then the next buffered command starts.
  void completeCommand(Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot);

private:
  bool axisChangedSlow(FbSlot& fb, Axis& ax, const CallCtx& c);
  void stepAxis(Axis& ax, int64_t nowNs, double dt, uint64_t cycle);
  void onReached(Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot);
  void updatePower(Axis& ax, int64_t nowNs, uint64_t cycle);
  void completeReset(Axis& ax, uint64_t cycle);
  // MC_Power reports an error when the drive is not enabled this long after the request.
  static constexpr int64_t kPowerTimeoutNs = 1'000'000'000;

  int64_t stepNowNs_ = 0;
  std::vector<std::unique_ptr<Axis>> axes_;
  std::vector<std::unique_ptr<FbSlot>> slots_;
  std::vector<std::unique_ptr<AxisGroup>> groups_;
  std::vector<uint8_t> stepped_;   // cycle(): axes already stepped
  std::vector<Axis*> encoders_;    // encoder axes (their kind is fixed at addAxis), stepped first
  std::vector<Axis*> chain_;       // cycle(): an axis and its not yet stepped masters
};

}  // namespace stc::motion
