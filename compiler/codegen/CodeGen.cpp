#include <llvm/IR/Verifier.h>
#include <llvm/Support/raw_ostream.h>

#include "basic/Text.h"
#include <algorithm>

#include "codegen/CGInternal.h"

namespace stc::codegen {

using namespace stc::ast;

// The largest stack frame a POU may declare (locals, VAR_TEMP, input copies).
constexpr uint64_t kMaxFrameBytes = 256 * 1024;

const char* faultCode(FaultKind k) {
  switch (k) {
    case FaultKind::DivisionByZero: return "fault-division-by-zero";
    case FaultKind::Index: return "fault-index";
    case FaultKind::Subrange: return "fault-subrange";
    case FaultKind::NullPointer: return "fault-null-pointer";
    case FaultKind::NullReference: return "fault-null-reference";
    case FaultKind::NullInterface: return "fault-null-interface";
    case FaultKind::UnboundInOut: return "fault-unbound-in-out";
    case FaultKind::ForStepZero: return "fault-for-step-zero";
    case FaultKind::StringIndex: return "fault-string-index";
    case FaultKind::BadVtable: return "fault-bad-vtable";
    case FaultKind::PointerRange: return "fault-pointer-range";
  }
  return "fault";
}

const ImageRoot* ImageMap::find(const std::string& upperPath) const {
  for (const ImageRoot& r : roots)
    if (asciiUpper(r.path) == upperPath) return &r;
  return nullptr;
}

CompiledModule::CompiledModule(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CompiledModule::~CompiledModule() = default;

CodeGen::CodeGen(const sema::Model& model, const SourceManager& sm, DiagnosticsEngine& diags, const CodegenOptions& opts,
                 llvm::LLVMContext& ctx, llvm::Module& mod, CompiledModule& out)
    : model_(model), layout_(*model.layout), sm_(sm), diags_(diags), opts_(opts), ctx_(ctx), mod_(mod), out_(out), b_(ctx) {
  ptrTy_ = llvm::PointerType::get(ctx, 0);
  i1_ = llvm::Type::getInt1Ty(ctx);
  i8_ = llvm::Type::getInt8Ty(ctx);
  i16_ = llvm::Type::getInt16Ty(ctx);
  i32_ = llvm::Type::getInt32Ty(ctx);
  i64_ = llvm::Type::getInt64Ty(ctx);
  // CODESYS computes integer temporaries in the target's register width.
  if (sema::dialectAllows(model.dialect, sema::DialectRule::RegisterWidthTemporaries)) registerBits_ = model.addressBits == 64 ? 64 : 32;
  out_.sites.emplace_back();   // site 0: unknown
  // A library (no PROGRAM to run) keeps every POU: with internal linkage the
  // optimiser would delete them all, since nothing calls them.
  libraryMode_ = std::none_of(model.pous.begin(), model.pous.end(), [](const Symbol* p) { return p->kind == Symbol::Program; });
}

// Deeper loop nests are compiled without optimisation (see emitPouBody).
constexpr size_t kMaxOptimisedLoopDepth = 64;
// Long bodies are lowered in parts of this many top-level statements.
constexpr size_t kStatementsPerPart = 128;

// Whether RETURN, JMP or a label appears anywhere in `body` (they cannot cross
// the functions a long body is split into).
bool transfersControl(const std::vector<Stmt*>& body) {
  for (const Stmt* s : body) {
    if (!s) continue;
    switch (s->kind) {
      case Stmt::Return: case Stmt::Jmp: case Stmt::Label: return true;
      case Stmt::If: {
        auto* i = cast<IfStmt>(s);
        for (const auto& b : i->branches) if (transfersControl(b.body)) return true;
        if (transfersControl(i->elseBody)) return true;
        break;
      }
      case Stmt::Case: {
        auto* c = cast<CaseStmt>(s);
        for (const auto& e : c->elements) if (transfersControl(e.body)) return true;
        if (transfersControl(c->elseBody)) return true;
        break;
      }
      case Stmt::For: if (transfersControl(cast<ForStmt>(s)->body)) return true; break;
      case Stmt::While: if (transfersControl(cast<WhileStmt>(s)->body)) return true; break;
      case Stmt::Repeat: if (transfersControl(cast<RepeatStmt>(s)->body)) return true; break;
      default: break;
    }
  }
  return false;
}

void CodeGen::error(SourceRange r, const std::string& msg) {
  ++errors_;
  if (folding_) return;   // a failed fold attempt: the value is computed at run time instead
  diags_.error(r.begin, msg, "codegen").range(r);
}

// ------------------------------------------------------------------ types

const Type* CodeGen::strip(const Type* t) {
  while (t && (t->kind == TypeKind::Enum || t->kind == TypeKind::Subrange) && t->element) t = t->element;
  return t;
}

bool CodeGen::isAggregate(const Type* t) const {
  switch (strip(t)->kind) {
    case TypeKind::String: case TypeKind::WString: case TypeKind::Array: case TypeKind::Struct: case TypeKind::Union:
    case TypeKind::FunctionBlock: case TypeKind::Program: case TypeKind::Interface:
      return true;
    default:
      return false;
  }
}

llvm::Type* CodeGen::valueType(const Type* t) {
  t = strip(t);
  switch (t->kind) {
    case TypeKind::Bool: case TypeKind::Bit: return i1_;
    case TypeKind::Real: return llvm::Type::getFloatTy(ctx_);
    case TypeKind::LReal: return llvm::Type::getDoubleTy(ctx_);
    case TypeKind::Pointer: case TypeKind::Reference: case TypeKind::Null: return ptrTy_;
    case TypeKind::Void: return llvm::Type::getVoidTy(ctx_);
    default:
      if (t->isElementary()) return llvm::IntegerType::get(ctx_, t->bits());
      return ptrTy_;   // aggregates are handled by address
  }
}

llvm::Type* CodeGen::memType(const Type* t) {
  const Type* s = strip(t);
  if (s->isBool()) return i8_;
  if (isAggregate(s)) return llvm::ArrayType::get(i8_, sizeOf(s));
  if (narrowSlot(s)) return i32_;
  return valueType(s);
}

// ------------------------------------------------------------------ POUs

bool CodeGen::isNative(const Symbol* pou) const {
  const PouDecl* d = pou && pou->pou ? pou->pou->decl : nullptr;
  if (!d) return false;
  for (const Pragma& p : d->attributes)
    if (equalsIgnoreCase(p.name, "native")) return true;
  // Accessors and methods of a native FB are native too.
  if (pou->pou->owner && pou->pou->owner != pou) return isNative(pou->pou->owner);
  return false;
}

Symbol* CodeGen::ownerOf(Symbol* pou) const {
  if (!pou || !pou->pou) return nullptr;
  if (pou->kind == Symbol::FunctionBlock || pou->kind == Symbol::Program) return pou;
  return pou->pou->owner;
}

const std::vector<Symbol*>& CodeGen::paramsOf(Symbol* pou) {
  auto it = params_.find(pou);
  if (it != params_.end()) return it->second;
  std::vector<Symbol*> chain, params;
  for (Symbol* p = pou; p && p->pou && chain.size() < 64; p = p->kind == Symbol::FunctionBlock ? p->pou->base : nullptr) chain.push_back(p);
  for (auto c = chain.rbegin(); c != chain.rend(); ++c)
    for (Symbol* p : (*c)->pou->params) params.push_back(p);
  return params_[pou] = params;
}

// Accessors of interface properties are never analysed as bodies: their
// types come from the property.
static Symbol* propertyOf(Symbol* accessor) {
  const PouDecl* d = accessor->pou ? accessor->pou->decl : nullptr;
  if (!d || (d->pouKind != PouKind::PropertyGet && d->pouKind != PouKind::PropertySet) || !accessor->pou->owner) return nullptr;
  return accessor->pou->owner->pou->members->lookupLocal(asciiUpper(d->owner->name.parts.back().name));
}

const Type* CodeGen::returnTypeOf(Symbol* pou) {
  if (Symbol* prop = propertyOf(pou)) {
    if (pou->pou->decl->pouKind == PouKind::PropertySet) return model_.types->voidType();
    return prop->pou->returnType ? prop->pou->returnType : prop->type;
  }
  return pou->pou->returnType;
}

bool CodeGen::returnsIndirect(Symbol* pou) {
  const Type* r = returnTypeOf(pou);
  return r && r->kind != TypeKind::Void && isAggregate(r);
}

static bool hasThis(const Symbol* pou) {
  return pou->kind == Symbol::Method || pou->kind == Symbol::Action || pou->kind == Symbol::FunctionBlock || pou->kind == Symbol::Program;
}

// The setter's value: the variable of the property's own name without a declaration.
static Symbol* setterValue(Symbol* pou) {
  if (!pou->pou || !pou->pou->decl || pou->pou->decl->pouKind != PouKind::PropertySet) return nullptr;
  for (Symbol* s : pou->pou->vars->symbols())
    if (s->kind == Symbol::Variable && !s->var) return s;
  return nullptr;
}

llvm::FunctionType* CodeGen::signatureOf(Symbol* pou) {
  std::vector<llvm::Type*> params;
  llvm::Type* ret = llvm::Type::getVoidTy(ctx_);
  if (pou->kind == Symbol::FunctionBlock || pou->kind == Symbol::Program || pou->kind == Symbol::Action)
    return llvm::FunctionType::get(ret, {ptrTy_}, false);
  const Type* rt = returnTypeOf(pou);
  if (returnsIndirect(pou)) params.push_back(ptrTy_);
  else if (rt && rt->kind != TypeKind::Void) ret = valueType(rt);
  if (hasThis(pou)) params.push_back(ptrTy_);
  for (Symbol* p : pou->pou->params) {
    VarSection sec = p->var->section;
    if (sec == VarSection::Input && !isAggregate(p->type)) params.push_back(valueType(p->type));
    else params.push_back(ptrTy_);
  }
  if (pou->pou->decl && pou->pou->decl->pouKind == PouKind::PropertySet)
    if (Symbol* prop = propertyOf(pou)) {
      const Type* vt = prop->pou->returnType ? prop->pou->returnType : prop->type;
      params.push_back(isAggregate(vt) ? ptrTy_ : valueType(vt));
    }
  return llvm::FunctionType::get(ret, params, false);
}

static std::string qualifiedName(const Symbol* s) {
  std::string n = s->name;
  for (const Symbol* ns = s->parentNamespace; ns; ns = ns->parentNamespace) n = ns->name + "." + n;
  return n;
}

llvm::Function* CodeGen::functionFor(Symbol* pou) {
  auto it = functions_.find(pou);
  if (it != functions_.end()) return it->second;
  std::string name = "st.";
  if (Symbol* owner = pou->pou->owner) name += qualifiedName(owner) + ".";
  const PouDecl* d = pou->pou->decl;
  if (d && d->pouKind == PouKind::PropertyGet) name += "__get_" + d->owner->name.parts.back().name;
  else if (d && d->pouKind == PouKind::PropertySet) name += "__set_" + d->owner->name.parts.back().name;
  else name += pou->pou->owner ? pou->name : qualifiedName(pou);
  bool native = isNative(pou);
  bool hasBody = d && d->hasBody && !d->isAbstract;
  // Library mode keeps the user's POUs, not the built-in libraries' ("<stdlib>/...").
  bool userSource = pou->declRange.begin.valid() && sm_.file(pou->declRange.begin.file).path.rfind("<stdlib>", 0) != 0;
  bool exported = userSource && ((opts_.exportFunctions && pou->kind == Symbol::Function) || libraryMode_);
  auto linkage = (native || !hasBody || exported) ? llvm::Function::ExternalLinkage : llvm::Function::InternalLinkage;
  if (native) name = "native." + name.substr(3);
  llvm::Function* f = llvm::Function::Create(signatureOf(pou), linkage, name, mod_);
  // Small integer parameters follow the System V convention (what C++ natives expect).
  unsigned i = 0;
  for (llvm::Argument& a : f->args()) {
    (void)a;
    ++i;
  }
  auto extAttr = [&](const Type* t) {
    const Type* s = strip(t);
    if (!s->isElementary() || s->bits() >= 32 || s->isReal()) return llvm::Attribute::None;
    return s->isSignedInt() ? llvm::Attribute::SExt : llvm::Attribute::ZExt;
  };
  unsigned idx = 0;
  if (!(pou->kind == Symbol::FunctionBlock || pou->kind == Symbol::Program || pou->kind == Symbol::Action)) {
    if (returnsIndirect(pou)) ++idx;
    else if (returnTypeOf(pou) && returnTypeOf(pou)->kind != TypeKind::Void)
      if (auto a = extAttr(returnTypeOf(pou)); a != llvm::Attribute::None) f->addRetAttr(a);
    if (hasThis(pou)) ++idx;
    for (Symbol* p : pou->pou->params) {
      if (p->var->section == VarSection::Input && !isAggregate(p->type))
        if (auto a = extAttr(p->type); a != llvm::Attribute::None) f->addParamAttr(idx, a);
      ++idx;
    }
  }
  if (native) out_.natives.push_back({name, pou->pou->owner ? pou->pou->owner->name + "." + pou->name : pou->name, layout_.pouHash(pou),
                                      pou->declRange});
  functions_[pou] = f;
  return f;
}

void CodeGen::beginFunction(FnState& st, llvm::Function* f) {
  st.fn = f;
  fs_ = &st;
  // Allocas go to their own entry block, which falls through to the code.
  auto* entry = llvm::BasicBlock::Create(ctx_, "entry", f);
  auto* code = llvm::BasicBlock::Create(ctx_, "code", f);
  st.allocaBuilderStorage = std::make_unique<llvm::IRBuilder<>>(entry);
  st.allocaBuilderStorage->CreateBr(code);
  st.allocaBuilderStorage->SetInsertPoint(entry->getTerminator());
  st.allocaBuilder = st.allocaBuilderStorage.get();
  b_.SetInsertPoint(code);
  b_.SetCurrentDebugLocation(llvm::DebugLoc());
}

// A program or FB body with thousands of statements (one call per axis) is
// lowered as a sequence of calls to `st.<POU>.__part<k>`, each holding
// kStatementsPerPart statements: LLVM's inliner and code generator take time
// that grows faster than linearly with the size of one function, so the build
// time of such a body grows linearly with its length this way.  The parts are
// not inlined back; they share the instance pointer and nothing else (bodies
// with VAR_TEMP, RETURN, JMP or labels are not split).
void CodeGen::emitBodyInParts(FnState& st, const std::vector<Stmt*>& body) {
  auto* ft = llvm::FunctionType::get(llvm::Type::getVoidTy(ctx_), {ptrTy_}, false);
  for (size_t first = 0, part = 0; first < body.size(); first += kStatementsPerPart, ++part) {
    std::vector<Stmt*> slice(body.begin() + static_cast<long>(first), body.begin() + static_cast<long>(std::min(body.size(), first + kStatementsPerPart)));
    auto* pf = llvm::Function::Create(ft, llvm::Function::InternalLinkage, st.fn->getName() + ".__part" + std::to_string(part), mod_);
    pf->addFnAttr(llvm::Attribute::NoInline);
    llvm::BasicBlock* savedBlock = b_.GetInsertBlock();
    llvm::DebugLoc savedLoc = b_.getCurrentDebugLocation();
    FnState ps;
    ps.pou = st.pou;
    beginFunction(ps, pf);
    ps.self = pf->getArg(0);
    ps.selfType = st.selfType;
    if (st.sp) ps.sp = debugFunction(pf, st.pou);
    ps.returnBlock = llvm::BasicBlock::Create(ctx_, "return", pf);
    emitStmts(slice);
    if (blockOpen()) b_.CreateBr(ps.returnBlock);
    b_.SetInsertPoint(ps.returnBlock);
    b_.CreateRetVoid();
    if (ps.hasSafepoint) safepointFns_.insert(pf);
    syncBudgetAroundCalls(ps);
    fs_ = &st;
    b_.SetInsertPoint(savedBlock);
    b_.SetCurrentDebugLocation(savedLoc);
    b_.CreateCall(pf, {st.self});
  }
}

void CodeGen::lowerPou(Symbol* pou) {
  const PouDecl* d = pou->pou->decl;
  if (!d || isNative(pou) || !d->hasBody || d->isAbstract) return;
  llvm::Function* f = functionFor(pou);
  FnState st;
  st.pou = pou;
  beginFunction(st, f);
  b_.SetCurrentDebugLocation(llvm::DebugLoc());
  st.sp = debugFunction(f, pou);
  debugLocation(pou->declRange.begin);
  auto argIt = f->arg_begin();
  bool isBody = pou->kind == Symbol::FunctionBlock || pou->kind == Symbol::Program || pou->kind == Symbol::Action;
  llvm::Value* sret = nullptr;
  if (!isBody && returnsIndirect(pou)) sret = &*argIt++;
  if (hasThis(pou)) {
    st.self = &*argIt++;
    st.self->setName("this");
    Symbol* owner = ownerOf(pou);
    st.selfType = owner ? owner->type : nullptr;
  }
  // Parameters of functions and methods.
  std::vector<std::pair<Address, const VarDecl*>> toInit;
  if (!isBody) {
    for (Symbol* p : pou->pou->params) {
      llvm::Value* a = &*argIt++;
      a->setName(p->name);
      const VarDecl* v = p->var;
      if (v->section == VarSection::Input) {
        Address slot = temporary(p->type, p->name.c_str());
        if (isAggregate(p->type)) {
          // Inputs are copies: the callee may write them.
          b_.CreateMemCpy(slot.ptr, llvm::MaybeAlign(alignOf(p->type)), a, llvm::MaybeAlign(1), sizeOf(p->type));
        } else {
          store(slot, a);
        }
        st.localDecls[v] = slot;
      } else if (v->section == VarSection::Output) {
        st.localDecls[v] = Address{a, p->type};
        toInit.push_back({Address{a, p->type}, v});
      } else {
        st.localDecls[v] = Address{a, p->type};   // VAR_IN_OUT: the caller's variable
      }
    }
    if (Symbol* v = setterValue(pou)) {
      llvm::Value* a = &*argIt++;
      Address slot = temporary(v->type, "value");
      if (isAggregate(v->type)) b_.CreateMemCpy(slot.ptr, llvm::MaybeAlign(alignOf(v->type)), a, llvm::MaybeAlign(1), sizeOf(v->type));
      else store(slot, a);
      st.locals[v] = slot;
    }
  }
  // Task stacks are 1 MiB fibers: large locals would overflow them.
  uint64_t frameBytes = 0;
  for (const VarBlock& vb : d->varBlocks)
    for (const VarDecl* v : vb.vars)
      if (v->resolvedType && (v->section == VarSection::Temp || (!isBody && (v->section == VarSection::Var || v->section == VarSection::Input))))
        frameBytes += sizeOf(v->resolvedType);
  if (frameBytes > kMaxFrameBytes) {
    error(d->name.range, "the local variables of '" + pou->name + "' take " + std::to_string(frameBytes) +
                             " bytes; a task stack holds 1 MiB: declare large arrays as VAR_GLOBAL or in a program or function block instance");
  }
  // Locals: function/method variables, VAR_TEMP everywhere.  Initialised on every call.
  for (const VarBlock& vb : d->varBlocks)
    for (const VarDecl* v : vb.vars) {
      bool local = v->section == VarSection::Temp ||
                   (!isBody && (v->section == VarSection::Var));
      if (!local || !v->resolvedType) continue;
      Address slot = temporary(v->resolvedType, v->name.name.c_str());
      st.localDecls[v] = slot;
      toInit.push_back({slot, v});
    }
  // The result variable.
  Address result;
  if (!isBody && pou->pou->result) {
    const Type* rt = pou->pou->result->type;
    result = sret ? Address{sret, rt} : temporary(rt, "result");
    st.locals[pou->pou->result] = result;
    initAt(result, nullptr);
  }
  for (auto& [addr, v] : toInit) {
    initAt(addr, v->init, v);
    // A function block local of a function or method: FB_INIT on every call.
    if (hasLifecycle(addr.type, Lifecycle::Init)) emitLifecycle(addr.ptr, addr.type, Lifecycle::Init, b_.getFalse(), fbInitArguments(v));
  }
  st.returnBlock = llvm::BasicBlock::Create(ctx_, "return", f);
  bool hasTemps = false;
  for (const VarBlock& vb : d->varBlocks) hasTemps = hasTemps || (vb.section == VarSection::Temp && !vb.vars.empty());
  if (isBody && !hasTemps && d->body.size() > kStatementsPerPart && !transfersControl(d->body)) emitBodyInParts(st, d->body);
  else emitStmts(d->body);
  if (blockOpen()) b_.CreateBr(st.returnBlock);
  b_.SetInsertPoint(st.returnBlock);
  debugLocation(d->endRange.valid() ? d->endRange.begin : pou->declRange.begin);
  if (result.ptr && !sret) b_.CreateRet(load(result));
  else b_.CreateRetVoid();
  if (st.hasSafepoint) safepointFns_.insert(f);
  syncBudgetAroundCalls(st);
  b_.SetCurrentDebugLocation(llvm::DebugLoc());
  // LLVM's loop passes take time cubic in the nesting depth (10,000 nested
  // WHILE would take hours): such a body is compiled without optimisation,
  // which is linear, and the user is told.
  if (st.maxLoopDepth > kMaxOptimisedLoopDepth && opts_.optLevel > 0) {
    f->addFnAttr(llvm::Attribute::OptimizeNone);
    f->addFnAttr(llvm::Attribute::NoInline);
    diags_.warning(pou->declRange.begin, "loops nested " + std::to_string(st.maxLoopDepth) + " deep in '" + pou->name +
                                             "': it is compiled without optimisation (more than " + std::to_string(kMaxOptimisedLoopDepth) +
                                             " levels)", "deep-nesting")
        .range(pou->declRange);
  }
  fs_ = nullptr;
}

// ------------------------------------------------------------------ tasks

namespace {
int64_t parseDurationNs(const Expr* e) {
  if (auto* l = dyn_cast<LiteralExpr>(e)) return static_cast<int64_t>(l->intValue);
  return -1;
}
}  // namespace

bool CodeGen::run(bool needTasks) {
  for (Symbol* pou : model_.pous)
    if (pou->pou && pou->pou->decl)
      for (const VarBlock& vb : pou->pou->decl->varBlocks)
        for (const VarDecl* v : vb.vars) varOwner_[v] = pou;
  budget_ = new llvm::GlobalVariable(mod_, i64_, false, llvm::GlobalValue::ExternalLinkage, nullptr, "__stc_budget");
  callChain_ = new llvm::GlobalVariable(mod_, ptrTy_, false, llvm::GlobalValue::ExternalLinkage, nullptr, "__stc_calls");
  beginDebugInfo();
  layoutImage();
  // Every POU body, then the image (its initialiser may refer to vtables and functions).
  for (Symbol* pou : model_.pous) lowerPou(pou);
  if (errors_) return false;
  buildImage();

  // Program entries: one function per program instance.
  // One entry per program instance; a configuration's program arguments
  // (PROGRAM p WITH T : Prog(IN := x, OUT => y)) are applied around the body
  // exactly like an FB call's.
  auto programEntry = [&](const std::string& instName, Symbol* progType, uint64_t off, const std::vector<Argument>* args) {
    std::string name = "__stc_prog." + instName;
    if (auto* existing = mod_.getFunction(name)) return std::string(existing->getName());
    auto* f = llvm::Function::Create(llvm::FunctionType::get(llvm::Type::getVoidTy(ctx_), false), llvm::Function::ExternalLinkage, name, mod_);
    FnState st;
    beginFunction(st, f);
    CallExpr call;
    call.target = progType;
    if (args) call.args = *args;
    callInstance(&call, progType, imageAddr(off));
    b_.CreateRetVoid();
    fs_ = nullptr;
    return name;
  };
  // May a function reach a safepoint?  (Closure over the direct call graph.)
  std::map<llvm::Function*, bool> memo;
  std::function<bool(llvm::Function*)> maySuspend = [&](llvm::Function* f) -> bool {
    auto it = memo.find(f);
    if (it != memo.end()) return it->second;
    memo[f] = false;
    bool r = safepointFns_.count(f) || indirectCallers_.count(f) || (f->isDeclaration() && f->getName().starts_with("native."));
    for (llvm::Function* c : calls_[f]) r = r || maySuspend(c);
    return memo[f] = r;
  };

  bool haveConfig = false;
  for (ConfigurationDecl* c : model_.configurations) {
    haveConfig = true;
    for (ResourceDecl& r : c->resources) {
      std::map<std::string, size_t> taskIndex;
      for (TaskDecl& t : r.tasks) {
        TaskPlan plan;
        plan.name = t.name.name;
        plan.kind = TaskPlan::Kind::Freewheeling;
        for (auto& in : t.inits) {
          std::string key = asciiUpper(in.name.name);
          if (key == "INTERVAL") {
            plan.kind = TaskPlan::Kind::Cyclic;
            plan.intervalNs = parseDurationNs(in.value);
            if (plan.intervalNs <= 0) error(in.value->range, "task INTERVAL must be a positive TIME literal");
          } else if (key == "PRIORITY") {
            if (auto* l = dyn_cast<LiteralExpr>(in.value)) plan.priority = static_cast<int>(l->intValue);
          } else if (key == "SINGLE") {
            plan.kind = TaskPlan::Kind::Event;
            Address a;
            if (in.value) {
              auto saved = fs_;
              fs_ = nullptr;
              // The trigger must be a global BOOL: resolve it to its image offset.
              if (auto* n = dyn_cast<NameExpr>(in.value); n && n->symbol && n->symbol->var && imageOffsets_.count(n->symbol->var)) {
                plan.singleOffset = imageOffsets_[n->symbol->var];
                plan.singlePath = n->ident.name;
              } else {
                error(in.value->range, "task SINGLE must name a global BOOL variable");
              }
              fs_ = saved;
            }
          }
        }
        taskIndex[asciiUpper(t.name.name)] = out_.tasks.size();
        out_.tasks.push_back(plan);
      }
      for (ProgramConfig& pc : r.programs) {
        Symbol* type = nullptr;
        for (Symbol* p : model_.pous)
          if (p->kind == Symbol::Program && equalsIgnoreCase(p->name, pc.type.parts.back().name)) type = p;
        auto root = out_.image.find(asciiUpper(pc.name.name));
        if (!type || !root) continue;
        std::string entry = programEntry(pc.name.name, type, root->offset, &pc.args);
        auto ti = taskIndex.find(asciiUpper(pc.task.name));
        if (pc.task.empty() || ti == taskIndex.end()) {
          // A program without a task runs in a default cyclic task.
          TaskPlan plan;
          plan.name = pc.name.name;
          plan.intervalNs = opts_.defaultIntervalNs;
          plan.priority = 31;
          taskIndex[asciiUpper(pc.task.name)] = out_.tasks.size();
          out_.tasks.push_back(plan);
          ti = taskIndex.find(asciiUpper(pc.task.name));
        }
        out_.tasks[ti->second].entries.push_back(entry);
        out_.tasks[ti->second].programNames.push_back(pc.name.name);
      }
    }
  }
  if (!haveConfig && needTasks) {
    std::vector<Symbol*> programs, chosen;
    for (Symbol* p : model_.pous)
      if (p->kind == Symbol::Program) programs.push_back(p);
    if (!opts_.programs.empty()) {
      for (const std::string& name : opts_.programs) {
        Symbol* found = nullptr;
        for (Symbol* p : programs)
          if (equalsIgnoreCase(p->name, name)) found = p;
        if (!found) {
          std::string list;
          for (Symbol* p : programs) list += (list.empty() ? "" : ", ") + p->name;
          diags_.error(SourceLoc{}, "no PROGRAM named '" + name + "'" + (list.empty() ? "" : "; the programs are: " + list), "no-program");
          return false;
        }
        chosen.push_back(found);
      }
    } else if (programs.size() == 1) {
      chosen.push_back(programs[0]);
    } else {
      for (Symbol* p : programs)
        if (equalsIgnoreCase(p->name, "MAIN") || equalsIgnoreCase(p->name, "PLC_PRG")) chosen.push_back(p);
      if (chosen.size() != 1) {
        std::string list;
        for (Symbol* p : programs) list += (list.empty() ? "" : ", ") + p->name;
        diags_.error(SourceLoc{}, programs.empty() ? std::string("there is no PROGRAM to run")
                                                   : "several programs and no CONFIGURATION: choose with --program (" + list + ")",
                     "no-program");
        return false;
      }
    }
    TaskPlan plan;
    plan.name = "Main";
    plan.intervalNs = opts_.defaultIntervalNs;
    for (Symbol* p : chosen) {
      plan.entries.push_back(programEntry(p->name, p, programOffsets_[p], nullptr));
      plan.programNames.push_back(p->name);
    }
    out_.tasks.push_back(plan);
  }
  out_.lowMemory = model_.addressBits == 32;
  for (TaskPlan& t : out_.tasks)
    for (const std::string& e : t.entries) t.mayBlock = t.mayBlock || maySuspend(mod_.getFunction(e));
  if (errors_) return false;
  std::string err;
  llvm::raw_string_ostream os(err);
  finishVtables();
  finishDebugInfo();
  if (getenv("STC_DUMP_IR")) mod_.print(llvm::errs(), nullptr);
  if (llvm::verifyModule(mod_, &os)) {
    diags_.error(SourceLoc{}, "internal compiler error: invalid LLVM IR: " + os.str().substr(0, 2000), "codegen");
    return false;
  }
  return true;
}

std::unique_ptr<CompiledModule> generate(const sema::Model& model, const SourceManager& sm, DiagnosticsEngine& diags,
                                         const CodegenOptions& opts, bool needTasks) {
  auto impl = std::make_unique<CompiledModule::Impl>();
  impl->context = std::make_unique<llvm::LLVMContext>();
  impl->module = std::make_unique<llvm::Module>("stc", *impl->context);
  impl->optLevel = opts.optLevel;
  auto out = std::make_unique<CompiledModule>(std::move(impl));
  CodeGen cg(model, sm, diags, opts, *out->impl().context, *out->impl().module, *out);
  if (!cg.run(needTasks)) return nullptr;
  optimize(*out->impl().module, opts.optLevel);
  return out;
}

}  // namespace stc::codegen
