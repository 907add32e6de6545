// Syntax error reporting in clang style: "expected ';'" at the insertion
// point with a fix-it, "did you mean 'ELSIF'?" for misspelled keywords, and
// expected-token sets reduced to what a person would type next.
//
// Recovery works in two steps.  ANTLR's single-token recovery only sees one
// token, so a misspelled keyword (`ELSEIF x < 0 THEN`, read as the start of
// an `x S= y` statement) or a keyword used as a name would cause a cascade of
// follow-on errors.  parseWithRecovery() therefore first parses silently,
// looks at each error for a clear fix (retype the misspelled keyword, read the
// keyword as a name, insert the missing ';', skip an index the grammar does
// not allow), applies it to the token stream and parses again; the fix is
// kept if the parser then gets further.  Only then the final parse reports
// what is left.  Valid code never gets here (it parses in the SLL stage).
#include <algorithm>
#include <cctype>
#include <set>

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

bool has(const antlr4::misc::IntervalSet& set, size_t type) { return set.contains(type); }

bool isKeyword(size_t t) { return t >= 1 && t <= STLexer::XOR; }

// Keywords that end a statement list: a statement before them that lacks its
// ';' gets "expected ';'" at the end of the statement.
bool endsStatementList(size_t t) {
  switch (t) {
    case STLexer::END_IF: case STLexer::ELSIF: case STLexer::ELSE: case STLexer::END_CASE: case STLexer::END_FOR:
    case STLexer::END_WHILE: case STLexer::UNTIL: case STLexer::END_REPEAT: case STLexer::END_PROGRAM:
    case STLexer::END_FUNCTION: case STLexer::END_FUNCTION_BLOCK: case STLexer::END_METHOD: case STLexer::END_ACTION:
    case STLexer::END_GET: case STLexer::END_SET:
      return true;
    default:
      return false;
  }
}

