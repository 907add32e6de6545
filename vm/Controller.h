// The virtual controller: loads a compiled program into the JIT, holds its
// memory image, builds the tasks on the deterministic scheduler and runs
// them; reports faults with their source location; prints watches and
// writes traces.  See docs/vm.md.
#pragma once

#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "basic/Diagnostics.h"
#include "codegen/CodeGen.h"
#include "vm/Time.h"
#include "vm/Trace.h"

namespace stc::sema { struct Model; class Type; }

namespace stc::vm {

class Jit;
class NativeLibrary;
struct NativeEntry;
class NativeSession;
class Scheduler;
struct FaultInfo;
class TraceWriter;
struct ValueRef;
struct RetainEntry;

struct RunOptions {
  std::optional<uint64_t> cycles;        // slots of the fastest cyclic task
  std::optional<Time> duration;          // run every tick T < duration
  bool realtime = false;
  bool stats = false;
  std::vector<std::string> watches;
  std::optional<Time> watchEvery;        // also print the watches every D of simulated time
  std::vector<std::string> traces;
  std::string traceOut;
  CsvTraceOptions traceCsv;              // how a CSV trace writes its rows (stc test: sampling, tolerance)
  std::optional<Time> watchdog;
  std::optional<int64_t> slice;
  std::string retainFile;                // RETAIN/PERSISTENT variables: restored at start, saved at stop
  std::optional<Time> retainEvery;       // also save every D of simulated time
  bool cold = false;                     // restore PERSISTENT variables only
  bool retainReset = false;              // start from the initial values; replace a damaged/newer file
  // Scenarios (stc test, tools/stc/TestCommand.cpp): called before every task
  // slot (before the inputs are copied in) and after every base tick (after
  // the trace sample), with the tick's time.
  std::function<void(Time now)> beforeSlot;
  std::function<void(Time now)> afterTick;
  // Something outside the program (a scenario probe ...) reads a path with
  // ValueRef::mirrored; watches, traces and retain files are checked by run().
  bool observesMirrored = false;
};

class Controller {
public:
  Controller(const sema::Model& model, DiagnosticsEngine& diags);
  ~Controller();
  // The native libraries whose natives the program may call (before load();
  // the libraries must outlive the controller).  Each gets its own session.
  void addLibrary(const NativeLibrary& lib) { libraries_.push_back(&lib); }
  // JIT-compiles the module and performs a cold start.  False with `error`.
  bool load(std::unique_ptr<codegen::CompiledModule> module, std::string& error);
  // Runs; prints the watches to `out`.  Returns the exit status:
  // 0 ok, 2 a bad watch/trace request or a retain file that cannot be used,
  // 3 a runtime fault happened, 4 the retain file could not be saved (and no fault).
  int run(const RunOptions& opts, std::ostream& out, std::ostream& err);

  uint8_t* image() const { return image_; }
  // The process image seen from outside (scenarios, simulated devices):
  // inputs are copied into %I before each task slot, %Q out after it.
  std::vector<uint8_t>& inputs() { return inputs_; }
  const std::vector<uint8_t>& outputs() const { return outputs_; }
  const codegen::ImageMap& imageMap() const { return module_->image; }
  Scheduler& scheduler() { return *sched_; }

  // The retained regions of the image (RETAIN/PERSISTENT at any depth).
  struct RetainRegion { std::string path; uint64_t offset; const sema::Type* type; bool persistent; };
  std::vector<RetainRegion> retainRegions() const;
  // The retained values one by one (vm/RetainImage.cpp): elementary values, strings,
  // arrays of them and unions; structures, FB instances and arrays of them are split
  // into their members; pointers, references, interfaces and vtables are not kept.
  struct RetainLeaf { std::string path; uint64_t offset; const sema::Type* type; int bit; bool persistent; };
  std::vector<RetainLeaf> retainLeaves() const;
  bool saveRetain(const std::string& file, std::string& error);
  // Warm: values were restored; Cold: none (no file, --retain-reset); Refused: the file
  // is not one to use or replace (the message is printed; the run must not start).
  enum class RetainStart { Cold, Warm, Refused };
  RetainStart restoreRetain(const std::string& file, bool coldStart, bool reset, std::ostream& err);

  std::string valueText(const ValueRef& r) const;

private:
  const NativeEntry* findNative(std::string_view name) const;
  void reportFaults(std::ostream& err);
  void reportFault(const FaultInfo& info, const std::string& prefix);
  bool callOutsideTasks(void (*fn)(bool), bool arg, FaultInfo& fault);
  std::string leafSignature(const RetainLeaf& l) const;
  std::vector<uint8_t> leafBytes(const RetainLeaf& l) const;
  void checkRestored(const RetainLeaf& l, std::vector<std::string>& notes);
  bool convertLeaf(const RetainLeaf& l, const RetainEntry& e, std::string& how);
  const sema::Model& model_;
  DiagnosticsEngine& diags_;
  std::unique_ptr<codegen::CompiledModule> module_;
  std::unique_ptr<Jit> jit_;
  std::unique_ptr<Scheduler> sched_;
  uint8_t* image_ = nullptr;
  std::vector<uint8_t> coldSnapshot_;
  void (*initDynamic_)() = nullptr;
  void (*fbInit_)(bool) = nullptr;   // __stc_fb_init(bInitRetains): FB_INIT of the image's instances
  void (*fbExit_)(bool) = nullptr;   // __stc_fb_exit: FB_EXIT at stop
  struct TaskRuntime {
    std::vector<void (*)()> entries;
  };
  std::vector<std::unique_ptr<TaskRuntime>> tasks_;
  std::function<void(Time)> tickFn_;       // trace sampling
  std::vector<uint8_t> inputs_, outputs_;
  std::vector<const NativeLibrary*> libraries_;
  std::vector<std::unique_ptr<NativeSession>> sessions_;
  std::vector<std::pair<const void*, NativeSession*>> sessionTable_;   // for currentSession()
};

}  // namespace stc::vm
