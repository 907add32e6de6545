// Declarations: symbols for every type, POU, method, global; resolution of
// type syntax to semantic types; POU signatures and inheritance.
#include <algorithm>
#include <cctype>

#include "basic/Text.h"
#include "sema/SemaInternal.h"

namespace stc::sema {

// The largest object (array, structure, instance) a program may declare.
constexpr uint64_t kMaxObjectBytes = 1ull << 30;

std::string upperCase(std::string_view s) { return asciiUpper(s); }

Symbol* Scope::add(Symbol* s) {
  auto [it, inserted] = map_.emplace(upperCase(s->name), s);
  if (!inserted) return it->second;
  order_.push_back(s);
  return s;
}

Symbol* Scope::lookupLocal(const std::string& upper) const {
  auto it = map_.find(upper);
  return it == map_.end() ? nullptr : it->second;
}

Symbol* Scope::lookup(const std::string& upper) const {
  for (const Scope* s = this; s; s = s->parent_)
    if (Symbol* r = s->lookupLocal(upper)) return r;
  return nullptr;
}

std::string typeName(const Type* t) { return t ? t->name : "<none>"; }

// ------------------------------------------------------------------ Sema API

Sema::Sema(ASTContext& ctx, DiagnosticsEngine& diags, SemaOptions opts)
    : impl_(std::make_unique<SemaImpl>(ctx, diags, opts)) {}
Sema::~Sema() = default;
bool Sema::run() { return impl_->run(); }
const Model& Sema::model() const { return impl_->model_; }

SemaImpl::SemaImpl(ASTContext& ast, DiagnosticsEngine& diags, SemaOptions opts)
    : ast_(ast), diags_(diags), opts_(opts) {
  types_.setAddress32(opts.addressBits == 32);
}

bool SemaImpl::run() {
  unsigned before = diags_.errorCount();
  registerBuiltins();
  for (SourceUnit& u : ast_.units()) declareDecls(u.decls, global_, nullptr);
  attachPendingMembers();
  for (Symbol* t : typeSymbols_) resolveTypeSymbol(t);
  for (size_t i = 0; i < pous_.size(); ++i) resolveSignature(pous_[i]);
  resolveGlobals();
  for (Symbol* p : pous_) checkInheritance(p);
  checkStaticInstances();
  for (Symbol* p : pous_) checkBody(p);
  for (auto& [c, ctx] : configs_) checkConfiguration(c, ctx);
  checkContainmentCycles();
  checkRecursion();
  checkUnused();
  layout_.reset();
  model_.types = &types_;
  model_.layout = &layout_;
  model_.dialect = opts_.dialect;
  model_.addressBits = opts_.addressBits;
  model_.pous = pous_;
  for (auto& [g, ctx] : globalDecls_) model_.globalLists.push_back(g);
  for (auto& [c, ctx] : configs_) model_.configurations.push_back(c);
  return diags_.errorCount() == before;
}

Symbol* SemaImpl::newSymbol(Symbol::Kind k, std::string name, SourceRange r) {
  symbols_.push_back(std::make_unique<Symbol>());
  Symbol* s = symbols_.back().get();
  s->kind = k;
  s->name = std::move(name);
  s->declRange = r;
  return s;
}

static const char* kindName(const Symbol* s) {
  switch (s->kind) {
    case Symbol::Variable: return "variable";
    case Symbol::Function: return "function";
    case Symbol::FunctionBlock: return "function block";
    case Symbol::Program: return "program";
    case Symbol::Interface: return "interface";
    case Symbol::Method: return "method";
    case Symbol::Property: return "property";
    case Symbol::Action: return "action";
    case Symbol::TypeName: return "type";
    case Symbol::EnumValue: return "enumeration value";
    case Symbol::Namespace: return "namespace";
    case Symbol::GlobalList: return "global variable list";
    case Symbol::BuiltinFunction: return "standard function";
  }
  return "symbol";
}

static std::string withArticle(const std::string& noun) {
  return (std::string("aeiou").find(noun[0]) != std::string::npos ? "an " : "a ") + noun;
}

bool SemaImpl::declare(Scope& scope, Symbol* s, const char* what) {
  Symbol* existing = scope.add(s);
  if (existing == s) return true;
  // A namespace may be reopened; a GVL name may span several files.
  if (existing->kind == s->kind && (s->kind == Symbol::Namespace || s->kind == Symbol::GlobalList)) return false;
  auto d = diags_.error(s->declRange.begin, std::string("redefinition of ") + what + " '" + s->name + "'", "redefinition");
  d.range(s->declRange);
  if (existing->declRange.valid())
    d.note(existing->declRange.begin, std::string("previous definition of ") + kindName(existing) + " '" + existing->name + "' is here",
           existing->declRange);
  else
    d.note(SourceLoc{}, "'" + existing->name + "' is a " + kindName(existing) + " of the standard library");
  return false;
}

// ------------------------------------------------------------------ declaring

void SemaImpl::declareDecls(std::vector<Decl*>& decls, Scope& scope, Symbol* ns) {
  std::vector<PouDecl*> qualifiedMembers;
  for (Decl* d : decls) {
    if (auto* td = dyn_cast<TypeDecl>(d)) {
      Symbol* s = newSymbol(Symbol::TypeName, td->name.name, td->name.range);
      s->typeDecl = td;
      s->parentNamespace = ns;
      if (declare(scope, s, "type")) {
        typeSymbols_.push_back(s);
        outerScope_[s] = &scope;
      }
    } else if (auto* pd = dyn_cast<PouDecl>(d)) {
      if ((pd->pouKind == PouKind::Method || pd->pouKind == PouKind::Action || pd->pouKind == PouKind::Property) &&
          pd->name.parts.size() >= 2) {
        qualifiedMembers.push_back(pd);
        continue;
      }
      if (pd->pouKind == PouKind::Method || pd->pouKind == PouKind::Action || pd->pouKind == PouKind::Property) {
        diags_.error(pd->name.range.begin, std::string(spelling(pd->pouKind)) + " '" + pd->name.str() +
                                               "' must belong to a function block or program; write it inside the POU or name it 'Owner." +
                                               pd->name.str() + "'", "orphan-member").range(pd->name.range);
        continue;
      }
      declarePou(pd, scope, ns);
    } else if (auto* gd = dyn_cast<GlobalVarDecl>(d)) {
      globalDecls_.push_back({gd, Context{nullptr, &scope}});
      bool qualifiedOnly = std::any_of(gd->attributes.begin(), gd->attributes.end(),
                                       [](const Pragma& p) { return upperCase(p.name) == "QUALIFIED_ONLY"; });
      Symbol* list = nullptr;
      if (!gd->listName.empty()) {
        list = newSymbol(Symbol::GlobalList, gd->listName.name, gd->listName.range);
        list->scope = std::make_unique<Scope>();
        if (!declare(scope, list, "global variable list")) {
          Symbol* existing = scope.lookupLocal(upperCase(list->name));
          list = existing && existing->kind == Symbol::GlobalList ? existing : nullptr;
        }
      }
      if (qualifiedOnly && !list) {
        diags_.warning(gd->range.begin, "{attribute 'qualified_only'} needs a named global variable list; put this VAR_GLOBAL block in a file of its own "
                                        "(the file name names the list); the variables stay global", "qualified-only").range(gd->block.range);
        qualifiedOnly = false;
      }
      for (VarDecl* v : gd->block.vars) {
        Symbol* s = newSymbol(Symbol::Variable, v->name.name, v->name.range);
        s->var = v;
        outerScope_[s] = &scope;
        if (!qualifiedOnly) declare(scope, s, "global variable");
        if (list) {
          if (qualifiedOnly) list->scope->add(s);
          else if (list->scope->add(s) != s) {
            // already reported through the global scope
          }
        }
      }
    } else if (auto* cd = dyn_cast<ConfigurationDecl>(d)) {
      configs_.push_back({cd, Context{nullptr, &scope}});
      auto declareBlock = [&](VarBlock& b) {
        auto* gd2 = ast_.make<GlobalVarDecl>();
        gd2->block = b;
        gd2->range = b.range;
        globalDecls_.push_back({gd2, Context{nullptr, &scope}});
        for (VarDecl* v : b.vars) {
          Symbol* s = newSymbol(Symbol::Variable, v->name.name, v->name.range);
          s->var = v;
          declare(scope, s, "global variable");
        }
      };
      for (VarBlock& b : cd->globals) declareBlock(b);
      for (ResourceDecl& r : cd->resources)
        for (VarBlock& b : r.globals) declareBlock(b);
    } else if (auto* nd = dyn_cast<NamespaceDecl>(d)) {
      Scope* target = &scope;
      Symbol* inner = ns;
      for (const Ident& part : nd->name.parts) {
        Symbol* existing = target->lookupLocal(upperCase(part.name));
        if (existing && existing->kind == Symbol::Namespace) {
          inner = existing;
        } else {
          Symbol* s = newSymbol(Symbol::Namespace, part.name, part.range);
          s->scope = std::make_unique<Scope>(target);
          s->parentNamespace = inner;
          if (!declare(*target, s, "namespace")) { inner = nullptr; break; }
          inner = s;
        }
        target = inner->scope.get();
      }
      if (inner) declareDecls(nd->decls, *inner->scope, inner);
    }
  }
  for (PouDecl* pd : qualifiedMembers) pendingMembers_.push_back({pd, &scope});
}

// METHOD FB.M / ACTION FB.A at top level: attach them to their owner once
// every file is declared (the owner may come later).
void SemaImpl::attachPendingMembers() {
  for (auto& [pd, scope] : pendingMembers_) {
    QualifiedName ownerName = pd->name;
    Ident memberName = ownerName.parts.back();
    ownerName.parts.pop_back();
    Symbol* owner = lookupQualified(ownerName, scope, false, "function block");
    if (!owner || !(owner->kind == Symbol::FunctionBlock || owner->kind == Symbol::Program || owner->kind == Symbol::Interface)) {
      diags_.error(ownerName.range.begin, "unknown function block or program '" + ownerName.str() + "' for " +
                                              spelling(pd->pouKind) + " '" + memberName.name + "'", "undeclared-name")
          .range(ownerName.range);
      continue;
    }
    pd->name.parts = {memberName};
    pd->owner = owner->pou->decl;
    if (pd->pouKind == PouKind::Method) owner->pou->decl->methods.push_back(pd);
    else if (pd->pouKind == PouKind::Action) owner->pou->decl->actions.push_back(pd);
    else owner->pou->decl->properties.push_back(pd);
  }
}

Symbol* SemaImpl::declarePou(PouDecl* d, Scope& scope, Symbol* ns) {
  Symbol::Kind k = Symbol::Program;
  TypeKind tk = TypeKind::Program;
  const char* what = "program";
  switch (d->pouKind) {
    case PouKind::Function: k = Symbol::Function; what = "function"; break;
    case PouKind::FunctionBlock: k = Symbol::FunctionBlock; tk = TypeKind::FunctionBlock; what = "function block"; break;
    case PouKind::Interface: k = Symbol::Interface; tk = TypeKind::Interface; what = "interface"; break;
    default: break;
  }
  const Ident& nameId = d->name.parts.back();
  Symbol* s = newSymbol(k, nameId.name, nameId.range);
  s->parentNamespace = ns;
  s->pou = std::make_unique<PouInfo>();
  s->pou->decl = d;
  s->pou->vars = std::make_unique<Scope>();
  s->pou->members = std::make_unique<Scope>();
  d->symbol = s;
  if (k != Symbol::Function) {
    Type* t = types_.create(tk, nameId.name);
    t->pou = s;
    s->pou->instanceType = t;
    s->type = t;
  }
  if (d->name.parts.size() > 1)
    diags_.error(d->name.range.begin, "a qualified name is not allowed here; declare '" + nameId.name + "' inside NAMESPACE " +
                                          d->name.parts.front().name, "syntax").range(d->name.range);
  if (!declare(scope, s, what)) return nullptr;
  outerScope_[s] = &scope;
  pous_.push_back(s);
  return s;
}

// Declares methods, properties and actions of an FB/program/interface.
void SemaImpl::declareMembers(Symbol* owner) {
  PouDecl* d = owner->pou->decl;
  auto add = [&](PouDecl* md, Symbol::Kind k, const char* what) -> Symbol* {
    const Ident& id = md->name.parts.back();
    Symbol* s = newSymbol(k, id.name, id.range);
    s->pou = std::make_unique<PouInfo>();
    s->pou->decl = md;
    s->pou->vars = std::make_unique<Scope>();
    s->pou->members = std::make_unique<Scope>();
    s->pou->owner = owner;
    md->symbol = s;
    if (owner->pou->vars->lookupLocal(upperCase(id.name))) {
      Symbol* v = owner->pou->vars->lookupLocal(upperCase(id.name));
      diags_.error(id.range.begin, std::string(what) + " '" + id.name + "' has the same name as a variable of '" + owner->name + "'",
                   "redefinition").range(id.range).note(v->declRange.begin, "variable declared here", v->declRange);
      return nullptr;
    }
    if (!declare(*owner->pou->members, s, what)) return nullptr;
    outerScope_[s] = outerScope_[owner];
    return s;
  };
  for (PouDecl* m : d->methods)
    if (Symbol* s = add(m, Symbol::Method, "method"); s && owner->kind != Symbol::Interface) pous_.push_back(s);
    else if (s) resolveSignature(s);
  for (PouDecl* a : d->actions) {
    if (owner->kind == Symbol::Interface) continue;
    if (Symbol* s = add(a, Symbol::Action, "action")) pous_.push_back(s);
  }
  for (PouDecl* p : d->properties) {
    Symbol* s = add(p, Symbol::Property, "property");
    if (!s) continue;
    for (PouDecl* acc : {p->getter, p->setter}) {
      if (!acc) continue;
      Symbol* a = newSymbol(Symbol::Method, p->name.parts.back().name + "." + acc->name.str(), acc->name.range);
      a->pou = std::make_unique<PouInfo>();
      a->pou->decl = acc;
      a->pou->vars = std::make_unique<Scope>();
      a->pou->members = std::make_unique<Scope>();
      a->pou->owner = owner;
      acc->symbol = a;
      outerScope_[a] = outerScope_[owner];
      if (owner->kind != Symbol::Interface) pous_.push_back(a);
    }
  }
}

// ------------------------------------------------------------------ lookup

Symbol* SemaImpl::ownerOf(Symbol* pou) {
  return pou && pou->pou && pou->pou->owner ? pou->pou->owner : pou;
}

Symbol* SemaImpl::lookupInPou(Symbol* pou, const std::string& upper, bool includeMembers) {
  int guard = 0;
  for (Symbol* p = pou; p && p->pou && guard < 64; p = p->pou->base, ++guard) {
    // Another POU may look inside this one before its turn came.
    if (!p->pou->signatureResolved && p->kind != Symbol::BuiltinFunction) resolveSignature(p);
    if (Symbol* s = p->pou->vars->lookupLocal(upper)) return s;
    if (includeMembers)
      if (Symbol* s = p->pou->members->lookupLocal(upper)) return s;
  }
  return nullptr;
}

Symbol* SemaImpl::pouMember(Symbol* pou, const std::string& upper) {
  // Interfaces: search the interface and the interfaces it extends.
  if (pou && pou->kind == Symbol::Interface) {
    if (Symbol* s = pou->pou->members->lookupLocal(upper)) return s;
    for (Symbol* b : pou->pou->interfaces)
      if (b != pou)
        if (Symbol* s = pouMember(b, upper)) return s;
    return nullptr;
  }
  return lookupInPou(pou, upper, true);
}

Symbol* SemaImpl::lookup(const std::string& upper, const Context& ctx) {
  if (ctx.pou && ctx.pou->pou) {
    if (Symbol* s = ctx.pou->pou->vars->lookupLocal(upper)) return s;
    Symbol* owner = ctx.pou->pou->owner;
    if (owner) {
      // A property accessor sees its property's variables first.
      if (Symbol* s = lookupInPou(owner, upper, true)) return s;
    } else if (ctx.pou->kind != Symbol::Function) {
      if (Symbol* s = lookupInPou(ctx.pou, upper, true)) return s;
    }
  }
  Scope* outer = ctx.outer ? ctx.outer : &global_;
  if (Symbol* s = outer->lookup(upper)) return s;
  auto it = builtinSymbols_.find(upper);
  if (it != builtinSymbols_.end()) return it->second;
  return nullptr;
}

Symbol* SemaImpl::lookupQualified(const QualifiedName& q, Scope* from, bool report, const char* what) {
  if (q.parts.empty()) return nullptr;
  Scope* scope = from ? from : &global_;
  Symbol* s = scope->lookup(upperCase(q.parts[0].name));
  for (size_t i = 1; s && i < q.parts.size(); ++i) {
    if (s->kind != Symbol::Namespace || !s->scope) {
      if (report)
        diags_.error(q.parts[i].range.begin, "'" + s->name + "' is not a namespace", "undeclared-name").range(q.parts[i - 1].range);
      return nullptr;
    }
    Symbol* next = s->scope->lookupLocal(upperCase(q.parts[i].name));
    if (!next && report) {
      diags_.error(q.parts[i].range.begin, "no " + std::string(what) + " named '" + q.parts[i].name + "' in namespace '" + s->name + "'",
                   "undeclared-name").range(q.parts[i].range);
      return nullptr;
    }
    s = next;
  }
  if (!s && report) {
    // A program named in a task: the hint comes from the PROGRAMs.
    std::string hint;
    if (q.parts.size() == 1 && std::string(what) == "program") {
      std::vector<std::string> programs;
      for (Symbol* p : pous_)
        if (p->kind == Symbol::Program) programs.push_back(p->name);
      hint = closestMatch(q.parts[0].name, programs);
    }
    auto d = diags_.error(q.range.begin, "unknown " + std::string(what) + " '" + q.str() + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"),
                          "undeclared-name");
    d.range(q.range);
    if (!hint.empty()) d.fixit(q.range, hint);
  }
  return s;
}

std::vector<std::string> SemaImpl::visibleNames(const Context& ctx) {
  std::vector<std::string> names;
  auto addScope = [&](const Scope* s) {
    for (const Symbol* sym : s->symbols()) names.push_back(sym->name);
  };
  if (ctx.pou && ctx.pou->pou) {
    addScope(ctx.pou->pou->vars.get());
    Symbol* o = ctx.pou->pou->owner ? ctx.pou->pou->owner : ctx.pou;
    for (Symbol* p = o; p && p->pou; p = p->pou->base) {
      addScope(p->pou->vars.get());
      addScope(p->pou->members.get());
      if (p->pou->base == o) break;
    }
  }
  for (const Scope* s = ctx.outer ? ctx.outer : &global_; s; s = s->parent()) addScope(s);
  for (auto& [n, vals] : enumValues_)
    for (Symbol* v : vals) names.push_back(v->name);
  return names;
}

// ------------------------------------------------------------------ types

const Type* SemaImpl::resolveNamedType(const QualifiedName& q, const Context& ctx, bool report) {
  if (q.parts.empty()) return types_.error();
  Symbol* s = nullptr;
  if (q.parts.size() == 1) {
    std::string up = upperCase(q.parts[0].name);
    if (const Type* t = types_.byName(up)) {
      // A user type may shadow nothing elementary; elementary names win.
      return t;
    }
    // Types live in namespace/global scopes only: `MC_Stop : MC_Stop;` names
    // the FB type even though the variable shadows it inside the POU.
    s = (ctx.outer ? ctx.outer : &global_)->lookup(up);
  } else {
    s = lookupQualified(q, ctx.outer, false, "type");
  }
  if (s) {
    switch (s->kind) {
      case Symbol::TypeName:
        resolveTypeSymbol(s);
        return s->type ? s->type : types_.error();
      case Symbol::FunctionBlock: case Symbol::Program: case Symbol::Interface:
        return s->type;
      default:
        if (report)
          diags_.error(q.range.begin, "'" + q.str() + "' is " + withArticle(kindName(s)) + ", not a type", "not-a-type")
              .range(q.range).note(s->declRange.begin, "'" + s->name + "' declared here", s->declRange);
        return types_.error();
    }
  }
  if (report) {
    std::vector<std::string> cands = {"BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT",
                                      "BYTE", "WORD", "DWORD", "LWORD", "REAL", "LREAL", "TIME", "LTIME", "DATE",
                                      "TIME_OF_DAY", "TOD", "DATE_AND_TIME", "DT", "STRING", "WSTRING", "CHAR", "WCHAR"};
    for (Symbol* t : typeSymbols_) cands.push_back(t->name);
    for (Symbol* p : pous_)
      if (p->kind == Symbol::FunctionBlock || p->kind == Symbol::Interface) cands.push_back(p->name);
    const std::string lib = opts_.libraryOf && q.parts.size() == 1 ? opts_.libraryOf(q.parts[0].name) : std::string();
    std::string hint = q.parts.size() == 1 && lib.empty() ? closestMatch(q.parts[0].name, cands) : "";
    auto d = diags_.error(q.range.begin, "unknown type '" + q.str() + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"),
                          "unknown-type");
    d.range(q.range);
    if (!hint.empty()) d.fixit(q.range, hint);
    if (!lib.empty())
      d.note(q.range.begin, "'" + q.str() + "' is declared by the library '" + lib + "': add it to [project] libraries in project.toml (or give --lib " +
                                lib + ")");
  }
  return types_.error();
}

void SemaImpl::resolveTypeSymbol(Symbol* s) {
  if (s->type) return;
  TypeDecl* td = s->typeDecl;
  if (!td || !td->def) { s->type = types_.error(); return; }
  if (s->resolving) {
    diags_.error(td->name.range.begin, "type '" + s->name + "' is defined in terms of itself", "type-cycle").range(td->name.range);
    s->type = types_.error();
    return;
  }
  Context ctx{nullptr, outerScope_.count(s) ? outerScope_[s] : &global_};
  s->resolving = true;
  const Type* t = resolveType(td->def, ctx, s->name);
  s->resolving = false;
  if (!s->type) s->type = t;
  td->resolved = s->type;
  if (s->type && !s->type->isError() && td->def->kind != TypeRef::Struct && td->def->kind != TypeRef::Union &&
      td->def->kind != TypeRef::Enum) {
    // An alias keeps the target's identity; nothing more to do.
  }
  if (td->init) checkInitializer(td->init, s->type, ctx);
  // A named enumeration, structure or subrange remembers its declaration:
  // its initial value is the default of every variable of the type.
  if (s->type && (td->def->kind == TypeRef::Struct || td->def->kind == TypeRef::Union || td->def->kind == TypeRef::Enum) && !s->type->decl)
    const_cast<Type*>(s->type)->decl = td;
  if (s->type && s->type->decl == td && s->type->isStructured() && hasAttribute(td->attributes, "mirrored"))
    const_cast<Type*>(s->type)->mirrored = true;
}

const Type* SemaImpl::resolveType(TypeRef* t, const Context& ctx, const std::string& derivedName) {
  if (!t) return types_.error();
  if (t->resolved) return t->resolved;
  const Type* result = types_.error();
  switch (t->kind) {
    case TypeRef::Named: {
      result = resolveNamedType(t->name, ctx, true);
      // Remember the TYPE declaration: an alias of an elementary type
      // (TYPE Percent : INT := 50) shares INT's identity but has its own default.
      if (Symbol* ts = lookupQualified(t->name, ctx.outer ? ctx.outer : &global_, false, "type"); ts && ts->kind == Symbol::TypeName)
        t->aliasDecl = ts->typeDecl;
      break;
    }
    case TypeRef::Sized: {
      std::string up = t->name.parts.size() == 1 ? upperCase(t->name.parts[0].name) : "";
      if (up != "STRING" && up != "WSTRING") {
        diags_.error(t->range.begin, "only STRING and WSTRING take a length; '" + t->name.str() + "' does not", "invalid-type")
            .range(t->range);
        break;
      }
      checkExpr(t->size, ctx);
      auto n = evalInt(t->size, ctx, "string length");
      if (!n) break;
      if (*n < 1 || *n > 65535) {
        diags_.error(t->size->range.begin, "string length " + std::to_string(*n) + " is outside 1..65535", "invalid-type").range(t->size->range);
        break;
      }
      result = types_.string(static_cast<uint32_t>(*n), up == "WSTRING");
      break;
    }
    case TypeRef::Subrange: {
      const Type* base = resolveNamedType(t->name, ctx, true);
      if (base->isError()) break;
      if (!base->isInteger()) {
        diags_.error(t->range.begin, "subrange base type must be an integer type, not '" + base->name + "'", "invalid-type").range(t->range);
        break;
      }
      checkExpr(t->lo, ctx, base);
      checkExpr(t->hi, ctx, base);
      allowUnsigned_ = base->isUnsignedInt();
      auto lo = evalInt(t->lo, ctx, "subrange bound");
      auto hi = evalInt(t->hi, ctx, "subrange bound");
      allowUnsigned_ = false;
      if (!lo || !hi) break;
      bool inverted = base->isUnsignedInt() ? static_cast<uint64_t>(*lo) > static_cast<uint64_t>(*hi) : *lo > *hi;
      if (inverted) {
        diags_.error(t->lo->range.begin, "subrange lower bound " + std::to_string(*lo) + " is greater than upper bound " + std::to_string(*hi),
                     "invalid-type").range(t->range);
        break;
      }
      if (!derivedName.empty()) {
        // TYPE Good : INT(1..10): a named type, so messages can name it.
        Type* st = types_.create(TypeKind::Subrange, derivedName);
        st->element = base;
        st->lo = *lo;
        st->hi = *hi;
        result = st;
      } else {
        result = types_.subrange(base, *lo, *hi);
      }
      break;
    }
    case TypeRef::Array: {
      std::vector<Dim> dims;
      bool ok = true;
      for (TypeRef::Dim& d : t->dims) {
        Dim dim;
        if (d.star) {
          dim.star = true;
        } else {
          checkExpr(d.lo, ctx);
          checkExpr(d.hi, ctx);
          auto lo = evalInt(d.lo, ctx, "array bound");
          auto hi = evalInt(d.hi, ctx, "array bound");
          if (!lo || !hi) { ok = false; continue; }
          if (*lo > *hi) {
            diags_.error(d.range.begin, "array lower bound " + std::to_string(*lo) + " is greater than upper bound " + std::to_string(*hi),
                         "invalid-type").range(d.range);
            ok = false;
            continue;
          }
          dim.lo = *lo;
          dim.hi = *hi;
        }
        dims.push_back(dim);
      }
      const Type* elem = resolveType(t->element, ctx);
      if (!ok || elem->isError()) break;
      // The size must fit the controller's memory: 1 GiB per object (also in
      // the 32-bit address model); checked where the array is written.
      uint64_t count = 1;
      bool overflow = false;
      for (const Dim& d : dims)
        if (!d.star) overflow = overflow || __builtin_mul_overflow(count, static_cast<uint64_t>(d.hi - d.lo) + 1, &count);
      uint64_t bytes = 0;
      bool sized = elem->isElementary() || elem->kind == TypeKind::Pointer || elem->kind == TypeKind::Reference || elem->kind == TypeKind::Array;
      if (sized) overflow = overflow || __builtin_mul_overflow(count, std::max<uint64_t>(layout_.sizeOf(elem), 1), &bytes);
      if (overflow || count > kMaxObjectBytes || bytes > kMaxObjectBytes) {
        diags_.error(t->range.begin, "array '" + types_.array(elem, dims)->name + "' is too large" +
                                         (overflow ? " (its size overflows)" : " (" + std::to_string(sized ? bytes : count) + (sized ? " bytes" : " elements") + ")") +
                                         "; an object may have at most 1 GiB", "invalid-type").range(t->range);
        break;
      }
      result = types_.array(elem, std::move(dims));
      break;
    }
    case TypeRef::Pointer:
    case TypeRef::Reference: {
      const Type* elem = types_.error();
      // Pointers may refer to a type still being resolved (linked lists).
      if (t->element && t->element->kind == TypeRef::Named) {
        Symbol* s = nullptr;
        if (t->element->name.parts.size() == 1 && !types_.byName(upperCase(t->element->name.parts[0].name)))
          s = lookup(upperCase(t->element->name.parts[0].name), ctx);
        if (s && s->kind == Symbol::TypeName && s->resolving && s->type) elem = s->type;
        else elem = resolveType(t->element, ctx);
      } else {
        elem = resolveType(t->element, ctx);
      }
      if (elem->isError()) break;
      // IEC REF_TO has pointer semantics (explicit ^, REF(x), NULL); CODESYS
      // REFERENCE TO is an alias that dereferences implicitly.
      // The native libraries' structures keep 8-byte pointer slots in either address model.
      bool wide = t->range.begin.valid() && diags_.sourceManager().file(t->range.begin.file).library;
      result = (t->kind == TypeRef::Pointer || t->refTo) ? types_.pointer(elem, wide) : types_.reference(elem, wide);
      break;
    }
    case TypeRef::Enum: {
      Type* et = types_.create(TypeKind::Enum, derivedName.empty() ? "<anonymous enum>" : derivedName);
      const Type* base = t->name.parts.empty() ? types_.elementary(TypeKind::Int) : resolveNamedType(t->name, ctx, true);
      if (!base->isError() && !base->isInteger() && !base->isBitString()) {
        diags_.error(t->name.range.begin, "enumeration base type must be an integer type, not '" + base->name + "'", "invalid-type")
            .range(t->name.range);
        base = types_.elementary(TypeKind::Int);
      }
      if (base->isError()) base = types_.elementary(TypeKind::Int);
      et->element = base;
      t->resolved = et;
      // Named enum types are visible through their symbol before the values are known.
      if (!derivedName.empty()) {
        Symbol* s = lookup(upperCase(derivedName), ctx);
        if (s && s->kind == Symbol::TypeName && !s->type) s->type = et;
      }
      int64_t next = 0;
      std::map<std::string, SourceRange> seen;
      for (EnumValueDecl& v : t->enumValues) {
        int64_t value = next;
        if (v.value) {
          checkExpr(v.value, ctx, base);
          if (auto x = evalInt(v.value, ctx, "enumeration value")) value = *x;
        }
        v.resolved = value;
        next = value + 1;
        std::string up = upperCase(v.name.name);
        auto [it, inserted] = seen.emplace(up, v.name.range);
        if (!inserted) {
          diags_.error(v.name.range.begin, "duplicate enumeration value '" + v.name.name + "'", "redefinition")
              .range(v.name.range).note(it->second.begin, "previous declaration is here", it->second);
          continue;
        }
        et->enumValues.emplace_back(v.name.name, value);
        Symbol* vs = newSymbol(Symbol::EnumValue, v.name.name, v.name.range);
        vs->type = et;
        vs->enumValue = value;
        enumValues_[up].push_back(vs);
      }
      result = et;
      break;
    }
    case TypeRef::Struct:
    case TypeRef::Union: {
      Type* st = types_.create(t->kind == TypeRef::Struct ? TypeKind::Struct : TypeKind::Union,
                               derivedName.empty() ? "<anonymous struct>" : derivedName);
      t->resolved = st;
      if (!derivedName.empty()) {
        Symbol* s = lookup(upperCase(derivedName), ctx);
        if (s && s->kind == Symbol::TypeName && !s->type) s->type = st;
      }
      std::map<std::string, SourceRange> seen;
      if (!t->structBase.parts.empty()) {
        const Type* base = resolveNamedType(t->structBase, ctx, true);
        if (!base->isError() && base->kind != TypeKind::Struct) {
          diags_.error(t->structBase.range.begin, "a structure can only extend a structure; '" + base->name + "' is not one", "invalid-base")
              .range(t->structBase.range);
        } else if (!base->isError()) {
          st->base = base;
          for (const Type* b = base; b; b = b->base)
            for (const Member& m : b->members) seen.emplace(upperCase(m.name), m.decl ? m.decl->name.range : SourceRange{});
        }
      }
      for (VarDecl* m : t->members) {
        const Type* mt = resolveType(m->type, ctx);
        if (mt == st) {
          diags_.error(m->name.range.begin, "structure '" + st->name + "' cannot contain itself", "type-cycle").range(m->type->range);
          mt = types_.error();
        }
        m->resolvedType = mt;
        auto [it, inserted] = seen.emplace(upperCase(m->name.name), m->name.range);
        if (!inserted) {
          diags_.error(m->name.range.begin, "duplicate member '" + m->name.name + "' in '" + st->name + "'", "redefinition")
              .range(m->name.range).note(it->second.begin, "previous declaration is here", it->second);
          continue;
        }
        st->members.push_back({m->name.name, mt, m});
        if (m->init) checkInitializer(m->init, mt, ctx);
      }
      result = st;
      break;
    }
  }
  t->resolved = result;
  return result;
}

// ------------------------------------------------------------------ signatures

void SemaImpl::resolveVarDecl(VarDecl* v, Symbol* sym, const Context& ctx) {
  const Type* t = resolveType(v->type, ctx);
  v->resolvedType = t;
  sym->type = t;
  if (!v->address.empty()) checkAddress(v);
  if (t->kind == TypeKind::Array) {
    bool star = std::any_of(t->dims.begin(), t->dims.end(), [](const Dim& d) { return d.star; });
    if (star && v->section != VarSection::InOut)
      diags_.error(v->type->range.begin, "'ARRAY[*]' is only allowed for VAR_IN_OUT parameters", "invalid-type").range(v->type->range);
  }
  if (t->kind == TypeKind::Program)
    diags_.error(v->type->range.begin, "'" + t->name + "' is a program; programs cannot be instantiated as variables", "invalid-type")
        .range(v->type->range);
}

void SemaImpl::checkAddress(VarDecl* v) {
  const std::string& a = v->address;   // %IX0.1
  if (a.size() < 3) return;
  char size = static_cast<char>(std::toupper(static_cast<unsigned char>(a[2])));
  bool hasSize = std::string("XBWDL").find(size) != std::string::npos;
  if (a.find('*') != std::string::npos) {
    if (v->section == VarSection::Global)
      diags_.error(v->addressRange.begin, "incomplete address '" + a + "' is not allowed in VAR_GLOBAL; locate it in VAR_CONFIG",
                   "invalid-address").range(v->addressRange);
    return;
  }
  unsigned bits = !hasSize || size == 'X' ? 1 : size == 'B' ? 8 : size == 'W' ? 16 : size == 'D' ? 32 : 64;
  const Type* t = v->resolvedType;
  if (!t || t->isError()) return;
  if (bits == 1 && a.find('.') == std::string::npos)
    diags_.error(v->addressRange.begin, "bit address '" + a + "' needs a bit number, as in %IX0.1", "invalid-address").range(v->addressRange);
  unsigned tb = t->bits();
  bool ok = (bits == 1) ? t->isBool() : (tb == bits && t->isElementary());
  if (t->kind == TypeKind::Array || t->isStructured()) ok = bits != 1;   // arrays/structs over an area
  if (!ok)
    diags_.error(v->addressRange.begin, "address '" + a + "' (" + std::to_string(bits) + " bit" + (bits == 1 ? "" : "s") +
                                            ") does not match the type '" + t->name + "'", "invalid-address")
        .range(v->addressRange).range(v->type->range);
}

void SemaImpl::resolveSignature(Symbol* pou) {
  PouInfo& pi = *pou->pou;
  if (pi.signatureResolved) return;
  pi.signatureResolved = true;
  PouDecl* d = pi.decl;
  Context ctx{pou, outerScope_.count(pou) ? outerScope_[pou] : &global_};

  // Members first, so that variable names can be checked against them.
  if (pou->kind == Symbol::FunctionBlock || pou->kind == Symbol::Program || pou->kind == Symbol::Interface) declareMembers(pou);

  if (pou->kind == Symbol::FunctionBlock && !d->extends.parts.empty() && d->extends.parts.size() == 1 &&
      types_.byName(upperCase(d->extends.parts[0].name))) {
    diags_.error(d->extends.range.begin, "'" + d->extends.str() + "' is an elementary type; a function block can only extend a function block",
                 "invalid-base").range(d->extends.range);
  } else if (pou->kind == Symbol::FunctionBlock && !d->extends.parts.empty()) {
    Symbol* base = lookupQualified(d->extends, ctx.outer, true, "function block");
    if (base && base->kind != Symbol::FunctionBlock) {
      diags_.error(d->extends.range.begin, "'" + d->extends.str() + "' is " + withArticle(kindName(base)) + "; a function block can only extend a function block",
                   "invalid-base").range(d->extends.range);
    } else if (base) {
      if (base->resolving) {
        diags_.error(d->extends.range.begin, "function block '" + pou->name + "' inherits from itself", "inheritance-cycle").range(d->extends.range);
      } else {
        pou->resolving = true;
        resolveSignature(base);
        pou->resolving = false;
        if (base->pou->decl->isFinal)
          diags_.error(d->extends.range.begin, "cannot extend FINAL function block '" + base->name + "'", "invalid-base").range(d->extends.range);
        // Cycle check through the base chain.
        bool cycle = false;
        for (Symbol* b = base; b; b = b->pou->base)
          if (b == pou) { cycle = true; break; }
        if (cycle)
          diags_.error(d->extends.range.begin, "function block '" + pou->name + "' inherits from itself", "inheritance-cycle").range(d->extends.range);
        else
          pi.base = base;
      }
    }
  }
  for (const QualifiedName& q : d->implements) {
    Symbol* itf = lookupQualified(q, ctx.outer, true, "interface");
    if (!itf) continue;
    if (itf->kind != Symbol::Interface) {
      diags_.error(q.range.begin, "'" + q.str() + "' is " + withArticle(kindName(itf)) + ", not an interface", "invalid-base").range(q.range);
      continue;
    }
    if (itf == pou || itf->resolving) {
      diags_.error(q.range.begin, "interface '" + pou->name + "' extends itself", "inheritance-cycle").range(q.range);
      continue;
    }
    pou->resolving = true;
    resolveSignature(itf);
    pou->resolving = false;
    pi.interfaces.push_back(itf);
  }

  if (d->returnType) {
    pi.returnType = resolveType(d->returnType, ctx);
  } else if (pou->kind == Symbol::Function || pou->kind == Symbol::Method) {
    pi.returnType = types_.voidType();
  }
  if (pou->kind == Symbol::Property) {
    pou->type = pi.returnType;
  }
  if (d->pouKind == PouKind::PropertyGet || d->pouKind == PouKind::PropertySet) {
    Symbol* prop = nullptr;
    if (pi.owner) prop = pi.owner->pou->members->lookupLocal(upperCase(d->owner->name.parts.back().name));
    if (prop) {
      resolveSignature(prop);
      pi.returnType = d->pouKind == PouKind::PropertyGet ? prop->pou->returnType : types_.voidType();
    }
  }

  // Variables.  Scalar VAR CONSTANTs come first: CODESYS lets an array bound or
  // a STRING length name a constant declared further down in the same POU.
  bool isFunction = pou->kind == Symbol::Function;
  auto earlyConstant = [](const VarDecl* v) {
    return v->isConstant && v->section == VarSection::Var && v->type && v->type->kind == TypeRef::Named;
  };
  for (int pass = 0; pass < 2; ++pass)
  for (VarBlock& b : d->varBlocks) {
    bool sectionReported = false;
    for (VarDecl* v : b.vars) {
      if (earlyConstant(v) != (pass == 0)) continue;
      if (sectionReported) goto declareVar;
      switch (v->section) {
        case VarSection::Global:
          diags_.error(b.range.begin, "VAR_GLOBAL is not allowed inside a POU; declare globals at top level", "invalid-section").range(b.range);
          sectionReported = true;
          break;
        case VarSection::Inst:
          if (pou->kind != Symbol::Method) {
            diags_.error(b.range.begin, "VAR_INST is only allowed in methods", "invalid-section").range(b.range);
            sectionReported = true;
          }
          break;
        case VarSection::Output:
        case VarSection::Input:
        case VarSection::InOut:
          if (pou->kind == Symbol::Action) {
            diags_.error(b.range.begin, std::string(spelling(v->section)) + " is not allowed in an action", "invalid-section").range(b.range);
            sectionReported = true;
          }
          break;
        default:
          break;
      }
    declareVar:
      if (v->isConstant && !v->init && !v->hasEmptyInit && (v->section == VarSection::Var || v->section == VarSection::Stat) &&
          v->type && v->type->kind != TypeRef::Array)
        diags_.warning(v->name.range.begin, "constant '" + v->name.name + "' has no initial value; it is always the default value",
                       "uninitialized-constant").range(v->name.range);
      Symbol* s = newSymbol(Symbol::Variable, v->name.name, v->name.range);
      s->var = v;
      // Redeclaring an inherited variable is an error.
      Symbol* inherited = pi.base ? lookupInPou(pi.base, upperCase(v->name.name), false) : nullptr;
      if (inherited) {
        diags_.error(v->name.range.begin, "variable '" + v->name.name + "' is already declared in base function block '" +
                                              pi.base->name + "'", "redefinition")
            .range(v->name.range).note(inherited->declRange.begin, "inherited declaration is here", inherited->declRange);
        v->used = true;
        continue;
      }
      if (Symbol* m = pi.members->lookupLocal(upperCase(v->name.name))) {
        diags_.error(v->name.range.begin, "variable '" + v->name.name + "' has the same name as " + kindName(m) + " '" + m->name + "'",
                     "redefinition").range(v->name.range).note(m->declRange.begin, "declared here", m->declRange);
        v->used = true;
        continue;
      }
      if (!declare(*pi.vars, s, "variable")) { v->used = true; continue; }
      resolveVarDecl(v, s, ctx);
      if (v->edge != VarDecl::NoEdge) {
        const char* q = v->edge == VarDecl::RisingEdge ? "R_EDGE" : "F_EDGE";
        if (pou->kind != Symbol::FunctionBlock && pou->kind != Symbol::Program)
          diags_.error(v->name.range.begin, std::string(q) + " needs state between calls: it is allowed on inputs of function blocks and programs, not of " +
                                                withArticle(kindName(pou)), "invalid-section").range(v->name.range);
        else if (s->type && !s->type->isError() && !s->type->isBool())
          diags_.error(v->name.range.begin, std::string(q) + " input '" + v->name.name + "' must be BOOL, not '" + s->type->name + "'", "type-mismatch")
              .range(v->name.range);
      }
      if (v->section == VarSection::Input || v->section == VarSection::Output || v->section == VarSection::InOut)
        pi.params.push_back(s);
      if (v->section == VarSection::External) {
        Symbol* g = global_.lookup(upperCase(v->name.name));
        if (Scope* o = ctx.outer) g = o->lookup(upperCase(v->name.name));
        if (!g || g->kind != Symbol::Variable) {
          diags_.error(v->name.range.begin, "VAR_EXTERNAL '" + v->name.name + "' does not name a global variable", "undeclared-name")
              .range(v->name.range);
        } else if (g->var) {
          if (!g->type) g->type = resolveType(g->var->type, Context{nullptr, &global_});
          if (g->type != s->type && !g->type->isError() && !s->type->isError())
            diags_.error(v->type->range.begin, "VAR_EXTERNAL '" + v->name.name + "' has type '" + s->type->name + "' but the global has type '" +
                                                   g->type->name + "'", "type-mismatch")
                .range(v->type->range).note(g->declRange.begin, "global declared here", g->declRange);
          else g->var->used = true;
          s->aliasOf = g;
        }
      }
      if (isFunction && v->section == VarSection::Stat) {
        // fine: CODESYS VAR_STAT in functions keeps its value between calls
      }
    }
  }
  // Property SET: the value is read through the property's own name.
  if (d->pouKind == PouKind::PropertySet && pi.owner) {
    Symbol* prop = pi.owner->pou->members->lookupLocal(upperCase(d->owner->name.parts.back().name));
    if (prop) {
      Symbol* val = newSymbol(Symbol::Variable, prop->name, prop->declRange);
      val->type = prop->pou->returnType;
      pi.vars->add(val);
    }
  }
  // Initial values (after all variables, so they can refer to constants).
  for (VarBlock& b : d->varBlocks)
    for (VarDecl* v : b.vars) {
      if (v->type && v->type->fbInitArgs) checkFbInitArgs(v, ctx);
      if (v->init && v->resolvedType) {
        Symbol* s = pi.vars->lookupLocal(upperCase(v->name.name));
        if (!s || s->var != v) continue;
        if (v->section == VarSection::InOut) {
          diags_.error(v->init->range.begin, "VAR_IN_OUT parameter '" + v->name.name + "' cannot have an initial value", "invalid-init")
              .range(v->init->range);
          continue;
        }
        checkVarInit(v, ctx);
      }
    }
}

// `fb : T(p := v)`: the arguments of T's FB_INIT (CODESYS V3), matched by
// name with the inputs of the FB_INIT methods along T's EXTENDS chain.
void SemaImpl::checkFbInitArgs(VarDecl* v, const Context& ctx) {
  StructInitExpr* args = v->type ? v->type->fbInitArgs : nullptr;
  const Type* t = v->resolvedType;
  if (!args || !t || t->isError()) return;
  if (t->kind != TypeKind::FunctionBlock) {
    diags_.error(args->range.begin, "arguments in a declaration are passed to FB_INIT of a function block; '" + t->name + "' is not one",
                 "call-args").range(args->range);
    return;
  }
  std::vector<Symbol*> inputs;
  for (Symbol* p = t->pou; p && p->pou; p = p->pou->base) {
    resolveSignature(p);
    Symbol* m = p->pou->members->lookupLocal("FB_INIT");
    if (!m || m->kind != Symbol::Method) continue;
    resolveSignature(m);
    for (Symbol* q : m->pou->params)
      if (q->var && q->var->section == VarSection::Input) inputs.push_back(q);
  }
  if (inputs.empty()) {
    diags_.error(args->range.begin, "'" + t->name + "' has no FB_INIT method to take these arguments", "call-args").range(args->range);
    return;
  }
  for (auto& f : args->fields) {
    Symbol* param = nullptr;
    std::vector<std::string> names;
    for (Symbol* q : inputs) {
      names.push_back(q->name);
      if (!param && upperCase(q->name) == upperCase(f.name.name)) param = q;
    }
    if (!param) {
      errorWithHint(f.name.range, "FB_INIT of '" + t->name + "' has no input named '" + f.name.name + "'", f.name.name, names, "call-args");
      continue;
    }
    checkExpr(f.value, ctx, param->type);
    checkConversion(param->type, f.value, "argument");
  }
}

// `r : REFERENCE TO T := x` and `r : REFERENCE TO T REF= x` bind r to x (as
// CODESYS does); any other initial value is an ordinary initializer.
void SemaImpl::checkVarInit(VarDecl* v, const Context& ctx) {
  const Type* t = v->resolvedType;
  if (!t->isReference()) {
    if (v->bindsReference)
      diags_.error(v->init->range.begin, "'REF=' in a declaration needs a REFERENCE TO variable, not '" + t->name + "'", "invalid-init")
          .range(v->init->range);
    else
      checkInitializer(v->init, t, ctx);
    return;
  }
  v->bindsReference = true;
  const Type* at = valueType(checkExpr(v->init, ctx, t->element));
  if (at->isError()) return;
  std::string why;
  Symbol* decl = nullptr;
  if (!isLvalue(v->init, ctx, why, &decl)) {
    diags_.error(v->init->range.begin, "a reference is bound to a variable, not " + why, "invalid-init").range(v->init->range);
    return;
  }
  Conv c = classify(at, t->element);
  if (!(c == Conv::Exact || (c == Conv::Widening && (at->kind == TypeKind::FunctionBlock || at->kind == TypeKind::Struct))))
    diags_.error(v->init->range.begin, "cannot bind '" + t->name + "' to a variable of type '" + at->name + "'", "type-mismatch")
        .range(v->init->range);
}

void SemaImpl::resolveGlobals() {
  for (auto& [gd, ctx] : globalDecls_) {
    for (VarDecl* v : gd->block.vars) {
      v->section = VarSection::Global;
      Symbol* s = ctx.outer->lookupLocal(upperCase(v->name.name));
      const Type* t = resolveType(v->type, ctx);
      v->resolvedType = t;
      if (s && s->var == v) s->type = t;
      // qualified_only globals live only in their list's scope
      for (auto& sym : symbols_)
        if (sym->var == v && !sym->type) sym->type = t;
      if (!v->address.empty()) checkAddress(v);
    }
  }
  for (auto& [gd, ctx] : globalDecls_)
    for (VarDecl* v : gd->block.vars) {
      if (v->type && v->type->fbInitArgs) checkFbInitArgs(v, ctx);
      if (v->init && v->resolvedType) checkVarInit(v, ctx);
      else if (gd->block.isConstant && !v->init && !v->hasEmptyInit && v->resolvedType && v->resolvedType->isElementary())
        diags_.warning(v->name.range.begin, "constant '" + v->name.name + "' has no initial value; it is always the default value",
                       "uninitialized-constant").range(v->name.range);
    }
}

void SemaImpl::checkInheritance(Symbol* pou) {
  if (!pou->pou || (pou->kind != Symbol::FunctionBlock)) return;
  PouInfo& pi = *pou->pou;
  PouDecl* d = pi.decl;
  // Every interface method must be implemented (by this FB or a base).
  std::vector<Symbol*> itfs = pi.interfaces;
  for (Symbol* b = pi.base; b && b->pou; b = b->pou->base)
    for (Symbol* i : b->pou->interfaces)
      if (std::find(itfs.begin(), itfs.end(), i) == itfs.end()) itfs.push_back(i);
  for (size_t i = 0; i < itfs.size(); ++i)
    for (Symbol* b : itfs[i]->pou->interfaces)
      if (std::find(itfs.begin(), itfs.end(), b) == itfs.end()) itfs.push_back(b);
  if (!d->isAbstract) {
    for (Symbol* itf : itfs) {
      for (Symbol* m : itf->pou->members->symbols()) {
        Symbol* impl = lookupInPou(pou, upperCase(m->name), true);
        if (!impl || impl->kind != m->kind) {
          SourceRange r = d->name.range;
          diags_.error(r.begin, "function block '" + pou->name + "' does not implement " + kindName(m) + " '" + m->name + "' of interface '" +
                                    itf->name + "'", "missing-implementation")
              .range(r).note(m->declRange.begin, "declared here", m->declRange);
          continue;
        }
        // Signatures must agree: return type and parameter types in order.
        if (m->kind == Symbol::Method) {
          resolveSignature(impl);
          resolveSignature(m);
          bool same = impl->pou->returnType == m->pou->returnType && impl->pou->params.size() == m->pou->params.size();
          for (size_t k = 0; same && k < m->pou->params.size(); ++k)
            same = impl->pou->params[k]->type == m->pou->params[k]->type &&
                   impl->pou->params[k]->var->section == m->pou->params[k]->var->section;
          if (!same)
            diags_.error(impl->declRange.begin, "method '" + impl->name + "' does not match its declaration in interface '" + itf->name + "'",
                         "signature-mismatch").range(impl->declRange).note(m->declRange.begin, "interface method declared here", m->declRange);
        }
      }
    }
    // Abstract methods inherited from abstract bases must be overridden.
    for (Symbol* b = pi.base; b; b = b->pou->base)
      for (Symbol* m : b->pou->members->symbols())
        if (m->pou && m->pou->decl->isAbstract) {
          Symbol* impl = lookupInPou(pou, upperCase(m->name), true);
          if (impl == m)
            diags_.error(d->name.range.begin, "function block '" + pou->name + "' does not override abstract " + kindName(m) + " '" + m->name + "'",
                         "missing-implementation").range(d->name.range).note(m->declRange.begin, "declared here", m->declRange);
        }
  }
  // Overrides: a FINAL method cannot be overridden; signatures must match.
  for (Symbol* m : pi.members->symbols()) {
    if (!pi.base || m->kind != Symbol::Method) continue;
    Symbol* over = lookupInPou(pi.base, upperCase(m->name), true);
    if (!over || over->kind != Symbol::Method) continue;
    if (over->pou->decl->isFinal)
      diags_.error(m->declRange.begin, "method '" + m->name + "' overrides FINAL method of '" + (over->pou->owner ? over->pou->owner->name : pi.base->name) + "'",
                   "invalid-override").range(m->declRange).note(over->declRange.begin, "declared FINAL here", over->declRange);
    resolveSignature(m);
    resolveSignature(over);
    bool sameParams = m->pou->params.size() == over->pou->params.size();
    for (size_t k = 0; sameParams && k < m->pou->params.size(); ++k)
      sameParams = m->pou->params[k]->type == over->pou->params[k]->type && m->pou->params[k]->var && over->pou->params[k]->var &&
                   m->pou->params[k]->var->section == over->pou->params[k]->var->section;
    if (m->pou->returnType != over->pou->returnType || !sameParams)
      diags_.error(m->declRange.begin, "method '" + m->name + "' does not match the method it overrides", "signature-mismatch")
          .range(m->declRange).note(over->declRange.begin, "overridden method declared here", over->declRange);
  }
}

}  // namespace stc::sema
