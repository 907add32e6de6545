// The variable names a project declares, as the controller's name lookup takes them
// (vm/Image.h resolvePath): a global `x`, `GVL.x`, a PROGRAM's `MAIN.y`, followed by members
// and indexes (`x[2]`, `GVL.pos.x`).  stc check uses it for what names variables outside
// ST: G-code `$name$`, project.toml tables and scenarios.  Only the root is checked: the
// members are the run's business (it has the types).
#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "ast/AST.h"

namespace stc {

class DeclaredNames {
public:
  explicit DeclaredNames(ast::ASTContext& ast);
  // The root of `name` (before an index or a member) is a global, GVL.global or a PROGRAM.
  bool known(std::string_view name) const;
  // A declared name close to `name` (its first one or two dotted parts), or "".
  std::string closest(std::string_view name) const;

private:
  std::set<std::string> names_;      // lower case: x, gvl.x
  std::set<std::string> programs_;   // lower case
  std::vector<std::string> spelled_; // as declared: x, GVL.x, MAIN
};

}  // namespace stc
