// Lexing stage: text normalisation, trivia removal, pragma evaluation.
#include <cctype>
#include <cstdio>

#include "basic/Text.h"
#include "parse/ParseInternal.h"

namespace stc::parse {

namespace {

struct FullWidth {
  uint32_t cp;
  char ascii;
};
// Punctuation that PDF-extracted Chinese manuals put into code.
constexpr FullWidth kFullWidth[] = {
    {0xFF0C, ','}, {0xFF1B, ';'}, {0xFF08, '('}, {0xFF09, ')'}, {0xFF1A, ':'}, {0xFF1D, '='},
    {0xFF1C, '<'}, {0xFF1E, '>'}, {0xFF3B, '['}, {0xFF3D, ']'}, {0xFF0B, '+'}, {0xFF0D, '-'},
    {0xFF0A, '*'}, {0xFF0F, '/'}, {0x3000, ' '}, {0x2013, '-'}, {0x2014, '-'}, {0x2018, '\''},
    {0x2019, '\''}, {0x201C, '"'}, {0x201D, '"'}, {0x3001, ','}, {0xFF0E, '.'},
};

// Decodes the 3-byte UTF-8 sequence at `i`, or returns 0.
uint32_t decode3(const std::string& t, size_t i) {
  if (i + 2 >= t.size()) return 0;
  unsigned char a = t[i], b = t[i + 1], c = t[i + 2];
  if ((a & 0xF0) != 0xE0 || (b & 0xC0) != 0x80 || (c & 0xC0) != 0x80) return 0;
  return ((a & 0x0F) << 12) | ((b & 0x3F) << 6) | (c & 0x3F);
}

char fullWidthAscii(uint32_t cp) {
  for (const FullWidth& f : kFullWidth)
    if (f.cp == cp) return f.ascii;
  return 0;
}

std::string hex(uint32_t cp) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "U+%04X", cp);
  return buf;
}

}  // namespace

void normalizeFullWidth(SourceFile& file, DiagnosticsEngine& diags) {
  std::string& t = file.text;
  // Fast exit: nothing above ASCII.
  bool any = false;
  for (char c : t)
    if (static_cast<unsigned char>(c) >= 0x80) { any = true; break; }
  if (!any) return;

  enum State { Code, Line, Block, String, WString, Pragma } st = Code;
  int depth = 0;
  bool stringFromTypographic = false;
  std::string original;
  for (size_t i = 0; i < t.size(); ++i) {
    char c = t[i];
    switch (st) {
      case Code: {
        if (c == '/' && i + 1 < t.size() && t[i + 1] == '/') { st = Line; ++i; continue; }
        if ((c == '(' || c == '/') && i + 1 < t.size() && t[i + 1] == '*') { st = Block; depth = 1; ++i; continue; }
        if (c == '\'') { st = String; stringFromTypographic = false; continue; }
        if (c == '"') { st = WString; stringFromTypographic = false; continue; }
        if (c == '{') { st = Pragma; continue; }
        uint32_t cp = decode3(t, i);
        char a = cp ? fullWidthAscii(cp) : 0;
        if (!a) continue;
        if (original.empty()) original = t;
        SourceLoc loc{file.id, static_cast<uint32_t>(i)};
        SourceRange r(loc, {file.id, static_cast<uint32_t>(i + 3)});
        std::string ch = t.substr(i, 3);
        std::string asciiStr(1, a);
        if (a == '\'' || a == '"')
          diags.warning(loc, "typographic quote '" + ch + "' (" + hex(cp) + ") treated as " + (a == '"' ? "'\"'" : "\"'\""), "fullwidth-punctuation")
              .range(r).fixit(r, asciiStr);
        else if (a == ' ')
          diags.warning(loc, "full-width space (" + hex(cp) + ") treated as a space", "fullwidth-punctuation").range(r).fixit(r, " ");
        else
          diags.warning(loc, "full-width character '" + ch + "' (" + hex(cp) + ") treated as '" + asciiStr + "'", "fullwidth-punctuation")
              .range(r).fixit(r, asciiStr);
        if (a == '(' || a == '[') {
          // Pad before an opening bracket so that "（*" becomes "(*" and is
          // then read as a comment opener by the Code state below.
          t[i] = ' ';
          t[i + 1] = ' ';
          t[i + 2] = a;
          i += 1;
          continue;
        }
        t[i] = a;
        t[i + 1] = ' ';
        t[i + 2] = ' ';
        if (a == '\'') { st = String; stringFromTypographic = true; }
        else if (a == '"') { st = WString; stringFromTypographic = true; }
        i += 2;
        break;
      }
      case Line:
        if (c == '\n' || c == '\r') st = Code;
        break;
      case Block:
        if (c == '*' && decode3(t, i + 1) == 0xFF09) {
          // "*）" closes a comment opened with a full-width parenthesis.
          if (original.empty()) original = t;
          SourceLoc loc{file.id, static_cast<uint32_t>(i + 1)};
          SourceRange r(loc, {file.id, static_cast<uint32_t>(i + 4)});
          diags.warning(loc, "full-width character '" + t.substr(i + 1, 3) + "' (U+FF09) treated as ')'", "fullwidth-punctuation").range(r).fixit(r, ")");
          t[i + 1] = ')';
          t[i + 2] = ' ';
          t[i + 3] = ' ';
        }
        if ((c == '(' || c == '/') && i + 1 < t.size() && t[i + 1] == '*') { ++depth; ++i; }
        else if (c == '*' && i + 1 < t.size() && (t[i + 1] == ')' || t[i + 1] == '/')) { if (--depth == 0) st = Code; ++i; }
        break;
      case String:
      case WString: {
        char q = st == String ? '\'' : '"';
        if (c == '$') { ++i; break; }
        if (c == q || c == '\n' || c == '\r') { st = Code; break; }
        if (stringFromTypographic) {
          uint32_t cp = decode3(t, i);
          if (cp && fullWidthAscii(cp) == q) {
            if (original.empty()) original = t;
            SourceLoc loc{file.id, static_cast<uint32_t>(i)};
            SourceRange r(loc, {file.id, static_cast<uint32_t>(i + 3)});
            diags.warning(loc, "typographic quote '" + t.substr(i, 3) + "' (" + hex(cp) + ") treated as " + (q == '"' ? "'\"'" : "\"'\""),
                          "fullwidth-punctuation").range(r).fixit(r, std::string(1, q));
            t[i] = q; t[i + 1] = ' '; t[i + 2] = ' ';
            i += 2;
            st = Code;
          }
        }
        break;
      }
      case Pragma:
        if (c == '}') st = Code;
        break;
    }
  }
  if (!original.empty()) file.original = std::move(original);
}

