// The in-process ORC JIT: turns a CompiledModule into machine code and
// resolves its symbols.  The only vm/ file that includes LLVM is Jit.cpp.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "codegen/CodeGen.h"

namespace stc::vm {

class Jit {
public:
  // `symbols`: every external symbol the module may reference (runtime,
  // natives, libm).  The host process is not searched, so a missing symbol
  // is a load error, not a silent binding.
  static std::unique_ptr<Jit> create(codegen::CompiledModule& module, const std::map<std::string, void*>& symbols, std::string& error);
  ~Jit();
  void* lookup(const std::string& name, std::string& error);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stc::vm
