// The deterministic scheduler of the virtual controller (plan §5.2-5.3).
//
// Time is simulated: ticks at T = 0, base, 2*base, ... where base is the gcd
// of the cyclic intervals (1 ms without any).  At each tick the due tasks run
// one *slot* each, in priority order (0 = highest, ties in declaration order):
//   before-callback -> start a new activation if idle, or resume the
//   suspended one -> the task's cycle hooks -> after-callback.
// Execution takes no simulated time; an activation only spans time by
// suspending on its fiber (slice exhausted at a safepoint, sleepFor,
// waitUntil, yield).  Task cycles are 1-based: a task's first slot is cycle 1.
//
// Due: a cyclic task at multiples of its interval; an event task on a rising
// edge, and at every tick while an activation is unfinished; a freewheeling
// task at every tick.  A suspended activation continues at a due slot: after
// a safepoint or yield at the next one, after sleepFor at the first one at or
// after the wake time, after waitUntil at the first one where ready() holds.
// An overrun is a cyclic slot that finds the activation preempted (a
// sleeping or waiting one is not counted).
//
// Watchdog: before a suspended activation continues, its run time is
// now - start - (time spent in sleepFor/waitUntil); reaching the limit faults
// the task ("fault-watchdog", the site of its last safepoint).  A faulted task
// finishes the faulting slot (hooks, after-callback) and has no slots after it.
#pragma once

#include <atomic>
#include <csetjmp>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vm/Time.h"

// The safepoint budget.  Generated code decrements it at loop back-edges and
// calls __stc_safepoint(site) when it reaches zero; the scheduler refills it
// with the task's slice at the start of every slot.
extern "C" int64_t __stc_budget;

namespace stc::vm {

class Fiber;

enum class TaskKind { Cyclic, Event, Freewheeling };

struct TaskConfig {
  std::string name;
  TaskKind kind = TaskKind::Cyclic;
  Time interval = 1'000'000;         // Cyclic: the period (> 0)
  int priority = 0;                  // 0 = highest; ties: declaration order
  // Event: the level of the SINGLE input.  Sampled at every base tick when
  // the scheduler reaches the task in priority order; a rising edge since
  // the previous sample (initially FALSE) starts an activation.
  std::function<bool()> eventInput;
  std::function<void()> entry;       // one activation: the task's programs
  // Run on a Fiber, so safepoints and blocking calls can suspend it.  Only a
  // mayBlock task can be stopped by the watchdog: a direct task is a plain
  // call that nothing can interrupt (the compiler marks every task that
  // contains a loop as mayBlock).
  bool mayBlock = false;
  // Simulated run time of one activation, excluding time waiting in
  // sleepFor/waitUntil; 0 = off.
  Time watchdog = 1'000'000'000;
  int64_t slice = 1'000'000;         // safepoint budget per slot
};

// The ST calls active in a task: generated code writes the call site into
// sites[1 + depth % 64] and increments depth around each call of an ST POU, so
// a fault can name its callers.  One per task; __stc_calls points to the
// running task's.
struct CallChain {
  uint32_t depth = 0;
  uint32_t sites[64] = {};
};

struct FaultInfo {
  uint32_t site = 0;                 // codegen's source-site id, 0 = unknown
  std::string code;                  // "fault-index", "fault-watchdog", ...
  std::string message;
  std::vector<uint32_t> callers = {};   // call sites, innermost first (at most 64)
};

struct TaskStats {
  uint64_t slots = 0;
  uint64_t activations = 0;          // activations started
  uint64_t overruns = 0;             // cyclic slots that found a preempted activation
  uint64_t lostEvents = 0;           // event edges while an activation was unfinished
  int64_t execMinNs = 0, execMaxNs = 0, execTotalNs = 0;  // wall time per slot (measure only)
};

struct HookCtx {
  uint32_t task;
  Time now;
  Time interval;                     // the task's period (base tick if not cyclic)
  uint64_t cycle;                    // the task's slot number, 1-based
};

// cycles: that many slots of the fastest cyclic task, counted from where the
// previous run stopped (the base tick if there is no cyclic task).
// until: run every tick T < until (absolute).  Both: the earlier end wins.
// Neither: run until requestStop().
struct RunLimit {
  std::optional<uint64_t> cycles = std::nullopt;
  std::optional<Time> until = std::nullopt;
};

struct TaskFault {
  uint32_t task;
  uint64_t cycle;
  Time now;
  FaultInfo info;
};

struct SchedulerOptions {
  bool measure = false;              // clock_gettime around each slot
  bool realtime = false;             // sleep until start + T before tick T
  bool lowMemory = false;            // fiber stacks below 4 GiB (the 32-bit address model)
};

class Scheduler {
public:
  explicit Scheduler(SchedulerOptions = {});
  ~Scheduler();
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  // A task activation is executing (generated code or a native it called).
  bool inActivation() const;
  // Configuration: before the first run().
  uint32_t addTask(TaskConfig);
  // Runs after the task's programs in each of its slots, also while its
  // activation is suspended, in registration order.  UINT32_MAX: after the
  // slot of every task.
  void addCycleHook(std::string name, std::function<void(const HookCtx&)>, uint32_t task = UINT32_MAX);
  // The base tick also divides `period` (periodic hooks of natives).
  void addTickPeriod(Time period);
  // Process image copy-in / copy-out around each slot.
  void setSlotCallbacks(std::function<void(uint32_t task)> before, std::function<void(uint32_t task)> after);
  // After all slots of a base tick (trace sampling).
  void setTickCallback(std::function<void(Time now)>);

