// Parsing: source text -> AST.  The ANTLR parser is an implementation detail
// of this stage; nothing outside compiler/parse includes ANTLR headers.
#pragma once

#include <set>
#include <string>

#include "ast/AST.h"
#include "basic/Diagnostics.h"

namespace stc {

struct ParseOptions {
  std::set<std::string> defines;   // lower-case names for {IF defined(...)}
};

struct ParseStats {
  size_t tokens = 0;
  bool usedLLFallback = false;
  double lexSeconds = 0, parseSeconds = 0, buildSeconds = 0;
};

// Parses one loaded file into `ctx` (appends a SourceUnit).  Reports every
// problem through `diags`; never throws.  Returns false on syntax errors.
bool parseFile(SourceManager& sm, uint32_t file, DiagnosticsEngine& diags, ast::ASTContext& ctx,
               const ParseOptions& opts, ParseStats* stats = nullptr);

// True if `name` (any case) is a keyword of the ST grammar and so cannot name a
// task, program or variable (used to check names that reach generated ST).
bool isReservedWord(const std::string& name);

// Lexes `text` with the generated ANTLR lexer and with the hand-written one;
// returns "" if they agree, else the first difference (for tests).
std::string compareLexers(const std::string& text);

}  // namespace stc
