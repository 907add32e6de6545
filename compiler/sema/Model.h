// The read-only view of a checked program that later stages (code
// generation, the virtual controller's symbol map) work from.  Valid while
// the Sema that produced it lives (the Compilation owns both).
#pragma once

#include <vector>

#include "ast/AST.h"
#include "sema/Layout.h"
#include "sema/Sema.h"
#include "sema/Symbols.h"
#include "sema/Types.h"

namespace stc::sema {

struct Model {
  TypeContext* types = nullptr;
  const Layout* layout = nullptr;
  Dialect dialect = Dialect::IEC;
  // Every POU with a body: programs, functions, FBs, methods, actions,
  // property accessors, in declaration order.
  std::vector<Symbol*> pous;
  std::vector<ast::GlobalVarDecl*> globalLists;     // VAR_GLOBAL blocks (GVLs), source order
  std::vector<ast::ConfigurationDecl*> configurations;
  // Symbol of a POU's own name, for each POU declaration.
  Symbol* symbolOf(const ast::PouDecl* d) const { return d ? d->symbol : nullptr; }
};

}  // namespace stc::sema
