#include "vm/Jit.h"

#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/ExecutionEngine/Orc/MapperJITLinkMemoryManager.h>
#include <llvm/ExecutionEngine/Orc/MemoryMapper.h>
#include <llvm/ExecutionEngine/Orc/ObjectLinkingLayer.h>
#include <llvm/ExecutionEngine/Orc/Shared/AllocationActions.h>
#include <llvm/ExecutionEngine/Orc/ThreadSafeModule.h>
#include <llvm/Support/Error.h>
#include <llvm/Support/TargetSelect.h>

#include <sys/mman.h>
#include <unistd.h>

#include <cstring>
#include <map>
#include <mutex>

#include "codegen/CodeGenLLVM.h"
#include "vm/Fiber.h"

namespace stc::vm {

struct Jit::Impl {
  std::unique_ptr<llvm::orc::LLJIT> jit;
};

namespace {

namespace orc = llvm::orc;

// The 32-bit address model: the JIT places code, constants and the memory image
// below 4 GiB, so that any address the program can take fits a 4-byte pointer.
// In-process, like orc::InProcessMemoryMapper, but with mmap(MAP_32BIT).
class LowMemoryMapper final : public orc::MemoryMapper {
public:
  unsigned int getPageSize() override { return static_cast<unsigned>(sysconf(_SC_PAGESIZE)); }

  void reserve(size_t bytes, OnReservedFunction onReserved) override {
    void* p = mapLow(bytes);
    if (!p)
      return onReserved(llvm::make_error<llvm::StringError>("no memory below 4 GiB for the 32-bit address model",
                                                            llvm::inconvertibleErrorCode()));
    {
      std::lock_guard<std::mutex> lock(mutex_);
      reservations_[reinterpret_cast<uintptr_t>(p)] = bytes;
    }
    onReserved(orc::ExecutorAddrRange(orc::ExecutorAddr::fromPtr(p), bytes));
  }

  char* prepare(orc::ExecutorAddr addr, size_t) override { return addr.toPtr<char*>(); }

  void initialize(AllocInfo& ai, OnInitializedFunction onInitialized) override {
    orc::ExecutorAddr lo(~0ULL);
    for (AllocInfo::SegInfo& seg : ai.Segments) {
      orc::ExecutorAddr base = ai.MappingBase + seg.Offset;
      size_t size = seg.ContentSize + seg.ZeroFillSize;
      if (base < lo) lo = base;
      std::memset((base + seg.ContentSize).toPtr<void*>(), 0, seg.ZeroFillSize);
      if (auto ec = llvm::sys::Memory::protectMappedMemory(llvm::sys::MemoryBlock(base.toPtr<void*>(), size),
                                                             orc::toSysMemoryProtectionFlags(seg.AG.getMemProt())))
        return onInitialized(llvm::errorCodeToError(ec));
      if (static_cast<unsigned>(seg.AG.getMemProt()) & static_cast<unsigned>(orc::MemProt::Exec))
        llvm::sys::Memory::InvalidateInstructionCache(base.toPtr<void*>(), size);
    }
    auto deinit = orc::shared::runFinalizeActions(ai.Actions);
    if (!deinit) return onInitialized(deinit.takeError());
    {
      std::lock_guard<std::mutex> lock(mutex_);   // callbacks may come back here: never call them under the lock
      deinitActions_[lo.getValue()] = std::move(*deinit);
    }
    onInitialized(lo);
  }

  void deinitialize(llvm::ArrayRef<orc::ExecutorAddr> allocations, OnDeinitializedFunction done) override {
    llvm::Error err = llvm::Error::success();
    for (orc::ExecutorAddr a : allocations) {
      std::vector<orc::shared::WrapperFunctionCall> actions;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = deinitActions_.find(a.getValue());
        if (it == deinitActions_.end()) continue;
        actions = std::move(it->second);
        deinitActions_.erase(it);
      }
      err = llvm::joinErrors(std::move(err), orc::shared::runDeallocActions(actions));
    }
    done(std::move(err));
  }

  void release(llvm::ArrayRef<orc::ExecutorAddr> reservations, OnReleasedFunction done) override {
    for (orc::ExecutorAddr a : reservations) {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = reservations_.find(a.getValue());
      if (it == reservations_.end()) continue;
      munmap(a.toPtr<void*>(), it->second);
      reservations_.erase(it);
    }
    done(llvm::Error::success());
  }

  ~LowMemoryMapper() override {
    for (auto& [base, bytes] : reservations_) munmap(reinterpret_cast<void*>(base), bytes);
  }

private:
  std::mutex mutex_;
  std::map<uint64_t, size_t> reservations_;
  std::map<uint64_t, std::vector<orc::shared::WrapperFunctionCall>> deinitActions_;
};

}  // namespace

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
  llvm::orc::LLJITBuilder builder;
  builder.setJITTargetMachineBuilder(std::move(*jtmb))
      .setLinkProcessSymbolsByDefault(false)
      .setPlatformSetUp(llvm::orc::setUpInactivePlatform);   // no static initialisers, no process symbols
  if (module.lowMemory)
    builder.setObjectLinkingLayerCreator([](llvm::orc::ExecutionSession& es, const llvm::Triple&)
                                             -> llvm::Expected<std::unique_ptr<llvm::orc::ObjectLayer>> {
      // Reserved in 64 MiB steps (address space only: MAP_NORESERVE).
      auto mm = std::make_unique<llvm::orc::MapperJITLinkMemoryManager>(size_t{64} << 20, std::make_unique<LowMemoryMapper>());
      return std::make_unique<llvm::orc::ObjectLinkingLayer>(es, std::move(mm));
    });
  auto jit = builder.create();
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
