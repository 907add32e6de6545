#include "sema/Types.h"

#include <set>

namespace stc::sema {

unsigned Type::bits() const {
  switch (underlying()->kind) {
    case TypeKind::Bool: case TypeKind::Bit: return 1;
    case TypeKind::SInt: case TypeKind::USInt: case TypeKind::Byte: case TypeKind::Char: return 8;
    case TypeKind::Int: case TypeKind::UInt: case TypeKind::Word: case TypeKind::WChar: return 16;
    case TypeKind::DInt: case TypeKind::UDInt: case TypeKind::DWord: case TypeKind::Real: return 32;
    case TypeKind::LInt: case TypeKind::ULInt: case TypeKind::LWord: case TypeKind::LReal: return 64;
    case TypeKind::Time: case TypeKind::LTime: case TypeKind::Date: case TypeKind::LDate:
    case TypeKind::Tod: case TypeKind::LTod: case TypeKind::DT: case TypeKind::LDT:
      return 64;
    default: return 0;
  }
}

const Type* Type::underlying() const {
  const Type* t = this;
  while ((t->kind == TypeKind::Enum || t->kind == TypeKind::Subrange) && t->element) t = t->element;
  return t;
}

Type* TypeContext::make(TypeKind k, std::string name) {
  owned_.push_back(std::make_unique<Type>());
  Type* t = owned_.back().get();
  t->kind = k;
  t->name = std::move(name);
  return t;
}

Type* TypeContext::create(TypeKind k, std::string name) { return make(k, std::move(name)); }

TypeContext::TypeContext() {
  error_ = make(TypeKind::Error, "<error>");
  void_ = make(TypeKind::Void, "VOID");
  null_ = make(TypeKind::Null, "NULL");
  struct E { TypeKind k; const char* names[3]; };
  const E table[] = {
      {TypeKind::Bool, {"BOOL"}}, {TypeKind::Bit, {"BIT"}},
      {TypeKind::SInt, {"SINT"}}, {TypeKind::Int, {"INT"}}, {TypeKind::DInt, {"DINT"}}, {TypeKind::LInt, {"LINT"}},
      {TypeKind::USInt, {"USINT"}}, {TypeKind::UInt, {"UINT"}}, {TypeKind::UDInt, {"UDINT"}}, {TypeKind::ULInt, {"ULINT"}},
      {TypeKind::Byte, {"BYTE"}}, {TypeKind::Word, {"WORD"}}, {TypeKind::DWord, {"DWORD"}}, {TypeKind::LWord, {"LWORD"}},
      {TypeKind::Real, {"REAL"}}, {TypeKind::LReal, {"LREAL"}},
      {TypeKind::Time, {"TIME"}}, {TypeKind::LTime, {"LTIME"}},
      {TypeKind::Date, {"DATE"}}, {TypeKind::LDate, {"LDATE"}},
      {TypeKind::Tod, {"TIME_OF_DAY", "TOD"}}, {TypeKind::LTod, {"LTIME_OF_DAY", "LTOD"}},
      {TypeKind::DT, {"DATE_AND_TIME", "DT"}}, {TypeKind::LDT, {"LDATE_AND_TIME", "LDT"}},
      {TypeKind::Char, {"CHAR"}}, {TypeKind::WChar, {"WCHAR"}},
  };
  for (const E& e : table) {
    const Type* t = make(e.k, e.names[0]);
    elementary_[e.k] = t;
    for (const char* n : e.names)
      if (n) byName_[n] = t;
  }
  // CODESYS pointer-sized integers (64-bit target).
  byName_["__XWORD"] = elementary_[TypeKind::LWord];
  byName_["__UXINT"] = elementary_[TypeKind::ULInt];
  byName_["__XINT"] = elementary_[TypeKind::LInt];
  byName_["STRING"] = string(80, false);
  byName_["WSTRING"] = string(80, true);
}

const Type* TypeContext::elementary(TypeKind k) const {
  auto it = elementary_.find(k);
  return it == elementary_.end() ? error_ : it->second;
}

const Type* TypeContext::byName(const std::string& n) const {
  auto it = byName_.find(n);
  return it == byName_.end() ? nullptr : it->second;
}

const Type* TypeContext::string(uint32_t length, bool wide) {
  auto key = std::make_pair(length, wide);
  auto it = strings_.find(key);
  if (it != strings_.end()) return it->second;
  Type* t = make(wide ? TypeKind::WString : TypeKind::String,
                 std::string(wide ? "WSTRING(" : "STRING(") + std::to_string(length) + ")");
  t->length = length;
  strings_[key] = t;
  return t;
}

const Type* TypeContext::pointer(const Type* to, bool wide) {
  wide = wide || !address32_;
  auto it = pointers_.find({to, wide});
  if (it != pointers_.end()) return it->second;
  Type* t = make(TypeKind::Pointer, "POINTER TO " + to->name);
  t->element = to;
  t->wide = wide;
  pointers_[{to, wide}] = t;
  return t;
}

const Type* TypeContext::reference(const Type* to, bool wide) {
  wide = wide || !address32_;
  auto it = references_.find({to, wide});
  if (it != references_.end()) return it->second;
  Type* t = make(TypeKind::Reference, "REFERENCE TO " + to->name);
  t->element = to;
  t->wide = wide;
  references_[{to, wide}] = t;
  return t;
}

const Type* TypeContext::array(const Type* element, std::vector<Dim> dims) {
  std::string key = std::to_string(reinterpret_cast<uintptr_t>(element));
  std::string name = "ARRAY[";
  for (size_t i = 0; i < dims.size(); ++i) {
    std::string d = dims[i].star ? "*" : std::to_string(dims[i].lo) + ".." + std::to_string(dims[i].hi);
    key += "," + d;
    name += (i ? ", " : "") + d;
  }
  auto it = arrays_.find(key);
  if (it != arrays_.end()) return it->second;
  Type* t = make(TypeKind::Array, name + "] OF " + element->name);
  t->element = element;
  t->dims = std::move(dims);
  arrays_[key] = t;
  return t;
}

const Type* TypeContext::subrange(const Type* base, int64_t lo, int64_t hi) {
  std::string key = base->name + "(" + std::to_string(lo) + ".." + std::to_string(hi) + ")";
  auto it = subranges_.find(key);
  if (it != subranges_.end()) return it->second;
  Type* t = make(TypeKind::Subrange, key);
  t->element = base;
  t->lo = lo;
  t->hi = hi;
  subranges_[key] = t;
  return t;
}

bool isMirrored(const Type* t) {
  for (int guard = 0; t && guard < 64; t = t->base, ++guard)
    if (t->mirrored) return true;
  return false;
}

namespace {

// Depth-first over the types held by value; `seen` ends containment cycles (an error that
// sema reports, but expressions in such a program are still checked) and shared subtypes.
bool holdsMirroredIn(const Type* t, std::set<const Type*>& seen) {
  while (t && t->kind == TypeKind::Array) t = t->element;
  if (!t || !seen.insert(t).second) return false;
  if (t->isPouInstance()) return true;   // its fields are not walked here: assume so
  if (!t->isStructured()) return false;
  if (isMirrored(t)) return true;
  int guard = 0;
  for (const Type* s = t; s && guard < 64; s = s->base, ++guard)
    for (const Member& m : s->members)
      if (holdsMirroredIn(m.type, seen)) return true;
  return false;
}

}  // namespace

bool holdsMirrored(const Type* t) {
  std::set<const Type*> seen;
  return holdsMirroredIn(t, seen);
}

}  // namespace stc::sema
