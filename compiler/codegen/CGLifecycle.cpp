// FB_INIT and FB_EXIT (CODESYS V3): methods a function block may declare,
// called implicitly.  FB_INIT(bInitRetains, bInCopyCode) runs for every
// instance once its initial values are in place: for the instances in the
// image (programs, GVLs, VAR_STAT) before the first task cycle, with
// bInitRetains FALSE when the retain file restored values (warm start); for an
// instance that is a local of a function or method on every call.  Contained
// instances come first and, along an EXTENDS chain, the base's FB_INIT before
// the derived one's.  FB_EXIT(bInCopyCode) runs for the image's instances
// when the controller stops, in the reverse order.  FB_REINIT belongs to
// online change, which stc does not have; it is an ordinary method here.
#include <algorithm>

#include "basic/Text.h"
#include "codegen/CGInternal.h"

namespace stc::codegen {

using namespace ast;
using sema::Symbol;
using sema::Type;
using sema::TypeKind;

namespace {

uint64_t alignUp(uint64_t v, uint64_t a) { return (v + a - 1) / a * a; }

// The FB_INIT / FB_EXIT method `fb` itself declares (not inherited).
Symbol* ownLifecycleMethod(const Symbol* fb, Lifecycle w) {
  if (!fb || !fb->pou || !fb->pou->members) return nullptr;
  Symbol* m = fb->pou->members->lookupLocal(w == Lifecycle::Init ? "FB_INIT" : "FB_EXIT");
  return m && m->kind == Symbol::Method && m->pou && m->pou->decl && m->pou->decl->hasBody ? m : nullptr;
}

}  // namespace

const StructInitExpr* CodeGen::fbInitArguments(const VarDecl* v) {
  return v && v->type ? v->type->fbInitArgs : nullptr;
}

bool CodeGen::hasLifecycle(const Type* t, Lifecycle w) {
  if (!t) return false;
  auto key = std::make_pair(t, w);
  if (auto it = lifecycleMemo_.find(key); it != lifecycleMemo_.end()) return it->second;
  lifecycleMemo_[key] = false;   // types cannot contain themselves by value; guards anyway
  bool any = false;
  switch (t->kind) {
    case TypeKind::Array:
      any = hasLifecycle(t->element, w);
      break;
    case TypeKind::FunctionBlock:
      for (const Symbol* p = t->pou; p && p->pou && !any; p = p->pou->base) any = ownLifecycleMethod(p, w) != nullptr;
      [[fallthrough]];
    case TypeKind::Struct:
    case TypeKind::Program:
      for (const sema::FieldLayout& f : layout_.of(t).fields)
        if (!any && !f.indirect && f.type && !f.type->isPointer() && !f.type->isReference()) any = hasLifecycle(f.type, w);
      break;
    default:
      break;
  }
  lifecycleMemo_[key] = any;
  return any;
}

void CodeGen::callLifecycleMethod(Symbol* m, llvm::Value* self, llvm::Value* initRetains, const StructInitExpr* args) {
  llvm::Function* f = functionFor(m);
  std::vector<llvm::Value*> args_;
  llvm::FunctionType* ft = f->getFunctionType();
  if (returnsIndirect(m)) args_.push_back(b_.CreateAlloca(valueType(returnTypeOf(m))));
  args_.push_back(self);
  for (Symbol* p : m->pou->params) {
    llvm::Type* pt = ft->getParamType(static_cast<unsigned>(args_.size()));
    std::string up = stc::asciiUpper(p->name);
    const Expr* given = nullptr;   // `fb : T(p := v)` at the instance's declaration
    if (args)
      for (const auto& f : args->fields)
        if (stc::asciiUpper(f.name.name) == up) given = f.value;
    if (isAggregate(p->type) || p->var->section != VarSection::Input) {
      // Passed by address: a temporary with the value given, or the type's default.
      Address tmp = temporary(p->type, p->name.c_str());
      initAt(tmp, p->var->section == VarSection::Input ? given : nullptr);
      args_.push_back(tmp.ptr);
    } else if (given) {
      args_.push_back(convert(emitValue(given, p->type), given->type, p->type, given));
    } else if (up == "BINITRETAINS" && pt->isIntegerTy()) {
      args_.push_back(b_.CreateZExtOrTrunc(initRetains, pt));
    } else {
      args_.push_back(llvm::Constant::getNullValue(pt));   // bInCopyCode FALSE; other inputs: their type's zero
    }
  }
  b_.CreateCall(f, args_);
}

void CodeGen::emitLifecycle(llvm::Value* obj, const Type* t, Lifecycle w, llvm::Value* initRetains, const StructInitExpr* args) {
  if (!hasLifecycle(t, w)) return;
  if (t->kind == TypeKind::Array) {
    uint64_t stride = alignUp(sizeOf(t->element), alignOf(t->element));
    uint64_t count = stride ? sizeOf(t) / stride : 0;
    llvm::Function* fn = b_.GetInsertBlock()->getParent();
    llvm::BasicBlock* pre = b_.GetInsertBlock();
    auto* loop = llvm::BasicBlock::Create(ctx_, "lifecycle.loop", fn);
    auto* done = llvm::BasicBlock::Create(ctx_, "lifecycle.done", fn);
    b_.CreateBr(loop);
    b_.SetInsertPoint(loop);
    llvm::PHINode* i = b_.CreatePHI(i64_, 2);
    i->addIncoming(b_.getInt64(0), pre);
    // FB_EXIT walks the elements from the last to the first.
    llvm::Value* index = w == Lifecycle::Init ? static_cast<llvm::Value*>(i) : b_.CreateSub(b_.getInt64(count - 1), i);
    emitLifecycle(b_.CreateInBoundsGEP(i8_, obj, b_.CreateMul(index, b_.getInt64(stride))), t->element, w, initRetains, args);
    llvm::Value* next = b_.CreateAdd(i, b_.getInt64(1));
    i->addIncoming(next, b_.GetInsertBlock());
    b_.CreateCondBr(b_.CreateICmpULT(next, b_.getInt64(count)), loop, done);
    b_.SetInsertPoint(done);
    return;
  }
  std::vector<const sema::FieldLayout*> fields;
  for (const sema::FieldLayout& f : layout_.of(t).fields)
    if (!f.indirect && f.type && !f.type->isPointer() && !f.type->isReference() && hasLifecycle(f.type, w)) fields.push_back(&f);
  std::vector<Symbol*> chain;   // own methods, base first
  if (t->kind == TypeKind::FunctionBlock)
    for (Symbol* p = t->pou; p && p->pou; p = p->pou->base)
      if (Symbol* m = ownLifecycleMethod(p, w)) chain.insert(chain.begin(), m);
  if (w == Lifecycle::Init) {
    for (const sema::FieldLayout* f : fields)
      emitLifecycle(b_.CreateConstInBoundsGEP1_64(i8_, obj, f->offset), f->type, w, initRetains, fbInitArguments(f->decl));
    for (Symbol* m : chain) callLifecycleMethod(m, obj, initRetains, args);
  } else {
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) callLifecycleMethod(*it, obj, initRetains, nullptr);
    for (auto it = fields.rbegin(); it != fields.rend(); ++it)
      emitLifecycle(b_.CreateConstInBoundsGEP1_64(i8_, obj, (*it)->offset), (*it)->type, w, initRetains);
  }
}

