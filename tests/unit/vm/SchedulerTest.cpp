#include "vm/Scheduler.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

using namespace stc::vm;

namespace {

constexpr Time ms = kMillisecond;

TaskConfig cyclic(std::string name, Time interval, std::function<void()> entry, int priority = 0) {
  TaskConfig c;
  c.name = std::move(name);
  c.interval = interval;
  c.priority = priority;
  c.entry = std::move(entry);
  return c;
}

// Spins on the safepoint budget like a generated WHILE loop.
void spin(Scheduler& s, uint32_t site, int iterations) {
  for (int i = 0; i < iterations; ++i)
    if (--__stc_budget <= 0) s.safepoint(site);
}

TEST(Scheduler, TwoCyclicTasksCount) {
  Scheduler s;
  int fast = 0, slow = 0;
  s.addTask(cyclic("Fast", 1 * ms, [&] { ++fast; }));
  s.addTask(cyclic("Slow", 10 * ms, [&] { ++slow; }));
  EXPECT_EQ(s.baseTick(), 1 * ms);
  s.run({.until = 100 * ms});
  EXPECT_EQ(fast, 100);
  EXPECT_EQ(slow, 10);
  EXPECT_EQ(s.endTime(), 100 * ms);
  EXPECT_EQ(s.now(), 99 * ms);
  EXPECT_EQ(s.stats()[0].slots, 100u);
  EXPECT_EQ(s.stats()[0].activations, 100u);
  EXPECT_EQ(s.stats()[1].slots, 10u);
  EXPECT_EQ(s.stats()[1].overruns, 0u);
  EXPECT_EQ(s.stats()[1].execMaxNs, 0);  // measure is off
  EXPECT_TRUE(s.faults().empty());
}

TEST(Scheduler, BaseTickIsTheGcd) {
  Scheduler s;
  s.addTask(cyclic("A", 4 * ms, [] {}));
  s.addTask(cyclic("B", 6 * ms, [] {}));
  EXPECT_EQ(s.baseTick(), 2 * ms);
  s.addTickPeriod(500 * kMicrosecond);
  EXPECT_EQ(s.baseTick(), 500 * kMicrosecond);
  Scheduler none;
  EXPECT_EQ(none.baseTick(), 1 * ms);
}

TEST(Scheduler, PriorityThenDeclarationOrder) {
  Scheduler s;
  std::vector<std::string> log;
  auto logger = [&](const char* n) { return [&log, &s, n] { log.push_back(n + ("@" + std::to_string(s.now() / ms))); }; };
  s.addTask(cyclic("A", 1 * ms, logger("A"), 2));
  s.addTask(cyclic("B", 2 * ms, logger("B"), 1));
  s.addTask(cyclic("C", 1 * ms, logger("C"), 1));
  s.addTask(cyclic("D", 2 * ms, logger("D"), 0));
  s.run({.until = 3 * ms});
  EXPECT_EQ(log, (std::vector<std::string>{"D@0", "B@0", "C@0", "A@0", "C@1", "A@1", "D@2", "B@2", "C@2", "A@2"}));
}

TEST(Scheduler, CurrentTaskAndCycleAreOneBased) {
  Scheduler s;
  std::vector<std::string> log;
  EXPECT_EQ(Scheduler::current(), nullptr);
  TaskConfig a = cyclic("A", 2 * ms, [&] {
    EXPECT_EQ(Scheduler::current(), &s);
    EXPECT_EQ(__stc_budget, 123);  // refilled with the task's slice
    log.push_back("A" + std::to_string(s.currentTask()) + "c" + std::to_string(s.currentCycle()));
  });
  a.slice = 123;
  s.addTask(a);
  s.addTask(cyclic("B", 1 * ms, [&] {
    log.push_back("B" + std::to_string(s.currentTask()) + "c" + std::to_string(s.currentCycle()));
  }, 1));
  s.addCycleHook("h", [&](const HookCtx& c) {
    log.push_back("h" + std::to_string(c.task) + "c" + std::to_string(c.cycle) + "i" + std::to_string(c.interval / ms));
  });
  s.run({.until = 3 * ms});
  EXPECT_EQ(Scheduler::current(), nullptr);
  EXPECT_EQ(s.currentTask(), UINT32_MAX);
  EXPECT_EQ(log, (std::vector<std::string>{"A0c1", "h0c1i2", "B1c1", "h1c1i1", "B1c2", "h1c2i1", "A0c2", "h0c2i2",
                                           "B1c3", "h1c3i1"}));
}

TEST(Scheduler, CallbacksAroundEachSlotAndTick) {
  Scheduler s;
  std::vector<std::string> log;
  uint32_t a = s.addTask(cyclic("A", 1 * ms, [&] { log.push_back("runA"); }));
  uint32_t b = s.addTask(cyclic("B", 2 * ms, [&] { log.push_back("runB"); }, 1));
  s.addCycleHook("onlyB", [&](const HookCtx&) { log.push_back("hookB"); }, b);
  s.addCycleHook("all", [&](const HookCtx& c) { log.push_back("hookAll" + std::to_string(c.task)); });
  s.addCycleHook("onlyA", [&](const HookCtx&) { log.push_back("hookA"); }, a);
  s.setSlotCallbacks([&](uint32_t t) { log.push_back("in" + std::to_string(t)); },
                     [&](uint32_t t) { log.push_back("out" + std::to_string(t)); });
  s.setTickCallback([&](Time t) { log.push_back("tick" + std::to_string(t / ms)); });
  s.run({.until = 2 * ms});
  EXPECT_EQ(log, (std::vector<std::string>{"in0", "runA", "hookAll0", "hookA", "out0",
                                           "in1", "runB", "hookB", "hookAll1", "out1", "tick0",
                                           "in0", "runA", "hookAll0", "hookA", "out0", "tick1"}));
}

TEST(Scheduler, EventTaskRunsOncePerRisingEdge) {
  Scheduler s;
  bool level = false;
  std::vector<Time> runs;
  // The 1 ms task's hook drives the input: high at k = 1, 2, 6, 7, 11, 12, ...
  uint32_t clock = s.addTask(cyclic("Clock", 1 * ms, [] {}));
  s.addCycleHook("drive", [&](const HookCtx& c) { level = (c.now / ms) % 5 == 1 || (c.now / ms) % 5 == 2; }, clock);
  TaskConfig ev;
  ev.name = "Ev";
  ev.kind = TaskKind::Event;
  ev.priority = 1;  // sampled after Clock's hook in the same tick
  ev.eventInput = [&] { return level; };
  ev.entry = [&] { runs.push_back(s.now()); };
  uint32_t e = s.addTask(ev);
  s.run({.until = 20 * ms});
  EXPECT_EQ(runs, (std::vector<Time>{1 * ms, 6 * ms, 11 * ms, 16 * ms}));
  EXPECT_EQ(s.stats()[e].slots, 4u);
  EXPECT_EQ(s.stats()[e].activations, 4u);
  EXPECT_EQ(s.stats()[e].lostEvents, 0u);
}

TEST(Scheduler, EventInputHighAtStartIsAnEdge) {
  Scheduler s;
  int runs = 0;
  TaskConfig ev;
  ev.kind = TaskKind::Event;
  ev.eventInput = [] { return true; };
  ev.entry = [&] { ++runs; };
  s.addTask(ev);
  s.run({.until = 10 * ms});
  EXPECT_EQ(runs, 1);
}

TEST(Scheduler, EventEdgesWhileUnfinishedAreLost) {
  Scheduler s;
  std::vector<Time> starts;
  TaskConfig ev;
  ev.name = "Ev";
  ev.kind = TaskKind::Event;
  ev.mayBlock = true;
  ev.eventInput = [&] { return (s.now() / ms) % 2 == 0; };  // edges at every even ms
  ev.entry = [&] {
    starts.push_back(s.now());
    s.yield();
    s.yield();  // three slots per activation; resumed at every tick
  };
  s.addTask(ev);
  s.run({.until = 12 * ms});
  EXPECT_EQ(starts, (std::vector<Time>{0, 4 * ms, 8 * ms}));
  EXPECT_EQ(s.stats()[0].slots, 9u);
  EXPECT_EQ(s.stats()[0].activations, 3u);
  EXPECT_EQ(s.stats()[0].lostEvents, 3u);  // at 2, 6 and 10 ms
  EXPECT_EQ(s.stats()[0].overruns, 0u);
}

TEST(Scheduler, FreewheelingRunsEveryBaseTick) {
  {
    Scheduler s;
    TaskConfig fw;
    fw.kind = TaskKind::Freewheeling;
    int n = 0;
    fw.entry = [&] { ++n; };
    s.addTask(fw);
    s.run({.until = 10 * ms});
    EXPECT_EQ(n, 10);
  }
  {
    Scheduler s;
    TaskConfig fw;
    fw.kind = TaskKind::Freewheeling;
    fw.priority = 5;
    std::vector<Time> at;
    fw.entry = [&] { at.push_back(s.now()); };
    s.addTask(cyclic("C", 5 * ms, [] {}));
    s.addTask(fw);
    s.run({.until = 20 * ms});
    EXPECT_EQ(at, (std::vector<Time>{0, 5 * ms, 10 * ms, 15 * ms}));
  }
}

TEST(Scheduler, SleepForResumesAtExactTime) {
  Scheduler s;
  int counter = 0;
  std::vector<std::pair<Time, int>> seen;
  s.addTask(cyclic("Count", 1 * ms, [&] { ++counter; }));
  TaskConfig sl = cyclic("Sleeper", 1 * ms, [&] {
    seen.push_back({s.now(), counter});
    s.sleepFor(500 * ms);
    seen.push_back({s.now(), counter});
  }, 1);
  sl.mayBlock = true;
  sl.watchdog = 100 * ms;  // sleeping does not count
  uint32_t t = s.addTask(sl);
  s.run({.until = 1000 * ms});
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], (std::pair<Time, int>{0, 1}));
  EXPECT_EQ(seen[1], (std::pair<Time, int>{500 * ms, 501}));
  EXPECT_EQ(seen[2], (std::pair<Time, int>{501 * ms, 502}));  // the next activation, asleep until 1001 ms
  EXPECT_EQ(s.stats()[t].slots, 1000u);
  EXPECT_EQ(s.stats()[t].activations, 2u);
  EXPECT_EQ(s.stats()[t].overruns, 0u);
  EXPECT_TRUE(s.faults().empty());
}

