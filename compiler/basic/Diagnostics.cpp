#include "basic/Diagnostics.h"

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

// Display column (1-based) of byte column `col` in `line`: counts code
// points, so a caret under UTF-8 text lands under the right character.
size_t displayCol(std::string_view line, size_t byteCol) {
  size_t n = 0;
  for (size_t i = 0; i < byteCol - 1 && i < line.size(); ++i)
    if ((static_cast<unsigned char>(line[i]) & 0xC0) != 0x80) ++n;
  return n + 1;
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

  // Source line, caret and ~ under ranges on the same line.
  std::string_view line = sm.lineText(d.loc);
  LineCol lc = sm.lineCol(d.loc);
  uint32_t lineBegin = d.loc.offset - (lc.col - 1);
  // Very long lines: show a window around the caret.
  std::string prefix;
  if (line.size() > 160) {
    size_t caretByte = std::min<size_t>(lc.col - 1, line.size());
    size_t from = caretByte > 60 ? caretByte - 60 : 0;
    while (from > 0 && (static_cast<unsigned char>(line[from]) & 0xC0) == 0x80) --from;
    size_t to = std::min(line.size(), from + 140);
    while (to < line.size() && (static_cast<unsigned char>(line[to]) & 0xC0) == 0x80) ++to;
    line = line.substr(from, to - from);
    lineBegin += static_cast<uint32_t>(from);
    lc.col -= static_cast<unsigned>(from);
    if (from > 0) prefix = "...";
  }
  uint32_t lineEnd = lineBegin + static_cast<uint32_t>(line.size());
  std::string shown;
  for (char c : line) {
    unsigned char u = static_cast<unsigned char>(c);
    shown += (c == '\t' || (u < 0x20) || u == 0x7F) ? ' ' : c;   // no raw control characters
  }
  out += "  " + prefix + shown + "\n";
  if (!prefix.empty()) out += "";
  size_t width = displayCol(line, line.size() + 1);
  std::string marks(width + 1, ' ');
  auto mark = [&](uint32_t b, uint32_t e, char ch) {
    if (e <= b) e = b + 1;
    for (uint32_t o = std::max(b, lineBegin); o < std::min(e, lineEnd + 1); ++o) {
      size_t c = displayCol(line, o - lineBegin + 1) - 1;
      if (c < marks.size() && marks[c] != '^') marks[c] = ch;
    }
  };
  for (const SourceRange& r : d.ranges)
    if (r.begin.file == d.loc.file) mark(r.begin.offset, r.end.offset, '~');
  size_t caret = displayCol(line, lc.col) - 1;
  if (caret < marks.size()) marks[caret] = '^';
  while (!marks.empty() && marks.back() == ' ') marks.pop_back();
  out += "  " + prefix + std::string(color ? "\033[1;32m" : "") + marks + reset + "\n";
  // Fix-it texts on one line under the caret line, each at its column, as clang does.
  std::vector<std::pair<size_t, std::string>> fixes;
  for (const FixIt& f : d.fixits) {
    if (f.range.begin.file != d.loc.file || f.range.begin.offset < lineBegin || f.range.begin.offset > lineEnd) continue;
    fixes.push_back({displayCol(line, f.range.begin.offset - lineBegin + 1) - 1, f.replacement});
  }
  std::sort(fixes.begin(), fixes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (!fixes.empty()) {
    std::string fl;
    for (auto& [c, text] : fixes) {
      if (fl.size() < c) fl.append(c - fl.size(), ' ');
      fl += text;
    }
    out += "  " + prefix + std::string(color ? "\033[32m" : "") + fl + reset + "\n";
  }
}

}  // namespace

std::string renderText(const SourceManager& sm, const Diagnostic& d, bool color) {
  std::string out;
  renderOne(sm, d, out, color);
  for (const Diagnostic& n : d.notes) renderOne(sm, n, out, color);
  return out;
}

static nlohmann::json toJson(const SourceManager& sm, const Diagnostic& d) {
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

static char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

unsigned editDistance(std::string_view a, std::string_view b, unsigned limit) {
  if (a.size() > b.size() + limit || b.size() > a.size() + limit) return limit + 1;
  std::vector<unsigned> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = static_cast<unsigned>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = static_cast<unsigned>(i);
    unsigned rowMin = cur[0];
    for (size_t j = 1; j <= b.size(); ++j) {
      unsigned sub = prev[j - 1] + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
      rowMin = std::min(rowMin, cur[j]);
    }
    if (rowMin > limit) return limit + 1;
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
