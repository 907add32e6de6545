// The typed abstract syntax tree.  Built by compiler/parse from the ANTLR
// parse tree; annotated in place by compiler/sema (types, resolved symbols,
// constant values).  Nodes are owned by an ASTContext arena and refer to each
// other with plain pointers.  LLVM-style RTTI: each node has a kind, and
// isa<>/dyn_cast<> below test it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "basic/SourceManager.h"

namespace stc {
namespace sema { class Type; struct Symbol; }

namespace ast {

template <typename T, typename N> bool isa(const N* n) { return n && T::classof(n); }
template <typename T, typename N> T* dyn_cast(N* n) { return isa<T>(n) ? static_cast<T*>(n) : nullptr; }
template <typename T, typename N> const T* dyn_cast(const N* n) { return isa<T>(n) ? static_cast<const T*>(n) : nullptr; }
template <typename T, typename N> T* cast(N* n) { return static_cast<T*>(n); }
template <typename T, typename N> const T* cast(const N* n) { return static_cast<const T*>(n); }

struct Node {
  virtual ~Node() = default;
  SourceRange range;
};

// A name as written (original spelling kept for messages) with its location.
struct Ident {
  std::string name;
  SourceRange range;
  bool empty() const { return name.empty(); }
};

// `A.B.C`: namespace / type / POU references.
struct QualifiedName {
  std::vector<Ident> parts;
  SourceRange range;
  std::string str() const;
};

struct Pragma {
  std::string name;    // attribute name, e.g. "qualified_only"
  std::string value;   // optional value
  SourceRange range;
};

// The attribute `name` (case-insensitive) among `attrs`, or null.
const Pragma* findAttribute(const std::vector<Pragma>& attrs, std::string_view name);
inline bool hasAttribute(const std::vector<Pragma>& attrs, std::string_view name) { return findAttribute(attrs, name) != nullptr; }

// ---------------------------------------------------------------- expressions
struct Expr : Node {
  enum Kind {
    Literal, Name, Member, Index, Deref, Call, Unary, Binary, This, Super, DirectAddress,
    ArrayInit, StructInit
  };
  explicit Expr(Kind k) : kind(k) {}
  Kind kind;
  // Filled by sema.
  const sema::Type* type = nullptr;
};

struct LiteralExpr : Expr {
  enum LitKind { Int, Real, Bool, String, WString, Time, Date, TimeOfDay, DateTime, Enum };
  LiteralExpr() : Expr(Literal) {}
  static bool classof(const Expr* e) { return e->kind == Literal; }
  LitKind litKind = Int;
  bool isLong = false;          // LTIME, LDATE, LTOD, LDT
  bool negative = false;        // typed literal with '-' (INT#-5)
  uint64_t intValue = 0;        // Int, Bool; Time in ns (two's complement); dates: ns since 1970
  double realValue = 0;
  std::string text;             // decoded String/WString value (UTF-8); enum value name
  Ident typePrefix;             // INT#, Color#; empty when untyped
};

struct NameExpr : Expr {
  NameExpr() : Expr(Name) {}
  static bool classof(const Expr* e) { return e->kind == Name; }
  Ident ident;
  sema::Symbol* symbol = nullptr;   // resolved by sema
};

struct MemberExpr : Expr {
  MemberExpr() : Expr(Member) {}
  static bool classof(const Expr* e) { return e->kind == Member; }
  Expr* base = nullptr;
  Ident member;                 // member name, or the bit number for x.3 / x.%X3
  enum Access { Field, Bit, PartialBit, PartialByte, PartialWord, PartialDWord } access = Field;
  unsigned bitIndex = 0;
  sema::Symbol* symbol = nullptr;   // resolved member, enum value, global ...
};

struct IndexExpr : Expr {
  IndexExpr() : Expr(Index) {}
  static bool classof(const Expr* e) { return e->kind == Index; }
  Expr* base = nullptr;
  std::vector<Expr*> indices;
};

struct DerefExpr : Expr {
  DerefExpr() : Expr(Deref) {}
  static bool classof(const Expr* e) { return e->kind == Deref; }
  Expr* base = nullptr;
};

struct Argument {
  enum Kind { Positional, Input, Output } kind = Positional;
  Ident name;                   // for Input / Output
  bool negated = false;         // NOT Q => x
  Expr* value = nullptr;        // null for empty `PT := ,` / `Q => )`
  SourceRange range;
  sema::Symbol* param = nullptr;   // the parameter it binds to (sema)
};

struct CallExpr : Expr {
  CallExpr() : Expr(Call) {}
  static bool classof(const Expr* e) { return e->kind == Call; }
  Expr* callee = nullptr;
  std::vector<Argument> args;
  SourceRange parenRange;
  sema::Symbol* target = nullptr;    // resolved function / FB / method / action
  std::vector<Expr*> orderedArgs;    // builtins: the arguments by position, after named binding (sema)
};

enum class UnaryOp { Neg, Plus, Not };
enum class BinaryOp {
  Pow, Mul, Div, Mod, Add, Sub, Lt, Gt, Le, Ge, Eq, Ne, And, AndThen, Xor, Or, OrElse
};
const char* spelling(UnaryOp op);
const char* spelling(BinaryOp op);

struct UnaryExpr : Expr {
  UnaryExpr() : Expr(Unary) {}
  static bool classof(const Expr* e) { return e->kind == Unary; }
  UnaryOp op = UnaryOp::Neg;
  Expr* operand = nullptr;
  SourceLoc opLoc;
};

struct BinaryExpr : Expr {
  BinaryExpr() : Expr(Binary) {}
  static bool classof(const Expr* e) { return e->kind == Binary; }
  BinaryOp op = BinaryOp::Add;
  Expr* lhs = nullptr;
  Expr* rhs = nullptr;
  SourceLoc opLoc;
  // The type both operands are converted to before the operation (sema);
  // differs from `type` for comparisons, whose result is BOOL.
  const sema::Type* operandType = nullptr;
};

struct ThisExpr : Expr {
  ThisExpr() : Expr(This) {}
  static bool classof(const Expr* e) { return e->kind == This; }
};

struct SuperExpr : Expr {
  SuperExpr() : Expr(Super) {}
  static bool classof(const Expr* e) { return e->kind == Super; }
};

// %IX0.1 etc.  `area` I/Q/M, `size` X/B/W/D/L (X when absent for bit addresses).
struct DirectAddressExpr : Expr {
  DirectAddressExpr() : Expr(DirectAddress) {}
  static bool classof(const Expr* e) { return e->kind == DirectAddress; }
  std::string text;
};

struct ArrayInitExpr : Expr {
  ArrayInitExpr() : Expr(ArrayInit) {}
  static bool classof(const Expr* e) { return e->kind == ArrayInit; }
  struct Element {
    Expr* value = nullptr;      // null for `3()`
    uint64_t repeat = 1;
    bool repeated = false;
    SourceRange range;
  };
  std::vector<Element> elements;
};

struct StructInitExpr : Expr {
  StructInitExpr() : Expr(StructInit) {}
  static bool classof(const Expr* e) { return e->kind == StructInit; }
  struct Field {
    Ident name;
    Expr* value = nullptr;
  };
  std::vector<Field> fields;
};

// ---------------------------------------------------------------- type syntax
struct VarDecl;
struct StructInitExpr;

struct EnumValueDecl {
  Ident name;
  Expr* value = nullptr;
  int64_t resolved = 0;         // filled by sema
};

struct TypeRef : Node {
  enum Kind { Named, Sized, Subrange, Array, Pointer, Reference, Enum, Struct, Union };
  explicit TypeRef(Kind k) : kind(k) {}
  Kind kind;
  QualifiedName name;                       // Named, Sized, Subrange (base), Enum (base type, may be empty)
  Expr* size = nullptr;                     // Sized: STRING(n)
  Expr* lo = nullptr;                       // Subrange
  Expr* hi = nullptr;
  struct Dim { Expr* lo = nullptr; Expr* hi = nullptr; bool star = false; SourceRange range; };
  std::vector<Dim> dims;                    // Array
  TypeRef* element = nullptr;               // Array, Pointer, Reference
  bool refTo = false;                       // REF_TO (vs REFERENCE TO)
  std::vector<EnumValueDecl> enumValues;    // Enum
  std::vector<VarDecl*> members;            // Struct, Union
  QualifiedName structBase;                 // STRUCT EXTENDS
  const sema::Type* resolved = nullptr;
  const struct TypeDecl* aliasDecl = nullptr;   // Named: the TYPE declaration it names, if any (sema)
  struct StructInitExpr* fbInitArgs = nullptr;  // Named: `fb : T(p := v)`, the FB_INIT arguments
};

// ---------------------------------------------------------------- statements
struct Stmt : Node {
  enum Kind { Assign, ExprS, If, Case, For, While, Repeat, Exit, Continue, Return, Jmp, Label, Empty };
  explicit Stmt(Kind k) : kind(k) {}
  Kind kind;
};

struct AssignStmt : Stmt {
  AssignStmt() : Stmt(Assign) {}
  static bool classof(const Stmt* s) { return s->kind == Assign; }
  enum Op { Normal, Ref, Set, Reset } op = Normal;
  Expr* lhs = nullptr;
  Expr* rhs = nullptr;
  SourceLoc opLoc;
};

struct ExprStmt : Stmt {
  ExprStmt() : Stmt(ExprS) {}
  static bool classof(const Stmt* s) { return s->kind == ExprS; }
  Expr* expr = nullptr;
};

struct IfStmt : Stmt {
  IfStmt() : Stmt(If) {}
  static bool classof(const Stmt* s) { return s->kind == If; }
  struct Branch { Expr* cond = nullptr; std::vector<Stmt*> body; };
  std::vector<Branch> branches;       // IF and ELSIFs
  std::vector<Stmt*> elseBody;
  bool hasElse = false;
};

struct CaseStmt : Stmt {
  CaseStmt() : Stmt(Case) {}
  static bool classof(const Stmt* s) { return s->kind == Case; }
  struct Label { Expr* lo = nullptr; Expr* hi = nullptr; SourceRange range; };
  struct Element { std::vector<Label> labels; std::vector<Stmt*> body; };
  Expr* selector = nullptr;
  std::vector<Element> elements;
  std::vector<Stmt*> elseBody;
  bool hasElse = false;
};

struct ForStmt : Stmt {
  ForStmt() : Stmt(For) {}
  static bool classof(const Stmt* s) { return s->kind == For; }
  NameExpr* var = nullptr;
  Expr* from = nullptr;
  Expr* to = nullptr;
  Expr* by = nullptr;
  std::vector<Stmt*> body;
};

struct WhileStmt : Stmt {
  WhileStmt() : Stmt(While) {}
  static bool classof(const Stmt* s) { return s->kind == While; }
  Expr* cond = nullptr;
  std::vector<Stmt*> body;
};

struct RepeatStmt : Stmt {
  RepeatStmt() : Stmt(Repeat) {}
  static bool classof(const Stmt* s) { return s->kind == Repeat; }
  std::vector<Stmt*> body;
  Expr* cond = nullptr;
};

struct SimpleStmt : Stmt {   // EXIT, CONTINUE, RETURN, empty
  explicit SimpleStmt(Kind k) : Stmt(k) {}
  static bool classof(const Stmt* s) {
    return s->kind == Exit || s->kind == Continue || s->kind == Return || s->kind == Empty;
  }
};

struct JmpStmt : Stmt {
  JmpStmt() : Stmt(Jmp) {}
  static bool classof(const Stmt* s) { return s->kind == Jmp; }
  Ident target;
};

struct LabelStmt : Stmt {
  LabelStmt() : Stmt(Label) {}
  static bool classof(const Stmt* s) { return s->kind == Label; }
  Ident label;
  Stmt* stmt = nullptr;
};

// ---------------------------------------------------------------- declarations
enum class VarSection { Var, Input, Output, InOut, Temp, Stat, Inst, Global, External, Access, Config };
const char* spelling(VarSection s);

struct VarDecl : Node {
  Ident name;
  TypeRef* type = nullptr;       // shared between the names of `a, b : INT`
  Expr* init = nullptr;
  bool hasEmptyInit = false;     // `x : INT := ;` (CODESYS input assistant)
  std::string address;           // AT %IX0.1
  SourceRange addressRange;
  VarSection section = VarSection::Var;
  bool isConstant = false, isRetain = false, isPersistent = false, isNonRetain = false;
  enum Edge : uint8_t { NoEdge, RisingEdge, FallingEdge } edge = NoEdge;   // VAR_INPUT x : BOOL R_EDGE
  bool bindsReference = false;   // `r : REFERENCE TO T REF= x` (or := x): init is the bound variable
  std::vector<Pragma> attributes;
  // Filled by sema.
  const sema::Type* resolvedType = nullptr;
  bool used = false;
  // A constant whose value is its initialiser: VAR CONSTANT, VAR_GLOBAL CONSTANT.
  // VAR_INPUT CONSTANT is not: it is an input the POU may not write, and callers
  // pass it like any input (CODESYS; OSCAT's setup parameters).
  bool isFoldableConstant() const {
    return isConstant && init && section != VarSection::Input && section != VarSection::InOut;
  }
};

struct VarBlock {
  VarSection section = VarSection::Var;
  bool isConstant = false, isRetain = false, isPersistent = false, isNonRetain = false;
  std::vector<VarDecl*> vars;
  SourceRange range;
};

struct Decl : Node {
  enum Kind { TypeD, Pou, GlobalVars, Configuration, Namespace };
  explicit Decl(Kind k) : kind(k) {}
  Kind kind;
  std::vector<Pragma> attributes;
};

struct TypeDecl : Decl {
  TypeDecl() : Decl(TypeD) {}
  static bool classof(const Decl* d) { return d->kind == TypeD; }
  Ident name;
  TypeRef* def = nullptr;
  Expr* init = nullptr;
  const sema::Type* resolved = nullptr;
};

enum class PouKind { Program, Function, FunctionBlock, Method, Property, Action, Interface, PropertyGet, PropertySet };
const char* spelling(PouKind k);
enum class Access { Default, Public, Private, Protected, Internal };

struct PouDecl : Decl {
  PouDecl() : Decl(Pou) {}
  static bool classof(const Decl* d) { return d->kind == Pou; }
  PouKind pouKind = PouKind::Program;
  QualifiedName name;            // methods/actions at top level: Owner.Name
  Access access = Access::Default;
  bool isAbstract = false, isFinal = false;
  TypeRef* returnType = nullptr; // FUNCTION, METHOD, PROPERTY
  QualifiedName extends;         // FUNCTION_BLOCK EXTENDS / INTERFACE EXTENDS (first)
  std::vector<QualifiedName> implements;   // IMPLEMENTS; INTERFACE EXTENDS list
  std::vector<VarBlock> varBlocks;
  std::vector<PouDecl*> methods, properties, actions;
  PouDecl* getter = nullptr;     // PROPERTY accessors
  PouDecl* setter = nullptr;
  std::vector<Stmt*> body;
  bool hasBody = true;           // interface prototypes have none
  SourceRange endRange;          // END_xxx keyword
  PouDecl* owner = nullptr;      // method/action/property → FB/program; accessor → property
  // Filled by sema.
  sema::Symbol* symbol = nullptr;
};

struct GlobalVarDecl : Decl {
  GlobalVarDecl() : Decl(GlobalVars) {}
  static bool classof(const Decl* d) { return d->kind == GlobalVars; }
  VarBlock block;
  Ident listName;                // GVL name (file stem in projects), for GVL.x
};

struct TaskDecl {
  Ident name;
  struct Init { Ident name; Expr* value = nullptr; };
  std::vector<Init> inits;
  SourceRange range;
};

struct ProgramConfig {
  Ident name;
  Ident task;
  QualifiedName type;
  std::vector<Argument> args;
  bool retain = false, nonRetain = false;
  SourceRange range;
};

struct ResourceDecl {
  Ident name;
  Ident on;
  std::vector<VarBlock> globals;
  std::vector<TaskDecl> tasks;
  std::vector<ProgramConfig> programs;
  SourceRange range;
};

struct ConfigurationDecl : Decl {
  ConfigurationDecl() : Decl(Configuration) {}
  static bool classof(const Decl* d) { return d->kind == Configuration; }
  Ident name;
  std::vector<VarBlock> globals;
  std::vector<ResourceDecl> resources;     // an implicit one when RESOURCE is omitted
  struct ConfigVar { QualifiedName path; std::string address; TypeRef* type = nullptr; Expr* init = nullptr; SourceRange range; };
  std::vector<ConfigVar> configVars;
};

struct NamespaceDecl : Decl {
  NamespaceDecl() : Decl(Namespace) {}
  static bool classof(const Decl* d) { return d->kind == Namespace; }
  QualifiedName name;
  std::vector<Decl*> decls;
};

// One parsed source file.
struct SourceUnit {
  uint32_t file = 0;
  std::vector<Decl*> decls;
};

// Owns every node.  One per compilation.
class ASTContext {
public:
  template <typename T, typename... Args> T* make(Args&&... args) {
    auto p = std::make_unique<T>(std::forward<Args>(args)...);
    T* raw = p.get();
    nodes_.push_back(std::move(p));
    return raw;
  }
  std::vector<SourceUnit>& units() { return units_; }
  size_t nodeCount() const { return nodes_.size(); }
  // Takes over the nodes and units of a context filled on another thread.
  void adopt(ASTContext&& other) {
    nodes_.reserve(nodes_.size() + other.nodes_.size());
    for (auto& n : other.nodes_) nodes_.push_back(std::move(n));
    for (auto& u : other.units_) units_.push_back(std::move(u));
    other.nodes_.clear();
    other.units_.clear();
  }

private:
  std::vector<std::unique_ptr<Node>> nodes_;
  std::vector<SourceUnit> units_;
};

}  // namespace ast
}  // namespace stc
