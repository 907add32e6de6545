#include "vm/Scheduler.h"

#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <stdexcept>

#include "vm/Fiber.h"

extern "C" {
int64_t __stc_budget = 1'000'000;
namespace {
stc::vm::CallChain gOutsideTasks;   // dynamic initialisation, FB_INIT / FB_EXIT
}
stc::vm::CallChain* __stc_calls = &gOutsideTasks;
}

namespace stc::vm {
namespace {
using detail::tScheduler;

int64_t monotonicNs() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t(ts.tv_sec) * kSecond + ts.tv_nsec;
}

[[noreturn]] void misuse(const char* what) {
  std::fprintf(stderr, "stc: internal error: %s\n", what);
  std::abort();
}

}  // namespace

enum class Scheduler::State : uint8_t {
  Idle,       // no activation
  Active,     // executing right now
  Preempted,  // suspended at a safepoint or yield: continues at the next due slot
  Sleeping,   // in sleepFor: continues at the first due slot at or after wakeAt
  Waiting,    // in waitUntil: continues at the first due slot where ready() holds
  Faulted,    // never runs again
};

struct Scheduler::Task {
  TaskConfig cfg;
  uint32_t index = 0;
  State state = State::Idle;
  bool lastLevel = false;      // Event: the previous sample of the input
  Time nextDue = 0;            // Cyclic: the next multiple of the interval
  Time hookInterval = 0;
  uint64_t cycle = 0;          // slots so far
  Time start = 0;              // of the current activation
  Time waited = 0;             // of the current activation, in sleepFor/waitUntil
  Time waitStart = 0;
  Time wakeAt = 0;
  std::function<bool()> ready;
  uint32_t lastSite = 0;       // the last safepoint of the current activation
  CallChain calls;             // the ST calls of the current activation
  std::unique_ptr<Fiber> fiber;
  std::vector<uint32_t> hooks; // into hooks_, in registration order
};

Scheduler::Scheduler(SchedulerOptions opts) : opts_(opts) {}
Scheduler::~Scheduler() = default;

uint32_t Scheduler::addTask(TaskConfig cfg) {
  if (prepared_) throw std::logic_error("Scheduler::addTask after run()");
  if (cfg.kind == TaskKind::Cyclic && cfg.interval <= 0)
    throw std::invalid_argument("task '" + cfg.name + "': the interval must be positive");
  if (!cfg.entry) throw std::invalid_argument("task '" + cfg.name + "' has no entry");
  if (cfg.slice <= 0) cfg.slice = 1;
  auto t = std::make_unique<Task>();
  t->cfg = std::move(cfg);
  t->index = static_cast<uint32_t>(tasks_.size());
  tasks_.push_back(std::move(t));
  stats_.emplace_back();
  return tasks_.back()->index;
}

void Scheduler::addCycleHook(std::string name, std::function<void(const HookCtx&)> fn, uint32_t task) {
  if (prepared_) throw std::logic_error("Scheduler::addCycleHook after run()");
  hooks_.push_back({std::move(name), std::move(fn), task});
}

void Scheduler::addTickPeriod(Time period) {
  if (prepared_) throw std::logic_error("Scheduler::addTickPeriod after run()");
  if (period <= 0) throw std::invalid_argument("tick period must be positive");
  tickPeriods_.push_back(period);
}

void Scheduler::setSlotCallbacks(std::function<void(uint32_t)> before, std::function<void(uint32_t)> after) {
  before_ = std::move(before);
  after_ = std::move(after);
}

void Scheduler::setTickCallback(std::function<void(Time)> fn) { tick_ = std::move(fn); }

Time Scheduler::baseTick() const {
  if (prepared_) return base_;
  Time base = 0;
  for (const auto& t : tasks_)
    if (t->cfg.kind == TaskKind::Cyclic) base = std::gcd(base, t->cfg.interval);
  for (Time p : tickPeriods_) base = std::gcd(base, p);
  return base ? base : kMillisecond;
}

const TaskConfig& Scheduler::task(uint32_t i) const { return tasks_.at(i)->cfg; }
size_t Scheduler::taskCount() const { return tasks_.size(); }
bool Scheduler::faulted(uint32_t i) const { return tasks_.at(i)->state == State::Faulted; }

void Scheduler::prepare() {
  if (prepared_) return;
  base_ = baseTick();
  fastest_ = 0;
  for (const auto& t : tasks_)
    if (t->cfg.kind == TaskKind::Cyclic && (fastest_ == 0 || t->cfg.interval < fastest_))
      fastest_ = t->cfg.interval;
  if (fastest_ == 0) fastest_ = base_;
  for (auto& t : tasks_) {
    t->hookInterval = t->cfg.kind == TaskKind::Cyclic ? t->cfg.interval : base_;
    for (uint32_t h = 0; h < hooks_.size(); ++h)
      if (hooks_[h].task == UINT32_MAX || hooks_[h].task == t->index) t->hooks.push_back(h);
  }
  order_.resize(tasks_.size());
  std::iota(order_.begin(), order_.end(), 0u);
  std::stable_sort(order_.begin(), order_.end(),
                   [&](uint32_t a, uint32_t b) { return tasks_[a]->cfg.priority < tasks_[b]->cfg.priority; });
  prepared_ = true;
}