TEST(Scheduler, SleepResumesAtTheNextDueSlotOfTheTask) {
  Scheduler s;
  std::vector<Time> at;
  TaskConfig t = cyclic("T", 10 * ms, [&] {
    at.push_back(s.now());
    s.sleepFor(15 * ms);
    at.push_back(s.now());
  });
  t.mayBlock = true;
  s.addTask(t);
  s.run({.until = 30 * ms});
  EXPECT_EQ(at, (std::vector<Time>{0, 20 * ms}));
}

TEST(Scheduler, WaitUntilFlagSetByHook) {
  Scheduler s;
  bool flag = false;
  std::vector<Time> at;
  int waiterHooks = 0;
  uint32_t c = s.addTask(cyclic("Setter", 1 * ms, [] {}));
  s.addCycleHook("set", [&](const HookCtx& h) { if (h.cycle == 7) flag = true; }, c);
  TaskConfig w = cyclic("Waiter", 1 * ms, [&] {
    at.push_back(s.now());
    s.waitUntil([&] { return flag; });
    at.push_back(s.now());
    flag = false;
  }, 1);
  w.mayBlock = true;
  w.watchdog = 1 * ms;
  uint32_t wi = s.addTask(w);
  s.addCycleHook("count", [&](const HookCtx&) { ++waiterHooks; }, wi);
  s.run({.until = 10 * ms});
  EXPECT_EQ(at, (std::vector<Time>{0, 6 * ms, 7 * ms}));  // cycle 7 of Setter is T = 6 ms
  EXPECT_EQ(waiterHooks, 10);  // hooks run while the activation waits
  EXPECT_TRUE(s.faults().empty());
}

