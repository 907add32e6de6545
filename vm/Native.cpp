#include "vm/Native.h"

#include "basic/Text.h"
#include "vm/Scheduler.h"

namespace stc::vm {

const NativeEntry* NativeRegistry::find(std::string_view name) const {
  for (const NativeEntry& e : entries_)
    if (equalsIgnoreCase(e.name, name)) return &e;
  return nullptr;
}

NativeRegistry& nativeRegistry() {
  static NativeRegistry r;
  return r;
}

void sleepFor(Time d) { Scheduler::current()->sleepFor(d); }
void waitUntil(std::function<bool()> ready) { Scheduler::current()->waitUntil(std::move(ready)); }
Time now() { return Scheduler::current() ? Scheduler::current()->now() : 0; }

}  // namespace stc::vm
