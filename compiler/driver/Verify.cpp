// clang -verify style checking.  In a source file,
//   x := y;  // expected-error {{undeclared identifier 'y'}}
//   // expected-warning@+1 {{unused variable}}
//   // expected-error@5:10 {{...}}       (absolute line, optional column)
// Each expected diagnostic must be produced (the text is a substring of the
// message) and every error and warning produced must be expected.  Notes are
// checked only in files that mention expected-note.
#include <algorithm>
#include <regex>
#include <sstream>

#include "driver/Driver.h"

namespace stc {

namespace {

struct Expectation {
  Severity sev;
  uint32_t file;
  unsigned line;
  unsigned col;      // 0 = any
  std::string text;
  bool matched = false;
};

const char* sevName(Severity s) { return s == Severity::Error ? "error" : s == Severity::Warning ? "warning" : "note"; }

}  // namespace

bool verifyDiagnostics(Compilation& c, std::string& out) {
  const SourceManager& sm = c.sources();
  std::vector<Expectation> exps;
  std::set<uint32_t> checkNotes;
  static const std::regex re(R"(expected-(error|warning|note)(@([+-]?)(\d+)(:(\d+))?)?\s*\{\{(.*?)\}\})");
  for (uint32_t f = 1; f <= sm.fileCount(); ++f) {
    const SourceFile& file = sm.file(f);
    if (file.path.rfind("<stdlib>", 0) == 0) continue;
    // Generated buffers (imported XML) are checked through the files they come
    // from: their comments are there too, and diagnostics are mapped there.
    if (sm.isGenerated(f)) continue;
    const std::string& t = file.original.empty() ? file.text : file.original;
    // Lines as the SourceManager counts them (LF, CRLF and CR line ends), so
    // expectations and diagnostics agree on line numbers.
    unsigned lines = sm.lineCount(f);
    for (unsigned line = 1; line <= lines; ++line) {
      size_t pos = std::min<size_t>(sm.lineStart(f, line), t.size());
      size_t e = line < lines ? std::min<size_t>(sm.lineStart(f, line + 1), t.size()) : t.size();
      while (e > pos && (t[e - 1] == '\n' || t[e - 1] == '\r')) --e;
      std::string l = t.substr(pos, e - pos);
      for (auto it = std::sregex_iterator(l.begin(), l.end(), re); it != std::sregex_iterator(); ++it) {
        const std::smatch& m = *it;
        Expectation x;
        x.sev = m[1] == "error" ? Severity::Error : m[1] == "warning" ? Severity::Warning : Severity::Note;
        x.file = f;
        x.line = line;
        x.col = 0;
        if (m[2].matched) {
          int n = std::stoi(m[4]);
          if (m[3] == "+") x.line = line + static_cast<unsigned>(n);
          else if (m[3] == "-") x.line = line - static_cast<unsigned>(n);
          else x.line = static_cast<unsigned>(n);
          if (m[6].matched) x.col = static_cast<unsigned>(std::stoi(m[6]));
        }
        x.text = m[7];
        if (x.sev == Severity::Note) checkNotes.insert(f);
        exps.push_back(x);
      }
    }
  }
  std::ostringstream msg;
  bool ok = true;
  auto consider = [&](const Diagnostic& generated) {
    Diagnostic d = originalDiagnostic(sm, generated);
    if (d.severity == Severity::Note && !checkNotes.count(d.loc.file)) return;
    LineCol lc = sm.lineCol(d.loc);
    for (Expectation& x : exps) {
      if (x.matched || x.sev != d.severity || x.file != d.loc.file || x.line != lc.line) continue;
      if (x.col && x.col != lc.col) continue;
      if (d.message.find(x.text) == std::string::npos) continue;
      x.matched = true;
      return;
    }
    ok = false;
    if (d.loc.valid())
      msg << "unexpected " << sevName(d.severity) << ": " << sm.file(d.loc.file).path << ":" << lc.line << ":" << lc.col << ": " << d.message << "\n";
    else
      msg << "unexpected " << sevName(d.severity) << ": " << d.message << "\n";
  };
  for (const Diagnostic& d : c.diags().diagnostics()) {
    consider(d);
    for (const Diagnostic& n : d.notes) consider(n);
  }
  for (const Expectation& x : exps)
    if (!x.matched) {
      ok = false;
      msg << "expected " << sevName(x.sev) << " not produced: " << sm.file(x.file).path << ":" << x.line << (x.col ? ":" + std::to_string(x.col) : "")
          << ": {{" << x.text << "}}\n";
    }
  out = msg.str();
  return ok;
}

}  // namespace stc
