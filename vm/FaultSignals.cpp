#include "vm/FaultSignals.h"

#include <signal.h>
#include <ucontext.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>

#include "vm/Fiber.h"
#include "vm/Runtime.h"
#include "vm/Scheduler.h"

namespace stc::vm {

namespace {

constexpr int kSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL};
constexpr size_t kAltStackBytes = 256 * 1024;   // the fault report allocates and formats
// The calling thread's alternate signal stack, released (and unregistered) when the thread ends.
struct AltStack {
  std::unique_ptr<char[]> memory;
  ~AltStack() {
    if (!memory) return;
    stack_t off{};
    off.ss_flags = SS_DISABLE;
    sigaltstack(&off, nullptr);
  }
};
thread_local AltStack tAltStack;

std::string hexAddress(uintptr_t a) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "16#%llX", static_cast<unsigned long long>(a));
  return buf;
}

// A fault address near the interrupted stack pointer, or in the guard page of the
// running fiber, is the stack running out.
bool isStackOverflow(uintptr_t addr, const void* uc) {
  if (const Fiber* f = Fiber::current()) {
    auto [guard, size] = f->guardRange();
    auto g = reinterpret_cast<uintptr_t>(guard);
    if (addr >= g && addr < g + size) return true;
  }
#if defined(__x86_64__) && defined(REG_RSP)
  auto sp = static_cast<uintptr_t>(static_cast<const ucontext_t*>(uc)->uc_mcontext.gregs[REG_RSP]);
  return addr + 65536 >= sp && addr <= sp + 65536;
#else
  (void)uc;
  return false;
#endif
}

void onFault(int sig, siginfo_t* si, void* uc) {
  Scheduler* s = Scheduler::current();
  bool inTask = s && s->inActivation();
  if (!inTask && !outsideTaskFaultHandlerSet()) {
    // Not the program's fault (the compiler, a hook, the controller itself): the
    // default action, as without this handler, when the instruction runs again.
    signal(sig, SIG_DFL);
    return;
  }
  // The handler is left by a jump, never by returning: unblock the signal first.
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  auto addr = reinterpret_cast<uintptr_t>(si->si_addr);
  uint32_t site = __stc_site;
  if (sig == SIGFPE) {
    raiseFault(site, "fault-arithmetic", "arithmetic exception (SIGFPE)");
  } else if (sig == SIGILL) {
    raiseFault(site, "fault-illegal-instruction", "illegal instruction at " + hexAddress(addr) + " (a corrupted code pointer)");
  } else if (isStackOverflow(addr, uc)) {
    // The innermost call site names where the chain went too deep.
    const CallChain& chain = *__stc_calls;
    if (chain.depth > 0) site = chain.sites[(chain.depth - 1) % 64];
    raiseFault(site, "fault-stack-overflow", "stack overflow: the chain of calls is too deep or its locals too large");
  } else {
    raiseFault(site, "fault-memory", std::string(addr < 4096 ? "access to a NULL pointer" : "access violation") + " at address " +
                                         hexAddress(addr) + (sig == SIGBUS ? " (bus error)" : ""));
  }
}

}  // namespace

void installFaultSignals() {
  static std::once_flag once;
  std::call_once(once, [] {
    struct sigaction sa {};
    sa.sa_sigaction = &onFault;
    sa.sa_flags = SA_SIGINFO | SA_ONSTACK;
    sigemptyset(&sa.sa_mask);
    for (int sig : kSignals) sigaction(sig, &sa, nullptr);
  });
  if (!tAltStack.memory) {
    // Kept until the thread ends: it may fault until then (one per controller thread).
    auto memory = std::make_unique<char[]>(kAltStackBytes);
    stack_t ss{};
    ss.ss_sp = memory.get();
    ss.ss_size = kAltStackBytes;
    ss.ss_flags = 0;
    if (sigaltstack(&ss, nullptr) == 0) tAltStack.memory = std::move(memory);
  }
}

}  // namespace stc::vm