// __stc_fb_init(bInitRetains) and __stc_fb_exit(): the controller calls them
// at start (after the retain file) and at stop.
void CodeGen::emitLifecycleEntryPoints() {
  for (Lifecycle w : {Lifecycle::Init, Lifecycle::Exit}) {
    auto* ft = llvm::FunctionType::get(llvm::Type::getVoidTy(ctx_), {i1_}, false);
    auto* f = llvm::Function::Create(ft, llvm::Function::ExternalLinkage, w == Lifecycle::Init ? "__stc_fb_init" : "__stc_fb_exit", mod_);
    FnState st;
    beginFunction(st, f);
    st.returnBlock = llvm::BasicBlock::Create(ctx_, "return", f);
    llvm::Value* flag = f->getArg(0);
    std::vector<const ImageRoot*> roots;
    for (const ImageRoot& r : out_.image.roots)
      if (!r.alias && r.bit < 0 && r.type && hasLifecycle(r.type, w)) roots.push_back(&r);
    if (w == Lifecycle::Exit) std::reverse(roots.begin(), roots.end());
    for (const ImageRoot* r : roots) {
      // A GVL instance's declaration carries its FB_INIT arguments.
      const VarDecl* decl = nullptr;
      for (const auto& [v, off] : imageOffsets_)
        if (off == r->offset && v->resolvedType == r->type) decl = v;
      emitLifecycle(imageAddr(r->offset), r->type, w, flag, w == Lifecycle::Init ? fbInitArguments(decl) : nullptr);
    }
    if (blockOpen()) b_.CreateBr(st.returnBlock);
    b_.SetInsertPoint(st.returnBlock);
    b_.CreateRetVoid();
    fs_ = nullptr;
  }
}

}  // namespace stc::codegen
