// `stc test` (docs/projects.md, "Scenarios and golden traces").
//
// The parent process validates the command line and the project directories
// and starts one child (`/proc/self/exe test --one DIR`) per project, at most
// -j at a time, so projects run in parallel.  A child writes its report to a
// temporary file; the parent prints the reports whole, in argument order, and
// counts their PASS/FAIL lines.  Inside a project the sources are parsed and
// checked once; then each scenario runs in a process of its own (fork): fresh
// generated code, controller, motion kernel and diagnostics, so whatever one
// scenario does (a runtime fault, a crash of stc itself) cannot touch the
// others; its outcome comes back through a pipe.
#include "tools/stc/TestCommand.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <toml++/toml.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include "basic/Text.h"
#include "codegen/CodeGen.h"
#include "config/ConfigSchema.h"
#include "driver/Driver.h"
#include "sema/Layout.h"
#include "sema/Model.h"
#include "sema/Types.h"
#include "tools/stc/Libraries.h"
#include "vm/Controller.h"
#include "vm/FileSandbox.h"
#include "vm/Image.h"
#include "vm/Time.h"
#include "vm/testlib/TestLib.h"

namespace fs = std::filesystem;

namespace stc::tools {

namespace {

// ---------------------------------------------------------------- scenario files

struct Located {
  std::string where;   // "scenarios/x.toml:12:1"
};

struct SetStep : Located {
  vm::Time at = 0;
  std::string var, value;
};

struct FaultStep : Located {
  vm::Time at = 0;
  std::string axis;
  motion::FaultKind kind = motion::FaultKind::DriveError;
};

struct Check : Located {
  enum Kind { Equals, Rises, Bounds } kind = Equals;
  std::string var;
  vm::Time at = 0, from = 0, to = 0;
  std::string equals;
  std::optional<double> min, max;
};

struct Scenario {
  std::string name, file;      // file: as printed (scenarios/x.toml)
  std::optional<vm::Time> duration;
  std::optional<uint64_t> cycles;
  std::vector<std::string> trace;
  double tolerance = 1e-9;
  // The golden trace's rows: every base tick, or those at multiples of `sampleEvery`,
  // or (sampleChange) those where a value changed, and the first and the last.
  std::optional<vm::Time> sampleEvery;
  bool sampleChange = false;
  std::string sampleWhere, sampleText;   // scenarios/x.toml:4:10, "10ms"
  std::vector<SetStep> sets;
  std::vector<FaultStep> faults;
  std::vector<Check> checks;
};

std::string where(const std::string& file, const toml::node& n) {
  const auto& s = n.source();
  if (!s.begin) return file;
  return file + ":" + std::to_string(s.begin.line) + ":" + std::to_string(s.begin.column);
}

// An ST literal given as a TOML string, or as a TOML boolean / number.
bool literalText(const toml::node* n, std::string& out) {
  if (!n) return false;
  if (auto s = n->value_exact<std::string>()) out = *s;
  else if (auto b = n->value_exact<bool>()) out = *b ? "TRUE" : "FALSE";
  else if (auto i = n->value_exact<int64_t>()) out = std::to_string(*i);
  else if (auto d = n->value_exact<double>()) out = vm::formatReal(*d, false);
  else return false;
  return true;
}

bool durationOf(const toml::node* n, vm::Time& out) {
  if (!n) return false;
  auto s = n->value_exact<std::string>();
  return s && vm::parseIecDuration(*s, out) && out >= 0;
}

// Parses and validates one scenario file (variables are resolved later).
bool loadScenario(const fs::path& path, const std::string& shown, Scenario& sc, std::string& error) {
  sc.file = shown;
  sc.name = path.stem().string();
  // Read, parsed and validated against the schema (compiler/config/ConfigSchema.cpp):
  // below, every key is known and every value has its type and range.
  toml::table tbl;
  if (!config::loadToml(path.string(), shown, config::scenarioSchema(), tbl, error)) return false;
  auto fail = [&](const toml::node& n, const std::string& msg) {
    error = where(shown, n) + ": error: " + msg;
    return false;
  };
  if (const toml::node* d = tbl.get("duration")) {
    vm::Time t = 0;
    if (!durationOf(d, t) || t == 0) return fail(*d, "duration must be a positive duration string, e.g. \"3s\" or \"T#500ms\"");
    sc.duration = t;
  }
  if (const toml::node* c = tbl.get("cycles")) {
    auto n = c->value_exact<int64_t>();
    if (!n || *n <= 0) return fail(*c, "cycles must be a positive integer");
    sc.cycles = static_cast<uint64_t>(*n);
  }
  if (sc.duration && sc.cycles) return fail(*tbl.get("cycles"), "give either duration or cycles, not both");
  if (!sc.duration && !sc.cycles) {
    error = shown + ": error: the scenario needs duration = \"<time>\" or cycles = N";
    return false;
  }
  if (const toml::node* tr = tbl.get("trace")) {
    const toml::array* a = tr->as_array();
    if (!a) return fail(*tr, "trace must be an array of variable names");
    for (const toml::node& e : *a) {
      auto s = e.value_exact<std::string>();
      if (!s || s->empty()) return fail(e, "trace must be an array of variable names");
      sc.trace.push_back(*s);
    }
  }
  if (const toml::node* tol = tbl.get("tolerance")) {
    auto d = tol->value<double>();
    if (!d || !(*d >= 0)) return fail(*tol, "tolerance must be a number >= 0");
    sc.tolerance = *d;
  }
  if (const toml::node* smp = tbl.get("sample")) {
    // The schema has checked: "change" or a positive duration.
    sc.sampleWhere = where(shown, *smp);
    sc.sampleText = smp->value_exact<std::string>().value_or("");
    vm::Time t = 0;
    if (sc.sampleText == "change") sc.sampleChange = true;
    else if (durationOf(smp, t) && t > 0) sc.sampleEvery = t;
    else return fail(*smp, "sample = \"" + sc.sampleText + "\": a positive duration (e.g. \"10ms\") or \"change\" is expected");
    if (sc.sampleEvery && sc.duration && *sc.sampleEvery > *sc.duration)
      return fail(*smp, "sample = \"" + sc.sampleText + "\": above the scenario's duration (" + vm::formatIecTime(*sc.duration) + ")");
    if (sc.trace.empty()) return fail(*smp, "sample = \"" + sc.sampleText + "\": the scenario has no trace to sample");
  }
  auto tables = [&](const char* key, const toml::array*& out) {
    out = nullptr;
    const toml::node* n = tbl.get(key);
    if (!n) return true;
    out = n->as_array();
    if (!out || !out->is_array_of_tables()) return fail(*n, std::string("'") + key + "' must be an array of tables ([[" + key + "]])");
    return true;
  };
  const toml::array* arr = nullptr;
  if (!tables("set", arr)) return false;
  if (arr)
    for (const toml::node& n : *arr) {
      const toml::table& t = *n.as_table();
      SetStep s;
      s.where = where(shown, n);
      auto var = t["var"].value_exact<std::string>();
      if (!durationOf(t.get("at"), s.at) || !var || !literalText(t.get("value"), s.value))
        return fail(n, "a [[set]] needs at = \"<duration>\", var = \"NAME\" and value = \"<ST literal>\"");
      s.var = *var;
      sc.sets.push_back(std::move(s));
    }
  if (!tables("fault", arr)) return false;
  if (arr)
    for (const toml::node& n : *arr) {
      const toml::table& t = *n.as_table();
      FaultStep f;
      f.where = where(shown, n);
      auto axis = t["axis"].value_exact<std::string>();
      auto kind = t["kind"].value_exact<std::string>();
      if (!durationOf(t.get("at"), f.at) || !axis || !kind || !motion::faultKindNamed(*kind, f.kind))
        return fail(n, std::string("a [[fault]] needs at = \"<duration>\", axis = \"NAME\" and kind = ") + motion::faultKindNames());
      f.axis = *axis;
      sc.faults.push_back(std::move(f));
    }
  if (!tables("check", arr)) return false;
  if (arr)
    for (const toml::node& n : *arr) {
      const toml::table& t = *n.as_table();
      Check c;
      c.where = where(shown, n);
      auto var = t["var"].value_exact<std::string>();
      if (!var) return fail(n, "a [[check]] needs var = \"NAME\"");
      c.var = *var;
      int kinds = (t.get("equals") ? 1 : 0) + (t.get("rises_between") ? 1 : 0) + ((t.get("min") || t.get("max")) ? 1 : 0);
      if (kinds != 1) return fail(n, "a [[check]] has exactly one of: equals (with at), rises_between, min/max");
      if (t.get("equals")) {
        c.kind = Check::Equals;
        if (!literalText(t.get("equals"), c.equals) || !durationOf(t.get("at"), c.at))
          return fail(n, "an equals check needs at = \"<duration>\" and equals = \"<ST literal>\"");
      } else if (const toml::node* rb = t.get("rises_between")) {
        c.kind = Check::Rises;
        const toml::array* a = rb->as_array();
        if (t.get("at") || !a || a->size() != 2 || !durationOf(a->get(0), c.from) || !durationOf(a->get(1), c.to) || c.to < c.from)
          return fail(n, "rises_between must be [\"T1\", \"T2\"] with T1 <= T2 (and no at)");
      } else {
        c.kind = Check::Bounds;
        if (t.get("at")) return fail(n, "a min/max check holds over the whole run; it has no at");
        for (const char* key : {"min", "max"})
          if (const toml::node* b = t.get(key)) {
            auto d = b->value<double>();
            if (!d) return fail(*b, std::string(key) + " must be a number");
            (std::string(key) == "min" ? c.min : c.max) = *d;
          }
      }
      sc.checks.push_back(std::move(c));
    }
  std::stable_sort(sc.sets.begin(), sc.sets.end(), [](const SetStep& a, const SetStep& b) { return a.at < b.at; });
  return true;
}

// ---------------------------------------------------------------- CSV

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
      else if (c == '"') quoted = false;
      else cur += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(std::move(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(std::move(cur));
  return out;
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    out.push_back(line);
  }
  return out;
}

bool readFile(const fs::path& p, std::string& out) {
  std::string why;
  return config::readRegularFile(p.string(), out, why, uint64_t(1) << 32);
}

bool numberOf(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end && *end == 0;
}

bool withinTolerance(double a, double e, double tol) {
  if (std::isnan(a) || std::isnan(e)) return std::isnan(a) && std::isnan(e);
  if (a == e) return true;
  return std::fabs(a - e) <= tol * std::max(1.0, std::fabs(e));
}

// A trace CSV: the header's variable names, then per row its time and values.
struct TraceTable {
  std::vector<std::string> names;
  std::vector<vm::Time> times;
  std::vector<std::vector<std::string>> rows;
};

bool parseTrace(const std::string& text, TraceTable& t, std::string& error) {
  std::vector<std::string> lines = splitLines(text);
  // Metadata lines before the header (`#units,...`, docs/projects.md "Traces and plots").
  size_t first = 0;
  while (first < lines.size() && !lines[first].empty() && lines[first][0] == '#') ++first;
  if (first >= lines.size()) return error = "is empty", false;
  std::vector<std::string> head = splitCsvLine(lines[first]);
  if (head.empty() || head[0] != "time") return error = fmt::format("line {}: the header does not start with 'time'", first + 1), false;
  t.names.assign(head.begin() + 1, head.end());
  for (size_t r = first + 1; r < lines.size(); ++r) {
    if (lines[r].empty() && r + 1 == lines.size()) break;
    std::vector<std::string> f = splitCsvLine(lines[r]);
    vm::Time at = 0;
    if (f.size() != head.size() || !vm::parseIecDuration(f[0] + "s", at) || at < 0 || (!t.times.empty() && at <= t.times.back()))
      return error = fmt::format("line {}: not a row of {} values after a time in seconds later than the row before", r + 1, head.size()), false;
    t.times.push_back(at);
    f.erase(f.begin());
    t.rows.push_back(std::move(f));
  }
  return true;
}

std::string shortValue(const std::string& v) { return v.size() > 60 ? v.substr(0, 57) + "..." : v; }

// Where a difference is: the time and the base tick's number (1 = time 0).
std::string whenText(vm::Time t, vm::Time base) {
  return fmt::format("{} (cycle {})", vm::formatIecTime(t), base > 0 ? t / base + 1 : 0);
}

struct GoldenCompare {
  const std::map<std::string, bool>* realColumn;   // trace name -> REAL/LREAL
  double tolerance = 0;
  vm::Time base = 0;             // the base tick, for cycle numbers
  bool held = false;             // sample = "change": a value holds until the next row
  std::string golden;            // "expected/x.csv", for messages
};

// Compares the run's trace with the golden one; appends the differences to `report`:
// per differing variable its first and last differing time, the number of differing
// rows and the values at the first difference (at most kMaxColumns variables).
bool compareTraces(const std::string& expectedText, const std::string& actualText, const GoldenCompare& g, std::string& report) {
  constexpr size_t kMaxColumns = 20;
  TraceTable e, a;
  std::string why;
  if (!parseTrace(expectedText, e, why)) return report += "  " + g.golden + ": " + why + "\n", false;
  if (!parseTrace(actualText, a, why)) return report += "  the run's trace: " + why + "\n", false;
  bool same = true;
  // Columns by name: the ones in both are compared.
  std::vector<std::pair<size_t, size_t>> common;   // (expected index, actual index)
  std::vector<std::string> onlyE, onlyA;
  for (size_t i = 0; i < e.names.size(); ++i) {
    auto it = std::find(a.names.begin(), a.names.end(), e.names[i]);
    if (it == a.names.end()) onlyE.push_back(e.names[i]);
    else common.emplace_back(i, static_cast<size_t>(it - a.names.begin()));
  }
  for (const std::string& n : a.names)
    if (std::find(e.names.begin(), e.names.end(), n) == e.names.end()) onlyA.push_back(n);
  auto joined = [](const std::vector<std::string>& v) {
    std::string out;
    for (size_t i = 0; i < v.size() && i < kMaxColumns; ++i) out += (i ? ", " : "") + v[i];
    if (v.size() > kMaxColumns) out += fmt::format(" and {} more", v.size() - kMaxColumns);
    return out;
  };
  if (!onlyE.empty() || !onlyA.empty()) {
    same = false;
    report += "  the traced variables differ from " + g.golden + ":";
    if (!onlyE.empty()) report += " only in the golden file: " + joined(onlyE) + ";";
    if (!onlyA.empty()) report += " only in this run: " + joined(onlyA) + ";";
    report.back() = '\n';
  }
  if (e.times.empty() || a.times.empty()) {
    if (e.times.size() != a.times.size())
      report += fmt::format("  {} has {} rows, this run {}\n", g.golden, e.times.size(), a.times.size());
    return same && e.times.size() == a.times.size();
  }

  struct ColumnDiff {
    size_t rows = 0;
    vm::Time first = 0, last = 0;
    std::string expected, actual;   // at the first difference
  };
  std::vector<ColumnDiff> diffs(common.size());
  size_t rowsDiffering = 0, rowsCompared = 0, onlyInE = 0, onlyInA = 0;
  vm::Time firstOnlyE = 0, firstOnlyA = 0, firstRow = 0, lastRow = 0;
  // Over the union of the two traces' times; with held values (sample = "change") a
  // row stands for every time up to the next one, else each time must be in both.
  size_t i = 0, j = 0;
  long ie = -1, ja = -1;
  while (i < e.times.size() || j < a.times.size()) {
    const vm::Time t = std::min(i < e.times.size() ? e.times[i] : INT64_MAX, j < a.times.size() ? a.times[j] : INT64_MAX);
    const bool inE = i < e.times.size() && e.times[i] == t, inA = j < a.times.size() && a.times[j] == t;
    if (inE) ie = static_cast<long>(i++);
    if (inA) ja = static_cast<long>(j++);
    if (!g.held && inE != inA) {
      if (inE && !onlyInE++) firstOnlyE = t;
      if (inA && !onlyInA++) firstOnlyA = t;
      continue;
    }
    if (ie < 0 || ja < 0) continue;   // held: before the other's first row (both start at 0)
    ++rowsCompared;
    bool rowDiffers = false;
    for (size_t c = 0; c < common.size(); ++c) {
      const std::string& ev = e.rows[static_cast<size_t>(ie)][common[c].first];
      const std::string& av = a.rows[static_cast<size_t>(ja)][common[c].second];
      if (ev == av) continue;
      double x, y;
      auto real = g.realColumn->find(a.names[common[c].second]);
      if (real != g.realColumn->end() && real->second && numberOf(ev, x) && numberOf(av, y) && withinTolerance(y, x, g.tolerance)) continue;
      ColumnDiff& d = diffs[c];
      if (d.rows++ == 0) d.first = t, d.expected = ev, d.actual = av;
      d.last = t;
      rowDiffers = true;
    }
    if (rowDiffers) {
      if (rowsDiffering++ == 0) firstRow = t;
      lastRow = t;
    }
  }
  if (rowsDiffering) {
    same = false;
    report += fmt::format("  the trace differs from {} in {} of {} rows, from {} to {}:\n", g.golden, rowsDiffering, rowsCompared,
                          whenText(firstRow, g.base), whenText(lastRow, g.base));
    size_t shown = 0, more = 0;
    for (size_t c = 0; c < common.size(); ++c) {
      const ColumnDiff& d = diffs[c];
      if (!d.rows) continue;
      if (shown == kMaxColumns) {
        ++more;
        continue;
      }
      ++shown;
      report += fmt::format("    {}: {} {}, first at {}: expected {}, actual {}", a.names[common[c].second], d.rows, d.rows == 1 ? "row differs" : "rows differ",
                            whenText(d.first, g.base), shortValue(d.expected), shortValue(d.actual));
      report += d.rows > 1 ? fmt::format("; last at {}\n", whenText(d.last, g.base)) : std::string("\n");
    }
    if (more) report += fmt::format("    ... and {} more variables differ\n", more);
  }
  if (onlyInE || onlyInA) {
    same = false;
    report += fmt::format("  {} has {} rows (last at {}), this run {} (last at {})", g.golden, e.times.size(), vm::formatIecTime(e.times.back()),
                          a.times.size(), vm::formatIecTime(a.times.back()));
    if (onlyInE) report += fmt::format("; {} rows only in the golden file, the first at {}", onlyInE, vm::formatIecTime(firstOnlyE));
    if (onlyInA) report += fmt::format("; {} rows only in this run, the first at {}", onlyInA, vm::formatIecTime(firstOnlyA));
    report += "\n";
  } else if (g.held && e.times.back() != a.times.back()) {
    same = false;
    report += fmt::format("  {} ends at {}, this run at {}\n", g.golden, vm::formatIecTime(e.times.back()), vm::formatIecTime(a.times.back()));
  }
  return same;
}

// ---------------------------------------------------------------- one project

struct ProjectRun {
  std::string dir;        // as given
  std::string label;      // directory name, printed before /scenario
  bool update = false, force = false;
  std::vector<std::string> only;   // --scenario names (empty: all)
  std::string actualDir;  // --actual: this project's directory for the actual traces
  std::string out;
  unsigned passed = 0, failed = 0;
};

// What a scenario's run says: the verdict, the note after the PASS/FAIL line and the report.
struct Outcome {
  bool pass = false;
  std::string note;       // ", expected/x.csv written"
  std::string report;     // indented lines
};

// A resolved variable, its text and its numeric value (if it has one).
struct Probe {
  vm::ValueRef ref;
  const sema::Type* type = nullptr;   // without subrange
  bool isReal = false, isNumeric = false, isBool = false;
};

bool makeProbe(vm::Controller& ctl, const sema::Layout& layout, const std::string& var, Probe& p, std::string& err) {
  if (!vm::resolvePath(ctl.imageMap(), layout, var, p.ref, err)) return false;
  const sema::Type* t = p.ref.type;
  while (t->kind == sema::TypeKind::Subrange && t->element) t = t->element;
  p.type = t;
  const sema::Type* u = t->underlying();
  p.isBool = p.ref.bit >= 0 || u->isBool();
  p.isReal = u->isReal();
  p.isNumeric = !p.isBool && (u->isInteger() || u->isBitString() || u->isReal());
  return true;
}

double numericValue(const vm::Controller& ctl, const Probe& p) {
  const uint8_t* q = ctl.image() + p.ref.offset;
  const sema::Type* u = p.type->underlying();
  if (u->kind == sema::TypeKind::Real) { float f; std::memcpy(&f, q, 4); return f; }
  if (u->kind == sema::TypeKind::LReal) { double d; std::memcpy(&d, q, 8); return d; }
  unsigned n = std::max(1u, u->bits() / 8);
  uint64_t v = 0;
  std::memcpy(&v, q, n);
  if (u->isSignedInt() && n < 8 && (v >> (8 * n - 1)) & 1) v |= ~0ull << (8 * n);
  return u->isSignedInt() ? static_cast<double>(static_cast<int64_t>(v)) : static_cast<double>(v);
}

bool boolValue(const vm::Controller& ctl, const Probe& p) {
  const uint8_t* q = ctl.image() + p.ref.offset;
  return p.ref.bit >= 0 ? ((*q >> p.ref.bit) & 1) : *q != 0;
}

std::string numText(double v) { return vm::formatReal(v, false); }

struct CheckState {
  const Check* c;
  Probe probe;
  std::vector<uint8_t> expected;      // Equals: the parsed literal
  std::string expectedText;
  double expectedReal = 0;
  bool seen = false;                  // Equals: a sample at or before `at`
  std::string actualText;
  double actualReal = 0;
  bool prev = false;                  // Rises
  std::optional<vm::Time> riseIn, riseAny;
  double lo = 0, hi = 0;              // Bounds
  vm::Time loAt = 0, hiAt = 0;
  bool any = false;
};

class TempFile {
public:
  TempFile() {
    const char* dir = std::getenv("TMPDIR");
    std::string tmpl = std::string(dir && *dir ? dir : "/tmp") + "/stc-test-XXXXXX.csv";
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back(0);
    int fd = mkstemps(buf.data(), 4);
    if (fd >= 0) {
      close(fd);
      path_ = buf.data();
    }
  }
  ~TempFile() {
    if (!path_.empty()) unlink(path_.c_str());
  }
  const std::string& path() const { return path_; }

private:
  std::string path_;
};

// Writes `text` to `name` inside `root` (never through a symbolic link out of it).
bool writeInside(const std::string& root, const std::string& name, const std::string& text, std::string& why) {
  const int fd = vm::openInside(root, name, vm::FileAccess::WriteMakeDirs, why);
  std::FILE* f = fd < 0 ? nullptr : ::fdopen(fd, "wb");
  if (!f) {
    if (fd >= 0) ::close(fd);
    if (why.empty()) why = "cannot open it";
    return false;
  }
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) return why = std::string("cannot write it: ") + std::strerror(errno), false;
  return true;
}

// Runs one scenario (in a process of its own, see runProject): whether it passed; the
// report and the note go to `outcome`.
bool runScenario(const ProjectRun& pr, Compilation& comp, const sema::Model& model, const Scenario& sc, Outcome& outcome) {
  std::string& report = outcome.report;
  // The axes, with the scenario's faults added.
  tool::RunLibraries libs;
  std::string err;
  if (!libs.motion.readProject(pr.dir, {}, err)) {
    report += "  " + err + "\n";
    return false;
  }
  std::vector<motion::AxisConfig>& axes = libs.motion.config().axes;
  for (const FaultStep& f : sc.faults) {
    auto ax = std::find_if(axes.begin(), axes.end(), [&](const motion::AxisConfig& a) { return equalsIgnoreCase(a.name, f.axis); });
    if (ax == axes.end()) {
      report += "  " + f.where + ": error: no [[axis]] named '" + f.axis + "' in project.toml\n";
      return false;
    }
    motion::FaultEvent ev;
    ev.atNs = f.at;
    ev.kind = f.kind;
    ax->drive.faults.push_back(ev);
    std::stable_sort(ax->drive.faults.begin(), ax->drive.faults.end(),
                     [](const motion::FaultEvent& a, const motion::FaultEvent& b) { return a.atNs < b.atNs; });
  }

  codegen::CodegenOptions o;
  o.optLevel = 1;   // as stc run
  o.checks = true;
  o.checkPointers = true;   // scenarios run with every pointer checked (docs/security.md)
  std::unique_ptr<codegen::CompiledModule> m;
  // The scenario's own diagnostics (code generation, runtime faults): the project's
  // compilation is shared by the scenarios and stays as it was checked.
  DiagnosticsEngine diags(comp.sources());
  diags.opts = comp.diags().opts;
  runWithLargeStack([&] { m = codegen::generate(model, comp.sources(), diags, o, true); });
  auto diagText = [&](size_t from) {
    std::string s;
    const auto& d = diags.diagnostics();
    for (size_t i = from; i < d.size(); ++i) s += renderText(comp.sources(), d[i]);
    return s;
  };
  if (!m) {
    report += diagText(0);
    return false;
  }
  // The base tick (the controller's: the gcd of the cyclic tasks' intervals, 1 ms
  // without any) and the fastest task's interval (`cycles` counts its slots).
  vm::Time base = 0, fastest = 0;
  for (const codegen::TaskPlan& t : m->tasks)
    if (t.kind == codegen::TaskPlan::Kind::Cyclic && t.intervalNs > 0) {
      base = std::gcd(base, t.intervalNs);
      fastest = fastest ? std::min(fastest, t.intervalNs) : t.intervalNs;
    }
  if (!base) base = fastest = vm::kMillisecond;
  if (sc.sampleEvery) {
    const vm::Time runEnd = sc.duration ? *sc.duration
                            : *sc.cycles > static_cast<uint64_t>(INT64_MAX / fastest) ? INT64_MAX
                                                                                     : static_cast<vm::Time>(*sc.cycles) * fastest;
    if (*sc.sampleEvery % base != 0) {
      report += "  " + sc.sampleWhere + ": error: sample = \"" + sc.sampleText + "\": not a multiple of the base cycle (" +
                vm::formatIecTime(base) + ")\n";
      return false;
    }
    if (*sc.sampleEvery > runEnd) {
      report += "  " + sc.sampleWhere + ": error: sample = \"" + sc.sampleText + "\": above the scenario's duration (" +
                std::to_string(*sc.cycles) + " cycles of " + vm::formatIecTime(fastest) + ")\n";
      return false;
    }
  }
  vm::Controller ctl(model, diags);
  libs.attachTo(ctl);
  if (!ctl.load(std::move(m), err)) {
    report += "  error: " + err + "\n";
    return false;
  }
  const sema::Layout& layout = *model.layout;

  // Stimuli: resolved and parsed before the run.
  struct Stim {
    vm::ValueRef ref;
    std::vector<uint8_t> bytes;
    vm::Time at;
  };
  std::vector<Stim> stims;
  bool ok = true;
  for (const SetStep& s : sc.sets) {
    Probe p;
    if (!makeProbe(ctl, layout, s.var, p, err)) {
      report += "  " + s.where + ": error: " + s.var + ": " + err + "\n";
      ok = false;
      continue;
    }
    Stim st{p.ref, std::vector<uint8_t>(std::max<uint64_t>(1, layout.sizeOf(p.ref.type))), s.at};
    if (!vm::parseValue(s.value, st.bytes.data(), p.ref.type, layout, err)) {
      report += "  " + s.where + ": error: " + s.var + ": " + err + "\n";
      ok = false;
      continue;
    }
    stims.push_back(std::move(st));
  }
  std::vector<CheckState> checks;
  for (const Check& c : sc.checks) {
    CheckState cs{&c, {}, {}, {}, 0, false, {}, 0, false, {}, {}, 0, 0, 0, 0, false};
    if (!makeProbe(ctl, layout, c.var, cs.probe, err)) {
      report += "  " + c.where + ": error: " + c.var + ": " + err + "\n";
      ok = false;
      continue;
    }
    if (c.kind == Check::Equals) {
      cs.expected.resize(std::max<uint64_t>(1, layout.sizeOf(cs.probe.ref.type)));
      if (!vm::parseValue(c.equals, cs.expected.data(), cs.probe.ref.type, layout, err)) {
        report += "  " + c.where + ": error: " + c.var + ": " + err + "\n";
        ok = false;
        continue;
      }
      cs.expectedText = cs.probe.ref.bit >= 0 ? (cs.expected[0] ? "TRUE" : "FALSE") : vm::formatValue(cs.expected.data(), cs.probe.ref.type, layout);
      if (cs.probe.isReal && (!numberOf(cs.expectedText, cs.expectedReal) || !std::isfinite(cs.expectedReal))) {
        // NaN never equals anything and Inf only itself: such a check could never say anything.
        report += "  " + c.where + ": error: " + c.var + ": equals " + c.equals + ": a finite number is expected\n";
        ok = false;
        continue;
      }
    } else if (c.kind == Check::Rises && !cs.probe.isBool) {
      report += "  " + c.where + ": error: rises_between needs a BOOL; " + c.var + " is " + cs.probe.type->name + "\n";
      ok = false;
      continue;
    } else if (c.kind == Check::Bounds && !cs.probe.isNumeric) {
      report += "  " + c.where + ": error: min/max need a number; " + c.var + " is " + cs.probe.type->name + "\n";
      ok = false;
      continue;
    }
    checks.push_back(std::move(cs));
  }
  std::map<std::string, bool> realColumn;
  for (const std::string& v : sc.trace) {
    Probe p;
    if (!makeProbe(ctl, layout, v, p, err)) {
      report += "  " + sc.file + ": error: trace " + v + ": " + err + "\n";
      ok = false;
      continue;
    }
    realColumn[v] = p.isReal;
  }
  if (!ok) return false;

  for (CheckState& cs : checks)
    if (cs.c->kind == Check::Rises) cs.prev = boolValue(ctl, cs.probe);

  vm::RunOptions ro;
  ro.cycles = sc.cycles;
  ro.duration = sc.duration;
  ro.traces = sc.trace;
  for (const CheckState& cs : checks) ro.observesMirrored = ro.observesMirrored || cs.probe.ref.mirrored;
  TempFile tmp;
  if (!sc.trace.empty() && tmp.path().empty()) {
    report += "  error: cannot create a temporary file\n";
    return false;
  }
  ro.traceOut = tmp.path();
  ro.traceCsv.tolerance = sc.tolerance;
  ro.traceCsv.every = sc.sampleEvery.value_or(0);
  ro.traceCsv.onChange = sc.sampleChange;
  size_t nextStim = 0;
  const codegen::ImageMap& im = ctl.imageMap();
  ro.beforeSlot = [&](vm::Time now) {
    for (; nextStim < stims.size() && stims[nextStim].at <= now; ++nextStim) {
      const Stim& s = stims[nextStim];
      uint8_t* q = ctl.image() + s.ref.offset;
      if (s.ref.bit >= 0) *q = static_cast<uint8_t>((*q & ~(1u << s.ref.bit)) | ((s.bytes[0] ? 1u : 0u) << s.ref.bit));
      else std::memcpy(q, s.bytes.data(), s.bytes.size());
      // A variable in %I: the external inputs are copied over it before the slot.
      uint64_t n = s.ref.bit >= 0 ? 1 : s.bytes.size();
      if (s.ref.offset >= im.inputOffset && s.ref.offset + n <= im.inputOffset + ctl.inputs().size())
        std::memcpy(ctl.inputs().data() + (s.ref.offset - im.inputOffset), q, n);
    }
  };
  vm::Time lastTick = -1;
  ro.afterTick = [&](vm::Time now) {
    lastTick = now;
    for (CheckState& cs : checks) {
      const Check& c = *cs.c;
      switch (c.kind) {
        case Check::Equals:
          if (now <= c.at) {
            cs.seen = true;
            cs.actualText = ctl.valueText(cs.probe.ref);
            if (cs.probe.isReal) cs.actualReal = numericValue(ctl, cs.probe);
          }
          break;
        case Check::Rises: {
          bool v = boolValue(ctl, cs.probe);
          if (v && !cs.prev) {
            if (!cs.riseAny) cs.riseAny = now;
            if (!cs.riseIn && now >= c.from && now <= c.to) cs.riseIn = now;
          }
          cs.prev = v;
          break;
        }
        case Check::Bounds: {
          double v = numericValue(ctl, cs.probe);
          if (!cs.any || v < cs.lo) cs.lo = v, cs.loAt = now;
          if (!cs.any || v > cs.hi) cs.hi = v, cs.hiAt = now;
          cs.any = true;
          break;
        }
      }
    }
  };
  std::ostringstream out, errs;
  size_t beforeRun = diags.diagnostics().size();
  int rc = ctl.run(ro, out, errs);
  bool pass = true;
  const bool faulted = rc != 0;
  if (faulted) {
    std::string e = errs.str() + diagText(beforeRun);
    for (const std::string& line : splitLines(e)) report += "  " + line + "\n";
    pass = false;
  }
  unsigned checksFailed = 0;

  // The checks.
  for (const CheckState& cs : checks) {
    const Check& c = *cs.c;
    switch (c.kind) {
      case Check::Equals: {
        std::string head = fmt::format("  check {} = {} at {} ({})", c.var, c.equals, vm::formatIecTime(c.at), c.where);
        // A run of `duration` covers [0, duration]: its last tick's values are those at `duration`.
        const vm::Time runEnd = sc.duration ? std::max(*sc.duration, lastTick) : lastTick;
        if (c.at > runEnd) {
          report += head + ": the run ends at " + vm::formatIecTime(runEnd) + ", before that time\n";
          pass = false, ++checksFailed;
        } else if (!cs.seen || (cs.probe.isReal ? !withinTolerance(cs.actualReal, cs.expectedReal, sc.tolerance) : cs.actualText != cs.expectedText)) {
          report += head + ": actual " + cs.actualText + "\n";
          pass = false, ++checksFailed;
        }
        break;
      }
      case Check::Rises:
        if (!cs.riseIn) {
          std::string why = cs.riseAny ? "it first rises at " + vm::formatIecTime(*cs.riseAny)
                                       : std::string("it never rises (") + (cs.prev ? "TRUE" : "FALSE") + " at the end)";
          report += fmt::format("  check {} rises between {} and {} ({}): {}\n", c.var, vm::formatIecTime(c.from), vm::formatIecTime(c.to), c.where, why);
          pass = false, ++checksFailed;
        }
        break;
      case Check::Bounds:
        if (c.min && cs.any && cs.lo < *c.min) {
          report += fmt::format("  check {} >= {} ({}): actual minimum {} at {}\n", c.var, numText(*c.min), c.where, numText(cs.lo), vm::formatIecTime(cs.loAt));
          pass = false, ++checksFailed;
        }
        if (c.max && cs.any && cs.hi > *c.max) {
          report += fmt::format("  check {} <= {} ({}): actual maximum {} at {}\n", c.var, numText(*c.max), c.where, numText(cs.hi), vm::formatIecTime(cs.hiAt));
          pass = false, ++checksFailed;
        }
        break;
    }
  }

  // The golden trace.
  if (sc.trace.empty()) return pass;
  std::string actual;
  if (!readFile(tmp.path(), actual)) {
    report += "  error: cannot read the trace '" + tmp.path() + "'\n";
    return false;
  }
  const std::string goldenName = "expected/" + sc.name + ".csv";
  if (!pr.actualDir.empty()) {
    std::string why;
    if (writeInside(pr.actualDir, sc.name + ".csv", actual, why)) {
      outcome.note += ", actual trace " + (fs::path(pr.actualDir) / (sc.name + ".csv")).string();
    } else {
      report += "  error: the actual trace " + sc.name + ".csv not written to '" + pr.actualDir + "': " + why + "\n";
      pass = false;
    }
  }
  fs::path golden = fs::path(pr.dir) / goldenName;
  std::string why;
  bool exists = false;
  if (!config::checkRegularFile(golden.string(), why, true, &exists)) {
    // A directory, FIFO, device or link loop in its place: never opened (a FIFO would block).
    report += "  error: " + goldenName + " " + why + "\n";
    return false;
  }
  if (pr.update) {
    if (!pass && !pr.force) {
      // A failing scenario is not blessed silently: its trace shows the failure.
      std::string reasons;
      if (faulted) reasons = "it faults";
      if (checksFailed) reasons += (reasons.empty() ? "" : " and ") + std::string(checksFailed == 1 ? "1 check fails" : std::to_string(checksFailed) + " checks fail");
      if (reasons.empty()) reasons = "it fails";
      report += "  " + goldenName + " not written: " + reasons + " (stc test --update --force writes it anyway)\n";
      return false;
    }
    // Never outside the project: a symbolic link (expected/ itself, or a golden file)
    // leading out of it is refused (vm/FileSandbox.h).
    if (writeInside(pr.dir, goldenName, actual, why)) {
      outcome.note += ", " + goldenName + " written" + (pass ? "" : " (--force)");
    } else {
      report += "  error: " + goldenName + " not written: " + why + "\n";
      pass = false;
    }
    return pass;
  }
  std::string expected;
  if (!exists) {
    report += "  no " + goldenName + "; run stc test --update\n";
    return false;
  }
  if (!config::readRegularFile(golden.string(), expected, why, uint64_t(1) << 32)) {
    report += "  error: " + goldenName + " " + why + "\n";
    return false;
  }
  GoldenCompare g{&realColumn, sc.tolerance, base, sc.sampleChange, goldenName};
  return compareTraces(expected, actual, g, report) && pass;
}

std::string label(const std::string& dir) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(dir), ec);
  std::string name = p.filename().string();
  return name.empty() ? dir : name;
}

