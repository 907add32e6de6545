#include "sema/Layout.h"

#include <algorithm>

#include "basic/Text.h"
#include "sema/Symbols.h"

namespace stc::sema {

namespace {
uint64_t alignUp(uint64_t v, uint64_t a) { return (v + a - 1) / a * a; }
}  // namespace

bool Layout::isInstanceField(const ast::VarDecl* v) {
  // `x AT %MW10` is a view of the process image, not storage of its own.
  if (!v->address.empty() && v->address.find('*') == std::string::npos) return false;
  switch (v->section) {
    case ast::VarSection::Input: case ast::VarSection::Output: case ast::VarSection::InOut:
    case ast::VarSection::Var: case ast::VarSection::Inst:
      return true;
    default:
      return false;   // VAR_TEMP, VAR_STAT, VAR_EXTERNAL, ...: not part of the instance
  }
}

uint64_t Layout::sizeOf(const Type* t) const {
  if (!t) return 0;
  t = t->underlying();
  if (t->isBool()) return 1;
  if (t->isElementary() && !t->isString()) return t->bits() / 8;
  switch (t->kind) {
    case TypeKind::String: return t->length + 1;
    case TypeKind::WString: return 2 * (static_cast<uint64_t>(t->length) + 1);
    case TypeKind::Pointer: case TypeKind::Reference: return t->wide ? 8 : 4;
    case TypeKind::Interface: return 16;   // {instance, itable}
    case TypeKind::Array: {
      uint64_t n = alignUp(sizeOf(t->element), alignOf(t->element));
      for (const Dim& d : t->dims) {
        if (d.star) return 0;
        // Saturates: sema refuses such arrays, nothing may wrap to a small size.
        if (__builtin_mul_overflow(n, static_cast<uint64_t>(d.hi - d.lo) + 1, &n)) return UINT64_MAX;
      }
      return n;
    }
    case TypeKind::Struct: case TypeKind::Union: case TypeKind::FunctionBlock: case TypeKind::Program:
      return of(t).size;
    default: return 0;
  }
}

uint64_t Layout::alignOf(const Type* t) const {
  if (!t) return 1;
  t = t->underlying();
  switch (t->kind) {
    case TypeKind::Array: return alignOf(t->element);
    case TypeKind::String: return 1;
    case TypeKind::WString: return 2;
    case TypeKind::Struct: case TypeKind::Union: case TypeKind::FunctionBlock: case TypeKind::Program:
      return of(t).align;
    default: {
      uint64_t s = sizeOf(t);
      return s ? std::min<uint64_t>(s, 8) : 1;
    }
  }
}

const TypeLayout& Layout::of(const Type* t) const {
  auto it = cache_.find(t);
  if (it != cache_.end()) return it->second;
  TypeLayout out;
  computeAggregate(t, out);
  return cache_.emplace(t, std::move(out)).first->second;
}

void Layout::computeAggregate(const Type* t, TypeLayout& out) const {
  auto add = [&](std::string name, const Type* type, const ast::VarDecl* decl, bool indirect) {
    uint64_t size = indirect ? 8 : sizeOf(type);
    uint64_t align = indirect ? 8 : alignOf(type);
    FieldLayout f{std::move(name), type, 0, decl, indirect};
    if (t->kind == TypeKind::Struct && type && type->kind == TypeKind::Bit) {
      // CODESYS packs consecutive BIT members into bytes (8 BITs: SIZEOF 1).
      const FieldLayout* prev = out.fields.empty() ? nullptr : &out.fields.back();
      if (prev && prev->bit >= 0 && prev->bit < 7) {
        f.offset = prev->offset;
        f.bit = prev->bit + 1;
      } else {
        f.offset = out.size;
        f.bit = 0;
        out.size += 1;
      }
      out.fields.push_back(std::move(f));
      return;
    }
    if (t->kind == TypeKind::Union) {
      out.size = std::max(out.size, size);
    } else {
      f.offset = alignUp(out.size, align);
      out.size = f.offset + size;
    }
    out.align = std::max(out.align, align);
    out.fields.push_back(std::move(f));
  };
  if (t->kind == TypeKind::Struct || t->kind == TypeKind::Union) {
    std::vector<const Type*> chain;
    for (const Type* s = t; s; s = s->base) chain.insert(chain.begin(), s);
    for (const Type* s : chain)
      for (const Member& m : s->members) add(m.name, m.type, m.decl, false);
  } else if ((t->kind == TypeKind::FunctionBlock || t->kind == TypeKind::Program) && t->pou && t->pou->pou) {
    const PouInfo& pi = *t->pou->pou;
    if (t->kind == TypeKind::FunctionBlock) {
      if (pi.base && pi.base->type) {
        out = of(pi.base->type);   // the base part is a prefix: SUPER^ and upcasts are free
      } else {
        out.hasVptr = true;
        out.size = 8;
        out.align = 8;
        out.fields.push_back(FieldLayout{"__vptr", nullptr, 0, nullptr, false});
      }
    }
    auto addVars = [&](const ast::PouDecl* d) {
      for (const ast::VarBlock& b : d->varBlocks)
        for (const ast::VarDecl* v : b.vars)
          if (isInstanceField(v) && v->section != ast::VarSection::Inst && v->resolvedType)
            add(v->name.name, v->resolvedType, v, v->section == ast::VarSection::InOut);
    };
    if (pi.decl) addVars(pi.decl);
    // VAR_INST of the methods: instance storage that only the method sees.
    if (pi.members)
      for (const Symbol* m : pi.members->symbols())
        if (m->kind == Symbol::Method && m->pou && m->pou->decl && m->pou->owner == t->pou)
          for (const ast::VarBlock& b : m->pou->decl->varBlocks)
            for (const ast::VarDecl* v : b.vars)
              if (v->section == ast::VarSection::Inst && v->resolvedType) add(v->name.name, v->resolvedType, v, false);
  }
  out.size = alignUp(out.size, out.align);
}

const FieldLayout* Layout::field(const Type* aggregate, const ast::VarDecl* decl) const {
  for (const FieldLayout& f : of(aggregate).fields)
    if (f.decl == decl) return &f;
  return nullptr;
}

const FieldLayout* Layout::field(const Type* aggregate, std::string_view name) const {
  const FieldLayout* found = nullptr;
  for (const FieldLayout& f : of(aggregate).fields)
    if (equalsIgnoreCase(f.name, name)) found = &f;   // the last one: a derived member shadows nothing, but be exact
  return found;
}

std::string Layout::signature(const Type* t) const {
  if (!t) return "?";
  const Type* u = t->underlying();
  switch (u->kind) {
    case TypeKind::String: case TypeKind::WString:
      return std::string(u->kind == TypeKind::String ? "STRING(" : "WSTRING(") + std::to_string(u->length) + ")";
    case TypeKind::Array: {
      std::string s = "ARRAY[";
      for (size_t i = 0; i < u->dims.size(); ++i)
        s += (i ? "," : "") + std::to_string(u->dims[i].lo) + ".." + std::to_string(u->dims[i].hi);
      return s + "] OF " + signature(u->element);
    }
    case TypeKind::Pointer: return "POINTER TO " + signature(u->element);
    case TypeKind::Reference: return "REFERENCE TO " + signature(u->element);
    case TypeKind::Struct: case TypeKind::Union: case TypeKind::FunctionBlock: case TypeKind::Program: {
      const TypeLayout& l = of(u);
      std::string s = u->name + "{" + std::to_string(l.size) + ":";
      for (const FieldLayout& f : l.fields)
        s += f.name + "@" + std::to_string(f.offset) + (f.bit >= 0 ? "." + std::to_string(f.bit) : "") + "=" + (f.indirect ? "&" : "") + (f.type ? signature(f.type) : "vptr") + ";";
      return s + "}";
    }
    default: return u->name;
  }
}

static uint64_t fnv1a(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (char c : s) {
    h ^= static_cast<unsigned char>(asciiUpper(c));
    h *= 1099511628211ull;
  }
  return h;
}

uint64_t Layout::hash(const Type* t) const { return fnv1a(signature(t)); }

std::string Layout::pouSignature(const Symbol* pou) const {
  if (!pou || !pou->pou) return "?";
  if (pou->kind == Symbol::FunctionBlock || pou->kind == Symbol::Program) return "FB " + signature(pou->type);
  std::string s = (pou->kind == Symbol::Method ? "METHOD " : "FUNCTION ") + pou->name + "(";
  for (const Symbol* p : pou->pou->params) {
    const char* sec = p->var->section == ast::VarSection::Input ? "IN " : p->var->section == ast::VarSection::Output ? "OUT " : "INOUT ";
    s += sec + signature(p->type) + ";";
  }
  s += ")";
  if (pou->pou->returnType) s += ":" + signature(pou->pou->returnType);
  return s;
}

uint64_t Layout::pouHash(const Symbol* pou) const { return fnv1a(pouSignature(pou)); }

}  // namespace stc::sema