void Scheduler::run(RunLimit limit) {
  prepare();
  // The last tick must leave room for next_ + base_ without overflow.
  Time until = INT64_MAX - base_;
  if (limit.until) until = std::min(until, *limit.until);
  if (limit.cycles) {
    uint64_t room = static_cast<uint64_t>(until - std::min(until, next_)) / static_cast<uint64_t>(fastest_);
    if (*limit.cycles < room) until = std::min(until, next_ + static_cast<Time>(*limit.cycles) * fastest_);
  }

  struct CurrentGuard {
    Scheduler* prev;
    explicit CurrentGuard(Scheduler* s) : prev(tScheduler) { tScheduler = s; }
    ~CurrentGuard() {
      tScheduler = prev;
      __stc_calls = &gOutsideTasks;   // the tasks' chains are not for code run outside them
    }
  } guard(this);

  if (opts_.realtime) wallStart_ = monotonicNs() - next_;
  if (!opts_.lowMemory) {
    runTicks(until);
    return;
  }
  // The 32-bit address model: the tasks that run as plain calls need a stack
  // below 4 GiB (ADR of a function local), so the whole loop runs on one.
  if (!lowStack_) lowStack_ = std::make_unique<Fiber>(size_t{8} << 20, true);
  struct Args { Scheduler* self; Time until; } args{this, until};
  lowStack_->start([](void* p) { auto* a = static_cast<Args*>(p); a->self->runTicks(a->until); }, &args);
  while (!lowStack_->resume()) {
  }
}

// One slot of a due task.  Inlined into tickLoop: this is the per-cycle path
// of every task.
__attribute__((always_inline)) inline void Scheduler::runSlot(Task& t, bool edge) {
  TaskStats& st = stats_[t.index];
  if (opts_.measure) slotWall_ = monotonicNs();
  curTask_ = t.index;
  curCycle_ = ++t.cycle;
  ++st.slots;
  if (before_) before_(t.index);

  switch (t.state) {
  case State::Idle:
    ++st.activations;
    t.start = now_;
    t.waited = 0;
    t.lastSite = 0;
    t.calls.depth = 0;   // a faulted activation left its chain behind
    execute(t);
    break;
  case State::Preempted:
    if (t.cfg.kind == TaskKind::Cyclic) ++st.overruns;
    if (edge) ++st.lostEvents;
    resume(t);
    break;
  case State::Sleeping:
    if (edge) ++st.lostEvents;
    if (now_ >= t.wakeAt) {
      t.waited += now_ - t.waitStart;
      resume(t);
    }
    break;
  case State::Waiting:
    if (edge) ++st.lostEvents;
    if (t.ready()) {
      t.ready = nullptr;
      t.waited += now_ - t.waitStart;
      resume(t);
    }
    break;
  case State::Active:
  case State::Faulted:
    break;
  }
  endSlot(t);
}

// One _setjmp per run() rather than one per slot (it costs about 5 ns):
// fault() in a direct task _longjmps back here, the faulted slot is finished
// and the loop goes on with the next slot.  _setjmp/_longjmp rather than an
// exception: generated frames have no unwind tables, and _setjmp does not
// save the signal mask (no system call).
__attribute__((noinline)) void Scheduler::runTicks(Time until) {
  if (_setjmp(directExit_) != 0) {
    endSlot(*tasks_[curTask_]);
    ++pos_;
  }
  tickLoop(until);
}

// Separate from runTicks so the hot loop is compiled without the
// pessimisation that a returns-twice call imposes on its function.
__attribute__((noinline)) void Scheduler::tickLoop(Time until) {
  size_t i = pos_;
  for (;;) {
    if (i == 0) {
      if (next_ >= until) return;
      if (opts_.realtime) {
        Time wall = wallStart_ + next_;
        timespec ts{static_cast<time_t>(wall / kSecond), static_cast<long>(wall % kSecond)};
        // A signal (requestStop) interrupts the sleep; the check below sees it.
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR &&
               !stop_.load(std::memory_order_relaxed)) {
        }
      }
      if (stop_.load(std::memory_order_relaxed)) [[unlikely]] {
        stop_.store(false, std::memory_order_relaxed);
        return;
      }
      now_ = next_;
    }
    for (const size_t n = order_.size(); i < n; ++i) {
      Task& t = *tasks_[order_[i]];
      if (t.state == State::Faulted) continue;
      bool edge = false;
      switch (t.cfg.kind) {
      case TaskKind::Cyclic:
        if (now_ != t.nextDue) continue;
        t.nextDue += t.cfg.interval;
        break;
      case TaskKind::Event: {
        bool level = t.cfg.eventInput && t.cfg.eventInput();
        edge = level && !t.lastLevel;
        t.lastLevel = level;
        // An unfinished activation is due at every tick, to be resumed.
        if (!edge && t.state == State::Idle) continue;
        break;
      }
      case TaskKind::Freewheeling:
        break;
      }
      pos_ = i;  // where runTicks goes on if this slot faults
      runSlot(t, edge);
    }
    i = 0;
    pos_ = 0;
    if (tick_) tick_(now_);
    next_ = now_ + base_;
  }
}

