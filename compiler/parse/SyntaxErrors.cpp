// Syntax error reporting in clang style: "expected ';'" at the insertion
// point with a fix-it, "did you mean 'ELSIF'?" for misspelled keywords, and
// expected-token sets reduced to what a person would type next.
#include <algorithm>

#include "parse/ParseInternal.h"

namespace stc::parse {

namespace {

bool isOperatorToken(size_t t) {
  switch (t) {
    case STLexer::DOT: case STLexer::LBRACKET: case STLexer::CARET: case STLexer::LPAREN:
    case STLexer::POWER: case STLexer::STAR: case STLexer::SLASH: case STLexer::MOD:
    case STLexer::PLUS: case STLexer::MINUS: case STLexer::LT: case STLexer::GT: case STLexer::LE:
    case STLexer::GE: case STLexer::EQ: case STLexer::NE: case STLexer::AND: case STLexer::AMP:
    case STLexer::AND_THEN: case STLexer::XOR: case STLexer::OR: case STLexer::OR_ELSE:
      return true;
    default:
      return false;
  }
}

bool startsExpression(size_t t) {
  switch (t) {
    case STLexer::IDENTIFIER: case STLexer::INTEGER_LITERAL: case STLexer::REAL_LITERAL:
    case STLexer::BASED_LITERAL: case STLexer::STRING_LITERAL: case STLexer::TRUE: case STLexer::FALSE:
    case STLexer::TIME_LITERAL: case STLexer::NOT: case STLexer::THIS:
      return true;
    default:
      return false;
  }
}

// Keywords a misspelling is compared against ("did you mean").
const char* const kStructureKeywords[] = {
    "END_IF", "ELSIF", "END_CASE", "END_FOR", "END_WHILE", "END_REPEAT", "END_VAR", "END_TYPE",
    "END_STRUCT", "END_PROGRAM", "END_FUNCTION", "END_FUNCTION_BLOCK", "END_METHOD", "END_PROPERTY",
    "END_ACTION", "END_INTERFACE", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_GLOBAL", "VAR_TEMP",
    "FUNCTION_BLOCK", "THEN", "ELSE", "REPEAT", "UNTIL", "WHILE", "RETURN", "CONTINUE", "PROGRAM",
    "FUNCTION", "CONSTANT", "END_UNION", "END_RESOURCE", "END_CONFIGURATION", "END_NAMESPACE",
};

class STErrorStrategy : public antlr4::DefaultErrorStrategy {
public:
  STErrorStrategy(const SourceFile& file, DiagnosticsEngine& diags) : file_(file), diags_(diags) {}

protected:
  std::string tokenName(size_t type, antlr4::Parser* p) const {
    if (type == antlr4::Token::EOF) return "end of file";
    switch (type) {
      case STLexer::IDENTIFIER: return "identifier";
      case STLexer::INTEGER_LITERAL: case STLexer::REAL_LITERAL: case STLexer::BASED_LITERAL: return "number";
      case STLexer::STRING_LITERAL: case STLexer::WSTRING_LITERAL: return "string literal";
      case STLexer::DIRECT_ADDRESS: return "direct address";
      default: break;
    }
    std::string lit = p->getVocabulary().getLiteralName(type);
    if (!lit.empty()) return lit;    // already quoted: ';'
    std::string sym = p->getVocabulary().getSymbolicName(type);
    return "'" + sym + "'";
  }

  std::string describe(antlr4::Token* t) const {
    if (t->getType() == antlr4::Token::EOF) return "end of file";
    std::string text(file_.text.substr(t->getStartIndex(), t->getStopIndex() + 1 - t->getStartIndex()));
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    if (t->getType() == STLexer::IDENTIFIER) return "identifier '" + text + "'";
    return "'" + text + "'";
  }

  std::string expectedText(antlr4::Parser* p, const antlr4::misc::IntervalSet& set) const {
    std::vector<size_t> types;
    for (const antlr4::misc::Interval& iv : set.getIntervals())
      for (ssize_t t = iv.a; t <= iv.b; ++t) types.push_back(static_cast<size_t>(t));
    bool anyNonOp = std::any_of(types.begin(), types.end(), [](size_t t) { return !isOperatorToken(t); });
    bool expr = std::any_of(types.begin(), types.end(), startsExpression);
    std::vector<std::string> names;
    for (size_t t : types) {
      if (anyNonOp && isOperatorToken(t)) continue;
      if (expr && (startsExpression(t) || t == STLexer::MINUS || t == STLexer::PLUS || t == STLexer::LPAREN ||
                   t == STLexer::SUPER || (t >= STLexer::TIME_LITERAL && t <= STLexer::IDENTIFIER)))
        continue;
      std::string n = tokenName(t, p);
      if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    }
    if (expr) names.insert(names.begin(), "an expression");
    if (names.empty()) return "";
    if (names.size() > 6) return names.front() + " or another token";
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) {
      if (i) out += (i + 1 == names.size()) ? " or " : ", ";
      out += names[i];
    }
    return out;
  }

