// Statements and bodies, plus the whole-program checks that need every body:
// recursion in the call graph and unused variables.
#include <algorithm>
#include <functional>

#include "sema/SemaInternal.h"

namespace stc::sema {

void SemaImpl::checkBody(Symbol* pou) {
  PouInfo& pi = *pou->pou;
  if (pi.bodyChecked) return;
  pi.bodyChecked = true;
  PouDecl* d = pi.decl;
  if (!d->hasBody && d->pouKind != PouKind::PropertyGet && d->pouKind != PouKind::PropertySet) return;
  Context ctx{pou, outerScope_.count(pou) ? outerScope_[pou] : &global_};
  BodyState st;
  st.pou = pou;
  // Result variable of functions, methods and GET accessors.
  std::unique_ptr<Symbol> result;
  if ((pou->kind == Symbol::Function || pou->kind == Symbol::Method) && pi.returnType && pi.returnType->kind != TypeKind::Void) {
    std::string name = pou->name;
    if (d->pouKind == PouKind::PropertyGet && d->owner) name = d->owner->name.parts.back().name;
    result = std::make_unique<Symbol>();
    result->kind = Symbol::Variable;
    result->name = name;
    result->type = pi.returnType;
    result->declRange = d->name.range;
    st.resultVar = result.get();
    pi.result = result.get();
  }
  BodyState* saveBody = body_;
  Symbol* saveCaller = currentCaller_;
  body_ = &st;
  // Calls from a method/action body count as calls from the FB for recursion.
  currentCaller_ = pou;
  checkStmts(d->body, ctx, st);
  for (JmpStmt* j : st.jumps)
    if (!st.labels.count(upperCase(j->target.name)))
      diags_.error(j->target.range.begin, "use of undeclared label '" + j->target.name + "'", "undeclared-label").range(j->target.range);
  bool native = false;   // implemented in C++: the ST body is only a declaration
  for (const Pragma& p : d->attributes) native = native || upperCase(p.name) == "NATIVE";
  if (st.resultVar && !st.resultAssigned && !native && d->pouKind != PouKind::PropertySet && !d->isAbstract && !pi.returnType->isError()) {
    const char* what = d->pouKind == PouKind::PropertyGet ? "GET accessor of property" : pou->kind == Symbol::Function ? "function" : "method";
    SourceRange at = d->endRange.valid() ? d->endRange : d->name.range;
    diags_.warning(at.begin, std::string(what) + " '" + st.resultVar->name + "' never assigns its return value; it returns the default value of '" +
                                 pi.returnType->name + "'", "return-value").range(at);
  }
  body_ = saveBody;
  currentCaller_ = saveCaller;
  // Keep the result symbol alive for AST references.
  if (result) symbols_.push_back(std::move(result));
}

void SemaImpl::checkStmts(std::vector<Stmt*>& stmts, const Context& ctx, BodyState& st) {
  for (Stmt* s : stmts) {
    if (diags_.limitReached()) return;
    checkStmt(s, ctx, st);
  }
}

void SemaImpl::checkCondition(Expr* e, const Context& ctx, const char* what) {
  const Type* boolT = types_.elementary(TypeKind::Bool);
  const Type* t = valueType(checkExpr(e, ctx, boolT));
  if (t->isError()) return;
  if (t->isBool()) return;
  auto* lit = dyn_cast<LiteralExpr>(e);
  if (allows(DialectRule::IntegerAsBool) && (t->underlying()->isInteger() || t->underlying()->isBitString())) {
    if (!(lit && lit->intValue <= 1))
      diags_.warning(e->range.begin, std::string(what) + " of type '" + t->name + "' is used as BOOL (non-zero is TRUE)", "int-bool-conversion")
          .range(e->range);
    return;
  }
  diags_.error(e->range.begin, std::string(what) + " must be BOOL, not '" + t->name + "'", "type-mismatch").range(e->range);
}

// `r REF= v`, and a call that passes `v` to a REFERENCE TO input: v must be a
// variable (not a constant) of the referenced type or derived from it, or 0.
void SemaImpl::checkReferenceBinding(const Type* refType, Expr* rhs, const Context& ctx, const std::string& what) {
  const Type* rt = checkExpr(rhs, ctx, refType->element);
  if (rt->isError()) return;
  auto* lit = dyn_cast<LiteralExpr>(rhs);
  if (lit && lit->litKind == LiteralExpr::Int && lit->intValue == 0) return;   // binding to 0 clears
  std::string why;
  Symbol* decl = nullptr;
  if (!isLvalue(rhs, ctx, why, &decl)) {
    diags_.error(rhs->range.begin, what + " needs a variable on the right, not " + why, "not-assignable").range(rhs->range);
    return;
  }
  if (decl && decl->var && decl->var->isConstant) {
    diags_.error(rhs->range.begin, "cannot bind a reference to constant '" + decl->name + "'", "assign-constant")
        .range(rhs->range).note(decl->declRange.begin, "declared CONSTANT here", decl->declRange);
    return;
  }
  Conv c = classify(rt, refType->element);
  if (!(c == Conv::Exact || (c == Conv::Widening && (rt->kind == TypeKind::FunctionBlock || rt->kind == TypeKind::Struct))))
    diags_.error(rhs->range.begin, "cannot bind a reference to '" + refType->element->name + "' to a variable of type '" + rt->name + "'",
                 "type-mismatch").range(rhs->range);
}

void SemaImpl::checkStmt(Stmt* s, const Context& ctx, BodyState& st) {
  if (!s) return;
  switch (s->kind) {
    case Stmt::Assign: {
      auto* a = cast<AssignStmt>(s);
      if (a->op == AssignStmt::Ref) {
        // r REF= v: r must be a reference, v a variable of the referenced type.
        const Type* lt = nullptr;
        Symbol* ls = nullptr;
        checkExpr(a->lhs, ctx);
        if (auto* n = dyn_cast<NameExpr>(a->lhs)) ls = n->symbol;
        else if (auto* m = dyn_cast<MemberExpr>(a->lhs)) ls = m->symbol;
        if (ls && ls->kind == Symbol::Variable) lt = ls->type;
        if (!lt || !lt->isReference()) {
          if (a->lhs->type && !a->lhs->type->isError())
            diags_.error(a->opLoc, "left side of 'REF=' must be a REFERENCE TO variable", "type-mismatch").range(a->lhs->range);
          checkExpr(a->rhs, ctx);
          return;
        }
        checkReferenceBinding(lt, a->rhs, ctx, "'REF='");
        return;
      }
      readingLhs_ = true;
      const Type* lt = checkExpr(a->lhs, ctx);
      readingLhs_ = false;
      if (a->op == AssignStmt::Set || a->op == AssignStmt::Reset) {
        checkAssignTarget(a->lhs, ctx, &st);
        if (!lt->isError() && !valueType(lt)->isBool())
          diags_.error(a->opLoc, std::string(a->op == AssignStmt::Set ? "'S='" : "'R='") + " needs a BOOL variable, not '" + lt->name + "'",
                       "type-mismatch").range(a->lhs->range);
        checkCondition(a->rhs, ctx, "the condition of S=/R=");
        return;
      }
      checkExpr(a->rhs, ctx, lt);
      checkAssignTarget(a->lhs, ctx, &st);
      if (!lt->isError() && checkConversion(valueType(lt), a->rhs, "assignment") && a->rhs->type && !a->rhs->type->isError())
        checkNoStaticCopy(valueType(lt), SourceRange(a->lhs->range.begin, a->rhs->range.end), "in an assignment");
      return;
    }
    case Stmt::ExprS: {
      auto* e = cast<ExprStmt>(s);
      checkExpr(e->expr, ctx);
      if (isa<CallExpr>(e->expr)) return;
      if (auto* b = dyn_cast<BinaryExpr>(e->expr); b && b->op == BinaryOp::Eq) {
        diags_.error(b->opLoc, "comparison result unused; did you mean ':=' to assign?", "unused-result")
            .range(e->expr->range).fixit(SourceRange(b->opLoc, {b->opLoc.file, b->opLoc.offset + 1}), ":=");
        return;
      }
      diags_.error(e->expr->range.begin, "expression result unused; only calls can stand alone as statements", "unused-result").range(e->expr->range);
      return;
    }
    case Stmt::If: {
      auto* i = cast<IfStmt>(s);
      for (auto& b : i->branches) {
        checkCondition(b.cond, ctx, "IF condition");
        checkStmts(b.body, ctx, st);
      }
      checkStmts(i->elseBody, ctx, st);
      return;
    }
    case Stmt::Case: checkCase(cast<CaseStmt>(s), ctx, st); return;
    case Stmt::For: checkFor(cast<ForStmt>(s), ctx, st); return;
    case Stmt::While: {
      auto* w = cast<WhileStmt>(s);
      checkCondition(w->cond, ctx, "WHILE condition");
      ++st.loopDepth;
      checkStmts(w->body, ctx, st);
      --st.loopDepth;
      return;
    }
    case Stmt::Repeat: {
      auto* r = cast<RepeatStmt>(s);
      ++st.loopDepth;
      checkStmts(r->body, ctx, st);
      --st.loopDepth;
      checkCondition(r->cond, ctx, "UNTIL condition");
      return;
    }
    case Stmt::Exit:
    case Stmt::Continue:
      if (st.loopDepth == 0)
        diags_.error(s->range.begin, std::string(s->kind == Stmt::Exit ? "EXIT" : "CONTINUE") + " outside of a loop", "loop-control").range(s->range);
      return;
    case Stmt::Return:
    case Stmt::Empty:
      return;
    case Stmt::Jmp:
      st.jumps.push_back(cast<JmpStmt>(s));
      return;
    case Stmt::Label: {
      auto* l = cast<LabelStmt>(s);
      auto [it, inserted] = st.labels.emplace(upperCase(l->label.name), l);
      if (!inserted)
        diags_.error(l->label.range.begin, "redefinition of label '" + l->label.name + "'", "redefinition")
            .range(l->label.range).note(it->second->label.range.begin, "previous definition is here", it->second->label.range);
      checkStmt(l->stmt, ctx, st);
      return;
    }
  }
}

void SemaImpl::checkCase(CaseStmt* s, const Context& ctx, BodyState& st) {
  const Type* sel = valueType(checkExpr(s->selector, ctx));
  const Type* u = sel->underlying();
  bool ok = sel->isError() || u->isInteger() || sel->kind == TypeKind::Enum || (allows(DialectRule::CaseOnBitString) && (u->isBitString() || u->isBool()));
  if (!ok) diags_.error(s->selector->range.begin, "CASE selector must be an integer or enumeration, not '" + sel->name + "'", "type-mismatch")
               .range(s->selector->range);
  struct Seen { int64_t lo, hi; SourceRange range; };
  std::vector<Seen> seen;
  for (auto& el : s->elements) {
    for (auto& lb : el.labels) {
      const Type* expect = sel->isError() ? nullptr : sel;
      checkExpr(lb.lo, ctx, expect);
      if (lb.hi) checkExpr(lb.hi, ctx, expect);
      bool labelOk = true;
      if (!sel->isError() && ok) {
        labelOk = checkConversion(sel, lb.lo, "CASE label");
        if (lb.hi) labelOk = checkConversion(sel, lb.hi, "CASE label") && labelOk;
        if (labelOk && sel->kind == TypeKind::Enum && lb.lo->type && valueType(lb.lo->type) != sel) labelOk = false;
      }
      if (!labelOk || (lb.lo->type && lb.lo->type->isError())) continue;
      constEvalFailed_ = false;
      auto lo = evalConst(lb.lo, ctx);
      std::optional<ConstValue> hi = lb.hi ? evalConst(lb.hi, ctx) : lo;
      if (!lo || !hi || lo->kind == ConstValue::Real || hi->kind == ConstValue::Real) {
        if (lb.lo->type && !lb.lo->type->isError() && (!lo || !hi) && !constEvalFailed_)
          diags_.error(lb.range.begin, "CASE label must be a constant", "not-constant").range(lb.range);
        continue;
      }
      if (lo->i > hi->i) {
        diags_.error(lb.range.begin, "empty CASE range: " + std::to_string(lo->i) + " is greater than " + std::to_string(hi->i), "case-range").range(lb.range);
        continue;
      }
      for (const Seen& p : seen) {
        if (lo->i <= p.hi && p.lo <= hi->i) {
          int64_t v = std::max(lo->i, p.lo);
          // Name enumeration values by name.
          std::string shown = std::to_string(v);
          if (sel->kind == TypeKind::Enum)
            for (auto& [n, ev] : sel->enumValues)
              if (ev == v) { shown = n; break; }
          diags_.error(lb.range.begin, "duplicate CASE value " + shown, "duplicate-case")
              .range(lb.range).note(p.range.begin, "previous CASE label is here", p.range);
          break;
        }
      }
      seen.push_back({lo->i, hi->i, lb.range});
    }
    checkStmts(el.body, ctx, st);
  }
  checkStmts(s->elseBody, ctx, st);
}

void SemaImpl::checkFor(ForStmt* s, const Context& ctx, BodyState& st) {
  const Type* vt = checkExpr(s->var, ctx);
  Symbol* v = const_cast<Symbol*>(s->var->symbol);
  if (!vt->isError()) {
    if (!v || v->kind != Symbol::Variable) {
      diags_.error(s->var->range.begin, "FOR loop variable must be a variable", "for-variable").range(s->var->range);
    } else if (!vt->underlying()->isInteger()) {
      diags_.error(s->var->range.begin, "FOR loop variable '" + v->name + "' must have an integer type, not '" + vt->name + "'", "for-variable")
          .range(s->var->range).note(v->declRange.begin, "declared here", v->declRange);
    } else {
      for (auto& [fv, f] : st.forVars)
        if (fv == v)
          diags_.error(s->var->range.begin, "FOR loop variable '" + v->name + "' is already the variable of an enclosing FOR", "for-variable")
              .range(s->var->range).note(f->var->range.begin, "enclosing loop is here", f->var->range);
      if (v->var && v->var->isConstant)
        diags_.error(s->var->range.begin, "FOR loop variable '" + v->name + "' is a constant", "assign-constant").range(s->var->range);
    }
  }
  for (Expr* e : {s->from, s->to, s->by}) {
    if (!e) continue;
    checkExpr(e, ctx, vt->isError() ? nullptr : vt);
    if (!vt->isError()) checkConversion(valueType(vt), e, "FOR bound");
  }
  if (s->by)
    if (auto c = evalConst(s->by, ctx); c && c->kind == ConstValue::Int && c->i == 0)
      diags_.error(s->by->range.begin, "FOR step is zero; the loop would never end", "for-step").range(s->by->range);
  if (v) st.forVars.push_back({v, s});
  ++st.loopDepth;
  checkStmts(s->body, ctx, st);
  --st.loopDepth;
  if (v) st.forVars.pop_back();
}

// IEC 61131-3 forbids recursion: any cycle in the call graph is an error.
void SemaImpl::checkRecursion() {
  // Methods and actions run on behalf of their owner; map them to their owner
  // only for FB body cycles through instance calls.
  std::map<Symbol*, int> state;   // 0 new, 1 on stack, 2 done
  std::vector<std::pair<Symbol*, SourceRange>> stack;
  std::set<Symbol*> reported;
  // A property read is a call of its GET accessor.
  std::map<const PouDecl*, Symbol*> byDecl;
  for (Symbol* p : pous_)
    if (p->pou && p->pou->decl) byDecl[p->pou->decl] = p;
  auto target = [&](Symbol* callee) {
    if (callee->kind == Symbol::Property && callee->pou && callee->pou->decl && callee->pou->decl->getter)
      if (auto it = byDecl.find(callee->pou->decl->getter); it != byDecl.end()) return it->second;
    return callee;
  };
  std::function<void(Symbol*)> dfs = [&](Symbol* s) {
    state[s] = 1;
    auto it = callGraph_.find(s);
    if (it != callGraph_.end()) {
      for (auto [callee0, where] : it->second) {
        Symbol* callee = target(callee0);
        if (state[callee] == 1) {
          if (reported.insert(callee).second) {
            auto d = diags_.error(where.begin, callee == s ? "'" + callee->name + "' calls itself; recursion is not allowed in IEC 61131-3"
                                                           : "recursive call cycle through '" + callee->name + "'; recursion is not allowed in IEC 61131-3",
                                  "recursion");
            d.range(where);
            // Notes walk the cycle only: from where `callee` was entered.
            size_t k = stack.size();
            for (size_t i = 0; i < stack.size(); ++i)
              if (stack[i].first == callee) { k = i; break; }
            for (size_t i = k; i < stack.size(); ++i)
              d.note(stack[i].second.begin, "called from '" + stack[i].first->name + "' here", stack[i].second);
          }
          continue;
        }
        if (state[callee] == 0) {
          stack.push_back({s, where});
          dfs(callee);
          stack.pop_back();
        }
      }
    }
    state[s] = 2;
  };
  for (Symbol* p : pous_)
    if (state[p] == 0) dfs(p);
}

void SemaImpl::checkUnused() {
  for (Symbol* p : pous_) {
    if (!p->pou || p->kind == Symbol::Program) continue;
    PouDecl* d = p->pou->decl;
    // A native POU's locals are the C++ implementation's state: ST never uses them.
    if (std::any_of(d->attributes.begin(), d->attributes.end(), [](const Pragma& pr) { return upperCase(pr.name) == "NATIVE"; }))
      continue;
    for (VarBlock& b : d->varBlocks) {
      if (b.section != VarSection::Var && b.section != VarSection::Temp) continue;
      for (VarDecl* v : b.vars) {
        if (v->used) continue;
        bool attr = std::any_of(v->attributes.begin(), v->attributes.end(), [](const Pragma& pr) {
          std::string n = upperCase(pr.name);
          return n == "HIDE" || n == "NO_UNUSED_WARNING" || n == "INSTANCE-PATH" || n == "NOINIT";
        });
        if (attr) continue;
        // FB locals may be used by methods and actions of the same FB: those
        // mark `used` too, since they resolve names through the owner.
        diags_.warning(v->name.range.begin, "unused variable '" + v->name.name + "'", "unused-variable").range(v->name.range);
      }
    }
  }
}

}  // namespace stc::sema

