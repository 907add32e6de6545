// Interfaces: fat pointers {instance, itable}.  An itable for (FB, I) is
// {ptr vtable, ptr baseItable..., ptr slot...}: one base pointer per direct
// EXTENDS of I (conversion to a base interface loads it), then one slot per
// method/accessor of I's closure, bases first (docs/vm.md, "Objects").
#include <llvm/IR/Constants.h>

#include <functional>

#include "basic/Text.h"
#include "codegen/CGInternal.h"

namespace stc::codegen {

using namespace stc::ast;

std::vector<std::string> CodeGen::itableKeys(const Type* itf) {
  std::vector<std::string> keys;
  std::function<void(const Type*)> walk = [&](const Type* t) {
    if (!t || !t->pou || !t->pou->pou) return;
    for (Symbol* b : t->pou->pou->interfaces) walk(b->type);
    for (Symbol* m : t->pou->pou->members->symbols()) {
      std::vector<std::string> own;
      if (m->kind == Symbol::Method) own.push_back(asciiUpper(m->name));
      else if (m->kind == Symbol::Property) {
        const PouDecl* d = m->pou ? m->pou->decl : nullptr;
        if (!d || d->getter) own.push_back("__GET_" + asciiUpper(m->name));
        if (!d || d->setter) own.push_back("__SET_" + asciiUpper(m->name));
      }
      for (auto& k : own)
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    }
  };
  walk(itf);
  return keys;
}

llvm::Constant* CodeGen::itableFor(const Type* fb, const Type* itf) {
  auto key = std::make_pair(fb, itf);
  auto it = itables_.find(key);
  if (it != itables_.end()) return it->second;
  std::vector<llvm::Constant*> fields;
  fields.push_back(vtableFor(fb));
  for (Symbol* b : itf->pou->pou->interfaces) fields.push_back(itableFor(fb, b->type));
  const auto& slots = vtableSlots(fb);
  for (const std::string& k : itableKeys(itf)) {
    // The slot holds the vtable index: the call goes through the
    // instance's own vtable, so overrides in derived FBs are honoured.
    int64_t index = -1;
    for (size_t i = 0; i < slots.size(); ++i)
      if (slots[i].first == k) index = static_cast<int64_t>(i);
    fields.push_back(llvm::ConstantInt::get(i64_, static_cast<uint64_t>(index)));
  }
  auto* init = llvm::ConstantStruct::getAnon(ctx_, fields);
  auto* g = new llvm::GlobalVariable(mod_, init->getType(), true, llvm::GlobalValue::InternalLinkage, init,
                                     "st." + fb->name + ".__itable." + itf->name);
  itables_[key] = g;
  return g;
}

// The instance pointer of an interface-valued expression (or of an FB
// instance, or NULL for the literal 0 / NULL).
llvm::Value* CodeGen::interfaceSelf(const Expr* e) {
  const Type* t = e->type ? strip(e->type) : nullptr;
  if (!t || t->kind == TypeKind::Null) return llvm::ConstantPointerNull::get(ptrTy_);
  if (auto* lit = dyn_cast<LiteralExpr>(e); lit && lit->litKind == LiteralExpr::Int) return llvm::ConstantPointerNull::get(ptrTy_);
  if (t->kind == TypeKind::FunctionBlock) return instancePtr(e);
  if (t->kind == TypeKind::Interface) return b_.CreateAlignedLoad(ptrTy_, emitValue(e, nullptr), llvm::MaybeAlign(8));
  if (t->isPointer()) return emitValue(e, nullptr);
  return llvm::ConstantPointerNull::get(ptrTy_);
}

void CodeGen::assignInterface(Address dst, const Expr* src) {
  const Type* to = strip(dst.type);
  const Type* st = src->type ? strip(src->type) : nullptr;
  llvm::Value* self = llvm::ConstantPointerNull::get(ptrTy_);
  llvm::Value* itable = llvm::ConstantPointerNull::get(ptrTy_);
  if (st && st->kind == TypeKind::FunctionBlock) {
    self = instancePtr(src);
    // The itable of the static type is right for any dynamic type: its
    // slots are vtable indices (see itableFor).
    itable = itableFor(st, to);
  } else if (st && st->kind == TypeKind::Interface) {
    llvm::Value* p = emitValue(src, nullptr);
    self = b_.CreateAlignedLoad(ptrTy_, p, llvm::MaybeAlign(8));
    llvm::Value* srcItable = b_.CreateAlignedLoad(ptrTy_, b_.CreateConstInBoundsGEP1_64(i8_, p, 8), llvm::MaybeAlign(8));
    if (st == to) {
      itable = srcItable;
    } else {
      // Up the EXTENDS chain: follow the base itable pointers.
      std::vector<int> path;
      std::function<bool(const Type*)> find = [&](const Type* cur) -> bool {
        if (cur == to) return true;
        const auto& bases = cur->pou->pou->interfaces;
        for (size_t i = 0; i < bases.size(); ++i) {
          path.push_back(static_cast<int>(i));
          if (find(bases[i]->type)) return true;
          path.pop_back();
        }
        return false;
      };
      find(st);
      llvm::Value* cur = srcItable;
      auto* isNull = b_.CreateIsNull(cur);
      for (int i : path)
        cur = b_.CreateAlignedLoad(ptrTy_, b_.CreateConstInBoundsGEP1_64(ptrTy_, cur, static_cast<uint64_t>(1 + i)), llvm::MaybeAlign(8));
      (void)isNull;
      itable = cur;
    }
  }
  b_.CreateAlignedStore(self, dst.ptr, llvm::MaybeAlign(8));
  b_.CreateAlignedStore(itable, b_.CreateConstInBoundsGEP1_64(i8_, dst.ptr, 8), llvm::MaybeAlign(8));
}

// itf.M(...): the instance (NULL faults) and the function of the slot,
// found through the instance's own vtable.
std::pair<llvm::Value*, llvm::Value*> CodeGen::interfaceSlot(const Expr* receiver, Symbol* method) {
  const Type* itf = strip(receiver->type);
  llvm::Value* p = emitValue(receiver, nullptr);
  llvm::Value* self = b_.CreateAlignedLoad(ptrTy_, p, llvm::MaybeAlign(8));
  check(b_.CreateIsNotNull(self), FaultKind::NullInterface, site(receiver));
  llvm::Value* itable = b_.CreateAlignedLoad(ptrTy_, b_.CreateConstInBoundsGEP1_64(i8_, p, 8), llvm::MaybeAlign(8));
  std::string key = slotKey(method);
  auto keys = itableKeys(itf);
  size_t slot = 0;
  while (slot < keys.size() && keys[slot] != key) ++slot;
  size_t index = 1 + itf->pou->pou->interfaces.size() + slot;
  llvm::Value* vslot = b_.CreateAlignedLoad(i64_, b_.CreateConstInBoundsGEP1_64(ptrTy_, itable, index), llvm::MaybeAlign(8));
  markSite(receiver);
  llvm::Value* vptr = b_.CreateAlignedLoad(ptrTy_, self, llvm::MaybeAlign(8));
  // The slot read (vtable pointer plus the itable's index) must lie in the program's vtables.
  llvm::Value* slotPtr = b_.CreateGEP(ptrTy_, vptr, b_.CreateAdd(vslot, b_.getInt64(2)));
  checkInVtables(slotPtr, receiver);
  llvm::Value* fp = b_.CreateAlignedLoad(ptrTy_, slotPtr, llvm::MaybeAlign(8));
  if (fs_ && fs_->fn) indirectCallers_.insert(fs_->fn);
  return {self, fp};
}

}  // namespace stc::codegen
