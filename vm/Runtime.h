// The __stc_* functions that generated code calls (faults, safepoints,
// strings), and the table of every symbol the JIT may bind.
#pragma once

#include <map>
#include <string>

namespace stc::vm {

// Name -> address of the runtime functions, __stc_budget and the libm and
// libc functions LLVM may emit calls to.
std::map<std::string, void*> runtimeSymbols();

}  // namespace stc::vm
