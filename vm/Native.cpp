#include "vm/Native.h"

#include "vm/Scheduler.h"

namespace stc::vm {

SessionScope::SessionScope(const Table* t) : prev_(detail::tSessions) { detail::tSessions = t; }
SessionScope::~SessionScope() { detail::tSessions = prev_; }

void sleepFor(Time d) { Scheduler::current()->sleepFor(d); }
void waitUntil(std::function<bool()> ready) { Scheduler::current()->waitUntil(std::move(ready)); }
Time now() { return Scheduler::current() ? Scheduler::current()->now() : 0; }

}  // namespace stc::vm
