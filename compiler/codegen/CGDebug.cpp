// -g: DWARF line tables that map machine code to ST lines.  One compile
// unit for the module, a DIFile per source file, a DISubprogram per POU and
// a location per statement.  Fault reports never use DWARF (they use the
// site table); this is for debuggers and profilers.
#include <llvm/BinaryFormat/Dwarf.h>
#include <llvm/IR/DebugInfoMetadata.h>

#include <filesystem>

#include "codegen/CGInternal.h"

namespace stc::codegen {

llvm::DIFile* CodeGen::debugFile(uint32_t fileId) {
  auto it = diFiles_.find(fileId);
  if (it != diFiles_.end()) return it->second;
  std::string path = fileId ? sm_.file(fileId).path : "<unknown>";
  std::filesystem::path p(path);
  std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
  llvm::DIFile* f = di_->createFile(p.filename().string(), dir);
  diFiles_[fileId] = f;
  return f;
}

void CodeGen::beginDebugInfo() {
  if (!opts_.debugInfo) return;
  di_ = std::make_unique<llvm::DIBuilder>(mod_);
  uint32_t first = 0;
  for (Symbol* p : model_.pous)
    if (p->declRange.begin.file && (!first || p->declRange.begin.file > first)) first = p->declRange.begin.file;
  // DW_LANG_C99 lets gdb print values; there is no DWARF code for ST.
  cu_ = di_->createCompileUnit(llvm::dwarf::DW_LANG_C99, debugFile(first), "stc", opts_.optLevel > 0, "", 0);
  mod_.addModuleFlag(llvm::Module::Warning, "Debug Info Version", llvm::DEBUG_METADATA_VERSION);
  mod_.addModuleFlag(llvm::Module::Warning, "Dwarf Version", 5);
}

void CodeGen::finishDebugInfo() {
  if (di_) di_->finalize();
}

llvm::DISubprogram* CodeGen::debugFunction(llvm::Function* f, Symbol* pou) {
  if (!di_) return nullptr;
  SourceLoc at = pou->declRange.begin;
  llvm::DIFile* file = debugFile(at.file);
  unsigned line = at.valid() ? sm_.lineCol(at).line : 0;
  auto* type = di_->createSubroutineType(di_->getOrCreateTypeArray({}));
  auto* sp = di_->createFunction(file, pou->name, f->getName(), file, line, type, line, llvm::DINode::FlagZero,
                                 llvm::DISubprogram::SPFlagDefinition | (f->hasLocalLinkage() ? llvm::DISubprogram::SPFlagLocalToUnit
                                                                                               : llvm::DISubprogram::SPFlagZero));
  f->setSubprogram(sp);
  return sp;
}

void CodeGen::debugLocation(SourceLoc loc) {
  if (!di_ || !fs_ || !fs_->sp || !loc.valid()) return;
  LineCol lc = sm_.lineCol(loc);
  b_.SetCurrentDebugLocation(llvm::DILocation::get(ctx_, lc.line, lc.col, fs_->sp));
}

}  // namespace stc::codegen
