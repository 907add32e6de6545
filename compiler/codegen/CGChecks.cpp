// Runtime checks.  Each check branches to a cold block that calls a
// noreturn __stc_fault* function with the site id; the controller maps the
// site to file:line:col and stops the task (docs/vm.md, "Faults").
#include <llvm/IR/Constants.h>
#include <llvm/IR/MDBuilder.h>

#include "codegen/CGInternal.h"

namespace stc::codegen {

uint32_t CodeGen::site(const ast::Node* n, std::string detail) { return site(n ? n->range : SourceRange{}, std::move(detail)); }

uint32_t CodeGen::site(SourceRange r, std::string detail) {
  Site s;
  s.range = r;
  s.detail = std::move(detail);
  if (fs_ && fs_->pou) s.pou = fs_->pou->pou && fs_->pou->pou->owner ? fs_->pou->pou->owner->name + "." + fs_->pou->name : fs_->pou->name;
  out_.sites.push_back(std::move(s));
  return static_cast<uint32_t>(out_.sites.size() - 1);
}

llvm::FunctionCallee CodeGen::runtime(const char* name, llvm::Type* ret, llvm::ArrayRef<llvm::Type*> params, bool noreturn) {
  llvm::FunctionCallee f = mod_.getOrInsertFunction(name, llvm::FunctionType::get(ret, params, false));
  if (auto* fn = llvm::dyn_cast<llvm::Function>(f.getCallee())) {
    fn->addFnAttr(llvm::Attribute::NoUnwind);
    if (noreturn) {
      fn->addFnAttr(llvm::Attribute::NoReturn);
      fn->addFnAttr(llvm::Attribute::Cold);
    }
  }
  return f;
}

void CodeGen::check(llvm::Value* ok, FaultKind kind, uint32_t s) {
  if (!opts_.checks) return;
  if (auto* c = llvm::dyn_cast<llvm::ConstantInt>(ok); c && c->isOne()) return;
  auto* fail = newBlock("check.fail");
  auto* cont = newBlock("check.ok");
  llvm::MDBuilder md(ctx_);
  b_.CreateCondBr(ok, cont, fail, md.createLikelyBranchWeights());
  b_.SetInsertPoint(fail);
  b_.CreateCall(runtime("__stc_fault", llvm::Type::getVoidTy(ctx_), {i32_, i32_}, true), {b_.getInt32(s), b_.getInt32(static_cast<uint32_t>(kind))});
  b_.CreateUnreachable();
  b_.SetInsertPoint(cont);
}

void CodeGen::checkIndex(llvm::Value* idx, int64_t lo, int64_t hi, uint32_t s) {
  llvm::Value* rel = b_.CreateSub(idx, b_.getInt64(static_cast<uint64_t>(lo)));
  llvm::Value* ok = b_.CreateICmpULE(rel, b_.getInt64(static_cast<uint64_t>(hi - lo)));
  if (auto* c = llvm::dyn_cast<llvm::ConstantInt>(ok); c && c->isOne()) return;
  auto* fail = newBlock("index.fail");
  auto* cont = newBlock("index.ok");
  llvm::MDBuilder md(ctx_);
  b_.CreateCondBr(ok, cont, fail, md.createLikelyBranchWeights());
  b_.SetInsertPoint(fail);
  b_.CreateCall(runtime("__stc_fault_index", llvm::Type::getVoidTy(ctx_), {i32_, i64_, i64_, i64_}, true),
                {b_.getInt32(s), idx, b_.getInt64(static_cast<uint64_t>(lo)), b_.getInt64(static_cast<uint64_t>(hi))});
  b_.CreateUnreachable();
  b_.SetInsertPoint(cont);
}

llvm::Value* CodeGen::checkedDivisor(llvm::Value* d, const ast::Node* at) {
  llvm::Value* nz = b_.CreateICmpNE(d, llvm::ConstantInt::get(d->getType(), 0));
  if (opts_.checks) {
    uint32_t s;
    if (auto* b = dynamic_cast<const ast::BinaryExpr*>(at)) {
      // Point at the operator, as the compile-time check does.
      s = site(b->range, b->op == ast::BinaryOp::Mod ? "MOD" : "");
      out_.sites[s].loc = b->opLoc;
    } else {
      s = site(at);
    }
    check(nz, FaultKind::DivisionByZero, s);
    return d;
  }
  // Without checks a zero divisor must still not raise SIGFPE: divide by 1.
  return b_.CreateSelect(nz, d, llvm::ConstantInt::get(d->getType(), 1));
}

llvm::Value* CodeGen::nullChecked(llvm::Value* p, FaultKind kind, const ast::Node* at) {
  if (opts_.checks) check(b_.CreateIsNotNull(p), kind, site(at));
  return p;
}

}  // namespace stc::codegen
