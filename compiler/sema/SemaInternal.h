// Internal interface of semantic analysis, shared by the Sema*.cpp files:
//   SemaDecl.cpp  - declaring symbols, resolving types and POU signatures
//   SemaExpr.cpp  - expressions, calls, conversions
//   SemaStmt.cpp  - statements, bodies, whole-program checks (recursion, unused)
//   ConstEval.cpp - constant folding for array bounds, CASE labels, enum values
//   Builtins.cpp  - the generic standard functions
#pragma once

#include <map>
#include <optional>
#include <set>
#include <unordered_map>

#include "sema/Layout.h"
#include "sema/Model.h"
#include "sema/Sema.h"
#include "sema/Symbols.h"

namespace stc::sema {

using namespace stc::ast;

struct ConstValue {
  enum Kind { Int, Real, Bool } kind = Int;
  int64_t i = 0;          // Int (as signed; ULINT beyond INT64_MAX wraps) and Bool
  bool isUnsignedBig = false;
  double r = 0;
  double asReal() const { return kind == Real ? r : static_cast<double>(i); }
};

// How one type converts implicitly to another.
enum class Conv { Exact, Widening, Narrowing, SignChange, IntBit, IntBool, EnumInt, Pointer, Incompatible };

// The lexical context an expression is checked in.
struct Context {
  Symbol* pou = nullptr;       // the POU (function, FB, method, action, accessor) or null (globals, types)
  Scope* outer = nullptr;      // namespace or global scope around it
};

// State of the body being checked.
struct BodyState {
  Symbol* pou = nullptr;
  Symbol* resultVar = nullptr;        // FUNCTION/METHOD/GET result variable
  bool resultAssigned = false;
  int loopDepth = 0;
  std::vector<std::pair<Symbol*, ForStmt*>> forVars;
  std::map<std::string, LabelStmt*> labels;
  std::vector<JmpStmt*> jumps;
};

struct Builtin {
  std::string name;
  // Checks a call and returns its type; null means "not applicable".
  const Type* (*check)(class SemaImpl& S, const Builtin& b, CallExpr* call, const Type* expected, const Context& ctx);
  int arg0 = 0, arg1 = 0;   // data for the checker (e.g. conversion source/target kinds)
};

class SemaImpl {
public:
  SemaImpl(ASTContext& ast, DiagnosticsEngine& diags, SemaOptions opts);
  bool run();

  // Whether the dialect accepts a construct (DialectRules.h).
  bool allows(DialectRule r) const { return dialectAllows(opts_.dialect, r); }
  bool strictIec() const { return opts_.dialect == Dialect::IEC; }
  bool allowsImplicit(Conv c) const;

  // ---------------------------------------------------------------- SemaDecl.cpp
  Symbol* newSymbol(Symbol::Kind k, std::string name, SourceRange r);
  bool declare(Scope& scope, Symbol* s, const char* what);
  void declareDecls(std::vector<Decl*>& decls, Scope& scope, Symbol* ns);
  Symbol* declarePou(PouDecl* d, Scope& scope, Symbol* ns);
  void attachPendingMembers();
  void declareMembers(Symbol* pou);
  void resolveTypeSymbol(Symbol* s);
  const Type* resolveType(TypeRef* t, const Context& ctx, const std::string& derivedName = "");
  const Type* resolveNamedType(const QualifiedName& q, const Context& ctx, bool report = true);
  void resolveSignature(Symbol* pou);
  void resolveVarDecl(VarDecl* v, Symbol* sym, const Context& ctx);
  void checkVarInit(VarDecl* v, const Context& ctx);
  void checkFbInitArgs(VarDecl* v, const Context& ctx);
  void resolveGlobals();
  void checkConfiguration(ConfigurationDecl* c, const Context& ctx);
  void checkAddress(VarDecl* v);
  Symbol* lookupQualified(const QualifiedName& q, Scope* from, bool report, const char* what);
  void checkInheritance(Symbol* pou);

  // ---------------------------------------------------------------- lookup
  Symbol* lookup(const std::string& upper, const Context& ctx);
  Symbol* lookupInPou(Symbol* pou, const std::string& upper, bool includeMembers = true);
  Symbol* pouMember(Symbol* pou, const std::string& upper);
  std::vector<std::string> visibleNames(const Context& ctx);
  Symbol* ownerOf(Symbol* pou);   // FB/program that a method/action/accessor belongs to

