// Lexer and parser of one G-code block (one line) of the DIN 66025 dialect
// (docs/cnc.md, "Syntax").  A Block is a fixed-size value the parser refills
// for every line, so parsing allocates nothing; words keep byte offsets into
// the source for diagnostics and for $variable$ names.
//
// The parser checks what a word means on its own (letters, number syntax,
// integers for N/G/M/H, the ranges of M/H/N, known G codes, magnitudes,
// duplicates, H/L/O pairing); what a word means in its block and in the modal
// state is the decoder's business.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <utility>

#include "basic/Diagnostics.h"
#include "stdlib-motion/cnc/Element.h"

namespace stc::cnc {

// Decoder error numbers of SMC_ERROR (the CODESYS SMC_NCDecoder's), for the
// function blocks' wErrorID.
enum class SmcError : uint16_t {
  NoError = 0,
  AccTooLittle = 1200,            // acceleration value not allowed
  RetTooLittle = 1201,            // deceleration value not allowed
  JumpToUnknownLine = 1203,
  InvalidSyntax = 1204,           // everything else
  ObjectNot3D = 1205,             // G5/G6/G8/G9 outside the XY plane
  ExclusiveAU = 1207,             // A and U in one program
  ExclusiveBV = 1208,
  ExclusiveCW = 1209,
};

// Word slots: the 26 letters A..Z, then the signed and two-letter forms.
enum Slot : uint8_t {
  SlotEMinus = 26,   // E-  deceleration
  SlotFF = 27,       // FF  G0 velocity
  SlotEF = 28,       // EF  G0 acceleration
  SlotEFMinus = 29,  // EF- G0 deceleration
  kSlotCount = 30,
};
constexpr uint8_t slotOf(char upperLetter) { return static_cast<uint8_t>(upperLetter - 'A'); }
constexpr uint32_t bit(char upperLetter) { return 1u << slotOf(upperLetter); }
// "X", "E-", "FF" ...
std::string slotName(uint8_t slot);

enum class WordKind : uint8_t { Literal, Variable, LabelRef };

struct Word {
  uint8_t slot = 0;
  WordKind kind = WordKind::Literal;
  bool negate = false;          // Variable: written -$name$
  uint32_t begin = 0, end = 0;  // the whole word
  double value = 0;             // Literal: the value (sign applied); LabelRef: the label index
  uint32_t nameBegin = 0, nameEnd = 0;   // Variable: the name between the dollars
};

constexpr int kMaxWords = 48;
constexpr int kMaxGWords = 8;

struct Block {
  uint32_t begin = 0, end = 0;  // the line, without its line break
  uint32_t line = 0;            // 1-based
  bool header = false;          // %name line
  bool skip = false;            // starts with '/'
  bool bad = false;             // a syntax error was reported: not decoded
  bool hasN = false, hasLabel = false;
  int32_t n = -1, label = -1;   // N number, L!label
  uint32_t nBegin = 0, nEnd = 0, labelBegin = 0, labelEnd = 0;
  uint32_t headerAt = 0;                  // header: the '%'
  uint32_t nameBegin = 0, nameEnd = 0;    // header: the program name
  uint32_t present = 0;         // bit per slot with a word (switch L/O excluded)
  int8_t at[kSlotCount];        // index of the slot's word, -1 if none (G: the first)
  uint8_t count = 0;
  Word words[kMaxWords];
  uint8_t gCount = 0;
  uint8_t g[kMaxGWords];        // indices of the G words
  struct Switch { uint8_t h; int8_t pos; };   // H word and its L/O word (-1: none)
  uint8_t switchCount = 0;
  Switch switches[kMaxSwitches];

  bool has(char upperLetter) const { return present & bit(upperLetter); }
  const Word& word(char upperLetter) const { return words[at[slotOf(upperLetter)]]; }
  const Word* find(uint8_t slot) const { return at[slot] >= 0 ? &words[at[slot]] : nullptr; }
  // TRUE if the block has nothing to decode (empty line, comment, lone N).
  bool empty() const { return count == 0 && !header; }
};

// Reports G-code diagnostics at byte offsets of one file.  A location is
// reported once per message (jumps decode blocks again); quiet reporters
// (index scans) drop everything.
class Reporter {
public:
  Reporter(DiagnosticsEngine* diags, uint32_t file) : diags_(diags), file_(file) {}
  DiagBuilder error(uint32_t begin, uint32_t end, std::string message, const char* code,
                    SmcError id = SmcError::InvalidSyntax);
  DiagBuilder warning(uint32_t begin, uint32_t end, std::string message, const char* name);
  SourceLoc loc(uint32_t offset) const { return SourceLoc{file_, offset}; }
  SourceRange range(uint32_t begin, uint32_t end) const { return SourceRange(loc(begin), loc(end)); }
  unsigned errors() const { return errors_; }
  SmcError firstError() const { return first_; }
  bool quiet = false;

private:
  bool seenBefore(uint32_t begin, const std::string& message);
  DiagnosticsEngine* diags_;
  uint32_t file_;
  unsigned errors_ = 0;
  SmcError first_ = SmcError::NoError;
  std::set<std::pair<uint32_t, std::string>> seen_;
};

// The shortest text that reads back as v ("12.5", "1e+20"): for values the
// user wrote.
std::string formatNumber(double v);
// Six significant digits ("8.30004"): for values the decoder computed.
std::string formatApprox(double v);

// Checks a value of a word that does not depend on the block: finite,
// |v| <= 1e12, N/G/M/H integers in range.  Returns an error message or "".
// Literals are checked by the parser, variable values by the decoder.
std::string checkWordValue(uint8_t slot, double v);

// The G codes of the dialect.
bool isKnownGCode(int g);

class BlockParser {
public:
  BlockParser(std::string_view text, Reporter& reporter) : text_(text), rep_(reporter) {}
  // Parses the line starting at `offset` (line number `line`) into `b`;
  // returns the offset of the next line.
  uint32_t parse(uint32_t offset, uint32_t line, Block& b);

private:
  uint32_t word(uint32_t pos, Block& b);
  uint32_t blockNumber(uint32_t start, uint32_t pos, Block& b);
  uint32_t label(uint32_t start, uint32_t pos, Block& b);
  uint32_t unsignedInt(uint32_t pos, int64_t& v, bool& ok) const;
  uint32_t skipToken(uint32_t pos) const;
  uint32_t lineEnd(uint32_t pos) const;
  void addWord(Block& b, const Word& w);
  void fail(Block& b) { b.bad = true; }
  std::string_view text_;
  Reporter& rep_;
};

}  // namespace stc::cnc
