// Semantic types.  Interned by TypeContext: two types are the same type iff
// their pointers are equal.  Aliases (TYPE T : INT) are transparent.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace stc::ast { struct VarDecl; struct TypeDecl; struct PouDecl; }

namespace stc::sema {

struct Symbol;

enum class TypeKind {
  Error,   // after a reported error; compatible with everything, never re-reported
  Void,
  Bool, Bit,
  SInt, Int, DInt, LInt, USInt, UInt, UDInt, ULInt,
  Byte, Word, DWord, LWord,
  Real, LReal,
  Time, LTime, Date, LDate, Tod, LTod, DT, LDT,
  String, WString, Char, WChar,
  Array, Struct, Union, Enum, Subrange, Pointer, Reference,
  FunctionBlock, Program, Interface,
  Null,    // the literal 0 / NULL as a pointer or interface value (CODESYS)
};

struct Member {
  std::string name;
  const class Type* type = nullptr;
  ast::VarDecl* decl = nullptr;
};

struct Dim {
  int64_t lo = 0, hi = -1;
  bool star = false;   // ARRAY[*]
};

class Type {
public:
  TypeKind kind = TypeKind::Error;
  std::string name;                       // display name
  // String/WString
  uint32_t length = 0;
  // Array
  const Type* element = nullptr;          // also Pointer/Reference pointee, Subrange/Enum base
  std::vector<Dim> dims;
  // Struct / Union
  std::vector<Member> members;
  const Type* base = nullptr;             // STRUCT EXTENDS
  // Enum
  std::vector<std::pair<std::string, int64_t>> enumValues;
  // Subrange
  int64_t lo = 0, hi = 0;
  // FunctionBlock / Program / Interface
  Symbol* pou = nullptr;
  const ast::TypeDecl* decl = nullptr;
  // Struct declared {attribute 'mirrored'}: natives refresh its fields from their own
  // state; they may skip that work while nobody reads them (Model::readsMirrored).
  bool mirrored = false;
  // Pointer/Reference: stored in 8 bytes.  In the 32-bit address model user-visible
  // pointers take 4 bytes (as on the controller); the native libraries' own
  // structures keep 8-byte slots (their C++ side is compiled once).
  bool wide = true;

  bool isError() const { return kind == TypeKind::Error; }
  bool isBool() const { return kind == TypeKind::Bool || kind == TypeKind::Bit; }
  bool isSignedInt() const { return kind >= TypeKind::SInt && kind <= TypeKind::LInt; }
  bool isUnsignedInt() const { return kind >= TypeKind::USInt && kind <= TypeKind::ULInt; }
  bool isInteger() const { return isSignedInt() || isUnsignedInt(); }
  bool isBitString() const { return kind >= TypeKind::Byte && kind <= TypeKind::LWord; }
  bool isAnyBit() const { return isBitString() || isBool(); }
  bool isReal() const { return kind == TypeKind::Real || kind == TypeKind::LReal; }
  bool isNumeric() const { return isInteger() || isReal(); }
  bool isDuration() const { return kind == TypeKind::Time || kind == TypeKind::LTime; }
  bool isDate() const { return kind >= TypeKind::Date && kind <= TypeKind::LDT; }
  bool isString() const { return kind == TypeKind::String || kind == TypeKind::WString; }
  bool isChar() const { return kind == TypeKind::Char || kind == TypeKind::WChar; }
  bool isElementary() const { return kind >= TypeKind::Bool && kind <= TypeKind::WChar; }
  bool isPointer() const { return kind == TypeKind::Pointer; }
  bool isReference() const { return kind == TypeKind::Reference; }
  bool isPouInstance() const { return kind == TypeKind::FunctionBlock || kind == TypeKind::Program; }
  bool isStructured() const { return kind == TypeKind::Struct || kind == TypeKind::Union; }
  // Size in bits of integer/bit types (BOOL = 1).
  unsigned bits() const;
  // The underlying integer type of enums and subranges, else this.
  const Type* underlying() const;
};

// Whether a value of type t is, or holds by value (arrays, struct members and
// bases, FB and program instances, conservatively), an {attribute 'mirrored'} struct.
bool holdsMirrored(const Type* t);
// Whether t is an {attribute 'mirrored'} struct or extends one.
bool isMirrored(const Type* t);

class TypeContext {
public:
  TypeContext();
  const Type* error() const { return error_; }
  const Type* voidType() const { return void_; }
  const Type* null() const { return null_; }
  const Type* elementary(TypeKind k) const;
  // Looks up an elementary type by (upper-case) IEC name; null if none.
  const Type* byName(const std::string& upperName) const;
  const Type* string(uint32_t length, bool wide);
  // Pointers and references: 4 bytes in the 32-bit address model unless `wide`.
  const Type* pointer(const Type* to, bool wide = false);
  const Type* reference(const Type* to, bool wide = false);
  // The 32-bit address model (set before any pointer type is made): pointers are 4 bytes.
  void setAddress32(bool on) { address32_ = on; }
  bool address32() const { return address32_; }
  const Type* array(const Type* element, std::vector<Dim> dims);
  const Type* subrange(const Type* base, int64_t lo, int64_t hi);
  // Named derived types: created once, filled by the caller.
  Type* create(TypeKind k, std::string name);

private:
  Type* make(TypeKind k, std::string name);
  std::vector<std::unique_ptr<Type>> owned_;
  std::map<TypeKind, const Type*> elementary_;
  std::map<std::string, const Type*> byName_;
  const Type *error_, *void_, *null_;
  std::map<std::pair<uint32_t, bool>, const Type*> strings_;
  std::map<std::pair<const Type*, bool>, const Type*> pointers_, references_;
  bool address32_ = false;
  std::map<std::string, const Type*> arrays_;
  std::map<std::string, const Type*> subranges_;
};

}  // namespace stc::sema
