// The read-only view of a checked program that later stages (code
// generation, the virtual controller's symbol map) work from.  Valid while
// the Sema that produced it lives (the Compilation owns both).
#pragma once

#include <set>
#include <vector>

#include "ast/AST.h"
#include "sema/Layout.h"
#include "sema/Sema.h"
#include "sema/Symbols.h"
#include "sema/Types.h"

namespace stc::sema {

// Builtin (generic standard) functions: their family and checker data.
enum BuiltinFamily {
  FConvert, FToGeneric, FAbs, FRealMath, FAtan2, FExpt, FArith, FMod, FMove, FShift, FSel, FMaxMin, FLimit, FMux,
  FCompare, FLen, FLeftRight, FMid, FConcat, FInsert, FDelete, FReplace, FFind, FFixed, FAdr, FBitAdr, FIsValidRef, FSizeOf,
  FIsValid, FIsValidBcd, FEndian, FTrunc, FRound, FBound, FToBcd, FFromBcd, FBitwise,
};
int builtinFamily(const Symbol* s);       // -1 if not a builtin
int builtinData(const Symbol* s);         // FConvert: from*100+to (indices of elementaryName)
const char* elementaryName(int index);

struct Model {
  TypeContext* types = nullptr;
  const Layout* layout = nullptr;
  Dialect dialect = Dialect::IEC;
  unsigned addressBits = 32;   // 32: user pointers are 4 bytes, the program's memory lies below 4 GiB
  // Every POU with a body: programs, functions, FBs, methods, actions,
  // property accessors, in declaration order.
  std::vector<Symbol*> pous;
  std::vector<ast::GlobalVarDecl*> globalLists;     // VAR_GLOBAL blocks (GVLs), source order
  std::vector<ast::ConfigurationDecl*> configurations;
  // PROGRAMs some POU calls (their own instance then runs, whatever the configuration says).
  std::set<const Symbol*> calledPrograms;
  // Some ST code names a field of an {attribute 'mirrored'} struct (AXIS_REF_SM3 ...)
  // or takes the address of a value holding one: the natives must keep those
  // structs current in every cycle (else they may leave them alone).
  bool readsMirrored = false;
  // Symbol of a POU's own name, for each POU declaration.
  Symbol* symbolOf(const ast::PouDecl* d) const { return d ? d->symbol : nullptr; }
};

}  // namespace stc::sema
