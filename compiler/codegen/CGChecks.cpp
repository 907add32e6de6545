// Runtime checks.  Each check branches to a cold block that calls a
// noreturn __stc_fault* function with the site id; the controller maps the
// site to file:line:col and stops the task (docs/vm.md, "Faults").
#include <llvm/IR/Constants.h>
#include <llvm/IR/MDBuilder.h>

#include "basic/Text.h"
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

void CodeGen::markSite(const ast::Node* at, const std::string& detail) {
  if (!siteVar_) siteVar_ = new llvm::GlobalVariable(mod_, i32_, false, llvm::GlobalValue::ExternalLinkage, nullptr, "__stc_site");
  // Volatile: the optimiser must neither drop nor move it past the access it marks.
  b_.CreateStore(b_.getInt32(site(at, detail)), siteVar_, /*isVolatile=*/true);
}

void CodeGen::checkPointerRange(llvm::Value* p, llvm::Value* bytes, const ast::Node* at) {
  b_.CreateCall(runtime("__stc_check_ptr", llvm::Type::getVoidTy(ctx_), {i32_, ptrTy_, i64_}),
                {b_.getInt32(site(at)), p, b_.CreateZExtOrTrunc(bytes, i64_)});
}

Symbol* CodeGen::implicitCheck(const char* name) {
  if (!implicitChecksFound_) {
    implicitChecksFound_ = true;
    for (Symbol* p : model_.pous) {
      if (p->kind != Symbol::Function || p->pou->owner || !p->declRange.begin.valid() || sm_.file(p->declRange.begin.file).library) continue;
      std::string up = asciiUpper(p->name);
      static const char* const kNames[] = {"CHECKBOUNDS", "CHECKRANGESIGNED", "CHECKRANGEUNSIGNED", "CHECKDIVINT", "CHECKDIVDINT",
                                           "CHECKDIVLINT", "CHECKDIVREAL", "CHECKDIVLREAL"};
      bool known = false;
      for (const char* k : kNames) known = known || up == k;
      if (!known) continue;
      // The signature CODESYS generates: scalar inputs, a scalar result of the same kind.
      const Type* rt = returnTypeOf(p);
      bool ok = rt && !isAggregate(rt) && rt->kind != TypeKind::Void && !p->pou->params.empty();
      for (Symbol* q : p->pou->params) ok = ok && q->var && q->var->section == ast::VarSection::Input && q->type && !isAggregate(q->type);
      if (ok) implicitChecks_[up] = p;
    }
  }
  // Not inside a check function: it would call itself.
  if (fs_ && fs_->pou)
    for (auto& [n, s] : implicitChecks_)
      if (s == fs_->pou) return nullptr;
  auto it = implicitChecks_.find(name);
  return it == implicitChecks_.end() ? nullptr : it->second;
}

// Calls a check function with `args` converted to its parameters; the result is
// converted back to the type of args[0].
llvm::Value* CodeGen::callImplicitCheck(Symbol* fn, std::vector<llvm::Value*> args, bool isSigned) {
  llvm::Function* f = functionFor(fn);
  llvm::FunctionType* ft = f->getFunctionType();
  llvm::Type* back = args[0]->getType();
  auto cast = [&](llvm::Value* v, llvm::Type* to) -> llvm::Value* {
    if (v->getType() == to) return v;
    if (v->getType()->isIntegerTy() && to->isIntegerTy()) return b_.CreateIntCast(v, to, isSigned);
    if (v->getType()->isFloatingPointTy() && to->isFloatingPointTy()) return b_.CreateFPCast(v, to);
    if (v->getType()->isIntegerTy() && to->isFloatingPointTy()) return isSigned ? b_.CreateSIToFP(v, to) : b_.CreateUIToFP(v, to);
    if (v->getType()->isFloatingPointTy() && to->isIntegerTy()) return isSigned ? b_.CreateFPToSI(v, to) : b_.CreateFPToUI(v, to);
    return v;
  };
  if (ft->getNumParams() != args.size()) return args[0];
  for (size_t i = 0; i < args.size(); ++i) args[i] = cast(args[i], ft->getParamType(static_cast<unsigned>(i)));
  llvm::Value* r = b_.CreateCall(f, args);
  return cast(r, back);
}

llvm::Value* CodeGen::nullChecked(llvm::Value* p, FaultKind kind, const ast::Node* at) {
  if (opts_.checks) check(b_.CreateIsNotNull(p), kind, site(at));
  return p;
}

}  // namespace stc::codegen
