// The generic standard functions of IEC 61131-3 (and the CODESYS helpers that
// vendor code uses).  Each has a checker computing the result type from the
// argument types; fixed-signature functions (time/date, memory) get
// synthetic parameter symbols and reuse the ordinary argument checking.
// docs/stdlib.md lists them with their status.
#include <algorithm>

#include "sema/SemaInternal.h"

namespace stc::sema {

namespace {

const char* const kElementary[] = {"BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT",
                                   "BYTE", "WORD", "DWORD", "LWORD", "REAL", "LREAL", "TIME", "LTIME", "DATE",
                                   "LDATE", "TOD", "LTOD", "DT", "LDT", "TIME_OF_DAY", "DATE_AND_TIME", "STRING",
                                   "WSTRING", "CHAR", "WCHAR"};


}  // namespace

// Positional view of a builtin call; named arguments are matched against
// `names` (several spellings per position, IEC first, CODESYS second).
static bool bindArgs(SemaImpl& S, CallExpr* call, const std::vector<std::vector<std::string>>& names, size_t minArgs, bool extensible,
                     const std::string& fn, std::vector<Expr*>& out) {
  out.clear();
  bool named = std::any_of(call->args.begin(), call->args.end(), [](const Argument& a) { return a.kind != Argument::Positional; });
  if (!named) {
    for (Argument& a : call->args) {
      if (!a.value) {
        S.diags_.error(a.range.begin, "missing argument in the call to '" + fn + "'", "call-args").range(a.range);
        return false;
      }
      out.push_back(a.value);
    }
  } else {
    for (Argument& a : call->args) {
      if (a.kind == Argument::Positional) {
        S.diags_.error(a.range.begin, "cannot mix positional and named arguments in the call to '" + fn + "'", "call-args").range(a.range);
        return false;
      }
      if (a.kind == Argument::Output) {
        S.diags_.error(a.range.begin, "'" + fn + "' has no outputs", "call-args").range(a.range);
        return false;
      }
      std::string up = upperCase(a.name.name);
      size_t pos = SIZE_MAX;
      for (size_t i = 0; i < names.size() && pos == SIZE_MAX; ++i)
        for (const std::string& n : names[i])
          if (n == up) pos = i;
      // Extensible functions: IN1, IN2, ... beyond the listed names.
      if (pos == SIZE_MAX && extensible && up.size() > 2 && up.rfind("IN", 0) == 0) {
        int k = std::atoi(up.c_str() + 2);
        if (k >= 0) {
          // INk sits after the named leading parameters (MUX: K, IN0, IN1, ...).
          size_t in0 = SIZE_MAX, in1 = SIZE_MAX;
          for (size_t j = 0; j < names.size(); ++j) {
            if (names[j][0] == "IN0") in0 = j;
            if (names[j][0] == "IN1") in1 = j;
          }
          if (in0 != SIZE_MAX) pos = in0 + static_cast<size_t>(k);
          else if (k > 0) pos = (in1 != SIZE_MAX ? in1 : 0) + static_cast<size_t>(k - 1);
        }
      }
      if (pos == SIZE_MAX) {
        std::vector<std::string> cands;
        for (auto& v : names) cands.push_back(v[0]);
        std::string hint = closestMatch(a.name.name, cands);
        S.diags_.error(a.name.range.begin, "'" + fn + "' has no parameter named '" + a.name.name + "'" +
                                               (hint.empty() ? "" : "; did you mean '" + hint + "'?"), "call-args").range(a.name.range);
        return false;
      }
      if (out.size() <= pos) out.resize(pos + 1, nullptr);
      if (out[pos]) {
        S.diags_.error(a.name.range.begin, "parameter '" + a.name.name + "' is given more than once", "call-args").range(a.name.range);
        return false;
      }
      out[pos] = a.value;
    }
    for (size_t i = 0; i < out.size(); ++i)
      if (!out[i]) {
        S.diags_.error(call->range.begin, "missing argument '" + (i < names.size() ? names[i][0] : "IN" + std::to_string(i)) + "' in the call to '" + fn + "'",
                       "call-args").range(call->range);
        return false;
      }
  }
  size_t maxArgs = extensible ? SIZE_MAX : names.size();
  if (out.size() < minArgs || out.size() > maxArgs) {
    std::string expect = extensible ? "at least " + std::to_string(minArgs) : minArgs == maxArgs ? std::to_string(minArgs)
                                                                                            : std::to_string(minArgs) + " to " + std::to_string(maxArgs);
    S.diags_.error(call->range.begin, "'" + fn + "' takes " + expect + " argument" + (expect == "1" ? "" : "s") + ", " +
                                          std::to_string(out.size()) + " given", "call-args").range(call->parenRange);
    return false;
  }
  call->orderedArgs = out;
  return true;
}

int builtinFamily(const Symbol* s) { return s && s->builtin ? s->builtin->arg0 : -1; }
int builtinData(const Symbol* s) { return s && s->builtin ? s->builtin->arg1 : 0; }
const char* elementaryName(int index) { return index >= 0 && index < static_cast<int>(std::size(kElementary)) ? kElementary[index] : ""; }

static const Type* builtinCheck(SemaImpl& S, const Builtin& b, CallExpr* call, const Type* expected, const Context& ctx);

void SemaImpl::registerBuiltins() {
  auto add = [&](const std::string& name, int family, int a1 = 0) {
    auto bi = std::make_unique<Builtin>();
    bi->name = name;
    bi->check = builtinCheck;
    bi->arg0 = family;
    bi->arg1 = a1;
    builtinMap_[name] = bi.get();
    Symbol* s = newSymbol(Symbol::BuiltinFunction, name, SourceRange{});
    s->builtin = bi.get();
    builtinSymbols_[name] = s;
    builtins_.push_back(std::move(bi));
  };
  // Every X_TO_Y of the elementary types (INT_TO_REAL, DINT_TO_STRING, LREAL_TO_STRING, ...)
  // and the generic TO_Y.
  int n = static_cast<int>(std::size(kElementary));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      if (i != j) add(std::string(kElementary[i]) + "_TO_" + kElementary[j], FConvert, i * 100 + j);
    add(std::string("TO_") + kElementary[i], FToGeneric, i);
  }
  // The bit-string forms (BYTE_TO_BCD, BCD_TO_WORD ...) are CODESYS Util / OSCAT names.
  for (const char* t : {"SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "BYTE", "WORD", "DWORD", "LWORD"}) {
    add(std::string("BCD_TO_") + t, FFromBcd);
    add(std::string(t) + "_TO_BCD", FToBcd);
  }
  for (const char* t : {"BYTE_BCD_TO_USINT", "WORD_BCD_TO_UINT", "DWORD_BCD_TO_UDINT", "LWORD_BCD_TO_ULINT"}) add(t, FFromBcd);
  for (const char* t : {"USINT_TO_BCD_BYTE", "UINT_TO_BCD_WORD", "UDINT_TO_BCD_DWORD", "ULINT_TO_BCD_LWORD"}) add(t, FToBcd);
  add("ABS", FAbs);
  for (const char* f : {"SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN"}) add(f, FRealMath);
  add("ATAN2", FAtan2);
  add("EXPT", FExpt);
  for (const char* f : {"ADD", "MUL", "SUB", "DIV"}) add(f, FArith);
  add("MOD", FMod);
  add("MOVE", FMove);
  for (const char* f : {"SHL", "SHR", "ROL", "ROR"}) add(f, FShift);
  add("SEL", FSel);
  for (const char* f : {"AND", "OR", "XOR"}) add(f, FBitwise);   // function forms: AND(a, b, ...)
  add("MAX", FMaxMin);
  add("MIN", FMaxMin);
  add("LIMIT", FLimit);
  add("MUX", FMux);
  for (const char* f : {"GT", "GE", "EQ", "LE", "LT", "NE"}) add(f, FCompare);
  for (const char* p : {"", "W"}) {
    std::string w = p;
    add(w + "LEN", FLen);
    add(w + "LEFT", FLeftRight);
    add(w + "RIGHT", FLeftRight);
    add(w + "MID", FMid);
    add(w + "CONCAT", FConcat);
    add(w + "INSERT", FInsert);
    add(w + "DELETE", FDelete);
    add(w + "REPLACE", FReplace);
    add(w + "FIND", FFind);
  }
  add("ADR", FAdr);
  add("REF", FAdr);   // IEC REF(x): a REF_TO value
  add("BITADR", FBitAdr);
  add("__ISVALIDREF", FIsValidRef);
  add("SIZEOF", FSizeOf);
  add("IS_VALID", FIsValid);
  add("IS_VALID_BCD", FIsValidBcd);
  for (const char* f : {"TO_BIG_ENDIAN", "TO_LITTLE_ENDIAN", "BIG_ENDIAN_TO", "LITTLE_ENDIAN_TO"}) add(f, FEndian);
  add("TRUNC", FTrunc);
  // Typed truncations: TRUNC_INT (CODESYS), REAL_TRUNC_INT / LREAL_TRUNC_DINT (IEC).
  const std::pair<const char*, TypeKind> ints[] = {{"SINT", TypeKind::SInt}, {"INT", TypeKind::Int}, {"DINT", TypeKind::DInt},
                                                   {"LINT", TypeKind::LInt}, {"USINT", TypeKind::USInt}, {"UINT", TypeKind::UInt},
                                                   {"UDINT", TypeKind::UDInt}, {"ULINT", TypeKind::ULInt}};
  for (auto [n, k] : ints)
    for (const char* prefix : {"", "REAL_", "LREAL_"}) add(std::string(prefix) + "TRUNC_" + n, FTrunc, static_cast<int>(k) + 1);
  add("ROUND", FRound);
  add("LOWER_BOUND", FBound);
  add("UPPER_BOUND", FBound);

  // Fixed signatures: name, result, parameters (name, type, output?).
  struct P { const char* name; const char* type; bool out; };
  struct F { const char* name; const char* result; std::vector<P> params; };
  const std::vector<F> fixed = {
      {"ADD_TIME", "TIME", {{"IN1", "TIME", false}, {"IN2", "TIME", false}}},
      {"ADD_LTIME", "LTIME", {{"IN1", "LTIME", false}, {"IN2", "LTIME", false}}},
      {"SUB_TIME", "TIME", {{"IN1", "TIME", false}, {"IN2", "TIME", false}}},
      {"SUB_LTIME", "LTIME", {{"IN1", "LTIME", false}, {"IN2", "LTIME", false}}},
      {"MUL_TIME", "TIME", {{"IN1", "TIME", false}, {"IN2", "LREAL", false}}},
      {"MUL_LTIME", "LTIME", {{"IN1", "LTIME", false}, {"IN2", "LREAL", false}}},
      {"DIV_TIME", "TIME", {{"IN1", "TIME", false}, {"IN2", "LREAL", false}}},
      {"DIV_LTIME", "LTIME", {{"IN1", "LTIME", false}, {"IN2", "LREAL", false}}},
      {"ADD_TOD_TIME", "TOD", {{"IN1", "TOD", false}, {"IN2", "TIME", false}}},
      {"ADD_LTOD_LTIME", "LTOD", {{"IN1", "LTOD", false}, {"IN2", "LTIME", false}}},
      {"ADD_DT_TIME", "DT", {{"IN1", "DT", false}, {"IN2", "TIME", false}}},
      {"ADD_LDT_LTIME", "LDT", {{"IN1", "LDT", false}, {"IN2", "LTIME", false}}},
      {"SUB_TOD_TIME", "TOD", {{"IN1", "TOD", false}, {"IN2", "TIME", false}}},
      {"SUB_LTOD_LTIME", "LTOD", {{"IN1", "LTOD", false}, {"IN2", "LTIME", false}}},
      {"SUB_TOD_TOD", "TIME", {{"IN1", "TOD", false}, {"IN2", "TOD", false}}},
      {"SUB_LTOD_LTOD", "LTIME", {{"IN1", "LTOD", false}, {"IN2", "LTOD", false}}},
      {"SUB_DT_TIME", "DT", {{"IN1", "DT", false}, {"IN2", "TIME", false}}},
      {"SUB_LDT_LTIME", "LDT", {{"IN1", "LDT", false}, {"IN2", "LTIME", false}}},
      {"SUB_DT_DT", "TIME", {{"IN1", "DT", false}, {"IN2", "DT", false}}},
      {"SUB_LDT_LDT", "LTIME", {{"IN1", "LDT", false}, {"IN2", "LDT", false}}},
      {"SUB_DATE_DATE", "TIME", {{"IN1", "DATE", false}, {"IN2", "DATE", false}}},
      {"SUB_LDATE_LDATE", "LTIME", {{"IN1", "LDATE", false}, {"IN2", "LDATE", false}}},
      {"CONCAT_DATE_TOD", "DT", {{"DATE", "DATE", false}, {"TOD", "TOD", false}}},
      {"CONCAT_LDATE_LTOD", "LDT", {{"DATE", "LDATE", false}, {"TOD", "LTOD", false}}},
      {"CONCAT_DATE", "DATE", {{"YEAR", "UINT", false}, {"MONTH", "USINT", false}, {"DAY", "USINT", false}}},
      {"CONCAT_LDATE", "LDATE", {{"YEAR", "UINT", false}, {"MONTH", "USINT", false}, {"DAY", "USINT", false}}},
      {"CONCAT_TOD", "TOD", {{"HOUR", "USINT", false}, {"MINUTE", "USINT", false}, {"SECOND", "USINT", false}, {"MILLISECOND", "UINT", false}}},
      {"CONCAT_LTOD", "LTOD", {{"HOUR", "USINT", false}, {"MINUTE", "USINT", false}, {"SECOND", "USINT", false}, {"MILLISECOND", "UINT", false}}},
      {"CONCAT_DT", "DT", {{"YEAR", "UINT", false}, {"MONTH", "USINT", false}, {"DAY", "USINT", false}, {"HOUR", "USINT", false},
                           {"MINUTE", "USINT", false}, {"SECOND", "USINT", false}, {"MILLISECOND", "UINT", false}}},
      {"CONCAT_LDT", "LDT", {{"YEAR", "UINT", false}, {"MONTH", "USINT", false}, {"DAY", "USINT", false}, {"HOUR", "USINT", false},
                             {"MINUTE", "USINT", false}, {"SECOND", "USINT", false}, {"MILLISECOND", "UINT", false}}},
      {"SPLIT_DATE", "VOID", {{"IN", "DATE", false}, {"YEAR", "UINT", true}, {"MONTH", "USINT", true}, {"DAY", "USINT", true}}},
      {"SPLIT_LDATE", "VOID", {{"IN", "LDATE", false}, {"YEAR", "UINT", true}, {"MONTH", "USINT", true}, {"DAY", "USINT", true}}},
      {"SPLIT_TOD", "VOID", {{"IN", "TOD", false}, {"HOUR", "USINT", true}, {"MINUTE", "USINT", true}, {"SECOND", "USINT", true}, {"MILLISECOND", "UINT", true}}},
      {"SPLIT_LTOD", "VOID", {{"IN", "LTOD", false}, {"HOUR", "USINT", true}, {"MINUTE", "USINT", true}, {"SECOND", "USINT", true}, {"MILLISECOND", "UINT", true}}},
      {"SPLIT_DT", "VOID", {{"IN", "DT", false}, {"YEAR", "UINT", true}, {"MONTH", "USINT", true}, {"DAY", "USINT", true}, {"HOUR", "USINT", true},
                            {"MINUTE", "USINT", true}, {"SECOND", "USINT", true}, {"MILLISECOND", "UINT", true}}},
      {"SPLIT_LDT", "VOID", {{"IN", "LDT", false}, {"YEAR", "UINT", true}, {"MONTH", "USINT", true}, {"DAY", "USINT", true}, {"HOUR", "USINT", true},
                             {"MINUTE", "USINT", true}, {"SECOND", "USINT", true}, {"MILLISECOND", "UINT", true}}},
      {"DAY_OF_WEEK", "USINT", {{"IN", "DATE", false}}},
      {"MEMCPY", "UDINT", {{"PDEST", "POINTER", false}, {"PSRC", "POINTER", false}, {"N", "UDINT", false}}},
      {"MEMMOVE", "UDINT", {{"PDEST", "POINTER", false}, {"PSRC", "POINTER", false}, {"N", "UDINT", false}}},
      {"MEMSET", "UDINT", {{"PDEST", "POINTER", false}, {"VALUE", "BYTE", false}, {"N", "UDINT", false}}},
      {"MEMCMP", "DINT", {{"P1", "POINTER", false}, {"P2", "POINTER", false}, {"N", "UDINT", false}}},
  };
  for (const F& f : fixed) {
    add(f.name, FFixed);
    Symbol* s = builtinSymbols_[f.name];
    s->pou = std::make_unique<PouInfo>();
    s->pou->vars = std::make_unique<Scope>();
    s->pou->members = std::make_unique<Scope>();
    s->pou->signatureResolved = true;
    auto tyOf = [&](const std::string& n) -> const Type* {
      if (n == "VOID") return types_.voidType();
      if (n == "POINTER") return types_.pointer(types_.elementary(TypeKind::Byte));
      return types_.byName(n);
    };
    s->pou->returnType = tyOf(f.result);
    for (const P& p : f.params) {
      auto* v = ast_.make<VarDecl>();
      v->name.name = p.name;
      v->section = p.out ? VarSection::Output : VarSection::Input;
      Symbol* ps = newSymbol(Symbol::Variable, p.name, SourceRange{});
      ps->var = v;
      ps->type = tyOf(p.type);
      v->resolvedType = ps->type;
      s->pou->params.push_back(ps);
    }
  }
}

const Builtin* SemaImpl::findBuiltin(const std::string& upper) const {
  auto it = builtinMap_.find(upper);
  return it == builtinMap_.end() ? nullptr : it->second;
}

// ------------------------------------------------------------------ checking

static const Type* builtinCheck(SemaImpl& S, const Builtin& b, CallExpr* call, const Type* expected, const Context& ctx) {
  const std::string& fn = b.name;
  TypeContext& T = S.types_;
  std::vector<Expr*> a;
  auto checkAll = [&](const Type* exp = nullptr) {
    for (Expr* e : a) S.checkExpr(e, ctx, exp);
  };
  auto argTypes = [&]() {
    std::vector<const Type*> ts;
    for (Expr* e : a) ts.push_back(S.valueType(e->type ? e->type : T.error()));
    return ts;
  };
  auto anyError = [&]() {
    for (Expr* e : a)
      if (!e->type || e->type->isError()) return true;
    return false;
  };
  auto bad = [&](Expr* e, const std::string& need) -> const Type* {
    S.diags_.error(e->range.begin, "argument of '" + fn + "' must be " + need + ", not '" + S.valueType(e->type)->name + "'", "type-mismatch")
        .range(e->range);
    return T.error();
  };
  // Common type of all arguments (for MAX, SEL, ADD ...), reporting mismatches.
  auto common = [&](size_t from) -> const Type* {
    // Typed arguments first, so literals adapt.
    const Type* t = nullptr;
    for (size_t i = from; i < a.size(); ++i)
      if (!S.isUntypedLiteral(a[i])) {
        const Type* at = S.valueType(S.checkExpr(a[i], ctx));
        if (at->isError()) return T.error();
        if (!t) t = at;
        else if (t->isString() && at->isString() && t->kind == at->kind) t = t->length >= at->length ? t : at;   // the longer string
        else if (t != at) t = S.commonType(t, at, a[from], a[i], a[i]->range.begin, fn.c_str());
        if (t->isError()) return t;
      }
    for (size_t i = from; i < a.size(); ++i)
      if (S.isUntypedLiteral(a[i])) {
        const Type* at = S.valueType(S.checkExpr(a[i], ctx, t ? t : expected));
        if (!t) t = at;
        else if (t->isString() && at->isString() && t->kind == at->kind) t = t->length >= at->length ? t : at;
        else if (t != at) t = S.commonType(t, at, a[from], a[i], a[i]->range.begin, fn.c_str());
      }
    return t ? t : T.error();
  };
  auto isStr = [&](const Type* t) { return t->isString(); };
  auto strResult = [&](const Type* like, uint64_t len) {
    return T.string(static_cast<uint32_t>(std::min<uint64_t>(std::max<uint64_t>(len, 1), 65535)), like->kind == TypeKind::WString);
  };
  const std::vector<std::string> IN = {"IN"};
  switch (b.arg0) {
    case FConvert:
    case FToGeneric: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      int toIdx = b.arg0 == FConvert ? b.arg1 % 100 : b.arg1;
      const Type* to = T.byName(kElementary[toIdx]);
      if (to->kind == TypeKind::String || to->kind == TypeKind::WString) to = T.string(255, to->kind == TypeKind::WString);
      if (b.arg0 == FToGeneric) {
        const Type* at = S.valueType(S.checkExpr(a[0], ctx));
        if (!at->isError() && !at->underlying()->isElementary())
          return bad(a[0], "an elementary value");
        return to;
      }
      const Type* from = T.byName(kElementary[b.arg1 / 100]);
      if (from->isString()) from = T.string(255, from->kind == TypeKind::WString);
      S.checkExpr(a[0], ctx, from);
      const Type* at = S.valueType(a[0]->type);
      if (at->isError()) return to;
      if (at->kind == TypeKind::Enum && (from->isInteger() || from->isBitString())) return to;   // enum to its integer
      S.checkConversion(from, a[0], "argument");
      return to;
    }
    case FFromBcd: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      checkAll();
      if (anyError()) return T.error();
      const Type* at = argTypes()[0]->underlying();
      if (!(at->isBitString() || (S.allows(DialectRule::IntegerBitString) && at->isInteger()))) return bad(a[0], "a bit string (BYTE, WORD, DWORD or LWORD)");
      std::string target = fn.substr(fn.rfind('_') + 1);
      return T.byName(target);
    }
    case FToBcd: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      std::string src = fn.substr(0, fn.find('_'));
      S.checkExpr(a[0], ctx, T.byName(src));
      if (anyError()) return T.error();
      S.checkConversion(T.byName(src), a[0], "argument");
      unsigned bits = T.byName(src)->bits();
      return T.elementary(bits == 8 ? TypeKind::Byte : bits == 16 ? TypeKind::Word : bits == 32 ? TypeKind::DWord : TypeKind::LWord);
    }
    case FAbs: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      checkAll(expected);
      if (anyError()) return T.error();
      const Type* t = argTypes()[0];
      if (!t->underlying()->isNumeric() && !t->isDuration()) return bad(a[0], "a number");
      return t;
    }
    case FRealMath: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      const Type* exp = expected && S.valueType(expected)->isReal() ? S.valueType(expected) : T.elementary(TypeKind::LReal);
      checkAll(exp);
      if (anyError()) return T.error();
      const Type* t = argTypes()[0];
      if (t->isReal()) return t;
      if (t->underlying()->isInteger()) {
        if (!S.allows(DialectRule::IntegerRealFunctions) && !S.isUntypedLiteral(a[0])) return bad(a[0], "REAL or LREAL (convert integers explicitly in IEC mode)");
        return T.elementary(TypeKind::LReal);
      }
      return bad(a[0], "REAL or LREAL");
    }
    case FAtan2:
    case FExpt: {
      if (!bindArgs(S, call, b.arg0 == FAtan2 ? std::vector<std::vector<std::string>>{{"Y", "IN1"}, {"X", "IN2"}}
                                                : std::vector<std::vector<std::string>>{{"IN1"}, {"IN2"}}, 2, false, fn, a))
        return T.error();
      checkAll(T.elementary(TypeKind::LReal));
      if (anyError()) return T.error();
      auto ts = argTypes();
      for (size_t i = 0; i < 2; ++i)
        if (!ts[i]->underlying()->isNumeric()) return bad(a[i], "a number");
      if (b.arg0 == FExpt) {
        // An untyped base takes the exponent's REAL type (EXPT(10.0, e) with e : REAL is REAL).
        if (S.isUntypedLiteral(a[0]) && ts[1]->kind == TypeKind::Real && !S.isUntypedLiteral(a[1])) return T.elementary(TypeKind::Real);
        return ts[0]->isReal() ? ts[0] : T.elementary(TypeKind::LReal);
      }
      return (ts[0]->kind == TypeKind::LReal || ts[1]->kind == TypeKind::LReal || !ts[0]->isReal() || !ts[1]->isReal())
                 ? T.elementary(TypeKind::LReal) : T.elementary(TypeKind::Real);
    }
    case FArith:
    case FMod: {
      bool ext = fn == "ADD" || fn == "MUL";
      if (!bindArgs(S, call, {{"IN1"}, {"IN2"}}, 2, ext, fn, a)) return T.error();
      const Type* t = common(0);
      if (t->isError()) return t;
      const Type* u = t->underlying();
      if (b.arg0 == FMod ? !(u->isInteger() || (S.allows(DialectRule::IntegerBitString) && u->isBitString())) : !(u->isNumeric() || u->isDuration() || (S.allows(DialectRule::IntegerBitString) && u->isBitString())))
        return bad(a[0], b.arg0 == FMod ? "an integer" : "a number");
      return t;
    }
    case FBitwise: {
      if (!bindArgs(S, call, {{"IN1"}, {"IN2"}}, 2, true, fn, a)) return T.error();
      const Type* t = common(0);
      if (t->isError()) return t;
      const Type* u = t->underlying();
      if (!(u->isAnyBit() || (S.allows(DialectRule::IntegerBitString) && u->isInteger()))) return bad(a[0], "BOOL or a bit string");
      return t;
    }
    case FMove: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      checkAll(expected);
      return anyError() ? T.error() : argTypes()[0];
    }
    case FShift: {
      if (!bindArgs(S, call, {{"IN"}, {"N"}}, 2, false, fn, a)) return T.error();
      S.checkExpr(a[0], ctx, expected);
      S.checkExpr(a[1], ctx, T.elementary(TypeKind::Int));
      if (anyError()) return T.error();
      auto ts = argTypes();
      const Type* u = ts[0]->underlying();
      if (!(u->isBitString() || (S.allows(DialectRule::IntegerBitString) && u->isInteger()))) return bad(a[0], "a bit string (BYTE, WORD, DWORD, LWORD)");
      if (!(ts[1]->underlying()->isInteger() || (S.allows(DialectRule::IntegerBitString) && ts[1]->underlying()->isBitString()))) return bad(a[1], "an integer");
      return ts[0];
    }
    case FSel: {
      if (!bindArgs(S, call, {{"G"}, {"IN0"}, {"IN1"}}, 3, false, fn, a)) return T.error();
      S.checkExpr(a[0], ctx, T.elementary(TypeKind::Bool));
      if (a[0]->type && !a[0]->type->isError()) S.checkConversion(T.elementary(TypeKind::Bool), a[0], "argument");
      if (!S.isUntypedLiteral(a[1]) && !S.isUntypedLiteral(a[2])) {
        const Type* t1 = S.valueType(S.checkExpr(a[1], ctx, expected));
        const Type* t2 = S.valueType(S.checkExpr(a[2], ctx, t1));
        if (t1->isError() || t2->isError()) return T.error();
        if (t1 == t2) return t1;
        if (t1->isString() && t2->isString() && t1->kind == t2->kind) return t1->length >= t2->length ? t1 : t2;
      }
      return common(1);
    }
    case FMaxMin:
    case FLimit: {
      if (b.arg0 == FLimit) {
        if (!bindArgs(S, call, {{"MN"}, {"IN"}, {"MX"}}, 3, false, fn, a)) return T.error();
      } else if (!bindArgs(S, call, {{"IN1"}, {"IN2"}}, 2, true, fn, a)) {
        return T.error();
      }
      const Type* t = common(0);
      if (t->isError()) return t;
      const Type* u = t->underlying();
      if (!(u->isElementary() || u->kind == TypeKind::Enum)) return bad(a[0], "an elementary value");
      return t;
    }
    case FMux: {
      if (!bindArgs(S, call, {{"K"}, {"IN0"}, {"IN1"}}, 3, true, fn, a)) return T.error();
      S.checkExpr(a[0], ctx, T.elementary(TypeKind::Int));
      if (a[0]->type && !a[0]->type->isError() && !S.valueType(a[0]->type)->underlying()->isInteger()) return bad(a[0], "an integer");
      return common(1);
    }
    case FCompare: {
      if (!bindArgs(S, call, {{"IN1"}, {"IN2"}}, 2, fn != "NE", fn, a)) return T.error();
      const Type* t = common(0);
      if (t->isError()) return t;
      return T.elementary(TypeKind::Bool);
    }
    case FLen: {
      if (!bindArgs(S, call, {{"IN", "STR"}}, 1, false, fn, a)) return T.error();
      checkAll();
      if (anyError()) return T.error();
      if (!isStr(argTypes()[0])) return bad(a[0], "a string");
      return T.elementary(TypeKind::Int);
    }
    case FLeftRight:
    case FMid:
    case FDelete: {
      std::vector<std::vector<std::string>> names = {{"IN", "STR"}, {"L", "SIZE", "LEN"}};
      if (b.arg0 != FLeftRight) names.push_back({"P", "POS"});
      if (!bindArgs(S, call, names, names.size(), false, fn, a)) return T.error();
      S.checkExpr(a[0], ctx);
      for (size_t i = 1; i < a.size(); ++i) S.checkExpr(a[i], ctx, T.elementary(TypeKind::Int));
      if (anyError()) return T.error();
      auto ts = argTypes();
      if (!isStr(ts[0])) return bad(a[0], "a string");
      for (size_t i = 1; i < a.size(); ++i) S.checkConversion(T.elementary(TypeKind::Int), a[i], "argument");
      return strResult(ts[0], ts[0]->length);
    }
    case FConcat:
    case FInsert:
    case FReplace:
    case FFind: {
      std::vector<std::vector<std::string>> names = {{"IN1", "STR1"}, {"IN2", "STR2"}};
      if (b.arg0 == FInsert) names.push_back({"P", "POS"});
      if (b.arg0 == FReplace) { names.push_back({"L", "LEN"}); names.push_back({"P", "POS"}); }
      if (!bindArgs(S, call, names, names.size(), b.arg0 == FConcat, fn, a)) return T.error();
      size_t nStr = b.arg0 == FConcat ? a.size() : 2;
      for (size_t i = 0; i < a.size(); ++i) S.checkExpr(a[i], ctx, i < nStr ? nullptr : T.elementary(TypeKind::Int));
      if (anyError()) return T.error();
      auto ts = argTypes();
      uint64_t len = 0;
      for (size_t i = 0; i < nStr; ++i) {
        if (!isStr(ts[i])) return bad(a[i], "a string");
        if (ts[i]->kind != ts[0]->kind) return bad(a[i], ts[0]->kind == TypeKind::String ? "a STRING" : "a WSTRING");
        len += ts[i]->length;
      }
      for (size_t i = nStr; i < a.size(); ++i) S.checkConversion(T.elementary(TypeKind::Int), a[i], "argument");
      if (b.arg0 == FFind) return T.elementary(TypeKind::Int);
      return strResult(ts[0], b.arg0 == FReplace ? len : len);
    }
    case FAdr:
    case FBitAdr: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      const Type* t = S.checkExpr(a[0], ctx);
      if (t->isError()) return t;
      std::string why;
      Symbol* decl = nullptr;
      if (!S.isLvalue(a[0], ctx, why, &decl)) {
        S.diags_.error(a[0]->range.begin, "cannot take the address of " + why, "not-assignable").range(a[0]->range);
        return T.error();
      }
      if (b.arg0 == FAdr && t->kind == TypeKind::Bit) {
        S.diags_.error(a[0]->range.begin, "cannot take the address of a BIT member: it is one bit of a byte", "not-assignable").range(a[0]->range);
        return T.error();
      }
      if (decl && decl->var && decl->var->isConstant) {
        S.diags_.error(a[0]->range.begin, "cannot take the address of constant '" + decl->name + "'", "assign-constant")
            .range(a[0]->range).note(decl->declRange.begin, "declared CONSTANT here", decl->declRange);
        return T.error();
      }
      // Through an address ST may read any byte of the value.
      if (holdsMirrored(S.valueType(t))) S.model_.readsMirrored = true;
      // ADR(<function name>): the result is written through the pointer (2.3 libraries).
      if (S.body_ && decl && decl == S.body_->resultVar) S.body_->resultAssigned = true;
      if (b.arg0 == FBitAdr) return T.elementary(TypeKind::DWord);
      return T.pointer(S.valueType(t));
    }
    case FIsValidRef: {
      // CODESYS __ISVALIDREF(r): whether REFERENCE TO variable r is bound.
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      const Type* t = S.checkExpr(a[0], ctx);
      if (t->isError()) return t;
      const Symbol* sym = nullptr;
      if (auto* n = dyn_cast<NameExpr>(a[0])) sym = n->symbol;
      else if (auto* m = dyn_cast<MemberExpr>(a[0])) sym = m->symbol;
      if (!sym || !sym->var || !sym->var->resolvedType || !sym->var->resolvedType->isReference())
        return bad(a[0], "a REFERENCE TO variable");
      return T.elementary(TypeKind::Bool);
    }
    case FSizeOf: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      // SIZEOF(type) or SIZEOF(variable).
      if (auto* n = dyn_cast<NameExpr>(a[0])) {
        QualifiedName q;
        q.parts.push_back(n->ident);
        q.range = n->range;
        std::string up = upperCase(n->ident.name);
        Symbol* s = S.lookup(up, ctx);
        if (T.byName(up) || (s && (s->kind == Symbol::TypeName || s->kind == Symbol::FunctionBlock))) {
          const Type* t = S.resolveNamedType(q, ctx, true);
          n->type = t;
          return t->isError() ? t : T.elementary(TypeKind::UDInt);
        }
      }
      const Type* t = S.checkExpr(a[0], ctx);
      return t->isError() ? t : T.elementary(TypeKind::UDInt);
    }
    case FIsValid:
    case FIsValidBcd: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      checkAll();
      if (anyError()) return T.error();
      const Type* t = argTypes()[0]->underlying();
      if (b.arg0 == FIsValid ? !t->isReal() : !t->isBitString()) return bad(a[0], b.arg0 == FIsValid ? "REAL or LREAL" : "a bit string");
      return T.elementary(TypeKind::Bool);
    }
    case FEndian: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      checkAll(expected);
      if (anyError()) return T.error();
      const Type* t = argTypes()[0];
      if (!(t->underlying()->isInteger() || t->underlying()->isBitString() || t->isReal())) return bad(a[0], "an integer, bit string or real");
      return t;
    }
    case FTrunc:
    case FRound: {
      if (!bindArgs(S, call, {{"IN"}}, 1, false, fn, a)) return T.error();
      checkAll(T.elementary(TypeKind::LReal));
      if (anyError()) return T.error();
      const Type* t = argTypes()[0];
      if (!t->isReal()) return bad(a[0], "REAL or LREAL");
      if (b.arg0 == FTrunc && b.arg1) return T.elementary(static_cast<TypeKind>(b.arg1 - 1));
      return b.arg0 == FTrunc ? T.elementary(TypeKind::DInt) : t;
    }
    case FBound: {
      if (!bindArgs(S, call, {{"ARR"}, {"DIM"}}, 2, false, fn, a)) return T.error();
      const Type* t = S.valueType(S.checkExpr(a[0], ctx));
      S.checkExpr(a[1], ctx, T.elementary(TypeKind::UInt));
      if (anyError()) return T.error();
      if (t->kind != TypeKind::Array) return bad(a[0], "an array");
      if (auto d = S.evalConst(a[1], ctx); d && (d->i < 1 || d->i > static_cast<int64_t>(t->dims.size())))
        S.diags_.error(a[1]->range.begin, "dimension " + std::to_string(d->i) + " is out of range for '" + t->name + "'", "index-range").range(a[1]->range);
      return T.elementary(TypeKind::DInt);
    }
    case FFixed: {
      Symbol* s = S.builtinSymbols_[fn];
      S.checkArguments(call, s->pou->params, ctx, fn, true);
      return s->pou->returnType;
    }
  }
  (void)IN;
  return T.error();
}

}  // namespace stc::sema