TEST(Scheduler, WatchdogStopsALoopingTask) {
  Scheduler s;
  int counter = 0;
  bool after = false;
  s.addTask(cyclic("Count", 1 * ms, [&] { ++counter; }));
  TaskConfig loop = cyclic("Loop", 1 * ms, [&] {
    for (;;)
      if (--__stc_budget <= 0) s.safepoint(7);
    after = true;
  }, 1);
  loop.mayBlock = true;
  loop.slice = 1000;
  loop.watchdog = 50 * ms;
  uint32_t l = s.addTask(loop);
  s.run({.until = 100 * ms});
  EXPECT_EQ(counter, 100);
  EXPECT_FALSE(after);
  ASSERT_EQ(s.faults().size(), 1u);
  const TaskFault& f = s.faults()[0];
  EXPECT_EQ(f.task, l);
  EXPECT_EQ(f.cycle, 51u);
  EXPECT_EQ(f.now, 50 * ms);
  EXPECT_EQ(f.info.site, 7u);
  EXPECT_EQ(f.info.code, "fault-watchdog");
  EXPECT_EQ(f.info.message, "watchdog: the activation ran for T#50ms without finishing");
  EXPECT_TRUE(s.faulted(l));
  EXPECT_EQ(s.stats()[l].slots, 51u);
  EXPECT_EQ(s.stats()[l].activations, 1u);
  EXPECT_EQ(s.stats()[l].overruns, 50u);
}

