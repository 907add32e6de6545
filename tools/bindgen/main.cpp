// stc_bindgen: ST declarations of native POUs -> a C++ header.
//
//   stc_bindgen OUT.h NAMESPACE FILE.st...
//
// For every POU marked {attribute 'native'} in the given files it writes the
// instance struct (function blocks) with static_asserts on each offset and
// the size, the C function type with the ST calling convention, and the
// declaration's hash that the implementation registers (vm/Native.h).  The
// layout comes from sema::Layout, the one layout of the toolchain, so C++ and
// ST cannot disagree without the build failing.
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include "basic/Text.h"
#include "driver/Driver.h"
#include "sema/Model.h"

using namespace stc;
using sema::Type;
using sema::TypeKind;

namespace {

struct Gen {
  const sema::Layout& layout;
  std::ostringstream out;
  std::set<const Type*> emitted;

  // C++ name of an ST type: a namespace's dot becomes '_' (TRAFO.CONFIGDATA -> TRAFO_CONFIGDATA).
  static std::string cName(const std::string& st) {
    std::string n = st;
    for (char& ch : n)
      if (ch == '.') ch = '_';
    return n;
  }

  // {attribute 'native_layout'}: an ST block the natives read (its instance struct is
  // emitted) but which has no native body.
  static bool hasAttribute(const sema::Symbol* s, const char* name) {
    if (!s->pou || !s->pou->decl) return false;
    for (const ast::Pragma& p : s->pou->decl->attributes)
      if (equalsIgnoreCase(p.name, name)) return true;
    return false;
  }

  static bool isNative(const sema::Symbol* s) {
    if (!s->pou || !s->pou->decl) return false;
    for (const ast::Pragma& p : s->pou->decl->attributes)
      if (equalsIgnoreCase(p.name, "native")) return true;
    // An ACTION of a native FB is native too (the compiler calls native.<FB>.<Action>(self)).
    if (s->kind == sema::Symbol::Action && s->pou->owner && s->pou->owner != s) return isNative(s->pou->owner);
    return false;
  }

  // C type of a scalar (or the struct name of an aggregate); `suffix` gets array extents.
  std::string cType(const Type* t, std::string& suffix) {
    t = t->underlying();
    switch (t->kind) {
      case TypeKind::Bool: case TypeKind::Bit: return "bool";
      case TypeKind::SInt: return "int8_t";
      case TypeKind::Int: return "int16_t";
      case TypeKind::DInt: return "int32_t";
      case TypeKind::LInt: return "int64_t";
      case TypeKind::USInt: case TypeKind::Byte: case TypeKind::Char: return "uint8_t";
      case TypeKind::UInt: case TypeKind::Word: case TypeKind::WChar: return "uint16_t";
      case TypeKind::UDInt: case TypeKind::DWord: return "uint32_t";
      case TypeKind::ULInt: case TypeKind::LWord: return "uint64_t";
      case TypeKind::Real: return "float";
      case TypeKind::LReal: return "double";
      case TypeKind::Time: case TypeKind::LTime: case TypeKind::Date: case TypeKind::LDate:
      case TypeKind::Tod: case TypeKind::LTod: case TypeKind::DT: case TypeKind::LDT:
        return "int64_t";   // nanoseconds
      case TypeKind::Pointer: case TypeKind::Reference:
        // Untyped, but a structure it points to is emitted so the native can cast to it.
        if (t->element && t->element->underlying()->kind == TypeKind::Struct) emitStruct(t->element->underlying());
        return "void*";
      // The characters are the innermost dimension: ARRAY[0..2] OF STRING(255) is char[3][256].
      case TypeKind::String: suffix += "[" + std::to_string(t->length + 1) + "]"; return "char";
      case TypeKind::WString: suffix += "[" + std::to_string(t->length + 1) + "]"; return "char16_t";
      case TypeKind::Interface: return "stc_interface";
      case TypeKind::Array: {
        uint64_t count = 1;
        for (const sema::Dim& d : t->dims) count *= static_cast<uint64_t>(d.hi - d.lo + 1);
        suffix += "[" + std::to_string(count) + "]";
        return cType(t->element, suffix);
      }
      case TypeKind::Struct: case TypeKind::Union: case TypeKind::FunctionBlock: case TypeKind::Program:
        emitStruct(t);
        return cName(t->name);
      default: return "void";
    }
  }

  // A VAR_IN_OUT field holds an address: typed for a structure (emitted
  // first, so the implementation can use its members), untyped otherwise.
  std::string inOutType(const Type* t) {
    const Type* u = t->underlying();
    if (u->kind != TypeKind::Struct && u->kind != TypeKind::FunctionBlock) return "void*";
    std::string suffix;
    return cType(u, suffix) + "*";
  }

