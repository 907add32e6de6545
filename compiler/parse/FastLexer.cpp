// A hand-written lexer producing exactly the tokens of grammar/STLexer.g4
// (same types, same boundaries), several times faster than the generated
// ANTLR lexer.  STLexer.g4 stays the definition of the token vocabulary; the
// unit test LexerDifferential compares the two on every corpus file.
#include <cctype>
#include <cstring>
#include <unordered_map>

#include "basic/Text.h"
#include "parse/ParseInternal.h"
#include "parse/Parser.h"

namespace stc::parse {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool isIdentStart(char c) { return isAlpha(c) || c == '_'; }
bool isIdentChar(char c) { return isIdentStart(c) || isDigit(c); }

const std::unordered_map<std::string, size_t>& keywords(antlr4::TokenSource* lexer = nullptr) {
  static const std::unordered_map<std::string, size_t> kw = [lexer] {
    std::unordered_map<std::string, size_t> m;
    // The vocabulary is static data of the generated lexer; without a lexer at
    // hand (a name checked before any file is lexed) a throwaway one reads it.
    antlr4::ANTLRInputStream none("");
    std::unique_ptr<STLexer> own = lexer ? nullptr : std::make_unique<STLexer>(&none);
    const antlr4::dfa::Vocabulary& v = (lexer ? static_cast<STLexer*>(lexer) : own.get())->getVocabulary();
    // Keyword tokens are the leading run of the vocabulary up to XOR.
    for (size_t t = 1; t <= STLexer::XOR; ++t) m.emplace(v.getSymbolicName(t), t);
    // Spellings of CoDeSys 2.3 exports (the same tokens in STLexer.g4).
    m.emplace("FUNCTIONBLOCK", STLexer::FUNCTION_BLOCK);
    m.emplace("END_FUNCTIONBLOCK", STLexer::END_FUNCTION_BLOCK);
    return m;
  }();
  return kw;
}

}  // namespace

}  // namespace stc::parse

bool stc::isReservedWord(const std::string& name) {
  std::string upper = name;
  for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return parse::keywords().count(upper) != 0;
}

