#include "stdlib-motion/cnc/Parser.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace stc::cnc {

namespace {

inline bool isDigit(char c) { return c >= '0' && c <= '9'; }
inline bool isAlpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
inline char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; }
inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                             1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// A character for a message: printable ASCII as is, a UTF-8 sequence whole,
// anything else as \xNN.
std::string showChar(std::string_view text, uint32_t pos, uint32_t& len) {
  unsigned char c = static_cast<unsigned char>(text[pos]);
  len = 1;
  if (c >= 0x20 && c < 0x7f) return std::string(1, static_cast<char>(c));
  unsigned n = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
  if (n && pos + n <= text.size()) {
    bool ok = true;
    for (unsigned k = 1; k < n; ++k) ok &= (static_cast<unsigned char>(text[pos + k]) & 0xC0) == 0x80;
    if (ok) {
      len = n;
      return std::string(text.substr(pos, n));
    }
  }
  static const char* hex = "0123456789ABCDEF";
  return std::string("\\x") + hex[c >> 4] + hex[c & 15];
}

}  // namespace

std::string slotName(uint8_t slot) {
  switch (slot) {
    case SlotEMinus: return "E-";
    case SlotFF: return "FF";
    case SlotEF: return "EF";
    case SlotEFMinus: return "EF-";
    default: return std::string(1, static_cast<char>('A' + slot));
  }
}

