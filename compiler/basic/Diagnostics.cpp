#include "basic/Diagnostics.h"

#include "basic/Text.h"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace stc {

DiagBuilder::~DiagBuilder() {
  if (engine_) engine_->commit(std::move(diag_));
}

DiagBuilder& DiagBuilder::note(SourceLoc loc, std::string message, SourceRange r) {
  Diagnostic n;
  n.severity = Severity::Note;
  n.loc = loc;
  n.message = std::move(message);
  if (r.valid()) n.ranges.push_back(r);
  diag_.notes.push_back(std::move(n));
  return *this;
}

DiagBuilder DiagnosticsEngine::error(SourceLoc loc, std::string message, std::string code) {
  Diagnostic d;
  d.severity = Severity::Error;
  d.loc = loc;
  d.message = std::move(message);
  d.code = std::move(code);
  return DiagBuilder(this, std::move(d));
}

DiagBuilder DiagnosticsEngine::warning(SourceLoc loc, std::string message, std::string warningName) {
  Diagnostic d;
  d.severity = Severity::Warning;
  d.loc = loc;
  d.message = std::move(message);
  d.code = "-W" + warningName;
  return DiagBuilder(this, std::move(d));
}

DiagBuilder DiagnosticsEngine::note(SourceLoc loc, std::string message) {
  Diagnostic d;
  d.severity = Severity::Note;
  d.loc = loc;
  d.message = std::move(message);
  return DiagBuilder(this, std::move(d));
}

void DiagnosticsEngine::commit(Diagnostic d) {
  if (d.severity == Severity::Warning) {
    if (opts.noWarnings) return;
    if (d.code.size() > 2 && opts.disabledWarnings.count(d.code.substr(2))) return;
    if (opts.warningsAsErrors) d.severity = Severity::Error;
  }
  if (d.severity == Severity::Error) {
    if (limitReached()) return;
    ++errors_;
  } else if (d.severity == Severity::Warning) {
    ++warnings_;
  }
  diags_.push_back(std::move(d));
}