// Keywords that open or close a block or a section.  When one of them stands
// where a name is expected, the name is missing; it is not a keyword used as
// a name.
bool isStructureKeyword(size_t t, const antlr4::dfa::Vocabulary& v) {
  std::string name = v.getSymbolicName(t);
  if (name.rfind("END_", 0) == 0 || name.rfind("VAR", 0) == 0) return true;
  switch (t) {
    case STLexer::PROGRAM: case STLexer::FUNCTION: case STLexer::FUNCTION_BLOCK: case STLexer::METHOD:
    case STLexer::PROPERTY: case STLexer::ACTION: case STLexer::INTERFACE: case STLexer::TYPE: case STLexer::STRUCT:
    case STLexer::UNION: case STLexer::CONFIGURATION: case STLexer::RESOURCE: case STLexer::NAMESPACE: case STLexer::IF:
    case STLexer::CASE: case STLexer::FOR: case STLexer::WHILE: case STLexer::REPEAT:
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
    "VAR_EXTERNAL", "VAR_STAT", "FUNCTION_BLOCK", "THEN", "ELSE", "REPEAT", "UNTIL", "WHILE", "RETURN",
    "CONTINUE", "PROGRAM", "FUNCTION", "CONSTANT", "END_UNION", "END_RESOURCE", "END_CONFIGURATION",
    "END_NAMESPACE", "END_GET", "END_SET", "METHOD", "PROPERTY", "INTERFACE",
};

// The structure keyword `text` looks like a misspelling of, or "".
// Words of the textual SFC (IEC 61131-3 2.6): not misspellings of ST keywords.
bool isSfcWord(std::string_view text) {
  std::string up;
  for (char c : text) up += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return up == "STEP" || up == "END_STEP" || up == "INITIAL_STEP" || up == "TRANSITION" || up == "END_TRANSITION";
}

std::string keywordTypo(std::string_view text) {
  if (text.size() < 4 || isSfcWord(text)) return "";
  static const std::vector<std::string> kws(std::begin(kStructureKeywords), std::end(kStructureKeywords));
  std::string up;
  for (char c : text) if (c != '_') up += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  // ENDIF / ELSEIF: the same letters without or with an extra underscore.
  if (up == "ELSEIF") return "ELSIF";
  for (const std::string& k : kws) {
    std::string kk;
    for (char c : k) if (c != '_') kk += c;
    if (kk == up) {
      // The keyword itself, spelled right, is not a misspelling.
      std::string exact;
      for (char c : text) exact += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      return exact == k ? "" : k;
    }
  }
  return closestMatch(text, kws);
}

size_t keywordTokenType(const std::string& kw, const antlr4::dfa::Vocabulary& v) {
  for (size_t t = 1; t <= STLexer::XOR; ++t)
    if (v.getSymbolicName(t) == kw) return t;
  return 0;
}


// Where the parser stood when it reported an error (used by the repairs).
struct ErrorPoint {
  size_t index = 0;            // index of the offending token in the stream
  uint32_t offset = 0;         // its start offset (the text size for EOF)
  bool eof = false;
  antlr4::misc::IntervalSet expected;
  size_t stmtStart = kNoTokenIndex;   // first token of the innermost statement
  bool inForHeader = false;    // error directly in a FOR statement's rule
  Diagnostic diag;             // what was reported there
};

class STErrorStrategy : public antlr4::DefaultErrorStrategy {
public:
  STErrorStrategy(const SourceFile& file, const LexedFile& lexed, DiagnosticsEngine& diags, std::vector<ErrorPoint>* points)
      : file_(file), lexed_(lexed), diags_(diags), points_(points) {}

  // A ';' is inserted rather than the offending token deleted when the
  // statement ends at a line end, at the end of the file or before a keyword
  // that closes the statement list: `IF c THEN y := 1 END_IF;`.
  antlr4::Token* recoverInline(antlr4::Parser* p) override {
    if (prefersSemicolonInsertion(p) && singleTokenInsertion(p)) return getMissingSymbol(p);
    return DefaultErrorStrategy::recoverInline(p);
  }

protected:
  // Deleting a ';' or an END_xxx to make the input fit would join two
  // statements or blocks (`x := x + ; y := 1;` would read `x := x + y`) and
  // cause follow-on errors; the normal recovery resynchronises at them.
  antlr4::Token* singleTokenDeletion(antlr4::Parser* p) override {
    size_t t = p->getTokenStream()->LA(1);
    if (t == STLexer::SEMI || endsStatementList(t) || t == STLexer::END_VAR || t == STLexer::END_TYPE ||
        t == STLexer::END_STRUCT)
      return nullptr;
    return DefaultErrorStrategy::singleTokenDeletion(p);
  }

  bool prefersSemicolonInsertion(antlr4::Parser* p) {
    if (!has(getExpectedTokens(p), STLexer::SEMI)) return false;
    antlr4::Token* cur = p->getTokenStream()->LT(1);
    antlr4::Token* prev = p->getTokenStream()->LT(-1);
    if (!cur || !prev || prev->getStartIndex() == kNoTokenIndex) return false;
    if (cur->getType() == antlr4::Token::EOF || endsStatementList(cur->getType())) return true;
    return newlineBetween(prev, cur);
  }

  bool newlineBetween(antlr4::Token* a, antlr4::Token* b) const {
    size_t from = a->getStopIndex() + 1, to = std::min<size_t>(b->getStartIndex(), file_.text.size());
    for (size_t i = from; i < to; ++i)
      if (file_.text[i] == '\n' || file_.text[i] == '\r') return true;
    return false;
  }

  std::string tokenName(size_t type, antlr4::Parser* p) const {
    if (type == antlr4::Token::EOF) return "end of file";
    switch (type) {
      case STLexer::IDENTIFIER: return "identifier";
      case STLexer::INTEGER_LITERAL: case STLexer::REAL_LITERAL: case STLexer::BASED_LITERAL: return "number";
      case STLexer::STRING_LITERAL: case STLexer::WSTRING_LITERAL: case STLexer::UNTERMINATED_STRING: return "string literal";
      case STLexer::TIME_LITERAL: return "time literal";
      case STLexer::DATE_LITERAL: return "date literal";
      case STLexer::TOD_LITERAL: return "time-of-day literal";
      case STLexer::DATE_TIME_LITERAL: return "date-and-time literal";
      case STLexer::DIRECT_ADDRESS: return "direct address";
      case STLexer::PARTIAL_ACCESS: return "bit access";
      case STLexer::REF_ASSIGN: return "'REF='";
      default: break;
    }
    std::string lit = p->getVocabulary().getLiteralName(type);
    if (!lit.empty()) return lit;    // already quoted: ';'
    // Keywords are spelled as their token names.
    std::string sym = p->getVocabulary().getSymbolicName(type);
    return "'" + sym + "'";
  }

  std::string describe(antlr4::Token* t, antlr4::Parser* p) const {
    if (t->getType() == antlr4::Token::EOF) return "end of file";
    if (t->getStartIndex() == kNoTokenIndex || t->getStopIndex() < t->getStartIndex() || t->getStopIndex() >= file_.text.size())
      return tokenName(t->getType(), p);
    std::string text(file_.text.substr(t->getStartIndex(), t->getStopIndex() + 1 - t->getStartIndex()));
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    if (t->getType() == STLexer::IDENTIFIER) return "identifier '" + text + "'";
    return "'" + text + "'";
  }

  std::string expectedText(antlr4::Parser* p, const antlr4::misc::IntervalSet& set) const {
    std::vector<size_t> types;
    for (const antlr4::misc::Interval& iv : set.getIntervals())
      for (ssize_t t = iv.a; t <= iv.b; ++t) types.push_back(static_cast<size_t>(t));
    // After `x := 4` the grammar also takes ':=' (a chained assignment), but
    // the ';' is what was forgotten.
    if (types.size() == 2 && std::count(types.begin(), types.end(), STLexer::SEMI) && std::count(types.begin(), types.end(), STLexer::ASSIGN))
      types = {STLexer::SEMI};
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

  // Remembers where the diagnostic just emitted was reported (repairs).
  void record(antlr4::Parser* p, antlr4::Token* off, const antlr4::misc::IntervalSet& expected, size_t diagsBefore) {
    if (!points_ || diags_.diagnostics().size() <= diagsBefore || !off) return;
    ErrorPoint e;
    e.index = off->getTokenIndex();
    e.eof = off->getType() == antlr4::Token::EOF;
    e.offset = e.eof ? static_cast<uint32_t>(file_.text.size()) : static_cast<uint32_t>(off->getStartIndex());
    e.expected = expected;
    for (antlr4::tree::ParseTree* c = p->getContext(); c; c = c->parent) {
      if (auto* s = dynamic_cast<antlr4::ParserRuleContext*>(c)) {
        if (c == p->getContext() && dynamic_cast<STParser::ForStmtContext*>(c)) e.inForHeader = true;
        if (dynamic_cast<STParser::UnlabeledStatementContext*>(c)) {
          if (s->getStart() && s->getStart()->getTokenIndex() != kNoTokenIndex) e.stmtStart = s->getStart()->getTokenIndex();
          break;
        }
      }
    }
    e.diag = diags_.diagnostics().back();
    points_->push_back(std::move(e));
  }

  // A misspelled keyword?  Returns true if a diagnostic was emitted.
  bool reportKeywordTypo(antlr4::Token* t) {
    if (!t || t->getType() != STLexer::IDENTIFIER) return false;
    std::string text(file_.text.substr(t->getStartIndex(), t->getStopIndex() + 1 - t->getStartIndex()));
    std::string best = keywordTypo(text);
    if (best.empty()) return false;
    SourceRange r = rangeOf(file_.id, t);
    diags_.error(r.begin, "unknown keyword '" + text + "'; did you mean '" + best + "'?", "syntax").range(r).fixit(r, best);
    return true;
  }

  // "expected ';'" right after an unterminated string, which swallowed the
  // ';', would only repeat the lexer's error.
  bool afterUnterminatedString(antlr4::Parser* p, const antlr4::misc::IntervalSet& expected) const {
    return has(expected, STLexer::SEMI) && lexed_.isUnterminatedString(p->getTokenStream()->LT(-1));
  }

  void reportNoViableAlternative(antlr4::Parser* p, const antlr4::NoViableAltException& e) override {
    size_t before = diags_.diagnostics().size();
    antlr4::Token* start = e.getStartToken();
    antlr4::Token* off = e.getOffendingToken();
    const antlr4::misc::IntervalSet& expected = e.getExpectedTokens();
    if (!reportKeywordTypo(start) && !reportKeywordTypo(off)) {
      std::string exp = expectedText(p, expected);
      SourceRange r = rangeOf(file_.id, off);
      std::string msg = "unexpected " + describe(off, p);
      if (!exp.empty()) msg += "; expected " + exp;
      diags_.error(r.begin, msg, "syntax").range(r);
    }
    record(p, off, expected, before);
  }

  void reportInputMismatch(antlr4::Parser* p, const antlr4::InputMismatchException& e) override {
    size_t before = diags_.diagnostics().size();
    antlr4::Token* off = e.getOffendingToken();
    const antlr4::misc::IntervalSet& expected = e.getExpectedTokens();
    if (afterUnterminatedString(p, expected)) return;
    auto* pou = dynamic_cast<STParser::PouDeclContext*>(p->getContext());
    if (off->getType() == antlr4::Token::EOF && pou && pou->kind && !pou->qualifiedName().empty() &&
        has(expected, STLexer::END_PROGRAM)) {
      // The file ends inside a POU (like clang's "expected '}'").
      size_t kind = pou->kind->getType();
      const char* name = kind == STLexer::PROGRAM ? "PROGRAM" : kind == STLexer::FUNCTION ? "FUNCTION" : "FUNCTION_BLOCK";
      antlr4::ParserRuleContext* n = pou->qualifiedName(0);
      SourceRange nr = rangeOf(file_.id, n->getStart());
      if (n->getStop() && n->getStop()->getStopIndex() >= n->getStart()->getStartIndex() && n->getStop()->getStopIndex() < file_.text.size())
        nr.end = {file_.id, static_cast<uint32_t>(n->getStop()->getStopIndex() + 1)};
      std::string_view shown = nr.end.offset > nr.begin.offset ? std::string_view(file_.text).substr(nr.begin.offset, nr.end.offset - nr.begin.offset)
                                                               : std::string_view();
      diags_.error(rangeOf(file_.id, off).begin, std::string("expected 'END_") + name + "', found end of file", "syntax")
          .note(nr.begin, std::string(name) + " '" + std::string(shown) + "' starts here", nr);
    } else if (!reportKeywordTypo(off)) {
      std::string exp = expectedText(p, expected);
      SourceRange r = rangeOf(file_.id, off);
      std::string msg = exp.empty() ? "unexpected " + describe(off, p) : "expected " + exp + ", found " + describe(off, p);
      diags_.error(r.begin, msg, "syntax").range(r);
    }
    record(p, off, expected, before);
  }

  void reportFailedPredicate(antlr4::Parser* p, const antlr4::FailedPredicateException& e) override {
    antlr4::Token* off = e.getOffendingToken();
    diags_.error(rangeOf(file_.id, off).begin, "unexpected " + describe(off, p), "syntax");
  }

  void reportUnwantedToken(antlr4::Parser* p) override {
    if (inErrorRecoveryMode(p)) return;
    beginErrorCondition(p);
    size_t before = diags_.diagnostics().size();
    antlr4::Token* t = p->getCurrentToken();
    antlr4::misc::IntervalSet expected = getExpectedTokens(p);
    if (!reportKeywordTypo(t)) {
      std::string exp = expectedText(p, expected);
      SourceRange r = rangeOf(file_.id, t);
      std::string msg = "unexpected " + describe(t, p);
      if (!exp.empty()) msg += "; expected " + exp;
      diags_.error(r.begin, msg, "syntax").range(r);
    }
    record(p, t, expected, before);
  }

  void reportMissingToken(antlr4::Parser* p) override {
    if (inErrorRecoveryMode(p)) return;
    beginErrorCondition(p);
    size_t before = diags_.diagnostics().size();
    antlr4::Token* t = p->getCurrentToken();
    antlr4::misc::IntervalSet expecting = getExpectedTokens(p);
    if (afterUnterminatedString(p, expecting)) return;
    std::string exp = expectedText(p, expecting);
    // Point just after the previous token, where the missing one belongs.
    antlr4::Token* prev = p->getTokenStream()->LT(-1);
    SourceLoc at = prev && prev->getStartIndex() != kNoTokenIndex ? SourceLoc{file_.id, static_cast<uint32_t>(prev->getStopIndex() + 1)}
                                                                   : rangeOf(file_.id, t).begin;
    {
      auto d = diags_.error(at, "expected " + exp, "syntax");
      if (expecting.size() == 1) {
        size_t tt = expecting.getSingleElement();
        std::string lit = p->getVocabulary().getLiteralName(tt);
        if (lit.size() >= 2) d.fixit(SourceRange(at), lit.substr(1, lit.size() - 2));
      }
    }
    record(p, t, expecting, before);
  }

private:
  const SourceFile& file_;
  const LexedFile& lexed_;
  DiagnosticsEngine& diags_;
  std::vector<ErrorPoint>* points_;
};

// ------------------------------------------------------------------ repairs

// One parse of the whole token stream with the reporting strategy; the
// diagnostics are kept aside until the run is chosen as the final one.
struct Run {
  STParser::CompilationUnitContext* cu = nullptr;
  std::vector<Diagnostic> diags;
  std::vector<ErrorPoint> errors;
};

// An edit of the token stream, with what is needed to undo it.
struct Edit {
  enum Kind { Retype, InsertSemi, Erase, Collapse } kind = Retype;
  size_t index = 0;       // first token concerned
  size_t last = 0;        // Erase / Collapse: last token concerned (inclusive)
  size_t type = 0;        // Retype: the new type
  size_t oldType = 0;
  size_t oldStop = 0;
  std::vector<std::unique_ptr<antlr4::Token>> removed;
  bool silent = false;    // no diagnostic (the lexer already reported the cause)
  Diagnostic diag;
};

class Repairer {
public:
  Repairer(STParser& parser, TokenEditStream& stream, const SourceFile& file, const LexedFile& lexed, DiagnosticsEngine& diags)
      : parser_(parser), stream_(stream), file_(file), lexed_(lexed), diags_(diags) {}

  STParser::CompilationUnitContext* parse() {
    Run cur = run();
    // Each attempt is a full parse, and recovering from many errors is slow:
    // bound the work on large or badly broken files (they then get fewer
    // repairs, never different ones), and stop where the error limit would
    // hide the rest anyway.
    size_t work = stream_.tokens().size() + 20 * cur.errors.size();
    size_t budget = std::clamp<size_t>(400000 / std::max<size_t>(work, 1), 1, 40);
    size_t maxPoints = diags_.opts.errorLimit ? diags_.opts.errorLimit : static_cast<size_t>(-1);
    bool curIsLast = true;
    uint32_t cursorOffset = 0;
    size_t cursorIndex = 0;
    bool haveCursor = false;
    std::vector<Diagnostic> repairDiags;
    for (size_t points = 0; budget > 0 && points < maxPoints; ++points) {
      // The next error after the cursor.
      const ErrorPoint* e = nullptr;
      for (const ErrorPoint& x : cur.errors)
        if (!haveCursor || x.offset > cursorOffset || (x.offset == cursorOffset && x.index > cursorIndex)) { e = &x; break; }
      if (!e) break;
      ErrorPoint point = *e;
      bool accepted = false;
      size_t insertedBefore = 0;
      for (Edit& cand : candidates(point)) {
        if (budget == 0) break;
        --budget;
        uint32_t from = editOffset(cand);
        apply(cand);
        Run next = run();
        curIsLast = true;
        if (improves(cur, next, point, from)) {
          if (!cand.silent) repairDiags.push_back(cand.diag);
          insertedBefore = cand.kind == Edit::InsertSemi ? 1 : 0;
          cur = std::move(next);
          accepted = true;
          break;
        }
        undo(cand);
        curIsLast = false;
      }
      haveCursor = true;
      cursorOffset = point.offset;
      cursorIndex = point.index + (accepted ? insertedBefore : 0);
    }
    if (!curIsLast) {
      cur = run();
    }
    // Repairs first where they share an offset; otherwise in file order.
    std::vector<Diagnostic> all = std::move(repairDiags);
    all.insert(all.end(), cur.diags.begin(), cur.diags.end());
    std::stable_sort(all.begin(), all.end(), [](const Diagnostic& a, const Diagnostic& b) { return a.loc.offset < b.loc.offset; });
    for (Diagnostic& d : all) diags_.commit(std::move(d));
    return cur.cu;
  }

private:
  Run run() {
    Run r;
    DiagnosticsEngine local(diags_.sourceManager());
    local.opts.errorLimit = 0;
    parser_.setErrorHandler(std::make_shared<STErrorStrategy>(file_, lexed_, local, &r.errors));
    parser_.reset();
    r.cu = parser_.compilationUnit();
    r.diags = local.diagnostics();
    return r;
  }

  antlr4::Token* tok(size_t i) {
    auto& toks = stream_.tokens();
    return i < toks.size() ? toks[i].get() : nullptr;
  }
  std::string_view text(antlr4::Token* t) const {
    if (!t || t->getType() == antlr4::Token::EOF || t->getStopIndex() < t->getStartIndex() || t->getStopIndex() >= file_.text.size()) return {};
    return std::string_view(file_.text).substr(t->getStartIndex(), t->getStopIndex() + 1 - t->getStartIndex());
  }
  bool real(antlr4::Token* t) const { return t && text(t).size() > 0; }
  bool newlineBetween(antlr4::Token* a, antlr4::Token* b) const {
    size_t from = a->getStopIndex() + 1;
    size_t to = b->getType() == antlr4::Token::EOF ? file_.text.size() : std::min<size_t>(b->getStartIndex(), file_.text.size());
    for (size_t i = from; i < to; ++i)
      if (file_.text[i] == '\n' || file_.text[i] == '\r') return true;
    return false;
  }
  uint32_t endOf(antlr4::Token* t) const { return static_cast<uint32_t>(t->getStopIndex() + 1); }

  Edit expectedSemicolon(size_t at, antlr4::Token* prev) {
    Edit e;
    e.kind = Edit::InsertSemi;
    e.index = at;
    e.silent = lexed_.isUnterminatedString(prev);
    SourceLoc l{file_.id, endOf(prev)};
    e.diag.severity = Severity::Error;
    e.diag.loc = l;
    e.diag.message = "expected ';'";
    e.diag.code = "syntax";
    e.diag.fixits.push_back({SourceRange(l), ";"});
    return e;
  }

  std::vector<Edit> candidates(const ErrorPoint& p) {
    std::vector<Edit> out;
    const antlr4::dfa::Vocabulary& voc = parser_.getVocabulary();
    size_t k = p.index;
    antlr4::Token* off = tok(k);
    if (!off) return out;
    antlr4::Token* prev = k > 0 ? tok(k - 1) : nullptr;

    // 1. A misspelled keyword: the offending token, the one before it (or
    //    before its ';'), or the first token of the statement.
    std::vector<size_t> idx = {k};
    if (k > 0) idx.push_back(k - 1);
    if (k > 1 && prev && prev->getType() == STLexer::SEMI) idx.push_back(k - 2);
    if (p.stmtStart != kNoTokenIndex && p.stmtStart <= k) idx.push_back(p.stmtStart);
    std::vector<size_t> seen;
    for (size_t i : idx) {
      if (std::find(seen.begin(), seen.end(), i) != seen.end()) continue;
      seen.push_back(i);
      antlr4::Token* t = tok(i);
      if (!t || t->getType() != STLexer::IDENTIFIER || !real(t)) continue;
      std::string written(text(t));
      std::string kw = keywordTypo(written);
      size_t type = kw.empty() ? 0 : keywordTokenType(kw, voc);
      if (!type) continue;
      Edit e;
      e.kind = Edit::Retype;
      e.index = i;
      e.type = type;
      SourceRange r = rangeOf(file_.id, t);
      e.diag.severity = Severity::Error;
      e.diag.loc = r.begin;
      e.diag.message = "unknown keyword '" + written + "'; did you mean '" + kw + "'?";
      e.diag.code = "syntax";
      e.diag.ranges.push_back(r);
      e.diag.fixits.push_back({r, kw});
      out.push_back(std::move(e));
    }

    // 2. A keyword used as a name (`by : BYTE;`, `PROGRAM Then`): read it as
    //    an identifier.  Not where an expression is expected.
    if (isKeyword(off->getType()) && real(off) && has(p.expected, STLexer::IDENTIFIER) &&
        !has(p.expected, STLexer::INTEGER_LITERAL) && !isStructureKeyword(off->getType(), voc)) {
      Edit e;
      e.kind = Edit::Retype;
      e.index = k;
      e.type = STLexer::IDENTIFIER;
      SourceRange r = rangeOf(file_.id, off);
      e.diag.severity = Severity::Error;
      e.diag.loc = r.begin;
      e.diag.message = "expected an identifier; '" + std::string(text(off)) + "' is a reserved keyword and cannot be used as a name";
      e.diag.code = "syntax";
      e.diag.ranges.push_back(r);
      out.push_back(std::move(e));
    }

    // 3. A missing ';' at the end of a line, of the file, or before END_IF etc.
    if (prev && real(prev) && has(p.expected, STLexer::SEMI) &&
        (off->getType() == antlr4::Token::EOF || endsStatementList(off->getType()) || newlineBetween(prev, off) ||
         lexed_.isUnterminatedString(prev)))
      out.push_back(expectedSemicolon(k, prev));

    // 4. `f()` NEWLINE `y := 1;`: the name was taken for the S of `a S= b`.
    if (k >= 2 && has(p.expected, STLexer::EQ) && p.expected.size() == 1 && prev && prev->getType() == STLexer::IDENTIFIER &&
        real(tok(k - 2))) {
      std::string up(text(prev));
      for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      if ((up != "S" && up != "R") || newlineBetween(tok(k - 2), prev)) out.push_back(expectedSemicolon(k - 1, tok(k - 2)));
    }

    // 5. An index or an initializer list where the grammar has none
    //    (`FOR a[1] := ...`, `x := [1, 2];`): skip the brackets, or read them
    //    as one operand; the diagnostic is the one already reported.
    if (off->getType() == STLexer::LBRACKET && !has(p.expected, STLexer::LBRACKET)) {
      int depth = 0;
      size_t j = k;
      for (; j < k + 10000; ++j) {
        antlr4::Token* t = tok(j);
        if (!t || t->getType() == antlr4::Token::EOF || t->getType() == STLexer::SEMI) { j = kNoTokenIndex; break; }
        if (t->getType() == STLexer::LBRACKET) ++depth;
        else if (t->getType() == STLexer::RBRACKET && --depth == 0) break;
      }
      if (j != kNoTokenIndex && j < k + 10000) {
        Edit e;
        e.kind = has(p.expected, STLexer::INTEGER_LITERAL) ? Edit::Collapse : Edit::Erase;
        e.index = k;
        e.last = j;
        e.diag = p.diag;
        out.push_back(std::move(e));
      }
    }
    return out;
  }

  uint32_t editOffset(const Edit& e) {
    antlr4::Token* t = tok(e.index);
    if (e.kind == Edit::InsertSemi) return endOf(tok(e.index - 1));
    return t->getType() == antlr4::Token::EOF ? static_cast<uint32_t>(file_.text.size()) : static_cast<uint32_t>(t->getStartIndex());
  }

  void apply(Edit& e) {
    auto& toks = stream_.tokens();
    switch (e.kind) {
      case Edit::Retype: {
        auto* t = static_cast<antlr4::CommonToken*>(toks[e.index].get());
        e.oldType = t->getType();
        t->setType(e.type);
        break;
      }
      case Edit::InsertSemi: {
        antlr4::Token* prev = toks[e.index - 1].get();
        size_t at = prev->getStopIndex() + 1;
        auto semi = std::make_unique<antlr4::CommonToken>(std::make_pair(prev->getTokenSource(), prev->getInputStream()), STLexer::SEMI,
                                                          antlr4::Token::DEFAULT_CHANNEL, at, at - 1);
        semi->setText(";");
        semi->setLine(prev->getLine());
        toks.insert(toks.begin() + static_cast<std::ptrdiff_t>(e.index), std::move(semi));
        stream_.renumber(e.index);
        break;
      }
      case Edit::Erase:
      case Edit::Collapse: {
        size_t first = e.kind == Edit::Erase ? e.index : e.index + 1;
        if (e.kind == Edit::Collapse) {
          auto* t = static_cast<antlr4::CommonToken*>(toks[e.index].get());
          e.oldType = t->getType();
          e.oldStop = t->getStopIndex();
          t->setType(STLexer::IDENTIFIER);
          t->setStopIndex(toks[e.last]->getStopIndex());
        }
        for (size_t i = first; i <= e.last; ++i) e.removed.push_back(std::move(toks[i]));
        toks.erase(toks.begin() + static_cast<std::ptrdiff_t>(first), toks.begin() + static_cast<std::ptrdiff_t>(e.last + 1));
        stream_.renumber(first);
        break;
      }
    }
  }

  void undo(Edit& e) {
    auto& toks = stream_.tokens();
    switch (e.kind) {
      case Edit::Retype:
        static_cast<antlr4::CommonToken*>(toks[e.index].get())->setType(e.oldType);
        break;
      case Edit::InsertSemi:
        toks.erase(toks.begin() + static_cast<std::ptrdiff_t>(e.index));
        stream_.renumber(e.index);
        break;
      case Edit::Erase:
      case Edit::Collapse: {
        size_t first = e.kind == Edit::Erase ? e.index : e.index + 1;
        if (e.kind == Edit::Collapse) {
          auto* t = static_cast<antlr4::CommonToken*>(toks[e.index].get());
          t->setType(e.oldType);
          t->setStopIndex(e.oldStop);
        }
        toks.insert(toks.begin() + static_cast<std::ptrdiff_t>(first), std::make_move_iterator(e.removed.begin()),
                    std::make_move_iterator(e.removed.end()));
        e.removed.clear();
        stream_.renumber(first);
        break;
      }
    }
  }

  // The edit helped if the errors before it are unchanged and the parser now
  // gets past the error it was meant to fix.
  static bool improves(const Run& before, const Run& after, const ErrorPoint& fixed, uint32_t editAt) {
    std::vector<uint32_t> a, b;
    for (const ErrorPoint& x : before.errors) if (x.offset < editAt) a.push_back(x.offset);
    for (const ErrorPoint& x : after.errors) if (x.offset < editAt) b.push_back(x.offset);
    if (a != b) return false;
    for (const ErrorPoint& x : after.errors) {
      if (x.offset < editAt) continue;
      if (x.offset > fixed.offset) return true;
      // At the end of the file: the parser consumed the inserted token.
      return fixed.eof && x.eof && x.index > fixed.index;
    }
    return true;
  }

  STParser& parser_;
  TokenEditStream& stream_;
  const SourceFile& file_;
  const LexedFile& lexed_;
  DiagnosticsEngine& diags_;
};

}  // namespace

STParser::CompilationUnitContext* parseWithRecovery(STParser& parser, TokenEditStream& stream, const SourceFile& file,
                                                    const LexedFile& lexed, DiagnosticsEngine& diags) {
  return Repairer(parser, stream, file, lexed, diags).parse();
}

// Misspelt declaration keywords (`FUNCTION_BLOK F1` ... `END_FUNCTION_BLOK`)
// are repaired before parsing, each with its error: otherwise the first one
// derails the parser and the later ones go unreported.  Only where no
// statement could start: a POU keyword followed by a name on its line, an
// END_/VAR_ keyword alone on its line.
void repairDeclarationKeywordTypos(const SourceFile& file, LexedFile& lexed, DiagnosticsEngine& diags) {
  static const std::set<std::string> kBegin = {"FUNCTION_BLOCK", "FUNCTION", "PROGRAM", "METHOD", "INTERFACE"};
  static const std::set<std::string> kAlone = {"END_FUNCTION_BLOCK", "END_FUNCTION", "END_PROGRAM", "END_METHOD", "END_VAR", "VAR_INPUT",
                                               "VAR_OUTPUT", "VAR_IN_OUT", "VAR_TEMP", "VAR_STAT", "END_TYPE", "END_STRUCT", "END_INTERFACE"};
  auto& toks = lexed.tokens;
  auto newlineBetween = [&](size_t a, size_t b) {   // b > a; offsets of the token ends/starts
    return file.text.find('\n', a) < b;
  };
  bool sfcReported = false;
  for (size_t i = 0; i + 1 < toks.size(); ++i) {
    antlr4::Token* t = toks[i].get();
    if (t->getType() != STLexer::IDENTIFIER) continue;
    bool lineStart = i == 0 || newlineBetween(toks[i - 1]->getStopIndex() + 1, t->getStartIndex());
    if (!lineStart) continue;
    std::string written(file.text.substr(t->getStartIndex(), t->getStopIndex() + 1 - t->getStartIndex()));
    // Textual SFC (STEP ... END_STEP, TRANSITION FROM ... TO ...): said once,
    // plainly, instead of a cascade of syntax errors alone.
    if (!sfcReported && isSfcWord(written) && toks[i + 1]->getType() == STLexer::IDENTIFIER) {
      SourceRange r = rangeOf(file.id, t);
      diags.error(r.begin, "Sequential Function Chart elements ('" + written + "') are not supported; stc compiles Structured Text", "unsupported")
          .range(r);
      sfcReported = true;
    }
    // Only where a declaration keyword could stand (checked first: the edit distance to
    // every keyword is what costs, and most lines start with a name followed by ':=' or '(').
    antlr4::Token* n = toks[i + 1].get();
    bool nextOnLine = n->getType() != antlr4::Token::EOF && !newlineBetween(t->getStopIndex() + 1, n->getStartIndex());
    bool beginShape = nextOnLine && n->getType() == STLexer::IDENTIFIER;
    bool aloneShape = !nextOnLine || n->getType() == STLexer::SEMI;
    if (!beginShape && !aloneShape) continue;
    std::string kw = keywordTypo(written);
    if (kw.empty()) continue;
    bool fits = kBegin.count(kw) ? (nextOnLine && n->getType() == STLexer::IDENTIFIER)
                                 : kAlone.count(kw) && (!nextOnLine || n->getType() == STLexer::SEMI);
    size_t type = fits ? keywordTokenTypeOf(kw) : 0;
    if (!type) continue;
    SourceRange r = rangeOf(file.id, t);
    diags.error(r.begin, "unknown keyword '" + written + "'; did you mean '" + kw + "'?", "syntax").range(r).fixit(r, kw);
    if (auto* ct = dynamic_cast<antlr4::CommonToken*>(t)) ct->setType(type);
  }
}

}  // namespace stc::parse
