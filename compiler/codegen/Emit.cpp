// Optimisation pipelines (new pass manager) and --emit llvm|obj.
#include <llvm/Analysis/CGSCCPassManager.h>
#include <llvm/Analysis/LoopAnalysisManager.h>
#include <llvm/IR/LegacyPassManager.h>
#include <llvm/IR/PassManager.h>
#include <llvm/MC/TargetRegistry.h>
#include <llvm/Passes/PassBuilder.h>
#include <llvm/Passes/StandardInstrumentations.h>
#include <llvm/Support/FileSystem.h>
#include <llvm/Support/TargetSelect.h>
#include <llvm/Support/raw_ostream.h>
#include <llvm/Target/TargetMachine.h>
#include <llvm/Target/TargetOptions.h>
#include <llvm/TargetParser/Host.h>
#include <llvm/TargetParser/SubtargetFeature.h>

#include <llvm/Support/CommandLine.h>

#include <cstdlib>
#include <mutex>

#include "codegen/CodeGenLLVM.h"

namespace stc::codegen {

namespace {
void initTargets() {
  static std::once_flag once;
  std::call_once(once, [] {
    llvm::InitializeNativeTarget();
    llvm::InitializeNativeTargetAsmPrinter();
    // Machine CSE takes time quadratic in the size of a function (a program
    // body with 3000 FB calls: 30 s of 33); the IR passes (EarlyCSE, GVN)
    // already removed what it would find.  Off for the JIT and objects alike.
    auto& opts = llvm::cl::getRegisteredOptions();
    if (auto it = opts.find("disable-machine-cse"); it != opts.end()) it->second->addOccurrence(0, "disable-machine-cse", "true");
    // Developers: STC_LLVM_ARGS="-time-passes" (any LLVM option) while measuring.
    if (std::getenv("STC_LLVM_ARGS")) {
      const char* argv[] = {"stc"};
      llvm::cl::ParseCommandLineOptions(1, argv, "", nullptr, "STC_LLVM_ARGS");
    }
  });
}
}  // namespace

// The host machine: the JIT generates code for it, so the optimiser must
// know its data layout and costs (vectorisation needs them).
static std::unique_ptr<llvm::TargetMachine> hostMachine(unsigned level) {
  initTargets();
  std::string error;
  std::string triple = llvm::sys::getProcessTriple();
  const llvm::Target* target = llvm::TargetRegistry::lookupTarget(triple, error);
  if (!target) return nullptr;
  llvm::SubtargetFeatures features;
  for (auto& f : llvm::sys::getHostCPUFeatures()) features.AddFeature(f.first(), f.second);
  llvm::CodeGenOptLevel lvl = level == 0 ? llvm::CodeGenOptLevel::None : level == 1 ? llvm::CodeGenOptLevel::Less
                              : level == 2 ? llvm::CodeGenOptLevel::Default : llvm::CodeGenOptLevel::Aggressive;
  return std::unique_ptr<llvm::TargetMachine>(target->createTargetMachine(triple, llvm::sys::getHostCPUName(), features.getString(),
                                                                          llvm::TargetOptions{}, std::nullopt, std::nullopt, lvl));
}

void optimize(llvm::Module& m, unsigned level) {
  auto tm = hostMachine(level);
  if (tm) {
    m.setTargetTriple(tm->getTargetTriple().str());
    m.setDataLayout(tm->createDataLayout());
  }
  llvm::LoopAnalysisManager lam;
  llvm::FunctionAnalysisManager fam;
  llvm::CGSCCAnalysisManager cgam;
  llvm::ModuleAnalysisManager mam;
  // The standard instrumentations make the passes skip `optnone` functions
  // (deep loop nests, see kMaxOptimisedLoopDepth).
  llvm::PassInstrumentationCallbacks pic;
  llvm::StandardInstrumentations si(m.getContext(), false);
  si.registerCallbacks(pic, &mam);
  llvm::PassBuilder pb(tm.get(), llvm::PipelineTuningOptions(), std::nullopt, &pic);
  pb.registerModuleAnalyses(mam);
  pb.registerCGSCCAnalyses(cgam);
  pb.registerFunctionAnalyses(fam);
  pb.registerLoopAnalyses(lam);
  pb.crossRegisterProxies(lam, fam, cgam, mam);
  llvm::ModulePassManager mpm;
  switch (level) {
    case 0: mpm = pb.buildO0DefaultPipeline(llvm::OptimizationLevel::O0); break;
    case 1: mpm = pb.buildPerModuleDefaultPipeline(llvm::OptimizationLevel::O1); break;
    case 2: mpm = pb.buildPerModuleDefaultPipeline(llvm::OptimizationLevel::O2); break;
    default: mpm = pb.buildPerModuleDefaultPipeline(llvm::OptimizationLevel::O3); break;
  }
  mpm.run(m, mam);
}

bool emit(CompiledModule& cm, EmitKind kind, const std::string& path, std::string& error) {
  llvm::Module& m = *cm.impl().module;
  if (kind == EmitKind::LLVM) {
    if (path == "-") {
      m.print(llvm::outs(), nullptr);
      return true;
    }
    std::error_code ec;
    llvm::raw_fd_ostream os(path, ec, llvm::sys::fs::OF_Text);
    if (ec) { error = "cannot write '" + path + "': " + ec.message(); return false; }
    m.print(os, nullptr);
    return true;
  }
  initTargets();
  std::string triple = m.getTargetTriple().empty() ? llvm::sys::getDefaultTargetTriple() : m.getTargetTriple();
  const llvm::Target* target = llvm::TargetRegistry::lookupTarget(triple, error);
  if (!target) return false;
  llvm::CodeGenOptLevel lvl = cm.impl().optLevel == 0 ? llvm::CodeGenOptLevel::None
                              : cm.impl().optLevel == 1 ? llvm::CodeGenOptLevel::Less
                              : cm.impl().optLevel == 2 ? llvm::CodeGenOptLevel::Default : llvm::CodeGenOptLevel::Aggressive;
  // A generic CPU keeps objects portable.
  std::unique_ptr<llvm::TargetMachine> tm(target->createTargetMachine(triple, "x86-64", "", llvm::TargetOptions{}, llvm::Reloc::PIC_,
                                                                      std::nullopt, lvl));
  m.setTargetTriple(triple);
  m.setDataLayout(tm->createDataLayout());
  std::error_code ec;
  llvm::raw_fd_ostream os(path, ec, llvm::sys::fs::OF_None);
  if (ec) { error = "cannot write '" + path + "': " + ec.message(); return false; }
  llvm::legacy::PassManager pm;
  if (tm->addPassesToEmitFile(pm, os, nullptr, llvm::CodeGenFileType::ObjectFile)) {
    error = "the target cannot emit object files";
    return false;
  }
  pm.run(m);
  return true;
}

}  // namespace stc::codegen
