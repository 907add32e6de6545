// The __stc_* functions that generated code calls (faults, safepoints,
// strings), and the table of every symbol the JIT may bind.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace stc::vm {

// Name -> address of the runtime functions, __stc_budget and the libm and
// libc functions LLVM may emit calls to.
std::map<std::string, void*> runtimeSymbols();

struct FaultInfo;
// Generated code that runs outside a task (dynamic initial values, FB_INIT,
// FB_EXIT) reports a fault to this handler, which must not return (the
// controller longjmps back to where it called the code); none: the process
// ends with status 3.  Returns the previous handler.
using OutsideTaskFaultHandler = void (*)(FaultInfo&& info);
OutsideTaskFaultHandler setOutsideTaskFaultHandler(OutsideTaskFaultHandler h);
// Whether a handler is set (generated code runs outside the tasks).
bool outsideTaskFaultHandlerSet();

// The program's static memory, for __stc_check_ptr (set by the controller on the
// thread that runs the program).
void setProgramMemory(const void* image, uint64_t bytes);

// Reports a fault of the running task (or to the outside handler) with its callers
// from the task's call chain; does not return.
[[noreturn]] void raiseFault(uint32_t site, const char* code, std::string message);

}  // namespace stc::vm

// The site of the last operation that may touch memory through a pointer (written
// by generated code before dereferences, MEMCPY and indirect calls): a hardware
// fault there is reported at that site (vm/FaultSignals.cpp).
extern "C" uint32_t __stc_site;

namespace stc::vm {

}  // namespace stc::vm
