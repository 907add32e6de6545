#include "vm/Fiber.h"

#include <sys/mman.h>
#include <unistd.h>

#include <boost/context/detail/fcontext.hpp>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <system_error>

#if defined(__SANITIZE_ADDRESS__)
#define STC_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define STC_ASAN 1
#endif
#endif
#ifdef STC_ASAN
#include <sanitizer/asan_interface.h>
#include <sanitizer/common_interface_defs.h>
#endif

namespace fctx = boost::context::detail;

namespace stc::vm {
namespace {

thread_local Fiber* tCurrent = nullptr;

// ASan keeps a shadow of each stack; it must be told about every switch or
// it reports false stack-buffer errors.  `save` == null means the stack being
// left is dead (its fake frames can be freed).
inline void startSwitch(void** save, const void* bottom, size_t size) {
#ifdef STC_ASAN
  __sanitizer_start_switch_fiber(save, bottom, size);
#endif
}

inline void finishSwitch(void* save, const void** oldBottom, size_t* oldSize) {
#ifdef STC_ASAN
  __sanitizer_finish_switch_fiber(save, oldBottom, oldSize);
#endif
}

[[noreturn]] void die(const char* what) {
  std::fprintf(stderr, "stc: internal error: %s\n", what);
  std::abort();
}

}  // namespace

struct FiberAccess {
  // First code on a fresh stack.  `t.fctx` is the resumer's context.
  static void trampoline(fctx::transfer_t t) {
    Fiber* f = static_cast<Fiber*>(t.data);
    f->callerCtx_ = t.fctx;
    finishSwitch(nullptr, &f->callerBottom_, &f->callerSize_);
    try {
      if (f->fn_)
        f->fn_(f->arg_);
      else
        f->body_();
    } catch (...) {
      // Never unwind past the trampoline: there is no frame to return to.
      f->error_ = std::current_exception();
    }
    f->leave(Fiber::Exit::Finished);
  }
};

void* mapLow(size_t bytes) {
#ifdef MAP_32BIT
  void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_32BIT | MAP_NORESERVE, -1, 0);
#else
  // Without MAP_32BIT: ask for an address below 4 GiB and check what came back.
  void* p = mmap(reinterpret_cast<void*>(uintptr_t{0x10000000}), bytes, PROT_READ | PROT_WRITE,
                 MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
#endif
  if (p == MAP_FAILED) return nullptr;
  if (reinterpret_cast<uintptr_t>(p) + bytes > (uintptr_t{1} << 32)) {
    munmap(p, bytes);
    return nullptr;
  }
  return p;
}

Fiber::Fiber(size_t stackBytes, bool lowMemory) {
  size_t page = static_cast<size_t>(sysconf(_SC_PAGESIZE));
  guardBytes_ = page;
  stackBytes_ = (stackBytes + page - 1) / page * page;
  if (stackBytes_ == 0) stackBytes_ = page;
  // NORESERVE: a 1 MiB stack costs only the pages a task really touches.
  void* p = lowMemory ? mapLow(guardBytes_ + stackBytes_)
                      : mmap(nullptr, guardBytes_ + stackBytes_, PROT_READ | PROT_WRITE,
                             MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE | MAP_STACK, -1, 0);
  if (p == MAP_FAILED || !p) throw std::system_error(lowMemory ? ENOMEM : errno, std::generic_category(), "fiber stack");
  map_ = p;
  if (mprotect(map_, guardBytes_, PROT_NONE) != 0) {
    int e = errno;
    munmap(map_, guardBytes_ + stackBytes_);
    throw std::system_error(e, std::generic_category(), "fiber guard page");
  }
}

Fiber::~Fiber() {
  if (tCurrent == this) die("a fiber destroyed itself");
  munmap(map_, guardBytes_ + stackBytes_);
}

void Fiber::start(std::function<void()> body) {
  body_ = std::move(body);
  start(nullptr, nullptr);
}

void Fiber::start(void (*fn)(void*), void* arg) {
  if (tCurrent == this) die("a fiber restarted itself");
  fn_ = fn;
  arg_ = arg;
  if (fn) body_ = nullptr;
  char* bottom = static_cast<char*>(map_) + guardBytes_;
#ifdef STC_ASAN
  // Frames of an abandoned run left their redzones poisoned.
  __asan_unpoison_memory_region(bottom, stackBytes_);
#endif
  ctx_ = fctx::make_fcontext(bottom + stackBytes_, stackBytes_, &FiberAccess::trampoline);
  running_ = true;
  abandoned_ = false;
  fakeStack_ = nullptr;
  error_ = nullptr;
}

bool Fiber::resume() {
  if (!running_) die("resume of a fiber that is not running");
  if (tCurrent == this) die("a fiber resumed itself");
  prevCurrent_ = tCurrent;
  tCurrent = this;
  startSwitch(&callerFakeStack_, static_cast<char*>(map_) + guardBytes_, stackBytes_);
  fctx::transfer_t t = fctx::jump_fcontext(ctx_, this);
  finishSwitch(callerFakeStack_, nullptr, nullptr);
  tCurrent = prevCurrent_;
  if (static_cast<Exit>(reinterpret_cast<uintptr_t>(t.data)) == Exit::Suspended) {
    ctx_ = t.fctx;
    return false;
  }
  ctx_ = nullptr;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  return true;
}

void Fiber::suspend() {
  Fiber* f = tCurrent;
  if (!f) die("Fiber::suspend outside a fiber");
  startSwitch(&f->fakeStack_, f->callerBottom_, f->callerSize_);
  fctx::transfer_t t =
      fctx::jump_fcontext(f->callerCtx_, reinterpret_cast<void*>(static_cast<uintptr_t>(Exit::Suspended)));
  // Resumed, possibly from a different stack than last time.
  finishSwitch(f->fakeStack_, &f->callerBottom_, &f->callerSize_);
  f->callerCtx_ = t.fctx;
}

void Fiber::abandon() {
  Fiber* f = tCurrent;
  if (!f) die("Fiber::abandon outside a fiber");
  f->leave(Exit::Abandoned);
}

void Fiber::leave(Exit why) {
  running_ = false;
  abandoned_ = why == Exit::Abandoned;
  startSwitch(nullptr, callerBottom_, callerSize_);
  fctx::jump_fcontext(callerCtx_, reinterpret_cast<void*>(static_cast<uintptr_t>(why)));
  die("a finished fiber was resumed");
}

Fiber* Fiber::current() { return tCurrent; }

}  // namespace stc::vm