bool writeAll(int fd, const std::string& text) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

// Runs `fn` in a child process (fork, no exec: it shares the parsed project as it
// was at the fork) and takes its Outcome back through a pipe, so nothing the run
// does (a runtime fault, a crash of stc itself, a leak) reaches the next scenario.
// A child that dies is this scenario's FAIL with the signal.  Without a process
// (fork refused), the scenario runs here.
void runIsolated(Outcome& o, const std::function<void(Outcome&)>& fn) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    fn(o);
    return;
  }
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    fn(o);
    return;
  }
  if (pid == 0) {
    ::close(fds[0]);
    Outcome mine;
    fn(mine);
    // "P"/"F", the note's length and text, then the report.
    const std::string msg = std::string(mine.pass ? "P" : "F") + std::to_string(mine.note.size()) + ":" + mine.note + mine.report;
    std::fflush(nullptr);
    ::_exit(writeAll(fds[1], msg) ? 0 : 1);
  }
  ::close(fds[1]);
  std::string msg;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    msg.append(buf, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  const size_t colon = msg.find(':');
  size_t noteLen = 0;
  const bool wellFormed = !msg.empty() && (msg[0] == 'P' || msg[0] == 'F') && colon != std::string::npos && colon > 1 && colon <= 12 &&
                          std::all_of(msg.begin() + 1, msg.begin() + static_cast<long>(colon), [](char c) { return c >= '0' && c <= '9'; }) &&
                          (noteLen = std::stoul(msg.substr(1, colon - 1))) <= msg.size() - colon - 1;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && wellFormed) {
    o.pass = msg[0] == 'P';
    o.note = msg.substr(colon + 1, noteLen);
    o.report = msg.substr(colon + 1 + noteLen);
    return;
  }
  o.pass = false;
  if (WIFSIGNALED(status))
    o.report += fmt::format("  error: the scenario's process died (signal {}: {})\n", WTERMSIG(status), ::strsignal(WTERMSIG(status)));
  else
    o.report += fmt::format("  error: the scenario's process ended with status {} without a report\n", WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

void runProject(ProjectRun& pr) {
  fs::path scenDir = fs::path(pr.dir) / "scenarios";
  std::vector<fs::path> files;
  std::error_code ec;
  // Every entry named *.toml is a scenario: one that is not a file (a directory, FIFO,
  // link loop ...) fails with that message rather than being skipped.
  if (fs::exists(fs::symlink_status(scenDir, ec)) && !fs::is_directory(scenDir, ec)) {
    std::string why;
    config::checkRegularFile(scenDir.string(), why);
    if (why.empty()) why = "is a file";
    if (why.size() > 12 && why.compare(why.size() - 12, 12, ", not a file") == 0) why.resize(why.size() - 12);
    pr.out += "FAIL " + pr.label + "\n  scenarios: error: " + why + ", not a directory of scenarios\n";
    ++pr.failed;
    return;
  }
  if (fs::is_directory(scenDir, ec))
    for (const auto& e : fs::directory_iterator(scenDir, ec))
      if (e.path().extension() == ".toml" &&
          (pr.only.empty() || std::find(pr.only.begin(), pr.only.end(), e.path().stem().string()) != pr.only.end()))
        files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty() && !pr.only.empty()) return;   // --scenario names none of this project's
  if (files.empty()) {
    // Nothing to run, but the project file is still checked.
    ProjectConfig cfg;
    std::string err;
    if (!loadProject(pr.dir, cfg, err)) {
      pr.out += "FAIL " + pr.label + "\n  " + err + "\n";
      ++pr.failed;
    }
    return;
  }

  Compilation comp;
  bool compiled = false;
  std::string compileErrors;
  {
    bool inputsOk = comp.addPath(pr.dir);
    CompileOptions co;
    bool ok = false;
    if (inputsOk) runWithLargeStack([&] { ok = comp.check(co); });
    compiled = ok && inputsOk && comp.model() && !comp.diags().hasErrors();
    if (!compiled)
      for (const Diagnostic& d : comp.diags().diagnostics()) compileErrors += renderText(comp.sources(), d);
  }
  // Taken once: the scenarios never add to the compilation's diagnostics.
  const sema::Model* model = compiled ? comp.model() : nullptr;
  for (const fs::path& f : files) {
    auto t0 = std::chrono::steady_clock::now();
    Scenario sc;
    Outcome o;
    std::string err;
    std::string shown = "scenarios/" + f.filename().string();
    if (!loadScenario(f, shown, sc, err)) {
      o.report = "  " + err + "\n";
      sc.name = f.stem().string();
    } else if (!model) {
      o.report = "  the project does not compile:\n";
      for (const std::string& line : splitLines(compileErrors)) o.report += "  " + line + "\n";
    } else {
      runIsolated(o, [&](Outcome& out) { out.pass = runScenario(pr, comp, *model, sc, out); });
    }
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    pr.out += fmt::format("{} {}/{} ({:.2f} s){}\n", o.pass ? "PASS" : "FAIL", pr.label, sc.name, secs, o.note);
    pr.out += o.report;
    ++(o.pass ? pr.passed : pr.failed);
  }
}