// The rest of a slot after the task's programs: hooks, copy-out, statistics.
void Scheduler::endSlot(Task& t) {
  if (!t.hooks.empty()) {
    HookCtx ctx{t.index, now_, t.hookInterval, t.cycle};
    for (uint32_t h : t.hooks) hooks_[h].fn(ctx);
  }
  if (after_) after_(t.index);
  curTask_ = UINT32_MAX;
  curCycle_ = 0;

  if (opts_.measure) {
    TaskStats& st = stats_[t.index];
    int64_t ns = monotonicNs() - slotWall_;
    if (st.slots == 1 || ns < st.execMinNs) st.execMinNs = ns;
    if (ns > st.execMaxNs) st.execMaxNs = ns;
    st.execTotalNs += ns;
  }
}

// Starts a new activation, or continues a suspended one, until it finishes,
// suspends or faults.
void Scheduler::execute(Task& t) {
  t.state = State::Active;
  __stc_budget = t.cfg.slice;
  __stc_calls = &t.calls;
  if (!t.cfg.mayBlock) {
    t.cfg.entry();  // fault() does not return here but to runTicks
    t.state = State::Idle;
    return;
  }
  if (!t.fiber) t.fiber = std::make_unique<Fiber>(size_t{1} << 20, opts_.lowMemory);
  if (!t.fiber->running()) {
    // The fiber runs activation after activation, suspending in between, so
    // a new activation costs two context switches and no stack set-up.
    t.fiber->start(
        [](void* p) {
          Task& task = *static_cast<Task*>(p);
          for (;;) {
            task.cfg.entry();
            task.state = State::Idle;
            Fiber::suspend();
          }
        },
        &t);
  }
  t.fiber->resume();
}

void Scheduler::resume(Task& t) {
  Time ran = now_ - t.start - t.waited;
  if (t.cfg.watchdog > 0 && ran >= t.cfg.watchdog) {
    recordFault(t, {t.lastSite, "fault-watchdog",
                    "watchdog: the activation ran for " + formatIecTime(ran) + " without finishing"});
    return;
  }
  execute(t);
}

void Scheduler::recordFault(Task& t, FaultInfo info) {
  t.state = State::Faulted;
  t.ready = nullptr;
  faults_.push_back({t.index, t.cycle, now_, std::move(info)});
}

bool Scheduler::inActivation() const { return curTask_ < tasks_.size() && tasks_[curTask_]->state == State::Active; }

Scheduler::Task& Scheduler::activeTask(const char* what) {
  if (curTask_ >= tasks_.size() || tasks_[curTask_]->state != State::Active)
    misuse((std::string(what) + " outside a task activation").c_str());
  return *tasks_[curTask_];
}

void Scheduler::safepoint(uint32_t site) {
  if (curTask_ >= tasks_.size()) {
    __stc_budget = 1'000'000;
    return;
  }
  Task& t = *tasks_[curTask_];
  t.lastSite = site;
  if (t.state == State::Active && t.cfg.mayBlock && Fiber::current() == t.fiber.get())
    suspend(t, State::Preempted);
  __stc_budget = t.cfg.slice;
}

Scheduler::Task& Scheduler::suspendableTask(const char* what) {
  Task& t = activeTask(what);
  if (!t.cfg.mayBlock || Fiber::current() != t.fiber.get())
    fault({t.lastSite, "fault-not-suspendable",
           std::string(what) + " in task '" + t.cfg.name + "', which cannot suspend"});
  return t;
}

void Scheduler::suspend(Task& t, State why) {
  t.state = why;
  if (why != State::Preempted) t.waitStart = now_;
  Fiber::suspend();
  // Back in a later slot: the scheduler set state = Active and refilled the budget.
}

void Scheduler::sleepFor(Time d) {
  Task& t = suspendableTask("sleepFor");
  t.wakeAt = d > INT64_MAX - now_ ? INT64_MAX : now_ + std::max<Time>(d, 0);
  suspend(t, State::Sleeping);
}

void Scheduler::waitUntil(std::function<bool()> ready) {
  Task& t = suspendableTask("waitUntil");
  t.ready = std::move(ready);
  suspend(t, State::Waiting);
}

void Scheduler::yield() { suspend(suspendableTask("yield"), State::Preempted); }

void Scheduler::fault(FaultInfo info) {
  Task& t = activeTask("fault");
  // Move the strings out first: the frames below are never unwound.
  recordFault(t, std::move(info));
  if (t.cfg.mayBlock) Fiber::abandon();
  _longjmp(directExit_, 1);
}

}  // namespace stc::vm
