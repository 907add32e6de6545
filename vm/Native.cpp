#include "vm/Native.h"

#include "vm/Scheduler.h"

namespace stc::vm {

namespace {
thread_local const SessionScope::Table* tSessions = nullptr;
}  // namespace

NativeSession* currentSession(const void* key) {
  if (tSessions)
    for (const auto& [k, s] : *tSessions)
      if (k == key) return s;
  return nullptr;
}

SessionScope::SessionScope(const Table* t) : prev_(tSessions) { tSessions = t; }
SessionScope::~SessionScope() { tSessions = prev_; }

void sleepFor(Time d) { Scheduler::current()->sleepFor(d); }
void waitUntil(std::function<bool()> ready) { Scheduler::current()->waitUntil(std::move(ready)); }
Time now() { return Scheduler::current() ? Scheduler::current()->now() : 0; }

}  // namespace stc::vm
