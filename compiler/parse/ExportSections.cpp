// CoDeSys 2.3 project exports (.EXP) end with sections that are not Structured
// Text: alarm configuration, library references, the PLC configuration and
// the task resources.  They are blanked out before lexing (offsets stay, so
// every later location is unchanged) and each one is reported with a note.
#include <string_view>

#include "parse/ParseInternal.h"

namespace stc::parse {

namespace {

struct Section {
  std::string_view start;   // the whole line, trimmed
  std::string_view end;     // a line starting with this ends the section ("" = braces)
  std::string_view what;
};

constexpr Section kSections[] = {
    {"_ALARMCONFIG", "_END_ALARMCONFIG", "alarm configuration"},
    {"LIBRARY", "END_LIBRARY", "library reference"},
    {"PLC_CONFIGURATION", "PLC_END", "PLC configuration"},
    {"_WORKSPACE", "_END_WORKSPACE", "workspace settings"},
    {"RESOURCE", "", "task configuration"},
};

std::string_view trimmed(std::string_view s) {
  size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  size_t e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

size_t lineEnd(std::string_view t, size_t i) {
  size_t e = t.find('\n', i);
  return e == std::string_view::npos ? t.size() : e;
}

// End (exclusive) of the section starting at the line `begin`, or npos when
// its end marker is missing (then it is left to the parser to complain).
size_t sectionEnd(std::string_view t, size_t begin, const Section& s) {
  size_t i = lineEnd(t, begin);
  if (s.end.empty()) {
    // RESOURCE { ... } with nested braces; only when a '{' comes next.
    size_t open = t.find_first_not_of(" \t\r\n", i);
    if (open == std::string_view::npos || t[open] != '{') return std::string_view::npos;
    int depth = 0;
    for (size_t k = open; k < t.size(); ++k) {
      if (t[k] == '{') ++depth;
      else if (t[k] == '}' && --depth == 0) {
        size_t e = lineEnd(t, k);
        // An END_RESOURCE line right after the braces belongs to the section.
        size_t next = t.find_first_not_of(" \t\r\n", e);
        if (next != std::string_view::npos && t.compare(next, 12, "END_RESOURCE") == 0) e = lineEnd(t, next);
        return e;
      }
    }
    return std::string_view::npos;
  }
  while (i < t.size()) {
    size_t ls = i + 1;
    size_t le = lineEnd(t, ls);
    if (ls >= t.size()) break;
    if (trimmed(t.substr(ls, le - ls)).substr(0, s.end.size()) == s.end) return le;
    i = le;
  }
  return std::string_view::npos;
}

}  // namespace

void skipExportSections(SourceFile& file, DiagnosticsEngine& diags) {
  std::string& t = file.text;
  // Cheap test first: most files have none of the markers.
  if (t.find("LIBRARY") == std::string::npos && t.find("_ALARMCONFIG") == std::string::npos &&
      t.find("PLC_CONFIGURATION") == std::string::npos && t.find("_WORKSPACE") == std::string::npos && t.find("RESOURCE") == std::string::npos)
    return;
  std::string before;
  for (size_t ls = 0; ls < t.size();) {
    size_t le = lineEnd(t, ls);
    std::string_view line = trimmed(std::string_view(t).substr(ls, le - ls));
    size_t next = le + 1;
    for (const Section& s : kSections) {
      if (line != s.start) continue;
      size_t end = sectionEnd(t, ls, s);
      if (end == std::string_view::npos) break;
      if (before.empty()) before = t;
      size_t col = t.find_first_not_of(" \t", ls);
      diags.note(SourceLoc{file.id, static_cast<uint32_t>(col)}, "skipped the CoDeSys 2.3 export section '" + std::string(s.start) + "' (" +
                                                                     std::string(s.what) + "); it is not Structured Text");
      for (size_t k = ls; k < end; ++k)
        if (t[k] != '\n' && t[k] != '\r') t[k] = ' ';
      next = end + 1;
      break;
    }
    ls = next;
  }
  if (!before.empty() && file.original.empty()) file.original = std::move(before);
}

}  // namespace stc::parse
