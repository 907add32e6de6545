// The __stc_* functions that generated code calls (faults, safepoints,
// strings), and the table of every symbol the JIT may bind.
#pragma once

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

}  // namespace stc::vm