namespace stc::parse {

size_t keywordTokenTypeOf(const std::string& upper) {
  auto it = keywords().find(upper);
  return it == keywords().end() ? 0 : it->second;
}

FastLexer::FastLexer(const std::string& text, antlr4::TokenSource* source, antlr4::CharStream* stream)
    : t_(text), source_({source, stream}) {
  (void)keywords(source);
}

// DIGITS : [0-9] ( '_'? [0-9] )*
size_t FastLexer::digits(size_t i) const {
  if (i >= t_.size() || !isDigit(t_[i])) return i;
  ++i;
  while (i < t_.size()) {
    if (isDigit(t_[i])) ++i;
    else if (t_[i] == '_' && i + 1 < t_.size() && isDigit(t_[i + 1])) i += 2;
    else break;
  }
  return i;
}

// TIME_BODY : TIME_PART ( '_'? TIME_PART )* ;
// TIME_PART : [0-9] [0-9_]* ( '.' [0-9_]+ )? [a-zA-Z]+ ; returns end or npos.
size_t FastLexer::timeBody(size_t i) const {
  size_t n = t_.size();
  bool any = false;
  while (i < n) {
    size_t p = i;
    if (any && t_[p] == '_') ++p;   // separator between two parts
    if (p >= n || !isDigit(t_[p])) break;
    size_t j = p + 1;
    while (j < n && (isDigit(t_[j]) || t_[j] == '_')) ++j;
    if (j + 1 < n && t_[j] == '.' && (isDigit(t_[j + 1]) || t_[j + 1] == '_')) {
      j += 1;
      while (j < n && (isDigit(t_[j]) || t_[j] == '_')) ++j;
    }
    size_t k = j;
    while (k < n && isAlpha(t_[k])) ++k;
    if (k == j) break;   // a part must end in a unit
    i = k;
    any = true;
  }
  return any ? i : std::string::npos;
}

// [0-9]+ ; returns end or npos
size_t FastLexer::number(size_t i) const {
  size_t j = i;
  while (j < t_.size() && isDigit(t_[j])) ++j;
  return j == i ? std::string::npos : j;
}

// DATE : [0-9] [0-9_]* '-' [0-9]+ '-' [0-9]+
size_t FastLexer::dateBody(size_t i) const {
  size_t n = t_.size();
  if (i >= n || !isDigit(t_[i])) return std::string::npos;
  size_t j = i + 1;
  while (j < n && (isDigit(t_[j]) || t_[j] == '_')) ++j;
  for (int part = 0; part < 2; ++part) {
    if (j >= n || t_[j] != '-') return std::string::npos;
    j = number(j + 1);
    if (j == std::string::npos) return j;
  }
  return j;
}

// TOD : [0-9]+ ':' [0-9]+ ( ':' [0-9]+ ( '.' [0-9]+ )? )?
size_t FastLexer::todBody(size_t i) const {
  size_t j = number(i);
  if (j == std::string::npos || j >= t_.size() || t_[j] != ':') return std::string::npos;
  j = number(j + 1);
  if (j == std::string::npos) return j;
  if (j < t_.size() && t_[j] == ':') {
    size_t k = number(j + 1);
    if (k != std::string::npos) {
      j = k;
      if (j < t_.size() && t_[j] == '.') {
        size_t f = number(j + 1);
        if (f != std::string::npos) j = f;
      }
    }
  }
  return j;
}

// End (exclusive) of the comment opening at `i`, or npos if it never closes.
size_t FastLexer::commentEnd(size_t i) {
  const size_t n = t_.size();
  char kind = t_[i];
  if (failedComment_.empty()) failedComment_.assign(n, 0);
  if (failedComment_[i]) return std::string::npos;
  size_t j = i + 2;
  while (j + 1 < n) {
    char d = t_[j], d1 = t_[j + 1];
    if (d == '*' && d1 == (kind == '(' ? ')' : '/')) return j + 2;
    if ((d == '(' || d == '/') && d1 == '*') {
      size_t e = commentEnd(j);
      if (e != std::string::npos) { j = e; continue; }
    }
    ++j;
  }
  failedComment_[i] = 1;
  return std::string::npos;
}

std::unique_ptr<antlr4::Token> FastLexer::make(size_t type, size_t start, size_t end, size_t channel) {
  return std::make_unique<FastToken>(source_, type, channel, start, end - 1, line_);
}

std::unique_ptr<antlr4::Token> FastLexer::next() {
  const size_t n = t_.size();
  size_t i = pos_;
  // Whitespace.
  while (i < n) {
    char c = t_[i];
    if (c == '\n') { ++line_; ++i; }
    else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') ++i;
    else break;
  }
  pos_ = i;
  if (i >= n) return make(antlr4::Token::EOF, n, n, antlr4::Token::DEFAULT_CHANNEL);
  char c = t_[i];
  char c1 = i + 1 < n ? t_[i + 1] : '\0';
  size_t start = i;
  auto tok = [&](size_t type, size_t end, size_t channel = antlr4::Token::DEFAULT_CHANNEL) {
    pos_ = end;
    return make(type, start, end, channel);
  };

  // Comments.  As in STLexer.g4: inside a comment, a nested (* *) or /* */
  // counts only if it is itself closed; the closer is matched first.
  if ((c == '(' || c == '/') && c1 == '*') {
    size_t end = commentEnd(i);
    if (end == std::string::npos) {
      // The ANTLR lexer would give '(' or '/' here and go on; we report the
      // unterminated comment and stop, which reads better.
      unterminatedComment_ = start;
      pos_ = n;
      return make(antlr4::Token::EOF, n, n, antlr4::Token::DEFAULT_CHANNEL);
    }
    for (size_t k = i; k < end; ++k)
      if (t_[k] == '\n') ++line_;
    return tok(c == '(' ? STLexer::BLOCK_COMMENT : STLexer::C_COMMENT, end, STLexer::COMMENTS);
  }
  if (c == '/' && c1 == '/') {
    size_t j = i + 2;
    while (j < n && t_[j] != '\n' && t_[j] != '\r') ++j;
    return tok(STLexer::LINE_COMMENT, j, STLexer::COMMENTS);
  }
  if (c == '{') {
    size_t j = i + 1;
    while (j < n && t_[j] != '}') ++j;
    if (j >= n) return tok(STLexer::ERROR_CHAR, i + 1);
    for (size_t k = i; k < j; ++k)
      if (t_[k] == '\n') ++line_;
    return tok(STLexer::PRAGMA, j + 1, STLexer::PRAGMAS);
  }

  // Identifiers, keywords and prefixed literals.
  if (isIdentStart(c)) {
    size_t j = i + 1;
    while (j < n && isIdentChar(t_[j])) ++j;
    size_t len = j - i;
    char buf[32];
    bool shortWord = len < sizeof buf;
    if (shortWord)
      for (size_t k = 0; k < len; ++k) buf[k] = asciiUpper(t_[i + k]);
    std::string_view w = shortWord ? std::string_view(buf, len) : std::string_view();
    if (shortWord && j < n && t_[j] == '#') {
      auto is = [&](std::initializer_list<const char*> names) {
        for (const char* nm : names)
          if (w == nm) return true;
        return false;
      };
      size_t body = j + 1;
      if (is({"T", "LT", "TIME", "LTIME"})) {
        size_t b = body < n && t_[body] == '-' ? body + 1 : body;
        size_t e = timeBody(b);
        if (e != std::string::npos) return tok(STLexer::TIME_LITERAL, e);
      } else if (is({"DT", "LDT", "DATE_AND_TIME", "LDATE_AND_TIME"})) {
        size_t e = dateBody(body);
        if (e != std::string::npos && e < n && t_[e] == '-') {
          size_t f = number(e + 1);
          if (f != std::string::npos && f < n && t_[f] == ':') {
            size_t g = number(f + 1);
            if (g != std::string::npos) {
              if (g < n && t_[g] == ':') {
                size_t h = number(g + 1);
                if (h != std::string::npos) {
                  g = h;
                  if (g < n && t_[g] == '.') {
                    size_t q = number(g + 1);
                    if (q != std::string::npos) g = q;
                  }
                }
              }
              return tok(STLexer::DATE_TIME_LITERAL, g);
            }
          }
        }
      } else if (is({"D", "LD", "DATE", "LDATE"})) {
        size_t e = dateBody(body);
        if (e != std::string::npos) return tok(STLexer::DATE_LITERAL, e);
      } else if (is({"TOD", "LTOD", "TIME_OF_DAY", "LTIME_OF_DAY"})) {
        size_t e = todBody(body);
        if (e != std::string::npos) return tok(STLexer::TOD_LITERAL, e);
      }
    }
    if (shortWord && w == "REF" && j < n && t_[j] == '=') return tok(STLexer::REF_ASSIGN, j + 1);
    if (shortWord) {
      auto it = keywords().find(std::string(w));
      if (it != keywords().end()) return tok(it->second, j);
    }
    return tok(STLexer::IDENTIFIER, j);
  }

  // Numbers.
  if (isDigit(c)) {
    size_t j = digits(i);
    std::string_view d(t_.data() + i, j - i);
    if (j < n && t_[j] == '#' && (d == "2" || d == "8" || d == "16")) {
      size_t k = j + 1;
      while (k < n && (isIdentChar(t_[k]))) ++k;
      if (k > j + 1) return tok(STLexer::BASED_LITERAL, k);
    }
    auto exponent = [&](size_t p) -> size_t {
      if (p < n && (t_[p] == 'e' || t_[p] == 'E')) {
        size_t q = p + 1;
        if (q < n && (t_[q] == '+' || t_[q] == '-')) ++q;
        size_t r = number(q);
        if (r != std::string::npos) return r;
      }
      return std::string::npos;
    };
    if (j + 1 < n && t_[j] == '.' && isDigit(t_[j + 1])) {
      size_t k = digits(j + 1);
      size_t e = exponent(k);
      return tok(STLexer::REAL_LITERAL, e != std::string::npos ? e : k);
    }
    size_t e = exponent(j);
    if (e != std::string::npos) return tok(STLexer::REAL_LITERAL, e);
    return tok(STLexer::INTEGER_LITERAL, j);
  }

  // Strings.
  if (c == '\'' || c == '"') {
    size_t j = i + 1;
    while (j < n) {
      char d = t_[j];
      if (d == '$') {
        if (j + 1 >= n) { ++j; break; }
        if (t_[j + 1] == '\n') ++line_;
        j += 2;
        continue;
      }
      if (d == c) return tok(c == '\'' ? STLexer::STRING_LITERAL : STLexer::WSTRING_LITERAL, j + 1);
      if (d == '\r' || d == '\n') break;
      ++j;
    }
    return tok(STLexer::UNTERMINATED_STRING, std::min(j, n));
  }

  // Direct addresses and partial access.
  if (c == '%') {
    char a = asciiUpper(c1);
    if (a == 'I' || a == 'Q' || a == 'M') {
      size_t j = i + 2;
      if (j < n && std::strchr("XBWDL", asciiUpper(t_[j])) && asciiUpper(t_[j]) != '\0') ++j;
      if (j < n && t_[j] == '*') return tok(STLexer::DIRECT_ADDRESS, j + 1);
      size_t k = number(j);
      if (k != std::string::npos) {
        while (k + 1 < n && t_[k] == '.' && isDigit(t_[k + 1])) k = number(k + 1);
        return tok(STLexer::DIRECT_ADDRESS, k);
      }
      // %IX without a number: try without the size letter (e.g. %IB is not valid either)
    }
    if (a == 'X' || a == 'B' || a == 'W' || a == 'D') {
      size_t k = number(i + 2);
      if (k != std::string::npos) return tok(STLexer::PARTIAL_ACCESS, k);
    }
    return tok(STLexer::ERROR_CHAR, i + 1);
  }

  // Operators and punctuation.
  switch (c) {
    case ':': return c1 == '=' ? tok(STLexer::ASSIGN, i + 2) : tok(STLexer::COLON, i + 1);
    case '=': return c1 == '>' ? tok(STLexer::OUTPUT_ASSIGN, i + 2) : tok(STLexer::EQ, i + 1);
    case '.': return c1 == '.' ? tok(STLexer::RANGE, i + 2) : tok(STLexer::DOT, i + 1);
    case '*': return c1 == '*' ? tok(STLexer::POWER, i + 2) : tok(STLexer::STAR, i + 1);
    case '<':
      if (c1 == '>') return tok(STLexer::NE, i + 2);
      if (c1 == '=') return tok(STLexer::LE, i + 2);
      return tok(STLexer::LT, i + 1);
    case '>': return c1 == '=' ? tok(STLexer::GE, i + 2) : tok(STLexer::GT, i + 1);
    case '+': return tok(STLexer::PLUS, i + 1);
    case '-': return tok(STLexer::MINUS, i + 1);
    case '/': return tok(STLexer::SLASH, i + 1);
    case '&': return tok(STLexer::AMP, i + 1);
    case '^': return tok(STLexer::CARET, i + 1);
    case ',': return tok(STLexer::COMMA, i + 1);
    case ';': return tok(STLexer::SEMI, i + 1);
    case '#': return tok(STLexer::HASH, i + 1);
    case '(': return tok(STLexer::LPAREN, i + 1);
    case ')': return tok(STLexer::RPAREN, i + 1);
    case '[': return tok(STLexer::LBRACKET, i + 1);
    case ']': return tok(STLexer::RBRACKET, i + 1);
    default: break;
  }
  // One invalid character; a UTF-8 sequence is one token.
  size_t j = i + 1;
  if (static_cast<unsigned char>(c) >= 0xC0)
    while (j < n && (static_cast<unsigned char>(t_[j]) & 0xC0) == 0x80) ++j;
  return tok(STLexer::ERROR_CHAR, j);
}

}  // namespace stc::parse

