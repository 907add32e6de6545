// The LLVM side of a CompiledModule, for the JIT (vm/Jit.cpp) and Emit.cpp.
// Only files that already include LLVM include this.
#pragma once

#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>

#include <memory>

#include "codegen/CodeGen.h"

namespace stc::codegen {

struct CompiledModule::Impl {
  std::unique_ptr<llvm::LLVMContext> context;
  std::unique_ptr<llvm::Module> module;
  unsigned optLevel = 2;
};

// Runs the new-PM pipeline for -O0..-O3 on the module.
void optimize(llvm::Module& m, unsigned level);

}  // namespace stc::codegen
