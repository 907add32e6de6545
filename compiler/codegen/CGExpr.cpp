// Expressions: values, lvalues, conversions, operators.
#include <llvm/IR/Constants.h>
#include <llvm/IR/Intrinsics.h>

#include "basic/Text.h"
#include "codegen/CGInternal.h"

namespace stc::codegen {

using namespace stc::ast;

Address CodeGen::temporary(const Type* t, const char* name) {
  llvm::Type* mt = memType(t);
  auto* a = fs_->allocaBuilder->CreateAlloca(mt, nullptr, name);
  a->setAlignment(llvm::Align(std::max<uint64_t>(alignOf(t), 1)));
  return Address{a, t};
}

// ------------------------------------------------------------------ memory

llvm::Value* CodeGen::load(Address a) {
  const Type* t = strip(a.type);
  if (a.bit >= 0) {
    llvm::Value* byte = b_.CreateLoad(i8_, a.ptr);
    return b_.CreateTrunc(b_.CreateLShr(byte, static_cast<uint64_t>(a.bit)), i1_);
  }
  if (isAggregate(t)) return a.ptr;
  if (narrowSlot(t)) return loadAddress(a.ptr, t);
  auto* l = b_.CreateAlignedLoad(memType(t), a.ptr, llvm::MaybeAlign(alignOf(t)));
  if (t->isBool()) return b_.CreateICmpNE(l, llvm::ConstantInt::get(i8_, 0));
  return l;
}

void CodeGen::store(Address a, llvm::Value* v) {
  const Type* t = strip(a.type);
  if (a.bit >= 0) {
    llvm::Value* byte = b_.CreateLoad(i8_, a.ptr);
    uint8_t mask = static_cast<uint8_t>(1u << a.bit);
    llvm::Value* cleared = b_.CreateAnd(byte, llvm::ConstantInt::get(i8_, static_cast<uint8_t>(~mask)));
    llvm::Value* bit = b_.CreateShl(b_.CreateZExt(v, i8_), static_cast<uint64_t>(a.bit));
    b_.CreateStore(b_.CreateOr(cleared, bit), a.ptr);
    return;
  }
  if (t->isBool()) v = b_.CreateZExt(v, i8_);
  if (narrowSlot(t)) return storeAddress(a.ptr, t, v);
  b_.CreateAlignedStore(v, a.ptr, llvm::MaybeAlign(alignOf(t)));
}

bool CodeGen::narrowSlot(const Type* t) const {
  t = t ? strip(t) : nullptr;
  return t && (t->isPointer() || t->isReference()) && !t->wide;
}

// The program's memory lies below 4 GiB in the 32-bit model (vm/Jit.cpp, vm/Fiber.cpp),
// so the 32-bit slot holds the whole address.
llvm::Value* CodeGen::loadAddress(llvm::Value* slot, const Type* slotType) {
  if (!narrowSlot(slotType)) return b_.CreateAlignedLoad(ptrTy_, slot, llvm::MaybeAlign(8));
  llvm::Value* a = b_.CreateAlignedLoad(i32_, slot, llvm::MaybeAlign(4));
  return b_.CreateIntToPtr(b_.CreateZExt(a, i64_), ptrTy_);
}

void CodeGen::storeAddress(llvm::Value* slot, const Type* slotType, llvm::Value* p) {
  if (!narrowSlot(slotType)) { b_.CreateAlignedStore(p, slot, llvm::MaybeAlign(8)); return; }
  if (p->getType()->isPointerTy()) p = b_.CreatePtrToInt(p, i64_);
  b_.CreateAlignedStore(b_.CreateZExtOrTrunc(p, i32_), slot, llvm::MaybeAlign(4));
}

// ------------------------------------------------------------------ conversions

llvm::Value* CodeGen::toBool(llvm::Value* v) {
  if (v->getType() == i1_) return v;
  if (v->getType()->isFloatingPointTy()) return b_.CreateFCmpUNE(v, llvm::ConstantFP::get(v->getType(), 0.0));
  if (v->getType()->isPointerTy()) return b_.CreateIsNotNull(v);
  return b_.CreateICmpNE(v, llvm::ConstantInt::get(v->getType(), 0));
}

static bool isTimeKind(const Type* t) { return t->isDuration() || t->isDate(); }

static int64_t timeUnitNs(const Type* t) {
  switch (t->kind) {
    case TypeKind::Time: case TypeKind::Tod: return 1'000'000;
    case TypeKind::Date: case TypeKind::DT: return 1'000'000'000;
    default: return 1;
  }
}

llvm::Value* CodeGen::convert(llvm::Value* v, const Type* from, const Type* to, const Expr* at) {
  if (!to || !from || !v) return v;
  const Type* f = strip(from);
  const Type* t = strip(to);
  if (isAggregate(t) || isAggregate(f)) return v;
  llvm::Type* dt = valueType(t);
  llvm::Value* r = v;
  if (f->kind == TypeKind::Null || dt->isPointerTy()) {
    if (v->getType()->isPointerTy()) r = v;
    else if (v->getType()->isIntegerTy()) r = b_.CreateIntToPtr(v, ptrTy_);
  } else if (v->getType()->isPointerTy()) {
    r = b_.CreatePtrToInt(v, dt->isIntegerTy() ? dt : i64_);
  } else if (t->isBool()) {
    r = toBool(v);
  } else if (dt->isFloatingPointTy()) {
    if (v->getType()->isFloatingPointTy()) r = b_.CreateFPCast(v, dt);
    else if (isTimeKind(f)) {
      // TIME_TO_REAL counts the type's unit (ms for TIME, s for DATE ...).
      r = b_.CreateFDiv(b_.CreateSIToFP(v, dt), llvm::ConstantFP::get(dt, static_cast<double>(timeUnitNs(f))));
    }
    else if (v->getType() == i1_ || !f->isSignedInt()) r = b_.CreateUIToFP(v, dt);
    else r = b_.CreateSIToFP(v, dt);
  } else if (dt->isIntegerTy()) {
    if (v->getType()->isFloatingPointTy() && isTimeKind(t)) {
      llvm::Type* d = llvm::Type::getDoubleTy(ctx_);
      llvm::Value* scaled = b_.CreateFMul(b_.CreateFPExt(v, d), llvm::ConstantFP::get(d, static_cast<double>(timeUnitNs(t))));
      r = b_.CreateIntrinsic(llvm::Intrinsic::fptosi_sat, {dt, d}, {b_.CreateUnaryIntrinsic(llvm::Intrinsic::round, scaled)});
    } else if (v->getType()->isFloatingPointTy()) {
      // IEC: REAL to integer rounds, halves away from zero; saturating, NaN -> 0.
      llvm::Value* rounded = b_.CreateUnaryIntrinsic(llvm::Intrinsic::round, v);
      auto id = t->isSignedInt() || isTimeKind(t) ? llvm::Intrinsic::fptosi_sat : llvm::Intrinsic::fptoui_sat;
      r = b_.CreateIntrinsic(id, {dt, v->getType()}, {rounded});
    } else {
      // Integers count the unit CODESYS uses for the type: TIME and TOD in
      // ms, DATE and DT in s, the L* types in ns (docs/decisions.md).
      if (isTimeKind(t) && !isTimeKind(f) && f->isElementary()) {
        r = b_.CreateMul(f->isSignedInt() ? b_.CreateSExtOrTrunc(v, i64_) : b_.CreateZExtOrTrunc(v, i64_), b_.getInt64(timeUnitNs(t)));
      } else if (isTimeKind(f) && !isTimeKind(t)) {
        r = b_.CreateIntCast(b_.CreateSDiv(v, b_.getInt64(timeUnitNs(f))), dt, true);
      } else if (isTimeKind(f) && isTimeKind(t)) {
        // DT -> DATE / TOD keep the date or time-of-day part.
        const int64_t day = 86'400'000'000'000;
        if ((f->kind == TypeKind::DT || f->kind == TypeKind::LDT) && (t->kind == TypeKind::Date || t->kind == TypeKind::LDate))
          r = b_.CreateMul(b_.CreateSDiv(v, b_.getInt64(day)), b_.getInt64(day));
        else if ((f->kind == TypeKind::DT || f->kind == TypeKind::LDT) && (t->kind == TypeKind::Tod || t->kind == TypeKind::LTod))
          r = b_.CreateSRem(v, b_.getInt64(day));
        else r = v;
      } else {
        bool isSigned = v->getType() != i1_ && f->isSignedInt();
        r = b_.CreateIntCast(v, dt, isSigned);
      }
    }
  }
  // Subrange targets are checked on the way in (first by the program's own check function).
  if (to->kind == TypeKind::Subrange && r->getType()->isIntegerTy() && at) {
    bool sgn = strip(to)->isSignedInt();
    if (Symbol* cr = implicitCheck(sgn ? "CHECKRANGESIGNED" : "CHECKRANGEUNSIGNED"))
      r = callImplicitCheck(cr, {r, llvm::ConstantInt::get(r->getType(), static_cast<uint64_t>(to->lo), sgn),
                                 llvm::ConstantInt::get(r->getType(), static_cast<uint64_t>(to->hi), sgn)}, sgn);
  }
  if (to->kind == TypeKind::Subrange && opts_.checks && r->getType()->isIntegerTy() && at) {
    const Type* base = strip(to);
    bool sgn = base->isSignedInt();
    llvm::Value* lo = llvm::ConstantInt::get(r->getType(), static_cast<uint64_t>(to->lo), sgn);
    llvm::Value* hi = llvm::ConstantInt::get(r->getType(), static_cast<uint64_t>(to->hi), sgn);
    llvm::Value* ok = sgn ? b_.CreateAnd(b_.CreateICmpSGE(r, lo), b_.CreateICmpSLE(r, hi))
                          : b_.CreateAnd(b_.CreateICmpUGE(r, lo), b_.CreateICmpULE(r, hi));
    uint32_t s = site(at, to->name + " (" + std::to_string(to->lo) + ".." + std::to_string(to->hi) + ")");
    if (auto* c = llvm::dyn_cast<llvm::ConstantInt>(ok); !(c && c->isOne())) {
      auto* fail = newBlock("range.fail");
      auto* cont = newBlock("range.ok");
      b_.CreateCondBr(ok, cont, fail);
      b_.SetInsertPoint(fail);
      b_.CreateCall(runtime("__stc_fault_range", llvm::Type::getVoidTy(ctx_), {i32_, i64_, i64_, i64_}, true),
                    {b_.getInt32(s), sgn ? b_.CreateSExt(r, i64_) : b_.CreateZExt(r, i64_), b_.getInt64(static_cast<uint64_t>(to->lo)),
                     b_.getInt64(static_cast<uint64_t>(to->hi))});
      b_.CreateUnreachable();
      b_.SetInsertPoint(cont);
    }
  }
  return r;
}

// ------------------------------------------------------------------ literals

llvm::Value* CodeGen::constantValue(const LiteralExpr* lit, const Type* t) {
  const Type* s = strip(t ? t : lit->type);
  llvm::Type* vt = valueType(s);
  switch (lit->litKind) {
    case LiteralExpr::Real:
      if (vt->isFloatingPointTy()) return llvm::ConstantFP::get(vt, lit->realValue);   // the parser already applied the sign
      return llvm::ConstantFP::get(llvm::Type::getDoubleTy(ctx_), lit->realValue);
    case LiteralExpr::Bool:
      if (vt == i1_) return llvm::ConstantInt::get(i1_, lit->intValue != 0);
      return llvm::ConstantInt::get(vt, lit->intValue != 0);
    case LiteralExpr::String: case LiteralExpr::WString:
      return nullptr;
    default: {
      int64_t v = static_cast<int64_t>(lit->negative ? 0 - lit->intValue : lit->intValue);   // two's complement, no overflow
      if (vt->isFloatingPointTy()) return llvm::ConstantFP::get(vt, static_cast<double>(v));
      if (vt->isPointerTy()) return llvm::ConstantPointerNull::get(ptrTy_);
      if (vt == i1_) return llvm::ConstantInt::get(i1_, v != 0);
      if (!vt->isIntegerTy()) return llvm::ConstantInt::get(i64_, static_cast<uint64_t>(v));
      return llvm::ConstantInt::get(vt, static_cast<uint64_t>(v), true);
    }
  }
}

llvm::Value* CodeGen::emitStringLiteral(const LiteralExpr* lit, const Type* t) {
  bool wide = lit->litKind == LiteralExpr::WString || (t && strip(t)->kind == TypeKind::WString);
  std::string bytes = literalBytes(lit, wide);
  std::string key = (wide ? "W" : "S") + bytes;
  auto it = stringLits_.find(key);
  if (it != stringLits_.end()) return it->second;
  bytes.push_back('\0');
  if (wide) bytes.push_back('\0');
  auto* arr = llvm::ConstantDataArray::get(ctx_, llvm::ArrayRef<uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  auto* g = new llvm::GlobalVariable(mod_, arr->getType(), true, llvm::GlobalValue::PrivateLinkage, arr, "str");
  g->setUnnamedAddr(llvm::GlobalValue::UnnamedAddr::Global);
  g->setAlignment(llvm::Align(wide ? 2 : 1));
  stringLits_[key] = g;
  return g;
}

// ------------------------------------------------------------------ names

Address CodeGen::varAddr(const Symbol* s, const Expr* at) {
  if (s->aliasOf) s = s->aliasOf;
  if (fs_) {
    auto it = fs_->locals.find(s);
    if (it != fs_->locals.end()) return it->second;
  }
  const VarDecl* v = s->var;
  if (!v) {
    error(at ? at->range : SourceRange{}, "internal: no storage for '" + s->name + "'");
    return Address{llvm::ConstantPointerNull::get(ptrTy_), s->type};
  }
  Address a;
  if (fs_) {
    auto it = fs_->localDecls.find(v);
    if (it != fs_->localDecls.end()) a = it->second;
  }
  if (!a.ptr) {
    if (auto vi = atViews_.find(v); vi != atViews_.end()) {
      const DirectLocation& loc = vi->second;
      return directAddress(std::string("%") + loc.area + (loc.bit >= 0 ? "X" + std::to_string(loc.byteOffset) + "." + std::to_string(loc.bit)
                                                                         : "B" + std::to_string(loc.byteOffset)),
                           s->type);
    }
  }
  if (!a.ptr) {
    if (auto it = imageOffsets_.find(v); it != imageOffsets_.end()) a = Address{imageAddr(it->second), v->resolvedType};
  }
  if (!a.ptr && fs_ && fs_->self && fs_->selfType) {
    if (const sema::FieldLayout* f = layout_.field(fs_->selfType, v)) {
      llvm::Value* p = b_.CreateConstInBoundsGEP1_64(i8_, fs_->self, f->offset);
      if (f->indirect) {
        // VAR_IN_OUT of an FB: the field holds the bound variable's address.
        llvm::Value* bound = b_.CreateAlignedLoad(ptrTy_, p, llvm::MaybeAlign(8));
        if (opts_.checks)
          check(b_.CreateIsNotNull(bound), FaultKind::UnboundInOut,
                site(at ? at->range : SourceRange{}, "'" + s->name + "' of '" + fs_->selfType->name + "'"));
        return Address{bound, f->type};
      }
      a = Address{p, f->type};
    }
  }
  if (!a.ptr) {
    error(at ? at->range : v->name.range, "internal: cannot locate variable '" + s->name + "'");
    return Address{llvm::ConstantPointerNull::get(ptrTy_), s->type};
  }
  // REFERENCE TO variables dereference implicitly.
  if (a.type && a.type->isReference()) {
    llvm::Value* p = loadAddress(a.ptr, a.type);
    return Address{nullChecked(p, FaultKind::NullReference, at), a.type->element};
  }
  return a;
}

Address CodeGen::directAddress(const std::string& text, const Type* t) {
  DirectLocation loc;
  if (!parseDirectAddress(text, loc)) return Address{llvm::ConstantPointerNull::get(ptrTy_), t};
  const ImageMap& im = out_.image;
  uint64_t base = loc.area == 'I' ? im.inputOffset : loc.area == 'Q' ? im.outputOffset : im.memoryOffset;
  uint64_t size = loc.area == 'I' ? im.inputSize : loc.area == 'Q' ? im.outputSize : im.memorySize;
  uint64_t end = loc.byteOffset + std::max<uint64_t>(loc.bytes, sizeOf(t));
  if (end > size) {
    error(SourceRange{}, "direct address " + text + " is beyond the %" + std::string(1, loc.area) + " area (" + std::to_string(size) +
                             " bytes); declare a variable AT it to enlarge the area");
    return Address{llvm::ConstantPointerNull::get(ptrTy_), t};
  }
  if (loc.area == 'I') out_.image.inputUsed = std::max(out_.image.inputUsed, end);
  if (loc.area == 'Q') out_.image.outputUsed = std::max(out_.image.outputUsed, end);
  llvm::Value* p = imageAddr(base + loc.byteOffset);
  if (loc.bit >= 0 && strip(t)->isBool()) return Address{p, t, loc.bit};
  return Address{p, t};
}

bool CodeGen::isOpenArray(const Type* t) {
  t = strip(t);
  if (!t || t->kind != TypeKind::Array) return false;
  for (const sema::Dim& d : t->dims)
    if (d.star) return true;
  return false;
}

llvm::Value* CodeGen::arrayDescriptor(const Expr* array) {
  const Type* at = strip(array->type);
  Address a = emitAddr(array);
  if (isOpenArray(at)) return a.ptr;   // passed on: the descriptor itself
  auto* ty = llvm::ArrayType::get(i64_, 1 + 2 * at->dims.size());
  auto* desc = fs_->allocaBuilder->CreateAlloca(ty, nullptr, "desc");
  b_.CreateAlignedStore(a.ptr, desc, llvm::MaybeAlign(8));
  for (size_t k = 0; k < at->dims.size(); ++k) {
    b_.CreateAlignedStore(b_.getInt64(static_cast<uint64_t>(at->dims[k].lo)), b_.CreateConstInBoundsGEP1_64(i64_, desc, 1 + 2 * k), llvm::MaybeAlign(8));
    b_.CreateAlignedStore(b_.getInt64(static_cast<uint64_t>(at->dims[k].hi)), b_.CreateConstInBoundsGEP1_64(i64_, desc, 2 + 2 * k), llvm::MaybeAlign(8));
  }
  return desc;
}

llvm::Value* CodeGen::instancePtr(const Expr* e) {
  if (auto* n = dyn_cast<NameExpr>(e); n && n->symbol && n->symbol->kind == Symbol::Program)
    return imageAddr(programOffsets_[n->symbol]);
  if (auto* m = dyn_cast<MemberExpr>(e); m && m->symbol && m->symbol->kind == Symbol::Program)
    return imageAddr(programOffsets_[m->symbol]);
  return emitAddr(e).ptr;
}

// ------------------------------------------------------------------ lvalues

Address CodeGen::emitAddr(const Expr* e) {
  switch (e->kind) {
    case Expr::Name: {
      auto* n = cast<NameExpr>(e);
      Symbol* s = n->symbol;
      if (s && s->kind == Symbol::Variable) return varAddr(s, e);
      if (s && s->kind == Symbol::Program) return Address{imageAddr(programOffsets_[s]), s->type};
      break;
    }
    case Expr::Member: {
      auto* m = cast<MemberExpr>(e);
      if (m->access != MemberExpr::Field) break;
      Symbol* s = m->symbol;
      if (s && s->kind == Symbol::Program) return Address{imageAddr(programOffsets_[s]), s->type};
      const Type* bt = m->base->type ? strip(m->base->type) : nullptr;
      // GVL.x, Namespace.x
      if (s && s->kind == Symbol::Variable && (!bt || bt->kind == TypeKind::Void)) return varAddr(s, e);
      if (!bt) break;
      if (bt->isReference()) bt = strip(bt->element);
      llvm::Value* base = instancePtr(m->base);
      const sema::FieldLayout* f = nullptr;
      if (s && s->var && (bt->kind == TypeKind::FunctionBlock || bt->kind == TypeKind::Program)) f = layout_.field(bt, s->var);
      if (!f) f = layout_.field(bt, m->member.name);
      if (!f) break;
      llvm::Value* p = b_.CreateConstInBoundsGEP1_64(i8_, base, f->offset);
      if (f->indirect) {
        llvm::Value* bound = b_.CreateAlignedLoad(ptrTy_, p, llvm::MaybeAlign(8));
        if (opts_.checks) check(b_.CreateIsNotNull(bound), FaultKind::UnboundInOut, site(e->range, "'" + f->name + "' of '" + bt->name + "'"));
        return Address{bound, f->type};
      }
      Address a{p, f->type, f->bit};
      if (f->type && f->type->isReference()) {
        llvm::Value* r = loadAddress(p, f->type);
        return Address{nullChecked(r, FaultKind::NullReference, e), f->type->element};
      }
      return a;
    }
    case Expr::Index: {
      auto* ix = cast<IndexExpr>(e);
      Address base = emitAddr(ix->base);
      const Type* bt = strip(base.type);
      if (bt->isString()) {
        bool wide = bt->kind == TypeKind::WString;
        llvm::Value* i = emitValue(ix->indices[0], elementary(TypeKind::LInt));
        // CODESYS: s[i] is the byte at 0-based position i.
        if (opts_.checks) checkIndex(i, 0, bt->length, site(ix->indices[0], "string"));
        const Type* et = elementary(wide ? TypeKind::Word : TypeKind::Byte);
        return Address{b_.CreateInBoundsGEP(wide ? i16_ : i8_, base.ptr, i), et};
      }
      if (bt->kind != TypeKind::Array) break;
      if (isOpenArray(bt)) {
        // Bounds from the descriptor; row-major with run-time extents.
        llvm::Value* desc = base.ptr;
        llvm::Value* data = b_.CreateAlignedLoad(ptrTy_, desc, llvm::MaybeAlign(8));
        uint64_t es = sizeOf(bt->element);
        es = (es + alignOf(bt->element) - 1) / alignOf(bt->element) * alignOf(bt->element);
        llvm::Value* linear = b_.getInt64(0);
        for (size_t k = 0; k < bt->dims.size() && k < ix->indices.size(); ++k) {
          llvm::Value* lo = b_.CreateAlignedLoad(i64_, b_.CreateConstInBoundsGEP1_64(i64_, desc, 1 + 2 * k), llvm::MaybeAlign(8));
          llvm::Value* hi = b_.CreateAlignedLoad(i64_, b_.CreateConstInBoundsGEP1_64(i64_, desc, 2 + 2 * k), llvm::MaybeAlign(8));
          llvm::Value* i = emitValue(ix->indices[k], elementary(TypeKind::LInt));
          llvm::Value* rel = b_.CreateSub(i, lo);
          if (opts_.checks) {
            uint32_t st = site(ix->indices[k], "");
            auto* fail = newBlock("index.fail");
            auto* cont = newBlock("index.ok");
            b_.CreateCondBr(b_.CreateICmpULE(rel, b_.CreateSub(hi, lo)), cont, fail);
            b_.SetInsertPoint(fail);
            b_.CreateCall(runtime("__stc_fault_index", llvm::Type::getVoidTy(ctx_), {i32_, i64_, i64_, i64_}, true), {b_.getInt32(st), i, lo, hi});
            b_.CreateUnreachable();
            b_.SetInsertPoint(cont);
          }
          llvm::Value* extent = b_.CreateAdd(b_.CreateSub(hi, lo), b_.getInt64(1));
          linear = b_.CreateAdd(b_.CreateMul(linear, extent), rel);
        }
        return Address{b_.CreateInBoundsGEP(i8_, data, b_.CreateMul(linear, b_.getInt64(es))), bt->element};
      }
      uint64_t stride = sizeOf(bt->element);
      stride = (stride + alignOf(bt->element) - 1) / alignOf(bt->element) * alignOf(bt->element);
      llvm::Value* offset = b_.getInt64(0);
      // Row-major: the last index varies fastest.
      std::vector<uint64_t> strides(bt->dims.size());
      uint64_t acc = stride;
      for (size_t k = bt->dims.size(); k-- > 0;) {
        strides[k] = acc;
        acc *= static_cast<uint64_t>(bt->dims[k].hi - bt->dims[k].lo + 1);
      }
      // a[i][j] on a 2-D array: a[i] is the row, an array of the rest.
      bool partial = ix->indices.size() < bt->dims.size();
      std::string arrName;
      if (auto* n = dyn_cast<NameExpr>(ix->base)) arrName = n->ident.name;
      else if (auto* mm = dyn_cast<MemberExpr>(ix->base)) arrName = mm->member.name;
      bool flexible = false;
      for (size_t k = 0; k < ix->indices.size(); ++k) {
        const sema::Dim& d = bt->dims[k];
        llvm::Value* i = emitValue(ix->indices[k], elementary(TypeKind::LInt));
        if (Symbol* cb = implicitCheck("CHECKBOUNDS"))
          i = callImplicitCheck(cb, {i, b_.getInt64(static_cast<uint64_t>(d.lo)), b_.getInt64(static_cast<uint64_t>(d.hi))}, true);
        // p^[i] on POINTER TO ARRAY[0..0] OF T: the flexible-array idiom of CODESYS libraries
        // (SMC_OUTQUEUE.pbyBuffer ...): the pointer says where, not how many (docs/dialect.md).
        flexible = isa<DerefExpr>(ix->base) && bt->dims.size() == 1 && d.lo == 0 && d.hi == 0;
        if (opts_.checks && !flexible) checkIndex(i, d.lo, d.hi, site(ix->indices[k], arrName));
        llvm::Value* rel = b_.CreateSub(i, b_.getInt64(static_cast<uint64_t>(d.lo)));
        offset = b_.CreateAdd(offset, b_.CreateMul(rel, b_.getInt64(strides[k])));
      }
      llvm::Value* at = flexible ? b_.CreateGEP(i8_, base.ptr, offset) : b_.CreateInBoundsGEP(i8_, base.ptr, offset);
      return Address{at, partial ? e->type : bt->element};
    }
    case Expr::Deref: {
      auto* d = cast<DerefExpr>(e);
      if (isa<SuperExpr>(d->base) || isa<ThisExpr>(d->base)) return Address{fs_->self, e->type};
      llvm::Value* p = emitValue(d->base, nullptr);
      markSite(e);
      if (opts_.checkPointers && e->type && !isOpenArray(e->type))
        checkPointerRange(p, b_.getInt64(std::max<uint64_t>(sizeOf(e->type), 1)), e);
      return Address{nullChecked(p, FaultKind::NullPointer, e), e->type};
    }
    case Expr::DirectAddress:
      return directAddress(cast<DirectAddressExpr>(e)->text, e->type);
    case Expr::Call: {
      // f().x, a function returning a structure: the result lives in a temporary.
      Address r;
      emitCall(cast<CallExpr>(e), &r);
      if (r.ptr) return r;
      break;
    }
    default:
      break;
  }
  if (e->type && isAggregate(e->type)) {
    // An aggregate rvalue (string literal, function result): its address.
    llvm::Value* v = emitRaw(e);
    return Address{v, e->type};
  }
  // A scalar rvalue used where memory is needed: spill it.
  llvm::Value* v = emitRaw(e);
  Address t = temporary(e->type);
  store(t, v);
  return t;
}

// ------------------------------------------------------------------ values

llvm::Value* CodeGen::emitValue(const Expr* e, const Type* to) {
  // 'A' as a CHAR / "A" as a WCHAR: the character, not the string.
  if (auto* lit = dyn_cast<LiteralExpr>(e); lit && to && strip(to)->isChar() &&
                                           (lit->litKind == LiteralExpr::String || lit->litKind == LiteralExpr::WString)) {
    bool wide = strip(to)->kind == TypeKind::WChar;
    std::string bytes = literalBytes(lit, wide);
    uint64_t v = bytes.empty() ? 0 : static_cast<unsigned char>(bytes[0]);
    if (wide && bytes.size() >= 2) v |= static_cast<uint64_t>(static_cast<unsigned char>(bytes[1])) << 8;
    return llvm::ConstantInt::get(valueType(to), v);
  }
  if (to && widensIntermediate(e)) {
    // The register-width temporary reaches a wider integer or a REAL as it is.
    const Type* t = strip(to);
    const Type* os = strip(cast<BinaryExpr>(e)->operandType ? cast<BinaryExpr>(e)->operandType : e->type);
    if ((t->isInteger() || t->isBitString()) && t->bits() > strip(e->type)->bits()) {
      llvm::Value* w = emitWideBinary(cast<BinaryExpr>(e));
      llvm::Type* dt = valueType(t);
      return os->isSignedInt() ? b_.CreateSExtOrTrunc(w, dt) : b_.CreateZExtOrTrunc(w, dt);
    }
    if (t->isReal()) {
      llvm::Value* w = emitWideBinary(cast<BinaryExpr>(e));
      return os->isSignedInt() ? b_.CreateSIToFP(w, valueType(t)) : b_.CreateUIToFP(w, valueType(t));
    }
  }
  llvm::Value* v = emitRaw(e);
  if (!to || !e->type) return v;
  if (auto* lit = dyn_cast<LiteralExpr>(e);
      lit && !isAggregate(to) && (lit->litKind == LiteralExpr::Int || lit->litKind == LiteralExpr::Real || lit->litKind == LiteralExpr::Bool)) {
    // Untyped literals take the target type directly (no double rounding).
    if (strip(to)->isReal() || lit->litKind != LiteralExpr::Real) {
      if (to->kind == TypeKind::Subrange) return convert(constantValue(lit, strip(to)), strip(to), to, e);
      if (!(strip(to)->isBool() && lit->litKind == LiteralExpr::Int) && !isTimeKind(strip(to))) return constantValue(lit, to);
    }
  }
  return convert(v, e->type, to, e);
}

llvm::Value* CodeGen::bitRead(llvm::Value* word, unsigned bit, unsigned width, llvm::Type* resultTy) {
  llvm::Value* sh = b_.CreateLShr(word, static_cast<uint64_t>(bit) * width);
  return b_.CreateTrunc(sh, resultTy);
}

llvm::Value* CodeGen::emitRaw(const Expr* e) {
  switch (e->kind) {
    case Expr::Literal: {
      auto* lit = cast<LiteralExpr>(e);
      if (lit->litKind == LiteralExpr::String || lit->litKind == LiteralExpr::WString) {
        const Type* t = strip(e->type);
        if (t->isChar()) {
          std::string bytes = literalBytes(lit, t->kind == TypeKind::WChar);
          uint64_t v = bytes.empty() ? 0 : static_cast<unsigned char>(bytes[0]);
          if (t->kind == TypeKind::WChar && bytes.size() >= 2) v |= static_cast<uint64_t>(static_cast<unsigned char>(bytes[1])) << 8;
          return llvm::ConstantInt::get(valueType(t), v);
        }
        return emitStringLiteral(lit, e->type);
      }
      return constantValue(lit, e->type);
    }
    case Expr::Name: {
      auto* n = cast<NameExpr>(e);
      Symbol* s = n->symbol;
      if (!s) break;
      if (s->kind == Symbol::EnumValue) return llvm::ConstantInt::get(valueType(e->type), static_cast<uint64_t>(s->enumValue), true);
      if (s->kind == Symbol::Property) return emitPropertyGet(e, s);
      if (s->kind == Symbol::Variable) {
        const VarDecl* v = (s->aliasOf ? s->aliasOf : s)->var;
        // Reads of a foldable constant are immediates.
        if (v && v->isFoldableConstant() && v->resolvedType && !isAggregate(v->resolvedType) && !isa<ArrayInitExpr>(v->init) &&
            !isa<StructInitExpr>(v->init))
          return emitValue(v->init, v->resolvedType);
        if (v && v->resolvedType && !isAggregate(v->resolvedType)) {
          // CONSTANT blocks mark the block, not each variable: check through the owner.
        }
      }
      return load(emitAddr(e));
    }
    case Expr::Member: {
      auto* m = cast<MemberExpr>(e);
      if (m->access != MemberExpr::Field) {
        llvm::Value* w = emitValue(m->base, nullptr);
        unsigned width = m->access == MemberExpr::PartialByte ? 8 : m->access == MemberExpr::PartialWord ? 16
                         : m->access == MemberExpr::PartialDWord ? 32 : 1;
        return bitRead(w, m->bitIndex, width, width == 1 ? static_cast<llvm::Type*>(i1_) : llvm::IntegerType::get(ctx_, width));
      }
      if (m->symbol && m->symbol->kind == Symbol::EnumValue)
        return llvm::ConstantInt::get(valueType(e->type), static_cast<uint64_t>(m->symbol->enumValue), true);
      if (e->type && e->type->kind == TypeKind::Enum && (!m->symbol || m->symbol->kind == Symbol::TypeName)) {
        for (auto& [name, val] : e->type->enumValues)
          if (equalsIgnoreCase(name, m->member.name)) return llvm::ConstantInt::get(valueType(e->type), static_cast<uint64_t>(val), true);
      }
      if (m->symbol && m->symbol->kind == Symbol::Property) return emitPropertyGet(e, m->symbol);
      if (m->symbol && m->symbol->kind == Symbol::Variable) {
        const VarDecl* v = m->symbol->var;
        if (v && v->isConstant && v->init && v->resolvedType && !isAggregate(v->resolvedType) && !isa<ArrayInitExpr>(v->init))
          return emitValue(v->init, v->resolvedType);
      }
      return load(emitAddr(e));
    }
    case Expr::Index: case Expr::Deref: case Expr::DirectAddress:
      return load(emitAddr(e));
    case Expr::Call: {
      Address r;
      llvm::Value* v = emitCall(cast<CallExpr>(e), &r);
      return v;
    }
    case Expr::Unary: {
      auto* u = cast<UnaryExpr>(e);
      llvm::Value* v = emitValue(u->operand, e->type);
      switch (u->op) {
        case UnaryOp::Plus: return v;
        case UnaryOp::Neg: return v->getType()->isFloatingPointTy() ? b_.CreateFNeg(v) : b_.CreateNeg(v);
        case UnaryOp::Not: return b_.CreateNot(v);
      }
      break;
    }
    case Expr::Binary:
      return emitBinary(cast<BinaryExpr>(e));
    case Expr::This:
      return fs_ && fs_->self ? fs_->self : llvm::ConstantPointerNull::get(ptrTy_);
    case Expr::Super:
      return fs_ && fs_->self ? fs_->self : llvm::ConstantPointerNull::get(ptrTy_);
    default:
      break;
  }
  error(e->range, "this expression is not supported by the code generator yet");
  return llvm::UndefValue::get(e->type ? valueType(e->type) : i32_);
}

// ------------------------------------------------------------------ operators

llvm::Value* CodeGen::emitCompare(BinaryOp op, llvm::Value* l, llvm::Value* r, const Type* t) {
  const Type* s = strip(t);
  if (l->getType()->isFloatingPointTy()) {
    switch (op) {
      case BinaryOp::Lt: return b_.CreateFCmpOLT(l, r);
      case BinaryOp::Gt: return b_.CreateFCmpOGT(l, r);
      case BinaryOp::Le: return b_.CreateFCmpOLE(l, r);
      case BinaryOp::Ge: return b_.CreateFCmpOGE(l, r);
      case BinaryOp::Eq: return b_.CreateFCmpOEQ(l, r);
      default: return b_.CreateFCmpUNE(l, r);
    }
  }
  if (l->getType()->isPointerTy() || r->getType()->isPointerTy()) {
    if (!l->getType()->isPointerTy()) l = b_.CreateIntToPtr(l, ptrTy_);
    if (!r->getType()->isPointerTy()) r = b_.CreateIntToPtr(r, ptrTy_);
    // Addresses compare as unsigned numbers (CODESYS: a pointer is an address).
    switch (op) {
      case BinaryOp::Eq: return b_.CreateICmpEQ(l, r);
      case BinaryOp::Lt: return b_.CreateICmpULT(l, r);
      case BinaryOp::Gt: return b_.CreateICmpUGT(l, r);
      case BinaryOp::Le: return b_.CreateICmpULE(l, r);
      case BinaryOp::Ge: return b_.CreateICmpUGE(l, r);
      default: return b_.CreateICmpNE(l, r);
    }
  }
  bool sgn = s->isSignedInt() || isTimeKind(s);
  switch (op) {
    case BinaryOp::Lt: return sgn ? b_.CreateICmpSLT(l, r) : b_.CreateICmpULT(l, r);
    case BinaryOp::Gt: return sgn ? b_.CreateICmpSGT(l, r) : b_.CreateICmpUGT(l, r);
    case BinaryOp::Le: return sgn ? b_.CreateICmpSLE(l, r) : b_.CreateICmpULE(l, r);
    case BinaryOp::Ge: return sgn ? b_.CreateICmpSGE(l, r) : b_.CreateICmpUGE(l, r);
    case BinaryOp::Eq: return b_.CreateICmpEQ(l, r);
    default: return b_.CreateICmpNE(l, r);
  }
}

llvm::Value* CodeGen::emitBinary(const BinaryExpr* e) {
  const Type* ot = e->operandType ? e->operandType : e->type;
  const Type* os = strip(ot);
  BinaryOp op = e->op;
  // Short-circuit forms.
  if (op == BinaryOp::AndThen || op == BinaryOp::OrElse) {
    llvm::Value* l = toBool(emitValue(e->lhs, nullptr));
    auto* lhsEnd = b_.GetInsertBlock();
    auto* rhsBlock = newBlock(op == BinaryOp::AndThen ? "and_then" : "or_else");
    auto* done = newBlock("sc.done");
    if (op == BinaryOp::AndThen) b_.CreateCondBr(l, rhsBlock, done);
    else b_.CreateCondBr(l, done, rhsBlock);
    b_.SetInsertPoint(rhsBlock);
    llvm::Value* r = toBool(emitValue(e->rhs, nullptr));
    auto* rhsEnd = b_.GetInsertBlock();
    b_.CreateBr(done);
    b_.SetInsertPoint(done);
    auto* phi = b_.CreatePHI(i1_, 2);
    phi->addIncoming(b_.getInt1(op == BinaryOp::OrElse), lhsEnd);
    phi->addIncoming(r, rhsEnd);
    return phi;
  }
  bool cmp = op >= BinaryOp::Lt && op <= BinaryOp::Ne;
  if (widensIntermediate(e)) return b_.CreateTrunc(emitWideBinary(e), valueType(e->type));
  if (cmp && registerBits_ && (os->isInteger() || os->isBitString()) && os->bits() < registerBits_ &&
      (widensIntermediate(e->lhs) || widensIntermediate(e->rhs))) {
    // (w + 1) = 0 compares the register-width temporary (CODESYS).
    llvm::Value* l = emitWideInt(e->lhs, ot);
    llvm::Value* r = emitWideInt(e->rhs, ot);
    return emitCompare(op, l, r, os->isSignedInt() ? elementary(registerBits_ == 64 ? TypeKind::LInt : TypeKind::DInt)
                                                   : elementary(registerBits_ == 64 ? TypeKind::ULInt : TypeKind::UDInt));
  }
  // Strings compare through the runtime.
  if (cmp && os->isString()) {
    llvm::Value* l = emitValue(e->lhs, nullptr);
    llvm::Value* r = emitValue(e->rhs, nullptr);
    bool wide = os->kind == TypeKind::WString;
    llvm::Value* c = b_.CreateCall(runtime(wide ? "__stc_wstr_cmp" : "__stc_str_cmp", i32_, {ptrTy_, ptrTy_}), {l, r});
    return emitCompare(op, c, b_.getInt32(0), elementary(TypeKind::DInt));
  }
  const Type* lt = e->lhs->type ? strip(e->lhs->type) : os;
  const Type* rt = e->rhs->type ? strip(e->rhs->type) : os;
  // Time arithmetic: TIME * n, TIME / n, DT - DT, TOD + TIME ...
  if (!cmp && (isTimeKind(lt) || isTimeKind(rt)) && !(lt->isPointer() || rt->isPointer())) {
    llvm::Value* l = emitValue(e->lhs, nullptr);
    llvm::Value* r = emitValue(e->rhs, nullptr);
    auto asI64 = [&](llvm::Value* v, const Type* t) -> llvm::Value* {
      if (v->getType()->isFloatingPointTy()) return nullptr;
      return t->isSignedInt() || isTimeKind(t) ? b_.CreateSExtOrTrunc(v, i64_) : b_.CreateZExtOrTrunc(v, i64_);
    };
    if (op == BinaryOp::Add) return b_.CreateAdd(asI64(l, lt), asI64(r, rt));
    if (op == BinaryOp::Sub) return b_.CreateSub(asI64(l, lt), asI64(r, rt));
    if (op == BinaryOp::Mul || op == BinaryOp::Div) {
      llvm::Value* t = isTimeKind(lt) ? l : r;
      llvm::Value* n = isTimeKind(lt) ? r : l;
      const Type* nt = isTimeKind(lt) ? rt : lt;
      if (n->getType()->isFloatingPointTy()) {
        llvm::Type* d = llvm::Type::getDoubleTy(ctx_);
        llvm::Value* tf = b_.CreateSIToFP(t, d);
        llvm::Value* nf = b_.CreateFPExt(n, d);
        llvm::Value* res = op == BinaryOp::Mul ? b_.CreateFMul(tf, nf) : b_.CreateFDiv(tf, nf);
        return b_.CreateIntrinsic(llvm::Intrinsic::fptosi_sat, {i64_, d}, {b_.CreateUnaryIntrinsic(llvm::Intrinsic::round, res)});
      }
      llvm::Value* ni = asI64(n, nt);
      if (op == BinaryOp::Mul) return b_.CreateMul(t, ni);
      ni = checkedDivisor(ni, e);
      return b_.CreateSDiv(t, ni);
    }
  }
  if (cmp && (lt->kind == TypeKind::Interface || rt->kind == TypeKind::Interface)) {
    // Interfaces compare by instance.
    return emitCompare(op, interfaceSelf(e->lhs), interfaceSelf(e->rhs), ot);
  }
  if (cmp) {
    llvm::Value* l = emitValue(e->lhs, ot);
    llvm::Value* r = emitValue(e->rhs, ot);
    return emitCompare(op, l, r, ot);
  }
  // Pointer arithmetic (CODESYS): byte offsets.
  if ((lt->isPointer() || rt->isPointer()) && (op == BinaryOp::Add || op == BinaryOp::Sub)) {
    llvm::Value* l = emitValue(e->lhs, nullptr);
    llvm::Value* r = emitValue(e->rhs, nullptr);
    if (lt->isPointer() && rt->isPointer()) return b_.CreateSub(b_.CreatePtrToInt(l, i64_), b_.CreatePtrToInt(r, i64_));
    llvm::Value* p = lt->isPointer() ? l : r;
    llvm::Value* n = lt->isPointer() ? r : l;
    const Type* nt = lt->isPointer() ? rt : lt;
    n = nt->isSignedInt() ? b_.CreateSExtOrTrunc(n, i64_) : b_.CreateZExtOrTrunc(n, i64_);
    if (op == BinaryOp::Sub) n = b_.CreateNeg(n);
    return b_.CreateGEP(i8_, p, n);
  }
  if (op == BinaryOp::Pow) {
    const Type* rtT = strip(e->type);
    llvm::Value* l = emitValue(e->lhs, rtT);
    llvm::Value* r = emitValue(e->rhs, rtT);
    return b_.CreateBinaryIntrinsic(llvm::Intrinsic::pow, l, r);
  }
  llvm::Value* l = emitValue(e->lhs, ot);
  llvm::Value* r = emitValue(e->rhs, ot);
  bool fp = l->getType()->isFloatingPointTy();
  bool sgn = os->isSignedInt();
  switch (op) {
    case BinaryOp::Add: return fp ? b_.CreateFAdd(l, r) : b_.CreateAdd(l, r);
    case BinaryOp::Sub: return fp ? b_.CreateFSub(l, r) : b_.CreateSub(l, r);
    case BinaryOp::Mul: return fp ? b_.CreateFMul(l, r) : b_.CreateMul(l, r);
    case BinaryOp::Div:
    case BinaryOp::Mod: {
      if (fp) {
        if (Symbol* cd = implicitCheck(r->getType()->isFloatTy() ? "CHECKDIVREAL" : "CHECKDIVLREAL")) r = callImplicitCheck(cd, {r}, true);
        return op == BinaryOp::Div ? b_.CreateFDiv(l, r) : b_.CreateFRem(l, r);
      }
      return intDivide(l, r, op == BinaryOp::Div, sgn, e);
    }
    case BinaryOp::And: return b_.CreateAnd(l, r);
    case BinaryOp::Or: return b_.CreateOr(l, r);
    case BinaryOp::Xor: return b_.CreateXor(l, r);
    default: break;
  }
  error(e->range, "operator not supported by the code generator yet");
  return llvm::UndefValue::get(l->getType());
}

bool CodeGen::widensIntermediate(const Expr* e) const {
  auto* b = dyn_cast<BinaryExpr>(e);
  if (!registerBits_ || !b || !b->type) return false;
  if (b->op != BinaryOp::Add && b->op != BinaryOp::Sub && b->op != BinaryOp::Mul && b->op != BinaryOp::Div && b->op != BinaryOp::Mod)
    return false;
  const Type* rt = strip(b->type);
  const Type* os = strip(b->operandType ? b->operandType : b->type);
  if (!(rt->isInteger() || rt->isBitString()) || !(os->isInteger() || os->isBitString())) return false;
  const Type* lt = b->lhs->type ? strip(b->lhs->type) : os;
  const Type* r2 = b->rhs->type ? strip(b->rhs->type) : os;
  if (lt->isPointer() || r2->isPointer() || isTimeKind(lt) || isTimeKind(r2)) return false;
  return os->bits() < registerBits_;
}

llvm::Value* CodeGen::emitWideInt(const Expr* e, const Type* as) {
  if (widensIntermediate(e)) return emitWideBinary(cast<BinaryExpr>(e));
  llvm::Value* v = emitValue(e, as);
  llvm::Type* wt = llvm::IntegerType::get(ctx_, registerBits_);
  const Type* t = strip(as ? as : e->type);
  return t->isSignedInt() ? b_.CreateSExtOrTrunc(v, wt) : b_.CreateZExtOrTrunc(v, wt);
}

llvm::Value* CodeGen::emitWideBinary(const BinaryExpr* e) {
  const Type* os = strip(e->operandType ? e->operandType : e->type);
  llvm::Value* l = emitWideInt(e->lhs, os);
  llvm::Value* r = emitWideInt(e->rhs, os);
  switch (e->op) {
    case BinaryOp::Add: return b_.CreateAdd(l, r);
    case BinaryOp::Sub: return b_.CreateSub(l, r);
    case BinaryOp::Mul: return b_.CreateMul(l, r);
    default: return intDivide(l, r, e->op == BinaryOp::Div, os->isSignedInt(), e);
  }
}

// Integer division and MOD with the divisor checked.  MIN / -1 overflows
// (undefined in LLVM, SIGFPE on x86): IEC wraps to MIN; MOD -1 gives 0.
llvm::Value* CodeGen::intDivide(llvm::Value* l, llvm::Value* r, bool isDiv, bool isSigned, const Node* at) {
  // CheckDivInt / CheckDivDInt / CheckDivLInt by the divisor's declared size.
  unsigned bits = r->getType()->getIntegerBitWidth();
  if (auto* b = dynamic_cast<const BinaryExpr*>(at); b && b->rhs && b->rhs->type) {
    const Type* dt = strip(b->operandType ? b->operandType : b->rhs->type);
    if (dt->isInteger() || dt->isBitString()) bits = dt->bits();
  }
  if (Symbol* cd = implicitCheck(bits <= 16 ? "CHECKDIVINT" : bits <= 32 ? "CHECKDIVDINT" : "CHECKDIVLINT"))
    r = callImplicitCheck(cd, {r}, isSigned);
  r = checkedDivisor(r, at);
  if (!isSigned) return isDiv ? b_.CreateUDiv(l, r) : b_.CreateURem(l, r);
  llvm::Value* minusOne = b_.CreateICmpEQ(r, llvm::ConstantInt::getSigned(r->getType(), -1));
  llvm::Value* safeR = b_.CreateSelect(minusOne, llvm::ConstantInt::get(r->getType(), 1), r);
  if (isDiv) return b_.CreateSelect(minusOne, b_.CreateNeg(l), b_.CreateSDiv(l, safeR));
  return b_.CreateSelect(minusOne, llvm::ConstantInt::get(r->getType(), 0), b_.CreateSRem(l, safeR));
}

// ------------------------------------------------------------------ assignment

void CodeGen::assign(Address dst, const Expr* src) {
  const Type* t = strip(dst.type);
  if (t->isString()) {
    bool wide = t->kind == TypeKind::WString;
    const Type* st = src->type ? strip(src->type) : t;
    llvm::Value* sp;
    if (st->isChar()) {
      // CHAR -> STRING: a one-character temporary.
      llvm::Value* c = emitValue(src, nullptr);
      Address tmp = temporary(model_.types->string(1, wide), "chr");
      llvm::Type* ct = wide ? i16_ : i8_;
      b_.CreateStore(c, tmp.ptr);
      b_.CreateStore(llvm::ConstantInt::get(ct, 0), b_.CreateConstInBoundsGEP1_64(ct, tmp.ptr, 1));
      sp = tmp.ptr;
    } else {
      if (auto* c = dyn_cast<CallExpr>(src)) {
        int fam = sema::builtinFamily(c->target);
        if (fam == sema::FLeftRight || fam == sema::FMid || fam == sema::FInsert || fam == sema::FDelete || fam == sema::FReplace)
          stringDest_ = Address{dst.ptr, t};
      }
      sp = emitValue(src, nullptr);
      stringDest_ = Address{};
      if (sp == dst.ptr) return;   // written in place
    }
    b_.CreateCall(runtime(wide ? "__stc_wstr_assign" : "__stc_str_assign", llvm::Type::getVoidTy(ctx_), {ptrTy_, i64_, ptrTy_}),
                  {dst.ptr, b_.getInt64(t->length), sp});
    return;
  }
  if (t->kind == TypeKind::Interface) {
    assignInterface(dst, src);
    return;
  }
  if (isAggregate(t)) {
    if (auto* ai = dyn_cast<ArrayInitExpr>(src)) { (void)ai; initAt(dst, src); return; }
    if (isa<StructInitExpr>(src)) { initAt(dst, src); return; }
    llvm::Value* sp = emitValue(src, nullptr);
    uint64_t n = std::min(sizeOf(t), src->type ? sizeOf(src->type) : sizeOf(t));
    if (sp != dst.ptr) b_.CreateMemMove(dst.ptr, llvm::MaybeAlign(1), sp, llvm::MaybeAlign(1), n);
    return;
  }
  store(dst, emitValue(src, dst.type));
}

}  // namespace stc::codegen