  // Runs ticks until the limit; a later call continues where this stopped.
  void run(RunLimit);
  // Async-signal-safe: run() returns at the next tick boundary.
  void requestStop() { stop_.store(true, std::memory_order_relaxed); }

  Time now() const { return now_; }            // the current (or last run) tick
  Time baseTick() const;
  Time endTime() const { return next_; }       // the first tick not run
  const std::vector<TaskStats>& stats() const { return stats_; }
  const std::vector<TaskFault>& faults() const { return faults_; }
  const TaskConfig& task(uint32_t i) const;
  size_t taskCount() const;
  bool faulted(uint32_t task) const;

  // From code running inside a task (runtime functions, natives, hooks).
  // The scheduler running on this thread, else null.
  static Scheduler* current();   // inline below: natives ask on every call
  uint32_t currentTask() const { return curTask_; }   // UINT32_MAX outside a slot
  uint64_t currentCycle() const { return curCycle_; } // the current task's cycle, 0 outside a slot
  // The budget ran out: remembers `site` for the watchdog report; on a fiber
  // the activation is suspended until the task's next due slot.  Refills
  // __stc_budget with the slice.
  void safepoint(uint32_t site);
  // Only on a fiber (a direct task faults with "fault-not-suspendable"):
  // suspend; resume in the task's first slot at or after now() + d.
  void sleepFor(Time d);
  // Suspend; `ready` is evaluated in each later slot of the task, the
  // activation resumes in the first one where it is true.
  void waitUntil(std::function<bool()> ready);
  // Give up the rest of this slot; continue at the task's next due slot.
  void yield();
  // Ends the current activation: the task is faulted (a TaskFault is
  // recorded) and never runs again; other tasks go on.  Only inside an
  // activation (aborts the process otherwise).
  [[noreturn]] void fault(FaultInfo);

private:
  struct Task;
  enum class State : uint8_t;
  void prepare();
  void runTicks(Time until);
  void tickLoop(Time until);
  void runSlot(Task& t, bool edge);
  void endSlot(Task& t);
  void execute(Task& t);
  void resume(Task& t);
  Task& activeTask(const char* what);
  Task& suspendableTask(const char* what);
  void suspend(Task& t, State why);
  void recordFault(Task& t, FaultInfo info);

  SchedulerOptions opts_;
  std::vector<std::unique_ptr<Task>> tasks_;
  std::unique_ptr<Fiber> lowStack_;   // the loop's stack in the 32-bit address model
  std::vector<TaskStats> stats_;
  std::vector<TaskFault> faults_;
  struct Hook {
    std::string name;
    std::function<void(const HookCtx&)> fn;
    uint32_t task;
  };
  std::vector<Hook> hooks_;
  std::vector<Time> tickPeriods_;
  std::function<void(uint32_t)> before_, after_;
  std::function<void(Time)> tick_;
  std::vector<uint32_t> order_;      // task indices by priority, then declaration
  bool prepared_ = false;
  Time base_ = 0;
  Time now_ = 0;
  uint64_t curCycle_ = 0;
  Time next_ = 0;
  Time fastest_ = 0;                 // the smallest cyclic interval
  int64_t wallStart_ = 0;            // realtime: CLOCK_MONOTONIC ns of T = 0
  int64_t slotWall_ = 0;             // measure: CLOCK_MONOTONIC ns at the slot start
  size_t pos_ = 0;                   // into order_: the slot in progress at now_
  uint32_t curTask_ = UINT32_MAX;
  std::jmp_buf directExit_;          // fault() from a direct task lands in runTicks
  std::atomic<bool> stop_{false};
};

namespace detail {
inline constinit thread_local Scheduler* tScheduler = nullptr;   // set while a scheduler runs on this thread (no TLS wrapper)
}
inline Scheduler* Scheduler::current() { return detail::tScheduler; }

}  // namespace stc::vm

extern "C" stc::vm::CallChain* __stc_calls;
