#include "driver/DeclaredNames.h"

#include "basic/Diagnostics.h"
#include "basic/Text.h"

namespace stc {

DeclaredNames::DeclaredNames(ast::ASTContext& ast) {
  for (const ast::SourceUnit& u : ast.units())
    for (const ast::Decl* d : u.decls) {
      if (auto* g = ast::dyn_cast<ast::GlobalVarDecl>(d)) {
        for (const ast::VarDecl* v : g->block.vars) {
          names_.insert(asciiLower(v->name.name));
          spelled_.push_back(v->name.name);
          if (!g->listName.name.empty()) {
            names_.insert(asciiLower(g->listName.name + "." + v->name.name));
            spelled_.push_back(g->listName.name + "." + v->name.name);
          }
        }
      } else if (auto* p = ast::dyn_cast<ast::PouDecl>(d); p && p->pouKind == ast::PouKind::Program) {
        programs_.insert(asciiLower(p->name.str()));
        spelled_.push_back(p->name.str());
      } else if (auto* c = ast::dyn_cast<ast::ConfigurationDecl>(d)) {
        // Program instances (`PROGRAM Conveyor WITH Fast : MAIN`) and the globals of a
        // CONFIGURATION and its RESOURCEs.
        auto globals = [&](const std::vector<ast::VarBlock>& blocks) {
          for (const ast::VarBlock& b : blocks)
            for (const ast::VarDecl* v : b.vars) {
              names_.insert(asciiLower(v->name.name));
              spelled_.push_back(v->name.name);
            }
        };
        globals(c->globals);
        for (const ast::ResourceDecl& r : c->resources) {
          globals(r.globals);
          for (const ast::ProgramConfig& pc : r.programs) {
            programs_.insert(asciiLower(pc.name.name));
            spelled_.push_back(pc.name.name);
          }
        }
      }
    }
}

bool DeclaredNames::known(std::string_view name) const {
  const std::string n = asciiLower(std::string(name.substr(0, name.find('['))));
  const size_t dot = n.find('.');
  if (names_.count(n) || names_.count(n.substr(0, dot))) return true;
  if (dot == std::string::npos) return false;
  if (programs_.count(n.substr(0, dot))) return true;
  return names_.count(n.substr(0, n.find('.', dot + 1))) != 0;   // GVL.x.member
}

std::string DeclaredNames::closest(std::string_view name) const {
  const std::string_view head = name.substr(0, name.find('['));
  const size_t dot = head.find('.');
  // `GVL.Axis9.fActPosition`: the best of `GVL.Axis9` and `GVL`.
  if (dot != std::string_view::npos) {
    std::string two = closestMatch(head.substr(0, head.find('.', dot + 1)), spelled_);
    if (!two.empty()) return two;
  }
  return closestMatch(head.substr(0, dot), spelled_);
}

}  // namespace stc
