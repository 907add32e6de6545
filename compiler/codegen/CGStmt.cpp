// Statements, loops and the safepoints at their back-edges.
#include <llvm/IR/Constants.h>
#include <llvm/IR/MDBuilder.h>

#include "basic/Text.h"
#include "codegen/CGInternal.h"

namespace stc::codegen {

using namespace stc::ast;

llvm::BasicBlock* CodeGen::newBlock(const char* name) { return llvm::BasicBlock::Create(ctx_, name, fs_->fn); }

bool CodeGen::blockOpen() const {
  auto* bb = b_.GetInsertBlock();
  return bb && !bb->getTerminator();
}

void CodeGen::emitStmts(const std::vector<Stmt*>& stmts) {
  for (const Stmt* s : stmts) emitStmt(s);
}

// The budget of back-edges of the running task: when it runs out, the
// scheduler may suspend the task here (docs/vm.md, "Safepoints").
void CodeGen::safepoint(const Node* at) {
  fs_->hasSafepoint = true;
  // Loops count down a local copy of the budget (kept in a register); the
  // copy meets the global at every call and return (syncBudgetAroundCalls).
  llvm::AllocaInst* slot = budgetSlot();
  llvm::Value* b = b_.CreateLoad(i64_, slot);
  llvm::Value* nb = b_.CreateSub(b, b_.getInt64(1));
  b_.CreateStore(nb, slot);
  auto* sp = newBlock("safepoint");
  auto* cont = newBlock("cont");
  llvm::MDBuilder md(ctx_);
  b_.CreateCondBr(b_.CreateICmpSLE(nb, b_.getInt64(0)), sp, cont, md.createUnlikelyBranchWeights());
  b_.SetInsertPoint(sp);
  b_.CreateCall(runtime("__stc_safepoint", llvm::Type::getVoidTy(ctx_), {i32_}), {b_.getInt32(site(at))});
  b_.CreateBr(cont);
  b_.SetInsertPoint(cont);
}

llvm::AllocaInst* CodeGen::budgetSlot() {
  if (!fs_->budget) {
    fs_->budget = fs_->allocaBuilder->CreateAlloca(i64_, nullptr, "budget");
    fs_->allocaBuilder->CreateStore(fs_->allocaBuilder->CreateLoad(i64_, budget_), fs_->budget);
  }
  return fs_->budget;
}

void CodeGen::syncBudgetAroundCalls(FnState& st) {
  if (!st.budget) return;
  std::vector<llvm::Instruction*> sites;
  for (llvm::BasicBlock& bb : *st.fn)
    for (llvm::Instruction& i : bb) {
      if (auto* call = llvm::dyn_cast<llvm::CallInst>(&i)) {
        llvm::Function* callee = call->getCalledFunction();
        if (callee && (callee->isIntrinsic() || callee->doesNotReturn())) continue;
        if (callee && callee->getName().starts_with("__stc_str")) continue;   // string helpers never suspend
        if (callee && callee->getName().starts_with("__stc_wstr")) continue;
        sites.push_back(call);
      } else if (llvm::isa<llvm::ReturnInst>(&i)) {
        sites.push_back(&i);
      }
    }
  for (llvm::Instruction* i : sites) {
    llvm::IRBuilder<> before(i);
    before.CreateStore(before.CreateLoad(i64_, st.budget), budget_);
    if (llvm::isa<llvm::CallInst>(i)) {
      llvm::IRBuilder<> after(i->getNextNode());
      after.CreateStore(after.CreateLoad(i64_, budget_), st.budget);
    }
  }
}

void CodeGen::emitStmt(const Stmt* s) {
  if (!blockOpen()) b_.SetInsertPoint(newBlock("dead"));
  debugLocation(s->range.begin);
  switch (s->kind) {
    case Stmt::Assign: {
      auto* a = cast<AssignStmt>(s);
      if (a->op == AssignStmt::Ref) {
        // REF= stores an address into the reference itself.
        Address slot = referenceSlot(a->lhs);
        if (!slot.ptr) { error(a->lhs->range, "REF= needs a reference variable"); return; }
        llvm::Value* target = referenceTarget(a->rhs);
        storeAddress(slot.ptr, slot.type, target);
        return;
      }
      if (auto* m = dyn_cast<MemberExpr>(a->lhs); m && m->symbol && m->symbol->kind == Symbol::Property) {
        emitPropertySet(a->lhs, m->symbol, a->rhs);
        return;
      }
      if (auto* n = dyn_cast<NameExpr>(a->lhs); n && n->symbol && n->symbol->kind == Symbol::Property) {
        emitPropertySet(a->lhs, n->symbol, a->rhs);
        return;
      }
      if (auto* m = dyn_cast<MemberExpr>(a->lhs); m && m->access != MemberExpr::Field) {
        llvm::Value* v = emitValue(a->rhs, a->lhs->type);
        if (a->op == AssignStmt::Set || a->op == AssignStmt::Reset) {
          auto* doIt = newBlock("sr.store");
          auto* done = newBlock("sr.done");
          b_.CreateCondBr(toBool(v), doIt, done);
          b_.SetInsertPoint(doIt);
          storeBits(m, b_.getInt1(a->op == AssignStmt::Set));
          b_.CreateBr(done);
          b_.SetInsertPoint(done);
          return;
        }
        storeBits(m, v);
        return;
      }
      if (a->op == AssignStmt::Set || a->op == AssignStmt::Reset) {
        llvm::Value* v = toBool(emitValue(a->rhs, nullptr));
        auto* doIt = newBlock("sr.store");
        auto* done = newBlock("sr.done");
        b_.CreateCondBr(v, doIt, done);
        b_.SetInsertPoint(doIt);
        store(emitAddr(a->lhs), b_.getInt1(a->op == AssignStmt::Set));
        b_.CreateBr(done);
        b_.SetInsertPoint(done);
        return;
      }
      // The target's address first (IEC evaluates the right side after?  The
      // order only matters for side effects in index expressions; CODESYS
      // evaluates the right side first).
      if (isAggregate(a->lhs->type)) {
        Address dst = emitAddr(a->lhs);
        assign(dst, a->rhs);
        return;
      }
      llvm::Value* v = emitValue(a->rhs, a->lhs->type);
      store(emitAddr(a->lhs), v);
      return;
    }
    case Stmt::ExprS: {
      auto* e = cast<ExprStmt>(s);
      if (auto* c = dyn_cast<CallExpr>(e->expr)) emitCall(c);
      else emitRaw(e->expr);
      return;
    }
    case Stmt::If: {
      auto* is = cast<IfStmt>(s);
      auto* done = newBlock("if.end");
      for (const auto& br : is->branches) {
        auto* then = newBlock("if.then");
        auto* next = newBlock("if.else");
        b_.CreateCondBr(toBool(emitValue(br.cond, elementary(TypeKind::Bool))), then, next);
        b_.SetInsertPoint(then);
        emitStmts(br.body);
        if (blockOpen()) b_.CreateBr(done);
        b_.SetInsertPoint(next);
      }
      emitStmts(is->elseBody);
      if (blockOpen()) b_.CreateBr(done);
      b_.SetInsertPoint(done);
      return;
    }
    case Stmt::Case:
      emitCase(cast<CaseStmt>(s));
      return;
    case Stmt::For:
      emitFor(cast<ForStmt>(s));
      return;
    case Stmt::While: {
      auto* w = cast<WhileStmt>(s);
      auto* head = newBlock("while.cond");
      auto* body = newBlock("while.body");
      auto* latch = newBlock("while.latch");
      auto* exit = newBlock("while.end");
      b_.CreateBr(head);
      b_.SetInsertPoint(head);
      b_.CreateCondBr(toBool(emitValue(w->cond, elementary(TypeKind::Bool))), body, exit);
      b_.SetInsertPoint(body);
      fs_->loops.push_back({latch, exit});
      fs_->maxLoopDepth = std::max(fs_->maxLoopDepth, fs_->loops.size());
      emitStmts(w->body);
      fs_->loops.pop_back();
      if (blockOpen()) b_.CreateBr(latch);
      b_.SetInsertPoint(latch);
      safepoint(w);
      b_.CreateBr(head);
      b_.SetInsertPoint(exit);
      return;
    }
    case Stmt::Repeat: {
      auto* r = cast<RepeatStmt>(s);
      auto* body = newBlock("repeat.body");
      auto* cond = newBlock("repeat.cond");
      auto* latch = newBlock("repeat.latch");
      auto* exit = newBlock("repeat.end");
      b_.CreateBr(body);
      b_.SetInsertPoint(body);
      fs_->loops.push_back({cond, exit});
      fs_->maxLoopDepth = std::max(fs_->maxLoopDepth, fs_->loops.size());
      emitStmts(r->body);
      fs_->loops.pop_back();
      if (blockOpen()) b_.CreateBr(cond);
      b_.SetInsertPoint(cond);
      b_.CreateCondBr(toBool(emitValue(r->cond, elementary(TypeKind::Bool))), exit, latch);
      b_.SetInsertPoint(latch);
      safepoint(r);
      b_.CreateBr(body);
      b_.SetInsertPoint(exit);
      return;
    }
    case Stmt::Exit:
      if (!fs_->loops.empty()) b_.CreateBr(fs_->loops.back().exit);
      return;
    case Stmt::Continue:
      if (!fs_->loops.empty()) b_.CreateBr(fs_->loops.back().cont);
      return;
    case Stmt::Return:
      b_.CreateBr(fs_->returnBlock);
      return;
    case Stmt::Jmp: {
      auto* j = cast<JmpStmt>(s);
      std::string key = asciiUpper(j->target.name);
      auto it = fs_->labels.find(key);
      if (it != fs_->labels.end() && it->second->getParent() && !it->second->empty()) {
        safepoint(j);   // a backward jump closes a loop
        b_.CreateBr(it->second);
        return;
      }
      if (it == fs_->labels.end()) it = fs_->labels.emplace(key, newBlock("label")).first;
      b_.CreateBr(it->second);
      return;
    }
    case Stmt::Label: {
      auto* l = cast<LabelStmt>(s);
      std::string key = asciiUpper(l->label.name);
      auto it = fs_->labels.find(key);
      if (it == fs_->labels.end()) it = fs_->labels.emplace(key, newBlock("label")).first;
      b_.CreateBr(it->second);
      b_.SetInsertPoint(it->second);
      if (l->stmt) emitStmt(l->stmt);
      return;
    }
    case Stmt::Empty:
      return;
  }
}

void CodeGen::storeBits(const MemberExpr* m, llvm::Value* v) {
  Address word = emitAddr(m->base);
  unsigned width = m->access == MemberExpr::PartialByte ? 8 : m->access == MemberExpr::PartialWord ? 16
                   : m->access == MemberExpr::PartialDWord ? 32 : 1;
  llvm::Value* w = load(word);
  llvm::Type* wt = w->getType();
  uint64_t shift = static_cast<uint64_t>(m->bitIndex) * width;
  llvm::APInt mask = llvm::APInt::getBitsSet(wt->getIntegerBitWidth(), static_cast<unsigned>(shift), static_cast<unsigned>(shift + width));
  llvm::Value* cleared = b_.CreateAnd(w, llvm::ConstantInt::get(wt, ~mask));
  llvm::Value* part = b_.CreateShl(b_.CreateZExt(v, wt), shift);
  store(word, b_.CreateOr(cleared, part));
}

// FOR: bounds and step are evaluated once; the trip count is computed in
// 64 bits so the loop always ends, even at the limits of the variable's
// type.  The variable holds from + count*step afterwards (docs/decisions.md).
void CodeGen::emitFor(const ForStmt* s) {
  const Type* vt = s->var->type;
  const Type* st = strip(vt);
  bool sgn = st->isSignedInt();
  Address var = emitAddr(s->var);
  auto wide = [&](const Expr* e) -> llvm::Value* {
    llvm::Value* v = emitValue(e, vt);
    return sgn ? b_.CreateSExt(v, i64_) : b_.CreateZExt(v, i64_);
  };
  llvm::Value* from = wide(s->from);
  llvm::Value* to = wide(s->to);
  llvm::Value* by = b_.getInt64(1);
  if (s->by) {
    const Type* bt = strip(s->by->type);
    llvm::Value* v = emitValue(s->by, nullptr);
    by = bt->isSignedInt() ? b_.CreateSExtOrTrunc(v, i64_) : b_.CreateZExtOrTrunc(v, i64_);
    // A zero step would never end: always a fault, even with --no-checks.
    llvm::Value* ok = b_.CreateICmpNE(by, b_.getInt64(0));
    bool saved = opts_.checks;
    const_cast<CodegenOptions&>(opts_).checks = true;
    check(ok, FaultKind::ForStepZero, site(s->by, "FOR step"));
    const_cast<CodegenOptions&>(opts_).checks = saved;
  }
  // count = by > 0 ? (to >= from ? (to - from) / by + 1 : 0) : (from >= to ? (from - to) / -by + 1 : 0)
  llvm::Value* up = b_.CreateICmpSGT(by, b_.getInt64(0));
  llvm::Value* ge = sgn ? b_.CreateICmpSGE(to, from) : b_.CreateICmpUGE(to, from);
  llvm::Value* le = sgn ? b_.CreateICmpSLE(to, from) : b_.CreateICmpULE(to, from);
  llvm::Value* span = b_.CreateSelect(up, b_.CreateSub(to, from), b_.CreateSub(from, to));
  llvm::Value* mag = b_.CreateSelect(up, by, b_.CreateNeg(by));
  llvm::Value* n = b_.CreateAdd(b_.CreateUDiv(span, mag), b_.getInt64(1));
  llvm::Value* count = b_.CreateSelect(b_.CreateSelect(up, ge, le), n, b_.getInt64(0));
  llvm::Type* narrow = valueType(st);
  // Strip-mined: the outer loop takes a chunk of at most `budget`
  // iterations, the inner loop is a plain counted loop (vectorisable, no
  // safepoint), and the safepoint is checked once per chunk.
  auto* pre = b_.GetInsertBlock();
  auto* outerHead = newBlock("for.chunk");
  auto* outerBody = newBlock("for.chunk.begin");
  auto* innerHead = newBlock("for.cond");
  auto* body = newBlock("for.body");
  auto* latch = newBlock("for.inc");
  auto* outerLatch = newBlock("for.chunk.end");
  auto* fin = newBlock("for.end");
  auto* done = newBlock("for.done");
  b_.CreateBr(outerHead);
  b_.SetInsertPoint(outerHead);
  auto* iOuter = b_.CreatePHI(i64_, 2, "for.base");
  iOuter->addIncoming(b_.getInt64(0), pre);
  llvm::Value* rem = b_.CreateSub(count, iOuter);
  b_.CreateCondBr(b_.CreateICmpEQ(rem, b_.getInt64(0)), fin, outerBody);
  b_.SetInsertPoint(innerHead);
  auto* k = b_.CreatePHI(i64_, 2, "for.i");
  b_.SetInsertPoint(body);
  store(var, b_.CreateTrunc(b_.CreateAdd(from, b_.CreateMul(k, by)), narrow));
  fs_->loops.push_back({latch, done});
  fs_->maxLoopDepth = std::max(fs_->maxLoopDepth, fs_->loops.size());
  bool hadSafepoint = fs_->hasSafepoint;
  fs_->hasSafepoint = false;
  emitStmts(s->body);
  bool innerSafepoint = fs_->hasSafepoint;
  fs_->hasSafepoint = hadSafepoint || innerSafepoint;
  fs_->loops.pop_back();
  if (blockOpen()) b_.CreateBr(latch);
  b_.SetInsertPoint(latch);
  llvm::Value* kNext = b_.CreateAdd(k, b_.getInt64(1));
  b_.CreateBr(innerHead);
  // A short constant loop without inner loops needs no safepoint at all.
  auto* cc = llvm::dyn_cast<llvm::ConstantInt>(count);
  bool budgeted = !(cc && cc->getZExtValue() <= 1024 && !innerSafepoint);
  b_.SetInsertPoint(outerBody);
  llvm::Value* chunk = rem;
  if (budgeted) {
    fs_->hasSafepoint = true;
    llvm::AllocaInst* budget = budgetSlot();
    llvm::Value* bv = b_.CreateLoad(i64_, budget);
    llvm::Value* atLeastOne = b_.CreateSelect(b_.CreateICmpSGT(bv, b_.getInt64(1)), bv, b_.getInt64(1));
    chunk = b_.CreateSelect(b_.CreateICmpULT(rem, atLeastOne), rem, atLeastOne);
    b_.CreateStore(b_.CreateSub(bv, chunk), budget);
  }
  llvm::Value* end = b_.CreateAdd(iOuter, chunk);
  b_.CreateBr(innerHead);
  k->addIncoming(iOuter, outerBody);
  k->addIncoming(kNext, latch);
  b_.SetInsertPoint(innerHead);
  b_.CreateCondBr(b_.CreateICmpULT(k, end), body, outerLatch);
  b_.SetInsertPoint(outerLatch);
  if (budgeted) {
    llvm::Value* bv = b_.CreateLoad(i64_, budgetSlot());
    auto* sp = newBlock("safepoint");
    auto* cont = newBlock("cont");
    llvm::MDBuilder md(ctx_);
    b_.CreateCondBr(b_.CreateICmpSLE(bv, b_.getInt64(0)), sp, cont, md.createUnlikelyBranchWeights());
    b_.SetInsertPoint(sp);
    b_.CreateCall(runtime("__stc_safepoint", llvm::Type::getVoidTy(ctx_), {i32_}), {b_.getInt32(site(s))});
    b_.CreateBr(cont);
    b_.SetInsertPoint(cont);
  }
  iOuter->addIncoming(end, b_.GetInsertBlock());
  b_.CreateBr(outerHead);
  // After normal completion the variable is from + count*by, as CODESYS
  // shows; after EXIT it keeps the value of the last iteration.
  b_.SetInsertPoint(fin);
  store(var, b_.CreateTrunc(b_.CreateAdd(from, b_.CreateMul(count, by)), narrow));
  b_.CreateBr(done);
  b_.SetInsertPoint(done);
}

void CodeGen::emitCase(const CaseStmt* s) {
  const Type* selT = s->selector->type;
  llvm::Value* sel = emitValue(s->selector, nullptr);
  bool sgn = strip(selT)->isSignedInt();
  auto* done = newBlock("case.end");
  auto* dflt = newBlock("case.else");
  std::vector<llvm::BasicBlock*> bodies;
  for (size_t k = 0; k < s->elements.size(); ++k) bodies.push_back(newBlock("case.body"));
  // Large ranges become compares before the switch.
  auto* cmpBlock = b_.GetInsertBlock();
  std::vector<std::pair<llvm::ConstantInt*, llvm::BasicBlock*>> cases;
  std::vector<std::tuple<llvm::Constant*, llvm::Constant*, llvm::BasicBlock*>> ranges;
  for (size_t k = 0; k < s->elements.size(); ++k)
    for (const auto& lab : s->elements[k].labels) {
      llvm::Constant* lo = nullptr;
      llvm::Constant* hi = nullptr;
      if (!foldScalar(lab.lo, selT, lo)) { error(lab.lo->range, "CASE label must be a constant"); continue; }
      if (lab.hi && !foldScalar(lab.hi, selT, hi)) { error(lab.hi->range, "CASE label must be a constant"); continue; }
      auto* l = llvm::dyn_cast<llvm::ConstantInt>(lo);
      auto* h = hi ? llvm::dyn_cast<llvm::ConstantInt>(hi) : nullptr;
      if (!l) continue;
      if (!h) { cases.push_back({l, bodies[k]}); continue; }
      int64_t a = sgn ? l->getSExtValue() : static_cast<int64_t>(l->getZExtValue());
      int64_t z = sgn ? h->getSExtValue() : static_cast<int64_t>(h->getZExtValue());
      if (z >= a && z - a < 64) {
        for (int64_t v = a; v <= z; ++v) cases.push_back({llvm::ConstantInt::get(llvm::cast<llvm::IntegerType>(sel->getType()), static_cast<uint64_t>(v), sgn), bodies[k]});
      } else {
        ranges.push_back({l, h, bodies[k]});
      }
    }
  b_.SetInsertPoint(cmpBlock);
  for (auto& [lo, hi, target] : ranges) {
    llvm::Value* in = sgn ? b_.CreateAnd(b_.CreateICmpSGE(sel, lo), b_.CreateICmpSLE(sel, hi))
                          : b_.CreateAnd(b_.CreateICmpUGE(sel, lo), b_.CreateICmpULE(sel, hi));
    auto* next = newBlock("case.next");
    b_.CreateCondBr(in, target, next);
    b_.SetInsertPoint(next);
  }
  auto* sw = b_.CreateSwitch(sel, dflt, static_cast<unsigned>(cases.size()));
  std::set<uint64_t> seen;
  for (auto& [v, target] : cases)
    if (seen.insert(v->getZExtValue()).second) sw->addCase(v, target);
  for (size_t k = 0; k < s->elements.size(); ++k) {
    b_.SetInsertPoint(bodies[k]);
    emitStmts(s->elements[k].body);
    if (blockOpen()) b_.CreateBr(done);
  }
  b_.SetInsertPoint(dflt);
  emitStmts(s->elseBody);
  if (blockOpen()) b_.CreateBr(done);
  b_.SetInsertPoint(done);
}

// The storage of a REFERENCE TO variable itself (not of what it refers to),
// or a null Address when `e` does not name one.
Address CodeGen::referenceSlot(const Expr* e) {
  if (auto* n = dyn_cast<NameExpr>(e); n && n->symbol && n->symbol->var) {
    const Symbol* sym = n->symbol->aliasOf ? n->symbol->aliasOf : n->symbol;
    if (!sym->var->resolvedType || !sym->var->resolvedType->isReference()) return {};
    if (fs_->localDecls.count(sym->var)) return fs_->localDecls[sym->var];
    if (imageOffsets_.count(sym->var)) return Address{imageAddr(imageOffsets_[sym->var]), sym->var->resolvedType};
    if (fs_->self && fs_->selfType)
      if (const sema::FieldLayout* f = layout_.field(fs_->selfType, sym->var))
        return Address{b_.CreateConstInBoundsGEP1_64(i8_, fs_->self, f->offset), f->type};
  } else if (auto* m = dyn_cast<MemberExpr>(e); m && m->symbol && m->symbol->var) {
    if (!m->symbol->var->resolvedType || !m->symbol->var->resolvedType->isReference()) return {};
    const Type* bt = strip(m->base->type);
    if (const sema::FieldLayout* f = layout_.field(bt, m->symbol->var))
      return Address{b_.CreateConstInBoundsGEP1_64(i8_, instancePtr(m->base), f->offset), f->type};
  }
  return {};
}

// The address a reference is bound to by `REF= e` (or at its declaration):
// 0 is null, a pointer its value, another reference its binding (copied as
// is, also when unbound), anything else the variable's address.
llvm::Value* CodeGen::referenceTarget(const Expr* e) {
  if (auto* lit = dyn_cast<LiteralExpr>(e); lit && lit->litKind == LiteralExpr::Int) return llvm::ConstantPointerNull::get(ptrTy_);
  if (e->type && (e->type->isPointer() || e->type->kind == TypeKind::Null)) return emitValue(e, nullptr);
  if (Address slot = referenceSlot(e); slot.ptr) return loadAddress(slot.ptr, slot.type);
  return emitAddr(e).ptr;
}

}  // namespace stc::codegen
