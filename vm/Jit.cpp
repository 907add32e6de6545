#include "vm/Jit.h"

#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/ExecutionEngine/Orc/ThreadSafeModule.h>
#include <llvm/Support/Error.h>
#include <llvm/Support/TargetSelect.h>

#include <mutex>

#include "codegen/CodeGenLLVM.h"

namespace stc::vm {

struct Jit::Impl {
  std::unique_ptr<llvm::orc::LLJIT> jit;
};

Jit::~Jit() = default;

std::unique_ptr<Jit> Jit::create(codegen::CompiledModule& module, const std::map<std::string, void*>& symbols, std::string& error) {
  static std::once_flag once;
  std::call_once(once, [] {
    llvm::InitializeNativeTarget();
    llvm::InitializeNativeTargetAsmPrinter();
  });
  auto jtmb = llvm::orc::JITTargetMachineBuilder::detectHost();
  if (!jtmb) { error = llvm::toString(jtmb.takeError()); return nullptr; }
  unsigned lvl = module.impl().optLevel;
  jtmb->setCodeGenOptLevel(lvl == 0 ? llvm::CodeGenOptLevel::None : lvl == 1 ? llvm::CodeGenOptLevel::Less
                           : lvl == 2 ? llvm::CodeGenOptLevel::Default : llvm::CodeGenOptLevel::Aggressive);
  auto jit = llvm::orc::LLJITBuilder().setJITTargetMachineBuilder(std::move(*jtmb))
                 .setLinkProcessSymbolsByDefault(false)
                 .setPlatformSetUp(llvm::orc::setUpInactivePlatform)   // no static initialisers, no process symbols
                 .create();
  if (!jit) { error = llvm::toString(jit.takeError()); return nullptr; }
  auto out = std::unique_ptr<Jit>(new Jit());
  out->impl_ = std::make_unique<Impl>();
  out->impl_->jit = std::move(*jit);
  llvm::orc::LLJIT& j = *out->impl_->jit;
  llvm::orc::SymbolMap map;
  for (auto& [name, addr] : symbols)
    map[j.mangleAndIntern(name)] = llvm::orc::ExecutorSymbolDef(llvm::orc::ExecutorAddr::fromPtr(addr),
                                                                 llvm::JITSymbolFlags::Exported | llvm::JITSymbolFlags::Callable);
  if (auto err = j.getMainJITDylib().define(llvm::orc::absoluteSymbols(std::move(map)))) {
    error = llvm::toString(std::move(err));
    return nullptr;
  }
  llvm::Module& m = *module.impl().module;
  m.setDataLayout(j.getDataLayout());
  m.setTargetTriple(j.getTargetTriple().str());
  auto tsm = llvm::orc::ThreadSafeModule(std::move(module.impl().module), std::move(module.impl().context));
  if (auto err = j.addIRModule(std::move(tsm))) {
    error = llvm::toString(std::move(err));
    return nullptr;
  }
  return out;
}

void* Jit::lookup(const std::string& name, std::string& error) {
  auto sym = impl_->jit->lookup(name);
  if (!sym) {
    error = llvm::toString(sym.takeError());
    return nullptr;
  }
  return sym->toPtr<void*>();
}

}  // namespace stc::vm