  void emitStruct(const Type* t) {
    if (!emitted.insert(t).second) return;
    const std::string tn = cName(t->name);
    const sema::TypeLayout& l = layout.of(t);
    std::ostringstream body;
    std::vector<std::string> asserts;
    uint64_t pos = 0;
    unsigned pad = 0;
    bool isUnion = t->kind == TypeKind::Union;
    for (const sema::FieldLayout& f : l.fields) {
      if (!isUnion && f.offset > pos) body << "  uint8_t _pad" << pad++ << "[" << f.offset - pos << "];\n";
      std::string suffix;
      std::string ct = !f.type ? "const void*" : f.indirect ? inOutType(f.type) : cType(f.type, suffix);
      std::string name = f.type ? f.name : "__vptr";
      body << "  " << ct << " " << name << suffix << ";   // offset " << f.offset << (f.indirect ? ", VAR_IN_OUT (address)" : "") << "\n";
      asserts.push_back("static_assert(offsetof(" + tn + ", " + name + ") == " + std::to_string(f.offset) + ");");
      uint64_t size = !f.type || f.indirect ? 8 : layout.sizeOf(f.type);
      if (!isUnion) pos = f.offset + size;
    }
    if (!isUnion && l.size > pos) body << "  uint8_t _pad" << pad++ << "[" << l.size - pos << "];\n";
    // A UNION's members share offset 0: a C++ union (a struct would lay them out one after another).
    out << (isUnion ? "union" : "struct") << " alignas(" << l.align << ") " << tn << (isUnion ? "_u" : "") << " {\n" << body.str() << "};\n";
    if (isUnion) out << "using " << tn << " = " << tn << "_u;\n";
    out << "static_assert(sizeof(" << tn << ") == " << l.size << ");\n";
    for (auto& a : asserts) out << a << "\n";
    out << "inline constexpr uint64_t " << tn << "_layout = " << layout.hash(t) << "ull;\n";
    // The ST name the vtable carries (natives identify an interface's block by it).
    out << "inline constexpr const char* " << tn << "_typename = \"" << t->name << "\";\n\n";
  }

  std::string paramType(const Type* t, bool byPointer, bool isConst) {
    std::string suffix;
    std::string ct = cType(t, suffix);
    bool aggregate = !suffix.empty() || ct == cName(t->underlying()->name) || ct == "stc_interface";
    if (byPointer || aggregate) return (isConst && !byPointer ? "const " : "") + ct + "*";
    return ct;
  }

  void emitPou(sema::Symbol* pou) {
    std::string name = pou->pou->owner ? pou->pou->owner->name + "_" + pou->name : pou->name;
    out << "// " << layout.pouSignature(pou) << "\n";
    if (pou->kind == sema::Symbol::FunctionBlock) {
      emitStruct(pou->type);
      out << "using " << name << "_fn = void(" << pou->name << "* self);\n";
    } else {
      std::vector<std::string> params;
      std::string ret = "void";
      const Type* rt = pou->pou->returnType;
      if (rt && rt->kind != TypeKind::Void) {
        std::string suffix;
        std::string ct = cType(rt, suffix);
        if (!suffix.empty() || rt->underlying()->isStructured() || rt->underlying()->isString()) params.push_back(ct + "* result");
        else ret = ct;
      }
      if (pou->kind == sema::Symbol::Method || pou->kind == sema::Symbol::Action) params.push_back(pou->pou->owner->name + "* self");
      for (const sema::Symbol* p : pou->pou->params) {
        ast::VarSection sec = p->var->section;
        params.push_back(paramType(p->type, sec != ast::VarSection::Input, true) + " " + p->name);
      }
      out << "using " << name << "_fn = " << ret << "(";
      for (size_t i = 0; i < params.size(); ++i) out << (i ? ", " : "") << params[i];
      out << ");\n";
    }
    out << "inline constexpr uint64_t " << name << "_hash = " << layout.pouHash(pou) << "ull;\n";
    out << "inline constexpr const char* " << name << "_name = \"" << (pou->pou->owner ? pou->pou->owner->name + "." + pou->name : pou->name)
        << "\";\n\n";
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: stc_bindgen OUT.h NAMESPACE [--no-stdlib] FILE.st...\n";
    return 2;
  }
  // --no-stdlib: the files are the standard library itself.
  bool stdlib = true;
  int first = 3;
  if (std::string(argv[3]) == "--no-stdlib") {
    stdlib = false;
    first = 4;
  }
  Compilation c;
  for (int i = first; i < argc; ++i) {
    if (!c.addPath(argv[i])) return 1;
  }
  CompileOptions o;
  o.includeStdlib = stdlib;
  // The library's own files: built into stc, their pointers keep 8-byte slots in
  // either address model, so the headers are the same for both.
  o.addressBits = 64;
  bool ok = false;
  runWithLargeStack([&] { ok = c.check(o); });
  for (const Diagnostic& d : c.diags().diagnostics()) std::cerr << renderText(c.sources(), d);
  if (!ok || !c.model()) return 1;
  const sema::Model& m = *c.model();
  Gen g{*m.layout, {}, {}};
  g.out << "// Generated by stc_bindgen from the ST declarations of the library.  Do not edit:\n"
           "// change the .st file; the build regenerates this header.\n"
           "#pragma once\n#include <cstddef>\n#include <cstdint>\n\n"
           "#ifndef STC_INTERFACE_DEFINED\n#define STC_INTERFACE_DEFINED\nstruct stc_interface { void* self; const void* itable; };\n#endif\n\n"
           "namespace "
        << argv[2] << " {\n\n";
  for (sema::Symbol* p : m.pous) {
    // Only the library's own declarations (not the standard library's).
    const bool layoutOnly = p->kind == sema::Symbol::FunctionBlock && Gen::hasAttribute(p, "native_layout");
    if ((!Gen::isNative(p) && !layoutOnly) || p->declRange.begin.file == 0) continue;
    std::string path = c.sources().file(p->declRange.begin.file).path;
    bool mine = false;
    for (int i = first; i < argc; ++i) mine = mine || path == argv[i];
    if (mine && layoutOnly) g.emitStruct(p->type);
    else if (mine) g.emitPou(p);
  }
  g.out << "}  // namespace " << argv[2] << "\n";
  std::ofstream f(argv[1]);
  f << g.out.str();
  return f ? 0 : 1;
}
