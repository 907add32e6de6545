// Ownership attributes (docs/dialect.md, "Ownership attributes"):
//   {attribute 'static_instance'} on a FUNCTION_BLOCK or STRUCT: instances live only
//     in storage that outlives any command they start (PROGRAM and FB VAR, GVLs,
//     VAR_GLOBAL, VAR_STAT, a method's VAR_INST) and are never copied;
//   {attribute 'internal'} on a variable of a FUNCTION_BLOCK or STRUCT: the field
//     binds the instance to a native implementation and ST cannot name it from
//     outside the block that declares it.
#include "sema/SemaInternal.h"

namespace stc::sema {

namespace {

const char* kStaticInstance = "static_instance";
const char* kInternal = "internal";

const char* pouWord(const Symbol* p) {
  if (p->pou && p->pou->decl) {
    switch (p->pou->decl->pouKind) {
      case PouKind::PropertyGet: case PouKind::PropertySet: return "property accessor";
      default: break;
    }
  }
  switch (p->kind) {
    case Symbol::Function: return "FUNCTION";
    case Symbol::FunctionBlock: return "FUNCTION_BLOCK";
    case Symbol::Program: return "PROGRAM";
    case Symbol::Method: return "METHOD";
    case Symbol::Action: return "ACTION";
    default: return "POU";
  }
}

}  // namespace

bool SemaImpl::isInternal(const VarDecl* v) { return v && hasAttribute(v->attributes, kInternal); }

const Type* SemaImpl::staticInstanceIn(const Type* t) {
  while (t && t->kind == TypeKind::Array) t = t->element;
  if (!t || !(t->kind == TypeKind::Struct || t->kind == TypeKind::Union || t->kind == TypeKind::FunctionBlock)) return nullptr;
  auto it = staticIn_.find(t);
  if (it != staticIn_.end()) return it->second;
  staticIn_[t] = nullptr;   // a containment cycle (reported by checkContainmentCycles) ends here
  const Type* found = nullptr;
  if (t->kind == TypeKind::FunctionBlock) {
    int guard = 0;
    for (Symbol* p = t->pou; p && p->pou && !found && guard < 64; p = p->pou->base, ++guard) {
      if (hasAttribute(p->pou->decl->attributes, kStaticInstance)) { found = p->type; break; }
      for (VarBlock& b : p->pou->decl->varBlocks)
        for (VarDecl* v : b.vars)
          if (!found && Layout::isInstanceField(v) && v->section != VarSection::InOut) found = staticInstanceIn(v->resolvedType);
    }
  } else {
    for (const Type* s = t; s && !found; s = s->base) {
      if (s->decl && hasAttribute(s->decl->attributes, kStaticInstance)) { found = s; break; }
      for (const Member& m : s->members)
        if (!found) found = staticInstanceIn(m.type);
    }
  }
  staticIn_[t] = found;
  return found;
}

std::string SemaImpl::staticInstanceReason(const Type* t, const Type* st) {
  std::string why;
  const Type* e = t;
  while (e && e->kind == TypeKind::Array) e = e->element;
  if (e != st) why = "'" + e->name + "' contains a '" + st->name + "' instance, and ";
  const Pragma* p = nullptr;
  if (st->kind == TypeKind::FunctionBlock && st->pou && st->pou->pou) p = findAttribute(st->pou->pou->decl->attributes, kStaticInstance);
  else if (st->decl) p = findAttribute(st->decl->attributes, kStaticInstance);
  if (p && !p->value.empty()) why += p->value;
  else why += "'" + st->name + "' instances must outlive the commands they start";
  return why;
}

bool SemaImpl::checkNoStaticCopy(const Type* t, SourceRange at, const std::string& what) {
  if (!t || t->isError() || t->isReference() || t->isPointer()) return true;
  const Type* st = staticInstanceIn(t);
  if (!st) return true;
  diags_.error(at.begin, "cannot copy '" + t->name + "' " + what + ": " + staticInstanceReason(t, st) +
                             " (pass it as VAR_IN_OUT, or use a REFERENCE TO or POINTER TO it)", "static-instance").range(at);
  return false;
}

bool SemaImpl::internalVisible(Symbol* var, const Context& ctx) {
  Symbol* home = ctx.pou ? ownerOf(ctx.pou) : nullptr;
  return home && home->pou && home->pou->vars && home->pou->vars->lookupLocal(upperCase(var->name)) == var;
}

void SemaImpl::reportInternal(const std::string& field, const std::string& owner, SourceRange at, SourceRange declared) {
  auto d = diags_.error(at.begin, "'" + field + "' is internal to '" + owner + "': it binds the instance to its native implementation and "
                                      "cannot be used from ST", "internal");
  d.range(at);
  if (declared.valid()) d.note(declared.begin, "declared {attribute 'internal'} here", declared);
}

void SemaImpl::checkStaticInstances() {
  auto check = [&](Symbol* p, VarDecl* v) {
    const Type* t = v->resolvedType;
    if (!t || t->isError()) return;
    const Type* st = staticInstanceIn(t);
    if (!st) return;
    std::string head = "'" + t->name + "' instance '" + v->name.name + "' ";
    std::string where, why, fix;
    Symbol::Kind k = p->kind;
    VarSection sec = v->section;
    bool callLocal = k == Symbol::Function || k == Symbol::Method || k == Symbol::Action;
    switch (sec) {
      case VarSection::Var: case VarSection::Temp:
        if (callLocal) {
          where = std::string("cannot be declared in ") + (sec == VarSection::Temp ? "the VAR_TEMP of " : "") +
                  (k == Symbol::Function ? "a FUNCTION" : std::string("a ") + pouWord(p));
          fix = k == Symbol::Function ? "declare it in a PROGRAM, a FUNCTION_BLOCK or a GVL and pass it as VAR_IN_OUT"
                                      : "declare it in the function block's VAR or the method's VAR_INST";
        } else if (sec == VarSection::Temp) {
          where = std::string("cannot be declared in the VAR_TEMP of a ") + pouWord(p);
          why = "temporaries live only during one call";
          fix = "declare it in VAR";
        }
        break;
      case VarSection::Input: case VarSection::Output:
        where = std::string("cannot be a ") + spelling(sec) + " of a " + pouWord(p);
        why = "inputs and outputs are copies, a second instance bound to nothing";
        fix = "use VAR_IN_OUT";
        break;
      default: break;   // VAR_IN_OUT, VAR_STAT, VAR_INST, VAR_EXTERNAL, globals
    }
    if (where.empty()) return;
    diags_.error(v->name.range.begin, head + where + ": " + (why.empty() ? "" : why + "; ") + staticInstanceReason(t, st) + " (" + fix + ")",
                 "static-instance")
        .range(v->type ? SourceRange(v->name.range.begin, v->type->range.end) : v->name.range);
  };
  auto checkResult = [&](Symbol* p, PouDecl* d) {
    const Type* t = p->pou->returnType;
    if (!t || t->isError() || !d->returnType) return;
    const Type* st = staticInstanceIn(t);
    if (!st) return;
    std::string what = d->pouKind == PouKind::Property ? "PROPERTY '" + p->name + "' cannot have type '" + t->name + "'"
                                                       : std::string(pouWord(p)) + " '" + p->name + "' cannot return a '" + t->name + "' instance";
    diags_.error(d->returnType->range.begin, what + ": the result is a copy; " + staticInstanceReason(t, st) +
                                                  " (pass the instance as VAR_IN_OUT, or return a REFERENCE TO or POINTER TO it)",
                 "static-instance").range(d->returnType->range);
  };
  auto visitPou = [&](Symbol* p) {
    if (!p->pou || !p->pou->decl) return;
    PouDecl* d = p->pou->decl;
    for (VarBlock& b : d->varBlocks)
      for (VarDecl* v : b.vars) check(p, v);
    if (p->kind == Symbol::Function || (p->kind == Symbol::Method && d->pouKind == PouKind::Method)) checkResult(p, d);
    if (p->kind == Symbol::FunctionBlock || p->kind == Symbol::Program || p->kind == Symbol::Interface)
      for (Symbol* m : p->pou->members->symbols()) {
        if (m->kind == Symbol::Property && m->pou) {
          resolveSignature(m);
          checkResult(m, m->pou->decl);
        }
        // Interface prototypes are not in pous_.
        if (p->kind == Symbol::Interface && m->kind == Symbol::Method && m->pou) {
          for (VarBlock& b : m->pou->decl->varBlocks)
            for (VarDecl* v : b.vars) check(m, v);
          checkResult(m, m->pou->decl);
        }
      }
  };
  for (Symbol* p : pous_) visitPou(p);

  // The attributes where they mean nothing.
  for (Symbol* s : typeSymbols_)
    if (TypeDecl* td = s->typeDecl) {
      if (const Pragma* pr = findAttribute(td->attributes, kStaticInstance); pr && !(s->type && s->type->decl == td && s->type->isStructured()))
        diags_.warning(pr->range.begin, "{attribute 'static_instance'} applies to FUNCTION_BLOCK and STRUCT declarations only; ignored",
                       "ignored-attribute").range(pr->range);
      if (const Pragma* pr = findAttribute(td->attributes, "mirrored"); pr && !(s->type && s->type->decl == td && s->type->isStructured()))
        diags_.warning(pr->range.begin, "{attribute 'mirrored'} applies to STRUCT declarations only; ignored", "ignored-attribute").range(pr->range);
    }
  for (Symbol* p : pous_) {
    PouDecl* d = p->pou ? p->pou->decl : nullptr;
    if (!d) continue;
    if (const Pragma* pr = findAttribute(d->attributes, kStaticInstance); pr && p->kind != Symbol::FunctionBlock)
      diags_.warning(pr->range.begin, "{attribute 'static_instance'} applies to FUNCTION_BLOCK and STRUCT declarations only; ignored",
                     "ignored-attribute").range(pr->range);
    if (p->kind == Symbol::FunctionBlock) continue;
    for (VarBlock& b : d->varBlocks)
      for (VarDecl* v : b.vars)
        if (const Pragma* pr = findAttribute(v->attributes, kInternal))
          diags_.warning(pr->range.begin, "{attribute 'internal'} applies to variables of a FUNCTION_BLOCK or STRUCT only; ignored", "ignored-attribute")
              .range(pr->range);
  }
}

}  // namespace stc::sema
