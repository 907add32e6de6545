// The rules in which the CODESYS dialect (the default) and strict IEC 61131-3
// (--dialect=iec) differ.  Sema asks `allows(rule)` instead of testing the
// dialect, so each difference is decided in one place: the table in
// DialectRules.cpp, which docs/dialect.md renders with the CODESYS behaviour
// every rule follows.
#pragma once

#include <cstdint>

namespace stc::sema {

enum class Dialect { IEC, Codesys };

enum class DialectRule : uint8_t {
  ImplicitNarrowing,       // INT := DINT, BYTE := INT, UINT := INT, REAL := LREAL: warnings
  IntegerBitString,        // INT <-> WORD, arithmetic on bit strings, bit operations and shifts on integers
  IntegerEnum,             // integers <-> enumerations, arithmetic and comparison on enumerations
  IntegerAsBool,           // an integer variable or expression where a BOOL is expected: warning
  PointerConversions,      // pointer <-> pointer of another type / DWORD / integer, pointer arithmetic and ordering
  ZeroAsNull,              // 0 for a null pointer, interface or reference
  CaseOnBitString,         // CASE on BYTE/WORD/DWORD/BOOL
  ArrayAsPointerArgument,  // an array passed to a POINTER TO parameter without ADR
  PositionalThenNamed,     // Add(1, b := 2)
  IntegerRealFunctions,    // SQRT(i), SIN(i) on integer variables
  StringInOutAnyLength,    // STRING(10) passed to VAR_IN_OUT s : STRING(80)
  UnsignedNegation,        // -w on UINT/WORD
  RegisterWidthTemporaries,  // + - * / MOD on narrow integers computed in the register width (32/64 bits)
  Count_
};

struct DialectRuleInfo {
  DialectRule rule;
  const char* name;       // as in docs/dialect.md
  bool iec, codesys;      // allowed in the dialect
  const char* codesysBehaviour;
};

const DialectRuleInfo& dialectRuleInfo(DialectRule r);
inline bool dialectAllows(Dialect d, DialectRule r) {
  const DialectRuleInfo& i = dialectRuleInfo(r);
  return d == Dialect::IEC ? i.iec : i.codesys;
}

}  // namespace stc::sema
