// The memory layout of every ST type: sizes, alignments and field offsets.
// This is the one layout of the toolchain: SIZEOF, code generation, the
// virtual controller's memory image and the native binding API all use it.
// Natural alignment capped at 8 bytes (x86-64 System V, what CODESYS uses on
// 64-bit targets).  No LLVM here.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sema/Types.h"

namespace stc::ast { struct VarDecl; }

namespace stc::sema {

struct Symbol;

struct FieldLayout {
  std::string name;                     // declared spelling
  const Type* type = nullptr;           // the declared type (VAR_IN_OUT: the parameter type; stored as a pointer)
  uint64_t offset = 0;
  const ast::VarDecl* decl = nullptr;   // null for the vptr
  bool indirect = false;                // VAR_IN_OUT field: holds the address of the bound variable
  int bit = -1;                         // a BIT member of a STRUCT: bit `bit` of the byte at `offset`
};

struct TypeLayout {
  uint64_t size = 0, align = 1;
  bool hasVptr = false;                 // function blocks: a vtable pointer at offset 0
  std::vector<FieldLayout> fields;      // struct/union members (base first), FB/program variables
};

class Layout {
public:
  uint64_t sizeOf(const Type* t) const;
  uint64_t alignOf(const Type* t) const;
  // Struct, union, function block, program.  Other kinds get an empty layout.
  const TypeLayout& of(const Type* t) const;
  const FieldLayout* field(const Type* aggregate, const ast::VarDecl* decl) const;
  const FieldLayout* field(const Type* aggregate, std::string_view name) const;   // case-insensitive
  // Stable FNV-1a over kinds, sizes, offsets and member names: equal for
  // equal layouts, across runs and machines (the native binding check).
  uint64_t hash(const Type* t) const;
  // A readable description of the layout-relevant shape (retain files).
  std::string signature(const Type* t) const;

  // The ABI-relevant shape of a FUNCTION, METHOD or FUNCTION_BLOCK (the
  // native binding check compares these): parameters, result, instance layout.
  std::string pouSignature(const Symbol* pou) const;
  uint64_t pouHash(const Symbol* pou) const;

  // Which POU variables are fields of an instance (FB, program).
  static bool isInstanceField(const ast::VarDecl* v);
  // Forgets computed layouts (sema may ask for SIZEOF before every variable
  // type is resolved; the final layouts are computed afresh).
  void reset() { cache_.clear(); }

private:
  void computeAggregate(const Type* t, TypeLayout& out) const;
  mutable std::map<const Type*, TypeLayout> cache_;
};

}  // namespace stc::sema
