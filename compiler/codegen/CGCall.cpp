// Calls: functions, FB instances, programs, methods, actions, properties and
// the generic standard functions that lower to IR.
#include <llvm/IR/Constants.h>
#include <llvm/IR/Intrinsics.h>

#include "basic/Text.h"
#include "codegen/CGInternal.h"

namespace stc::codegen {

using namespace stc::ast;

namespace {
const Argument* argFor(const CallExpr* e, const Symbol* p) {
  for (const Argument& a : e->args)
    if (a.param == p) return &a;
  return nullptr;
}
bool isValueInstance(const Expr* e) {
  // A receiver that is an instance itself (not reached through a pointer,
  // reference or VAR_IN_OUT) has a known dynamic type.
  if (isa<DerefExpr>(e)) return false;
  const sema::Symbol* s = nullptr;
  if (auto* n = dyn_cast<NameExpr>(e)) s = n->symbol;
  else if (auto* m = dyn_cast<MemberExpr>(e)) s = m->symbol;
  if (s && s->var && (s->var->section == VarSection::InOut || (s->type && s->type->isReference()))) return false;
  return true;
}
}  // namespace

llvm::Value* CodeGen::emitCall(const CallExpr* e, Address* resultOut) {
  Symbol* t = e->target;
  if (!t) {
    error(e->range, "internal: unresolved call");
    return llvm::UndefValue::get(i32_);
  }
  switch (t->kind) {
    case Symbol::BuiltinFunction:
      return emitBuiltin(e);
    case Symbol::Function: {
      llvm::Value* r = callPou(e, t, nullptr, false);
      if (resultOut && returnsIndirect(t)) *resultOut = Address{r, returnTypeOf(t)};
      return r;
    }
    case Symbol::Program: {
      // Calling a program from another POU runs its singleton instance.
      llvm::Value* inst = imageAddr(programOffsets_[t]);
      callInstance(e, t, inst);
      return nullptr;
    }
    case Symbol::FunctionBlock: {
      llvm::Value* inst = instancePtr(e->callee);
      callInstance(e, t, inst);
      return nullptr;
    }
    case Symbol::Method:
    case Symbol::Action: {
      llvm::Value* self = nullptr;
      bool virt = false;
      if (auto* m = dyn_cast<MemberExpr>(e->callee)) {
        const Type* bt = m->base->type ? strip(m->base->type) : nullptr;
        if (bt && bt->kind == TypeKind::Interface) {
          auto [s, fp] = interfaceSlot(m->base, t);
          llvm::Value* r = callPou(e, t, s, false, fp);
          if (resultOut && returnsIndirect(t)) *resultOut = Address{r, returnTypeOf(t)};
          return r;
        }
        bool viaSuper = false;
        if (auto* d = dyn_cast<DerefExpr>(m->base)) viaSuper = isa<SuperExpr>(d->base);
        self = instancePtr(m->base);
        virt = t->kind == Symbol::Method && !viaSuper && !isValueInstance(m->base);
      } else {
        self = fs_->self;   // own method or action: implicit THIS
        virt = t->kind == Symbol::Method;
      }
      llvm::Value* r = callPou(e, t, self, virt);
      if (resultOut && t->kind == Symbol::Method && returnsIndirect(t)) *resultOut = Address{r, returnTypeOf(t)};
      return r;
    }
    default:
      error(e->range, "this call is not supported by the code generator yet");
      return nullptr;
  }
}

llvm::Value* CodeGen::callPou(const CallExpr* e, Symbol* target, llvm::Value* self, bool virtualCall, llvm::Value* fnPtr) {
  // Through an interface slot only the signature is needed (the interface's
  // own method has no body).
  llvm::Function* f = fnPtr ? nullptr : functionFor(target);
  llvm::FunctionType* fty = f ? f->getFunctionType() : signatureOf(target);
  std::vector<llvm::Value*> args;
  Address result;
  bool indirect = target->kind != Symbol::Action && returnsIndirect(target);
  if (indirect) {
    result = temporary(returnTypeOf(target), "ret");
    args.push_back(result.ptr);
  }
  if (target->kind == Symbol::Method || target->kind == Symbol::Action) args.push_back(self);
  struct Out { Address temp; const Argument* arg; };
  std::vector<Out> outs;
  if (target->kind != Symbol::Action)
    for (Symbol* p : target->pou->params) {
      const Argument* a = argFor(e, p);
      const VarDecl* v = p->var;
      if (v->section == VarSection::Input) {
        if (isAggregate(p->type)) {
          Address tmp = temporary(p->type, p->name.c_str());
          if (a && a->value) assign(tmp, a->value);
          else initAt(tmp, v->init, v);
          args.push_back(tmp.ptr);
        } else if (a && a->value && p->type && p->type->isReference()) {
          Address tmp = temporary(p->type, p->name.c_str());   // bound, as by REF=
          storeAddress(tmp.ptr, p->type, referenceTarget(a->value));
          args.push_back(load(tmp));
        } else if (a && a->value) {
          args.push_back(emitValue(a->value, p->type));
        } else if (v->init) {
          args.push_back(emitValue(v->init, p->type));
        } else {
          Address tmp = temporary(p->type, p->name.c_str());
          initAt(tmp, nullptr, v);
          args.push_back(load(tmp));
        }
      } else if (v->section == VarSection::Output) {
        Address tmp = temporary(p->type, p->name.c_str());
        args.push_back(tmp.ptr);
        if (a && a->value) outs.push_back({tmp, a});
      } else {
        if (!a || !a->value) {
          error(e->range, "missing VAR_IN_OUT argument '" + p->name + "'");
          args.push_back(llvm::ConstantPointerNull::get(ptrTy_));
          continue;
        }
        if (isOpenArray(p->type)) args.push_back(arrayDescriptor(a->value));
        else args.push_back(emitAddr(a->value).ptr);
      }
    }
  llvm::Value* chainDepth = (!target || !isNative(target)) ? pushCallSite(site(e, target ? target->name : "")) : nullptr;
  llvm::CallInst* call;
  if (fnPtr) {
    call = b_.CreateCall(fty, fnPtr, args);
  } else if (virtualCall && fs_ && fs_->fn) {
    Symbol* owner = ownerOf(target);
    int slot = owner ? vtableSlot(owner->type, slotKey(target)) : -1;
    if (slot < 0) {
      call = b_.CreateCall(f, args);
    } else {
      llvm::Value* vptr = loadVptr(self, e);
      llvm::Value* fp = b_.CreateAlignedLoad(ptrTy_, b_.CreateConstInBoundsGEP1_64(ptrTy_, vptr, static_cast<uint64_t>(slot + 2)), llvm::MaybeAlign(8));
      call = b_.CreateCall(f->getFunctionType(), fp, args);
      if (fs_) indirectCallers_.insert(fs_->fn);
    }
  } else {
    call = b_.CreateCall(f, args);
    if (fs_ && fs_->fn) calls_[fs_->fn].insert(f);
  }
  if (f) call->setAttributes(f->getAttributes());
  if (chainDepth) popCallSite(chainDepth);
  for (Out& o : outs) {
    Address dst = emitAddr(o.arg->value);
    llvm::Value* v = load(o.temp);
    if (o.arg->negated) v = b_.CreateNot(v);
    if (isAggregate(o.temp.type)) {
      b_.CreateMemCpy(dst.ptr, llvm::MaybeAlign(1), o.temp.ptr, llvm::MaybeAlign(1), std::min(sizeOf(o.temp.type), sizeOf(dst.type)));
    } else {
      store(dst, convert(v, o.temp.type, dst.type, o.arg->value));
    }
  }
  if (indirect) return result.ptr;
  if (call->getType()->isVoidTy()) return call;
  return call;
}

// fb(IN := a, io := v, Q => q): inputs into the instance, in-outs bound,
// the body called, outputs read back.  Omitted inputs keep their values.
void CodeGen::callInstance(const CallExpr* e, Symbol* fbSym, llvm::Value* inst) {
  const Type* fbType = fbSym->type;
  std::vector<const Argument*> outputs;
  for (const Argument& a : e->args) {
    if (!a.param || !a.param->var) continue;
    const sema::FieldLayout* f = layout_.field(fbType, a.param->var);
    if (!f) continue;
    llvm::Value* p = b_.CreateConstInBoundsGEP1_64(i8_, inst, f->offset);
    switch (a.param->var->section) {
      case VarSection::Input:
        if (!a.value) break;
        if (f->type && f->type->isReference()) storeAddress(p, f->type, referenceTarget(a.value));   // bound, as by REF=
        else assign(Address{p, f->type}, a.value);
        break;
      case VarSection::InOut:
        if (a.value) b_.CreateAlignedStore(emitAddr(a.value).ptr, p, llvm::MaybeAlign(8));
        break;
      case VarSection::Output:
        if (a.value) outputs.push_back(&a);
        break;
      default:
        break;
    }
  }
  llvm::Function* body = functionFor(fbSym);
  // SUPER^() runs the base body itself; other calls through pointers,
  // references and in-outs run the body of the instance's own type.
  bool viaSuper = isa<DerefExpr>(e->callee) && isa<SuperExpr>(cast<DerefExpr>(e->callee)->base);
  bool virt = fbSym->kind == Symbol::FunctionBlock && !viaSuper && !isValueInstance(e->callee);
  llvm::Value* chainDepth = isNative(fbSym) ? nullptr : pushCallSite(site(e, fbSym->name));
  if (virt) {
    llvm::Value* vptr = loadVptr(inst, e);
    llvm::Value* fp = b_.CreateAlignedLoad(ptrTy_, b_.CreateConstInBoundsGEP1_64(ptrTy_, vptr, 1), llvm::MaybeAlign(8));
    b_.CreateCall(body->getFunctionType(), fp, {inst});
    if (fs_ && fs_->fn) indirectCallers_.insert(fs_->fn);
  } else {
    b_.CreateCall(body, {inst});
    if (fs_ && fs_->fn) calls_[fs_->fn].insert(body);
  }
  if (chainDepth) popCallSite(chainDepth);
  for (const Argument* a : outputs) {
    const sema::FieldLayout* f = layout_.field(fbType, a->param->var);
    Address src{b_.CreateConstInBoundsGEP1_64(i8_, inst, f->offset), f->type};
    Address dst = emitAddr(a->value);
    if (isAggregate(f->type)) {
      if (strip(dst.type)->isString())
        b_.CreateCall(runtime(strip(dst.type)->kind == TypeKind::WString ? "__stc_wstr_assign" : "__stc_str_assign", llvm::Type::getVoidTy(ctx_),
                              {ptrTy_, i64_, ptrTy_}),
                      {dst.ptr, b_.getInt64(strip(dst.type)->length), src.ptr});
      else
        b_.CreateMemCpy(dst.ptr, llvm::MaybeAlign(1), src.ptr, llvm::MaybeAlign(1), std::min(sizeOf(f->type), sizeOf(dst.type)));
      continue;
    }
    llvm::Value* v = load(src);
    if (a->negated) v = b_.CreateNot(v);
    store(dst, convert(v, f->type, dst.type, a->value));
  }
}

// ------------------------------------------------------------------ properties

static Symbol* accessorOf(Symbol* prop, PouKind kind) {
  const PouDecl* d = prop->pou ? prop->pou->decl : nullptr;
  const PouDecl* acc = d ? (kind == PouKind::PropertyGet ? d->getter : d->setter) : nullptr;
  return acc ? acc->symbol : nullptr;
}

llvm::Value* CodeGen::emitPropertyGet(const Expr* e, Symbol* prop) {
  Symbol* get = accessorOf(prop, PouKind::PropertyGet);
  if (!get) {
    error(e->range, "property '" + prop->name + "' has no GET accessor");
    return llvm::UndefValue::get(valueType(e->type));
  }
  llvm::Value* self = fs_ ? fs_->self : nullptr;
  bool virt = true;
  CallExpr fake;
  fake.target = get;
  if (auto* m = dyn_cast<MemberExpr>(e)) {
    if (m->base->type && strip(m->base->type)->kind == TypeKind::Interface) {
      auto [s, fp] = interfaceSlot(m->base, get);
      return callPou(&fake, get, s, false, fp);
    }
    self = instancePtr(m->base);
    virt = !isValueInstance(m->base);
  }
  return callPou(&fake, get, self, virt);
}

void CodeGen::emitPropertySet(const Expr* lhs, Symbol* prop, const Expr* rhs) {
  Symbol* set = accessorOf(prop, PouKind::PropertySet);
  if (!set) {
    error(lhs->range, "property '" + prop->name + "' has no SET accessor");
    return;
  }
  llvm::Value* self = fs_->self;
  bool virt = true;
  llvm::Value* fnPtr = nullptr;
  if (auto* m = dyn_cast<MemberExpr>(lhs); m && m->base->type && strip(m->base->type)->kind == TypeKind::Interface) {
    auto [s, fp] = interfaceSlot(m->base, set);
    self = s;
    fnPtr = fp;
  } else if (auto* m = dyn_cast<MemberExpr>(lhs)) {
    self = instancePtr(m->base);
    virt = !isValueInstance(m->base);
  }
  llvm::FunctionType* fty = fnPtr ? signatureOf(set) : functionFor(set)->getFunctionType();
  const Type* vt = prop->pou->returnType;
  llvm::Value* v;
  if (isAggregate(vt)) {
    Address tmp = temporary(vt, "value");
    assign(tmp, rhs);
    v = tmp.ptr;
  } else {
    v = emitValue(rhs, vt);
  }
  Symbol* owner = ownerOf(set);
  int slot = virt && owner ? vtableSlot(owner->type, slotKey(set)) : -1;
  if (fnPtr) {
    b_.CreateCall(fty, fnPtr, {self, v});
  } else if (slot >= 0) {
    llvm::Value* vptr = loadVptr(self, lhs);
    llvm::Value* fp = b_.CreateAlignedLoad(ptrTy_, b_.CreateConstInBoundsGEP1_64(ptrTy_, vptr, static_cast<uint64_t>(slot + 2)), llvm::MaybeAlign(8));
    b_.CreateCall(fty, fp, {self, v});
    indirectCallers_.insert(fs_->fn);
  } else {
    llvm::Function* f = functionFor(set);
    b_.CreateCall(f, {self, v});
    calls_[fs_->fn].insert(f);
  }
}

// ------------------------------------------------------------------ builtins

llvm::Value* CodeGen::arg(const CallExpr* e, size_t i, const Type* to) {
  const Expr* a = i < e->orderedArgs.size() ? e->orderedArgs[i] : (i < e->args.size() ? e->args[i].value : nullptr);
  if (!a) return llvm::UndefValue::get(to ? valueType(to) : i32_);
  return emitValue(a, to);
}

// Conversions to and from STRING/WSTRING: decimal integers, shortest REAL,
// TRUE/FALSE, T#..., D#/TOD#/DT#...; parsing the same texts back; STRING <->
// WSTRING (UTF-8/Latin-1 <-> UTF-16).  WSTRING goes through a STRING.
llvm::Value* CodeGen::stringConversion(const Expr* a, const Type* rt, const Expr* at) {
  const Type* from = strip(a->type);
  const Type* to = strip(rt);
  llvm::Type* v = llvm::Type::getVoidTy(ctx_);
  auto narrowOf = [&](llvm::Value* wide, uint32_t len) {
    Address tmp = temporary(model_.types->string(std::max<uint32_t>(len * 4, 1), false), "narrow");
    b_.CreateCall(runtime("__stc_wstr_to_str", v, {ptrTy_, i64_, ptrTy_}), {tmp.ptr, b_.getInt64(std::max<uint32_t>(len * 4, 1)), wide});
    return tmp.ptr;
  };
  if (from->isString() && to->isString()) {
    if (from->kind == to->kind) return emitValue(a, nullptr);
    Address tmp = temporary(rt, "conv");
    llvm::Value* src = emitValue(a, nullptr);
    if (to->kind == TypeKind::WString)
      b_.CreateCall(runtime("__stc_str_to_wstr", v, {ptrTy_, i64_, ptrTy_}), {tmp.ptr, b_.getInt64(to->length), src});
    else
      b_.CreateCall(runtime("__stc_wstr_to_str", v, {ptrTy_, i64_, ptrTy_}), {tmp.ptr, b_.getInt64(to->length), src});
    return tmp.ptr;
  }
  if (to->isString()) {
    // Build the text as a STRING, then widen for WSTRING.
    const Type* narrow = to->kind == TypeKind::String ? rt : model_.types->string(std::max<uint32_t>(to->length * 4, 64), false);
    Address tmp = temporary(narrow, "str");
    llvm::Value* cap = b_.getInt64(strip(narrow)->length);
    llvm::Value* x = emitValue(a, nullptr);
    if (from->isBool()) {
      b_.CreateCall(runtime("__stc_bool_to_str", v, {ptrTy_, i64_, i32_}), {tmp.ptr, cap, b_.CreateZExt(x, i32_)});
    } else if (from->isReal()) {
      b_.CreateCall(runtime("__stc_real_to_str", v, {ptrTy_, i64_, llvm::Type::getDoubleTy(ctx_), i32_}),
                    {tmp.ptr, cap, b_.CreateFPExt(x, llvm::Type::getDoubleTy(ctx_)), b_.getInt32(from->kind == TypeKind::Real)});
    } else if (from->isDuration()) {
      b_.CreateCall(runtime("__stc_time_to_str", v, {ptrTy_, i64_, i64_, i32_}), {tmp.ptr, cap, x, b_.getInt32(from->kind == TypeKind::LTime)});
    } else if (from->isDate()) {
      int kind = (from->kind == TypeKind::Date || from->kind == TypeKind::LDate) ? 'D' : (from->kind == TypeKind::Tod || from->kind == TypeKind::LTod) ? 'T' : 'S';
      bool isLong = from->kind == TypeKind::LDate || from->kind == TypeKind::LTod || from->kind == TypeKind::LDT;
      b_.CreateCall(runtime("__stc_date_to_str", v, {ptrTy_, i64_, i64_, i32_, i32_}), {tmp.ptr, cap, x, b_.getInt32(kind), b_.getInt32(isLong)});
    } else if (from->isChar()) {
      llvm::Type* ct = from->kind == TypeKind::WChar ? i16_ : i8_;
      Address one = temporary(model_.types->string(1, from->kind == TypeKind::WChar), "chr");
      b_.CreateStore(x, one.ptr);
      b_.CreateStore(llvm::ConstantInt::get(ct, 0), b_.CreateConstInBoundsGEP1_64(ct, one.ptr, 1));
      llvm::Value* src = from->kind == TypeKind::WChar ? narrowOf(one.ptr, 1) : one.ptr;
      b_.CreateCall(runtime("__stc_str_assign", v, {ptrTy_, i64_, ptrTy_}), {tmp.ptr, cap, src});
    } else if (from->isInteger() || from->isBitString()) {
      bool sgn = from->isSignedInt();
      b_.CreateCall(runtime("__stc_int_to_str", v, {ptrTy_, i64_, i64_, i32_}),
                    {tmp.ptr, cap, sgn ? b_.CreateSExt(x, i64_) : b_.CreateZExtOrBitCast(x, i64_), b_.getInt32(sgn)});
    } else {
      error(a->range, "conversion of '" + from->name + "' to " + to->name + " is not supported");
      return tmp.ptr;
    }
    if (to->kind == TypeKind::String) return tmp.ptr;
    Address w = temporary(rt, "wstr");
    b_.CreateCall(runtime("__stc_str_to_wstr", v, {ptrTy_, i64_, ptrTy_}), {w.ptr, b_.getInt64(to->length), tmp.ptr});
    return w.ptr;
  }
  // From text: parse.
  llvm::Value* p = emitValue(a, nullptr);
  if (from->kind == TypeKind::WString) p = narrowOf(p, from->length);
  if (to->isReal())
    return convert(b_.CreateCall(runtime("__stc_str_to_real", llvm::Type::getDoubleTy(ctx_), {ptrTy_}), {p}), elementary(TypeKind::LReal), rt, at);
  if (to->isDuration()) return b_.CreateCall(runtime("__stc_str_to_time", i64_, {ptrTy_}), {p});
  if (to->isDate()) {
    int kind = (to->kind == TypeKind::Date || to->kind == TypeKind::LDate) ? 'D' : (to->kind == TypeKind::Tod || to->kind == TypeKind::LTod) ? 'T' : 'S';
    return b_.CreateCall(runtime("__stc_str_to_date", i64_, {ptrTy_, i32_}), {p, b_.getInt32(kind)});
  }
  if (to->isBool()) {
    // 'TRUE' (any case) or a non-zero number.
    llvm::Value* n = b_.CreateCall(runtime("__stc_str_to_int", i64_, {ptrTy_}), {p});
    llvm::Value* t = b_.CreateICmpEQ(b_.CreateCall(runtime("__stc_str_is_true", i32_, {ptrTy_}), {p}), b_.getInt32(1));
    return b_.CreateOr(t, b_.CreateICmpNE(n, b_.getInt64(0)));
  }
  if (to->isChar()) {
    // STRING_TO_CHAR: the first character (NUL for an empty string).
    if (from->kind == TypeKind::WString) p = emitValue(a, nullptr);
    llvm::Type* ct = from->kind == TypeKind::WString ? i16_ : i8_;
    return b_.CreateZExtOrTrunc(b_.CreateLoad(ct, p), valueType(rt));
  }
  if (to->isInteger() || to->isBitString())
    return b_.CreateTrunc(b_.CreateCall(runtime("__stc_str_to_int", i64_, {ptrTy_}), {p}), valueType(rt));
  error(a->range, "conversion of '" + from->name + "' to '" + to->name + "' is not supported");
  return llvm::UndefValue::get(valueType(rt));
}

llvm::Value* CodeGen::emitBuiltin(const CallExpr* e) {
  Symbol* t = e->target;
  int fam = sema::builtinFamily(t);
  const Type* rt = e->type;
  const std::string& name = t->name;
  auto argExpr = [&](size_t i) -> const Expr* {
    if (i < e->orderedArgs.size()) return e->orderedArgs[i];
    return i < e->args.size() ? e->args[i].value : nullptr;
  };
  size_t n = e->orderedArgs.empty() ? e->args.size() : e->orderedArgs.size();
  auto unsupported = [&]() -> llvm::Value* {
    error(e->range, "standard function '" + name + "' is not implemented by the code generator yet (see docs/status.md)");
    return llvm::UndefValue::get(rt && !isAggregate(rt) && rt->kind != TypeKind::Void ? valueType(rt) : ptrTy_);
  };
  switch (fam) {
    case sema::FConvert: case sema::FToGeneric: case sema::FMove: {
      const Expr* a = argExpr(0);
      if (!a) return unsupported();
      const Type* at = strip(a->type);
      const Type* st = strip(rt);
      if (st->isString() || at->isString()) return stringConversion(a, rt, e);
      if (isAggregate(rt) || isAggregate(a->type)) {
        if (isAggregate(rt) && at->kind == st->kind) return emitValue(a, nullptr);
        return unsupported();
      }
      return emitValue(a, rt);
    }
    case sema::FRound: {
      llvm::Value* v = arg(e, 0, rt);
      return b_.CreateUnaryIntrinsic(llvm::Intrinsic::round, v);
    }
    case sema::FToBcd: case sema::FFromBcd: {
      const Expr* a = argExpr(0);
      llvm::Value* v = emitValue(a, nullptr);
      bool sgn = strip(a->type)->isSignedInt();
      llvm::Value* w = sgn ? b_.CreateSExtOrTrunc(v, i64_) : b_.CreateZExtOrTrunc(v, i64_);
      llvm::Value* r = b_.CreateCall(runtime(fam == sema::FToBcd ? "__stc_to_bcd" : "__stc_from_bcd", i64_, {i64_}), {w});
      return b_.CreateTrunc(r, valueType(rt));
    }
    case sema::FIsValid: {
      llvm::Value* v = arg(e, 0, nullptr);
      llvm::Value* mag = b_.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, v);
      return b_.CreateFCmpOLT(mag, llvm::ConstantFP::getInfinity(v->getType()));
    }
    case sema::FIsValidBcd: {
      llvm::Value* v = b_.CreateZExtOrTrunc(arg(e, 0, nullptr), i64_);
      return b_.CreateICmpNE(b_.CreateCall(runtime("__stc_is_valid_bcd", i32_, {i64_}), {v}), b_.getInt32(0));
    }
    case sema::FEndian: {
      // The host is little-endian: TO_BIG_ENDIAN and BIG_ENDIAN_TO swap bytes.
      llvm::Value* v = arg(e, 0, rt);
      std::string up = asciiUpper(name);
      bool swap = up == "TO_BIG_ENDIAN" || up == "BIG_ENDIAN_TO";
      llvm::Type* ty = v->getType();
      unsigned bits = ty->getPrimitiveSizeInBits();
      if (!swap || bits <= 8) return v;
      llvm::Type* it = llvm::IntegerType::get(ctx_, bits);
      llvm::Value* x = ty->isIntegerTy() ? v : b_.CreateBitCast(v, it);
      x = b_.CreateUnaryIntrinsic(llvm::Intrinsic::bswap, x);
      return ty->isIntegerTy() ? x : b_.CreateBitCast(x, ty);
    }
    case sema::FIsValidRef: {
      Address slot = referenceSlot(argExpr(0));
      if (!slot.ptr) return unsupported();
      return b_.CreateIsNotNull(loadAddress(slot.ptr, slot.type));
    }
    case sema::FBitAdr: {
      // The bit address of a variable located in the process image.
      const Expr* a = argExpr(0);
      const Symbol* sym = nullptr;
      if (auto* n = dyn_cast<NameExpr>(a)) sym = n->symbol;
      else if (auto* m = dyn_cast<MemberExpr>(a)) sym = m->symbol;
      auto it = sym && sym->var ? atViews_.find(sym->var) : atViews_.end();
      if (it == atViews_.end()) {
        error(a->range, "BITADR needs a variable located in the process image (AT %I, %Q or %M)");
        return llvm::ConstantInt::get(valueType(rt), 0);
      }
      uint64_t bit = it->second.byteOffset * 8 + static_cast<uint64_t>(std::max(it->second.bit, 0));
      return llvm::ConstantInt::get(valueType(rt), bit);
    }
    case sema::FLeftRight: case sema::FMid: case sema::FInsert: case sema::FDelete: case sema::FReplace: {
      const Type* st = strip(rt);
      if (!st->isString()) return unsupported();
      bool wide = st->kind == TypeKind::WString;
      std::string up = asciiUpper(name);
      if (up[0] == 'W') up = up.substr(1);
      auto fn = [&](const char* base) { return std::string(wide ? "__stc_wstr_" : "__stc_str_") + base; };
      // `t := MID(s, ...)`: the runtime writes straight into t (it copes with
      // t being an argument too), saving the temporary and the copy.
      Address tmp = stringDest_.ptr && strip(stringDest_.type)->kind == st->kind ? stringDest_ : temporary(rt, "str");
      stringDest_ = Address{};
      llvm::Value* cap = b_.getInt64(strip(tmp.type)->length);
      auto s0 = [&](size_t i) { return emitValue(argExpr(i), nullptr); };
      auto n0 = [&](size_t i) { return emitValue(argExpr(i), elementary(TypeKind::LInt)); };
      llvm::Type* v = llvm::Type::getVoidTy(ctx_);
      if (up == "LEFT" || up == "RIGHT")
        b_.CreateCall(runtime(fn(up == "LEFT" ? "left" : "right").c_str(), v, {ptrTy_, i64_, ptrTy_, i64_}), {tmp.ptr, cap, s0(0), n0(1)});
      else if (up == "MID")
        b_.CreateCall(runtime(fn("mid").c_str(), v, {ptrTy_, i64_, ptrTy_, i64_, i64_}), {tmp.ptr, cap, s0(0), n0(1), n0(2)});
      else if (up == "INSERT")
        b_.CreateCall(runtime(fn("insert").c_str(), v, {ptrTy_, i64_, ptrTy_, ptrTy_, i64_}), {tmp.ptr, cap, s0(0), s0(1), n0(2)});
      else if (up == "DELETE")
        b_.CreateCall(runtime(fn("delete").c_str(), v, {ptrTy_, i64_, ptrTy_, i64_, i64_}), {tmp.ptr, cap, s0(0), n0(1), n0(2)});
      else
        b_.CreateCall(runtime(fn("replace").c_str(), v, {ptrTy_, i64_, ptrTy_, ptrTy_, i64_, i64_}), {tmp.ptr, cap, s0(0), s0(1), n0(2), n0(3)});
      return tmp.ptr;
    }
    case sema::FFind: {
      const Type* at = strip(argExpr(0)->type);
      if (!at->isString()) return unsupported();
      const char* f = at->kind == TypeKind::WString ? "__stc_wstr_find" : "__stc_str_find";
      llvm::Value* r = b_.CreateCall(runtime(f, i64_, {ptrTy_, ptrTy_}), {emitValue(argExpr(0), nullptr), emitValue(argExpr(1), nullptr)});
      return b_.CreateTrunc(r, valueType(rt));
    }
    case sema::FTrunc: {
      llvm::Value* v = arg(e, 0, nullptr);
      auto id = strip(rt)->isSignedInt() ? llvm::Intrinsic::fptosi_sat : llvm::Intrinsic::fptoui_sat;
      return b_.CreateIntrinsic(id, {valueType(rt), v->getType()}, {v});
    }
    case sema::FAbs: {
      llvm::Value* v = arg(e, 0, rt);
      if (v->getType()->isFloatingPointTy()) return b_.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, v);
      if (!strip(rt)->isSignedInt()) return v;
      return b_.CreateBinaryIntrinsic(llvm::Intrinsic::abs, v, b_.getFalse());
    }
    case sema::FRealMath: {
      llvm::Value* v = arg(e, 0, rt);
      std::string up = asciiUpper(name);
      if (up == "SQRT") return b_.CreateUnaryIntrinsic(llvm::Intrinsic::sqrt, v);
      if (up == "LN") return b_.CreateUnaryIntrinsic(llvm::Intrinsic::log, v);
      if (up == "LOG") return b_.CreateUnaryIntrinsic(llvm::Intrinsic::log10, v);
      if (up == "EXP") return b_.CreateUnaryIntrinsic(llvm::Intrinsic::exp, v);
      if (up == "SIN") return b_.CreateUnaryIntrinsic(llvm::Intrinsic::sin, v);
      if (up == "COS") return b_.CreateUnaryIntrinsic(llvm::Intrinsic::cos, v);
      bool f32 = v->getType()->isFloatTy();
      std::string fn = asciiLower(up) + (f32 ? "f" : "");
      return b_.CreateCall(runtime(fn.c_str(), v->getType(), {v->getType()}), {v});
    }
    case sema::FAtan2: {
      llvm::Value* y = arg(e, 0, rt);
      llvm::Value* x = arg(e, 1, rt);
      bool f32 = y->getType()->isFloatTy();
      return b_.CreateCall(runtime(f32 ? "atan2f" : "atan2", y->getType(), {y->getType(), y->getType()}), {y, x});
    }
    case sema::FExpt: {
      llvm::Value* x = arg(e, 0, rt);
      const Expr* ex = argExpr(1);
      if (ex && strip(ex->type)->isInteger()) {
        llvm::Value* k = arg(e, 1, elementary(TypeKind::DInt));
        return b_.CreateIntrinsic(llvm::Intrinsic::powi, {x->getType(), i32_}, {x, k});
      }
      return b_.CreateBinaryIntrinsic(llvm::Intrinsic::pow, x, arg(e, 1, rt));
    }
    case sema::FArith: case sema::FMod: {
      std::string up = asciiUpper(name);
      llvm::Value* acc = arg(e, 0, rt);
      bool fp = acc->getType()->isFloatingPointTy();
      for (size_t i = 1; i < n; ++i) {
        llvm::Value* v = arg(e, i, rt);
        if (up == "ADD") acc = fp ? b_.CreateFAdd(acc, v) : b_.CreateAdd(acc, v);
        else if (up == "MUL") acc = fp ? b_.CreateFMul(acc, v) : b_.CreateMul(acc, v);
        else if (up == "SUB") acc = fp ? b_.CreateFSub(acc, v) : b_.CreateSub(acc, v);
        else if (fp) acc = up == "DIV" ? b_.CreateFDiv(acc, v) : b_.CreateFRem(acc, v);
        else acc = intDivide(acc, v, up == "DIV", strip(rt)->isSignedInt(), e);
      }
      return acc;
    }
    case sema::FBitwise: {
      std::string up = asciiUpper(name);
      llvm::Value* acc = arg(e, 0, rt);
      for (size_t i = 1; i < n; ++i) {
        llvm::Value* v = arg(e, i, rt);
        acc = up == "AND" ? b_.CreateAnd(acc, v) : up == "OR" ? b_.CreateOr(acc, v) : b_.CreateXor(acc, v);
      }
      return acc;
    }
    case sema::FShift: {
      llvm::Value* v = arg(e, 0, rt);
      llvm::Value* k = b_.CreateZExtOrTrunc(arg(e, 1, nullptr), v->getType());
      unsigned w = v->getType()->getIntegerBitWidth();
      llvm::Value* width = llvm::ConstantInt::get(v->getType(), w);
      std::string up = asciiUpper(name);
      if (up == "ROL" || up == "ROR")
        return b_.CreateIntrinsic(up == "ROL" ? llvm::Intrinsic::fshl : llvm::Intrinsic::fshr, {v->getType()}, {v, v, b_.CreateURem(k, width)});
      // A shift by the width or more gives 0 (an over-wide shift is poison in LLVM).
      llvm::Value* big = b_.CreateICmpUGE(k, width);
      llvm::Value* safeK = b_.CreateSelect(big, llvm::ConstantInt::get(v->getType(), 0), k);
      llvm::Value* r = up == "SHL" ? b_.CreateShl(v, safeK) : b_.CreateLShr(v, safeK);
      return b_.CreateSelect(big, llvm::ConstantInt::get(v->getType(), 0), r);
    }
    case sema::FSel: {
      if (isAggregate(rt)) {
        // Strings, structures, arrays: choose the address.
        llvm::Value* g = toBool(arg(e, 0, nullptr));
        llvm::Value* a = emitAddr(argExpr(1)).ptr;
        llvm::Value* b = emitAddr(argExpr(2)).ptr;
        return b_.CreateSelect(g, b, a);
      }
      llvm::Value* g = toBool(arg(e, 0, nullptr));
      llvm::Value* a = arg(e, 1, rt);
      llvm::Value* b = arg(e, 2, rt);
      return b_.CreateSelect(g, b, a);
    }
    case sema::FMaxMin: {
      bool isMax = asciiUpper(name) == "MAX";
      if (strip(rt)->isString()) {
        bool wide = strip(rt)->kind == TypeKind::WString;
        llvm::Value* acc = emitValue(argExpr(0), nullptr);
        for (size_t i = 1; i < n; ++i) {
          llvm::Value* v = emitValue(argExpr(i), nullptr);
          llvm::Value* c = b_.CreateCall(runtime(wide ? "__stc_wstr_cmp" : "__stc_str_cmp", i32_, {ptrTy_, ptrTy_}), {v, acc});
          acc = b_.CreateSelect(isMax ? b_.CreateICmpSGT(c, b_.getInt32(0)) : b_.CreateICmpSLT(c, b_.getInt32(0)), v, acc);
        }
        return acc;
      }
      if (isAggregate(rt)) return unsupported();
      llvm::Value* acc = arg(e, 0, rt);
      for (size_t i = 1; i < n; ++i) {
        llvm::Value* v = arg(e, i, rt);
        llvm::Value* gt = emitCompare(isMax ? BinaryOp::Gt : BinaryOp::Lt, v, acc, rt);
        acc = b_.CreateSelect(gt, v, acc);
      }
      return acc;
    }
    case sema::FLimit: {
      if (strip(rt)->isString()) {
        bool wide = strip(rt)->kind == TypeKind::WString;
        auto cmp = [&](llvm::Value* x, llvm::Value* y) {
          return b_.CreateCall(runtime(wide ? "__stc_wstr_cmp" : "__stc_str_cmp", i32_, {ptrTy_, ptrTy_}), {x, y});
        };
        llvm::Value* mn = emitValue(argExpr(0), nullptr);
        llvm::Value* v = emitValue(argExpr(1), nullptr);
        llvm::Value* mx = emitValue(argExpr(2), nullptr);
        v = b_.CreateSelect(b_.CreateICmpSLT(cmp(v, mn), b_.getInt32(0)), mn, v);
        return b_.CreateSelect(b_.CreateICmpSGT(cmp(v, mx), b_.getInt32(0)), mx, v);
      }
      if (isAggregate(rt)) return unsupported();
      llvm::Value* mn = arg(e, 0, rt);
      llvm::Value* v = arg(e, 1, rt);
      llvm::Value* mx = arg(e, 2, rt);
      v = b_.CreateSelect(emitCompare(BinaryOp::Lt, v, mn, rt), mn, v);
      return b_.CreateSelect(emitCompare(BinaryOp::Gt, v, mx, rt), mx, v);
    }
    case sema::FMux: {
      if (isAggregate(rt)) {
        llvm::Value* k = b_.CreateSExtOrTrunc(arg(e, 0, nullptr), i64_);
        llvm::Value* acc = emitAddr(argExpr(n - 1)).ptr;
        for (size_t i = n - 1; i-- > 1;)
          acc = b_.CreateSelect(b_.CreateICmpEQ(k, b_.getInt64(i - 1)), emitAddr(argExpr(i)).ptr, acc);
        return acc;
      }
      llvm::Value* k = b_.CreateSExtOrTrunc(arg(e, 0, nullptr), i64_);
      // Out of range: the last input (CODESYS); evaluate all inputs (no side effects expected).
      llvm::Value* acc = arg(e, n - 1, rt);
      for (size_t i = n - 1; i-- > 1;) {
        llvm::Value* v = arg(e, i, rt);
        acc = b_.CreateSelect(b_.CreateICmpEQ(k, b_.getInt64(i - 1)), v, acc);
      }
      return acc;
    }
    case sema::FCompare: {
      std::string up = asciiUpper(name);
      BinaryOp op = up == "GT" ? BinaryOp::Gt : up == "GE" ? BinaryOp::Ge : up == "EQ" ? BinaryOp::Eq
                    : up == "LE" ? BinaryOp::Le : up == "LT" ? BinaryOp::Lt : BinaryOp::Ne;
      const Type* ot = argExpr(0)->type;
      bool str = strip(ot)->isString();
      bool wide = strip(ot)->kind == TypeKind::WString;
      llvm::Value* res = nullptr;
      for (size_t i = 0; i + 1 < n; ++i) {
        llvm::Value* c;
        if (str) {
          // Strings compare by content (byte or UTF-16 unit order).
          llvm::Value* r = b_.CreateCall(runtime(wide ? "__stc_wstr_cmp" : "__stc_str_cmp", i32_, {ptrTy_, ptrTy_}),
                                         {emitValue(argExpr(i), nullptr), emitValue(argExpr(i + 1), nullptr)});
          c = emitCompare(op, r, b_.getInt32(0), elementary(TypeKind::DInt));
        } else {
          c = emitCompare(op, arg(e, i, ot), arg(e, i + 1, ot), ot);
        }
        res = res ? b_.CreateAnd(res, c) : c;
      }
      return res;
    }
    case sema::FAdr: {
      const Expr* a = argExpr(0);
      return emitAddr(a).ptr;
    }
    case sema::FSizeOf: {
      const Expr* a = argExpr(0);
      uint64_t sz = a && a->type ? sizeOf(a->type) : 0;
      if (auto* nm = dyn_cast<NameExpr>(a); nm && nm->symbol && nm->symbol->kind == Symbol::TypeName) sz = sizeOf(nm->symbol->type);
      return llvm::ConstantInt::get(valueType(rt), sz);
    }
    case sema::FLen: {
      const Expr* a = argExpr(0);
      bool wide = strip(a->type)->kind == TypeKind::WString;
      llvm::Value* p = emitValue(a, nullptr);
      llvm::Value* len = b_.CreateCall(runtime(wide ? "__stc_wstr_len" : "__stc_str_len", i64_, {ptrTy_}), {p});
      return b_.CreateTrunc(len, valueType(rt));
    }
    case sema::FConcat: {
      const Type* st = strip(rt);
      bool wide = st->kind == TypeKind::WString;
      Address tmp = temporary(rt, "concat");
      b_.CreateStore(llvm::ConstantInt::get(wide ? i16_ : i8_, 0), tmp.ptr);
      for (size_t i = 0; i < n; ++i)
        b_.CreateCall(runtime(wide ? "__stc_wstr_append" : "__stc_str_append", llvm::Type::getVoidTy(ctx_), {ptrTy_, i64_, ptrTy_}),
                      {tmp.ptr, b_.getInt64(st->length), arg(e, i, nullptr)});
      return tmp.ptr;
    }
    case sema::FBound: {
      // LOWER_BOUND(arr, dim) / UPPER_BOUND: constants for declared arrays,
      // read from the descriptor for ARRAY[*] parameters.
      const Expr* a = argExpr(0);
      bool lower = asciiUpper(name) == "LOWER_BOUND";
      const Type* at = strip(a->type);
      llvm::Value* dim = b_.CreateSub(arg(e, 1, elementary(TypeKind::LInt)), b_.getInt64(1));
      llvm::Value* r;
      if (isOpenArray(at)) {
        llvm::Value* desc = emitAddr(a).ptr;
        check(b_.CreateICmpULT(dim, b_.getInt64(at->dims.size())), FaultKind::Index, site(argExpr(1), "dimension"));
        llvm::Value* slot = b_.CreateAdd(b_.CreateMul(dim, b_.getInt64(2)), b_.getInt64(lower ? 1 : 2));
        r = b_.CreateAlignedLoad(i64_, b_.CreateInBoundsGEP(i64_, desc, slot), llvm::MaybeAlign(8));
      } else {
        r = b_.getInt64(0);
        for (size_t k = at->dims.size(); k-- > 0;)
          r = b_.CreateSelect(b_.CreateICmpEQ(dim, b_.getInt64(k)), b_.getInt64(static_cast<uint64_t>(lower ? at->dims[k].lo : at->dims[k].hi)), r);
      }
      return b_.CreateTrunc(r, valueType(rt));
    }
    case sema::FFixed: {
      // The typed time arithmetic of IEC table 37 and the CODESYS memory helpers.
      std::string up = asciiUpper(name);
      auto input = [&](const char* pname) -> const Expr* {
        for (const Argument& a : e->args)
          if (a.param && asciiUpper(a.param->name) == pname) return a.value;
        return nullptr;
      };
      auto num = [&](const char* pname) -> llvm::Value* {
        const Expr* x = input(pname);
        return x ? emitValue(x, elementary(TypeKind::LInt)) : static_cast<llvm::Value*>(b_.getInt64(0));
      };
      if (up == "CONCAT_DATE_TOD" || up == "CONCAT_LDATE_LTOD") {
        llvm::Value* d = emitValue(input("DATE"), nullptr);
        llvm::Value* t = emitValue(input("TOD"), nullptr);
        return b_.CreateAdd(d, t);
      }
      if (up == "CONCAT_DATE" || up == "CONCAT_LDATE" || up == "CONCAT_DT" || up == "CONCAT_LDT") {
        llvm::Value* d = b_.CreateCall(runtime("__stc_date_make", i64_, {i64_, i64_, i64_}), {num("YEAR"), num("MONTH"), num("DAY")});
        if (up == "CONCAT_DATE" || up == "CONCAT_LDATE") return d;
        llvm::Value* t = b_.CreateCall(runtime("__stc_tod_make", i64_, {i64_, i64_, i64_, i64_}), {num("HOUR"), num("MINUTE"), num("SECOND"), num("MILLISECOND")});
        return b_.CreateAdd(d, t);
      }
      if (up == "CONCAT_TOD" || up == "CONCAT_LTOD")
        return b_.CreateCall(runtime("__stc_tod_make", i64_, {i64_, i64_, i64_, i64_}), {num("HOUR"), num("MINUTE"), num("SECOND"), num("MILLISECOND")});
      if (up == "DAY_OF_WEEK")
        return b_.CreateTrunc(b_.CreateCall(runtime("__stc_day_of_week", i64_, {i64_}), {emitValue(input("IN"), nullptr)}), valueType(rt));
      if (up.rfind("SPLIT_", 0) == 0) {
        auto* parts = fs_->allocaBuilder->CreateAlloca(llvm::ArrayType::get(i64_, 7), nullptr, "split");
        b_.CreateCall(runtime("__stc_date_split", llvm::Type::getVoidTy(ctx_), {i64_, ptrTy_}), {emitValue(input("IN"), nullptr), parts});
        static const char* names[] = {"YEAR", "MONTH", "DAY", "HOUR", "MINUTE", "SECOND", "MILLISECOND"};
        for (const Argument& a : e->args) {
          if (a.kind != Argument::Output || !a.value || !a.param) continue;
          for (int k = 0; k < 7; ++k)
            if (asciiUpper(a.param->name) == names[k]) {
              llvm::Value* v = b_.CreateAlignedLoad(i64_, b_.CreateConstInBoundsGEP1_64(i64_, parts, static_cast<uint64_t>(k)), llvm::MaybeAlign(8));
              Address dst = emitAddr(a.value);
              store(dst, convert(v, elementary(TypeKind::LInt), dst.type, a.value));
            }
        }
        return nullptr;
      }
      if (up.rfind("ADD_", 0) == 0 || up.rfind("SUB_", 0) == 0 || up.rfind("MUL_", 0) == 0 || up.rfind("DIV_", 0) == 0) {
        const Expr* a = input("IN1");
        const Expr* b = input("IN2");
        if (!a || !b) return unsupported();
        llvm::Value* x = emitValue(a, nullptr);
        if (up[0] == 'A') return b_.CreateAdd(x, emitValue(b, elementary(TypeKind::LTime)));
        if (up[0] == 'S') return b_.CreateSub(x, emitValue(b, elementary(TypeKind::LTime)));
        llvm::Type* d = llvm::Type::getDoubleTy(ctx_);
        llvm::Value* f = emitValue(b, elementary(TypeKind::LReal));
        llvm::Value* tv = b_.CreateSIToFP(x, d);
        llvm::Value* res = up[0] == 'M' ? b_.CreateFMul(tv, f) : b_.CreateFDiv(tv, f);
        return b_.CreateIntrinsic(llvm::Intrinsic::fptosi_sat, {i64_, d}, {b_.CreateUnaryIntrinsic(llvm::Intrinsic::round, res)});
      }
      if (up == "MEMCPY" || up == "MEMMOVE" || up == "MEMSET" || up == "MEMCMP") {
        markSite(e, up);
        const Expr* n = input("N");
        llvm::Value* count = n ? emitValue(n, elementary(TypeKind::ULInt)) : b_.getInt64(0);
        // The byte functions return the number of bytes (CODESYS MemUtils).
        llvm::Value* result = rt && rt->kind != TypeKind::Void && !isAggregate(rt) ? b_.CreateTrunc(count, valueType(rt)) : nullptr;
        if (up == "MEMSET") {
          llvm::Value* dst = emitValue(input("PDEST"), nullptr);
          if (opts_.checks) checkPointerRange(dst, count, e);
          llvm::Value* v = b_.CreateTrunc(emitValue(input("VALUE"), elementary(TypeKind::ULInt)), i8_);
          b_.CreateMemSet(dst, v, count, llvm::MaybeAlign(1));
          return result;
        }
        if (up == "MEMCMP") {
          llvm::Value* p1 = emitValue(input("P1"), nullptr);
          llvm::Value* p2 = emitValue(input("P2"), nullptr);
          if (opts_.checks) {
            checkPointerRange(p1, count, e);
            checkPointerRange(p2, count, e);
          }
          llvm::Value* c = b_.CreateCall(runtime("memcmp", llvm::Type::getInt32Ty(ctx_), {ptrTy_, ptrTy_, i64_}), {p1, p2, count});
          return b_.CreateIntCast(c, valueType(rt), true);
        }
        llvm::Value* dst = emitValue(input("PDEST"), nullptr);
        llvm::Value* src = emitValue(input("PSRC"), nullptr);
        if (opts_.checks) {
          checkPointerRange(dst, count, e);
          checkPointerRange(src, count, e);
        }
        if (up == "MEMCPY") b_.CreateMemCpy(dst, llvm::MaybeAlign(1), src, llvm::MaybeAlign(1), count);
        else b_.CreateMemMove(dst, llvm::MaybeAlign(1), src, llvm::MaybeAlign(1), count);
        return result;
      }
      return unsupported();
    }
    default:
      return unsupported();
  }
}

// vm::CallChain is { uint32 depth; uint32 sites[64] }: the site goes into the
// ring at depth % 64 and depth grows by one; after the call it is restored
// (also when the callee faulted, the task's next activation resets it).
llvm::Value* CodeGen::pushCallSite(uint32_t site) {
  llvm::Value* chain = b_.CreateAlignedLoad(ptrTy_, callChain_, llvm::MaybeAlign(8));
  llvm::Value* depth = b_.CreateAlignedLoad(i32_, chain, llvm::MaybeAlign(4));
  llvm::Value* slot = b_.CreateAdd(b_.CreateAnd(depth, b_.getInt32(63)), b_.getInt32(1));
  b_.CreateAlignedStore(b_.getInt32(site), b_.CreateInBoundsGEP(i32_, chain, slot), llvm::MaybeAlign(4));
  b_.CreateAlignedStore(b_.CreateAdd(depth, b_.getInt32(1)), chain, llvm::MaybeAlign(4));
  return depth;
}

void CodeGen::popCallSite(llvm::Value* depth) {
  b_.CreateAlignedStore(depth, b_.CreateAlignedLoad(ptrTy_, callChain_, llvm::MaybeAlign(8)), llvm::MaybeAlign(4));
}

}  // namespace stc::codegen
