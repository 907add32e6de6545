// Symbols and scopes.  Names are case-insensitive: scopes key on the
// upper-case spelling and symbols keep the declared spelling for messages.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "ast/AST.h"
#include "sema/Types.h"

namespace stc::sema {

struct Builtin;
class Scope;

struct PouInfo {
  ast::PouDecl* decl = nullptr;
  std::vector<Symbol*> params;          // VAR_INPUT, VAR_IN_OUT, VAR_OUTPUT in declaration order
  std::unique_ptr<Scope> vars;          // every variable of the POU
  std::unique_ptr<Scope> members;       // methods, properties, actions (FB, program, interface)
  const Type* returnType = nullptr;     // FUNCTION, METHOD, PROPERTY
  const Type* instanceType = nullptr;   // FUNCTION_BLOCK, PROGRAM, INTERFACE
  Symbol* base = nullptr;               // EXTENDS (FB) — interfaces: see bases
  std::vector<Symbol*> interfaces;      // IMPLEMENTS; INTERFACE EXTENDS
  Symbol* owner = nullptr;              // method/action/property -> FB/program/interface
  Symbol* result = nullptr;             // the result variable (functions, methods, GET accessors)
  bool signatureResolved = false;
  bool bodyChecked = false;
};

struct Symbol {
  enum Kind { Variable, Function, FunctionBlock, Program, Interface, Method, Property, Action,
              TypeName, EnumValue, Namespace, GlobalList, BuiltinFunction };
  Kind kind = Variable;
  std::string name;                     // declared spelling
  SourceRange declRange;
  const Type* type = nullptr;           // variable type; type of a TypeName; enum type of an EnumValue
  ast::VarDecl* var = nullptr;
  ast::TypeDecl* typeDecl = nullptr;
  int64_t enumValue = 0;
  std::unique_ptr<PouInfo> pou;         // Function ... Action
  std::unique_ptr<Scope> scope;         // Namespace / GlobalList contents
  const Builtin* builtin = nullptr;
  Symbol* parentNamespace = nullptr;
  Symbol* aliasOf = nullptr;            // VAR_EXTERNAL: the global variable it names
  bool resolving = false;               // cycle detection while resolving types / constants
  bool cyclic = false;                  // a constant on a reported definition cycle

  bool isPou() const { return kind >= Function && kind <= Action; }
  bool isCallableUnit() const { return kind == Function || kind == Method || kind == Action || kind == Program; }
};

class Scope {
public:
  explicit Scope(Scope* parent = nullptr) : parent_(parent) {}
  // Adds; returns the existing symbol instead if the name is taken.
  Symbol* add(Symbol* s);
  Symbol* lookupLocal(const std::string& upperName) const;
  Symbol* lookup(const std::string& upperName) const;
  Scope* parent() const { return parent_; }
  void setParent(Scope* p) { parent_ = p; }
  const std::vector<Symbol*>& symbols() const { return order_; }

private:
  Scope* parent_;
  std::unordered_map<std::string, Symbol*> map_;
  std::vector<Symbol*> order_;
};

std::string upperCase(std::string_view s);

}  // namespace stc::sema