TEST(Scheduler, OverrunsAreCounted) {
  Scheduler s;
  std::vector<Time> finished;
  TaskConfig t = cyclic("T", 10 * ms, [&] {
    spin(s, 1, 250);  // slice 100: suspends twice, ends in the third slot
    finished.push_back(s.now());
  });
  t.mayBlock = true;
  t.slice = 100;
  s.addTask(t);
  s.run({.until = 100 * ms});
  EXPECT_EQ(finished, (std::vector<Time>{20 * ms, 50 * ms, 80 * ms}));
  EXPECT_EQ(s.stats()[0].slots, 10u);
  EXPECT_EQ(s.stats()[0].activations, 4u);
  EXPECT_EQ(s.stats()[0].overruns, 6u);
  EXPECT_TRUE(s.faults().empty());
}

TEST(Scheduler, DirectTaskSafepointOnlyRefills) {
  Scheduler s;
  int done = 0;
  TaskConfig t = cyclic("T", 1 * ms, [&] {
    spin(s, 3, 1000);  // slice 10: a hundred safepoints, no suspension
    EXPECT_EQ(s.currentCycle(), static_cast<uint64_t>(++done));
  });
  t.slice = 10;
  s.addTask(t);
  s.run({.until = 5 * ms});
  EXPECT_EQ(done, 5);
  EXPECT_EQ(s.stats()[0].overruns, 0u);
}

TEST(Scheduler, FaultFromDirectTask) {
  Scheduler s;
  int counter = 0, runs = 0;
  bool after = false;
  uint32_t bad = s.addTask(cyclic("Bad", 1 * ms, [&] {
    ++runs;
    if (s.currentCycle() == 3) {
      s.fault({42, "fault-index", "index 11 is outside 1..10 of 'buf'"});
      after = true;
    }
  }));
  s.addTask(cyclic("Good", 1 * ms, [&] { ++counter; }, 1));
  s.run({.until = 10 * ms});
  EXPECT_FALSE(after);
  EXPECT_EQ(runs, 3);
  EXPECT_EQ(counter, 10);
  ASSERT_EQ(s.faults().size(), 1u);
  EXPECT_EQ(s.faults()[0].task, bad);
  EXPECT_EQ(s.faults()[0].cycle, 3u);
  EXPECT_EQ(s.faults()[0].now, 2 * ms);
  EXPECT_EQ(s.faults()[0].info.site, 42u);
  EXPECT_EQ(s.faults()[0].info.code, "fault-index");
  EXPECT_EQ(s.faults()[0].info.message, "index 11 is outside 1..10 of 'buf'");
  EXPECT_EQ(s.stats()[bad].slots, 3u);
}