namespace stc::sema {

// CONFIGURATION / RESOURCE / TASK / PROGRAM ... WITH: the names and values
// the scheduler will rely on.
void SemaImpl::checkConfiguration(ConfigurationDecl* c, const Context& ctx) {
  // VAR_CONFIG: Resource.Instance.var (or Instance.var) AT a full address,
  // for a variable declared with an incomplete address (AT %I* / %Q*).
  for (auto& cv : c->configVars) {
    const auto& parts = cv.path.parts;
    size_t i = 0;
    const ResourceDecl* res = nullptr;
    for (const ResourceDecl& r : c->resources)
      if (!parts.empty() && upperCase(r.name.name) == upperCase(parts[0].name)) res = &r;
    if (res) ++i;
    if (parts.size() < i + 2) {
      diags_.error(cv.path.range.begin, "VAR_CONFIG needs a path Resource.Instance.variable", "var-config").range(cv.path.range);
      continue;
    }
    const ProgramConfig* inst = nullptr;
    for (const ResourceDecl& r : c->resources) {
      if (res && &r != res) continue;
      for (const ProgramConfig& p : r.programs)
        if (upperCase(p.name.name) == upperCase(parts[i].name)) inst = &p;
    }
    if (!inst) {
      diags_.error(parts[i].range.begin, "unknown program instance '" + parts[i].name + "' in VAR_CONFIG", "var-config").range(parts[i].range);
      continue;
    }
    Symbol* prog = lookupQualified(inst->type, ctx.outer, false, "program");
    if (!prog || prog->kind != Symbol::Program) continue;
    resolveSignature(prog);
    const Ident& vn = parts[i + 1];
    Symbol* var = prog->pou->vars->lookupLocal(upperCase(vn.name));
    if (!var || !var->var) {
      diags_.error(vn.range.begin, "program '" + prog->name + "' has no variable '" + vn.name + "'", "var-config").range(vn.range);
      continue;
    }
    if (var->var->address.find('*') == std::string::npos) {
      diags_.error(vn.range.begin, "'" + vn.name + "' is not declared with an incomplete address (AT %I* or %Q*); VAR_CONFIG can only locate such variables",
                   "var-config").range(vn.range).note(var->declRange.begin, "declared here", var->declRange);
      continue;
    }
    const Type* t = resolveType(cv.type, ctx);
    if (!t->isError() && var->type && !var->type->isError() && t != var->type)
      diags_.error(cv.type->range.begin, "VAR_CONFIG type '" + t->name + "' does not match '" + vn.name + "' of type '" + var->type->name + "'",
                   "var-config").range(cv.type->range).note(var->declRange.begin, "declared here", var->declRange);
    if (cv.address.find('*') != std::string::npos)
      diags_.error(cv.range.begin, "VAR_CONFIG must give a complete address, not '" + cv.address + "'", "var-config").range(cv.range);
  }
  for (ResourceDecl& r : c->resources) {
    std::map<std::string, const TaskDecl*> tasks;
    for (const TaskDecl& t : r.tasks) {
      auto [it, inserted] = tasks.emplace(upperCase(t.name.name), &t);
      if (!inserted)
        diags_.error(t.name.range.begin, "redefinition of task '" + t.name.name + "'", "redefinition")
            .range(t.name.range).note(it->second->name.range.begin, "previous definition is here", it->second->name.range);
      for (const TaskDecl::Init& init : t.inits) {
        std::string n = upperCase(init.name.name);
        const Type* want = nullptr;
        if (n == "INTERVAL") want = types_.elementary(TypeKind::Time);
        else if (n == "PRIORITY") want = types_.elementary(TypeKind::UDInt);
        else if (n == "SINGLE") want = types_.elementary(TypeKind::Bool);
        else {
          std::string hint = closestMatch(init.name.name, {"INTERVAL", "PRIORITY", "SINGLE"});
          auto d = diags_.error(init.name.range.begin, "unknown task property '" + init.name.name + "'; expected INTERVAL, PRIORITY or SINGLE", "task");
          d.range(init.name.range);
          if (!hint.empty()) d.fixit(init.name.range, hint);
          continue;
        }
        checkExpr(init.value, ctx, want);
        bool constPriority = n == "PRIORITY" && evalConst(init.value, ctx).has_value();
        if (!constPriority) checkConversion(want, init.value, "task property");
        if (n == "PRIORITY")
          if (auto v = evalConst(init.value, ctx); v && (v->i < 0 || v->i > 31))
            diags_.error(init.value->range.begin, "task priority " + std::to_string(v->i) + " is outside 0..31", "task").range(init.value->range);
        if (n == "INTERVAL")
          if (auto v = evalConst(init.value, ctx); v && v->i <= 0)
            diags_.error(init.value->range.begin, "task interval must be positive", "task").range(init.value->range);
      }
    }
    std::map<std::string, SourceRange> instances;
    for (ProgramConfig& p : r.programs) {
      auto [it, inserted] = instances.emplace(upperCase(p.name.name), p.name.range);
      if (!inserted)
        diags_.error(p.name.range.begin, "redefinition of program instance '" + p.name.name + "'", "redefinition")
            .range(p.name.range).note(it->second.begin, "previous definition is here", it->second);
      if (!p.task.empty() && !tasks.count(upperCase(p.task.name))) {
        std::vector<std::string> names;
        for (auto& [k, t] : tasks) names.push_back(t->name.name);
        std::string hint = closestMatch(p.task.name, names);
        auto d = diags_.error(p.task.range.begin, "unknown task '" + p.task.name + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"),
                              "undeclared-name");
        d.range(p.task.range);
        if (!hint.empty()) d.fixit(p.task.range, hint);
      }
      // A program instance shares the global name space: a global variable of the same name
      // would be two objects under one name.
      for (auto& [g, gctx] : globalDecls_)
        for (const VarDecl* v : g->block.vars)
          if (upperCase(v->name.name) == upperCase(p.name.name))
            diags_.error(p.name.range.begin, "program instance '" + p.name.name + "' has the name of a global variable", "redefinition")
                .range(p.name.range).note(v->name.range.begin, "the global variable is declared here", v->name.range);
      Symbol* prog = lookupQualified(p.type, ctx.outer, true, "program");
      if (!prog) continue;
      if (prog->kind != Symbol::Program) {
        diags_.error(p.type.range.begin, "'" + p.type.str() + "' is not a PROGRAM", "task").range(p.type.range);
        continue;
      }
      if (!p.args.empty()) {
        CallExpr call;
        call.args = p.args;
        call.range = p.range;
        call.parenRange = p.range;
        resolveSignature(prog);
        checkArguments(&call, prog->pou->params, ctx, prog->name, false);
        p.args = call.args;   // keep the parameter bindings for code generation
      }
    }
  }
}

}  // namespace stc::sema

