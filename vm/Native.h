// The native binding API: C++ implementations of POUs declared in ST.
//
// One declaration is the source of truth: the ST file declares the FUNCTION
// or FUNCTION_BLOCK with {attribute 'native'} (and {attribute 'blocking'}
// when it may wait).  stc_bindgen turns that declaration into a C++ header
// with the instance struct, static_asserts on every offset and the size, the
// function type and the declaration's hash.  The implementation registers
// itself with that hash; at load the controller compares it with the hash of
// the declaration the program was compiled against, so a stale build is a
// load error, never memory corruption.  See docs/native-api.md.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "vm/Scheduler.h"
#include "vm/Time.h"

namespace stc::vm {

struct NativeEntry {
  std::string name;            // ST name, as declared (FB, FUNCTION, or FB.METHOD)
  const void* address;         // the C function with the ST calling convention
  uint64_t hash;               // Layout::pouHash of the declaration it was built for
};

struct NativeLibrary {
  std::string name;            // shown in diagnostics, e.g. "<testlib>"
  std::string source;          // ST declarations
};

// A per-cycle hook of a native library (the motion kernel registers here):
// runs after the programs of every task slot, also while the task is
// suspended in a wait, in registration order.
struct NativeHook {
  std::string name;
  std::function<void(const HookCtx&)> fn;
};

// A start hook of a native library: runs once per run, after the tasks are
// built and before the first tick (the motion library binds the configured
// axes to their AXIS_REF globals here).  Returning false stops the run.
class Scheduler;
struct StartCtx {
  Scheduler& scheduler;
  uint8_t* image;
  // The address of a variable (`GVL.x`, `Axis1`) and its type name; null if none.
  std::function<void*(const std::string& path, std::string& typeName)> lookup;
  // A BOOL variable, also one AT a bit address (%IX0.1), for simulated devices:
  // where to write it.  Inputs (%I) are written into the external input buffer,
  // which is copied into the image before each task slot.  False if no BOOL of that name.
  struct BoolTarget {
    uint8_t* byte = nullptr;
    int bit = -1;              // -1: the whole byte is the BOOL
  };
  std::function<bool(const std::string& path, BoolTarget& out)> lookupBool;
};
struct NativeStartHook {
  std::string name;
  std::function<bool(const StartCtx&, std::string& error)> fn;
};

class NativeRegistry {
public:
  void addStartHook(NativeStartHook h) { startHooks_.push_back(std::move(h)); }
  const std::vector<NativeStartHook>& startHooks() const { return startHooks_; }
  void add(NativeEntry e) { entries_.push_back(std::move(e)); }
  void addCycleHook(NativeHook h) { hooks_.push_back(std::move(h)); }
  const std::vector<NativeHook>& cycleHooks() const { return hooks_; }
  void addLibrary(NativeLibrary lib) { libraries_.push_back(std::move(lib)); }
  const NativeEntry* find(std::string_view name) const;
  const std::vector<NativeLibrary>& libraries() const { return libraries_; }

private:
  std::vector<NativeEntry> entries_;
  std::vector<NativeLibrary> libraries_;
  std::vector<NativeHook> hooks_;
  std::vector<NativeStartHook> startHooks_;
};

NativeRegistry& nativeRegistry();

// For natives declared {attribute 'blocking'}: suspend the calling task
// (its fiber) while the rest of the controller goes on.  A blocking native
// must not hold objects with destructors across these calls: a task that is
// stopped by a fault is abandoned, not unwound.
void sleepFor(Time d);
void waitUntil(std::function<bool()> ready);
Time now();

}  // namespace stc::vm