TEST(Scheduler, FaultFromFiberTask) {
  Scheduler s;
  int counter = 0, badHooks = 0;
  bool after = false;
  TaskConfig t = cyclic("Bad", 2 * ms, [&] {
    s.yield();
    s.fault({9, "fault-div-zero", "division by zero"});
    after = true;
  });
  t.mayBlock = true;
  uint32_t bad = s.addTask(t);
  s.addCycleHook("h", [&](const HookCtx&) { ++badHooks; }, bad);
  s.addTask(cyclic("Good", 1 * ms, [&] { ++counter; }));
  s.run({.until = 10 * ms});
  EXPECT_FALSE(after);
  EXPECT_EQ(counter, 10);
  ASSERT_EQ(s.faults().size(), 1u);
  EXPECT_EQ(s.faults()[0].task, bad);
  EXPECT_EQ(s.faults()[0].cycle, 2u);
  EXPECT_EQ(s.faults()[0].now, 2 * ms);
  EXPECT_EQ(s.faults()[0].info.code, "fault-div-zero");
  EXPECT_EQ(s.stats()[bad].slots, 2u);
  EXPECT_EQ(badHooks, 2);  // the faulting slot still runs its hooks
}

TEST(Scheduler, BlockingCallInDirectTaskFaults) {
  Scheduler s;
  bool after = false;
  s.addTask(cyclic("Direct", 1 * ms, [&] {
    s.sleepFor(5 * ms);
    after = true;
  }));
  s.run({.until = 3 * ms});
  EXPECT_FALSE(after);
  ASSERT_EQ(s.faults().size(), 1u);
  EXPECT_EQ(s.faults()[0].info.code, "fault-not-suspendable");
  EXPECT_EQ(s.faults()[0].cycle, 1u);
}

TEST(Scheduler, CyclesLimitCountsTheFastestTask) {
  Scheduler s;
  int a = 0, b = 0;
  s.addTask(cyclic("A", 5 * ms, [&] { ++a; }));
  s.addTask(cyclic("B", 2 * ms, [&] { ++b; }));
  s.run({.cycles = 10});
  EXPECT_EQ(s.endTime(), 20 * ms);
  EXPECT_EQ(b, 10);
  EXPECT_EQ(a, 4);
  s.run({.cycles = 5});  // counted from where the last run stopped
  EXPECT_EQ(s.endTime(), 30 * ms);
  EXPECT_EQ(b, 15);
  EXPECT_EQ(a, 6);
  s.run({.cycles = 100, .until = 34 * ms});  // the earlier end wins
  EXPECT_EQ(s.endTime(), 34 * ms);
  s.run({.cycles = 0});
  EXPECT_EQ(s.endTime(), 34 * ms);
  EXPECT_EQ(b, 17);
}

// A mix of everything, logging each slot; used for continuation and determinism.
struct Mix {
  Scheduler s;
  std::vector<std::string> log;
  bool level = false;
  explicit Mix() {
    auto note = [this](const char* what) {
      log.push_back(std::string(what) + " t" + std::to_string(s.currentTask()) + " c" +
                    std::to_string(s.currentCycle()) + " @" + std::to_string(s.now()));
    };
    uint32_t fast = s.addTask(cyclic("Fast", 1 * ms, [note] { note("fast"); }, 1));
    s.addCycleHook("edge", [this](const HookCtx& c) { level = (c.cycle / 3) % 2 == 1; }, fast);
    TaskConfig slow = cyclic("Slow", 4 * ms, [this, note] {
      note("slow-start");
      spin(s, 5, 250);
      note("slow-mid");
      s.sleepFor(7 * ms);
      note("slow-end");
    }, 2);
    slow.mayBlock = true;
    slow.slice = 100;
    s.addTask(slow);
    TaskConfig ev;
    ev.name = "Ev";
    ev.kind = TaskKind::Event;
    ev.mayBlock = true;
    ev.eventInput = [this] { return level; };
    ev.entry = [this, note] {
      note("ev-start");
      s.yield();
      note("ev-end");
    };
    s.addTask(ev);
    s.setTickCallback([this](Time t) { log.push_back("tick " + std::to_string(t)); });
  }
};