namespace stc::sema {

// A structure or function block that contains itself by value (directly,
// through arrays, or through other types) would have infinite size.
void SemaImpl::checkContainmentCycles() {
  std::map<const Type*, int> state;   // 0 new, 1 in progress, 2 done
  std::set<const Type*> reported;
  std::vector<std::pair<const Type*, VarDecl*>> path;   // type being visited, member being followed
  std::function<void(const Type*, VarDecl*)> visit = [&](const Type* t, VarDecl* via) {
    while (t && t->kind == TypeKind::Array) t = t->element;
    if (!t || !(t->kind == TypeKind::Struct || t->kind == TypeKind::Union || t->kind == TypeKind::FunctionBlock)) return;
    int& st = state[t];
    if (st == 2) return;
    if (st == 1) {
      // Report at the member of `t` that starts the cycle.
      VarDecl* at = via;
      for (auto& [pt, pm] : path)
        if (pt == t) { at = pm; break; }
      if (at && reported.insert(t).second)
        diags_.error(at->name.range.begin, "'" + t->name + "' cannot contain itself: this member makes its size infinite (use a POINTER TO or "
                                               "REFERENCE TO)", "type-cycle").range(at->type ? at->type->range : at->name.range);
      return;
    }
    st = 1;
    if (t->kind == TypeKind::FunctionBlock) {
      for (Symbol* p = t->pou; p && p->pou; p = p->pou->base)
        for (VarBlock& b : p->pou->decl->varBlocks)
          for (VarDecl* v : b.vars)
            if (v->section != VarSection::InOut && v->section != VarSection::Temp && v->section != VarSection::External) {
              path.push_back({t, v});
              visit(v->resolvedType, v);
              path.pop_back();
            }
    } else {
      for (const Type* s = t; s; s = s->base)
        for (const Member& m : s->members) {
          path.push_back({t, m.decl});
          visit(m.type, m.decl);
          path.pop_back();
        }
    }
    state[t] = 2;
  };
  for (Symbol* t : typeSymbols_) visit(t->type, nullptr);
  for (Symbol* p : pous_)
    if (p->kind == Symbol::FunctionBlock) visit(p->type, nullptr);
}

}  // namespace stc::sema