std::string formatNumber(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string formatApprox(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// ---------------------------------------------------------------- Reporter

bool Reporter::seenBefore(uint32_t begin, const std::string& message) {
  return !seen_.emplace(begin, message).second;
}

DiagBuilder Reporter::error(uint32_t begin, uint32_t end, std::string message, const char* code, SmcError id) {
  if (quiet || !diags_ || seenBefore(begin, message)) return DiagBuilder(nullptr, Diagnostic{});
  ++errors_;
  if (first_ == SmcError::NoError) first_ = id;
  DiagBuilder d = diags_->error(loc(begin), std::move(message), code);
  if (end > begin) d.range(range(begin, end));
  return d;
}

DiagBuilder Reporter::warning(uint32_t begin, uint32_t end, std::string message, const char* name) {
  if (quiet || !diags_ || seenBefore(begin, message)) return DiagBuilder(nullptr, Diagnostic{});
  DiagBuilder d = diags_->warning(loc(begin), std::move(message), name);
  if (end > begin) d.range(range(begin, end));
  return d;
}

// ---------------------------------------------------------------- values

bool isKnownGCode(int g) {
  switch (g) {
    case 0: case 1: case 2: case 3: case 4: case 5: case 6: case 8: case 9: case 10:
    case 16: case 17: case 18: case 19: case 20: case 25: case 36: case 37:
    case 40: case 41: case 42: case 50: case 51: case 52: case 53: case 54: case 55: case 56:
    case 60: case 61: case 75: case 90: case 91: case 92: case 98: case 99:
      return true;
    default:
      return false;
  }
}

std::string checkWordValue(uint8_t slot, double v) {
  std::string name = slotName(slot);
  if (!std::isfinite(v)) return "the value of '" + name + "' is not a finite number";
  if (std::fabs(v) > 1e12) return "the value of '" + name + "' (" + formatNumber(v) + ") is out of range (magnitude above 1e12)";
  char letter = slot < 26 ? static_cast<char>('A' + slot) : 0;
  bool integral = v == std::trunc(v);
  switch (letter) {
    case 'N':
      if (!integral || v < 0 || v > 2147483647.0) return "a block number is an integer from 0 to 2147483647";
      break;
    case 'G':
      if (!integral || v < 0) return "a G code is a non-negative integer";
      if (v > 999) return "unknown G code 'G" + formatNumber(v) + "'";
      break;
    case 'M':
      if (!integral) return "an M function number is an integer";
      if (v >= 65533 && v <= 65535) return "M" + formatNumber(v) + " is reserved for internal functions (M functions are 1..65532)";
      if (v < 1 || v > 65535) return "M" + formatNumber(v) + " is out of range (M functions are 1..65532)";
      break;
    case 'H':
      if (!integral) return "a switch number H is an integer";
      if (std::fabs(v) > 32767) return "H" + formatNumber(v) + " is out of range (switch numbers are 1..32767, negative to switch off)";
      break;
    default:
      break;
  }
  return {};
}

// ---------------------------------------------------------------- parser

uint32_t BlockParser::lineEnd(uint32_t pos) const {
  size_t e = text_.find('\n', pos);
  return static_cast<uint32_t>(e == std::string_view::npos ? text_.size() : e);
}

uint32_t BlockParser::skipToken(uint32_t pos) const {
  while (pos < text_.size() && !isBlank(text_[pos]) && text_[pos] != '\n' && text_[pos] != '(' && text_[pos] != ';')
    ++pos;
  return pos;
}

uint32_t BlockParser::unsignedInt(uint32_t pos, int64_t& v, bool& ok) const {
  v = 0;
  ok = false;
  uint32_t n = static_cast<uint32_t>(text_.size());
  while (pos < n && isDigit(text_[pos])) {
    if (v <= 99999999999) v = v * 10 + (text_[pos] - '0');
    ok = true;
    ++pos;
  }
  return pos;
}

void BlockParser::addWord(Block& b, const Word& w) {
  if (b.count >= kMaxWords) {
    if (b.count == kMaxWords) {
      rep_.error(w.begin, w.end, "more than " + std::to_string(kMaxWords) + " words in one block", "gcode-syntax");
      ++b.count;   // report once; the block is dropped
    }
    fail(b);
    return;
  }
  uint8_t idx = b.count;
  const Word* prev = idx > 0 ? &b.words[idx - 1] : nullptr;
  uint8_t s = w.slot;
  // An L or O directly after an H word is that switch point's position.
  if ((s == slotOf('L') || s == slotOf('O')) && w.kind != WordKind::LabelRef && prev && prev->slot == slotOf('H') &&
      b.switchCount > 0 && b.switches[b.switchCount - 1].h == idx - 1 && b.switches[b.switchCount - 1].pos < 0) {
    b.words[b.count++] = w;
    b.switches[b.switchCount - 1].pos = static_cast<int8_t>(idx);
    return;
  }
  if (s == slotOf('H')) {
    if (b.switchCount >= kMaxSwitches) {
      rep_.error(w.begin, w.end, "more than " + std::to_string(kMaxSwitches) + " switch points (H) in one block",
                 "gcode-syntax");
      fail(b);
      return;
    }
    b.words[b.count++] = w;
    b.switches[b.switchCount++] = {idx, -1};
    b.present |= 1u << s;
    if (b.at[s] < 0) b.at[s] = static_cast<int8_t>(idx);
    return;
  }
  if (s == slotOf('G')) {
    if (b.gCount >= kMaxGWords) {
      rep_.error(w.begin, w.end, "more than " + std::to_string(kMaxGWords) + " G words in one block", "gcode-syntax");
      fail(b);
      return;
    }
    b.words[b.count++] = w;
    b.g[b.gCount++] = idx;
    b.present |= 1u << s;
    if (b.at[s] < 0) b.at[s] = static_cast<int8_t>(idx);
    return;
  }
  if (b.at[s] >= 0) {
    const Word& first = b.words[b.at[s]];
    rep_.error(w.begin, w.end, "duplicate word '" + slotName(s) + "' in one block", "gcode-duplicate-word")
        .note(rep_.loc(first.begin), "the first '" + slotName(s) + "' is here", rep_.range(first.begin, first.end));
    fail(b);
    return;
  }
  b.words[b.count++] = w;
  b.at[s] = static_cast<int8_t>(idx);
  b.present |= 1u << s;
}

uint32_t BlockParser::blockNumber(uint32_t start, uint32_t pos, Block& b) {
  int64_t v;
  bool ok;
  uint32_t end = unsignedInt(pos, v, ok);
  uint32_t n = static_cast<uint32_t>(text_.size());
  if (b.count > 0 || b.hasN || b.hasLabel) {
    uint32_t tokEnd = skipToken(end);
    rep_.error(start, tokEnd, b.hasN ? "a block has one block number N (start the next block on a new line)"
                                     : "the block number must be the first word of the block",
               "gcode-syntax");
    fail(b);
    // The rest of the line is another block's: checking it here only repeats errors.
    return b.hasN ? lineEnd(tokEnd) : tokEnd;
  }
  char next = end < n ? text_[end] : '\n';
  if (!ok || !(isBlank(next) || next == '\n' || next == '(' || next == ';' || next == '/' || isAlpha(next))) {
    uint32_t tokEnd = skipToken(end);
    while (tokEnd > end && isAlpha(text_[tokEnd - 1])) --tokEnd;
    if (tokEnd <= pos) tokEnd = end < n && text_[end] != '\n' ? end + 1 : end;
    rep_.error(start, tokEnd, "a block number is 'N' followed by digits", "gcode-syntax");
    fail(b);
    return tokEnd;
  }
  if (v > 2147483647) {
    rep_.error(start, end, "block number out of range (at most 2147483647)", "gcode-range");
    fail(b);
    return end;
  }
  b.hasN = true;
  b.n = static_cast<int32_t>(v);
  b.nBegin = start;
  b.nEnd = end;
  return end;
}

uint32_t BlockParser::label(uint32_t start, uint32_t pos, Block& b) {
  bool def = text_[pos] == '!';
  int64_t v;
  bool ok;
  uint32_t end = unsignedInt(pos + 1, v, ok);
  uint32_t tokEnd = skipToken(end);
  if (!ok || (tokEnd != end && !isAlpha(text_[end]))) {
    rep_.error(start, tokEnd, std::string("a jump label is 'L") + (def ? "!" : "?") + "' followed by digits",
               "gcode-syntax");
    fail(b);
    return tokEnd;
  }
  if (v > 2147483647) {
    rep_.error(start, end, "jump label out of range (at most 2147483647)", "gcode-range");
    fail(b);
    return end;
  }
  if (def) {
    if (b.hasLabel) {
      rep_.error(start, end, "a block has one jump label 'L!'", "gcode-duplicate-word")
          .note(rep_.loc(b.labelBegin), "the first label is here", rep_.range(b.labelBegin, b.labelEnd));
      fail(b);
      return end;
    }
    b.hasLabel = true;
    b.label = static_cast<int32_t>(v);
    b.labelBegin = start;
    b.labelEnd = end;
    return end;
  }
  Word w;
  w.slot = slotOf('L');
  w.kind = WordKind::LabelRef;
  w.begin = start;
  w.end = end;
  w.value = static_cast<double>(v);
  addWord(b, w);
  return end;
}

uint32_t BlockParser::word(uint32_t pos, Block& b) {
  const char* s = text_.data();
  uint32_t n = static_cast<uint32_t>(text_.size());
  uint32_t start = pos;
  char letter = upper(s[pos++]);
  uint8_t slot = slotOf(letter);
  if ((letter == 'F' || letter == 'E') && pos < n && upper(s[pos]) == 'F') {
    slot = letter == 'F' ? SlotFF : SlotEF;
    ++pos;
  }
  if (pos < n && isAlpha(s[pos])) {
    uint32_t e = pos;
    while (e < n && (isAlpha(s[e]) || isDigit(s[e]) || s[e] == '_')) ++e;
    std::string run;
    for (uint32_t i = start; i < e; ++i) run += upper(s[i]);
    if (run == "SUBPROGRAM" || run == "END_SUBPROGRAM" || run == "RETURN" || (e < n && (s[e] == '{' || s[e] == '(')))
      rep_.error(start, e, "subprograms are not part of this G-code dialect (docs/cnc.md)", "gcode-unsupported");
    else
      rep_.error(start, e, "unknown word '" + std::string(text_.substr(start, e - start)) +
                               "': a word is one address letter followed by a number",
                 "gcode-unknown-word");
    fail(b);
    return skipToken(e);
  }
  if (letter == 'N') return blockNumber(start, pos, b);
  if (letter == 'L' && pos < n && (s[pos] == '!' || s[pos] == '?')) return label(start, pos, b);

  Word w;
  w.slot = slot;
  w.begin = start;
  bool neg = false;
  if (pos < n && s[pos] == '+') {
    ++pos;
  } else if (pos < n && s[pos] == '-') {
    ++pos;
    if (slot == slotOf('E')) w.slot = SlotEMinus;
    else if (slot == SlotEF) w.slot = SlotEFMinus;
    else neg = true;
  }
  if (pos < n && s[pos] == '$') {
    uint32_t nameBegin = pos + 1, e = nameBegin;
    while (e < n && s[e] != '$' && s[e] != '\n' && !isBlank(s[e])) ++e;
    if (e >= n || s[e] != '$') {
      rep_.error(pos, e, "unterminated variable reference: '$' without a closing '$'", "gcode-syntax");
      fail(b);
      return skipToken(e);
    }
    if (e == nameBegin) {
      rep_.error(pos, e + 1, "empty variable name", "gcode-syntax");
      fail(b);
      return e + 1;
    }
    w.kind = WordKind::Variable;
    w.negate = neg;
    w.nameBegin = nameBegin;
    w.nameEnd = e;
    pos = e + 1;
    w.end = pos;
    if (slot == slotOf('G')) {
      rep_.error(start, pos, "a G code cannot come from a variable (the travel command is fixed at decode time)",
                 "gcode-syntax");
      fail(b);
      return pos;
    }
  } else if (pos < n && (isDigit(s[pos]) || s[pos] == '.')) {
    // digits [. digits]; the fast path reads up to 15 significant digits
    // exactly, from_chars (correctly rounded) the rest.
    uint32_t numBegin = pos;
    uint64_t mant = 0;
    int sig = 0, frac = 0;
    bool dot = false, any = false;
    for (; pos < n; ++pos) {
      char c = s[pos];
      if (isDigit(c)) {
        any = true;
        if (mant || c != '0') {
          if (sig < 19) mant = mant * 10 + static_cast<uint64_t>(c - '0');
          ++sig;
        }
        if (dot) ++frac;
      } else if (c == '.' && !dot) {
        dot = true;
      } else {
        break;
      }
    }
    uint32_t numEnd = pos;
    if (pos < n && (isDigit(s[pos]) || s[pos] == '.' || s[pos] == '$' || s[pos] == '+' || s[pos] == '-')) {
      uint32_t e = pos;
      while (e < n && (isDigit(s[e]) || s[e] == '.' || s[e] == '$' || s[e] == '+' || s[e] == '-')) ++e;
      rep_.error(start, e, "malformed number '" + std::string(text_.substr(numBegin, e - numBegin)) + "'",
                 "gcode-syntax");
      fail(b);
      return e;
    }
    if (!any) {
      rep_.error(start, pos, "expected digits in the value of '" + slotName(w.slot) + "'", "gcode-syntax");
      fail(b);
      return pos;
    }
    double v;
    if (sig <= 15 && frac <= 22) {
      v = static_cast<double>(mant) / kPow10[frac];
    } else {
      auto r = std::from_chars(s + numBegin, s + numEnd, v, std::chars_format::fixed);
      if (r.ec != std::errc() || !std::isfinite(v)) {
        rep_.error(start, numEnd, "number out of range", "gcode-range");
        fail(b);
        return numEnd;
      }
    }
    w.value = neg ? -v : v;
    w.end = pos;
    std::string msg = checkWordValue(w.slot, w.value);
    if (!msg.empty()) {
      rep_.error(start, pos, msg, "gcode-range");
      fail(b);
      return pos;
    }
    if (slot == slotOf('G') && !isKnownGCode(static_cast<int>(w.value))) {
      int g = static_cast<int>(w.value);
      const char* what = nullptr;
      switch (g) {
        case 7: case 11: case 12: case 13: case 14: what = "is not a G code of the dialect"; break;
        case 15: what = "(2.5D mode) is a SoftMotion code this dialect does not include"; break;
        case 31: what = "(probing) is a SoftMotion code this dialect does not include"; break;
        case 38: case 39: what = "(extended parameters) is a SoftMotion code this dialect does not include"; break;
        case 43: case 44: what = "(tool length) is a SoftMotion code this dialect does not include"; break;
        case 58: case 59: what = "(zero offsets) is a SoftMotion code this dialect does not include"; break;
        case 70: case 71: what = "(additional axis smoothing) is a SoftMotion code this dialect does not include"; break;
        default: break;
      }
      rep_.error(start, pos,
                 "unknown G code 'G" + std::to_string(g) + "'" + (what ? std::string(" ") + what : std::string()),
                 "gcode-unknown-code");
      fail(b);
      return pos;
    }
  } else if (pos < n && s[pos] == '{') {
    uint32_t e = pos;
    while (e < n && s[e] != '}' && s[e] != '\n') ++e;
    rep_.error(pos, e < n && s[e] == '}' ? e + 1 : e, "expressions in braces are not part of this G-code dialect",
               "gcode-unsupported");
    fail(b);
    return e < n && s[e] == '}' ? e + 1 : e;
  } else {
    std::string after = "end of line";
    if (pos < n && s[pos] != '\n' && s[pos] != '\r') {
      uint32_t len;
      after = "'" + showChar(text_, pos, len) + "'";
    }
    rep_.error(start, pos, "expected a number after '" + slotName(w.slot) + "', found " + after, "gcode-syntax");
    fail(b);
    return pos;
  }
  addWord(b, w);
  return pos;
}

uint32_t BlockParser::parse(uint32_t pos, uint32_t line, Block& b) {
  const char* s = text_.data();
  uint32_t n = static_cast<uint32_t>(text_.size());
  b.begin = pos;
  b.line = line;
  b.header = b.skip = b.bad = b.hasN = b.hasLabel = false;
  b.n = b.label = -1;
  b.present = 0;
  b.count = b.gCount = b.switchCount = 0;
  for (int8_t& a : b.at) a = -1;
  uint32_t firstOther = 0;   // offset + 1 of the first word that is not N or G
  bool orderWarned = false;

  while (pos < n && isBlank(s[pos])) ++pos;
  if (pos < n && s[pos] == '/' && !(pos + 1 < n && s[pos + 1] == '/')) {
    b.skip = true;
    ++pos;
  }
  while (pos < n) {
    char c = s[pos];
    if (c == '\n') break;
    if (isBlank(c)) {
      ++pos;
      continue;
    }
    if (isAlpha(c)) {
      uint8_t before = b.count;
      uint32_t wordBegin = pos;
      pos = word(pos, b);
      if (b.count > before && b.count <= kMaxWords) {
        const Word& w = b.words[b.count - 1];
        if (w.slot == slotOf('G')) {
          if (firstOther && !orderWarned) {
            orderWarned = true;
            rep_.warning(wordBegin, w.end, "G word after other words; the dialect writes N and G first",
                         "gcode-word-order")
                .note(rep_.loc(firstOther - 1), "first other word here");
          }
        } else if (!firstOther) {
          firstOther = w.begin + 1;
        }
      }
      continue;
    }
    switch (c) {
      case '(': {
        uint32_t e = pos + 1;
        while (e < n && s[e] != ')' && s[e] != '\n') ++e;
        if (e >= n || s[e] != ')') {
          rep_.error(pos, pos + 1, "unterminated comment: '(' without ')' on this line", "gcode-syntax");
          fail(b);
          pos = e;
        } else {
          pos = e + 1;
        }
        continue;
      }
      case ';':
        pos = lineEnd(pos);
        continue;
      case '/':
        if (pos + 1 < n && s[pos + 1] == '/') {
          pos = lineEnd(pos);
          continue;
        }
        rep_.error(pos, pos + 1, "'/' (block skip) must be the first character of the block", "gcode-syntax");
        fail(b);
        ++pos;
        continue;
      case '%': {
        uint32_t e = lineEnd(pos);
        if (b.count || b.hasN || b.skip) {
          rep_.error(pos, pos + 1, "'%' (program header) must be on a line of its own", "gcode-syntax");
          fail(b);
          pos = e;
          continue;
        }
        b.header = true;
        b.headerAt = pos;
        uint32_t nb = pos + 1;
        while (nb < e && isBlank(s[nb])) ++nb;
        uint32_t ne = nb;
        while (ne < e && !isBlank(s[ne]) && s[ne] != '(' && s[ne] != ';') ++ne;
        b.nameBegin = nb;
        b.nameEnd = ne;
        pos = ne;
        continue;
      }
      default: {
        uint32_t len;
        std::string ch = showChar(text_, pos, len);
        rep_.error(pos, pos + len, "unexpected character '" + ch + "'", "gcode-syntax");
        fail(b);
        pos = skipToken(pos + len);
        continue;
      }
    }
  }
  if (b.header && (b.count || b.hasN)) {
    rep_.error(b.headerAt, b.headerAt + 1, "'%' (program header) must be on a line of its own", "gcode-syntax");
    fail(b);
  }
  b.end = pos;
  return pos < n ? pos + 1 : pos;
}

}  // namespace stc::cnc
