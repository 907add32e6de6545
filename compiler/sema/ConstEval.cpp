// Constant evaluation on checked expressions: literals, CONSTANT variables,
// enumeration values and arithmetic on them.  Used for array bounds, string
// lengths, subranges, enumeration values and CASE labels.
#include <cmath>

#include "sema/SemaInternal.h"

namespace stc::sema {

std::optional<ConstValue> SemaImpl::evalConst(Expr* e, const Context& ctx) {
  if (!e) return std::nullopt;
  if (auto* l = dyn_cast<LiteralExpr>(e)) {
    ConstValue v;
    switch (l->litKind) {
      case LiteralExpr::Int:
        v.kind = ConstValue::Int;
        v.i = static_cast<int64_t>(l->negative ? 0 - l->intValue : l->intValue);
        if (!l->negative && l->intValue > static_cast<uint64_t>(INT64_MAX)) v.isUnsignedBig = true;
        if (e->type && e->type->isBool()) v.kind = ConstValue::Bool;
        return v;
      case LiteralExpr::Real: v.kind = ConstValue::Real; v.r = l->realValue; return v;
      case LiteralExpr::Bool: v.kind = ConstValue::Bool; v.i = static_cast<int64_t>(l->intValue); return v;
      case LiteralExpr::Enum: v.kind = ConstValue::Int; v.i = static_cast<int64_t>(l->intValue); return v;
      case LiteralExpr::Time: v.kind = ConstValue::Int; v.i = static_cast<int64_t>(l->intValue); return v;
      default: return std::nullopt;
    }
  }
  const Symbol* sym = nullptr;
  if (auto* n = dyn_cast<NameExpr>(e)) sym = n->symbol;
  else if (auto* m = dyn_cast<MemberExpr>(e)) {
    sym = m->symbol;
    // E.value of an enumeration type.
    if (!sym && m->type && m->type->kind == TypeKind::Enum) {
      for (auto& [name, val] : m->type->enumValues)
        if (upperCase(name) == upperCase(m->member.name)) { ConstValue v; v.i = val; return v; }
    }
  }
  if (sym) {
    if (sym->kind == Symbol::EnumValue) { ConstValue v; v.i = sym->enumValue; return v; }
    if (sym->kind == Symbol::Variable && sym->var && sym->var->isFoldableConstant()) {
      auto* s = const_cast<Symbol*>(sym);
      if (s->cyclic) {
        constEvalFailed_ = true;
        return std::nullopt;
      }
      if (s->resolving) {
        diags_.error(e->range.begin, "constant '" + sym->name + "' depends on itself", "not-constant").range(e->range);
        for (Symbol* c : constStack_) c->cyclic = true;   // report each cycle once
        constEvalFailed_ = true;
        return std::nullopt;
      }
      Context declCtx = ctx;
      auto it = outerScope_.find(s);
      if (it != outerScope_.end()) declCtx = Context{nullptr, it->second};
      s->resolving = true;
      constStack_.push_back(s);
      if (!s->type) s->type = resolveType(s->var->type, declCtx);
      if (!sym->var->init->type) checkExpr(sym->var->init, declCtx, s->type);
      auto v = evalConst(sym->var->init, declCtx);
      constStack_.pop_back();
      s->resolving = false;
      return v;
    }
    return std::nullopt;
  }
  if (auto* u = dyn_cast<UnaryExpr>(e)) {
    auto v = evalConst(u->operand, ctx);
    if (!v) return v;
    if (u->op == UnaryOp::Neg) { if (v->kind == ConstValue::Real) v->r = -v->r; else v->i = -v->i; }
    else if (u->op == UnaryOp::Not) { if (v->kind == ConstValue::Bool) v->i = !v->i; else v->i = ~v->i; }
    return v;
  }
  if (auto* b = dyn_cast<BinaryExpr>(e)) {
    auto l = evalConst(b->lhs, ctx);
    auto r = evalConst(b->rhs, ctx);
    if (!l || !r) return std::nullopt;
    ConstValue v;
    bool real = l->kind == ConstValue::Real || r->kind == ConstValue::Real;
    auto boolean = [&](bool x) { ConstValue c; c.kind = ConstValue::Bool; c.i = x; return c; };
    switch (b->op) {
      case BinaryOp::Add:
      case BinaryOp::Sub:
      case BinaryOp::Mul: {
        if (real) {
          v.kind = ConstValue::Real;
          v.r = b->op == BinaryOp::Add ? l->asReal() + r->asReal() : b->op == BinaryOp::Sub ? l->asReal() - r->asReal() : l->asReal() * r->asReal();
          return v;
        }
        bool ovf = b->op == BinaryOp::Add ? __builtin_add_overflow(l->i, r->i, &v.i)
                   : b->op == BinaryOp::Sub ? __builtin_sub_overflow(l->i, r->i, &v.i) : __builtin_mul_overflow(l->i, r->i, &v.i);
        if (ovf) {
          diags_.error(b->opLoc, "integer overflow in a constant expression (beyond 64-bit LINT)", "constant-range").range(b->range);
          constEvalFailed_ = true;
          return std::nullopt;
        }
        return v;
      }
      case BinaryOp::Div:
        if (real) { v.kind = ConstValue::Real; v.r = l->asReal() / r->asReal(); return v; }
        if (r->i == 0) {
          constEvalFailed_ = true;   // reported by checkBinary
          return std::nullopt;
        }
        if (l->i == INT64_MIN && r->i == -1) return std::nullopt;
        v.i = l->i / r->i;
        return v;
      case BinaryOp::Mod:
        if (real) return std::nullopt;
        if (r->i == 0) {
          constEvalFailed_ = true;   // reported by checkBinary
          return std::nullopt;
        }
        if (l->i == INT64_MIN && r->i == -1) { v.i = 0; return v; }
        v.i = l->i % r->i;
        return v;
      case BinaryOp::Pow: v.kind = ConstValue::Real; v.r = std::pow(l->asReal(), r->asReal()); return v;
      case BinaryOp::Lt: return boolean(l->asReal() < r->asReal());
      case BinaryOp::Gt: return boolean(l->asReal() > r->asReal());
      case BinaryOp::Le: return boolean(l->asReal() <= r->asReal());
      case BinaryOp::Ge: return boolean(l->asReal() >= r->asReal());
      case BinaryOp::Eq: return boolean(real ? l->asReal() == r->asReal() : l->i == r->i);
      case BinaryOp::Ne: return boolean(real ? l->asReal() != r->asReal() : l->i != r->i);
      case BinaryOp::And: case BinaryOp::AndThen: v = *l; v.i = l->i & r->i; return v;
      case BinaryOp::Or: case BinaryOp::OrElse: v = *l; v.i = l->i | r->i; return v;
      case BinaryOp::Xor: v = *l; v.i = l->i ^ r->i; return v;
    }
  }
  if (auto* c = dyn_cast<CallExpr>(e)) {
    // SIZEOF(type or variable) is a constant.
    if (c->target && c->target->kind == Symbol::BuiltinFunction && c->target->name == "SIZEOF" && c->args.size() == 1 && c->args[0].value) {
      const Type* t = c->args[0].value->type;
      if (t && !t->isError()) {
        if (uint64_t n = sizeOf(valueType(t))) { ConstValue v; v.i = static_cast<int64_t>(n); return v; }
      }
      return std::nullopt;
    }
    // Conversions between integer types keep constant values (INT_TO_DINT(5)).
    if (c->target && c->target->kind == Symbol::BuiltinFunction && c->args.size() == 1 && c->args[0].value &&
        c->target->name.find("_TO_") != std::string::npos && e->type && e->type->isInteger()) {
      auto v = evalConst(c->args[0].value, ctx);
      if (v && v->kind == ConstValue::Real) { v->kind = ConstValue::Int; v->i = static_cast<int64_t>(std::llround(v->r)); }
      if (v) {
        // The target type's width and signedness: WORD_TO_INT(16#FF00) = -256.
        unsigned bits = e->type->bits();
        if (bits < 64) {
          uint64_t mask = (1ull << bits) - 1;
          uint64_t u = static_cast<uint64_t>(v->i) & mask;
          if (e->type->isSignedInt() && (u >> (bits - 1))) u |= ~mask;
          v->i = static_cast<int64_t>(u);
        }
        v->kind = ConstValue::Int;
      }
      return v;
    }
  }
  return std::nullopt;
}

// Size in bytes with natural alignment (the layout code generation uses).
uint64_t SemaImpl::sizeOf(const Type* t) const { return layout_.sizeOf(t); }
uint64_t SemaImpl::alignOf(const Type* t) const { return layout_.alignOf(t); }

std::optional<int64_t> SemaImpl::evalInt(Expr* e, const Context& ctx, const char* what) {
  if (!e || (e->type && e->type->isError())) return std::nullopt;
  constEvalFailed_ = false;
  auto v = evalConst(e, ctx);
  if (!v && constEvalFailed_) return std::nullopt;   // the cause is already reported
  if (!v) {
    diags_.error(e->range.begin, std::string(what) + " must be a constant expression", "not-constant").range(e->range);
    return std::nullopt;
  }
  if (v->isUnsignedBig && allowUnsigned_) return v->i;   // bit pattern of a ULINT bound
  if (v->isUnsignedBig) {
    diags_.error(e->range.begin, std::string(what) + " " + std::to_string(static_cast<uint64_t>(v->i)) + " is too large (at most 9223372036854775807)",
                 "constant-range").range(e->range);
    return std::nullopt;
  }
  if (v->kind == ConstValue::Real) {
    diags_.error(e->range.begin, std::string(what) + " must be an integer, not a real number", "not-constant").range(e->range);
    return std::nullopt;
  }
  return v->i;
}

}  // namespace stc::sema
