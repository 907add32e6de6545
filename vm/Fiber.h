// A fiber: an mmap'd stack with a guard page plus a saved machine context.
// Tasks that may suspend (safepoints, blocking natives) run on one, so the
// scheduler can leave them mid-activation and come back at a later slot.
// The context switch is Boost.Context's fcontext (a resume + suspend round
// trip measured about 25 ns here; ucontext would add two system calls); it
// appears in Fiber.cpp only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <utility>

namespace stc::vm {

// Anonymous read-write memory below 4 GiB (the 32-bit address model: JIT
// memory, task stacks), address space only until touched; null if none is left.
void* mapLow(size_t bytes);

class Fiber {
public:
  // lowMemory: the stack lies below 4 GiB (the 32-bit address model).
  explicit Fiber(size_t stackBytes = 1 << 20, bool lowMemory = false);
  ~Fiber();
  Fiber(const Fiber&) = delete;
  Fiber& operator=(const Fiber&) = delete;

  // Arms the fiber: the next resume() runs `body` from the top of the stack.
  // Whatever was left on the stack from an earlier run (abandoned, or still
  // suspended) is dropped without unwinding.
  void start(std::function<void()> body);
  // The same without std::function (no allocation, one indirect call).
  void start(void (*fn)(void*), void* arg);

  // Called from outside: runs until the fiber suspends, returns or abandons.
  // Returns true once the fiber is no longer running (body returned or
  // abandon()), false when it suspended.  A C++ exception escaping the body
  // ends the fiber and is rethrown here.
  bool resume();

  // Called from inside the running fiber: back to whoever resumed it.
  static void suspend();
  // Called from inside: leave for good.  The stack is not unwound, so no
  // frame on it may own resources.  The fiber can be start()ed again.
  [[noreturn]] static void abandon();

  // Started and neither finished nor abandoned.
  bool running() const { return running_; }
  // True if the last run ended through abandon().
  bool abandoned() const { return abandoned_; }
  // The fiber executing on this thread, or null on a normal thread stack.
  static Fiber* current();
  // The PROT_NONE page below the stack (stack overflow detection).
  std::pair<const void*, size_t> guardRange() const { return {map_, guardBytes_}; }
  // The usable stack: [bottom, bottom + size).
  std::pair<const void*, size_t> stackRange() const {
    return {static_cast<char*>(map_) + guardBytes_, stackBytes_};
  }

private:
  friend struct FiberAccess;  // Fiber.cpp: the entry point on the new stack
  enum class Exit : uintptr_t { Suspended, Finished, Abandoned };
  [[noreturn]] void leave(Exit why);

  void* map_ = nullptr;        // guard page + stack
  size_t guardBytes_ = 0;
  size_t stackBytes_ = 0;
  void* ctx_ = nullptr;        // the fiber's saved context while not running
  void* callerCtx_ = nullptr;  // the resumer's context while the fiber runs
  Fiber* prevCurrent_ = nullptr;
  bool running_ = false;
  bool abandoned_ = false;
  void (*fn_)(void*) = nullptr;
  void* arg_ = nullptr;
  std::function<void()> body_;
  std::exception_ptr error_;
  // AddressSanitizer bookkeeping (unused otherwise).
  void* fakeStack_ = nullptr;
  void* callerFakeStack_ = nullptr;
  const void* callerBottom_ = nullptr;
  size_t callerSize_ = 0;
};

}  // namespace stc::vm
