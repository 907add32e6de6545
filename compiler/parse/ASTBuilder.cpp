// Parse tree -> AST.  Every accessor of the generated parser may return null
// after error recovery, so each step checks; a missing piece yields a null
// node and the syntax error already reported explains it.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <typeinfo>

#include "basic/Text.h"
#include "parse/ParseInternal.h"

namespace stc::parse {

using namespace stc::ast;
using P = STParser;

namespace {

// The labelled-alternative contexts are leaf classes, so an exact type test
// is equivalent to dynamic_cast and much cheaper.  The generated parser and
// the ANTLR runtime are linked statically into the same binary, so each class
// has one type_info object and comparing addresses is exact (operator== would
// fall back to strcmp for every mismatch).
template <typename T> bool sameType(const std::type_info& ti) { return &ti == &typeid(T); }
template <typename T, typename B> T* as(B* node) {
  return node && sameType<T>(typeid(*node)) ? static_cast<T*>(node) : nullptr;
}

// Positional child access for the hot paths.  The generated accessors scan
// all children with dynamic_cast; here a child is tested with typeid
// (terminals) or its rule index (rule contexts derive non-virtually from
// ParseTree, so the static_cast is valid).
bool isTerminal(antlr4::tree::ParseTree* p) {
  const std::type_info& ti = typeid(*p);
  return sameType<antlr4::tree::TerminalNodeImpl>(ti) || sameType<antlr4::tree::ErrorNodeImpl>(ti);
}

antlr4::Token* tokenAt(antlr4::ParserRuleContext* c, size_t i) {
  if (i >= c->children.size()) return nullptr;
  antlr4::tree::ParseTree* p = c->children[i];
  if (!sameType<antlr4::tree::TerminalNodeImpl>(typeid(*p))) return nullptr;
  return static_cast<antlr4::tree::TerminalNode*>(p)->getSymbol();
}

template <typename T> T* ruleAt(antlr4::ParserRuleContext* c, size_t i, size_t ruleIndex) {
  if (i >= c->children.size()) return nullptr;
  antlr4::tree::ParseTree* p = c->children[i];
  if (isTerminal(p)) return nullptr;
  auto* r = static_cast<antlr4::ParserRuleContext*>(p);
  return r->getRuleIndex() == ruleIndex ? static_cast<T*>(r) : nullptr;
}

template <typename T, typename F> void forEachRule(antlr4::ParserRuleContext* c, size_t ruleIndex, F&& f) {
  for (antlr4::tree::ParseTree* p : c->children) {
    if (isTerminal(p)) continue;
    auto* r = static_cast<antlr4::ParserRuleContext*>(p);
    if (r->getRuleIndex() == ruleIndex) f(static_cast<T*>(r));
  }
}


int64_t daysFromCivil(int64_t y, unsigned m, unsigned d) {
  // Howard Hinnant's days-from-civil algorithm (public domain formula).
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

bool isLeap(int64_t y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

class Builder {
public:
  Builder(const SourceFile& f, const LexedFile& lx, DiagnosticsEngine& d, ASTContext& c)
      : file_(f), lexed_(lx), diags_(d), ctx_(c) {}

  void unit(P::CompilationUnitContext* cu, SourceUnit& out) {
    PouDecl* lastPou = nullptr;
    for (auto* le : cu->libraryElement()) libraryElement(le, out.decls, lastPou);
  }

private:
  // ------------------------------------------------------------ helpers
  // Tokens conjured by error recovery ("missing ';'") have no position.
  bool conjured(antlr4::Token* t) const {
    return !t || t->getStartIndex() == kNoTokenIndex || t->getStartIndex() > t->getStopIndex() ||
           t->getStopIndex() >= file_.text.size();
  }
  std::string_view text(antlr4::Token* t) const {
    if (conjured(t)) return {};
    return std::string_view(file_.text).substr(t->getStartIndex(), t->getStopIndex() + 1 - t->getStartIndex());
  }
  std::string_view text(antlr4::tree::TerminalNode* n) const { return text(n->getSymbol()); }
  SourceLoc loc(antlr4::Token* t) const {
    return conjured(t) ? SourceLoc{file_.id, static_cast<uint32_t>(file_.text.size())} : locOf(file_.id, t);
  }
  SourceRange range(antlr4::Token* t) const { return conjured(t) ? SourceRange(loc(t)) : rangeOf(file_.id, t); }
  SourceRange range(antlr4::tree::TerminalNode* n) const { return range(n->getSymbol()); }
  SourceRange range(antlr4::ParserRuleContext* c) const {
    antlr4::Token* a = c->getStart();
    antlr4::Token* b = c->getStop();
    if (!a || conjured(a)) return a ? SourceRange(loc(a)) : SourceRange();
    if (!b || conjured(b) || b->getStopIndex() + 1 < a->getStartIndex() || b->getType() == antlr4::Token::EOF)
      return SourceRange(loc(a));
    return {loc(a), {file_.id, static_cast<uint32_t>(b->getStopIndex() + 1)}};
  }
  Ident ident(antlr4::tree::TerminalNode* n) const {
    if (!n || conjured(n->getSymbol())) return {};
    return {std::string(text(n)), range(n)};
  }
  Ident ident(antlr4::Token* t) const {
    if (conjured(t) || t->getType() == antlr4::Token::EOF) return {};
    return {std::string(text(t)), range(t)};
  }
  QualifiedName qname(P::QualifiedNameContext* c) const {
    QualifiedName q;
    if (!c) return q;
    for (size_t k = 0; k < c->children.size(); k += 2) {   // IDENTIFIER ( '.' IDENTIFIER )*
      antlr4::Token* t = tokenAt(c, k);
      if (!t || t->getType() != STLexer::IDENTIFIER) continue;
      Ident i = ident(t);
      if (!i.empty()) q.parts.push_back(std::move(i));
    }
    q.range = range(c);
    return q;
  }
  std::vector<Pragma> attributesFor(antlr4::ParserRuleContext* c) const {
    if (!c || !c->getStart()) return {};
    auto it = lexed_.attributesAt.find(static_cast<uint32_t>(c->getStart()->getStartIndex()));
    return it == lexed_.attributesAt.end() ? std::vector<Pragma>{} : it->second;
  }

  // ------------------------------------------------------------ library elements
  void libraryElement(P::LibraryElementContext* le, std::vector<Decl*>& out, PouDecl*& lastPou) {
    if (auto* t = le->dataTypeDecl()) {
      // Attributes written before TYPE belong to the first type of the block.
      std::vector<Pragma> before = attributesFor(t);
      for (auto* item : t->typeDeclItem())
        if (TypeDecl* d = typeDecl(item)) {
          if (!before.empty()) d->attributes.insert(d->attributes.begin(), before.begin(), before.end());
          before.clear();
          out.push_back(d);
        }
    } else if (auto* p = le->pouDecl()) {
      if (PouDecl* d = pou(p)) { out.push_back(d); lastPou = d; }
    } else if (auto* i = le->interfaceDecl()) {
      if (PouDecl* d = interfaceDecl(i)) out.push_back(d);
    } else if (auto* g = le->globalVarBlock()) {
      auto* d = ctx_.make<GlobalVarDecl>();
      d->range = range(g);
      d->block = globalBlock(g);
      d->attributes = attributesFor(g);
      out.push_back(d);
    } else if (auto* c = le->configurationDecl()) {
      if (Decl* d = configuration(c)) out.push_back(d);
    } else if (auto* n = le->namespaceDecl()) {
      auto* d = ctx_.make<NamespaceDecl>();
      d->range = range(n);
      d->name = qname(n->qualifiedName());
      PouDecl* inner = nullptr;
      for (auto* e : n->libraryElement()) libraryElement(e, d->decls, inner);
      out.push_back(d);
    } else if (auto* a = le->actionDecl()) {
      // A top-level ACTION belongs to the POU before it (CODESYS 2.3 export),
      // unless it is qualified (ACTION FB.Name).
      PouDecl* act = action(a);
      if (!act) return;
      if (act->name.parts.size() == 1 && lastPou) {
        act->owner = lastPou;
        lastPou->actions.push_back(act);
      } else {
        out.push_back(act);
      }
    } else if (auto* m = le->methodDecl()) {
      if (PouDecl* d = method(m)) out.push_back(d);
    } else if (auto* pr = le->propertyDecl()) {
      if (PouDecl* d = property(pr)) out.push_back(d);
    }
  }

  TypeDecl* typeDecl(P::TypeDeclItemContext* c) {
    auto* d = ctx_.make<TypeDecl>();
    d->range = range(c);
    d->attributes = attributesFor(c);
    d->name = ident(c->IDENTIFIER());
    if (d->name.empty()) return nullptr;
    auto* def = c->typeDefinition();
    if (!def) return nullptr;
    if (auto* s = as<P::StructDefContext>(def)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Struct);
      t->range = range(s);
      if (s->qualifiedName()) t->structBase = qname(s->qualifiedName());
      for (auto* m : s->memberDecl()) varDecl(m->varDecl(), VarSection::Var, t->members, nullptr);
      d->def = t;
    } else if (auto* u = as<P::UnionDefContext>(def)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Union);
      t->range = range(u);
      for (auto* m : u->memberDecl()) varDecl(m->varDecl(), VarSection::Var, t->members, nullptr);
      d->def = t;
    } else if (auto* e = as<P::TypedEnumDefContext>(def)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Enum);
      t->range = range(e);
      if (e->typeName()) t->name = qname(e->typeName()->qualifiedName());
      EnumValueDecl first;
      first.name = ident(e->IDENTIFIER());
      first.value = expr(e->expression());
      t->enumValues.push_back(first);
      for (auto* v : e->enumValue()) t->enumValues.push_back(enumValue(v));
      d->def = t;
    } else if (auto* a = as<P::AliasDefContext>(def)) {
      d->def = typeSpec(a->typeSpec());
    }
    // STRUCT EXTENDS written before the colon (CODESYS: TYPE S EXTENDS B : STRUCT).
    if (c->qualifiedName() && d->def && d->def->kind == TypeRef::Struct) d->def->structBase = qname(c->qualifiedName());
    if (c->initializerList()) d->init = initializerList(c->initializerList());
    return d->def ? d : nullptr;
  }

