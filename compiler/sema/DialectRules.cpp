#include "sema/DialectRules.h"

#include <cstddef>

namespace stc::sema {

namespace {
using R = DialectRule;
// In the order of DialectRule.  Where CODESYS warns, Sema warns with the same
// flag in both dialects' wording-free form; IEC refuses.
const DialectRuleInfo kRules[] = {
    {R::ImplicitNarrowing, "implicit narrowing and sign changes", false, true,
     "accepted with a warning (C0195/C0196 \"possible loss of information\", \"possible change of sign\"): -Wnarrowing, -Wsign-conversion"},
    {R::IntegerBitString, "integers and bit strings mix", false, true,
     "INT <-> WORD and the like are silent at the same size (a narrower target warns); + - * / MOD on BYTE/WORD/DWORD; AND/OR/XOR/NOT and "
     "SHL/SHR/ROL/ROR on signed integers; bit strings as array indices"},
    {R::IntegerEnum, "integers and enumerations mix", false, true,
     "an enumeration is its base integer: assignment both ways, arithmetic, comparison with integers; a constant that is no value of "
     "the enumeration warns (-Wenum-value)"},
    {R::IntegerAsBool, "integers as BOOL", false, true,
     "an integer or bit-string value where a BOOL is expected is TRUE when non-zero, with a warning (-Wint-bool-conversion)"},
    {R::PointerConversions, "pointer conversions and arithmetic", false, true,
     "POINTER TO x <-> POINTER TO y, pointers <-> DWORD/LWORD/integers, pointer + integer (bytes), pointer - pointer, < > <= >= on "
     "pointers, pointers compared with integers"},
    {R::ZeroAsNull, "0 as a null reference", false, true, "0 initialises or compares with a pointer, an interface or a reference"},
    {R::CaseOnBitString, "CASE on bit strings", false, true, "CASE selectors of type BYTE, WORD, DWORD, LWORD or BOOL"},
    {R::ArrayAsPointerArgument, "arrays for POINTER TO parameters", false, true,
     "an array passed to a POINTER TO parameter passes its address (2.3 libraries)"},
    {R::PositionalThenNamed, "positional, then named arguments", false, true, "Add(1, b := 2): positional arguments first, then named ones"},
    {R::IntegerRealFunctions, "integers into REAL functions", false, true, "SQRT, LN, SIN ... of an integer variable compute in LREAL"},
    {R::StringInOutAnyLength, "STRING of any length to VAR_IN_OUT", false, true,
     "a STRING(n) variable is passed to a VAR_IN_OUT STRING(m) of another length"},
    {R::UnsignedNegation, "unary minus on unsigned values", false, true, "-x on UINT/WORD/... is the two's complement in the same type"},
    {R::RegisterWidthTemporaries, "integer temporaries in the register width", false, true,
     "+ - * / MOD on integers narrower than the target's registers (32 bits, or 64 with address_model = 64) compute in the register "
     "width; only an assignment, a parameter or a conversion truncates: (i1 + i2) / 2 does not overflow, dw := w + 1 can be 65536, "
     "(w + 1) = 0 is FALSE for w = 65535"},
};
static_assert(sizeof(kRules) / sizeof(kRules[0]) == static_cast<std::size_t>(DialectRule::Count_), "one entry per DialectRule");
}  // namespace

const DialectRuleInfo& dialectRuleInfo(DialectRule r) { return kRules[static_cast<std::size_t>(r)]; }

}  // namespace stc::sema