TEST(Scheduler, ContinuedRunEqualsOneRun) {
  Mix once, parts;
  once.s.run({.until = 60 * ms});
  parts.s.run({.until = 13 * ms});
  parts.s.run({.cycles = 20});
  EXPECT_EQ(parts.s.endTime(), 33 * ms);
  parts.s.run({.until = 60 * ms});
  EXPECT_EQ(once.log, parts.log);
  EXPECT_GT(once.log.size(), 100u);
  for (size_t i = 0; i < once.s.taskCount(); ++i) {
    EXPECT_EQ(once.s.stats()[i].slots, parts.s.stats()[i].slots);
    EXPECT_EQ(once.s.stats()[i].activations, parts.s.stats()[i].activations);
    EXPECT_EQ(once.s.stats()[i].overruns, parts.s.stats()[i].overruns);
    EXPECT_EQ(once.s.stats()[i].lostEvents, parts.s.stats()[i].lostEvents);
  }
}

TEST(Scheduler, Deterministic) {
  Mix a, b;
  a.s.run({.until = 200 * ms});
  b.s.run({.until = 200 * ms});
  EXPECT_EQ(a.log, b.log);
  // The mix really exercises suspension and events.
  EXPECT_GT(a.s.stats()[1].overruns, 0u);
  EXPECT_GT(a.s.stats()[2].activations, 10u);
}

TEST(Scheduler, RequestStopEndsAtTheTickBoundary) {
  Scheduler s;
  int n = 0;
  s.addTask(cyclic("A", 1 * ms, [&] {
    if (++n == 6) s.requestStop();
  }));
  s.addTask(cyclic("B", 1 * ms, [] {}, 1));
  s.run({});  // no limit: only the stop request ends it
  EXPECT_EQ(n, 6);
  EXPECT_EQ(s.endTime(), 6 * ms);
  EXPECT_EQ(s.stats()[1].slots, 6u);  // the tick in progress completes
  s.run({.until = 10 * ms});          // the request was consumed
  EXPECT_EQ(n, 10);
  s.requestStop();
  s.run({.until = 20 * ms});          // requested before: no tick runs
  EXPECT_EQ(n, 10);
  EXPECT_EQ(s.endTime(), 10 * ms);
}

TEST(Scheduler, MeasureRecordsWallTime) {
  Scheduler s({.measure = true});
  s.addTask(cyclic("A", 1 * ms, [] {
    volatile int x = 0;
    for (int i = 0; i < 1000; ++i) x = x + i;
  }));
  s.run({.until = 20 * ms});
  const TaskStats& st = s.stats()[0];
  EXPECT_GT(st.execMinNs, 0);
  EXPECT_LE(st.execMinNs, st.execMaxNs);
  EXPECT_GE(st.execTotalNs, 20 * st.execMinNs);
  EXPECT_LE(st.execTotalNs, 20 * st.execMaxNs);
}

TEST(Scheduler, RealtimeFollowsTheWallClock) {
  Scheduler s({.realtime = true});
  int n = 0;
  s.addTask(cyclic("A", 2 * ms, [&] { ++n; }));
  auto t0 = std::chrono::steady_clock::now();
  s.run({.until = 20 * ms});
  auto took = std::chrono::steady_clock::now() - t0;
  EXPECT_EQ(n, 10);
  EXPECT_GE(took, std::chrono::milliseconds(18));  // the last tick starts at 18 ms
}

}  // namespace
