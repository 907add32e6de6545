// Shared between the files of compiler/parse only (includes ANTLR).
#pragma once

#include <algorithm>
#include <map>
#include <memory>
#include <vector>

#include "STLexer.h"
#include "STParser.h"
#include "antlr4-runtime.h"
#include "parse/Parser.h"

namespace stc::parse {

using grammar::STLexer;
using grammar::STParser;

// A char stream over raw bytes: one "code point" per byte, so ANTLR token
// indices are byte offsets into the SourceFile text.  Non-ASCII bytes only
// occur in comments, strings and error tokens; their text is taken from the
// source buffer, never from ANTLR.
class ByteInputStream : public antlr4::ANTLRInputStream {
public:
  explicit ByteInputStream(const std::string& bytes, const std::string& name) {
    _data.resize(bytes.size());
    for (size_t i = 0; i < bytes.size(); ++i) _data[i] = static_cast<unsigned char>(bytes[i]);
    name_ = name;
    p = 0;
  }
  std::string getSourceName() const override { return name_; }

private:
  std::string name_;
};

// A CommonToken built without asking its source for line and column (the
// stock constructor does, through two dynamic_casts per token); the fast
// lexer knows the line itself.
class FastToken : public antlr4::CommonToken {
public:
  FastToken(std::pair<antlr4::TokenSource*, antlr4::CharStream*> source, size_t type, size_t channel, size_t start, size_t stop, size_t line)
      : antlr4::CommonToken(type) {
    _source = source;
    _channel = channel;
    _start = start;
    _stop = stop;
    _line = line;
    _charPositionInLine = 0;
  }
};

// The hand-written lexer (FastLexer.cpp): same tokens as STLexer.g4.
class FastLexer {
public:
  FastLexer(const std::string& text, antlr4::TokenSource* source, antlr4::CharStream* stream);
  std::unique_ptr<antlr4::Token> next();
  // Offset of an unterminated comment's opener, if next() stopped at one.
  size_t unterminatedComment() const { return unterminatedComment_; }

private:
  size_t digits(size_t i) const;
  size_t number(size_t i) const;
  size_t timeBody(size_t i) const;
  size_t dateBody(size_t i) const;
  size_t todBody(size_t i) const;
  size_t commentEnd(size_t i);
  std::unique_ptr<antlr4::Token> make(size_t type, size_t start, size_t end, size_t channel);

  const std::string& t_;
  std::pair<antlr4::TokenSource*, antlr4::CharStream*> source_;
  size_t pos_ = 0;
  size_t line_ = 1;
  size_t unterminatedComment_ = std::string::npos;
  std::vector<uint8_t> failedComment_;   // openers known not to close
};

// A token stream whose tokens the error recovery can edit between parses
// (retype a misspelled keyword, insert a missing ';').
class TokenEditStream : public antlr4::CommonTokenStream {
public:
  using antlr4::CommonTokenStream::CommonTokenStream;

protected:
  // As BufferedTokenStream::fetch, without a dynamic_cast per token: every
  // token here is a CommonToken (ours, or the EOF ListTokenSource makes).
  size_t fetch(size_t n) override {
    if (_fetchedEOF) return 0;
    for (size_t i = 0; i < n; ++i) {
      std::unique_ptr<antlr4::Token> t = _tokenSource->nextToken();
      static_cast<antlr4::CommonToken*>(t.get())->setTokenIndex(_tokens.size());
      bool eof = t->getType() == antlr4::Token::EOF;
      _tokens.push_back(std::move(t));
      if (eof) {
        _fetchedEOF = true;
        return i + 1;
      }
    }
    return n;
  }

public:
  // All tokens, EOF last; edits must be followed by renumber().
  std::vector<std::unique_ptr<antlr4::Token>>& tokens() {
    fill();
    return _tokens;
  }
  void renumber(size_t from) {
    for (size_t i = from; i < _tokens.size(); ++i)
      if (auto* w = dynamic_cast<antlr4::WritableToken*>(_tokens[i].get())) w->setTokenIndex(i);
  }
};

// Result of the lexing stage for one file.
struct LexedFile {
  // Tokens keep pointers to their lexer and char stream (ANTLR's error
  // recovery follows them), so both live as long as the tokens.
  std::unique_ptr<ByteInputStream> input;
  std::unique_ptr<STLexer> lexer;
  std::vector<std::unique_ptr<antlr4::Token>> tokens;   // default channel, then EOF
  std::map<uint32_t, std::vector<ast::Pragma>> attributesAt;  // offset of the next token -> attributes
  std::vector<uint32_t> unterminatedStrings;   // start offsets (ascending) of strings missing their closing quote
  bool isUnterminatedString(const antlr4::Token* t) const {
    return t && std::binary_search(unterminatedStrings.begin(), unterminatedStrings.end(), static_cast<uint32_t>(t->getStartIndex()));
  }
};

// Blanks the non-ST trailer sections of CoDeSys 2.3 exports (LIBRARY ...
// END_LIBRARY, PLC_CONFIGURATION ... PLC_END, ...) with a note each.
void skipExportSections(SourceFile& file, DiagnosticsEngine& diags);

// Rewrites full-width punctuation to ASCII in place (warning + fix-it).
void normalizeFullWidth(SourceFile& file, DiagnosticsEngine& diags);

// Lexes, drops trivia, reports bad characters, unterminated comments and
// strings, evaluates pragmas and conditional compilation.
void lexFile(const SourceFile& file, DiagnosticsEngine& diags, const ParseOptions& opts, LexedFile& out);

// Repairs misspelt declaration keywords before parsing (SyntaxErrors.cpp).
void repairDeclarationKeywordTypos(const SourceFile& file, LexedFile& lexed, DiagnosticsEngine& diags);
// The token type of an upper-case keyword, or 0 (FastLexer.cpp; valid once a file was lexed).
size_t keywordTokenTypeOf(const std::string& upper);

// Builds the AST of one compilation unit.
void buildAST(STParser::CompilationUnitContext* cu, const SourceFile& file, const LexedFile& lexed,
              DiagnosticsEngine& diags, ast::ASTContext& ctx, ast::SourceUnit& unit);

// Stage 2 of parsing, after the fast SLL stage failed: full LL with error
// recovery and clang-style diagnostics (SyntaxErrors.cpp).  Before the final
// parse, mistakes with a clear fix (misspelled keyword, keyword used as a
// name, missing ';') are repaired in the token stream and reported once, so
// that they do not cause follow-on errors.  The tree is owned by `parser`.
STParser::CompilationUnitContext* parseWithRecovery(STParser& parser, TokenEditStream& stream, const SourceFile& file,
                                                    const LexedFile& lexed, DiagnosticsEngine& diags);

constexpr size_t kNoTokenIndex = static_cast<size_t>(-1);

// Tokens invented by error recovery have no position (kNoTokenIndex); they are
// placed at the previous real token by the callers, or at 0 here.
inline SourceLoc locOf(uint32_t file, const antlr4::Token* t) {
  size_t s = t->getStartIndex();
  return {file, s == kNoTokenIndex ? 0u : static_cast<uint32_t>(s)};
}
inline SourceRange rangeOf(uint32_t file, const antlr4::Token* t) {
  if (t->getType() == antlr4::Token::EOF || t->getStartIndex() == kNoTokenIndex || t->getStopIndex() < t->getStartIndex())
    return SourceRange(locOf(file, t));
  return {{file, static_cast<uint32_t>(t->getStartIndex())}, {file, static_cast<uint32_t>(t->getStopIndex() + 1)}};
}

}  // namespace stc::parse
