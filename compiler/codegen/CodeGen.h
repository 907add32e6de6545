// Code generation: the checked program (sema::Model) to one LLVM module.
// This header is LLVM-free so that the driver and the controller can include
// it cheaply; CodeGenLLVM.h gives the JIT access to the module itself.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"

namespace stc::sema { struct Model; class Type; }

namespace stc::codegen {

struct CodegenOptions {
  unsigned optLevel = 2;       // -O0..-O3
  bool checks = true;          // runtime checks (division by zero, bounds, null, subranges)
  // --check-pointers: every dereference must land in the memory image or the running
  // task's stack (default in stc test); MEMCPY/MEMSET/MEMMOVE/MEMCMP are always checked.
  bool checkPointers = false;
  bool debugInfo = false;      // -g
  // Programs to run when there is no CONFIGURATION (stc run --program); empty: automatic.
  std::vector<std::string> programs;
  int64_t defaultIntervalNs = 1'000'000;
  // Give FUNCTIONs external linkage ("st.<Name>") so a host can call them
  // (benchmarks, embedding).  Off: everything internal, for inlining.
  bool exportFunctions = false;
};

// Where a runtime fault can happen: each check and safepoint has one.
struct Site {
  SourceRange range;
  SourceLoc loc;               // where to point (an operator); invalid: range.begin
  std::string pou;
  std::string detail;          // e.g. the array or variable name
};

enum class FaultKind : uint32_t {
  DivisionByZero = 1, Index = 2, Subrange = 3, NullPointer = 4, NullReference = 5,
  NullInterface = 6, UnboundInOut = 7, ForStepZero = 8, StringIndex = 9, BadVtable = 10, PointerRange = 11,
};
const char* faultCode(FaultKind k);      // "fault-division-by-zero", ...

// A named top-level object in the memory image.
struct ImageRoot {
  std::string path;            // "GVL.x", "x", "MAIN", "FB_Counter.count" (VAR_STAT)
  uint64_t offset = 0;
  const sema::Type* type = nullptr;
  bool retain = false, persistent = false, constant = false, alias = false;   // alias: another name of an earlier root
  int bit = -1;                // a BOOL view of one bit (AT %IX1.2)
  // A PROGRAM's own instance that never runs: the configuration runs the program
  // only under these instance names (paths through it are refused with a hint).
  std::string runsAs;
};

struct ImageMap {
  uint64_t size = 0;
  std::vector<ImageRoot> roots;
  // The process image areas %I, %Q, %M, at the end of the image.
  uint64_t inputOffset = 0, inputSize = 0, outputOffset = 0, outputSize = 0, memoryOffset = 0, memorySize = 0;
  uint64_t inputUsed = 0, outputUsed = 0;   // bytes of %I / %Q the program uses (copied at slot boundaries)
  const ImageRoot* find(const std::string& upperPath) const;
};

// A task and what it runs (from a CONFIGURATION, or the implicit one).
struct TaskPlan {
  enum class Kind { Cyclic, Event, Freewheeling };
  std::string name;
  Kind kind = Kind::Cyclic;
  int64_t intervalNs = 1'000'000;
  int priority = 0;
  std::string singlePath;                   // Event: the BOOL that triggers it (image path)
  std::optional<uint64_t> singleOffset;     // its image offset
  std::vector<std::string> entries;         // JIT symbols, one per program instance, in order
  std::vector<std::string> programNames;    // instance names (messages)
  bool mayBlock = false;                    // contains a safepoint (loop) or a blocking call
};

class CompiledModule {
public:
  struct Impl;
  explicit CompiledModule(std::unique_ptr<Impl> impl);
  ~CompiledModule();
  Impl& impl() { return *impl_; }

  ImageMap image;
  std::vector<Site> sites;                  // index = site id (0 unused)
  std::vector<TaskPlan> tasks;
  // The 32-bit address model: the JIT, the task stacks and everything else the
  // program can point into must lie below 4 GiB (vm/Jit.cpp, vm/Fiber.cpp).
  bool lowMemory = false;
  // POUs implemented in C++ (native bindings) that the module references.
  struct Native {
    std::string symbol;                     // "native.TON", "native.TEST_Sleep"
    std::string name;                       // the ST name
    uint64_t hash = 0;                      // Layout::pouHash of the ST declaration
    SourceRange decl;
  };
  std::vector<Native> natives;

private:
  std::unique_ptr<Impl> impl_;
};

// Generates and optimises the module.  Reports problems (e.g. no program
// to run) to `diags`; returns null then.
std::unique_ptr<CompiledModule> generate(const sema::Model& model, const SourceManager& sm, DiagnosticsEngine& diags,
                                         const CodegenOptions& opts, bool needTasks);

enum class EmitKind { LLVM, Object };
// Writes the module as textual IR or a relocatable object ("-" = stdout for IR).
bool emit(CompiledModule& m, EmitKind kind, const std::string& path, std::string& error);

}  // namespace stc::codegen