namespace {


std::string trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

// Evaluates the condition of {IF ...}: defined(X), NOT, AND, OR, (), TRUE, FALSE.
class CondParser {
public:
  CondParser(std::string_view s, const std::set<std::string>& defs) : s_(s), defs_(defs) {}
  bool parse(bool& value, std::string& error) {
    value = orExpr();
    skip();
    if (ok_ && pos_ != s_.size()) fail("unexpected '" + std::string(s_.substr(pos_)) + "'");
    error = err_;
    return ok_;
  }

private:
  void skip() { while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_; }
  void fail(std::string m) { if (ok_) { ok_ = false; err_ = std::move(m); } }
  // The next word, lower-cased (names are case-insensitive); `asWritten`
  // receives its spelling in the source, for messages.
  std::string word(std::string* asWritten = nullptr) {
    skip();
    size_t b = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_' || s_[pos_] == '.')) ++pos_;
    if (asWritten) *asWritten = std::string(s_.substr(b, pos_ - b));
    return asciiLower(s_.substr(b, pos_ - b));
  }
  bool peekWord(const char* w) {
    size_t save = pos_;
    bool r = word() == w;
    pos_ = save;
    return r;
  }
  bool orExpr() {
    bool v = andExpr();
    while (ok_ && peekWord("or")) { word(); bool r = andExpr(); v = v || r; }
    return v;
  }
  bool andExpr() {
    bool v = unary();
    while (ok_ && peekWord("and")) { word(); bool r = unary(); v = v && r; }
    return v;
  }
  bool unary() {
    if (peekWord("not")) { word(); return !unary(); }
    skip();
    if (pos_ < s_.size() && s_[pos_] == '(') {
      ++pos_;
      bool v = orExpr();
      skip();
      if (pos_ < s_.size() && s_[pos_] == ')') ++pos_; else fail("expected ')'");
      return v;
    }
    std::string written;
    std::string w = word(&written);
    if (w == "true") return true;
    if (w == "false") return false;
    if (w == "defined") {
      skip();
      if (pos_ >= s_.size() || s_[pos_] != '(') { fail("expected '(' after defined"); return false; }
      ++pos_;
      std::string name = word();
      skip();
      // CODESYS forms defined(variable: x), defined(pou: x), defined(type: x):
      // only compile-time defines are known here, so they test the define set.
      if (pos_ < s_.size() && s_[pos_] == ':') { ++pos_; name = word(); skip(); }
      if (pos_ < s_.size() && s_[pos_] == ')') ++pos_; else fail("expected ')'");
      return defs_.count(name) != 0;
    }
    fail(w.empty() ? "expected a condition" : "unsupported condition '" + written + "'");
    return false;
  }
  std::string_view s_;
  const std::set<std::string>& defs_;
  size_t pos_ = 0;
  bool ok_ = true;
  std::string err_;
};

// Reads a '...' string at the start of `s` (after trimming); returns false if none.
bool quoted(std::string_view s, std::string& out, size_t& consumed) {
  size_t i = 0;
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  if (i >= s.size() || (s[i] != '\'' && s[i] != '"')) return false;
  char q = s[i++];
  size_t b = i;
  while (i < s.size() && s[i] != q) ++i;
  if (i >= s.size()) return false;
  out = std::string(s.substr(b, i - b));
  consumed = i + 1;
  return true;
}

struct CondFrame {
  bool parentActive;
  bool active;
  bool taken;
  bool sawElse;
  SourceLoc loc;
  SourceLoc elseLoc = {};
};

}  // namespace