namespace stc {

std::string compareLexers(const std::string& text) {
  using namespace parse;
  ByteInputStream a(text, "a"), b(text, "b");
  STLexer ref(&a);
  ref.removeErrorListeners();
  STLexer holder(&b);
  FastLexer fast(text, &holder, &b);
  for (size_t n = 0;; ++n) {
    std::unique_ptr<antlr4::Token> x = ref.nextToken();
    std::unique_ptr<antlr4::Token> y = fast.next();
    // The generated lexer sends whitespace to the hidden channel; the fast one skips it.
    while (x->getType() == STLexer::WS) x = ref.nextToken();
    auto show = [&](antlr4::Token* t) {
      return std::string(ref.getVocabulary().getSymbolicName(t->getType())) + "@" + std::to_string(t->getStartIndex()) + ".." +
             std::to_string(t->getStopIndex());
    };
    // At an unterminated comment the fast lexer stops and reports; ANTLR's
    // non-greedy rule may close it at an inner "*)" instead (see STLexer.g4).
    if (y->getType() == antlr4::Token::EOF && fast.unterminatedComment() != std::string::npos) return "";
    if (x->getType() != y->getType() || (x->getType() != antlr4::Token::EOF && (x->getStartIndex() != y->getStartIndex() ||
                                                                              x->getStopIndex() != y->getStopIndex())))
      return "token " + std::to_string(n) + ": ANTLR lexer " + show(x.get()) + ", fast lexer " + show(y.get());
    if (x->getType() == antlr4::Token::EOF) return "";
  }
}

}  // namespace stc
