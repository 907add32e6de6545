// Expressions: names, members, indexing, calls, operators and the implicit
// conversion rules (docs/dialect.md, "Decisions").
#include <algorithm>
#include <cmath>
#include <limits>

#include "sema/SemaInternal.h"

namespace stc::sema {

namespace {

bool isPouType(const Type* t) {
  return t && (t->kind == TypeKind::FunctionBlock || t->kind == TypeKind::Program || t->kind == TypeKind::Interface);
}

// Widening between the duration/date/char kinds.
bool timeWidening(TypeKind f, TypeKind t) {
  return (f == TypeKind::Time && t == TypeKind::LTime) || (f == TypeKind::Date && t == TypeKind::LDate) ||
         (f == TypeKind::Tod && t == TypeKind::LTod) || (f == TypeKind::DT && t == TypeKind::LDT);
}

bool isTimeLike(const Type* t) { return t->isDuration() || t->isDate(); }

}  // namespace

// "<message>; did you mean 'X'?" with a fix-it, when a close name exists.
void SemaImpl::errorWithHint(SourceRange r, const std::string& message, const std::string& name, const std::vector<std::string>& candidates,
                             const char* code) {
  std::string hint = closestMatch(name, candidates);
  auto d = diags_.error(r.begin, message + (hint.empty() ? "" : "; did you mean '" + hint + "'?"), code);
  d.range(r);
  if (!hint.empty()) d.fixit(r, hint);
}

void SemaImpl::markUsed(Symbol* s) {
  if (s && s->var) s->var->used = true;
}

void SemaImpl::recordCall(Symbol* target, SourceRange where) {
  if (currentCaller_ && target) callGraph_[currentCaller_].push_back({target, where});
}

bool SemaImpl::isUntypedLiteral(const Expr* e) const {
  auto* l = dyn_cast<LiteralExpr>(e);
  return l && l->typePrefix.empty() && (l->litKind == LiteralExpr::Int || l->litKind == LiteralExpr::Real);
}

// ------------------------------------------------------------------ conversions

Conv SemaImpl::classify(const Type* from, const Type* to) const {
  if (!from || !to || from == to || from->isError() || to->isError()) return Conv::Exact;
  if (from->kind == TypeKind::Null)
    return (to->isPointer() || to->isReference() || to->kind == TypeKind::Interface) ? Conv::Exact : Conv::Incompatible;
  // Subranges convert freely to and from their base (checked at run time).
  if (from->kind == TypeKind::Subrange) return classify(from->element, to) == Conv::Exact ? Conv::Exact : classify(from->element, to);
  if (to->kind == TypeKind::Subrange) {
    Conv c = classify(from, to->element);
    return c == Conv::Exact ? Conv::Widening : c;
  }
  if (from->kind == TypeKind::Enum || to->kind == TypeKind::Enum) {
    if (from->kind == TypeKind::Enum && to->kind == TypeKind::Enum) return Conv::Incompatible;
    const Type* other = from->kind == TypeKind::Enum ? to : from;
    return (other->isInteger() || other->isBitString()) ? Conv::EnumInt : Conv::Incompatible;
  }
  if (from->isString() || to->isString()) {
    if (from->kind == to->kind) return Conv::Exact;          // any lengths; truncation at run time
    if (from->kind == TypeKind::Char && to->kind == TypeKind::String) return Conv::Widening;
    if (from->kind == TypeKind::WChar && to->kind == TypeKind::WString) return Conv::Widening;
    return Conv::Incompatible;
  }
  if (isTimeLike(from) || isTimeLike(to)) {
    if (timeWidening(from->kind, to->kind)) return Conv::Widening;
    if (isTimeLike(from) && isTimeLike(to)) {
      bool sameFamily = (from->isDuration() && to->isDuration()) ||
                        ((from->kind == TypeKind::Date || from->kind == TypeKind::LDate) && (to->kind == TypeKind::Date || to->kind == TypeKind::LDate)) ||
                        ((from->kind == TypeKind::Tod || from->kind == TypeKind::LTod) && (to->kind == TypeKind::Tod || to->kind == TypeKind::LTod)) ||
                        ((from->kind == TypeKind::DT || from->kind == TypeKind::LDT) && (to->kind == TypeKind::DT || to->kind == TypeKind::LDT));
      return sameFamily ? Conv::Narrowing : Conv::Incompatible;
    }
    const Type* other = isTimeLike(from) ? to : from;
    return (other->isInteger() || other->isBitString()) ? Conv::IntBit : Conv::Incompatible;
  }
  if (from->isChar() || to->isChar()) {
    const Type* other = from->isChar() ? to : from;
    if (from->isChar() && to->isChar()) return from->kind == TypeKind::Char ? Conv::Widening : Conv::Narrowing;
    return (other->isInteger() || other->isBitString()) ? Conv::IntBit : Conv::Incompatible;
  }
  if (from->isPointer() || to->isPointer()) {
    if (from->isPointer() && to->isPointer()) {
      if (from->element == to->element) return Conv::Exact;   // a 4- and an 8-byte slot (address models)
      const Type* te = to->element;
      if (te->kind == TypeKind::Byte || te->kind == TypeKind::Void) return Conv::Widening;
      return Conv::Pointer;
    }
    const Type* other = from->isPointer() ? to : from;
    return ((other->isInteger() || other->isBitString()) && other->bits() >= 32) ? Conv::Pointer : Conv::Incompatible;
  }
  if (from->isReference() || to->isReference()) {
    if (from->isReference() && to->isReference()) return from->element == to->element ? Conv::Exact : classify(from->element, to->element) == Conv::Exact ? Conv::Exact : Conv::Incompatible;
    return Conv::Incompatible;
  }
  if (isPouType(from) || isPouType(to)) {
    if (!isPouType(from) || !isPouType(to)) return Conv::Incompatible;
    Symbol* f = from->pou;
    Symbol* t = to->pou;
    // FB -> base FB; FB -> implemented interface; interface -> base interface.
    std::vector<Symbol*> work = {f};
    for (size_t i = 0; i < work.size() && i < 256; ++i) {
      Symbol* s = work[i];
      if (s == t) return Conv::Widening;
      if (!s->pou) continue;
      if (s->pou->base) work.push_back(s->pou->base);
      for (Symbol* itf : s->pou->interfaces) work.push_back(itf);
    }
    return Conv::Incompatible;
  }
  if (from->kind == TypeKind::Array && to->kind == TypeKind::Array) {
    bool toStar = std::any_of(to->dims.begin(), to->dims.end(), [](const Dim& d) { return d.star; });
    if (toStar && to->dims.size() == from->dims.size() && classify(from->element, to->element) == Conv::Exact) return Conv::Exact;
    return Conv::Incompatible;
  }
  if (from->isStructured() || to->isStructured() || from->kind == TypeKind::Array || to->kind == TypeKind::Array) {
    if (from->kind == TypeKind::Struct && to->kind == TypeKind::Struct)
      for (const Type* b = from->base; b; b = b->base)
        if (b == to) return Conv::Widening;
    return Conv::Incompatible;
  }
  // Elementary numbers, bit strings and BOOL.
  if (from->isBool() && to->isBool()) return Conv::Exact;
  if (from->isBool()) return to->isBitString() ? Conv::Widening : to->isInteger() ? Conv::IntBool : Conv::Incompatible;
  if (to->isBool()) return (from->isInteger() || from->isBitString()) ? Conv::IntBool : Conv::Incompatible;
  if (from->isBitString() && to->isBitString()) return to->bits() >= from->bits() ? Conv::Widening : Conv::Narrowing;
  if (from->isBitString() || to->isBitString()) {
    const Type* other = from->isBitString() ? to : from;
    return other->isInteger() ? Conv::IntBit : Conv::Incompatible;
  }
  if (from->isInteger() && to->isInteger()) {
    bool fs = from->isSignedInt(), ts = to->isSignedInt();
    unsigned fb = from->bits(), tb = to->bits();
    if (fs == ts) return tb >= fb ? Conv::Widening : Conv::Narrowing;
    if (!fs && ts) return tb > fb ? Conv::Widening : tb == fb ? Conv::SignChange : Conv::Narrowing;
    return tb >= fb ? Conv::SignChange : Conv::Narrowing;
  }
  if (from->isInteger() && to->isReal()) {
    if (to->kind == TypeKind::LReal) return Conv::Widening;
    return from->bits() <= 16 ? Conv::Widening : Conv::Narrowing;
  }
  if (from->isReal() && to->isInteger()) return Conv::Narrowing;
  if (from->isReal() && to->isReal()) return to->kind == TypeKind::LReal ? Conv::Widening : Conv::Narrowing;
  return Conv::Incompatible;
}

// Whether the dialect converts implicitly where classify() found `c`.
bool SemaImpl::allowsImplicit(Conv c) const {
  switch (c) {
    case Conv::Exact: case Conv::Widening: return true;
    case Conv::Narrowing: case Conv::SignChange: return allows(DialectRule::ImplicitNarrowing);
    case Conv::IntBit: return allows(DialectRule::IntegerBitString);
    case Conv::EnumInt: return allows(DialectRule::IntegerEnum);
    case Conv::IntBool: return allows(DialectRule::IntegerAsBool);
    case Conv::Pointer: return allows(DialectRule::PointerConversions);
    case Conv::Incompatible: return false;
  }
  return false;
}

bool SemaImpl::literalFits(const LiteralExpr* lit, const Type* to) const {
  // Integer constants convert to an enumeration only in CODESYS mode.
  if (to->kind == TypeKind::Enum && !allows(DialectRule::IntegerEnum)) return false;
  // A subrange takes the constants inside its bounds.
  if (to->kind == TypeKind::Subrange && lit->litKind == LiteralExpr::Int) {
    if (lit->intValue > static_cast<uint64_t>(INT64_MAX) && !(to->element && to->element->isUnsignedInt())) return false;
    if (to->element && to->element->isUnsignedInt())
      return !lit->negative && lit->intValue >= static_cast<uint64_t>(to->lo) && lit->intValue <= static_cast<uint64_t>(to->hi);
    int64_t v = static_cast<int64_t>(lit->negative ? 0 - lit->intValue : lit->intValue);
    return v >= to->lo && v <= to->hi;
  }
  const Type* u = to->underlying();
  if (lit->litKind == LiteralExpr::Real) return u->isReal() && (u->kind == TypeKind::LReal || std::isfinite(static_cast<float>(lit->realValue)));   // rounds to a finite REAL
  if (lit->litKind != LiteralExpr::Int) return false;
  uint64_t v = lit->intValue;
  bool neg = lit->negative && v != 0;
  if (u->isReal()) return true;
  if (u->kind == TypeKind::Subrange) u = u->element;
  if (u->isInteger()) {
    unsigned bits = u->bits();
    if (u->isSignedInt()) {
      uint64_t maxPos = (bits == 64) ? static_cast<uint64_t>(INT64_MAX) : (1ull << (bits - 1)) - 1;
      return neg ? v <= maxPos + 1 : v <= maxPos;
    }
    if (neg) return false;
    return bits == 64 || v <= (1ull << bits) - 1;
  }
  if (u->isBitString()) {
    unsigned bits = u->bits();
    if (neg) return allows(DialectRule::IntegerBitString) && v <= (1ull << (bits - 1));
    return bits == 64 || v <= (1ull << bits) - 1;
  }
  if (u->isBool()) return !neg && v <= 1;   // IEC allows BOOL#0 / BOOL#1 written as 0 / 1
  if ((to->isPointer() || to->kind == TypeKind::Interface || to->isReference()) && v == 0 && allows(DialectRule::ZeroAsNull)) return true;
  return false;
}

// Bytes a string literal occupies: STRING uses Latin-1 when every character
// fits (as CODESYS does for Western text), else UTF-8; WSTRING counts UTF-16
// code units.
size_t SemaImpl::storedLength(const LiteralExpr* lit) const {
  const std::string& t = lit->text;
  size_t chars = 0, units = 0;
  bool latin1 = true;
  for (size_t i = 0; i < t.size();) {
    unsigned char c = static_cast<unsigned char>(t[i]);
    uint32_t cp = c;
    size_t len = 1;
    if (c >= 0xF0 && i + 3 < t.size() + 0) { len = 4; cp = 0x10000; }
    else if (c >= 0xE0) { len = 3; cp = 0x800; }
    else if (c >= 0xC0) { len = 2; cp = ((c & 0x1F) << 6) | (i + 1 < t.size() ? (static_cast<unsigned char>(t[i + 1]) & 0x3F) : 0); }
    if (cp > 0xFF) latin1 = false;
    units += cp >= 0x10000 ? 2 : 1;
    ++chars;
    i += len;
  }
  if (lit->litKind == LiteralExpr::WString) return units;
  return latin1 ? chars : t.size();
}

std::string SemaImpl::conversionFunction(const Type* from, const Type* to) const {
  const Type* f = from->underlying();
  const Type* t = to->underlying();
  if (!f->isElementary() || !t->isElementary()) return "";
  auto base = [](const Type* x) {
    std::string n = x->name;
    size_t p = n.find('(');
    return p == std::string::npos ? n : n.substr(0, p);
  };
  return base(f) + "_TO_" + base(t);
}

bool SemaImpl::checkConversion(const Type* to, Expr* e, const char* what) {
  if (!e || !to) return true;
  const Type* from = e->type;
  if (!from || from->isError() || to->isError()) return true;
  SourceRange r = e->range;
  if (from->kind == TypeKind::Void) {
    diags_.error(r.begin, "expression does not return a value", "void-value").range(r);
    return false;
  }
  if (to->kind == TypeKind::Void) return true;
  auto* lit = dyn_cast<LiteralExpr>(e);
  if (lit && lit->typePrefix.empty() && (lit->litKind == LiteralExpr::Int || lit->litKind == LiteralExpr::Real)) {
    if (literalFits(lit, to)) {
      // CODESYS mode: an integer for an enumeration should name one of its values.
      if (to->kind == TypeKind::Enum && lit->litKind == LiteralExpr::Int) {
        int64_t v = static_cast<int64_t>(lit->negative ? 0 - lit->intValue : lit->intValue);
        bool known = false;
        for (auto& [n, ev] : to->enumValues) known = known || ev == v;
        if (!known)
          diags_.warning(r.begin, std::to_string(v) + " is not a value of enumeration '" + to->name + "'", "enum-value").range(r);
      }
      return true;
    }
    const Type* u = to->underlying();
    if (to->kind == TypeKind::Subrange && lit->litKind == LiteralExpr::Int) {
      std::string val = (lit->negative ? "-" : "") + std::to_string(lit->intValue);
      diags_.error(r.begin, "constant " + val + " is out of range for type '" + to->name + "' (" + std::to_string(to->lo) + ".." +
                                std::to_string(to->hi) + ")", "constant-range").range(r);
      return false;
    }
    if (to->kind == TypeKind::Enum) {
      diags_.error(r.begin, "cannot convert an integer to '" + to->name + "' in IEC mode; use one of its values",
                   "type-mismatch").range(r);
      return false;
    }
    if (lit->litKind == LiteralExpr::Int && (u->isInteger() || u->isBitString())) {
      std::string val = (lit->negative ? "-" : "") + std::to_string(lit->intValue);
      diags_.error(r.begin, "constant " + val + " is out of range for type '" + to->name + "'", "constant-range").range(r);
      return false;
    }
    if (lit->litKind == LiteralExpr::Int && u->isBool()) {
      if (allows(DialectRule::IntegerAsBool)) {
        diags_.warning(r.begin, "implicit conversion of an integer constant to 'BOOL' (non-zero is TRUE)", "int-bool-conversion").range(r)
            .fixit(r, lit->intValue ? "TRUE" : "FALSE");
        return true;
      }
      diags_.error(r.begin, "cannot use an integer constant other than 0 or 1 as BOOL in IEC mode; use TRUE or FALSE", "type-mismatch")
          .range(r).fixit(r, lit->intValue ? "TRUE" : "FALSE");
      return false;
    }
    if (lit->litKind == LiteralExpr::Real && u->kind == TypeKind::Real) {
      diags_.error(r.begin, "constant is out of range for REAL", "constant-range").range(r);
      return false;
    }
  }
  if (lit && (lit->litKind == LiteralExpr::String || lit->litKind == LiteralExpr::WString) && lit->typePrefix.empty()) {
    size_t len = storedLength(lit);
    // One-character literals initialise CHAR / WCHAR.
    if ((to->kind == TypeKind::Char && lit->litKind == LiteralExpr::String) || (to->kind == TypeKind::WChar && lit->litKind == LiteralExpr::WString)) {
      if (len == 1) return true;
      diags_.error(r.begin, "a constant of type '" + to->name + "' must hold exactly one character", "type-mismatch").range(r);
      return false;
    }
    if (to->isString() && (to->kind == TypeKind::String) == (lit->litKind == LiteralExpr::String) && len > to->length) {
      diags_.warning(r.begin, "string constant of length " + std::to_string(len) + " is truncated to " + to->name, "string-truncation").range(r);
      return true;
    }
  }
  // Constant expressions must fit too (SINT := 100 + 100).
  auto isSizeOf = [](const Expr* x) {
    auto* c = dyn_cast<CallExpr>(x);
    auto* n = c ? dyn_cast<NameExpr>(c->callee) : nullptr;
    return n && upperCase(n->ident.name) == "SIZEOF";
  };
  if (!lit && from->isInteger() && (to->underlying()->isInteger() || to->kind == TypeKind::Subrange) && (!isa<CallExpr>(e) || isSizeOf(e))) {
    constEvalFailed_ = false;
    if (auto v = evalConst(e, Context{nullptr, &global_}); v && v->kind == ConstValue::Int && !v->isUnsignedBig) {
      LiteralExpr tmp;
      tmp.litKind = LiteralExpr::Int;
      tmp.negative = v->i < 0;
      tmp.intValue = v->i < 0 ? static_cast<uint64_t>(-(v->i + 1)) + 1 : static_cast<uint64_t>(v->i);
      const Type* target = to->kind == TypeKind::Subrange ? to : to->underlying();
      if (!literalFits(&tmp, target) && !(to->kind == TypeKind::Enum)) {
        diags_.error(r.begin, "constant expression value " + std::to_string(v->i) + " is out of range for type '" + to->name + "'", "constant-range")
            .range(r);
        return false;
      }
      // CODESYS: a constant that fits converts silently (n : INT := SIZEOF(buf)).
      if (allows(DialectRule::ImplicitNarrowing) && to->underlying()->isInteger()) return true;
    }
  }
  Conv c = classify(from, to);
  auto convHint = [&](DiagBuilder& d) {
    std::string fn = conversionFunction(from, to);
    if (fn.empty()) return;
    d.note(r.begin, "use " + fn + "() to convert explicitly");
    d.fixit(SourceRange(r.begin), fn + "(");
    d.fixit(SourceRange(r.end), ")");
  };
  switch (c) {
    case Conv::Exact:
    case Conv::Widening:
      return true;
    case Conv::Narrowing:
    case Conv::SignChange: {
      const char* verb = c == Conv::Narrowing ? "may lose data" : "changes signedness";
      std::string msg = "implicit conversion from '" + from->name + "' to '" + to->name + "' " + verb;
      if (allows(DialectRule::ImplicitNarrowing)) {
        diags_.warning(r.begin, msg, c == Conv::Narrowing ? "narrowing" : "sign-conversion").range(r);
        return true;
      }
      auto d = diags_.error(r.begin, msg, c == Conv::Narrowing ? "narrowing" : "sign-conversion");
      d.range(r);
      convHint(d);
      return false;
    }
    case Conv::IntBit:
    case Conv::EnumInt: {
      if (allows(c == Conv::IntBit ? DialectRule::IntegerBitString : DialectRule::IntegerEnum)) {
        unsigned fb = from->bits(), tb = to->bits();
        if (fb && tb && tb < fb)
          diags_.warning(r.begin, "implicit conversion from '" + from->name + "' to '" + to->name + "' may lose data", "narrowing").range(r);
        return true;
      }
      auto d = diags_.error(r.begin, "no implicit conversion from '" + from->name + "' to '" + to->name + "' in IEC mode", "type-mismatch");
      d.range(r);
      if (c == Conv::IntBit) convHint(d);
      return false;
    }
    case Conv::IntBool: {
      if (allows(DialectRule::IntegerAsBool)) {
        if (to->isBool())
          diags_.warning(r.begin, "implicit conversion from '" + from->name + "' to 'BOOL' (non-zero is TRUE)", "int-bool-conversion").range(r);
        return true;
      }
      auto d = diags_.error(r.begin, "no implicit conversion from '" + from->name + "' to '" + to->name + "' in IEC mode", "type-mismatch");
      d.range(r);
      convHint(d);
      return false;
    }
    case Conv::Pointer:
      if (allows(DialectRule::PointerConversions)) return true;
      diags_.error(r.begin, "no implicit conversion from '" + from->name + "' to '" + to->name + "' in IEC mode",
                   "type-mismatch").range(r);
      return false;
    case Conv::Incompatible:
      break;
  }
  diags_.error(r.begin, std::string("cannot convert '") + from->name + "' to '" + to->name + "' in " + what, "type-mismatch").range(r);
  return false;
}

// ------------------------------------------------------------------ expressions

const Type* SemaImpl::checkExpr(Expr* e, const Context& ctx, const Type* expected) {
  if (!e) return types_.error();
  if (e->type) return e->type;
  const Type* t = types_.error();
  switch (e->kind) {
    case Expr::Literal: t = checkLiteral(cast<LiteralExpr>(e), ctx, expected); break;
    case Expr::Name: t = checkName(cast<NameExpr>(e), ctx, expected); break;
    case Expr::Member: t = checkMember(cast<MemberExpr>(e), ctx, expected); break;
    case Expr::Index: t = checkIndex(cast<IndexExpr>(e), ctx); break;
    case Expr::Deref: {
      auto* d = cast<DerefExpr>(e);
      const Type* bt = checkExpr(d->base, ctx);
      if (bt->isError()) break;
      if (bt->isPointer()) { t = bt->element; break; }
      diags_.error(d->range.begin, "cannot dereference a value of type '" + bt->name + "'; '^' needs a pointer", "type-mismatch")
          .range(d->base->range);
      break;
    }
    case Expr::Call: t = checkCall(cast<CallExpr>(e), ctx, expected); break;
    case Expr::Unary: t = checkUnary(cast<UnaryExpr>(e), ctx, expected); break;
    case Expr::Binary: {
      auto* b = cast<BinaryExpr>(e);
      t = checkBinary(b, ctx, expected);
      b->operandType = t;
      if (!t->isError() && b->op >= BinaryOp::Lt && b->op <= BinaryOp::Ne) {
        // Comparisons: the common type of the operands (already checked, so
        // commonType reports nothing here).
        const Type* lt = valueType(b->lhs->type);
        const Type* rt = valueType(b->rhs->type);
        const Type* ul = lt->underlying();
        const Type* ur = rt->underlying();
        auto numLike = [](const Type* x) { return x->isNumeric() || x->isBitString() || x->isBool(); };
        if (lt == rt) b->operandType = lt;
        else if (numLike(ul) && numLike(ur)) b->operandType = commonType(ul, ur, b->lhs, b->rhs, b->opLoc, "=");
        else if (ul->kind == TypeKind::Enum && numLike(ur)) b->operandType = commonType(ul->underlying(), ur, b->lhs, b->rhs, b->opLoc, "=");
        else if (ur->kind == TypeKind::Enum && numLike(ul)) b->operandType = commonType(ul, ur->underlying(), b->lhs, b->rhs, b->opLoc, "=");
        else if (ul->isDuration() || ul->isDate()) b->operandType = ul->kind == TypeKind::LTime || ur->kind == TypeKind::LTime ? types_.elementary(TypeKind::LTime) : ul;
        else b->operandType = lt;
      }
      break;
    }
    case Expr::This:
    case Expr::Super: {
      Symbol* owner = ownerOf(ctx.pou);
      bool isThis = e->kind == Expr::This;
      if (!owner || owner->kind != Symbol::FunctionBlock) {
        diags_.error(e->range.begin, std::string(isThis ? "THIS" : "SUPER") + " is only available inside a function block", "invalid-this")
            .range(e->range);
        break;
      }
      // THIS and SUPER are pointers: THIS^.x, SUPER^.M().
      if (isThis) { t = types_.pointer(owner->type); break; }
      if (!owner->pou->base) {
        diags_.error(e->range.begin, "SUPER used in '" + owner->name + "', which does not extend a function block", "invalid-this").range(e->range);
        break;
      }
      t = types_.pointer(owner->pou->base->type);
      break;
    }
    case Expr::DirectAddress: {
      auto* a = cast<DirectAddressExpr>(e);
      char sz = a->text.size() > 2 ? static_cast<char>(std::toupper(static_cast<unsigned char>(a->text[2]))) : 'X';
      if (a->text.find('*') != std::string::npos) {
        diags_.error(e->range.begin, "incomplete address '" + a->text + "' cannot be used in an expression", "invalid-address").range(e->range);
        break;
      }
      t = types_.elementary(sz == 'B' ? TypeKind::Byte : sz == 'W' ? TypeKind::Word : sz == 'D' ? TypeKind::DWord
                            : sz == 'L' ? TypeKind::LWord : TypeKind::Bool);
      break;
    }
    case Expr::ArrayInit:
    case Expr::StructInit:
      diags_.error(e->range.begin, "an initializer list is only allowed as the initial value of a declaration", "invalid-init").range(e->range);
      break;
  }
  e->type = t;
  return t;
}

const Type* SemaImpl::checkLiteral(LiteralExpr* e, const Context& ctx, const Type* expected) {
  const Type* exp = expected ? valueType(expected) : nullptr;
  if (!e->typePrefix.empty()) {
    QualifiedName q;
    q.parts.push_back(e->typePrefix);
    q.range = e->typePrefix.range;
    const Type* t = resolveNamedType(q, ctx, true);
    if (t->isError()) return t;
    if (e->litKind == LiteralExpr::Enum) {
      if (t->kind != TypeKind::Enum) {
        diags_.error(e->range.begin, "'" + t->name + "#" + e->text + "' names a value of a type that is not an enumeration", "type-mismatch").range(e->range);
        return types_.error();
      }
      for (auto& [n, v] : t->enumValues)
        if (upperCase(n) == upperCase(e->text)) {
          e->intValue = static_cast<uint64_t>(v);
          return t;
        }
      std::vector<std::string> names;
      for (auto& [n, v] : t->enumValues) names.push_back(n);
      std::string hint = closestMatch(e->text, names);
      diags_.error(e->range.begin, "no value '" + e->text + "' in enumeration '" + t->name + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"),
                   "undeclared-name").range(e->range);
      return types_.error();
    }
    if (e->litKind == LiteralExpr::Bool) {
      if (!t->isBool()) diags_.error(e->range.begin, "TRUE/FALSE cannot be typed as '" + t->name + "'", "type-mismatch").range(e->range);
      return t;
    }
    if (e->litKind == LiteralExpr::String || e->litKind == LiteralExpr::WString) {
      if (!t->isString() && !t->isChar()) {
        diags_.error(e->range.begin, "a string literal cannot be typed as '" + t->name + "'", "type-mismatch").range(e->range);
        return types_.error();
      }
      return t;
    }
    // Numeric typed literal: the value must fit.
    if (!literalFits(e, t) && !(t->isBool() && e->litKind == LiteralExpr::Int && e->intValue <= 1 && !e->negative)) {
      std::string val = e->litKind == LiteralExpr::Int ? (e->negative ? "-" : "") + std::to_string(e->intValue) : "value";
      diags_.error(e->range.begin, "constant " + val + " is out of range for type '" + t->name + "'", "constant-range").range(e->range);
      return types_.error();
    }
    return t;
  }
  switch (e->litKind) {
    case LiteralExpr::Int: {
      if (exp && !exp->isError() && literalFits(e, exp) && !exp->isPointer() && exp->kind != TypeKind::Interface) {
        if (exp->isBool()) return exp;
        return exp->kind == TypeKind::Subrange ? exp->element : exp->kind == TypeKind::Enum ? exp->element : exp;
      }
      // Default type: the smallest of DINT, LINT, ULINT that holds the value.
      if (literalFits(e, types_.elementary(TypeKind::DInt))) return types_.elementary(TypeKind::DInt);
      if (literalFits(e, types_.elementary(TypeKind::LInt))) return types_.elementary(TypeKind::LInt);
      if (!e->negative) return types_.elementary(TypeKind::ULInt);
      diags_.error(e->range.begin, "integer constant is too small for LINT", "constant-range").range(e->range);
      return types_.error();
    }
    case LiteralExpr::Real:
      if (exp && exp->kind == TypeKind::Real && literalFits(e, exp)) return exp;
      return types_.elementary(TypeKind::LReal);
    case LiteralExpr::Bool: return types_.elementary(TypeKind::Bool);
    case LiteralExpr::String: return types_.string(static_cast<uint32_t>(std::max<size_t>(1, std::min<size_t>(storedLength(e), 65535))), false);
    case LiteralExpr::WString: return types_.string(static_cast<uint32_t>(std::max<size_t>(1, std::min<size_t>(storedLength(e), 65535))), true);
    case LiteralExpr::Time: return types_.elementary(e->isLong ? TypeKind::LTime : TypeKind::Time);
    case LiteralExpr::Date: return types_.elementary(e->isLong ? TypeKind::LDate : TypeKind::Date);
    case LiteralExpr::TimeOfDay: return types_.elementary(e->isLong ? TypeKind::LTod : TypeKind::Tod);
    case LiteralExpr::DateTime: return types_.elementary(e->isLong ? TypeKind::LDT : TypeKind::DT);
    case LiteralExpr::Enum: break;
  }
  return types_.error();
}

static const char* kindWord(const Symbol* s) {
  switch (s->kind) {
    case Symbol::Function: return "function";
    case Symbol::FunctionBlock: return "function block type";
    case Symbol::Program: return "program";
    case Symbol::Interface: return "interface type";
    case Symbol::Method: return "method";
    case Symbol::Action: return "action";
    case Symbol::TypeName: return "type";
    case Symbol::Namespace: return "namespace";
    case Symbol::GlobalList: return "global variable list";
    case Symbol::BuiltinFunction: return "standard function";
    default: return "name";
  }
}

const Type* SemaImpl::checkName(NameExpr* e, const Context& ctx, const Type* expected) {
  std::string up = upperCase(e->ident.name);
  // Inside a function, method or GET accessor its own name is the result.
  if (body_ && body_->resultVar && upperCase(body_->resultVar->name) == up) {
    e->symbol = body_->resultVar;
    return body_->resultVar->type;
  }
  Symbol* s = lookup(up, ctx);
  if (!s) {
    auto it = enumValues_.find(up);
    if (it != enumValues_.end() && !it->second.empty()) {
      const auto& vals = it->second;
      if (vals.size() == 1) s = vals[0];
      else {
        const Type* exp = expected ? valueType(expected) : nullptr;
        for (Symbol* v : vals)
          if (exp && v->type == exp) s = v;
        if (!s) {
          auto d = diags_.error(e->range.begin, "enumeration value '" + e->ident.name + "' is ambiguous; qualify it as Type#" + e->ident.name, "ambiguous");
          d.range(e->range);
          for (Symbol* v : vals) d.note(v->declRange.begin, "could be " + v->type->name + "#" + v->name, v->declRange);
          return types_.error();
        }
      }
    }
  }
  if (!s) {
    errorWithHint(e->range, "use of undeclared identifier '" + e->ident.name + "'", e->ident.name, visibleNames(ctx), "undeclared-name");
    return types_.error();
  }
  e->symbol = s;
  switch (s->kind) {
    case Symbol::Variable: {
      markUsed(s);
      // An internal variable of a base FB, named inside a derived one.
      if (isInternal(s->var) && ctx.pou && ownerOf(ctx.pou)->kind == Symbol::FunctionBlock && !internalVisible(s, ctx)) {
        Symbol* declaring = nullptr;
        for (Symbol* p = ownerOf(ctx.pou); p && p->pou && !declaring; p = p->pou->base)
          if (p->pou->vars->lookupLocal(up) == s) declaring = p;
        if (declaring) {
          reportInternal(s->name, declaring->name, e->range, s->declRange);
          return types_.error();
        }
      }
      if (!s->type && s->var) {
        Context declCtx{nullptr, outerScope_.count(s) ? outerScope_[s] : &global_};
        s->type = resolveType(s->var->type, declCtx);
      }
      return valueType(s->type ? s->type : types_.error());
    }
    case Symbol::EnumValue: return s->type;
    case Symbol::Property: {
      resolveSignature(s);
      checkAccess(s, ctx, e->range);
      if (!readingLhs_) recordCall(s, e->range);   // a read runs the GET accessor (recursion check)
      if (!readingLhs_ && !s->pou->decl->getter) {
        diags_.error(e->range.begin, "property '" + s->name + "' has no GET accessor and cannot be read", "not-a-value")
            .range(e->range).note(s->declRange.begin, "property declared here", s->declRange);
        return types_.error();
      }
      return s->pou->returnType ? s->pou->returnType : types_.error();
    }
    case Symbol::Program: return s->type;
    default: break;
  }
  auto d = diags_.error(e->range.begin, "'" + e->ident.name + "' is a " + kindWord(s) + ", not a value", "not-a-value");
  d.range(e->range);
  if (s->kind == Symbol::Function || s->kind == Symbol::Method || s->kind == Symbol::Action || s->kind == Symbol::BuiltinFunction)
    d.fixit(SourceRange(e->range.end), "()");
  if (s->declRange.valid()) d.note(s->declRange.begin, "declared here", s->declRange);
  return types_.error();
}

Symbol* SemaImpl::entityOf(Expr* e, const Context& ctx) {
  if (auto* n = dyn_cast<NameExpr>(e)) {
    std::string up = upperCase(n->ident.name);
    if (body_ && body_->resultVar && upperCase(body_->resultVar->name) == up) return nullptr;
    Symbol* s = lookup(up, ctx);
    if (!s) return nullptr;
    if (s->kind == Symbol::Namespace || s->kind == Symbol::GlobalList || s->kind == Symbol::TypeName) {
      n->symbol = s;
      n->type = types_.voidType();
      return s;
    }
    return nullptr;
  }
  if (auto* m = dyn_cast<MemberExpr>(e)) {
    Symbol* base = entityOf(m->base, ctx);
    if (!base || base->kind != Symbol::Namespace) return nullptr;
    Symbol* s = base->scope->lookupLocal(upperCase(m->member.name));
    if (s && (s->kind == Symbol::Namespace || s->kind == Symbol::GlobalList || s->kind == Symbol::TypeName)) {
      m->symbol = s;
      m->type = types_.voidType();
      return s;
    }
  }
  return nullptr;
}

const Type* SemaImpl::checkMember(MemberExpr* e, const Context& ctx, const Type* expected) {
  std::string up = upperCase(e->member.name);
  if (Symbol* ent = entityOf(e->base, ctx)) {
    Symbol* s = nullptr;
    if (ent->kind == Symbol::Namespace || ent->kind == Symbol::GlobalList) {
      s = ent->scope->lookupLocal(up);
      if (!s) {
        std::vector<std::string> names;
        for (Symbol* x : ent->scope->symbols()) names.push_back(x->name);
        std::string hint = closestMatch(e->member.name, names);
        diags_.error(e->member.range.begin, "no member named '" + e->member.name + "' in " + kindWord(ent) + " '" + ent->name + "'" +
                                                (hint.empty() ? "" : "; did you mean '" + hint + "'?"), "undeclared-name")
            .range(e->member.range);
        return types_.error();
      }
      e->symbol = s;
      if (s->kind == Symbol::Variable) {
        markUsed(s);
        if (!s->type && s->var) s->type = resolveType(s->var->type, Context{nullptr, ent->scope.get()});
        return valueType(s->type);
      }
      if (s->kind == Symbol::Program) return s->type;
      diags_.error(e->range.begin, "'" + ent->name + "." + s->name + "' is a " + kindWord(s) + ", not a value", "not-a-value").range(e->range);
      return types_.error();
    }
    if (ent->kind == Symbol::TypeName) {
      resolveTypeSymbol(ent);
      const Type* t = ent->type;
      if (t && t->kind == TypeKind::Enum) {
        for (auto& [n, v] : t->enumValues)
          if (upperCase(n) == up) return t;
        std::vector<std::string> names;
        for (auto& [n, v] : t->enumValues) names.push_back(n);
        std::string hint = closestMatch(e->member.name, names);
        diags_.error(e->member.range.begin, "no value '" + e->member.name + "' in enumeration '" + t->name + "'" +
                                                (hint.empty() ? "" : "; did you mean '" + hint + "'?"), "undeclared-name").range(e->member.range);
        return types_.error();
      }
      diags_.error(e->range.begin, "'" + ent->name + "' is a type; only enumeration types have members", "not-a-value").range(e->base->range);
      return types_.error();
    }
  }
  const Type* bt = valueType(checkExpr(e->base, ctx));
  if (bt->isError()) return bt;
  if (e->access != MemberExpr::Field) {
    const Type* u = bt->underlying();
    if (!(u->isInteger() || u->isBitString())) {
      diags_.error(e->member.range.begin, "bit access needs an integer or bit-string value, not '" + bt->name + "'", "type-mismatch").range(e->range);
      return types_.error();
    }
    unsigned width = e->access == MemberExpr::PartialByte ? 8 : e->access == MemberExpr::PartialWord ? 16 : e->access == MemberExpr::PartialDWord ? 32 : 1;
    if (static_cast<uint64_t>(e->bitIndex + 1) * width > u->bits()) {
      diags_.error(e->member.range.begin, "bit index " + std::to_string(e->bitIndex) + " is out of range for '" + bt->name + "' (" +
                                              std::to_string(u->bits() / width) + " parts)", "index-range").range(e->member.range);
      return types_.error();
    }
    return types_.elementary(width == 1 ? TypeKind::Bool : width == 8 ? TypeKind::Byte : width == 16 ? TypeKind::Word : TypeKind::DWord);
  }
  if (bt->kind == TypeKind::Struct || bt->kind == TypeKind::Union) {
    for (const Type* t = bt; t; t = t->base)
      for (const Member& m : t->members)
        if (upperCase(m.name) == up) {
          if (isInternal(m.decl)) {
            reportInternal(m.name, t->name, e->member.range, m.decl->name.range);
            return types_.error();
          }
          if (isMirrored(bt)) model_.readsMirrored = true;
          return m.type;
        }
    std::vector<std::string> names;
    for (const Type* t = bt; t; t = t->base)
      for (const Member& m : t->members) names.push_back(m.name);
    errorWithHint(e->member.range, "no member named '" + e->member.name + "' in '" + bt->name + "'", e->member.name, names, "no-member");
    return types_.error();
  }
  if (isPouType(bt)) {
    Symbol* owner = bt->pou;
    resolveSignature(owner);
    Symbol* s = pouMember(owner, up);
    if (!s) {
      std::vector<std::string> names;
      for (Symbol* p = owner; p && p->pou; p = p->pou->base) {
        for (Symbol* x : p->pou->vars->symbols()) names.push_back(x->name);
        for (Symbol* x : p->pou->members->symbols()) names.push_back(x->name);
        if (p->pou->base == owner) break;
      }
      errorWithHint(e->member.range, "no member named '" + e->member.name + "' in '" + bt->name + "'", e->member.name, names, "no-member");
      return types_.error();
    }
    e->symbol = s;
    if (s->kind == Symbol::Variable) {
      markUsed(s);
      // From outside an FB only its parameters are visible (programs expose everything).
      bool inside = isa<ThisExpr>(e->base) || (isa<DerefExpr>(e->base) && (isa<ThisExpr>(cast<DerefExpr>(e->base)->base) ||
                                                                            isa<SuperExpr>(cast<DerefExpr>(e->base)->base)));
      if (isInternal(s->var) && !(inside && internalVisible(s, ctx))) {
        std::string declaring = owner->name;
        for (Symbol* p = owner; p && p->pou; p = p->pou->base)
          if (p->pou->vars->lookupLocal(up) == s) { declaring = p->name; break; }
        reportInternal(s->name, declaring, e->member.range, s->declRange);
        return types_.error();
      }
      VarSection sec = s->var ? s->var->section : VarSection::Var;
      if (owner->kind == Symbol::FunctionBlock && !inside &&
          !(sec == VarSection::Input || sec == VarSection::Output || sec == VarSection::InOut)) {
        diags_.error(e->member.range.begin, "'" + s->name + "' is a local variable of '" + owner->name +
                                                "' and cannot be accessed from outside; only inputs, outputs and in-outs can",
                     "access").range(e->member.range).note(s->declRange.begin, "declared here", s->declRange);
        return types_.error();
      }
      return valueType(s->type ? s->type : types_.error());
    }
    if (s->kind == Symbol::Property) {
      resolveSignature(s);
      checkAccess(s, ctx, e->member.range);
      if (!readingLhs_) recordCall(s, e->range);
      if (!readingLhs_ && !s->pou->decl->getter) {
        diags_.error(e->member.range.begin, "property '" + s->name + "' has no GET accessor and cannot be read", "not-a-value")
            .range(e->member.range).note(s->declRange.begin, "property declared here", s->declRange);
        return types_.error();
      }
      return s->pou->returnType ? s->pou->returnType : types_.error();
    }
    diags_.error(e->member.range.begin, std::string(kindWord(s)) + " '" + s->name + "' must be called: write '" + s->name + "()'", "not-a-value")
        .range(e->member.range).fixit(SourceRange(e->range.end), "()");
    return types_.error();
  }
  if (bt->isPointer()) {
    diags_.error(e->member.range.begin, "member access through a pointer needs '^': write '" + std::string("...^.") + e->member.name + "'", "type-mismatch")
        .range(e->base->range).fixit(SourceRange(e->base->range.end), "^");
    return types_.error();
  }
  // dw.C_BIT: a bit index given by an integer constant (CODESYS V3).
  if (const Type* u = bt->underlying(); u->isInteger() || u->isBitString()) {
    Symbol* c = lookup(up, ctx);
    const Type* ct = c && c->var ? (c->type ? c->type : c->var->resolvedType) : nullptr;
    if (c && c->kind == Symbol::Variable && c->var && c->var->isFoldableConstant() && ct && ct->underlying()->isInteger()) {
      markUsed(c);
      NameExpr* ref = ast_.make<NameExpr>();
      ref->ident = e->member;
      ref->range = e->member.range;
      ref->symbol = c;
      ref->type = ct;
      std::optional<ConstValue> v = evalConst(ref, ctx);
      if (v && v->i >= 0 && static_cast<uint64_t>(v->i) < u->bits()) {
        e->access = MemberExpr::Bit;
        e->bitIndex = static_cast<unsigned>(v->i);
        return types_.elementary(TypeKind::Bool);
      }
      if (v) {
        diags_.error(e->member.range.begin, "bit index " + std::to_string(v->i) + " ('" + e->member.name + "') is out of range for '" +
                                                bt->name + "' (" + std::to_string(u->bits()) + " bits)", "index-range").range(e->member.range);
        return types_.error();
      }
    }
  }
  diags_.error(e->member.range.begin, "a value of type '" + bt->name + "' has no members", "no-member").range(e->range);
  return types_.error();
}

const Type* SemaImpl::checkIndex(IndexExpr* e, const Context& ctx) {
  const Type* bt = valueType(checkExpr(e->base, ctx));
  for (Expr* i : e->indices) {
    const Type* it = checkExpr(i, ctx);
    if (it->isError()) continue;
    const Type* u = it->underlying();
    if (!(u->isInteger() || (allows(DialectRule::IntegerBitString) && u->isBitString()) || (allows(DialectRule::IntegerEnum) && u->kind == TypeKind::Enum)))
      diags_.error(i->range.begin, "array index must be an integer, not '" + it->name + "'", "type-mismatch").range(i->range);
  }
  if (bt->isError()) return bt;
  if (bt->isString()) {
    if (e->indices.size() != 1) {
      diags_.error(e->range.begin, "a string takes one index", "index-count").range(e->range);
      return types_.error();
    }
    return types_.elementary(bt->kind == TypeKind::String ? TypeKind::Byte : TypeKind::Word);
  }
  if (bt->kind != TypeKind::Array) {
    diags_.error(e->range.begin, "subscripted value of type '" + bt->name + "' is not an array", "type-mismatch").range(e->base->range);
    return types_.error();
  }
  if (e->indices.size() > bt->dims.size()) {
    diags_.error(e->indices[bt->dims.size()]->range.begin, "too many indices for '" + bt->name + "' (" + std::to_string(bt->dims.size()) +
                                                               " dimension" + (bt->dims.size() == 1 ? "" : "s") + ")", "index-count")
        .range(e->range);
    return types_.error();
  }
  // p^[i] on POINTER TO ARRAY[0..0] OF T is the flexible-array idiom (CodeGen: no bounds check).
  const bool flexible = isa<DerefExpr>(e->base) && bt->dims.size() == 1 && bt->dims[0].lo == 0 && bt->dims[0].hi == 0;
  for (size_t k = 0; k < e->indices.size() && !flexible; ++k) {
    const Dim& d = bt->dims[k];
    if (d.star) continue;
    if (auto v = evalConst(e->indices[k], ctx); v && v->kind == ConstValue::Int) {
      if (v->i < d.lo || v->i > d.hi)
        diags_.error(e->indices[k]->range.begin, "array index " + std::to_string(v->i) + " is outside the bounds " + std::to_string(d.lo) + ".." +
                                                     std::to_string(d.hi) + " of '" + bt->name + "'", "index-range")
            .range(e->indices[k]->range);
    }
  }
  if (e->indices.size() < bt->dims.size()) {
    // C-style a[i][j]: the rest of the dimensions.
    std::vector<Dim> rest(bt->dims.begin() + static_cast<long>(e->indices.size()), bt->dims.end());
    return types_.array(bt->element, std::move(rest));
  }
  return bt->element;
}

// ------------------------------------------------------------------ operators

const Type* SemaImpl::commonType(const Type* a, const Type* b, Expr* ea, Expr* eb, SourceLoc opLoc, const char* op) {
  if (a->isError() || b->isError()) return types_.error();
  a = a->kind == TypeKind::Subrange ? a->element : a;
  b = b->kind == TypeKind::Subrange ? b->element : b;
  if (a == b) return a;
  static const TypeKind order[] = {TypeKind::SInt, TypeKind::USInt, TypeKind::Int, TypeKind::UInt, TypeKind::DInt,
                                   TypeKind::UDInt, TypeKind::LInt, TypeKind::ULInt, TypeKind::Real, TypeKind::LReal,
                                   TypeKind::Byte, TypeKind::Word, TypeKind::DWord, TypeKind::LWord};
  auto ok = [&](const Type* from, const Type* to) {
    Conv c = classify(from, to);
    return c == Conv::Exact || c == Conv::Widening;
  };
  for (TypeKind k : order) {
    const Type* t = types_.elementary(k);
    if (ok(a, t) && ok(b, t)) return t;
  }
  if (allows(DialectRule::IntegerBitString)) {
    const Type* ua = a->underlying();
    const Type* ub = b->underlying();
    auto intLike = [](const Type* t) { return t->isInteger() || t->isBitString() || t->isBool(); };
    if (intLike(ua) && intLike(ub)) {
      if (ua->bits() != ub->bits()) return ua->bits() > ub->bits() ? ua : ub;
      return ua->isInteger() ? ua : ub;
    }
    if ((ua->isNumeric() || ua->isBitString()) && (ub->isNumeric() || ub->isBitString()))
      return (ua->kind == TypeKind::LReal || ub->kind == TypeKind::LReal) ? types_.elementary(TypeKind::LReal) : types_.elementary(TypeKind::Real);
  }
  auto d = diags_.error(opLoc, std::string("invalid operands to '") + op + "' ('" + a->name + "' and '" + b->name + "')", "type-mismatch");
  d.range(ea->range).range(eb->range);
  if (a->isInteger() && b->isInteger())
    d.note(opLoc, "IEC has no implicit conversion between these types; convert one operand explicitly");
  return types_.error();
}

const Type* SemaImpl::checkUnary(UnaryExpr* e, const Context& ctx, const Type* expected) {
  const Type* t = valueType(checkExpr(e->operand, ctx, expected));
  if (t->isError()) return t;
  const Type* u = t->underlying();
  switch (e->op) {
    case UnaryOp::Neg:
      if (u->isSignedInt() || u->isReal() || u->isDuration()) return t;
      if (allows(DialectRule::UnsignedNegation) && (u->isUnsignedInt() || u->isBitString())) return t;
      if (u->isUnsignedInt()) {
        diags_.error(e->opLoc, "unary '-' applied to unsigned type '" + t->name + "'", "sign-conversion").range(e->operand->range);
        return types_.error();
      }
      break;
    case UnaryOp::Plus:
      if (u->isNumeric() || u->isDuration()) return t;
      break;
    case UnaryOp::Not:
      if (u->isBool() || u->isBitString()) return t;
      if (allows(DialectRule::IntegerBitString) && u->isInteger()) return t;
      break;
  }
  diags_.error(e->opLoc, std::string("invalid operand to unary '") + spelling(e->op) + "' ('" + t->name + "')", "type-mismatch")
      .range(e->operand->range);
  return types_.error();
}

// An integer division by a constant zero is reported where it is written.
void SemaImpl::checkDivisor(BinaryExpr* e, const Context& ctx) {
  if (!e->rhs->type || !valueType(e->rhs->type)->underlying()->isInteger()) return;
  auto v = evalConst(e->rhs, ctx);
  if (v && v->kind == ConstValue::Int && v->i == 0)
    diags_.error(e->opLoc, "division by zero in a constant expression", "division-by-zero").range(e->range);
}

const Type* SemaImpl::checkBinary(BinaryExpr* e, const Context& ctx, const Type* expected) {
  bool cmp = e->op >= BinaryOp::Lt && e->op <= BinaryOp::Ne;
  const Type* exp = cmp ? nullptr : expected;
  // Check the typed operand first so that a literal can take its type.
  const Type *lt, *rt;
  if (isBareEnumValueName(e->lhs, ctx) && !isBareEnumValueName(e->rhs, ctx)) {
    // `Run = state`: the other operand decides which enumeration Run is from.
    rt = valueType(checkExpr(e->rhs, ctx, exp));
    lt = valueType(checkExpr(e->lhs, ctx, rt));
  } else if (isUntypedLiteral(e->lhs) && !isUntypedLiteral(e->rhs)) {
    rt = valueType(checkExpr(e->rhs, ctx, exp));
    lt = valueType(checkExpr(e->lhs, ctx, rt->isNumeric() || rt->isBitString() ? rt : exp));
  } else {
    lt = valueType(checkExpr(e->lhs, ctx, exp));
    bool literalRhs = isUntypedLiteral(e->rhs) && (lt->isNumeric() || lt->isBitString() || lt->underlying()->isNumeric());
    rt = valueType(checkExpr(e->rhs, ctx, literalRhs || lt->kind == TypeKind::Enum ? lt : exp));
  }
  if (lt->isError() || rt->isError()) return types_.error();
  const char* op = spelling(e->op);
  const Type* ul = lt->underlying();
  const Type* ur = rt->underlying();
  auto invalid = [&]() -> const Type* {
    diags_.error(e->opLoc, std::string("invalid operands to '") + op + "' ('" + lt->name + "' and '" + rt->name + "')", "type-mismatch")
        .range(e->lhs->range).range(e->rhs->range);
    return types_.error();
  };
  const Type* boolT = types_.elementary(TypeKind::Bool);
  auto timeOf = [&](const Type* a, const Type* b) {
    return types_.elementary((a->kind == TypeKind::LTime || b->kind == TypeKind::LTime || a->kind == TypeKind::LDT || a->kind == TypeKind::LTod ||
                              a->kind == TypeKind::LDate) ? TypeKind::LTime : TypeKind::Time);
  };
  switch (e->op) {
    case BinaryOp::Add:
    case BinaryOp::Sub: {
      bool add = e->op == BinaryOp::Add;
      if (ul->isDuration() && ur->isDuration()) return timeOf(ul, ur);
      if ((ul->kind == TypeKind::Tod || ul->kind == TypeKind::LTod || ul->kind == TypeKind::DT || ul->kind == TypeKind::LDT) && ur->isDuration())
        return lt;
      if (add && ul->isDuration() && (ur->kind == TypeKind::Tod || ur->kind == TypeKind::DT)) return rt;
      // DATE + TIME (CODESYS): the point in time that far after the date's midnight, a DT.
      if (ul->kind == TypeKind::Date && ur->kind == TypeKind::Time) return types_.elementary(TypeKind::DT);
      if (!add && ul->isDate() && ur->isDate() && classify(lt, rt) != Conv::Incompatible) return timeOf(ul, ur);
      if (ul->isPointer() || ur->isPointer()) {
        if (!allows(DialectRule::PointerConversions)) {
          diags_.error(e->opLoc, "pointer arithmetic is not allowed with --dialect=iec", "pointer-arithmetic").range(e->range);
          return types_.error();
        }
        if (ul->isPointer() && (ur->isInteger() || ur->isBitString())) return lt;
        if (add && ur->isPointer() && (ul->isInteger() || ul->isBitString())) return rt;
        if (!add && ul->isPointer() && ur->isPointer()) return types_.elementary(TypeKind::LInt);
        return invalid();
      }
      [[fallthrough]];
    }
    case BinaryOp::Mul:
    case BinaryOp::Div: {
      if (e->op == BinaryOp::Div) checkDivisor(e, ctx);
      // TIME * n, TIME / n, n * TIME; CODESYS also takes bit strings for n (T#1s * byteVar).
      auto factor = [&](const Type* u) { return u->isNumeric() || (allows(DialectRule::IntegerBitString) && u->isBitString()); };
      if ((e->op == BinaryOp::Mul || e->op == BinaryOp::Div) && ul->isDuration() && factor(ur)) return lt;
      if (e->op == BinaryOp::Mul && factor(ul) && ur->isDuration()) return rt;
      bool lnum = ul->isNumeric() || (allows(DialectRule::IntegerBitString) && ul->isBitString()) || (allows(DialectRule::IntegerEnum) && ul->kind == TypeKind::Enum);
      bool rnum = ur->isNumeric() || (allows(DialectRule::IntegerBitString) && ur->isBitString()) || (allows(DialectRule::IntegerEnum) && ur->kind == TypeKind::Enum);
      if (!lnum || !rnum) {
        if ((ul->isBitString() || ur->isBitString()) && strictIec())
          diags_.error(e->opLoc, std::string("arithmetic '") + op + "' on bit-string type '" + (ul->isBitString() ? lt : rt)->name +
                                     "' is not allowed in IEC mode; convert to an integer type first", "type-mismatch")
              .range(e->lhs->range).range(e->rhs->range);
        else
          return invalid();
        return types_.error();
      }
      return commonType(ul->kind == TypeKind::Enum ? ul->element : lt, ur->kind == TypeKind::Enum ? ur->element : rt, e->lhs, e->rhs, e->opLoc, op);
    }
    case BinaryOp::Mod: {
      checkDivisor(e, ctx);
      bool lok = ul->isInteger() || (allows(DialectRule::IntegerBitString) && ul->isBitString());
      bool rok = ur->isInteger() || (allows(DialectRule::IntegerBitString) && ur->isBitString());
      if (!lok || !rok) return invalid();
      return commonType(lt, rt, e->lhs, e->rhs, e->opLoc, op);
    }
    case BinaryOp::Pow:
      if (!ul->isNumeric() || !ur->isNumeric()) return invalid();
      if (ul->isReal()) return lt;
      return types_.elementary(ur->kind == TypeKind::LReal || ul->bits() > 16 ? TypeKind::LReal : TypeKind::Real);
    case BinaryOp::Lt: case BinaryOp::Gt: case BinaryOp::Le: case BinaryOp::Ge:
    case BinaryOp::Eq: case BinaryOp::Ne: {
      bool eq = e->op == BinaryOp::Eq || e->op == BinaryOp::Ne;
      if (lt == rt && (lt->isElementary() || lt->kind == TypeKind::Enum || lt->kind == TypeKind::Subrange)) return boolT;
      // Enumerations compare only with the same enumeration (CODESYS: also integers).
      if (lt->kind == TypeKind::Enum || rt->kind == TypeKind::Enum) {
        const Type* other = lt->kind == TypeKind::Enum ? rt : lt;
        if (allows(DialectRule::IntegerEnum) && (other->underlying()->isInteger() || other->isBitString())) return boolT;
        return invalid();
      }
      if ((ul->isNumeric() || ul->isBitString() || ul->isBool()) && (ur->isNumeric() || ur->isBitString() || ur->isBool())) {
        if (ul->isBool() != ur->isBool() && !allows(DialectRule::IntegerAsBool)) return invalid();
        if (!commonType(ul, ur, e->lhs, e->rhs, e->opLoc, op)->isError()) return boolT;
        return types_.error();
      }
      if (ul->isString() && ur->isString() && ul->kind == ur->kind) return boolT;
      if (isTimeLike(ul) && isTimeLike(ur) && classify(ul, ur) != Conv::Incompatible) return boolT;
      if (ul->isChar() && ur->isChar()) return boolT;
      if (lt->kind == TypeKind::Enum || rt->kind == TypeKind::Enum) {
        const Type* other = lt->kind == TypeKind::Enum ? rt : lt;
        if (allows(DialectRule::IntegerEnum) && (other->isInteger() || other->isBitString())) return boolT;
        if (lt->kind == TypeKind::Enum && rt->kind == TypeKind::Enum && lt == rt) return boolT;
        return invalid();
      }
      // CODESYS: pointers order like the addresses they hold (`WHILE p < pEnd`), also against integers.
      if (!eq && allows(DialectRule::PointerConversions) && (ul->isPointer() || ur->isPointer()) &&
          (ul->isPointer() || ul->isInteger() || ul->isBitString()) && (ur->isPointer() || ur->isInteger() || ur->isBitString()))
        return boolT;
      if (eq) {
        bool lp = ul->isPointer() || ul->kind == TypeKind::Interface || ul->isReference();
        bool rp = ur->isPointer() || ur->kind == TypeKind::Interface || ur->isReference();
        if (lp && rp) return boolT;
        if (lp || rp) {
          Expr* other = lp ? e->rhs : e->lhs;
          auto* lit = dyn_cast<LiteralExpr>(other);
          if (lit && lit->litKind == LiteralExpr::Int && lit->intValue == 0) return boolT;
          if (allows(DialectRule::PointerConversions)) return boolT;
        }
        if (isPouType(ul) && isPouType(ur)) return boolT;
      }
      return invalid();
    }
    case BinaryOp::And: case BinaryOp::Or: case BinaryOp::Xor: {
      if (ul->isBool() && ur->isBool()) return boolT;
      bool lok = ul->isAnyBit() || (allows(DialectRule::IntegerBitString) && ul->isInteger());
      bool rok = ur->isAnyBit() || (allows(DialectRule::IntegerBitString) && ur->isInteger());
      if (!lok || !rok) return invalid();
      return commonType(lt, rt, e->lhs, e->rhs, e->opLoc, op);
    }
    case BinaryOp::AndThen: case BinaryOp::OrElse:
      if (ul->isBool() && ur->isBool()) return boolT;
      if (allows(DialectRule::IntegerAsBool) && (ul->isBool() || ul->isInteger()) && (ur->isBool() || ur->isInteger())) return boolT;
      return invalid();
  }
  return invalid();
}

// PRIVATE members are visible inside the declaring FB only; PROTECTED ones
// also inside FBs derived from it.
bool SemaImpl::checkAccess(Symbol* member, const Context& ctx, SourceRange where) {
  if (!member || !member->pou || !member->pou->decl) return true;
  Access a = member->pou->decl->access;
  if (a != Access::Private && a != Access::Protected) return true;
  Symbol* declaring = member->pou->owner;
  Symbol* caller = ownerOf(ctx.pou);
  bool ok = caller == declaring;
  if (!ok && a == Access::Protected)
    for (Symbol* b = caller && caller->pou ? caller->pou->base : nullptr; b && !ok; b = b->pou ? b->pou->base : nullptr) ok = b == declaring;
  if (ok) return true;
  const char* what = member->kind == Symbol::Property ? "property" : member->kind == Symbol::Action ? "action" : "method";
  diags_.error(where.begin, std::string(what) + " '" + member->name + "' is " + (a == Access::Private ? "PRIVATE to '" : "PROTECTED in '") +
                                (declaring ? declaring->name : std::string("?")) + "'", "access")
      .range(where);
  return false;
}

bool SemaImpl::isBareEnumValueName(Expr* e, const Context& ctx) {
  auto* n = dyn_cast<NameExpr>(e);
  if (!n) return false;
  std::string up = upperCase(n->ident.name);
  return !lookup(up, ctx) && enumValues_.count(up) && enumValues_[up].size() > 1;
}

// ------------------------------------------------------------------ calls

void SemaImpl::checkArguments(CallExpr* e, const std::vector<Symbol*>& params, const Context& ctx, const std::string& callee, bool isFunction) {
  bool anyNamed = false, anyPositional = false;
  for (Argument& a : e->args) (a.kind == Argument::Positional ? anyPositional : anyNamed) = true;
  if (anyNamed && anyPositional) {
    // CODESYS allows positional arguments first, then named ones; IEC does not.
    bool orderOk = true;
    bool seenNamed = false;
    for (Argument& a : e->args) {
      if (a.kind != Argument::Positional) seenNamed = true;
      else if (seenNamed) orderOk = false;
    }
    if (!allows(DialectRule::PositionalThenNamed) || !orderOk)
      diags_.error(e->range.begin, "cannot mix positional and named arguments in the call to '" + callee + "'", "call-args").range(e->parenRange);
  }
  // Non-formal calls bind every parameter in declaration order, outputs too
  // (`Add(1, 2, sum)`, `Ton1(start, T#3s, done, elapsed)`).
  std::vector<Symbol*> positionalParams;
  for (Symbol* p : params)
    if (p->var) positionalParams.push_back(p);
  std::set<Symbol*> given;
  size_t posIndex = 0;
  auto checkInOut = [&](Symbol* p, Expr* v) {
    const Type* pt = p->type ? p->type : types_.error();
    const Type* at = checkExpr(v, ctx, pt);
    if (at->isError() || pt->isError()) return;
    std::string why;
    Symbol* decl = nullptr;
    if (!isLvalue(v, ctx, why, &decl)) {
      diags_.error(v->range.begin, "VAR_IN_OUT '" + p->name + "' of '" + callee + "' needs a variable, not " + why, "in-out").range(v->range);
      return;
    }
    if (decl && decl->var && decl->var->isConstant) {
      diags_.error(v->range.begin, "cannot pass constant '" + decl->name + "' to VAR_IN_OUT '" + p->name + "'", "assign-constant").range(v->range);
      return;
    }
    if (at->kind == TypeKind::Bit) {
      diags_.error(v->range.begin, "cannot pass a BIT member to VAR_IN_OUT '" + p->name + "': it is one bit of a byte", "in-out").range(v->range);
      return;
    }
    Conv c = classify(at, pt);
    bool ok = c == Conv::Exact || (c == Conv::Widening && (isPouType(at) || at->kind == TypeKind::Struct));
    if (allows(DialectRule::StringInOutAnyLength) && at->isString() && pt->isString() && at->kind == pt->kind) ok = true;
    if (!ok)
      diags_.error(v->range.begin, "cannot pass '" + at->name + "' to VAR_IN_OUT '" + p->name + "' of type '" + pt->name + "'", "type-mismatch")
          .range(v->range).note(p->declRange.begin, "parameter declared here", p->declRange);
  };
  auto checkInput = [&](Symbol* p, Expr* v) {
    // A REFERENCE TO input is bound to what is passed (as by REF=), not assigned through.
    if (p->type && p->type->isReference()) return checkReferenceBinding(p->type, v, ctx, "REFERENCE TO input '" + p->name + "'");
    const Type* pt = p->type ? valueType(p->type) : types_.error();
    checkExpr(v, ctx, pt);
    // Arrays passed to POINTER TO parameters (CODESYS libraries do this).
    if (allows(DialectRule::ArrayAsPointerArgument) && pt->isPointer() && v->type && v->type->kind == TypeKind::Array) return;
    if (checkConversion(pt, v, "argument") && p->type && v->type && !v->type->isError())
      checkNoStaticCopy(p->type, v->range, "into " + std::string(p->var ? spelling(p->var->section) : "parameter") + " '" + p->name + "' of '" + callee + "'");
  };
  for (Argument& a : e->args) {
    if (a.kind == Argument::Positional) {
      if (posIndex >= positionalParams.size()) {
        auto d = diags_.error(a.range.begin, "too many arguments in the call to '" + callee + "' (it takes " +
                                                 std::to_string(positionalParams.size()) + ")", "call-args");
        d.range(a.range);
        if (a.value) checkExpr(a.value, ctx);
        break;
      }
      Symbol* p = positionalParams[posIndex++];
      if (p->var->section == VarSection::Output) {
        // An output in its place: checked below as `name => value`.
        a.kind = Argument::Output;
        a.name = Ident{p->name, a.range};
      } else {
        given.insert(p);
        a.param = p;
        if (!a.value) continue;
        if (p->var->section == VarSection::InOut) checkInOut(p, a.value);
        else checkInput(p, a.value);
        continue;
      }
    }
    std::string up = upperCase(a.name.name);
    Symbol* p = nullptr;
    for (Symbol* q : params)
      if (upperCase(q->name) == up) p = q;
    // CODESYS spells some standard parameters differently (CTU.RESET for
    // IEC's R): declarations carry {attribute 'alias' := 'RESET'}.
    if (!p)
      for (Symbol* q : params)
        if (q->var)
          for (const Pragma& pr : q->var->attributes)
            if (upperCase(pr.name) == "ALIAS" && upperCase(pr.value) == up) p = q;
    if (!p) {
      std::vector<std::string> names;
      for (Symbol* q : params) names.push_back(q->name);
      errorWithHint(a.name.range, "'" + callee + "' has no parameter named '" + a.name.name + "'", a.name.name, names, "call-args");
      if (a.value) checkExpr(a.value, ctx);
      continue;
    }
    if (!given.insert(p).second) {
      diags_.error(a.name.range.begin, "parameter '" + p->name + "' is given more than once", "call-args").range(a.name.range);
      continue;
    }
    a.param = p;
    VarSection sec = p->var ? p->var->section : VarSection::Input;
    if (a.kind == Argument::Input) {
      if (sec == VarSection::Output) {
        diags_.error(a.name.range.begin, "'" + p->name + "' is an output of '" + callee + "'; use '=>' to read it", "call-args")
            .range(a.range).note(p->declRange.begin, "declared here", p->declRange);
        continue;
      }
      if (!a.value) {
        if (sec == VarSection::InOut)
          diags_.error(a.name.range.begin, "VAR_IN_OUT '" + p->name + "' of '" + callee + "' needs a variable", "in-out").range(a.range);
        continue;
      }
      if (sec == VarSection::InOut) checkInOut(p, a.value);
      else checkInput(p, a.value);
    } else {
      if (sec != VarSection::Output) {
        diags_.error(a.name.range.begin, "'" + p->name + "' is not an output of '" + callee + "'; use ':=' to pass it", "call-args")
            .range(a.range).note(p->declRange.begin, "declared here", p->declRange);
        continue;
      }
      if (!a.value) continue;
      const Type* vt = checkExpr(a.value, ctx);
      checkAssignTarget(a.value, ctx, body_);
      const Type* pt = p->type ? valueType(p->type) : types_.error();
      if (a.negated && !valueType(pt)->isBool()) {
        diags_.error(a.range.begin, "'NOT' on an output needs a BOOL output; '" + p->name + "' is '" + pt->name + "'", "type-mismatch").range(a.range);
        continue;
      }
      if (!vt->isError() && !pt->isError()) {
        Conv c = classify(pt, valueType(vt));
        bool ok = c == Conv::Exact || c == Conv::Widening ||
                  allowsImplicit(c);
        if (!ok)
          diags_.error(a.value->range.begin, "cannot store output '" + p->name + "' of type '" + pt->name + "' in a variable of type '" +
                                                 valueType(vt)->name + "'", "type-mismatch").range(a.value->range);
      }
    }
  }
  // Required parameters.
  for (Symbol* p : params) {
    if (given.count(p) || !p->var) continue;
    if (p->var->section == VarSection::InOut) {
      diags_.error(e->range.begin, "missing VAR_IN_OUT argument '" + p->name + "' in the call to '" + callee + "'", "in-out")
          .range(e->range).note(p->declRange.begin, "parameter declared here", p->declRange);
    } else if (isFunction && !anyNamed && p->var->section == VarSection::Input && !p->var->init && posIndex < positionalParams.size()) {
      // Outputs may be left out at the end; they are not counted as needed.
      size_t needed = 0;
      for (Symbol* q : positionalParams) needed += q->var->section != VarSection::Output;
      diags_.error(e->range.begin, "too few arguments in the call to '" + callee + "' (it takes " + std::to_string(needed) +
                                       ", " + std::to_string(posIndex) + " given)", "call-args").range(e->parenRange);
      break;
    }
  }
}

const Type* SemaImpl::callPou(CallExpr* e, Symbol* target, const Context& ctx, const std::string& displayName, bool instanceCall) {
  if (target && target->kind == Symbol::Program) model_.calledPrograms.insert(target);
  resolveSignature(target);
  e->target = target;
  std::vector<Symbol*> params;
  // FB calls see inherited parameters, base first.
  std::vector<Symbol*> chain;
  for (Symbol* p = target; p && p->pou && chain.size() < 64; p = p->kind == Symbol::FunctionBlock ? p->pou->base : nullptr) chain.push_back(p);
  for (auto it = chain.rbegin(); it != chain.rend(); ++it)
    for (Symbol* p : (*it)->pou->params) params.push_back(p);
  bool isFunction = target->kind == Symbol::Function || target->kind == Symbol::Method;
  checkArguments(e, params, ctx, displayName, isFunction);
  recordCall(target, e->range);
  if (target->kind == Symbol::Function || target->kind == Symbol::Method)
    return target->pou->returnType ? target->pou->returnType : types_.voidType();
  (void)instanceCall;
  return types_.voidType();
}

const Type* SemaImpl::checkCall(CallExpr* e, const Context& ctx, const Type* expected) {
  Expr* callee = e->callee;
  auto notCallable = [&](const std::string& what, SourceRange r) -> const Type* {
    diags_.error(r.begin, what, "not-callable").range(r);
    for (Argument& a : e->args)
      if (a.value) checkExpr(a.value, ctx);
    return types_.error();
  };
  if (auto* n = dyn_cast<NameExpr>(callee)) {
    std::string up = upperCase(n->ident.name);
    Symbol* s = lookup(up, ctx);
    // CODESYS: TIME() is the controller's clock (the standard library's __STC_CLOCK_TIME).
    if (!s && up == "TIME" && e->args.empty())
      if (Symbol* clock = lookup("__STC_CLOCK_TIME", ctx); clock && clock->kind == Symbol::Function)
        return callPou(e, clock, ctx, n->ident.name, false);
    if (!s) {
      std::vector<std::string> names = visibleNames(ctx);
      for (auto& [k, b] : builtinMap_) names.push_back(b->name);
      errorWithHint(n->range, "call to undeclared function '" + n->ident.name + "'", n->ident.name, names, "undeclared-name");
      for (Argument& a : e->args)
        if (a.value) checkExpr(a.value, ctx);
      return types_.error();
    }
    n->symbol = s;
    n->type = types_.voidType();
    switch (s->kind) {
      case Symbol::BuiltinFunction: {
        e->target = s;
        const Type* t = s->builtin->check(*this, *s->builtin, e, expected, ctx);
        return t ? t : types_.error();
      }
      case Symbol::Method:
      case Symbol::Action:
        checkAccess(s, ctx, n->range);
        return callPou(e, s, ctx, s->name, false);
      case Symbol::Function:
      case Symbol::Program:
        return callPou(e, s, ctx, s->name, false);
      case Symbol::Variable: {
        markUsed(s);
        const Type* t = valueType(s->type ? s->type : types_.error());
        if (t->isError()) return t;
        if (t->kind == TypeKind::FunctionBlock) return callPou(e, t->pou, ctx, s->name, true);
        return notCallable("'" + s->name + "' is a variable of type '" + t->name + "' and cannot be called", n->range);
      }
      case Symbol::FunctionBlock:
        return notCallable("'" + s->name + "' is a function block type; declare an instance (x : " + s->name + ";) and call the instance", n->range);
      default:
        return notCallable("'" + s->name + "' is a " + kindWord(s) + " and cannot be called", n->range);
    }
  }
  if (auto* m = dyn_cast<MemberExpr>(callee)) {
    if (Symbol* ent = entityOf(m->base, ctx)) {
      if (ent->kind == Symbol::Namespace || ent->kind == Symbol::GlobalList) {
        Symbol* s = ent->scope->lookupLocal(upperCase(m->member.name));
        m->symbol = s;
        m->type = types_.voidType();
        if (!s) return notCallable("no function named '" + m->member.name + "' in " + kindWord(ent) + " '" + ent->name + "'", m->member.range);
        if (s->kind == Symbol::Function || s->kind == Symbol::Program) return callPou(e, s, ctx, ent->name + "." + s->name, false);
        if (s->kind == Symbol::Variable) {
          markUsed(s);
          const Type* t = valueType(s->type ? s->type : resolveType(s->var->type, Context{nullptr, ent->scope.get()}));
          if (t->kind == TypeKind::FunctionBlock) return callPou(e, t->pou, ctx, ent->name + "." + s->name, true);
        }
        return notCallable("'" + ent->name + "." + s->name + "' cannot be called", m->range);
      }
    }
    const Type* bt = valueType(checkExpr(m->base, ctx));
    m->type = types_.voidType();
    if (bt->isError()) {
      for (Argument& a : e->args)
        if (a.value) checkExpr(a.value, ctx);
      return bt;
    }
    if (isPouType(bt)) {
      Symbol* s = pouMember(bt->pou, upperCase(m->member.name));
      m->symbol = s;
      if (!s) {
        std::vector<std::string> names;
        for (Symbol* x : bt->pou->pou->members->symbols()) names.push_back(x->name);
        std::string hint = closestMatch(m->member.name, names);
        return notCallable("no method or action named '" + m->member.name + "' in '" + bt->name + "'" +
                               (hint.empty() ? "" : "; did you mean '" + hint + "'?"), m->member.range);
      }
      if (s->kind == Symbol::Method || s->kind == Symbol::Action) {
        checkAccess(s, ctx, m->member.range);
        return callPou(e, s, ctx, bt->name + "." + s->name, false);
      }
      if (s->kind == Symbol::Variable) {
        markUsed(s);
        const Type* vt = valueType(s->type);
        if (vt && vt->kind == TypeKind::FunctionBlock) return callPou(e, vt->pou, ctx, s->name, true);
      }
      return notCallable("'" + s->name + "' of '" + bt->name + "' cannot be called", m->member.range);
    }
    return notCallable("a value of type '" + bt->name + "' has no methods", m->range);
  }
  if (auto* d = dyn_cast<DerefExpr>(callee)) {
    const Type* bt = checkExpr(d, ctx);
    if (bt->isError()) return bt;
    if (bt->kind == TypeKind::FunctionBlock) return callPou(e, bt->pou, ctx, bt->name, true);
    return notCallable("a value of type '" + bt->name + "' cannot be called", d->range);
  }
  // Any other expression of function block type: arrays of instances
  // (timers[i](...)), struct members holding instances.
  const Type* ct = valueType(checkExpr(callee, ctx));
  if (ct->isError()) return ct;
  if (ct->kind == TypeKind::FunctionBlock) return callPou(e, ct->pou, ctx, ct->name, true);
  return notCallable("a value of type '" + ct->name + "' cannot be called", callee->range);
}

// ------------------------------------------------------------------ lvalues

bool SemaImpl::isLvalue(Expr* e, const Context& ctx, std::string& why, Symbol** declOut) {
  if (auto* n = dyn_cast<NameExpr>(e)) {
    Symbol* s = n->symbol;
    if (!s) { why = "an unresolved name"; return false; }
    if (declOut) *declOut = s;
    if (s->kind == Symbol::Variable) return true;
    if (s->kind == Symbol::Property) return true;
    why = std::string("a ") + kindWord(s);
    if (s->kind == Symbol::EnumValue) why = "an enumeration value";
    return false;
  }
  if (auto* m = dyn_cast<MemberExpr>(e)) {
    if (m->symbol && m->symbol->kind == Symbol::Variable) {
      if (declOut) *declOut = m->symbol;
      if (!m->base->type || m->base->type->kind == TypeKind::Void) return true;   // GVL.x, NS.x
      if (isPouType(valueType(m->base->type))) return true;
    }
    if (m->symbol && m->symbol->kind == Symbol::Property) { if (declOut) *declOut = m->symbol; return true; }
    if (m->type && m->type->kind == TypeKind::Enum && (!m->base->type || m->base->type->kind == TypeKind::Void)) { why = "an enumeration value"; return false; }
    return isLvalue(m->base, ctx, why, declOut);
  }
  if (auto* i = dyn_cast<IndexExpr>(e)) return isLvalue(i->base, ctx, why, declOut);
  if (isa<DerefExpr>(e)) return true;
  if (isa<CallExpr>(e)) { why = "a call result"; return false; }
  if (isa<LiteralExpr>(e)) { why = "a constant"; return false; }
  if (isa<DirectAddressExpr>(e)) return true;
  why = "an expression";
  return false;
}

void SemaImpl::checkAssignTarget(Expr* lhs, const Context& ctx, BodyState* body) {
  if (!lhs || !lhs->type || lhs->type->isError()) return;
  std::string why;
  Symbol* decl = nullptr;
  if (!isLvalue(lhs, ctx, why, &decl)) {
    diags_.error(lhs->range.begin, "cannot assign to " + why, "not-assignable").range(lhs->range);
    return;
  }
  if (body && decl && decl == body->resultVar) body->resultAssigned = true;
  if (decl && decl->kind == Symbol::Property) {
    if (!decl->pou->decl->setter)
      diags_.error(lhs->range.begin, "property '" + decl->name + "' has no SET accessor and cannot be assigned", "not-assignable")
          .range(lhs->range).note(decl->declRange.begin, "property declared here", decl->declRange);
    return;
  }
  // The root variable decides constness; an FB output decides outside writes.
  Expr* root = lhs;
  while (true) {
    if (auto* m = dyn_cast<MemberExpr>(root)) {
      if (m->symbol && m->symbol->kind == Symbol::Variable && m->symbol->var && m->base->type && isPouType(valueType(m->base->type))) {
        Symbol* member = m->symbol;
        bool inside = isa<ThisExpr>(m->base) || isa<DerefExpr>(m->base);
        if (member->var->section == VarSection::Output && !inside && valueType(m->base->type)->kind == TypeKind::FunctionBlock) {
          diags_.error(lhs->range.begin, "cannot assign to output '" + member->name + "' of function block instance; outputs are written by the block",
                       "assign-output").range(lhs->range).note(member->declRange.begin, "output declared here", member->declRange);
          return;
        }
        if (member->var->isConstant) {
          diags_.error(lhs->range.begin, "cannot assign to constant '" + member->name + "'", "assign-constant")
              .range(lhs->range).note(member->declRange.begin, "declared CONSTANT here", member->declRange);
          return;
        }
      }
      if (m->symbol && m->symbol->kind == Symbol::Variable && (!m->base->type || m->base->type->kind == TypeKind::Void)) {
        decl = m->symbol;
        break;
      }
      root = m->base;
      continue;
    }
    if (auto* i = dyn_cast<IndexExpr>(root)) { root = i->base; continue; }
    break;
  }
  if (auto* n = dyn_cast<NameExpr>(root)) decl = n->symbol;
  else if (!isa<MemberExpr>(root)) decl = nullptr;
  if (!decl || decl->kind != Symbol::Variable || !decl->var) return;
  if (decl->var->isConstant) {
    const char* what = decl->var->section == VarSection::Input ? "input" : "constant";
    diags_.error(lhs->range.begin, std::string("cannot assign to ") + what + " '" + decl->name + "'" +
                                       (decl->var->section == VarSection::Input ? " declared VAR_INPUT CONSTANT" : ""), "assign-constant")
        .range(lhs->range).note(decl->declRange.begin, "declared CONSTANT here", decl->declRange);
    return;
  }
  // A function's or method's input is a copy: writing it is legal but the
  // caller never sees the change, which is almost always a mistake.
  // (Through a REFERENCE TO input the write reaches the caller's variable.)
  if (decl->var->section == VarSection::Input && !(decl->type && decl->type->isReference()) && ctx.pou && ctx.pou->pou &&
      (ctx.pou->kind == Symbol::Function || ctx.pou->kind == Symbol::Method) &&
      ctx.pou->pou->vars->lookupLocal(upperCase(decl->name)) == decl)
    diags_.warning(lhs->range.begin, "assignment to input '" + decl->name + "' of " + (ctx.pou->kind == Symbol::Function ? "function" : "method") +
                                         " '" + ctx.pou->name + "'; the caller does not see the change", "assign-input")
        .range(lhs->range).note(decl->declRange.begin, "declared VAR_INPUT here", decl->declRange);
  if (body)
    for (auto& [v, f] : body->forVars)
      if (v == decl) {
        diags_.error(lhs->range.begin, "cannot assign to FOR loop variable '" + decl->name + "' inside its loop", "for-variable")
            .range(lhs->range).note(f->var->range.begin, "loop variable of this FOR", f->var->range);
        return;
      }
}

// ------------------------------------------------------------------ initializers

const Type* SemaImpl::checkInitializer(Expr* init, const Type* target, const Context& ctx) {
  if (!init || !target || target->isError()) return target;
  if (auto* a = dyn_cast<ArrayInitExpr>(init)) {
    init->type = target;
    if (target->kind != TypeKind::Array) {
      diags_.error(init->range.begin, "an array initializer needs an array type, not '" + target->name + "'", "invalid-init").range(init->range);
      return types_.error();
    }
    uint64_t capacity = 1;
    for (const Dim& d : target->dims) capacity *= d.star ? 1 : static_cast<uint64_t>(d.hi - d.lo + 1);
    // Nested [[..],[..]] for multi-dimensional arrays initialise row by row.
    const Type* elem = target->element;
    uint64_t count = 0;
    for (auto& el : a->elements) {
      count += el.repeat;
      if (el.repeated && el.repeat == 0)
        diags_.error(el.range.begin, "repetition count must be at least 1", "invalid-init").range(el.range);
      if (el.value) checkInitializer(el.value, isa<ArrayInitExpr>(el.value) && target->dims.size() > 1
                                                   ? types_.array(elem, std::vector<Dim>(target->dims.begin() + 1, target->dims.end()))
                                                   : elem, ctx);
    }
    bool nested = !a->elements.empty() && a->elements[0].value && isa<ArrayInitExpr>(a->elements[0].value) && target->dims.size() > 1;
    uint64_t limit = nested ? static_cast<uint64_t>(target->dims[0].hi - target->dims[0].lo + 1) : capacity;
    if (count > limit)
      diags_.error(init->range.begin, "too many initial values (" + std::to_string(count) + ") for '" + target->name + "' (" +
                                          std::to_string(limit) + " elements)", "invalid-init").range(init->range);
    return target;
  }
  if (auto* s = dyn_cast<StructInitExpr>(init)) {
    init->type = target;
    if (target->kind == TypeKind::Struct || target->kind == TypeKind::Union) {
      for (auto& f : s->fields) {
        const Member* found = nullptr;
        for (const Type* t = target; t && !found; t = t->base)
          for (const Member& m : t->members)
            if (upperCase(m.name) == upperCase(f.name.name)) { found = &m; break; }
        if (!found) {
          diags_.error(f.name.range.begin, "no member named '" + f.name.name + "' in '" + target->name + "'", "no-member").range(f.name.range);
          continue;
        }
        if (isInternal(found->decl)) {
          reportInternal(found->name, target->name, f.name.range, found->decl->name.range);
          continue;
        }
        checkInitializer(f.value, found->type, ctx);
      }
      return target;
    }
    if (target->kind == TypeKind::FunctionBlock) {
      // FB instance initialisation sets inputs (and other parameters).
      for (auto& f : s->fields) {
        Symbol* m = lookupInPou(target->pou, upperCase(f.name.name), false);
        if (!m) {
          diags_.error(f.name.range.begin, "no parameter named '" + f.name.name + "' in '" + target->name + "'", "no-member").range(f.name.range);
          continue;
        }
        if (isInternal(m->var)) {
          reportInternal(m->name, target->name, f.name.range, m->declRange);
          continue;
        }
        checkInitializer(f.value, m->type, ctx);
      }
      return target;
    }
    diags_.error(init->range.begin, "a structure initializer needs a structure or function block type, not '" + target->name + "'", "invalid-init")
        .range(init->range);
    return types_.error();
  }
  if (!init->type) checkExpr(init, ctx, target);
  if (checkConversion(target, init, "initializer") && init->type && !init->type->isError()) checkNoStaticCopy(target, init->range, "in an initializer");
  return target;
}

}  // namespace stc::sema
