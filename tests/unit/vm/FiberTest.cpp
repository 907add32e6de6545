#include "vm/Fiber.h"

#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

using stc::vm::Fiber;

namespace {

TEST(Fiber, SwitchesBackAndForth) {
  Fiber f;
  std::vector<std::string> log;
  f.start([&] {
    log.push_back("a");
    EXPECT_EQ(Fiber::current(), &f);
    Fiber::suspend();
    log.push_back("b");
    Fiber::suspend();
    log.push_back("c");
  });
  EXPECT_TRUE(f.running());
  EXPECT_EQ(Fiber::current(), nullptr);
  EXPECT_FALSE(f.resume());
  log.push_back("1");
  EXPECT_FALSE(f.resume());
  log.push_back("2");
  EXPECT_TRUE(f.resume());
  EXPECT_FALSE(f.running());
  EXPECT_FALSE(f.abandoned());
  EXPECT_EQ(Fiber::current(), nullptr);
  EXPECT_EQ(log, (std::vector<std::string>{"a", "1", "b", "2", "c"}));
}

TEST(Fiber, StackDataSurvivesSuspension) {
  Fiber f;
  uint64_t sum = 0;
  f.start([&] {
    // Frames below the suspension point keep their data.
    auto nested = [&](auto& self, int depth) -> uint64_t {
      char buf[512];
      std::memset(buf, depth, sizeof buf);
      if (depth < 8) {
        uint64_t below = self(self, depth + 1);
        for (char c : buf)
          if (c != static_cast<char>(depth)) return 0;
        return below + depth;
      }
      Fiber::suspend();
      return 1000;
    };
    sum = nested(nested, 0);
  });
  EXPECT_FALSE(f.resume());
  // Scribble on the caller's stack between the switches.
  volatile char noise[4096];
  for (size_t i = 0; i < sizeof noise; ++i) noise[i] = static_cast<char>(i);
  EXPECT_TRUE(f.resume());
  EXPECT_EQ(sum, 1000u + (0 + 1 + 2 + 3 + 4 + 5 + 6 + 7));
}

TEST(Fiber, AbandonThenRestart) {
  Fiber f;
  int reached = 0;
  f.start([&] {
    reached = 1;
    Fiber::abandon();
    reached = 2;  // never
  });
  EXPECT_TRUE(f.resume());
  EXPECT_EQ(reached, 1);
  EXPECT_FALSE(f.running());
  EXPECT_TRUE(f.abandoned());

  f.start([&] {
    reached = 10;
    Fiber::suspend();
    reached = 11;
  });
  EXPECT_TRUE(f.running());
  EXPECT_FALSE(f.abandoned());
  EXPECT_FALSE(f.resume());
  EXPECT_EQ(reached, 10);
  EXPECT_TRUE(f.resume());
  EXPECT_EQ(reached, 11);
}

TEST(Fiber, RestartWhileSuspendedDropsTheOldRun) {
  Fiber f;
  int runs = 0;
  f.start([&] {
    ++runs;
    Fiber::suspend();
    runs += 100;  // never: the fiber is re-armed while suspended here
  });
  EXPECT_FALSE(f.resume());
  f.start([&] { ++runs; });
  EXPECT_TRUE(f.resume());
  EXPECT_EQ(runs, 2);
}

void rawBody(void* p) {
  ++*static_cast<int*>(p);
  Fiber::suspend();
  ++*static_cast<int*>(p);
}

TEST(Fiber, RawFunctionBody) {
  Fiber f;
  int n = 0;
  for (int round = 0; round < 3; ++round) {
    f.start(&rawBody, &n);
    EXPECT_FALSE(f.resume());
    EXPECT_TRUE(f.resume());
  }
  EXPECT_EQ(n, 6);
}

TEST(Fiber, GuardRangeIsBelowTheStack) {
  Fiber f(64 * 1024);
  auto [guard, guardSize] = f.guardRange();
  auto [stack, stackSize] = f.stackRange();
  EXPECT_NE(guard, nullptr);
  EXPECT_GT(guardSize, 0u);
  EXPECT_EQ(static_cast<const char*>(guard) + guardSize, stack);
  EXPECT_EQ(stackSize, 64u * 1024);

  // The body runs inside the stack range.
  const char* inside = nullptr;
  f.start([&] {
    // Not a local's address: ASan may put locals on a heap "fake stack".
    inside = static_cast<const char*>(__builtin_frame_address(0));
  });
  f.resume();
  EXPECT_GE(inside, static_cast<const char*>(stack));
  EXPECT_LT(inside, static_cast<const char*>(stack) + stackSize);
}

TEST(FiberDeathTest, GuardPageTraps) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Fiber f(64 * 1024);
  auto* guard = static_cast<volatile char*>(const_cast<void*>(f.guardRange().first));
  EXPECT_DEATH(guard[f.guardRange().second - 1] = 1, "");
}

TEST(Fiber, NestedFibers) {
  Fiber outer, inner;
  std::vector<int> log;
  inner.start([&] {
    log.push_back(2);
    EXPECT_EQ(Fiber::current(), &inner);
    Fiber::suspend();
    log.push_back(4);
  });
  outer.start([&] {
    log.push_back(1);
    EXPECT_FALSE(inner.resume());
    EXPECT_EQ(Fiber::current(), &outer);
    log.push_back(3);
    Fiber::suspend();
    EXPECT_TRUE(inner.resume());
    log.push_back(5);
  });
  EXPECT_FALSE(outer.resume());
  EXPECT_TRUE(outer.resume());
  EXPECT_EQ(log, (std::vector<int>{1, 2, 3, 4, 5}));
}

TEST(Fiber, ExceptionIsRethrownByResume) {
  Fiber f;
  f.start([] { throw std::runtime_error("boom"); });
  EXPECT_THROW(f.resume(), std::runtime_error);
  EXPECT_FALSE(f.running());
  f.start([] {});
  EXPECT_TRUE(f.resume());
}

}  // namespace