namespace {

const char* severityName(Severity s) {
  switch (s) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "error";
}

// Decodes the UTF-8 sequence at `i` (advancing `i`); a malformed byte is
// returned as itself, one byte long.
uint32_t decodeUtf8(std::string_view s, size_t& i) {
  unsigned char c = static_cast<unsigned char>(s[i]);
  unsigned len = c < 0x80 ? 1 : (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 1;
  if (len == 1 || i + len > s.size()) { ++i; return c; }
  uint32_t cp = len == 2 ? (c & 0x1F) : len == 3 ? (c & 0x0F) : (c & 0x07);
  for (unsigned k = 1; k < len; ++k) {
    unsigned char cc = static_cast<unsigned char>(s[i + k]);
    if ((cc & 0xC0) != 0x80) { ++i; return c; }
    cp = (cp << 6) | (cc & 0x3F);
  }
  i += len;
  return cp;
}

// Characters that are not printed as they are (they would move or garble the
// terminal output): C0/C1 controls, DEL, bidirectional overrides.
bool isUnprintable(uint32_t cp) {
  return cp < 0x20 || (cp >= 0x7F && cp < 0xA0) || (cp >= 0x202A && cp <= 0x202E) || (cp >= 0x2066 && cp <= 0x2069) ||
         cp == 0xFEFF;
}

// Columns a character takes on a terminal: 2 for East Asian wide and
// full-width characters, 0 for combining marks, 1 otherwise (as wcwidth).
unsigned charWidth(uint32_t cp) {
  if (cp < 0x300) return 1;
  if ((cp >= 0x0300 && cp <= 0x036F) || (cp >= 0x1AB0 && cp <= 0x1AFF) || (cp >= 0x1DC0 && cp <= 0x1DFF) ||
      (cp >= 0x20D0 && cp <= 0x20FF) || (cp >= 0xFE00 && cp <= 0xFE0F) || (cp >= 0xFE20 && cp <= 0xFE2F) ||
      (cp >= 0x200B && cp <= 0x200F))
    return 0;
  static const uint32_t wide[][2] = {
      {0x1100, 0x115F},   {0x231A, 0x231B},   {0x2329, 0x232A},   {0x23E9, 0x23EC},   {0x23F0, 0x23F0},
      {0x23F3, 0x23F3},   {0x25FD, 0x25FE},   {0x2614, 0x2615},   {0x2648, 0x2653},   {0x267F, 0x267F},
      {0x2693, 0x2693},   {0x26A1, 0x26A1},   {0x26AA, 0x26AB},   {0x26BD, 0x26BE},   {0x26C4, 0x26C5},
      {0x26CE, 0x26CE},   {0x26D4, 0x26D4},   {0x26EA, 0x26EA},   {0x26F2, 0x26F3},   {0x26F5, 0x26F5},
      {0x26FA, 0x26FA},   {0x26FD, 0x26FD},   {0x2705, 0x2705},   {0x270A, 0x270B},   {0x2728, 0x2728},
      {0x274C, 0x274C},   {0x274E, 0x274E},   {0x2753, 0x2755},   {0x2757, 0x2757},   {0x2795, 0x2797},
      {0x27B0, 0x27B0},   {0x27BF, 0x27BF},   {0x2B1B, 0x2B1C},   {0x2B50, 0x2B50},   {0x2B55, 0x2B55},
      {0x2E80, 0x303E},   {0x3041, 0x33FF},   {0x3400, 0x4DBF},   {0x4E00, 0x9FFF},   {0xA000, 0xA4CF},
      {0xA960, 0xA97F},   {0xAC00, 0xD7A3},   {0xF900, 0xFAFF},   {0xFE10, 0xFE19},   {0xFE30, 0xFE6F},
      {0xFF00, 0xFF60},   {0xFFE0, 0xFFE6},   {0x16FE0, 0x16FE4}, {0x17000, 0x18CFF}, {0x1B000, 0x1B2FF},
      {0x1F004, 0x1F004}, {0x1F0CF, 0x1F0CF}, {0x1F18E, 0x1F18E}, {0x1F191, 0x1F19A}, {0x1F200, 0x1F2FF},
      {0x1F300, 0x1F64F}, {0x1F680, 0x1F6FF}, {0x1F7E0, 0x1F7EB}, {0x1F90C, 0x1F9FF}, {0x1FA70, 0x1FAFF},
      {0x20000, 0x2FFFD}, {0x30000, 0x3FFFD},
  };
  for (const auto& r : wide) {
    if (cp < r[0]) break;
    if (cp <= r[1]) return 2;
  }
  return 1;
}

// The shown form of a source line and where each byte lands on screen.
struct DisplayLine {
  std::string text;                 // control characters replaced by spaces
  std::vector<unsigned> col;        // per byte (and one past the end): display column of its character (0-based)
  std::vector<unsigned> width;      // per byte: display width of its character
  std::vector<uint32_t> charStart;  // per byte: byte index where its character starts
};

DisplayLine layoutLine(std::string_view line) {
  DisplayLine d;
  d.col.resize(line.size() + 1);
  d.width.resize(line.size() + 1);
  d.charStart.resize(line.size() + 1);
  unsigned col = 0;
  size_t i = 0;
  while (i < line.size()) {
    size_t b = i;
    uint32_t cp = decodeUtf8(line, i);
    unsigned w;
    if (cp == '\t' || isUnprintable(cp)) {
      d.text += ' ';
      w = 1;
    } else {
      d.text.append(line.substr(b, i - b));
      w = charWidth(cp);
    }
    for (size_t k = b; k < i; ++k) {
      d.col[k] = col;
      d.width[k] = w;
      d.charStart[k] = static_cast<uint32_t>(b);
    }
    col += w;
  }
  d.col[line.size()] = col;
  d.width[line.size()] = 1;
  d.charStart[line.size()] = static_cast<uint32_t>(line.size());
  return d;
}

void renderOne(const SourceManager& sm, const Diagnostic& d, std::string& out, bool color) {
  const char* bold = color ? "\033[1m" : "";
  const char* reset = color ? "\033[0m" : "";
  const char* sevColor = "";
  if (color)
    sevColor = d.severity == Severity::Error ? "\033[1;31m" : d.severity == Severity::Warning ? "\033[1;35m" : "\033[1;36m";
  if (d.loc.valid()) {
    LineCol lc = sm.lineCol(d.loc);
    out += bold + sm.file(d.loc.file).path + ":" + std::to_string(lc.line) + ":" + std::to_string(lc.col) + ": " + reset;
  } else {
    out += std::string(bold) + "stc: " + reset;
  }
  out += std::string(sevColor) + severityName(d.severity) + ": " + reset + bold + d.message + reset;
  if (!d.code.empty()) out += " [" + d.code + "]";
  out += "\n";
  if (!d.loc.valid()) return;

  // Source line, caret and ~ under ranges on the same line.  Positions are
  // byte offsets; the screen columns come from the display width of the
  // characters before them (wide CJK characters take two columns).
  std::string_view line = sm.lineText(d.loc);
  LineCol lc = sm.lineCol(d.loc);
  uint32_t lineBegin = sm.lineStart(d.loc.file, lc.line);
  size_t caretByte = std::min<size_t>(d.loc.offset - std::min(d.loc.offset, lineBegin), line.size());
  // Very long lines: show a window around the caret.
  std::string prefix;
  if (line.size() > 160) {
    size_t from = caretByte > 60 ? caretByte - 60 : 0;
    while (from > 0 && (static_cast<unsigned char>(line[from]) & 0xC0) == 0x80) --from;
    size_t to = std::min(line.size(), from + 140);
    while (to < line.size() && (static_cast<unsigned char>(line[to]) & 0xC0) == 0x80) ++to;
    line = line.substr(from, to - from);
    lineBegin += static_cast<uint32_t>(from);
    caretByte = std::min(caretByte - from, line.size());
    if (from > 0) prefix = "...";
  }
  uint32_t lineEnd = lineBegin + static_cast<uint32_t>(line.size());
  DisplayLine dl = layoutLine(line);
  out += "  " + prefix + dl.text + "\n";
  std::string marks(dl.col[line.size()] + 2, ' ');
  auto put = [&](size_t byte, char ch, bool wholeChar) {
    unsigned c = dl.col[byte];
    unsigned w = wholeChar ? std::max(1u, dl.width[byte]) : 1;
    if (dl.width[byte] == 0) return;
    for (unsigned k = 0; k < w && c + k < marks.size(); ++k)
      if (marks[c + k] != '^') marks[c + k] = ch;
  };
  auto mark = [&](uint32_t b, uint32_t e) {
    if (e <= b) e = b + 1;
    uint32_t from = std::max(b, lineBegin), to = std::min(e, lineEnd + 1);
    for (uint32_t o = from; o < to; ++o) {
      size_t byte = o - lineBegin;
      if (dl.charStart[byte] == byte || o == from) put(dl.charStart[byte], '~', true);
    }
  };
  for (const SourceRange& r : d.ranges)
    if (r.begin.file == d.loc.file) mark(r.begin.offset, r.end.offset);
  size_t caretAt = dl.charStart[caretByte];
  if (dl.col[caretAt] < marks.size()) marks[dl.col[caretAt]] = '^';
  while (!marks.empty() && marks.back() == ' ') marks.pop_back();
  out += "  " + prefix + std::string(color ? "\033[1;32m" : "") + marks + reset + "\n";
  // Fix-it texts on one line under the caret line, each at its column, as clang does.
  std::vector<std::pair<size_t, std::string>> fixes;
  for (const FixIt& f : d.fixits) {
    if (f.range.begin.file != d.loc.file || f.range.begin.offset < lineBegin || f.range.begin.offset > lineEnd) continue;
    fixes.push_back({dl.col[dl.charStart[f.range.begin.offset - lineBegin]], f.replacement});
  }
  std::sort(fixes.begin(), fixes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (!fixes.empty()) {
    std::string fl;
    size_t shownWidth = 0;
    for (auto& [c, text] : fixes) {
      if (shownWidth < c) { fl.append(c - shownWidth, ' '); shownWidth = c; }
      fl += text;
      for (size_t i = 0; i < text.size();) shownWidth += charWidth(decodeUtf8(text, i));
    }
    out += "  " + prefix + std::string(color ? "\033[32m" : "") + fl + reset + "\n";
  }
}

}  // namespace

Diagnostic originalDiagnostic(const SourceManager& sm, const Diagnostic& d) {
  Diagnostic m = d;
  m.loc = sm.originalLoc(d.loc);
  m.ranges.clear();
  for (const SourceRange& r : d.ranges) {
    SourceRange o = sm.originalRange(r);
    if (o.valid()) m.ranges.push_back(o);
  }
  // A fix-it on synthesized text has nothing to edit in the original file.
  m.fixits.clear();
  for (const FixIt& f : d.fixits)
    if (sm.isVerbatim(f.range.begin) && (!f.range.end.valid() || sm.isVerbatim(f.range.end)))
      m.fixits.push_back({sm.originalRange(f.range), f.replacement});
  for (Diagnostic& n : m.notes) n = originalDiagnostic(sm, n);
  return m;
}

std::string renderText(const SourceManager& sm, const Diagnostic& diag, bool color) {
  std::string out;
  Diagnostic d = originalDiagnostic(sm, diag);
  renderOne(sm, d, out, color);
  for (const Diagnostic& n : d.notes) renderOne(sm, n, out, color);
  return out;
}

static nlohmann::json toJson(const SourceManager& sm, const Diagnostic& diag) {
  Diagnostic d = originalDiagnostic(sm, diag);
  nlohmann::json j;
  j["severity"] = severityName(d.severity);
  j["message"] = d.message;
  if (!d.code.empty()) j["code"] = d.code;
  auto loc = [&](SourceLoc l) {
    nlohmann::json o;
    LineCol lc = sm.lineCol(l);
    o["file"] = sm.file(l.file).path;
    o["line"] = lc.line;
    o["column"] = lc.col;
    o["offset"] = l.offset;
    return o;
  };
  if (d.loc.valid()) j["location"] = loc(d.loc);
  nlohmann::json ranges = nlohmann::json::array();
  for (const SourceRange& r : d.ranges) ranges.push_back({{"begin", loc(r.begin)}, {"end", loc(r.end)}});
  j["ranges"] = ranges;
  nlohmann::json fixits = nlohmann::json::array();
  for (const FixIt& f : d.fixits)
    fixits.push_back({{"begin", loc(f.range.begin)}, {"end", loc(f.range.end.valid() ? f.range.end : f.range.begin)}, {"replacement", f.replacement}});
  j["fixits"] = fixits;
  nlohmann::json notes = nlohmann::json::array();
  for (const Diagnostic& n : d.notes) notes.push_back(toJson(sm, n));
  j["notes"] = notes;
  return j;
}

std::string renderJson(const SourceManager& sm, const std::vector<Diagnostic>& diags) {
  nlohmann::json arr = nlohmann::json::array();
  for (const Diagnostic& d : diags) arr.push_back(toJson(sm, d));
  return arr.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}


// Optimal string alignment distance: a swap of two neighbours ("Fats" for
// "Fast") counts as one edit, as people mistype.
unsigned editDistance(std::string_view a, std::string_view b, unsigned limit) {
  if (a.size() > b.size() + limit || b.size() > a.size() + limit) return limit + 1;
  std::vector<unsigned> prev2(b.size() + 1), prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = static_cast<unsigned>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = static_cast<unsigned>(i);
    unsigned rowMin = cur[0];
    for (size_t j = 1; j <= b.size(); ++j) {
      unsigned sub = prev[j - 1] + (asciiLower(a[i - 1]) == asciiLower(b[j - 1]) ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
      if (i > 1 && j > 1 && asciiLower(a[i - 1]) == asciiLower(b[j - 2]) && asciiLower(a[i - 2]) == asciiLower(b[j - 1])) cur[j] = std::min(cur[j], prev2[j - 2] + 1);
      rowMin = std::min(rowMin, cur[j]);
    }
    if (rowMin > limit) return limit + 1;
    prev2 = prev;
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closestMatch(std::string_view name, const std::vector<std::string>& candidates) {
  unsigned maxDist = std::max<unsigned>(1, static_cast<unsigned>((name.size() + 2) / 3));
  unsigned best = maxDist + 1;
  std::string bestName;
  for (const std::string& c : candidates) {
    unsigned d = editDistance(name, c, maxDist);
    if (d < best && d > 0) {
      best = d;
      bestName = c;
    }
  }
  return bestName;
}

}  // namespace stc
