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
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vm/Scheduler.h"
#include "vm/Time.h"

namespace stc::vm {

struct NativeEntry {
  std::string name;            // ST name, as declared (FB, FUNCTION, or FB.METHOD)
  const void* address;         // the C function with the ST calling convention
  uint64_t hash;               // Layout::pouHash of the declaration it was built for
};

// The state one controller keeps for a native library (the motion kernel
// and its axes, simulated devices ...): made at load, so two controllers in
// one process never share it.  Natives reach the session of the controller
// that calls them with currentSession().
class Scheduler;
struct StartCtx {
  Scheduler& scheduler;
  uint8_t* image;
  uint64_t imageSize;          // bytes: [image, image + imageSize) holds every static variable
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
  // A variable found by name while the run goes (G-code `$name$`): where it is, its type
  // name as declared (`LREAL`, `INT`, an alias ...) and whether it is a CONSTANT.  Unlike
  // the two above, this one may be kept and called until the run ends (it refers only to
  // the controller, which outlives its sessions).  False with `error` if there is none.
  struct Variable {
    uint8_t* address = nullptr;
    int bit = -1;              // a BOOL view of one bit (AT %MX1.2)
    std::string typeName;
    bool constant = false;
  };
  std::function<bool(const std::string& path, Variable& out, std::string& error)> lookupVariable;
  // Whether anyone reads the {attribute 'mirrored'} structs (AXIS_REF_SM3 ...): ST code
  // (sema::Model::readsMirrored), a watch, a trace, a scenario probe or a retain file.
  // When false the natives may leave them as they are (they still bind them).
  bool mirroredRead = true;
};

class NativeSession {
public:
  virtual ~NativeSession() = default;
  // Once per run, after the tasks are built and before the first tick (the
  // motion library binds the configured axes to their AXIS_REF globals here).
  // False stops the run with `error`.
  virtual bool start(const StartCtx&, std::string& /*error*/) { return true; }
  // After the programs of every task slot, also while the task is suspended in a wait.
  virtual void cycle(const HookCtx&) {}
  // The units of measure of the variables the library configures, as (path,
  // unit) pairs (the motion library: each [[axis]] with a `unit`).  A traced
  // variable at or under a path (names case-insensitive) takes its unit;
  // traces record it (vm/Trace.h).  Asked before start().
  virtual std::vector<std::pair<std::string, std::string>> units() const { return {}; }
};

// A native library as the controller sees it: the C++ bodies of its
// {attribute 'native'} POUs (code, the same for every controller) and a
// factory for its per-controller state.  The tool that builds a controller
// hands it the libraries (Controller::addLibrary); vm/ knows none by name.
class NativeLibrary {
public:
  virtual ~NativeLibrary() = default;
  virtual std::string_view name() const = 0;
  virtual const std::vector<NativeEntry>& natives() const = 0;
  // The key natives pass to currentSession() to find this library's session.
  virtual const void* sessionKey() const { return this; }
  // A fresh session for one controller; null when the library keeps no state.
  virtual std::unique_ptr<NativeSession> newSession() const { return nullptr; }
};

namespace detail {
using SessionTable = std::vector<std::pair<const void*, NativeSession*>>;
// constinit: accessed directly, without a TLS wrapper function (natives read it on every call).
inline constinit thread_local const SessionTable* tSessions = nullptr;   // set by SessionScope
}  // namespace detail

// The session that the controller running on this thread keeps under `key`
// (null outside a controller's load or run, or when it has none).  Inline:
// natives call it on every call.
inline NativeSession* currentSession(const void* key) {
  if (const detail::SessionTable* t = detail::tSessions)
    for (const auto& [k, s] : *t)
      if (k == key) return s;
  return nullptr;
}

// Makes a controller's sessions current on this thread for the guard's life.
class SessionScope {
public:
  using Table = detail::SessionTable;
  explicit SessionScope(const Table* t);
  ~SessionScope();
  SessionScope(const SessionScope&) = delete;
  SessionScope& operator=(const SessionScope&) = delete;

private:
  const Table* prev_;
};

// For natives declared {attribute 'blocking'}: suspend the calling task
// (its fiber) while the rest of the controller goes on.  A blocking native
// must not hold objects with destructors across these calls: a task that is
// stopped by a fault is abandoned, not unwound.
void sleepFor(Time d);
void waitUntil(std::function<bool()> ready);
Time now();

}  // namespace stc::vm
