// Semantic analysis: name resolution, type checking and the IEC rules.
// Runs over every SourceUnit of an ASTContext, annotating the AST in place.
#pragma once

#include <functional>
#include <string>

#include <memory>

#include "ast/AST.h"
#include "basic/Diagnostics.h"
#include "sema/DialectRules.h"

namespace stc::sema {

struct SemaOptions {
  Dialect dialect = Dialect::Codesys;   // what CODESYS V3 accepts; IEC is strict
  // The address model: 32 = POINTER TO / REF_TO / REFERENCE TO take 4 bytes and the
  // program's memory lies below 4 GiB, as on a 32-bit controller (docs/dialect.md).
  unsigned addressBits = 32;
  // The optional library (not compiled in) that declares an unknown type or program name,
  // for the hint "add the library"; empty: none.  May be unset.
  std::function<std::string(const std::string& name)> libraryOf;
};

class SemaImpl;
struct Model;

class Sema {
public:
  Sema(ast::ASTContext& ctx, DiagnosticsEngine& diags, SemaOptions opts);
  ~Sema();
  // Returns false if errors were reported.
  bool run();
  // The checked program (after run()).
  const Model& model() const;

private:
  std::unique_ptr<SemaImpl> impl_;
};

}  // namespace stc::sema