  // ---------------------------------------------------------------- SemaExpr.cpp
  const Type* checkExpr(Expr* e, const Context& ctx, const Type* expected = nullptr);
  const Type* checkName(NameExpr* e, const Context& ctx, const Type* expected);
  const Type* checkMember(MemberExpr* e, const Context& ctx, const Type* expected);
  const Type* checkIndex(IndexExpr* e, const Context& ctx);
  const Type* checkCall(CallExpr* e, const Context& ctx, const Type* expected);
  const Type* checkUnary(UnaryExpr* e, const Context& ctx, const Type* expected);
  const Type* checkBinary(BinaryExpr* e, const Context& ctx, const Type* expected);
  const Type* checkLiteral(LiteralExpr* e, const Context& ctx, const Type* expected);
  const Type* checkInitializer(Expr* init, const Type* target, const Context& ctx);
  // Entity (namespace, GVL, type, program) named by an expression, if any.
  Symbol* entityOf(Expr* e, const Context& ctx);
  const Type* callPou(CallExpr* e, Symbol* target, const Context& ctx, const std::string& displayName, bool instanceCall);
  void checkArguments(CallExpr* e, const std::vector<Symbol*>& params, const Context& ctx, const std::string& callee, bool isFunction);
  // Checks that `e` (already typed `from`) converts to `to`; reports otherwise.
  bool checkConversion(const Type* to, Expr* e, const char* what);
  Conv classify(const Type* from, const Type* to) const;
  bool literalFits(const LiteralExpr* lit, const Type* to) const;
  const Type* commonType(const Type* a, const Type* b, Expr* ea, Expr* eb, SourceLoc opLoc, const char* op);
  bool isLvalue(Expr* e, const Context& ctx, std::string& why, Symbol** declOut = nullptr);
  void checkReferenceBinding(const Type* refType, Expr* rhs, const Context& ctx, const std::string& what);
  void checkAssignTarget(Expr* lhs, const Context& ctx, BodyState* body);
  bool isUntypedLiteral(const Expr* e) const;
  const Type* valueType(const Type* t) const { return t && t->isReference() ? t->element : t; }
  std::string conversionFunction(const Type* from, const Type* to) const;
  size_t storedLength(const LiteralExpr* lit) const;
  void markUsed(Symbol* s);
  void errorWithHint(SourceRange r, const std::string& message, const std::string& name, const std::vector<std::string>& candidates,
                     const char* code);
  void recordCall(Symbol* target, SourceRange where);

  // ---------------------------------------------------------------- SemaStmt.cpp
  void checkBody(Symbol* pou);
  void checkStmts(std::vector<Stmt*>& stmts, const Context& ctx, BodyState& st);
  void checkStmt(Stmt* s, const Context& ctx, BodyState& st);
  void checkCondition(Expr* e, const Context& ctx, const char* what);
  void checkCase(CaseStmt* s, const Context& ctx, BodyState& st);
  void checkFor(ForStmt* s, const Context& ctx, BodyState& st);
  void checkRecursion();
  void checkContainmentCycles();
  bool checkAccess(Symbol* member, const Context& ctx, SourceRange where);
  bool isBareEnumValueName(Expr* e, const Context& ctx);
  void checkDivisor(BinaryExpr* e, const Context& ctx);
  void checkUnused();

  // ---------------------------------------------------------------- SemaOwnership.cpp
  // The {attribute 'static_instance'} type that `t` is or holds by value, or null.
  const Type* staticInstanceIn(const Type* t);
  std::string staticInstanceReason(const Type* t, const Type* staticType);
  // Reports copying a value of `t` (`what`: "in an assignment", ...) when it holds a static instance.
  bool checkNoStaticCopy(const Type* t, SourceRange at, const std::string& what);
  void checkStaticInstances();
  static bool isInternal(const VarDecl* v);
  // Whether an {attribute 'internal'} variable may be named here: only by the block declaring it.
  bool internalVisible(Symbol* var, const Context& ctx);
  void reportInternal(const std::string& field, const std::string& owner, SourceRange at, SourceRange declared);

  // ---------------------------------------------------------------- ConstEval.cpp
  std::optional<ConstValue> evalConst(Expr* e, const Context& ctx);
  std::optional<int64_t> evalInt(Expr* e, const Context& ctx, const char* what);
  uint64_t sizeOf(const Type* t) const;
  uint64_t alignOf(const Type* t) const;

  // ---------------------------------------------------------------- Builtins.cpp
  void registerBuiltins();
  const Builtin* findBuiltin(const std::string& upper) const;

  // ---------------------------------------------------------------- state
  Layout layout_;
  Model model_;
  ASTContext& ast_;
  DiagnosticsEngine& diags_;
  SemaOptions opts_;
  TypeContext types_;
  Scope global_;
  std::vector<std::unique_ptr<Symbol>> symbols_;
  std::vector<std::unique_ptr<Builtin>> builtins_;
  std::unordered_map<std::string, const Builtin*> builtinMap_;
  std::unordered_map<std::string, Symbol*> builtinSymbols_;
  std::unordered_map<std::string, std::vector<Symbol*>> enumValues_;   // unqualified enum values
  std::vector<Symbol*> pous_;                 // every POU with a body, in declaration order
  std::vector<Symbol*> typeSymbols_;
  std::vector<std::pair<GlobalVarDecl*, Context>> globalDecls_;
  std::vector<std::pair<ConfigurationDecl*, Context>> configs_;
  std::map<Symbol*, std::vector<std::pair<Symbol*, SourceRange>>> callGraph_;
  std::map<Symbol*, Scope*> outerScope_;      // scope each POU / type was declared in
  std::vector<std::unique_ptr<Scope>> scopes_;
  std::vector<std::pair<PouDecl*, Scope*>> pendingMembers_;
  BodyState* body_ = nullptr;                 // the body being checked, if any
  bool constEvalFailed_ = false;              // evalConst hit an already reported error
  std::vector<Symbol*> constStack_;
  bool allowUnsigned_ = false;                // evalInt may return ULINT bit patterns           // constants being evaluated (cycle reports)
  bool readingLhs_ = false;                   // checking an assignment target (properties need SET, not GET)
  Symbol* currentCaller_ = nullptr;
  std::map<const Type*, const Type*> staticIn_;   // staticInstanceIn memo
};

std::string typeName(const Type* t);

}  // namespace stc::sema