  EnumValueDecl enumValue(P::EnumValueContext* v) {
    EnumValueDecl e;
    e.name = ident(v->IDENTIFIER());
    if (v->expression()) e.value = expr(v->expression());
    return e;
  }

  TypeRef* typeSpec(P::TypeSpecContext* c) {
    if (!c) return nullptr;
    if (auto* a = as<P::ArrayTypeContext>(c)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Array);
      t->range = range(a);
      for (auto* r : a->arrayRange()) {
        TypeRef::Dim dim;
        dim.range = range(r);
        if (r->STAR()) dim.star = true;
        else { dim.lo = expr(r->lo); dim.hi = expr(r->hi); }
        t->dims.push_back(dim);
      }
      t->element = typeSpec(a->typeSpec());
      return t->element ? t : nullptr;
    }
    if (auto* p = as<P::PointerTypeContext>(c)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Pointer);
      t->range = range(p);
      t->element = typeSpec(p->typeSpec());
      return t->element ? t : nullptr;
    }
    if (auto* r = as<P::ReferenceTypeContext>(c)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Reference);
      t->range = range(r);
      t->refTo = r->REF_TO() != nullptr;
      t->element = typeSpec(r->typeSpec());
      return t->element ? t : nullptr;
    }
    if (auto* s = as<P::SubrangeTypeContext>(c)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Subrange);
      t->range = range(s);
      t->name = qname(s->qualifiedName());
      t->lo = expr(s->lo);
      t->hi = expr(s->hi);
      return t;
    }
    if (auto* f = as<P::FbInitTypeContext>(c)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Named);
      t->range = range(f);
      t->name = qname(f->qualifiedName());
      auto* args = ctx_.make<StructInitExpr>();
      args->range = range(f);
      for (auto* el : f->structInitElement()) {
        StructInitExpr::Field fld;
        fld.name = ident(el->IDENTIFIER());
        fld.value = initializer(el->initializer());
        if (!fld.name.empty() && fld.value) args->fields.push_back(fld);
      }
      t->fbInitArgs = args;
      return t->name.parts.empty() ? nullptr : t;
    }
    if (auto* s = as<P::SizedTypeContext>(c)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Sized);
      t->range = range(s);
      t->name = qname(s->qualifiedName());
      t->size = expr(s->expression());
      return t;
    }
    if (auto* e = as<P::InlineEnumTypeContext>(c)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Enum);
      t->range = range(e);
      for (auto* v : e->enumValue()) t->enumValues.push_back(enumValue(v));
      if (e->typeName()) t->name = qname(e->typeName()->qualifiedName());
      return t;
    }
    if (auto* n = as<P::NamedTypeContext>(c)) {
      TypeRef* t = ctx_.make<TypeRef>(TypeRef::Named);
      t->range = range(n);
      t->name = qname(n->qualifiedName());
      return t->name.parts.empty() ? nullptr : t;
    }
    return nullptr;
  }

  // ------------------------------------------------------------ POUs
  void modifiers(const std::vector<P::PouModifierContext*>& mods, PouDecl* d) {
    for (auto* m : mods) {
      if (m->ABSTRACT()) d->isAbstract = true;
      else if (m->FINAL()) d->isFinal = true;
      else if (m->PUBLIC()) d->access = Access::Public;
      else if (m->PRIVATE()) d->access = Access::Private;
      else if (m->PROTECTED()) d->access = Access::Protected;
      else if (m->INTERNAL()) d->access = Access::Internal;
    }
  }

  void varBlocks(const std::vector<P::VarBlockContext*>& blocks, PouDecl* d) {
    for (auto* b : blocks) d->varBlocks.push_back(varBlock(b));
  }

  // VAR_INPUT x : BOOL R_EDGE (F_EDGE): inside the block, x is TRUE only in
  // the call where the value passed rose (fell).  Lowered to two hidden
  // instance variables and three statements in front of the body:
  //   __x_in := x;  x := __x_in AND NOT __x_prev;  __x_prev := __x_in;
  // (F_EDGE: x := NOT __x_in AND __x_prev).
  void lowerEdgeInputs(PouDecl* d) {
    // Only function blocks and programs keep state between calls (sema reports the rest).
    if (d->pouKind != PouKind::FunctionBlock && d->pouKind != PouKind::Program) return;
    std::vector<Stmt*> front;
    VarBlock hidden;
    hidden.section = VarSection::Var;
    for (VarBlock& b : d->varBlocks)
      for (VarDecl* v : b.vars) {
        if (v->edge == VarDecl::NoEdge || !v->type || v->type->kind != TypeRef::Named || v->type->name.parts.size() != 1 ||
            asciiUpper(v->type->name.parts[0].name) != "BOOL")
          continue;
        SourceRange r = v->name.range;
        auto hiddenVar = [&](const std::string& suffix) {
          auto* h = ctx_.make<VarDecl>();
          h->range = r;
          h->name = Ident{"__" + v->name.name + suffix, r};
          auto* t = ctx_.make<TypeRef>(TypeRef::Named);
          t->range = r;
          t->name.parts.push_back(Ident{"BOOL", r});
          t->name.range = r;
          h->type = t;
          h->section = VarSection::Var;
          h->used = true;
          h->attributes.push_back(Pragma{"hide", "", r});
          hidden.vars.push_back(h);
          return h->name.name;
        };
        std::string in = hiddenVar("_edge_in"), prev = hiddenVar("_edge_prev");
        auto name = [&](const std::string& n) {
          auto* e = ctx_.make<NameExpr>();
          e->range = r;
          e->ident = Ident{n, r};
          return e;
        };
        auto assign = [&](Expr* lhs, Expr* rhs) {
          auto* s = ctx_.make<AssignStmt>();
          s->range = r;
          s->opLoc = r.begin;
          s->lhs = lhs;
          s->rhs = rhs;
          front.push_back(s);
        };
        auto notOf = [&](Expr* x) {
          auto* u = ctx_.make<UnaryExpr>();
          u->range = r;
          u->op = UnaryOp::Not;
          u->operand = x;
          u->opLoc = r.begin;
          return u;
        };
        auto* both = ctx_.make<BinaryExpr>();
        both->range = r;
        both->op = BinaryOp::And;
        both->opLoc = r.begin;
        bool rising = v->edge == VarDecl::RisingEdge;
        both->lhs = rising ? static_cast<Expr*>(name(in)) : notOf(name(in));
        both->rhs = rising ? static_cast<Expr*>(notOf(name(prev))) : name(prev);
        assign(name(in), name(v->name.name));
        assign(name(v->name.name), both);
        assign(name(prev), name(in));
      }
    if (front.empty()) return;
    d->varBlocks.push_back(std::move(hidden));
    d->body.insert(d->body.begin(), front.begin(), front.end());
  }

  PouDecl* pou(P::PouDeclContext* c) {
    if (!c->kind) return nullptr;
    auto* d = ctx_.make<PouDecl>();
    d->range = range(c);
    d->attributes = attributesFor(c);
    switch (c->kind->getType()) {
      case STLexer::PROGRAM: d->pouKind = PouKind::Program; break;
      case STLexer::FUNCTION: d->pouKind = PouKind::Function; break;
      default: d->pouKind = PouKind::FunctionBlock; break;
    }
    auto names = c->qualifiedName();
    if (names.empty()) return nullptr;
    d->name = qname(names[0]);
    if (d->name.parts.empty()) return nullptr;
    modifiers(c->pouModifier(), d);
    d->returnType = typeSpec(c->returnType);
    if (c->baseName) d->extends = qname(c->baseName);
    for (size_t i = 1; i < names.size(); ++i)
      if (names[i] != c->baseName) d->implements.push_back(qname(names[i]));
    varBlocks(c->varBlock(), d);
    for (auto* m : c->pouMember()) member(m, d);
    if (c->body()) d->body = body(c->body());
    lowerEdgeInputs(d);
    if (c->endKw) d->endRange = range(c->endKw);
    // END_xxx must match the opening keyword.
    if (c->endKw && conjured(c->endKw)) {
      std::string expected = c->kind->getType() == STLexer::PROGRAM ? "END_PROGRAM" : c->kind->getType() == STLexer::FUNCTION ? "END_FUNCTION" : "END_FUNCTION_BLOCK";
      diags_.error(loc(c->endKw), "missing '" + expected + "' at end of file", "syntax")
          .note(d->name.range.begin, std::string(spelling(d->pouKind)) + " '" + d->name.str() + "' starts here");
    } else if (c->endKw) {
      size_t want = c->kind->getType() == STLexer::PROGRAM ? STLexer::END_PROGRAM
                    : c->kind->getType() == STLexer::FUNCTION ? STLexer::END_FUNCTION : STLexer::END_FUNCTION_BLOCK;
      if (c->endKw->getType() != want) {
        std::string expected = want == STLexer::END_PROGRAM ? "END_PROGRAM" : want == STLexer::END_FUNCTION ? "END_FUNCTION" : "END_FUNCTION_BLOCK";
        diags_.error(loc(c->endKw), "'" + std::string(text(c->endKw)) + "' does not close " + spelling(d->pouKind) + " '" +
                                        d->name.str() + "'; expected '" + expected + "'", "syntax")
            .range(range(c->endKw)).fixit(range(c->endKw), expected)
            .note(d->name.range.begin, std::string(spelling(d->pouKind)) + " '" + d->name.str() + "' starts here");
      }
    }
    return d;
  }

  void member(P::PouMemberContext* m, PouDecl* owner) {
    if (auto* md = m->methodDecl()) {
      if (PouDecl* x = method(md)) { x->owner = owner; owner->methods.push_back(x); }
    } else if (auto* pd = m->propertyDecl()) {
      if (PouDecl* x = property(pd)) { x->owner = owner; owner->properties.push_back(x); }
    } else if (auto* ad = m->actionDecl()) {
      if (PouDecl* x = action(ad)) { x->owner = owner; owner->actions.push_back(x); }
    }
  }

  PouDecl* method(P::MethodDeclContext* c) {
    auto* d = ctx_.make<PouDecl>();
    d->pouKind = PouKind::Method;
    d->range = range(c);
    d->attributes = attributesFor(c);
    d->name = qname(c->qualifiedName());
    if (d->name.parts.empty()) return nullptr;
    modifiers(c->pouModifier(), d);
    d->returnType = typeSpec(c->typeSpec());
    varBlocks(c->varBlock(), d);
    if (c->body()) d->body = body(c->body());
    if (c->END_METHOD()) d->endRange = range(c->END_METHOD());
    return d;
  }

  PouDecl* property(P::PropertyDeclContext* c) {
    auto* d = ctx_.make<PouDecl>();
    d->pouKind = PouKind::Property;
    d->range = range(c);
    d->attributes = attributesFor(c);
    d->name = qname(c->qualifiedName());
    if (d->name.parts.empty()) return nullptr;
    modifiers(c->pouModifier(), d);
    d->returnType = typeSpec(c->typeSpec());
    varBlocks(c->varBlock(), d);
    d->hasBody = false;
    for (auto* a : c->propertyAccessor()) {
      Ident which = ident(a->accessor);
      std::string w = asciiUpper(which.name);
      auto* acc = ctx_.make<PouDecl>();
      acc->range = range(a);
      acc->name.parts.push_back(which);
      acc->name.range = which.range;
      acc->owner = d;
      modifiers(a->pouModifier(), acc);
      varBlocks(a->varBlock(), acc);
      if (a->body()) acc->body = body(a->body());
      bool endGet = a->endKw && a->endKw->getType() == STLexer::END_GET;
      if (w == "GET") {
        acc->pouKind = PouKind::PropertyGet;
        if (d->getter) diags_.error(which.range.begin, "property '" + d->name.str() + "' has more than one GET accessor", "syntax").range(which.range);
        d->getter = acc;
        if (a->endKw && !endGet) diags_.error(loc(a->endKw), "expected 'END_GET' to close the GET accessor", "syntax").range(range(a->endKw)).fixit(range(a->endKw), "END_GET");
      } else if (w == "SET") {
        acc->pouKind = PouKind::PropertySet;
        if (d->setter) diags_.error(which.range.begin, "property '" + d->name.str() + "' has more than one SET accessor", "syntax").range(which.range);
        d->setter = acc;
        if (a->endKw && endGet) diags_.error(loc(a->endKw), "expected 'END_SET' to close the SET accessor", "syntax").range(range(a->endKw)).fixit(range(a->endKw), "END_SET");
      } else {
        std::string hint = closestMatch(which.name, {"GET", "SET"});
        auto diag = diags_.error(which.range.begin, "expected 'GET' or 'SET' in property '" + d->name.str() + "'", "syntax");
        diag.range(which.range);
        if (!hint.empty()) diag.fixit(which.range, hint);
      }
    }
    return d;
  }

  PouDecl* action(P::ActionDeclContext* c) {
    auto* d = ctx_.make<PouDecl>();
    d->pouKind = PouKind::Action;
    d->range = range(c);
    d->attributes = attributesFor(c);
    d->name = qname(c->qualifiedName());
    if (d->name.parts.empty()) return nullptr;
    if (c->body()) d->body = body(c->body());
    return d;
  }

  PouDecl* interfaceDecl(P::InterfaceDeclContext* c) {
    auto* d = ctx_.make<PouDecl>();
    d->pouKind = PouKind::Interface;
    d->range = range(c);
    d->attributes = attributesFor(c);
    auto names = c->qualifiedName();
    if (names.empty()) return nullptr;
    d->name = qname(names[0]);
    if (d->name.parts.empty()) return nullptr;
    for (size_t i = 1; i < names.size(); ++i) d->implements.push_back(qname(names[i]));
    d->hasBody = false;
    for (auto* m : c->methodDecl())
      if (PouDecl* x = method(m)) { x->owner = d; x->hasBody = !x->body.empty(); d->methods.push_back(x); }
    for (auto* p : c->propertyDecl())
      if (PouDecl* x = property(p)) { x->owner = d; d->properties.push_back(x); }
    return d;
  }

  // ------------------------------------------------------------ variables
  static VarSection sectionOf(size_t tokenType) {
    switch (tokenType) {
      case STLexer::VAR_INPUT: return VarSection::Input;
      case STLexer::VAR_OUTPUT: return VarSection::Output;
      case STLexer::VAR_IN_OUT: return VarSection::InOut;
      case STLexer::VAR_TEMP: return VarSection::Temp;
      case STLexer::VAR_STAT: return VarSection::Stat;
      case STLexer::VAR_INST: return VarSection::Inst;
      case STLexer::VAR_EXTERNAL: return VarSection::External;
      case STLexer::VAR_ACCESS: return VarSection::Access;
      case STLexer::VAR_GLOBAL: return VarSection::Global;
      default: return VarSection::Var;
    }
  }

  void qualifiers(const std::vector<P::VarQualifierContext*>& qs, VarBlock& b) {
    for (auto* q : qs) {
      if (q->CONSTANT()) b.isConstant = true;
      else if (q->RETAIN()) b.isRetain = true;
      else if (q->PERSISTENT()) b.isPersistent = true;
      else if (q->NON_RETAIN()) b.isNonRetain = true;
    }
  }

  VarBlock varBlock(P::VarBlockContext* c) {
    VarBlock b;
    b.range = range(c);
    b.section = c->kind ? sectionOf(c->kind->getType()) : VarSection::Var;
    qualifiers(c->varQualifier(), b);
    for (auto* v : c->varDecl()) varDecl(v, b.section, b.vars, &b);
    return b;
  }

  VarBlock globalBlock(P::GlobalVarBlockContext* c) {
    VarBlock b;
    b.range = range(c);
    b.section = VarSection::Global;
    qualifiers(c->varQualifier(), b);
    for (auto* v : c->varDecl()) varDecl(v, b.section, b.vars, &b);
    return b;
  }

  void varDecl(P::VarDeclContext* c, VarSection section, std::vector<VarDecl*>& out, const VarBlock* block) {
    if (!c) return;
    // One pass over the children: names ( ',' name )* ( AT address )? ':' type ( ':=' init? )? ';'
    std::vector<antlr4::Token*> names;
    antlr4::Token* address = nullptr;
    P::TypeSpecContext* typeCtx = nullptr;
    P::InitializerListContext* initCtx = nullptr;
    antlr4::Token* edge = nullptr;
    bool assign = false, afterColon = false;
    for (antlr4::tree::ParseTree* ch : c->children) {
      if (isTerminal(ch)) {
        antlr4::Token* t = sameType<antlr4::tree::TerminalNodeImpl>(typeid(*ch)) ? static_cast<antlr4::tree::TerminalNode*>(ch)->getSymbol() : nullptr;
        if (!t) continue;
        if (t->getType() == STLexer::IDENTIFIER && !afterColon) names.push_back(t);
        else if (t->getType() == STLexer::R_EDGE || t->getType() == STLexer::F_EDGE) edge = t;
        else if (t->getType() == STLexer::DIRECT_ADDRESS) address = t;
        else if (t->getType() == STLexer::COLON) afterColon = true;
        else if (t->getType() == STLexer::ASSIGN) assign = true;
        continue;
      }
      auto* r = static_cast<antlr4::ParserRuleContext*>(ch);
      if (r->getRuleIndex() == P::RuleTypeSpec) typeCtx = static_cast<P::TypeSpecContext*>(r);
      else if (r->getRuleIndex() == P::RuleInitializerList) initCtx = static_cast<P::InitializerListContext*>(r);
    }
    TypeRef* type = typeSpec(typeCtx);
    if (!type) return;
    Expr* init = initCtx ? initializerList(initCtx) : nullptr;
    bool refBind = false;
    if (c->refInit) {
      init = expr(c->refInit);
      refBind = true;
    }
    VarDecl::Edge edgeKind = VarDecl::NoEdge;
    if (edge) {
      edgeKind = edge->getType() == STLexer::R_EDGE ? VarDecl::RisingEdge : VarDecl::FallingEdge;
      if (edgeKind != VarDecl::NoEdge && section != VarSection::Input)
        diags_.error(loc(edge), std::string(text(edge)) + " is only allowed on VAR_INPUT variables", "invalid-section").range(range(edge));
    }
    std::vector<Pragma> attrs = attributesFor(c);
    for (antlr4::Token* id : names) {
      Ident name = ident(id);
      if (name.empty()) continue;
      auto* v = ctx_.make<VarDecl>();
      v->range = range(c);
      v->name = name;
      v->type = type;
      v->init = init;
      v->hasEmptyInit = assign && !initCtx;
      v->bindsReference = refBind;
      v->edge = edgeKind;
      v->section = section;
      v->attributes = attrs;
      if (address) {
        v->address = std::string(text(address));
        v->addressRange = range(address);
      }
      if (block) {
        v->isConstant = block->isConstant;
        v->isRetain = block->isRetain;
        v->isPersistent = block->isPersistent;
        v->isNonRetain = block->isNonRetain;
      }
      out.push_back(v);
    }
  }

  // The elements of `[ ... ]`, or of a CODESYS 2.3 list without brackets.
  ArrayInitExpr* arrayElements(const std::vector<P::ArrayInitElementContext*>& els, SourceRange r) {
    auto* e = ctx_.make<ArrayInitExpr>();
    e->range = r;
    for (auto* el : els) {
      ArrayInitExpr::Element elem;
      elem.range = range(el);
      if (auto* rep = as<P::RepeatedElementContext>(el)) {
        elem.repeated = true;
        elem.repeat = integerValue(rep->INTEGER_LITERAL());
        elem.value = rep->initializer() ? initializer(rep->initializer()) : nullptr;
      } else if (auto* s = as<P::SingleElementContext>(el)) {
        elem.value = initializer(s->initializer());
        if (!elem.value) continue;
      }
      e->elements.push_back(elem);
    }
    return e;
  }

  Expr* initializerList(P::InitializerListContext* c) {
    if (!c) return nullptr;
    auto els = c->arrayInitElement();
    if (els.size() == 1)
      if (auto* s = as<P::SingleElementContext>(els[0])) return initializer(s->initializer());
    return arrayElements(els, range(c));
  }

  Expr* initializer(P::InitializerContext* c) {
    if (!c) return nullptr;
    if (auto* a = as<P::ArrayInitContext>(c)) return arrayElements(a->arrayInitElement(), range(a));
    if (auto* s = as<P::StructInitContext>(c)) {
      auto* e = ctx_.make<StructInitExpr>();
      e->range = range(s);
      for (auto* f : s->structInitElement()) {
        StructInitExpr::Field fld;
        fld.name = ident(f->IDENTIFIER());
        fld.value = initializer(f->initializer());
        if (!fld.name.empty() && fld.value) e->fields.push_back(fld);
      }
      return e;
    }
    if (auto* x = as<P::ExprInitContext>(c)) return expr(x->expression());
    return nullptr;
  }

  // ------------------------------------------------------------ configuration
  Decl* configuration(P::ConfigurationDeclContext* c) {
    auto* d = ctx_.make<ConfigurationDecl>();
    d->range = range(c);
    d->name = ident(c->IDENTIFIER());
    for (auto* g : c->globalVarBlock()) d->globals.push_back(globalBlock(g));
    for (auto* r : c->resourceDecl()) {
      ResourceDecl res;
      res.range = range(r);
      auto ids = r->IDENTIFIER();   // name ( ON target )?
      if (!ids.empty()) res.name = ident(ids[0]);
      if (ids.size() > 2) {
        if (!equalsIgnoreCase(text(ids[1]), "ON"))
          diags_.error(loc(ids[1]->getSymbol()), "expected 'ON' after the resource name, found '" + std::string(text(ids[1])) + "'", "syntax")
              .range(range(ids[1]));
        res.on = ident(ids[2]);
      }
      if (r->resourceBody()) resourceBody(r->resourceBody(), res);
      d->resources.push_back(std::move(res));
    }
    if (c->resourceBody()) {
      ResourceDecl res;
      res.range = range(c->resourceBody());
      resourceBody(c->resourceBody(), res);
      if (!res.tasks.empty() || !res.programs.empty() || !res.globals.empty()) d->resources.push_back(std::move(res));
    }
    for (auto* vc : c->varConfigBlock())
      for (auto* it : vc->varConfigItem()) {
        ConfigurationDecl::ConfigVar cv;
        cv.range = range(it);
        cv.path = qname(it->qualifiedName());
        if (it->DIRECT_ADDRESS()) cv.address = std::string(text(it->DIRECT_ADDRESS()));
        cv.type = typeSpec(it->typeSpec());
        if (it->initializer()) cv.init = initializer(it->initializer());
        d->configVars.push_back(std::move(cv));
      }
    return d;
  }

  void resourceBody(P::ResourceBodyContext* c, ResourceDecl& res) {
    for (auto* g : c->globalVarBlock()) res.globals.push_back(globalBlock(g));
    for (auto* t : c->taskDecl()) {
      TaskDecl td;
      td.range = range(t);
      td.name = ident(t->IDENTIFIER());
      for (auto* i : t->taskInit()) td.inits.push_back({ident(i->IDENTIFIER()), expr(i->expression())});
      res.tasks.push_back(std::move(td));
    }
    for (auto* p : c->programConfig()) {
      ProgramConfig pc;
      pc.range = range(p);
      auto ids = p->IDENTIFIER();
      if (!ids.empty()) pc.name = ident(ids[0]);
      if (ids.size() > 1) pc.task = ident(ids[1]);
      pc.type = qname(p->qualifiedName());
      pc.retain = p->RETAIN() != nullptr;
      pc.nonRetain = p->NON_RETAIN() != nullptr;
      for (auto* a : p->callArgument()) pc.args.push_back(argument(a));
      res.programs.push_back(std::move(pc));
    }
  }

  // ------------------------------------------------------------ statements
  std::vector<Stmt*> body(P::BodyContext* c) {
    std::vector<Stmt*> out;
    if (!c) return out;
    out.reserve(c->children.size());
    // Children: IDENTIFIER ':' pairs (labels) and unlabeledStatement contexts.
    std::vector<antlr4::Token*> labels;
    auto wrap = [&](Stmt* st, antlr4::Token* endTok) -> Stmt* {
      for (auto it = labels.rbegin(); it != labels.rend(); ++it) {
        auto* l = ctx_.make<LabelStmt>();
        l->label = ident(*it);
        l->range = SourceRange(loc(*it), st ? st->range.end : range(endTok).end);
        l->stmt = st;
        st = l;
      }
      labels.clear();
      return st;
    };
    for (antlr4::tree::ParseTree* ch : c->children) {
      if (isTerminal(ch)) {
        antlr4::Token* t = sameType<antlr4::tree::TerminalNodeImpl>(typeid(*ch)) ? static_cast<antlr4::tree::TerminalNode*>(ch)->getSymbol() : nullptr;
        if (t && t->getType() == STLexer::IDENTIFIER && !conjured(t)) labels.push_back(t);
        continue;
      }
      auto* r = static_cast<antlr4::ParserRuleContext*>(ch);
      if (r->getRuleIndex() != P::RuleUnlabeledStatement) continue;
      Stmt* st = unlabeled(static_cast<P::UnlabeledStatementContext*>(r));
      if (!labels.empty()) st = wrap(st, r->getStop());
      if (st) out.push_back(st);
      out.insert(out.end(), chained_.begin(), chained_.end());
      chained_.clear();
    }
    if (!labels.empty()) {
      // A label at the end of a body labels an empty statement.
      antlr4::Token* last = labels.back();
      auto* empty = ctx_.make<SimpleStmt>(Stmt::Empty);
      empty->range = SourceRange(range(last).end);
      out.push_back(wrap(empty, last));
    }
    return out;
  }

  // `e0 := e1 := ... := v` (CODESYS ExST: an assignment is an expression with
  // the assigned value).  Lowered to `e_n-1 := v; ...; e0 := e1;`, each target
  // reading the one assigned before it, so conversions apply at every step as
  // CODESYS does; the statements after the first wait in chained_.
  Stmt* chainedAssignment(AssignStmt* first, P::ExprBasedStmtContext* a) {
    if (first->op != AssignStmt::Normal) {
      diags_.error(loc(a->chain[0]->getStart()), "'REF=' cannot be chained", "syntax").range(range(a->chain[0]));
      return first;
    }
    // Each target is built again from the parse tree where it is read, so
    // that no AST node has two parents.
    std::vector<P::ExpressionContext*> parts{a->lhs, a->rhs};
    parts.insert(parts.end(), a->chain.begin(), a->chain.end());
    std::vector<AssignStmt*> out;
    for (size_t i = parts.size() - 1; i > 0; --i) {
      auto* s = ctx_.make<AssignStmt>();
      s->range = first->range;
      s->opLoc = first->opLoc;
      s->op = AssignStmt::Normal;
      s->lhs = expr(parts[i - 1]);
      s->rhs = expr(parts[i]);
      if (!s->lhs || !s->rhs) return nullptr;
      out.push_back(s);
    }
    chained_.insert(chained_.end(), out.begin() + 1, out.end());
    return out.front();
  }

  Stmt* unlabeled(P::UnlabeledStatementContext* c) {
    if (!c) return nullptr;
    if (auto* a = as<P::ExprBasedStmtContext>(c)) {
      Expr* lhs = expr(a->lhs);
      if (!lhs) return nullptr;
      if (!a->rhs) {
        auto* s = ctx_.make<ExprStmt>();
        s->range = range(a);
        s->expr = lhs;
        return s;
      }
      auto* s = ctx_.make<AssignStmt>();
      s->range = range(a);
      s->lhs = lhs;
      s->rhs = expr(a->rhs);
      if (!s->rhs) return nullptr;
      if (a->op) {
        s->opLoc = loc(a->op);
        s->op = a->op->getType() == STLexer::REF_ASSIGN ? AssignStmt::Ref : AssignStmt::Normal;
        if (!a->chain.empty()) return chainedAssignment(s, a);
        return s;
      }
      if (!a->sr) return nullptr;
      s->opLoc = loc(a->sr);
      std::string op = asciiUpper(text(a->sr));
      if (op == "S") s->op = AssignStmt::Set;
      else if (op == "R") s->op = AssignStmt::Reset;
      else {
        diags_.error(loc(a->sr), "unexpected identifier '" + std::string(text(a->sr)) + "'; expected ':=', 'S=' or 'R='", "syntax")
            .range(range(a->sr));
        return nullptr;
      }
      return s;
    }
    if (auto* i = as<P::IfStmtContext>(c)) {
      auto* s = ctx_.make<IfStmt>();
      s->range = range(i);
      auto bodies = i->body();
      IfStmt::Branch first;
      first.cond = expr(i->expression());
      if (!bodies.empty()) first.body = body(bodies[0]);
      s->branches.push_back(std::move(first));
      for (auto* e : i->elsifPart()) {
        IfStmt::Branch b;
        b.cond = expr(e->expression());
        b.body = body(e->body());
        s->branches.push_back(std::move(b));
      }
      if (i->elseBody) {
        s->hasElse = true;
        s->elseBody = body(i->elseBody);
      }
      return s;
    }
    if (auto* k = as<P::CaseStmtContext>(c)) {
      auto* s = ctx_.make<CaseStmt>();
      s->range = range(k);
      s->selector = expr(k->expression());
      for (auto* el : k->caseElement()) {
        CaseStmt::Element e;
        for (auto* lb : el->caseLabel()) {
          CaseStmt::Label l;
          l.range = range(lb);
          l.lo = expr(lb->lo);
          l.hi = lb->hi ? expr(lb->hi) : nullptr;
          if (l.lo) e.labels.push_back(l);
        }
        if (el->caseBody())
          for (auto* u : el->caseBody()->unlabeledStatement())
            if (Stmt* st = unlabeled(u)) {
              e.body.push_back(st);
              e.body.insert(e.body.end(), chained_.begin(), chained_.end());
              chained_.clear();
            }
        s->elements.push_back(std::move(e));
      }
      if (k->elseBody) {
        s->hasElse = true;
        s->elseBody = body(k->elseBody);
      }
      return s;
    }
    if (auto* f = as<P::ForStmtContext>(c)) {
      auto* s = ctx_.make<ForStmt>();
      s->range = range(f);
      Ident v = ident(f->IDENTIFIER());
      if (v.empty()) return nullptr;
      s->var = ctx_.make<NameExpr>();
      s->var->ident = v;
      s->var->range = v.range;
      s->from = expr(f->from);
      s->to = expr(f->to);
      s->by = f->by ? expr(f->by) : nullptr;
      s->body = body(f->body());
      return s->from && s->to ? s : nullptr;
    }
    if (auto* w = as<P::WhileStmtContext>(c)) {
      auto* s = ctx_.make<WhileStmt>();
      s->range = range(w);
      s->cond = expr(w->expression());
      s->body = body(w->body());
      return s->cond ? s : nullptr;
    }
    if (auto* r = as<P::RepeatStmtContext>(c)) {
      auto* s = ctx_.make<RepeatStmt>();
      s->range = range(r);
      s->body = body(r->body());
      s->cond = expr(r->expression());
      return s->cond ? s : nullptr;
    }
    if (auto* j = as<P::JmpStmtContext>(c)) {
      auto* s = ctx_.make<JmpStmt>();
      s->range = range(j);
      s->target = ident(j->IDENTIFIER());
      return s->target.empty() ? nullptr : s;
    }
    Stmt::Kind k;
    if (as<P::ExitStmtContext>(c)) k = Stmt::Exit;
    else if (as<P::ContinueStmtContext>(c)) k = Stmt::Continue;
    else if (as<P::ReturnStmtContext>(c)) k = Stmt::Return;
    else if (as<P::EmptyStmtContext>(c)) k = Stmt::Empty;
    else return nullptr;
    auto* s = ctx_.make<SimpleStmt>(k);
    s->range = range(c);
    return s;
  }

  // ------------------------------------------------------------ expressions
  Argument argument(P::CallArgumentContext* c) {
    Argument a;
    a.range = range(c);
    auto* first = ruleAt<P::ExpressionContext>(c, 0, P::RuleExpression);
    if (!c->op) {
      a.value = expr(first);
      return a;
    }
    bool output = c->op->getType() == STLexer::OUTPUT_ASSIGN;
    a.kind = output ? Argument::Output : Argument::Input;
    // The part before ':=' / '=>' must be a parameter name (or NOT name for '=>').
    P::ExpressionContext* nameCtx = first;
    if (auto* u = as<P::UnaryExprContext>(first); u && output && u->op && u->op->getType() == STLexer::NOT) {
      a.negated = true;
      nameCtx = ruleAt<P::ExpressionContext>(u, 1, P::RuleExpression);
    }
    if (auto* n = as<P::NameExprContext>(nameCtx)) {
      a.name = ident(tokenAt(n, 0));
    } else if (first) {
      diags_.error(loc(first->getStart()), std::string("expected a parameter name before '") + (output ? "=>" : ":=") + "'", "syntax")
          .range(range(first));
    }
    a.value = c->value ? expr(c->value) : nullptr;
    return a;
  }

  static BinaryOp binaryOp(size_t t) {
    switch (t) {
      case STLexer::POWER: return BinaryOp::Pow;
      case STLexer::STAR: return BinaryOp::Mul;
      case STLexer::SLASH: return BinaryOp::Div;
      case STLexer::MOD: return BinaryOp::Mod;
      case STLexer::PLUS: return BinaryOp::Add;
      case STLexer::MINUS: return BinaryOp::Sub;
      case STLexer::LT: return BinaryOp::Lt;
      case STLexer::GT: return BinaryOp::Gt;
      case STLexer::LE: return BinaryOp::Le;
      case STLexer::GE: return BinaryOp::Ge;
      case STLexer::EQ: return BinaryOp::Eq;
      case STLexer::NE: return BinaryOp::Ne;
      case STLexer::AND: case STLexer::AMP: return BinaryOp::And;
      case STLexer::AND_THEN: return BinaryOp::AndThen;
      case STLexer::XOR: return BinaryOp::Xor;
      case STLexer::OR: return BinaryOp::Or;
      default: return BinaryOp::OrElse;
    }
  }

  Expr* expr(P::ExpressionContext* c) {
    if (!c) return nullptr;
    if (auto* n = as<P::NameExprContext>(c)) {
      auto* e = ctx_.make<NameExpr>();
      e->ident = ident(tokenAt(n, 0));
      e->range = e->ident.range;
      return e->ident.empty() ? nullptr : e;
    }
    if (auto* t = as<P::ThisExprContext>(c)) {
      auto* e = ctx_.make<ThisExpr>();
      e->range = range(t);
      return e;
    }
    if (auto* s = as<P::SuperExprContext>(c)) {
      auto* e = ctx_.make<SuperExpr>();
      e->range = range(s);
      return e;
    }
    if (auto* a = as<P::AddressExprContext>(c)) {
      auto* e = ctx_.make<DirectAddressExpr>();
      e->range = range(a);
      e->text = std::string(text(a->DIRECT_ADDRESS()));
      return e;
    }
    if (auto* l = as<P::SimpleLiteralExprContext>(c)) return literal(l);
    if (auto* l = as<P::TypedLiteralExprContext>(c)) return literal(l);
    if (auto* p = as<P::ParenExprContext>(c)) {
      Expr* inner = expr(ruleAt<P::ExpressionContext>(p, 1, P::RuleExpression));
      if (inner) inner->range = range(p);
      return inner;
    }
    if (auto* m = as<P::MemberExprContext>(c)) {
      auto* e = ctx_.make<MemberExpr>();
      e->range = range(m);
      e->base = expr(ruleAt<P::ExpressionContext>(m, 0, P::RuleExpression));
      if (!e->base) return nullptr;
      antlr4::Token* mt = tokenAt(m, 2);
      if (mt && mt->getType() == STLexer::IDENTIFIER) {
        e->member = ident(mt);
      } else if (m->INTEGER_LITERAL()) {
        e->access = MemberExpr::Bit;
        e->member = ident(m->INTEGER_LITERAL());
        e->bitIndex = static_cast<unsigned>(std::min<uint64_t>(integerValue(m->INTEGER_LITERAL()), 1u << 20));
      } else if (m->PARTIAL_ACCESS()) {
        e->member = ident(m->PARTIAL_ACCESS());
        char sz = static_cast<char>(std::toupper(static_cast<unsigned char>(e->member.name[1])));
        e->access = sz == 'X' ? MemberExpr::PartialBit : sz == 'B' ? MemberExpr::PartialByte
                    : sz == 'W' ? MemberExpr::PartialWord : MemberExpr::PartialDWord;
        e->bitIndex = static_cast<unsigned>(std::min(std::strtoull(e->member.name.c_str() + 2, nullptr, 10), 1ull << 20));
      }
      return e->member.empty() ? nullptr : e;
    }
    if (auto* x = as<P::IndexExprContext>(c)) {
      auto* e = ctx_.make<IndexExpr>();
      e->range = range(x);
      auto es = x->expression();
      if (es.empty()) return nullptr;
      e->base = expr(es[0]);
      for (size_t i = 1; i < es.size(); ++i)
        if (Expr* ix = expr(es[i])) e->indices.push_back(ix);
      return e->base && !e->indices.empty() ? e : nullptr;
    }
    if (auto* d = as<P::DerefExprContext>(c)) {
      auto* e = ctx_.make<DerefExpr>();
      e->range = range(d);
      e->base = expr(d->expression());
      return e->base ? e : nullptr;
    }
    if (auto* k = as<P::CallExprContext>(c)) {
      auto* e = ctx_.make<CallExpr>();
      e->range = range(k);
      e->callee = expr(ruleAt<P::ExpressionContext>(k, 0, P::RuleExpression));
      if (!e->callee) return nullptr;
      forEachRule<P::CallArgumentContext>(k, P::RuleCallArgument, [&](P::CallArgumentContext* a) { e->args.push_back(argument(a)); });
      if (k->LPAREN()) e->parenRange = SourceRange(loc(k->LPAREN()->getSymbol()), range(k).end);
      return e;
    }
    if (auto* u = as<P::UnaryExprContext>(c)) {
      Expr* operand = expr(ruleAt<P::ExpressionContext>(u, 1, P::RuleExpression));
      if (!operand || !u->op) return nullptr;
      // Fold '-' into a numeric literal so that -128 fits SINT.
      if (u->op->getType() == STLexer::MINUS) {
        if (auto* lit = dyn_cast<LiteralExpr>(operand)) {
          if ((lit->litKind == LiteralExpr::Int || lit->litKind == LiteralExpr::Real) && lit->typePrefix.empty() && !lit->negative) {
            lit->negative = true;
            lit->realValue = -lit->realValue;
            lit->range = range(u);
            return lit;
          }
        }
      }
      auto* e = ctx_.make<UnaryExpr>();
      e->range = range(u);
      e->op = u->op->getType() == STLexer::MINUS ? UnaryOp::Neg : u->op->getType() == STLexer::PLUS ? UnaryOp::Plus : UnaryOp::Not;
      e->opLoc = loc(u->op);
      e->operand = operand;
      return e;
    }
    if (auto* b = as<P::BinaryExprContext>(c)) {
      auto* e = ctx_.make<BinaryExpr>();
      e->range = range(b);
      e->lhs = expr(ruleAt<P::ExpressionContext>(b, 0, P::RuleExpression));
      e->rhs = expr(ruleAt<P::ExpressionContext>(b, 2, P::RuleExpression));
      if (!e->lhs || !e->rhs || !b->op) return nullptr;
      e->op = binaryOp(b->op->getType());
      e->opLoc = loc(b->op);
      return e;
    }
    return nullptr;
  }

  // ------------------------------------------------------------ literals
  uint64_t integerValue(antlr4::tree::TerminalNode* n) {
    if (!n) return 0;
    uint64_t v = 0;
    parseInteger(text(n), 10, v, n->getSymbol());
    return v;
  }

  bool parseInteger(std::string_view digits, unsigned base, uint64_t& out, antlr4::Token* t) {
    uint64_t v = 0;
    bool any = false;
    for (char ch : digits) {
      if (ch == '_') continue;
      unsigned d;
      if (ch >= '0' && ch <= '9') d = static_cast<unsigned>(ch - '0');
      else if (ch >= 'a' && ch <= 'z') d = static_cast<unsigned>(ch - 'a' + 10);
      else if (ch >= 'A' && ch <= 'Z') d = static_cast<unsigned>(ch - 'A' + 10);
      else d = 99;
      if (d >= base) {
        diags_.error(loc(t), "invalid digit '" + std::string(1, ch) + "' in base-" + std::to_string(base) + " literal", "literal").range(range(t));
        return false;
      }
      if (v > (UINT64_MAX - d) / base) {
        diags_.error(loc(t), "integer literal is too large for any integer type", "literal").range(range(t));
        return false;
      }
      v = v * base + d;
      any = true;
    }
    if (!any) {
      diags_.error(loc(t), "missing digits in literal", "literal").range(range(t));
      return false;
    }
    out = v;
    return true;
  }

  void numeric(antlr4::Token* t, LiteralExpr* e) {
    std::string_view s = text(t);
    switch (t->getType()) {
      case STLexer::INTEGER_LITERAL:
        e->litKind = LiteralExpr::Int;
        parseInteger(s, 10, e->intValue, t);
        e->realValue = static_cast<double>(e->intValue);
        break;
      case STLexer::BASED_LITERAL: {
        size_t h = s.find('#');
        unsigned base = static_cast<unsigned>(std::atoi(std::string(s.substr(0, h)).c_str()));
        e->litKind = LiteralExpr::Int;
        parseInteger(s.substr(h + 1), base, e->intValue, t);
        e->realValue = static_cast<double>(e->intValue);
        break;
      }
      case STLexer::REAL_LITERAL: {
        std::string clean;
        for (char ch : s) if (ch != '_') clean += ch;
        e->litKind = LiteralExpr::Real;
        e->realValue = std::strtod(clean.c_str(), nullptr);
        if (std::isinf(e->realValue))
          diags_.error(loc(t), "real literal is too large for LREAL", "literal").range(range(t));
        break;
      }
      default:
        break;
    }
  }

  std::string decodeString(antlr4::Token* t, bool wide) {
    std::string_view s = text(t);
    std::string out;
    char q = wide ? '"' : '\'';
    size_t end = s.size();
    if (end >= 2 && s.back() == q) --end;   // unterminated strings lack it
    for (size_t i = 1; i < end; ++i) {
      char c = s[i];
      if (c != '$') { out += c; continue; }
      if (i + 1 >= end) {
        diags_.error({file_.id, static_cast<uint32_t>(t->getStartIndex() + i)}, "incomplete '$' escape at the end of the string", "literal");
        break;
      }
      char n = s[++i];
      switch (std::toupper(static_cast<unsigned char>(n))) {
        case '$': out += '$'; break;
        case '\'': out += '\''; break;
        case '"': out += '"'; break;
        case 'L': case 'N': out += '\n'; break;
        case 'P': out += '\f'; break;
        case 'R': out += '\r'; break;
        case 'T': out += '\t'; break;
        default: {
          unsigned digits = wide ? 4 : 2;
          unsigned v = 0;
          bool ok = i + digits <= end;
          for (unsigned k = 0; ok && k < digits; ++k) {
            char h = s[i + k];
            if (!std::isxdigit(static_cast<unsigned char>(h))) ok = false;
            else v = v * 16 + static_cast<unsigned>(std::isdigit(static_cast<unsigned char>(h)) ? h - '0' : std::toupper(static_cast<unsigned char>(h)) - 'A' + 10);
          }
          if (!ok) {
            SourceLoc l{file_.id, static_cast<uint32_t>(t->getStartIndex() + i - 1)};
            diags_.error(l, std::string("invalid escape sequence '$") + n + "' in string literal", "literal")
                .range(SourceRange(l, {file_.id, l.offset + 2}));
            break;
          }
          // The text is UTF-8 for both kinds: a STRING's $hh is the character U+00hh, which
          // codegen stores as the byte hh (Latin-1), never as the start of a UTF-8 sequence.
          if (v < 0x80) {
            out += static_cast<char>(v);
          } else if (v < 0x800) {
            out += static_cast<char>(0xC0 | (v >> 6));
            out += static_cast<char>(0x80 | (v & 0x3F));
          } else {
            out += static_cast<char>(0xE0 | (v >> 12));
            out += static_cast<char>(0x80 | ((v >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (v & 0x3F));
          }
          i += digits - 1;
        }
      }
    }
    return out;
  }

  void timeLiteral(antlr4::Token* t, LiteralExpr* e) {
    std::string_view s = text(t);
    size_t h = s.find('#');
    std::string prefix = asciiUpper(s.substr(0, h));
    e->litKind = LiteralExpr::Time;
    e->isLong = prefix[0] == 'L';
    std::string_view body = s.substr(h + 1);
    bool neg = false;
    if (!body.empty() && body[0] == '-') { neg = true; body.remove_prefix(1); }
    long double total = 0;
    size_t i = 0;
    bool bad = false;
    std::string lastUnit;
    static const char* order[] = {"D", "H", "M", "S", "MS", "US", "NS"};
    int lastRank = -1;
    while (i < body.size() && !bad) {
      size_t b = i;
      while (i < body.size() && (std::isdigit(static_cast<unsigned char>(body[i])) || body[i] == '_' || body[i] == '.')) ++i;
      std::string num;
      for (char ch : body.substr(b, i - b)) if (ch != '_') num += ch;
      size_t ub = i;
      while (i < body.size() && std::isalpha(static_cast<unsigned char>(body[i]))) ++i;
      std::string unit = asciiUpper(body.substr(ub, i - ub));
      // Split fused units such as "1m30s" lexed as one body: handled by the loop;
      // but "ms"/"us"/"ns" must not be read as "m"+"s".
      long double scale;
      int rank;
      if (unit == "D") { scale = 86400e9L; rank = 0; }
      else if (unit == "H") { scale = 3600e9L; rank = 1; }
      else if (unit == "M") { scale = 60e9L; rank = 2; }
      else if (unit == "S") { scale = 1e9L; rank = 3; }
      else if (unit == "MS") { scale = 1e6L; rank = 4; }
      else if (unit == "US") { scale = 1e3L; rank = 5; }
      else if (unit == "NS") { scale = 1; rank = 6; }
      else { bad = true; break; }
      if (num.empty()) { bad = true; break; }
      if (rank <= lastRank) {
        diags_.error(loc(t), std::string("time literal units out of order: '") + order[rank] + "' after '" + order[lastRank] + "'", "literal").range(range(t));
        return;
      }
      lastRank = rank;
      total += std::strtold(num.c_str(), nullptr) * scale;
    }
    if (bad) {
      diags_.error(loc(t), "malformed time literal; expected a value with units d, h, m, s, ms, us or ns, as in T#1h30m", "literal").range(range(t));
      return;
    }
    if (total > 9.2e18L) {
      diags_.error(loc(t), "time literal is too large for " + std::string(e->isLong ? "LTIME" : "TIME"), "literal").range(range(t));
      return;
    }
    int64_t ns = static_cast<int64_t>(std::llround(static_cast<double>(total)));
    if (total < 1e15L) ns = static_cast<int64_t>(total + 0.5L);
    e->intValue = static_cast<uint64_t>(neg ? -ns : ns);
  }

  bool parseDate(std::string_view s, antlr4::Token* t, int64_t& days) {
    int64_t y = 0;
    unsigned m = 0, d = 0;
    std::string clean;
    for (char ch : s) if (ch != '_') clean += ch;
    if (std::sscanf(clean.c_str(), "%ld-%u-%u", &y, &m, &d) != 3 || m < 1 || m > 12 || d < 1) {
      diags_.error(loc(t), "malformed date; expected YYYY-MM-DD", "literal").range(range(t));
      return false;
    }
    static const unsigned mdays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    unsigned maxd = mdays[m - 1] + (m == 2 && isLeap(y) ? 1 : 0);
    if (d > maxd) {
      diags_.error(loc(t), "day " + std::to_string(d) + " is out of range for month " + std::to_string(m) + " of " + std::to_string(y), "literal").range(range(t));
      return false;
    }
    if (y < 1970 || y > 2554) {
      diags_.error(loc(t), "year " + std::to_string(y) + " is out of the supported range 1970..2554", "literal").range(range(t));
      return false;
    }
    days = daysFromCivil(y, m, d);
    return true;
  }

  bool parseTod(std::string_view s, antlr4::Token* t, int64_t& ns) {
    unsigned h = 0, m = 0;
    double sec = 0;
    std::string str(s);
    int n = std::sscanf(str.c_str(), "%u:%u:%lf", &h, &m, &sec);
    if (n < 2 || h > 23 || m > 59 || sec < 0 || sec >= 60) {
      diags_.error(loc(t), "malformed time of day; expected HH:MM:SS[.fff] within 00:00:00..23:59:59.999", "literal").range(range(t));
      return false;
    }
    ns = (static_cast<int64_t>(h) * 3600 + m * 60) * 1000000000LL + static_cast<int64_t>(std::llround(sec * 1e9));
    return true;
  }

  // `c` is a simpleLiteralExpr (its first token is the literal) or a
  // typedLiteralExpr (its child is the typedLiteral rule).
  Expr* literal(antlr4::ParserRuleContext* c) {
    if (!c) return nullptr;
    auto* e = ctx_.make<LiteralExpr>();
    e->range = range(c);
    if (auto* tl = ruleAt<P::TypedLiteralContext>(c, 0, P::RuleTypedLiteral)) {
      auto ids = tl->IDENTIFIER();
      if (ids.empty()) return nullptr;
      e->typePrefix = ident(ids[0]);
      if (tl->MINUS()) e->negative = true;
      if (tl->INTEGER_LITERAL()) numeric(tl->INTEGER_LITERAL()->getSymbol(), e);
      else if (tl->REAL_LITERAL()) numeric(tl->REAL_LITERAL()->getSymbol(), e);
      else if (tl->BASED_LITERAL()) numeric(tl->BASED_LITERAL()->getSymbol(), e);
      else if (tl->TRUE()) { e->litKind = LiteralExpr::Bool; e->intValue = 1; }
      else if (tl->FALSE()) { e->litKind = LiteralExpr::Bool; e->intValue = 0; }
      else if (tl->STRING_LITERAL()) { e->litKind = LiteralExpr::String; e->text = decodeString(tl->STRING_LITERAL()->getSymbol(), false); }
      else if (tl->WSTRING_LITERAL()) { e->litKind = LiteralExpr::WString; e->text = decodeString(tl->WSTRING_LITERAL()->getSymbol(), true); }
      else if (ids.size() > 1) { e->litKind = LiteralExpr::Enum; e->text = std::string(text(ids[1])); }
      else return nullptr;
      if (e->negative) e->realValue = -e->realValue;
      return e;
    }
    antlr4::Token* t = c->getStart();
    if (!t) return nullptr;
    switch (t->getType()) {
      case STLexer::INTEGER_LITERAL: case STLexer::BASED_LITERAL: case STLexer::REAL_LITERAL:
        numeric(t, e);
        break;
      case STLexer::TRUE: e->litKind = LiteralExpr::Bool; e->intValue = 1; break;
      case STLexer::FALSE: e->litKind = LiteralExpr::Bool; e->intValue = 0; break;
      case STLexer::STRING_LITERAL: e->litKind = LiteralExpr::String; e->text = decodeString(t, false); break;
      case STLexer::WSTRING_LITERAL: e->litKind = LiteralExpr::WString; e->text = decodeString(t, true); break;
      case STLexer::TIME_LITERAL: timeLiteral(t, e); break;
      case STLexer::DATE_LITERAL: {
        std::string_view s = text(t);
        e->litKind = LiteralExpr::Date;
        e->isLong = std::toupper(static_cast<unsigned char>(s[0])) == 'L';
        int64_t days = 0;
        if (parseDate(s.substr(s.find('#') + 1), t, days)) e->intValue = static_cast<uint64_t>(days * 86400LL * 1000000000LL);
        break;
      }
      case STLexer::TOD_LITERAL: {
        std::string_view s = text(t);
        e->litKind = LiteralExpr::TimeOfDay;
        e->isLong = std::toupper(static_cast<unsigned char>(s[0])) == 'L';
        int64_t ns = 0;
        if (parseTod(s.substr(s.find('#') + 1), t, ns)) e->intValue = static_cast<uint64_t>(ns);
        break;
      }
      case STLexer::DATE_TIME_LITERAL: {
        std::string_view s = text(t);
        e->litKind = LiteralExpr::DateTime;
        e->isLong = std::toupper(static_cast<unsigned char>(s[0])) == 'L';
        std::string_view body = s.substr(s.find('#') + 1);
        // YYYY-MM-DD-HH:MM:SS: the third '-' separates date and time.
        size_t dash = 0;
        int count = 0;
        for (size_t i = 0; i < body.size(); ++i)
          if (body[i] == '-' && ++count == 3) { dash = i; break; }
        int64_t days = 0, ns = 0;
        if (parseDate(body.substr(0, dash), t, days) && parseTod(body.substr(dash + 1), t, ns))
          e->intValue = static_cast<uint64_t>(days * 86400LL * 1000000000LL + ns);
        break;
      }
      default:
        return nullptr;
    }
    return e;
  }

  const SourceFile& file_;
  const LexedFile& lexed_;
  DiagnosticsEngine& diags_;
  ASTContext& ctx_;
  std::vector<Stmt*> chained_;   // statements of a chained assignment after the first
};

}  // namespace

void buildAST(STParser::CompilationUnitContext* cu, const SourceFile& file, const LexedFile& lexed,
              DiagnosticsEngine& diags, ASTContext& ctx, SourceUnit& unit) {
  Builder(file, lexed, diags, ctx).unit(cu, unit);
}

}  // namespace stc::parse