void lexFile(const SourceFile& file, DiagnosticsEngine& diags, const ParseOptions& opts, LexedFile& out) {
  out.input = std::make_unique<ByteInputStream>(file.text, file.path);
  out.lexer = std::make_unique<STLexer>(out.input.get());
  out.lexer->removeErrorListeners();
  FastLexer lexer(file.text, out.lexer.get(), out.input.get());
  std::set<std::string> defines = opts.defines;
  std::vector<CondFrame> conds;
  std::vector<ast::Pragma> pendingAttrs;
  bool active = true;
  const std::string& t = file.text;
  out.tokens.reserve(t.size() / 5 + 16);

  auto here = [&](antlr4::Token* tok) { return locOf(file.id, tok); };
  // Joining names around non-ASCII letters (see the ERROR_CHAR case).
  auto isWordToken = [](size_t ty) {
    return ty == STLexer::IDENTIFIER || ty == STLexer::INTEGER_LITERAL || (ty >= 1 && ty <= STLexer::XOR);
  };
  bool lastGlued = false;
  size_t pendingStart = std::string::npos, pendingEnd = 0;

  while (true) {
    std::unique_ptr<antlr4::Token> tok = lexer.next();
    size_t type = tok->getType();
    if (type == antlr4::Token::EOF) {
      if (lexer.unterminatedComment() != std::string::npos) {
        SourceLoc l{file.id, static_cast<uint32_t>(lexer.unterminatedComment())};
        diags.error(l, "unterminated comment", "syntax").range(SourceRange(l, {file.id, l.offset + 2}));
      }
      if (!conds.empty())
        diags.error(conds.back().loc, "unterminated '{IF}' pragma: missing '{END_IF}'", "pragma");
      out.tokens.push_back(std::move(tok));
      break;
    }
    if (type == STLexer::PRAGMA) {
      std::string_view text(t.data() + tok->getStartIndex() + 1, tok->getStopIndex() - tok->getStartIndex() - 1);
      std::string body = trim(text);
      std::string lw = asciiLower(body);
      SourceRange r = rangeOf(file.id, tok.get());
      auto starts = [&](const char* kw) {
        size_t n = std::char_traits<char>::length(kw);
        return lw.compare(0, n, kw) == 0 && (lw.size() == n || (!std::isalnum(static_cast<unsigned char>(lw[n])) && lw[n] != '_'));
      };
      std::string error;
      if (starts("if")) {
        bool v = false;
        if (active && !CondParser(std::string_view(body).substr(2), defines).parse(v, error))
          diags.error(here(tok.get()), "invalid {IF} condition: " + error, "pragma").range(r);
        conds.push_back({active, active && v, active && v, false, here(tok.get())});
        active = conds.back().active;
      } else if (starts("elsif")) {
        if (conds.empty()) {
          diags.error(here(tok.get()), "'{ELSIF}' without a matching '{IF}'", "pragma").range(r);
        } else if (conds.back().sawElse) {
          diags.error(here(tok.get()), "'{ELSIF}' after '{ELSE}'", "pragma").range(r).note(conds.back().elseLoc, "'{ELSE}' is here");
        } else {
          CondFrame& f = conds.back();
          bool v = false;
          if (f.parentActive && !f.taken && !CondParser(std::string_view(body).substr(5), defines).parse(v, error))
            diags.error(here(tok.get()), "invalid {ELSIF} condition: " + error, "pragma").range(r);
          f.active = f.parentActive && !f.taken && v;
          f.taken = f.taken || f.active;
          active = f.active;
        }
      } else if (starts("else")) {
        if (conds.empty()) {
          diags.error(here(tok.get()), "'{ELSE}' without a matching '{IF}'", "pragma").range(r);
        } else if (conds.back().sawElse) {
          diags.error(here(tok.get()), "'{ELSE}' after '{ELSE}'", "pragma").range(r).note(conds.back().elseLoc, "the first '{ELSE}' is here");
        } else {
          CondFrame& f = conds.back();
          f.sawElse = true;
          f.elseLoc = here(tok.get());
          f.active = f.parentActive && !f.taken;
          f.taken = true;
          active = f.active;
        }
      } else if (starts("end_if")) {
        if (conds.empty()) {
          diags.error(here(tok.get()), "'{END_IF}' without a matching '{IF}'", "pragma").range(r);
        } else {
          active = conds.back().parentActive;
          conds.pop_back();
        }
      } else if (!active) {
        // other pragmas inside an inactive region are ignored
      } else if (starts("attribute")) {
        ast::Pragma p;
        size_t used = 0;
        std::string rest = body.substr(9);
        if (!quoted(rest, p.name, used)) {
          diags.error(here(tok.get()), "expected a quoted attribute name, as in {attribute 'name'}", "pragma").range(r);
        } else {
          std::string tail = trim(std::string_view(rest).substr(used));
          if (tail.rfind(":=", 0) == 0) {
            size_t u2 = 0;
            if (!quoted(tail.substr(2), p.value, u2))
              diags.error(here(tok.get()), "expected a quoted attribute value after ':='", "pragma").range(r);
          } else if (!tail.empty()) {
            diags.warning(here(tok.get()), "extra text after the attribute name is ignored", "pragma").range(r);
          }
          p.range = r;
          pendingAttrs.push_back(std::move(p));
        }
      } else if (starts("warning") || starts("error") || starts("info") || starts("message")) {
        bool isErr = starts("error");
        size_t kwLen = starts("warning") ? 7 : isErr ? 5 : starts("info") ? 4 : 7;
        std::string msg;
        size_t used = 0;
        if (!quoted(body.substr(kwLen), msg, used)) msg = trim(body.substr(kwLen));
        if (isErr) diags.error(here(tok.get()), msg, "user-pragma").range(r);
        else if (starts("warning")) diags.warning(here(tok.get()), msg, "user-pragma").range(r);
        else diags.note(here(tok.get()), msg).range(r);
      } else if (starts("define")) {
        std::string name = asciiLower(trim(body.substr(6)));
        size_t sp = name.find_first_of(" \t");
        if (sp != std::string::npos) name = name.substr(0, sp);
        if (name.empty()) diags.error(here(tok.get()), "expected a name after 'define'", "pragma").range(r);
        else defines.insert(name);
      } else if (starts("undefine")) {
        defines.erase(asciiLower(trim(body.substr(8))));
      } else if (starts("library") || starts("flag") || starts("text") || starts("messageguid") || starts("implicit")) {
        // CODESYS export bookkeeping pragmas: no meaning for compilation.
      } else {
        diags.warning(here(tok.get()), "unknown pragma '{" + body + "}' ignored", "unknown-pragma").range(r);
      }
      continue;
    }
    if (tok->getChannel() != antlr4::Token::DEFAULT_CHANNEL) continue;
    if (!active) continue;
    if (type == STLexer::ERROR_CHAR) {
      size_t b = tok->getStartIndex();
      unsigned char c = static_cast<unsigned char>(t[b]);
      SourceLoc l = here(tok.get());
      if (c >= 0x80) {
        // Swallow the rest of the UTF-8 sequence (continuation bytes).
        size_t e = tok->getStopIndex() + 1;
        std::string seq = t.substr(b, e - b);
        diags.error(l, "non-ASCII character '" + seq + "' is not allowed outside strings and comments", "invalid-character")
            .range(SourceRange(l, {file.id, static_cast<uint32_t>(e)}));
        // A letter such as 'ö' inside a name (grösse): the name stays one
        // identifier token, so the parser does not report its pieces.
        if (!out.tokens.empty() && out.tokens.back()->getStopIndex() + 1 == b && isWordToken(out.tokens.back()->getType())) {
          auto* last = static_cast<antlr4::CommonToken*>(out.tokens.back().get());
          last->setStopIndex(e - 1);
          last->setType(STLexer::IDENTIFIER);
          lastGlued = true;
        } else if (pendingStart != std::string::npos && pendingEnd == b) {
          pendingEnd = e;
        } else {
          pendingStart = b;
          pendingEnd = e;
        }
        continue;
      } else if (c < 0x20 || c == 0x7F) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "0x%02X", c);
        diags.error(l, std::string("invalid control character ") + buf + " in source", "invalid-character");
      } else {
        diags.error(l, std::string("invalid character '") + static_cast<char>(c) + "' in source", "invalid-character")
            .range(rangeOf(file.id, tok.get()));
      }
      continue;
    }
    // The rest of a name after a non-ASCII letter joins it (see above).
    if (lastGlued && isWordToken(type) && out.tokens.back()->getStopIndex() + 1 == tok->getStartIndex()) {
      static_cast<antlr4::CommonToken*>(out.tokens.back().get())->setStopIndex(tok->getStopIndex());
      continue;
    }
    lastGlued = false;
    if (pendingStart != std::string::npos) {
      if (pendingEnd == tok->getStartIndex() && isWordToken(type)) {
        auto* ct = static_cast<antlr4::CommonToken*>(tok.get());
        ct->setStartIndex(pendingStart);
        ct->setType(STLexer::IDENTIFIER);
        type = STLexer::IDENTIFIER;
        lastGlued = true;
      }
      pendingStart = std::string::npos;
    }
    if (type == STLexer::UNTERMINATED_STRING) {
      SourceLoc l = here(tok.get());
      char q = t[tok->getStartIndex()];
      diags.error(l, std::string("missing terminating ") + q + " character", "syntax").range(rangeOf(file.id, tok.get()));
      out.unterminatedStrings.push_back(static_cast<uint32_t>(tok->getStartIndex()));
      static_cast<antlr4::CommonToken*>(tok.get())->setType(q == '\'' ? STLexer::STRING_LITERAL : STLexer::WSTRING_LITERAL);
      type = tok->getType();
    }
    if (!pendingAttrs.empty()) {
      out.attributesAt[static_cast<uint32_t>(tok->getStartIndex())] = std::move(pendingAttrs);
      pendingAttrs.clear();
    }
    out.tokens.push_back(std::move(tok));
  }
  // MOD(a, b), AND(a, b, ...), OR(...), XOR(...) are also standard functions:
  // where an operand is expected, such a keyword followed by '(' is the
  // function's name, not the operator.
  auto endsOperand = [](size_t ty) {
    return ty == STLexer::IDENTIFIER || ty == STLexer::RPAREN || ty == STLexer::RBRACKET || ty == STLexer::CARET ||
           ty == STLexer::INTEGER_LITERAL || ty == STLexer::REAL_LITERAL || ty == STLexer::BASED_LITERAL || ty == STLexer::STRING_LITERAL ||
           ty == STLexer::WSTRING_LITERAL || ty == STLexer::TIME_LITERAL || ty == STLexer::DATE_LITERAL || ty == STLexer::TOD_LITERAL ||
           ty == STLexer::DATE_TIME_LITERAL || ty == STLexer::TRUE || ty == STLexer::FALSE || ty == STLexer::DIRECT_ADDRESS;
  };
  for (size_t i = 0; i + 1 < out.tokens.size(); ++i)
    if ((out.tokens[i]->getType() == STLexer::MOD || out.tokens[i]->getType() == STLexer::AND || out.tokens[i]->getType() == STLexer::OR ||
         out.tokens[i]->getType() == STLexer::XOR) &&
        out.tokens[i + 1]->getType() == STLexer::LPAREN &&
        (i == 0 || !endsOperand(out.tokens[i - 1]->getType())))
      static_cast<antlr4::CommonToken*>(out.tokens[i].get())->setType(STLexer::IDENTIFIER);
}

}  // namespace stc::parse
