// Semantic analysis: name resolution, type checking and the IEC rules.
// Runs over every SourceUnit of an ASTContext, annotating the AST in place.
#pragma once

#include <memory>

#include "ast/AST.h"
#include "basic/Diagnostics.h"
#include "sema/DialectRules.h"

namespace stc::sema {

struct SemaOptions {
  Dialect dialect = Dialect::Codesys;   // what CODESYS V3 accepts; IEC is strict
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