// ---------------------------------------------------------------- processes

struct Child {
  pid_t pid = -1;
  std::string outFile;
  bool done = false;
  int status = 0;
};

}  // namespace

int runTest(const TestArgs& args) {
  if (!args.one.empty()) {
    // A child: one project, the report on stdout.
    ProjectRun pr;
    pr.dir = args.one;
    pr.label = label(args.one);
    pr.update = args.update;
    pr.force = args.force;
    pr.only = args.scenarios;
    pr.actualDir = args.actual;
    runProject(pr);
    std::fwrite(pr.out.data(), 1, pr.out.size(), stdout);
    std::fflush(stdout);
    return pr.failed ? 1 : 0;
  }
  std::vector<std::string> dirs = args.paths.empty() ? std::vector<std::string>{"."} : args.paths;
  for (const std::string& d : dirs) {
    std::error_code ec;
    // A project.toml that is not a regular file is the child's error (exit 1), with its reason.
    if (!fs::is_directory(d, ec) || !fs::exists(fs::symlink_status(fs::path(d) / "project.toml", ec))) {
      std::fprintf(stderr, "stc: error: '%s' is not a project directory (no project.toml)\n", d.c_str());
      return 2;
    }
  }
  if (args.force && !args.update) {
    std::fprintf(stderr, "stc: error: --force only goes with --update (it writes the golden files of failing scenarios)\n");
    return 2;
  }
  // --scenario: each name is a scenario of at least one of the projects.
  if (!args.scenarios.empty()) {
    std::vector<std::string> known;
    for (const std::string& d : dirs) {
      std::error_code ec;
      for (const auto& e : fs::directory_iterator(fs::path(d) / "scenarios", ec))
        if (e.path().extension() == ".toml") known.push_back(e.path().stem().string());
    }
    for (const std::string& n : args.scenarios)
      if (std::find(known.begin(), known.end(), n) == known.end()) {
        const std::string hint = config::closest(n, known);
        std::fprintf(stderr, "stc: error: --scenario %s: no scenarios/%s.toml in %s%s\n", n.c_str(), n.c_str(),
                     dirs.size() == 1 ? ("'" + dirs[0] + "'").c_str() : "the projects given",
                     hint.empty() ? "" : ("; did you mean '" + hint + "'?").c_str());
        return 2;
      }
  }
  // --actual DIR: created; with several projects one subdirectory per project. Never a
  // project's expected/ (or a directory in it): the golden files stay as they are.
  std::vector<std::string> actualDirs(dirs.size());
  if (!args.actual.empty()) {
    std::error_code ec;
    const fs::path root = fs::weakly_canonical(fs::absolute(args.actual, ec), ec);
    std::vector<std::string> labels;
    for (size_t i = 0; i < dirs.size(); ++i) {
      const std::string l = label(dirs[i]);
      if (dirs.size() > 1 && std::find(labels.begin(), labels.end(), l) != labels.end()) {
        std::fprintf(stderr, "stc: error: --actual: two projects are named '%s'; give them one at a time\n", l.c_str());
        return 2;
      }
      labels.push_back(l);
      const fs::path dir = dirs.size() > 1 ? root / l : root;
      for (const std::string& d : dirs) {
        const fs::path expected = fs::weakly_canonical(fs::absolute(fs::path(d) / "expected", ec), ec);
        const auto rel = dir.lexically_relative(expected);
        if (!rel.empty() && *rel.begin() != "..") {
          std::fprintf(stderr, "stc: error: --actual %s: this is %s, where the golden files are; choose another directory\n",
                       args.actual.c_str(), rel == "." ? (d + "/expected").c_str() : ("inside " + d + "/expected").c_str());
          return 2;
        }
      }
      fs::create_directories(dir, ec);
      if (ec || !fs::is_directory(dir)) {
        std::fprintf(stderr, "stc: error: --actual %s: cannot create the directory '%s'%s\n", args.actual.c_str(), dir.string().c_str(),
                     ec ? (": " + ec.message()).c_str() : "");
        return 2;
      }
      actualDirs[i] = dir.string();
    }
  }
  unsigned jobs = args.jobs ? args.jobs : std::max(1u, static_cast<unsigned>(sysconf(_SC_NPROCESSORS_ONLN)));
  std::vector<Child> kids(dirs.size());
  unsigned passed = 0, failed = 0;
  size_t started = 0, printed = 0, running = 0;
  std::fflush(stdout);
  std::fflush(stderr);
  while (printed < dirs.size()) {
    while (running < jobs && started < dirs.size()) {
      Child& k = kids[started];
      const char* tdir = std::getenv("TMPDIR");
      std::string t = std::string(tdir && *tdir ? tdir : "/tmp") + "/stc-test-out-XXXXXX";
      std::vector<char> buf(t.begin(), t.end());
      buf.push_back(0);
      int fd = mkstemp(buf.data());
      if (fd < 0) {
        std::fprintf(stderr, "stc: error: cannot create a temporary file: %s\n", std::strerror(errno));
        return 1;
      }
      k.outFile = buf.data();
      std::vector<std::string> argvS = {"stc", "test", "--one", dirs[started]};
      if (args.update) argvS.push_back("--update");
      if (args.force) argvS.push_back("--force");
      for (const std::string& n : args.scenarios) argvS.insert(argvS.end(), {"--scenario", n});
      if (!actualDirs[started].empty()) argvS.insert(argvS.end(), {"--actual", actualDirs[started]});
      pid_t pid = fork();
      if (pid == 0) {
        dup2(fd, STDOUT_FILENO);
        dup2(fd, STDERR_FILENO);
        close(fd);
        std::vector<char*> argv;
        for (std::string& s : argvS) argv.push_back(s.data());
        argv.push_back(nullptr);
        execv("/proc/self/exe", argv.data());
        std::fprintf(stderr, "stc: error: cannot start /proc/self/exe: %s\n", std::strerror(errno));
        _exit(127);
      }
      close(fd);
      if (pid < 0) {
        std::fprintf(stderr, "stc: error: fork: %s\n", std::strerror(errno));
        return 1;
      }
      k.pid = pid;
      ++started;
      ++running;
    }
    // Print every finished report that is next in argument order.
    while (printed < started && kids[printed].done) {
      Child& k = kids[printed];
      std::string text;
      readFile(k.outFile, text);
      unlink(k.outFile.c_str());
      unsigned p = 0, f = 0;
      for (const std::string& line : splitLines(text)) {
        if (line.rfind("PASS ", 0) == 0) ++p;
        else if (line.rfind("FAIL ", 0) == 0) ++f;
      }
      bool crashed = !WIFEXITED(k.status) || (WEXITSTATUS(k.status) != 0 && WEXITSTATUS(k.status) != 1) ||
                     (WEXITSTATUS(k.status) == 1 && f == 0);
      if (crashed) {
        text += WIFSIGNALED(k.status) ? fmt::format("FAIL {}: the test process died (signal {})\n", label(dirs[printed]), WTERMSIG(k.status))
                                      : fmt::format("FAIL {}: the test process exited with status {}\n", label(dirs[printed]),
                                                    WIFEXITED(k.status) ? WEXITSTATUS(k.status) : -1);
        ++f;
      }
      std::fwrite(text.data(), 1, text.size(), stdout);
      std::fflush(stdout);
      passed += p;
      failed += f;
      ++printed;
    }
    if (printed == dirs.size()) break;
    if (running == 0) continue;
    int status = 0;
    pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      std::fprintf(stderr, "stc: error: waitpid: %s\n", std::strerror(errno));
      return 1;
    }
    for (Child& k : kids)
      if (k.pid == pid && !k.done) {
        k.done = true;
        k.status = status;
        --running;
      }
  }
  std::printf("%u passed, %u failed\n", passed, failed);
  return failed ? 1 : 0;
}

}  // namespace stc::tools