  // A misspelled keyword?  Returns true if a diagnostic was emitted.
  bool reportKeywordTypo(antlr4::Token* t) {
    if (!t || t->getType() != STLexer::IDENTIFIER) return false;
    std::string text(file_.text.substr(t->getStartIndex(), t->getStopIndex() + 1 - t->getStartIndex()));
    if (text.size() < 4) return false;
    std::vector<std::string> kws(std::begin(kStructureKeywords), std::end(kStructureKeywords));
    std::string best = closestMatch(text, kws);
    if (best.empty()) {
      // ENDIF / ELSEIF: the same letters without or with an extra underscore.
      std::string up;
      for (char c : text) if (c != '_') up += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      for (const std::string& k : kws) {
        std::string kk;
        for (char c : k) if (c != '_') kk += c;
        if (kk == up) best = k;
      }
      if (up == "ELSEIF") best = "ELSIF";
    }
    if (best.empty()) return false;
    SourceRange r = rangeOf(file_.id, t);
    diags_.error(r.begin, "unknown keyword '" + text + "'; did you mean '" + best + "'?", "syntax").range(r).fixit(r, best);
    return true;
  }

  void reportNoViableAlternative(antlr4::Parser* p, const antlr4::NoViableAltException& e) override {
    antlr4::Token* start = e.getStartToken();
    antlr4::Token* off = e.getOffendingToken();
    if (reportKeywordTypo(start) || reportKeywordTypo(off)) return;
    std::string exp = expectedText(p, e.getExpectedTokens());
    SourceRange r = rangeOf(file_.id, off);
    // `x = 1;` as a statement: assignment written with '='.
    if (off->getType() == STLexer::SEMI || off->getType() == STLexer::EQ) {
      // fall through to the generic message
    }
    std::string msg = "unexpected " + describe(off);
    if (!exp.empty()) msg += "; expected " + exp;
    diags_.error(r.begin, msg, "syntax").range(r);
  }

  void reportInputMismatch(antlr4::Parser* p, const antlr4::InputMismatchException& e) override {
    antlr4::Token* off = e.getOffendingToken();
    if (reportKeywordTypo(off)) return;
    std::string exp = expectedText(p, e.getExpectedTokens());
    SourceRange r = rangeOf(file_.id, off);
    std::string msg = exp.empty() ? "unexpected " + describe(off) : "expected " + exp + ", found " + describe(off);
    diags_.error(r.begin, msg, "syntax").range(r);
  }

  void reportFailedPredicate(antlr4::Parser*, const antlr4::FailedPredicateException& e) override {
    antlr4::Token* off = e.getOffendingToken();
    diags_.error(rangeOf(file_.id, off).begin, "unexpected " + describe(off), "syntax");
  }

  void reportUnwantedToken(antlr4::Parser* p) override {
    if (inErrorRecoveryMode(p)) return;
    beginErrorCondition(p);
    antlr4::Token* t = p->getCurrentToken();
    if (reportKeywordTypo(t)) return;
    std::string exp = expectedText(p, getExpectedTokens(p));
    SourceRange r = rangeOf(file_.id, t);
    std::string msg = "unexpected " + describe(t);
    if (!exp.empty()) msg += "; expected " + exp;
    diags_.error(r.begin, msg, "syntax").range(r);
  }

  void reportMissingToken(antlr4::Parser* p) override {
    if (inErrorRecoveryMode(p)) return;
    beginErrorCondition(p);
    antlr4::Token* t = p->getCurrentToken();
    antlr4::misc::IntervalSet expecting = getExpectedTokens(p);
    std::string exp = expectedText(p, expecting);
    // Point just after the previous token, where the missing one belongs.
    antlr4::Token* prev = p->getTokenStream()->LT(-1);
    SourceLoc at = prev ? SourceLoc{file_.id, static_cast<uint32_t>(prev->getStopIndex() + 1)} : rangeOf(file_.id, t).begin;
    auto d = diags_.error(at, "expected " + exp, "syntax");
    if (expecting.size() == 1) {
      size_t tt = expecting.getSingleElement();
      std::string lit = p->getVocabulary().getLiteralName(tt);
      if (lit.size() >= 2) d.fixit(SourceRange(at), lit.substr(1, lit.size() - 2));
    }
  }

private:
  const SourceFile& file_;
  DiagnosticsEngine& diags_;
};

}  // namespace

std::shared_ptr<antlr4::DefaultErrorStrategy> makeErrorStrategy(const SourceFile& file, DiagnosticsEngine& diags) {
  return std::make_shared<STErrorStrategy>(file, diags);
}

}  // namespace stc::parse
