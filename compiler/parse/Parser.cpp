// Parse driver: normalise -> lex -> parse (SLL, then LL on failure) -> AST.
#include "parse/Parser.h"

#include <chrono>

#include "parse/ParseInternal.h"

namespace stc {

using namespace parse;

namespace {

// Deeply nested input would overflow the recursive-descent parser's stack.
// Brackets deeper than this are reported instead of parsed.
constexpr int kMaxNesting = 256;
constexpr int kMaxStatementNesting = 256;   // IF/CASE/FOR/WHILE/REPEAT inside each other

// The SLL stage reports nothing: a failure only means "retry with LL".
class SilentBail : public antlr4::BailErrorStrategy {
public:
  void reportError(antlr4::Parser*, const antlr4::RecognitionException&) override {}
};

// Likewise a single statement longer than this (a million-term expression or
// a chain of unary operators) is reported instead of parsed.
constexpr size_t kMaxStatementTokens = 100000;

bool checkNesting(const SourceFile& file, const LexedFile& lexed, DiagnosticsEngine& diags) {
  int depth = 0, statements = 0;
  size_t sinceSemi = 0;
  for (const auto& t : lexed.tokens) {
    size_t ty = t->getType();
    // Compound statements: the optimiser's loop analyses grow with the square
    // of the nesting, so deep nests are refused here (see also CodeGen's
    // kMaxOptimisedLoopDepth).
    if (ty == STLexer::IF || ty == STLexer::CASE || ty == STLexer::FOR || ty == STLexer::WHILE || ty == STLexer::REPEAT) {
      if (++statements > kMaxStatementNesting) {
        diags.error(locOf(file.id, t.get()), "statements nested more than " + std::to_string(kMaxStatementNesting) +
                                                 " levels deep; move the inner part into a function", "nesting");
        return false;
      }
    } else if (ty == STLexer::END_IF || ty == STLexer::END_CASE || ty == STLexer::END_FOR || ty == STLexer::END_WHILE ||
               ty == STLexer::END_REPEAT) {
      if (statements > 0) --statements;
    }
    if (ty == STLexer::SEMI) sinceSemi = 0;
    else if (++sinceSemi > kMaxStatementTokens) {
      diags.error(locOf(file.id, t.get()), "statement longer than " + std::to_string(kMaxStatementTokens) + " tokens; split it", "nesting");
      return false;
    }
    if (ty == STLexer::LPAREN || ty == STLexer::LBRACKET) {
      if (++depth > kMaxNesting) {
        diags.error(locOf(file.id, t.get()), "brackets nested more than " + std::to_string(kMaxNesting) + " levels deep", "nesting");
        return false;
      }
    } else if (ty == STLexer::RPAREN || ty == STLexer::RBRACKET) {
      if (depth > 0) --depth;
    }
  }
  return true;
}

}  // namespace

bool parseFile(SourceManager& sm, uint32_t fileId, DiagnosticsEngine& diags, ast::ASTContext& ctx,
               const ParseOptions& opts, ParseStats* stats) {
  SourceFile& file = sm.file(fileId);
  unsigned errorsBefore = diags.errorCount();
  try {
    using clock = std::chrono::steady_clock;
    auto secondsSince = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
    auto t0 = clock::now();
    normalizeFullWidth(file, diags);
    skipExportSections(file, diags);
    LexedFile lexed;
    lexFile(file, diags, opts, lexed);
    if (stats) stats->lexSeconds += secondsSince(t0);
    auto t1 = clock::now();
    if (stats) stats->tokens += lexed.tokens.size();
    if (!checkNesting(file, lexed, diags)) return false;
    repairDeclarationKeywordTypos(file, lexed, diags);

    // ListTokenSource takes the tokens; keep raw pointers for the builder's
    // attribute lookups (only offsets are needed, which live in lexed).
    std::vector<std::unique_ptr<antlr4::Token>> toks = std::move(lexed.tokens);
    antlr4::ListTokenSource source(std::move(toks));
    TokenEditStream stream(&source);
    STParser parser(&stream);
    parser.removeErrorListeners();

    // Stage 1: SLL with bail-out; almost every valid file parses here.
    parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->setPredictionMode(antlr4::atn::PredictionMode::SLL);
    parser.setErrorHandler(std::make_shared<SilentBail>());
    STParser::CompilationUnitContext* cu = nullptr;
    try {
      cu = parser.compilationUnit();
    } catch (antlr4::ParseCancellationException&) {
      cu = nullptr;
    }
    if (!cu) {
      // Stage 2: full LL with error recovery and our diagnostics.
      if (stats) stats->usedLLFallback = true;
      parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->setPredictionMode(antlr4::atn::PredictionMode::LL);
      cu = parseWithRecovery(parser, stream, file, lexed, diags);
    }
    if (stats) stats->parseSeconds += secondsSince(t1);
    auto t2 = clock::now();
    ctx.units().push_back({});
    ast::SourceUnit& unit = ctx.units().back();
    unit.file = fileId;
    if (cu) buildAST(cu, file, lexed, diags, ctx, unit);
    if (stats) stats->buildSeconds += secondsSince(t2);
  } catch (std::exception& e) {
    diags.error(SourceLoc{fileId, 0}, std::string("internal parser error: ") + e.what(), "internal");
  } catch (...) {
    diags.error(SourceLoc{fileId, 0}, "internal parser error", "internal");
  }
  return diags.errorCount() == errorsBefore;
}

}  // namespace stc
