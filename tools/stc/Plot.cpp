#include "tools/stc/Plot.h"
#include "tools/stc/Ticks.h"

#include "config/ConfigSchema.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <tuple>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/cnc/Geometry.h"
#include "vm/Time.h"

#include <unistd.h>

namespace stc::plot {
namespace {

// ------------------------------------------------------------------ CSV

// Splits one CSV record (RFC 4180 quoting).  False on an unterminated quote.
bool splitCsv(const std::string& line, std::vector<std::string>& fields) {
  fields.clear();
  std::string cur;
  size_t i = 0;
  for (;;) {
    cur.clear();
    if (i < line.size() && line[i] == '"') {
      ++i;
      for (;;) {
        if (i >= line.size()) return false;
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cur += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        cur += line[i++];
      }
      while (i < line.size() && line[i] != ',') cur += line[i++];
    } else {
      while (i < line.size() && line[i] != ',') cur += line[i++];
    }
    fields.push_back(cur);
    if (i >= line.size()) return true;
    ++i;   // the comma
  }
}

std::string lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

bool parseDouble(const std::string& s, double& out) {
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

// ------------------------------------------------------------------ values

enum class Kind { Bool, Number, State };

struct Column {
  std::string name;
  Kind kind = Kind::Number;
  bool isTime = false;               // Number: TIME/LTIME values (seconds)
  bool isInteger = false;            // Number: every value an integer literal (ticks at integers only)
  std::vector<double> num;           // Bool (0/1), Number; NaN = no value
  std::vector<int> state;            // State: index into labels
  std::vector<std::string> labels;   // State: distinct values, first seen first
  std::string labelPrefix;           // State: `Type#` common to every value (dropped in labels)
  std::string unit;                  // the axis unit from the trace's #units line ("" none)
  std::string role;                  // --compare: "expected" or "actual" ("" otherwise)
  bool dashed = false;               // --compare: the expected line
  int color = 0;
};

// An IEC literal as a number: integers, REAL (1.5, 1.0E+19, NaN, Inf), 16#FF, T#1s.
bool literalNumber(const std::string& s, double& v, bool& isTime) {
  isTime = false;
  if (s == "NaN") { v = std::numeric_limits<double>::quiet_NaN(); return true; }
  if (s == "Inf") { v = std::numeric_limits<double>::infinity(); return true; }
  if (s == "-Inf") { v = -std::numeric_limits<double>::infinity(); return true; }
  size_t hash = s.find('#');
  if (hash == std::string::npos) {
    if (s.empty() || !(std::isdigit(static_cast<unsigned char>(s[0])) || s[0] == '-' || s[0] == '+' || s[0] == '.')) return false;
    return parseDouble(s, v);
  }
  std::string pre = lower(s.substr(0, hash));
  if (pre == "t" || pre == "time" || pre == "ltime") {
    vm::Time ns = 0;
    if (!vm::parseIecDuration(s, ns)) return false;
    v = static_cast<double>(ns) / 1e9;
    isTime = true;
    return true;
  }
  int base = pre == "16" ? 16 : pre == "8" ? 8 : pre == "2" ? 2 : 0;
  if (!base) return false;
  uint64_t x = 0;
  bool any = false;
  for (size_t i = hash + 1; i < s.size(); ++i) {
    char c = s[i];
    if (c == '_') continue;
    int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : 99;
    if (d >= base) return false;
    x = x * static_cast<uint64_t>(base) + static_cast<uint64_t>(d);
    any = true;
  }
  v = static_cast<double>(x);
  return any;
}

// An integer as a trace writes it: 42, -7, 16#FF (REALs always have a '.' or an exponent).
bool integerLiteral(const std::string& s) {
  if (s.empty()) return true;   // no value
  size_t hash = s.find('#');
  if (hash != std::string::npos) {
    std::string pre = s.substr(0, hash);
    return pre == "16" || pre == "8" || pre == "2";
  }
  size_t i = s[0] == '-' || s[0] == '+' ? 1 : 0;
  return i < s.size() && s.find_first_not_of("0123456789", i) == std::string::npos;
}

Column classify(const std::string& name, const std::vector<std::string>& raw) {
  Column c;
  c.name = name;
  bool allBool = true, allNum = true, allTime = true;
  for (const std::string& s : raw) {
    if (s.empty()) continue;
    if (s != "TRUE" && s != "FALSE") allBool = false;
    double v;
    bool t;
    if (allNum && !literalNumber(s, v, t)) allNum = false;
    if (allNum && !t) allTime = false;
    if (!allBool && !allNum) break;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (allBool && !raw.empty()) {
    c.kind = Kind::Bool;
    c.num.reserve(raw.size());
    for (const std::string& s : raw) c.num.push_back(s.empty() ? nan : s == "TRUE" ? 1.0 : 0.0);
    return c;
  }
  if (allNum) {
    c.kind = Kind::Number;
    c.isTime = allTime && !raw.empty();
    c.isInteger = !c.isTime && std::any_of(raw.begin(), raw.end(), [](const std::string& s) { return !s.empty(); }) &&
                  std::all_of(raw.begin(), raw.end(), integerLiteral);
    c.num.reserve(raw.size());
    for (const std::string& s : raw) {
      double v;
      bool t;
      c.num.push_back(!s.empty() && literalNumber(s, v, t) ? v : nan);
    }
    return c;
  }
  c.kind = Kind::State;
  std::map<std::string, int> ids;
  c.state.reserve(raw.size());
  for (const std::string& s : raw) {
    auto [it, fresh] = ids.emplace(s, static_cast<int>(c.labels.size()));
    if (fresh) c.labels.push_back(s);
    c.state.push_back(it->second);
  }
  // Enums print as `Type#Value`: the labels show the values.
  size_t hash = c.labels.empty() ? std::string::npos : c.labels[0].find('#');
  if (hash != std::string::npos && c.labels[0][0] != '\'' && c.labels[0][0] != '"') {
    std::string prefix = c.labels[0].substr(0, hash + 1);
    bool common = true;
    for (const std::string& l : c.labels)
      if (l.compare(0, prefix.size(), prefix) != 0) common = false;
    if (common) c.labelPrefix = prefix;
  }
  return c;
}

// The name shown for a column: `X (expected)` when compared.
std::string shownName(const Column& c) { return c.role.empty() ? c.name : c.name + " (" + c.role + ")"; }

// Column i of the trace, classified, with its unit.
Column columnOf(const TraceTable& trace, size_t i) {
  Column c = classify(trace.names[i], trace.columns[i]);
  if (i < trace.units.size()) c.unit = trace.units[i];
  return c;
}

// What a numeric variable measures, from its name: the panel it goes into.
struct KindInfo {
  const char* key;
  const char* label;
  const char* unit;
};
// The unit of the kinds 0..3 is the axis unit (project.toml [[axis]] unit,
// carried by the trace's #units line; "u" when none) per second^n.
const KindInfo kKinds[] = {
    {"position", "position", ""},       {"velocity", "velocity", "/s"},
    {"acceleration", "acceleration", "/s²"}, {"jerk", "jerk", "/s³"},
    {"torque", "torque", ""},           {"current", "current", ""},
    {"time", "time", "s"},              {"other", "", ""},
};

bool endsWith(const std::string& s, const char* suffix) {
  size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

// The unit of a value of kind `kind` in column c: "mm/s" for a velocity of an axis in mm.
std::string unitOf(int kind, const Column& c) {
  if (kind > 3) return kKinds[kind].unit;
  return (c.unit.empty() ? "u" : c.unit) + kKinds[kind].unit;
}

int kindOf(const Column& c) {
  std::string n = lower(c.name);
  size_t dot = n.find_last_of('.');
  if (dot != std::string::npos) n = n.substr(dot + 1);
  if (c.isTime) return 6;
  for (const char* s : {"position", "pos"}) if (endsWith(n, s)) return 0;
  for (const char* s : {"velocity", "vel", "speed"}) if (endsWith(n, s)) return 1;
  for (const char* s : {"acceleration", "acc", "deceleration", "dec"}) if (endsWith(n, s)) return 2;
  if (endsWith(n, "jerk")) return 3;
  if (endsWith(n, "torque")) return 4;
  if (endsWith(n, "current")) return 5;
  return 7;
}

// ------------------------------------------------------------------ numbers and ticks

std::string xmlEscape(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (c < 0x20) out += ' ';
        else out += static_cast<char>(c);
    }
  }
  return out;
}

// Shortens `s` to about `maxWidth` pixels, keeping the informative tail.
std::string fitText(const std::string& s, double maxWidth) {
  if (textWidth(s) <= maxWidth) return s;
  size_t keep = static_cast<size_t>(std::max(1.0, maxWidth / 6.6 - 1));
  if (keep >= s.size()) return s;
  return "…" + s.substr(s.size() - keep);
}

std::string num(double v) {
  if (std::fabs(v - std::round(v)) < 0.05) return fmt::format("{}", static_cast<long long>(std::llround(v)));
  return fmt::format("{:.1f}", v);
}

const char* kLineColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                             "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};
const char* kBandColors[] = {"#cfe2f3", "#fce5cd", "#d9ead3", "#f4cccc", "#d9d2e9", "#fff2cc",
                             "#d0e0e3", "#ead1dc", "#e6e6e6", "#c9daf8", "#f9cb9c", "#b6d7a8"};

// ------------------------------------------------------------------ the drawing

class Svg {
public:
  std::string out;
  template <typename... A>
  void add(fmt::format_string<A...> f, A&&... a) {
    out += fmt::format(f, std::forward<A>(a)...);
    out += '\n';
  }
};

// ------------------------------------------------------------------ pieces every plot uses

// The rows and seconds --from/--to select: rows [r0, r1) lie in [t0, t1].
struct Window {
  double t0 = 0, t1 = 1;
  size_t r0 = 0, r1 = 0;
};

Window timeWindow(const TraceTable& trace, const PlotOptions& options) {
  Window w;
  double tFirst = trace.time.empty() ? 0 : trace.time.front(), tLast = trace.time.empty() ? 1 : trace.time.back();
  w.t0 = options.from ? *options.from : tFirst;
  w.t1 = options.to ? *options.to : tLast;
  if (!(w.t1 > w.t0)) w.t1 = w.t0 + (w.t0 == 0 ? 1 : std::fabs(w.t0) * 0.01);
  w.r0 = static_cast<size_t>(std::lower_bound(trace.time.begin(), trace.time.end(), w.t0 - 1e-12) - trace.time.begin());
  w.r1 = static_cast<size_t>(std::upper_bound(trace.time.begin(), trace.time.end(), w.t1 + 1e-12) - trace.time.begin());
  return w;
}

// A data range [lo, hi] (lo > hi: no data) with a 5 % margin either side; a
// flat range is widened around its value.
void padRange(double& lo, double& hi) {
  if (!(lo <= hi)) lo = 0, hi = 1;
  lo = std::clamp(lo, -1e300, 1e300), hi = std::clamp(hi, -1e300, 1e300);   // spans stay finite
  if (hi - lo <= std::max(std::fabs(hi), std::fabs(lo)) * 1e-12) {
    double d = lo == 0 ? 1 : std::fabs(lo) * 0.1;
    lo -= d, hi += d;
  } else {
    double pad = (hi - lo) * 0.05;
    lo -= pad, hi += pad;
  }
}

// The document, its background, the title and the line under it.
// Times as short as tells them apart at a millionth of the window (4.2, not 4.199999999).
std::string windowText(const Window& w) {
  const double tol = std::max(5e-10, (w.t1 - w.t0) * 1e-6);
  return fmt::format("{} samples, {} s to {} s", w.r1 - w.r0, formatSeconds(w.t0, tol), formatSeconds(w.t1, tol));
}

void openSvg(Svg& s, double width, double height, double left, const std::string& title, const std::string& subtitle) {
  s.add(R"(<?xml version="1.0" encoding="UTF-8"?>)");
  s.add(R"(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" font-family="DejaVu Sans, Arial, Helvetica, sans-serif" font-size="11">)",
        num(width), num(height), num(width), num(height));
  s.add(R"(<rect width="100%" height="100%" fill="#ffffff"/>)");
  s.add(R"(<text class="title" x="{}" y="24" font-size="16" font-weight="bold">{}</text>)", num(left), xmlEscape(title));
  s.add(R"(<text class="subtitle" x="{}" y="40" fill="#666666">{}</text>)", num(left), xmlEscape(subtitle));
}

// A horizontal grid line from x0 to x1 at `y`, its tick and label left of x0.
void yTick(Svg& s, double x0, double x1, double y, const std::string& label) {
  s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#e3e3e3"/>)", num(x0), num(y), num(x1), num(y));
  s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#999999"/>)", num(x0 - 4), num(y), num(x0), num(y));
  s.add(R"(<text class="ytick" x="{}" y="{}" text-anchor="end">{}</text>)", num(x0 - 6), num(y + 4), label);
}

// A vertical grid line from y0 to y1 at `x`, its tick and label below y1.
void xTick(Svg& s, double x, double y0, double y1, const char* gridColor, const std::string& label) {
  s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}"/>)", num(x), num(y0), num(x), num(y1), gridColor);
  s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#999999"/>)", num(x), num(y1), num(x), num(y1 + 4));
  s.add(R"(<text class="xtick" x="{}" y="{}" text-anchor="middle">{}</text>)", num(x), num(y1 + 16), label);
}

// One legend line: a short stroke in `color` (dashed: `dash` is its
// stroke-dasharray) and the text (baseline at y).
void legendEntry(Svg& s, double x, double y, const char* color, const std::string& text, double maxWidth, const char* dash = nullptr) {
  if (dash)
    s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="2" stroke-dasharray="{}"/>)", num(x), num(y - 4), num(x + 18),
          num(y - 4), color, dash);
  else
    s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="3"/>)", num(x), num(y - 4), num(x + 16), num(y - 4), color);
  s.add(R"(<text class="legend" x="{}" y="{}">{}</text>)", num(x + 22), num(y), xmlEscape(fitText(text, maxWidth - 22)));
}

struct Layout {
  double width = 1100;
  double left = 76;
  double legend = 180;   // right-hand column for legends and lane names
  double plotW = 0;
  double t0 = 0, t1 = 1;
  int pixels = 0;        // pixel columns of the plot area
  size_t r0 = 0, r1 = 0; // visible rows [r0, r1)
  double x(double t) const { return left + (t - t0) / (t1 - t0) * plotW; }
  int column(double t) const {
    int c = static_cast<int>(std::floor((t - t0) / (t1 - t0) * pixels));
    return std::clamp(c, 0, pixels - 1);
  }
};

// Per pixel column: which values occur (Bool: bit 0 = low, bit 1 = high;
// State: the value or -2 for several).  -1: no sample.
std::vector<int> columnStates(const Layout& L, const std::vector<double>& time, const std::function<int(size_t)>& valueAt) {
  std::vector<int> cols(static_cast<size_t>(L.pixels), -1);
  // A sample holds until the next one: the one before the window counts too.
  for (size_t r = L.r0 > 0 ? L.r0 - 1 : 0; r < L.r1; ++r) {
    int v = valueAt(r);
    if (v == -1) continue;
    int c0 = L.column(time[r]);
    int c1 = r + 1 < time.size() ? std::max(c0, L.column(time[r + 1]) - 1) : c0;
    for (int c = c0; c <= c1; ++c) {
      int& slot = cols[static_cast<size_t>(c)];
      if (slot == -1) slot = v;
      else if (slot != v) slot = -2;
    }
  }
  return cols;
}

struct Panel {
  int kind;
  std::vector<size_t> series;   // indices into columns
  std::string unit;             // of every series ("" none)
  std::string title;            // empty: from the kind
};

void drawNumeric(Svg& s, const Layout& L, const Panel& p, const std::vector<Column>& cols, const std::vector<double>& t, double top,
                 double height, int index, const std::vector<double>& timeTicks) {
  const KindInfo& k = kKinds[p.kind];
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t ci : p.series)
    for (size_t r = L.r0; r < L.r1; ++r) {
      double v = cols[ci].num[r];
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
  TickRequest tr;
  tr.pixels = height;
  tr.minGap = 22;
  tr.integer = std::all_of(p.series.begin(), p.series.end(), [&](size_t ci) { return cols[ci].isInteger; });
  const TickAxis axis = niceAxis(lo, hi, tr);
  lo = axis.lo, hi = axis.hi;
  auto y = [&](double v) { return top + height - (v - lo) / (hi - lo) * height; };
  std::string title = !p.title.empty() ? p.title : p.kind != 7 ? k.label : p.series.size() == 1 ? cols[p.series[0]].name : "values";
  if (!p.unit.empty()) title += fmt::format(" [{}]", p.unit);
  s.add(R"(<g class="panel" data-kind="{}">)", p.kind == 7 ? "other" : k.key);
  s.add(R"(<text class="panel-title" x="{}" y="{}" font-weight="bold">{}</text>)", num(L.left), num(top - 6), xmlEscape(title));
  s.add(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="#ffffff" stroke="#999999"/>)", num(L.left), num(top), num(L.plotW), num(height));
  for (size_t i = 0; i < axis.ticks.size(); ++i) yTick(s, L.left, L.left + L.plotW, y(axis.ticks[i]), axis.labels[i]);
  for (double tt : timeTicks)
    s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#e3e3e3"/>)", num(L.x(tt)), num(top), num(L.x(tt)), num(top + height));
  s.add(R"(<clipPath id="clip{}"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath>)", index, num(L.left), num(top - 1),
        num(L.plotW), num(height + 2));
  double ly = top + 12;
  for (size_t ci : p.series) {
    const Column& c = cols[ci];
    const char* color = kLineColors[c.color % 10];
    // Min/max per pixel column, in time order, so steps and spikes survive.
    std::vector<std::string> lines;
    std::string pts;
    int curCol = -1;
    size_t firstR = 0, minR = 0, maxR = 0, lastR = 0;
    auto flushCol = [&]() {
      if (curCol < 0) return;
      size_t order[4] = {firstR, std::min(minR, maxR), std::max(minR, maxR), lastR};
      size_t prev = static_cast<size_t>(-1);
      for (size_t r : order) {
        if (r == prev) continue;
        prev = r;
        pts += num(L.x(t[r])) + ',' + num(y(c.num[r])) + ' ';
      }
      curCol = -1;
    };
    auto endLine = [&]() {
      flushCol();
      if (!pts.empty()) {
        pts.pop_back();
        lines.push_back(std::move(pts));
      }
      pts.clear();
    };
    // One sample either side of the window, so lines run on to the (clipped) edges.
    for (size_t r = L.r0 > 0 ? L.r0 - 1 : 0, end = std::min(L.r1 + 1, t.size()); r < end; ++r) {
      double v = c.num[r];
      if (!std::isfinite(v)) {
        endLine();
        continue;
      }
      int col = L.column(t[r]);
      if (col != curCol) {
        flushCol();
        curCol = col;
        firstR = minR = maxR = lastR = r;
      } else {
        if (v < c.num[minR]) minR = r;
        if (v > c.num[maxR]) maxR = r;
        lastR = r;
      }
    }
    endLine();
    const char* dash = c.dashed ? "5 3" : nullptr;
    std::string role = c.role.empty() ? "" : fmt::format(R"( data-trace="{}")", c.role);
    s.add(R"s(<g class="series" data-var="{}"{} clip-path="url(#clip{})">)s", xmlEscape(c.name), role, index);
    for (const std::string& l : lines)
      s.add(R"(<polyline fill="none" stroke="{}" stroke-width="1.5" stroke-linejoin="round"{} points="{}"/>)", color,
            dash ? fmt::format(R"( stroke-dasharray="{}")", dash) : "", l);
    s.add("</g>");
    legendEntry(s, L.left + L.plotW + 12, ly, color, shownName(c), L.legend - 12, dash);
    ly += 16;
  }
  s.add("</g>");
}

void drawBool(Svg& s, const Layout& L, const Column& c, const std::vector<double>& time, double top, double height) {
  const char* color = kLineColors[c.color % 10];
  std::vector<int> cols = columnStates(L, time, [&](size_t r) {
    double v = c.num[r];
    return std::isnan(v) ? -1 : v != 0 ? 1 : 0;
  });
  double hiY = top + 3, loY = top + height - 3;
  s.add(R"(<g class="lane" data-var="{}"{}>)", xmlEscape(c.name), c.role.empty() ? "" : fmt::format(R"( data-trace="{}")", c.role));
  s.add(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#dddddd"/>)", num(L.left), num(top), num(L.plotW), num(height));
  std::string wave, fill, mixed;
  double px = L.plotW / L.pixels;
  int prev = -1;
  for (int i = 0; i < L.pixels;) {
    int v = cols[static_cast<size_t>(i)];
    int j = i;
    while (j < L.pixels && cols[static_cast<size_t>(j)] == v) ++j;
    double x0 = L.left + i * px, x1 = L.left + j * px;
    if (v == 0 || v == 1) {
      double yy = v ? hiY : loY;
      if (prev == 0 || prev == 1) wave += fmt::format("V{}H{}", num(yy), num(x1));
      else wave += fmt::format("M{},{}H{}", num(x0), num(yy), num(x1));
      if (v) fill += fmt::format("M{},{}H{}V{}H{}Z", num(x0), num(hiY), num(x1), num(loY), num(x0));
    } else if (v == -2) {
      mixed += fmt::format("M{},{}H{}V{}H{}Z", num(x0), num(hiY), num(x1), num(loY), num(x0));
    }
    prev = v;
    i = j;
  }
  if (!fill.empty()) s.add(R"(<path d="{}" fill="{}" fill-opacity="0.18"/>)", fill, color);
  if (!mixed.empty()) s.add(R"(<path d="{}" fill="{}" fill-opacity="0.6"/>)", mixed, color);
  if (!wave.empty()) s.add(R"(<path class="wave" d="{}" fill="none" stroke="{}" stroke-width="1.5"/>)", wave, color);
  s.add(R"(<text class="lane-name" x="{}" y="{}" fill="{}">{}</text>)", num(L.left + L.plotW + 12), num(top + height / 2 + 4), color,
        xmlEscape(fitText(shownName(c), L.legend - 14)));
  s.add("</g>");
}

void drawState(Svg& s, const Layout& L, const Column& c, const std::vector<double>& time, double top, double height) {
  std::vector<int> cols = columnStates(L, time, [&](size_t r) { return c.state[r]; });
  s.add(R"(<g class="band" data-var="{}"{}>)", xmlEscape(c.name), c.role.empty() ? "" : fmt::format(R"( data-trace="{}")", c.role));
  s.add(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="#fafafa" stroke="#dddddd"/>)", num(L.left), num(top), num(L.plotW), num(height));
  double px = L.plotW / L.pixels;
  for (int i = 0; i < L.pixels;) {
    int v = cols[static_cast<size_t>(i)];
    int j = i;
    while (j < L.pixels && cols[static_cast<size_t>(j)] == v) ++j;
    double x0 = L.left + i * px, w = (j - i) * px;
    if (v >= 0) {
      std::string full = c.labels[static_cast<size_t>(v)];
      std::string label = full.substr(c.labelPrefix.size());
      s.add(R"(<rect class="state" x="{}" y="{}" width="{}" height="{}" fill="{}" stroke="#ffffff" stroke-width="0.5"><title>{}</title></rect>)",
            num(x0), num(top + 1), num(w), num(height - 2), kBandColors[static_cast<size_t>(v) % 12], xmlEscape(full));
      if (textWidth(label, 6.2) + 8 <= w)
        s.add(R"(<text class="state-label" x="{}" y="{}" font-size="10">{}</text>)", num(x0 + 4), num(top + height / 2 + 4), xmlEscape(label));
    } else if (v == -2) {
      s.add(R"(<rect class="state-mixed" x="{}" y="{}" width="{}" height="{}" fill="#888888"><title>several values</title></rect>)", num(x0),
            num(top + 1), num(w), num(height - 2));
    }
    i = j;
  }
  s.add(R"(<text class="lane-name" x="{}" y="{}">{}</text>)", num(L.left + L.plotW + 12), num(top + height / 2 + 4),
        xmlEscape(fitText(shownName(c), L.legend - 14)));
  s.add("</g>");
}

// The shared time axis: grid through every panel and lane from gridTop to
// gridBottom, labels below.  A trace of 10 s at 1 ms ends at 9.999 s: with
// `extend` the axis runs on to the next round tick when that is close (2 %
// of the range).  The tick times.
std::vector<double> drawTimeAxis(Svg& s, Layout& L, double gridTop, double gridBottom, bool extend) {
  TickRequest tr;
  tr.pixels = L.plotW;
  tr.minGap = 14;
  tr.horizontal = true;
  tr.pad = false;
  double xstep = chooseStep(L.t0, L.t1, tr);
  if (extend) {
    double end = std::ceil(L.t1 / xstep - 1e-9) * xstep;
    if (end > L.t1 && end - L.t1 <= 0.02 * (L.t1 - L.t0)) {
      L.t1 = end;
      xstep = chooseStep(L.t0, L.t1, tr);   // one more tick may be one too many
    }
  }
  s.add(R"(<g class="time-axis">)");
  std::vector<double> ticks = tickValues(L.t0, L.t1, xstep);
  const std::vector<std::string> labels = tickLabels(ticks, xstep);
  for (size_t i = 0; i < ticks.size(); ++i) xTick(s, L.x(ticks[i]), gridTop, gridBottom, "#eeeeee", labels[i]);
  s.add(R"(<text class="xlabel" x="{}" y="{}" text-anchor="middle">time [s]</text>)", num(L.left + L.plotW / 2), num(gridBottom + 34));
  s.add("</g>");
  return ticks;
}

// ------------------------------------------------------------------ legends of lanes and bands

const double kLegendRowH = 14;

// A state band's legend: each value with its colour, in rows under the band.
struct StateLegend {
  std::vector<std::vector<size_t>> rows;   // label indices per row
  size_t omitted = 0;                      // values beyond the last row
};

std::string stateName(const Column& c, size_t v) { return c.labels[v].substr(c.labelPrefix.size()); }

double stateEntryWidth(const Column& c, size_t v) { return 14 + textWidth(stateName(c, v), 6.2) + 12; }

StateLegend stateLegend(const Column& c, double width) {
  const size_t kMaxRows = 3;
  StateLegend g;
  // The enum's type first (`E_State:`), then the values, first seen first
  // (an empty one is no value: --compare past the end of a trace).
  double x = c.labelPrefix.empty() ? 0 : textWidth(c.labelPrefix, 6.2) + 8;
  g.rows.emplace_back();
  for (size_t v = 0; v < c.labels.size(); ++v) {
    if (c.labels[v].empty()) continue;
    double w = stateEntryWidth(c, v);
    if (x + w > width && !g.rows.back().empty()) {
      if (g.rows.size() == kMaxRows) {
        g.omitted = c.labels.size() - v;
        break;
      }
      g.rows.emplace_back();
      x = 0;
    }
    g.rows.back().push_back(v);
    x += w;
  }
  // Room for "+N more" at the end of the last row.
  while (g.omitted && !g.rows.back().empty()) {
    double used = 0;
    for (size_t v : g.rows.back()) used += stateEntryWidth(c, v);
    if (used + 70 <= width) break;
    g.rows.back().pop_back();
    ++g.omitted;
  }
  return g;
}

void drawStateLegend(Svg& s, double left, double top, const Column& c, const StateLegend& g) {
  s.add(R"(<g class="state-legend" data-var="{}">)", xmlEscape(c.name));
  double y = top + 10;
  for (size_t r = 0; r < g.rows.size(); ++r) {
    double x = left;
    if (r == 0 && !c.labelPrefix.empty()) {
      std::string type = c.labelPrefix.substr(0, c.labelPrefix.size() - 1) + ":";
      s.add(R"(<text class="state-legend-type" x="{}" y="{}" font-size="10" fill="#666666">{}</text>)", num(x), num(y), xmlEscape(type));
      x += textWidth(c.labelPrefix, 6.2) + 8;
    }
    for (size_t v : g.rows[r]) {
      s.add(R"(<rect class="swatch" x="{}" y="{}" width="10" height="10" fill="{}" stroke="#999999" stroke-width="0.5"/>)", num(x), num(y - 9),
            kBandColors[v % 12]);
      s.add(R"(<text class="state-legend-entry" x="{}" y="{}" font-size="10">{}</text>)", num(x + 14), num(y), xmlEscape(stateName(c, v)));
      x += stateEntryWidth(c, v);
    }
    if (r + 1 == g.rows.size() && g.omitted)
      s.add(R"(<text class="state-legend-more" x="{}" y="{}" font-size="10" fill="#666666">+{} more</text>)", num(x), num(y), g.omitted);
    y += kLegendRowH;
  }
  s.add("</g>");
}

// What the digital lanes show: shaded high = TRUE, low line = FALSE.
void drawBoolLegend(Svg& s, double left, double top) {
  const double y = top + 10;
  s.add(R"(<g class="bool-legend">)");
  s.add(R"(<rect x="{}" y="{}" width="16" height="10" fill="#555555" fill-opacity="0.18"/>)", num(left), num(y - 9));
  s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#555555" stroke-width="1.5"/>)", num(left), num(y - 9), num(left + 16), num(y - 9));
  s.add(R"(<text class="bool-legend-entry" x="{}" y="{}" font-size="10">TRUE</text>)", num(left + 20), num(y));
  s.add(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#555555" stroke-width="1.5"/>)", num(left + 62), num(y), num(left + 78), num(y));
  s.add(R"(<text class="bool-legend-entry" x="{}" y="{}" font-size="10">FALSE</text>)", num(left + 82), num(y));
  s.add("</g>");
}

// The column named `name` (case-insensitive), or npos.
size_t findColumn(const TraceTable& trace, const std::string& name) {
  for (size_t i = 0; i < trace.names.size(); ++i)
    if (lower(trace.names[i]) == lower(name)) return i;
  return std::string::npos;
}

// The axis label of a path plot: the distinct names, and the unit when all share one.
std::string pathAxisLabel(const std::vector<const Column*>& cols) {
  std::vector<std::string> names;
  int kind = cols.empty() ? 7 : kindOf(*cols[0]);
  for (const Column* c : cols) {
    if (std::find(names.begin(), names.end(), c->name) == names.end()) names.push_back(c->name);
    if (kindOf(*c) != kind) kind = 7;
  }
  std::string label;
  for (const std::string& n : names) label += (label.empty() ? "" : ", ") + n;
  std::string unit = cols.empty() ? "" : unitOf(kind, *cols[0]);
  for (const Column* c : cols)
    if (unitOf(kind, *c) != unit) unit.clear();
  if (!unit.empty()) label += fmt::format(" [{}]", unit);
  return label;
}

// ------------------------------------------------------------------ G-code programs (--gcode)

// One motion element of a program as a polyline in the drawn plane.
struct ProgramMove {
  bool rapid = false;   // G0 (LinPos): dashed
  int line = 0;         // source line of the block
  cnc::MoveType type = cnc::MoveType::Lin;
  std::vector<std::pair<double, double>> pts;   // data coordinates (axis H, axis V)
};

struct Program {
  std::string file;    // as given
  std::string axes;    // "X,Y"
  std::vector<ProgramMove> moves;
  size_t feeds = 0, rapids = 0;
};

// The point of `e` at u, projected onto the plane of axes h (across) and v (up).
std::pair<double, double> project(const cnc::Element& e, double u, cnc::Axis h, cnc::Axis v) {
  cnc::Pos p = cnc::point(e, u);
  return {p[h], p[v]};
}

// Distance of q from the segment a-b.
double segmentDistance(std::pair<double, double> q, std::pair<double, double> a, std::pair<double, double> b) {
  double dx = b.first - a.first, dy = b.second - a.second, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? std::clamp(((q.first - a.first) * dx + (q.second - a.second) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(q.first - a.first - t * dx, q.second - a.second - t * dy);
}

// Appends the points of `e` over (u0, u1] so that no chord is further than
// `tol` from the curve (checked at the quarter points of each chord; the
// uniform start below keeps each piece far less than a half turn, where that
// check cannot miss a bulge).
void refine(const cnc::Element& e, cnc::Axis h, cnc::Axis v, double u0, std::pair<double, double> p0, double u1,
            std::pair<double, double> p1, double tol, int depth, std::vector<std::pair<double, double>>& out) {
  if (depth < 14) {
    for (double f : {0.5, 0.25, 0.75}) {
      if (segmentDistance(project(e, u0 + f * (u1 - u0), h, v), p0, p1) > tol) {
        double um = (u0 + u1) / 2;
        auto pm = project(e, um, h, v);
        refine(e, h, v, u0, p0, um, pm, tol, depth + 1, out);
        refine(e, h, v, um, pm, u1, p1, tol, depth + 1, out);
        return;
      }
    }
  }
  out.push_back(p1);
}

// The polyline of one element: lines (G0, G1; every axis is linear in u, so
// their projection is a line) by their end points, curves sampled to `tol`.
// tol <= 0: a coarse uniform sampling (for the extent).
std::vector<std::pair<double, double>> sampleElement(const cnc::Element& e, cnc::Axis h, cnc::Axis v, double tol) {
  std::vector<std::pair<double, double>> pts{project(e, 0, h, v)};
  if (e.type == cnc::MoveType::Lin || e.type == cnc::MoveType::LinPos) {
    pts.push_back(project(e, 1, h, v));
    return pts;
  }
  // At most 1/16 turn per starting piece (arcs and ellipses can turn many times).
  double turn = e.type == cnc::MoveType::Clw || e.type == cnc::MoveType::Cclw         ? std::fabs(e.arc.sweep)
                : e.type == cnc::MoveType::EllClw || e.type == cnc::MoveType::EllCclw ? std::fabs(e.ellipse.sweepPhi)
                                                                                       : 0.0;
  int n = std::clamp(static_cast<int>(std::ceil(turn / (std::numbers::pi / 8))), 16, 16 * 100);
  auto prev = pts.back();
  for (int i = 1; i <= n; ++i) {
    double u0 = static_cast<double>(i - 1) / n, u1 = static_cast<double>(i) / n;
    auto p1 = project(e, u1, h, v);
    if (tol > 0) refine(e, h, v, u0, prev, u1, p1, tol, 0, pts);
    else pts.push_back(p1);
    prev = p1;
  }
  return pts;
}

cnc::Axis axisOf(char letter) {
  for (int a = 0; a < cnc::kAxisCount; ++a)
    if (cnc::axisLetter(static_cast<cnc::Axis>(a)) == letter) return static_cast<cnc::Axis>(a);
  return cnc::AxX;
}

// The motion elements as polylines in the plane of options.gcodeH/V, curves
// within 0.05 % of the program's extent (the plot spans at least 110 % of it,
// so the chord error stays below 0.1 % of the plot).
void sampleProgram(const std::vector<cnc::Element>& elements, const PlotOptions& options, Program& prog) {
  cnc::Axis h = axisOf(options.gcodeH), v = axisOf(options.gcodeV);
  prog.axes = fmt::format("{},{}", options.gcodeH, options.gcodeV);
  double inf = std::numeric_limits<double>::infinity();
  double xlo = inf, xhi = -inf, ylo = inf, yhi = -inf;
  std::vector<const cnc::Element*> moves;
  for (const cnc::Element& e : elements) {
    if (!cnc::isMotion(e.type)) continue;   // G92 jumps, M, G4, G75: no path
    moves.push_back(&e);
    for (auto [x, y] : sampleElement(e, h, v, 0)) {
      xlo = std::min(xlo, x), xhi = std::max(xhi, x);
      ylo = std::min(ylo, y), yhi = std::max(yhi, y);
    }
  }
  double extent = moves.empty() ? 0 : std::max(xhi - xlo, yhi - ylo);
  // A program that stays on one point: any small tolerance will do.
  double tol = extent > 0 ? extent * 5e-4 : 1e-9;
  for (const cnc::Element* e : moves) {
    ProgramMove m;
    m.rapid = e->type == cnc::MoveType::LinPos;
    m.line = e->line;
    m.type = e->type;
    m.pts = sampleElement(*e, h, v, tol);
    ++(m.rapid ? prog.rapids : prog.feeds);
    prog.moves.push_back(std::move(m));
  }
}

// $name$ values from --gcode-var (names case-insensitive, as ST names).
class OptionVariables : public cnc::VariableAccess {
public:
  explicit OptionVariables(const std::vector<std::pair<std::string, double>>& vars) : vars_(vars) {}
  bool read(std::string_view name, double& value) override {
    for (const auto& [n, v] : vars_)
      if (lower(n) == lower(std::string(name))) {
        value = v;
        return true;
      }
    return false;
  }
  bool write(std::string_view, double) override { return false; }   // G36 O$x$: the plot has nowhere to keep it
  std::string suggest(std::string_view name) override {
    std::vector<std::string> names;
    for (const auto& nv : vars_) names.push_back(nv.first);
    return config::closest(std::string(name), names);
  }

private:
  const std::vector<std::pair<std::string, double>>& vars_;
};

// Decodes options.gcode into `prog`.  0 ok; 1 decode errors (rendered into
// `diagnostics`); 2 the file cannot be read (`error`).
int decodeProgram(const PlotOptions& options, Program& prog, std::string& error, std::string& diagnostics) {
  std::string why;
  if (!config::checkRegularFile(options.gcode, why)) {   // a FIFO would block
    error = fmt::format("--gcode: cannot open '{}': {}", options.gcode, why);
    return 2;
  }
  SourceManager sm;
  uint32_t file = sm.loadFile(options.gcode, why);
  if (!file) {
    error = fmt::format("--gcode: {}", why);
    return 2;
  }
  DiagnosticsEngine diags(sm);
  diags.opts.errorLimit = 0;
  OptionVariables vars(options.gcodeVars);
  std::vector<cnc::Element> elements = cnc::decodeAll(sm, file, diags, cnc::DecoderOptions{}, &vars);
  const bool color = isatty(STDERR_FILENO);
  bool variables = false;
  for (const Diagnostic& d : diags.diagnostics()) {
    diagnostics += renderText(sm, d, color);
    variables = variables || d.code == "gcode-variable";
  }
  if (diags.hasErrors()) {
    if (variables) diagnostics += "note: stc plot reads $name$ values from --gcode-var NAME=VALUE\n";
    error = fmt::format("--gcode: '{}' has errors; nothing drawn", options.gcode);
    return 1;
  }
  prog.file = options.gcode;
  sampleProgram(elements, options, prog);
  return 0;
}

// --xy: each pair's Y over its X in one square panel, the same scale on both
// axes.  A path is one polyline per run of finite samples, thinned to points at
// least half a pixel apart; its first and last samples in the window are marked
// (--rapid: runs where the flag is set are dashed).  `prog` (--gcode): the
// commanded path under them; without pairs the program alone.
std::string renderPathSvg(const TraceTable& trace, const PlotOptions& options, const Program* prog) {
  struct Path {
    Column x, y;
    const char* color;
  };
  std::vector<Path> paths;
  for (const auto& [xn, yn] : options.xy) {
    size_t xi = findColumn(trace, xn), yi = findColumn(trace, yn);
    if (xi == std::string::npos || yi == std::string::npos) continue;
    paths.push_back({columnOf(trace, xi), columnOf(trace, yi),
                     kLineColors[paths.size() % 10]});
  }
  // --rapid: the flag column (Bool or Number; NaN counts as not rapid).
  std::optional<Column> rapidCol;
  if (!options.rapid.empty()) {
    size_t ri = findColumn(trace, options.rapid);
    if (ri != std::string::npos) rapidCol = columnOf(trace, ri);
    if (rapidCol && rapidCol->kind == Kind::State) rapidCol.reset();
  }
  auto rapidAt = [&](size_t r) { return rapidCol && std::isfinite(rapidCol->num[r]) && rapidCol->num[r] != 0; };
  Window w = timeWindow(trace, options);
  auto finiteAt = [](const Path& p, size_t r) {
    return p.x.kind == Kind::Number && p.y.kind == Kind::Number && std::isfinite(p.x.num[r]) && std::isfinite(p.y.num[r]);
  };

  // The data's box (the trace's window and the whole program), padded, then
  // both ranges widened to the larger span.
  double inf = std::numeric_limits<double>::infinity();
  double xlo = inf, xhi = -inf, ylo = inf, yhi = -inf;
  for (const Path& p : paths)
    for (size_t r = w.r0; r < w.r1; ++r)
      if (finiteAt(p, r)) {
        xlo = std::min(xlo, p.x.num[r]), xhi = std::max(xhi, p.x.num[r]);
        ylo = std::min(ylo, p.y.num[r]), yhi = std::max(yhi, p.y.num[r]);
      }
  if (prog)
    for (const ProgramMove& m : prog->moves)
      for (auto [x, y] : m.pts) {
        xlo = std::min(xlo, x), xhi = std::max(xhi, x);
        ylo = std::min(ylo, y), yhi = std::max(yhi, y);
      }
  padRange(xlo, xhi);
  padRange(ylo, yhi);
  double span = std::max(xhi - xlo, yhi - ylo);
  auto widen = [span](double& lo, double& hi) {
    double mid = (lo + hi) / 2;
    lo = mid - span / 2, hi = mid + span / 2;
  };
  widen(xlo, xhi);
  widen(ylo, yhi);

  const double left = 84, top = 56, side = 560;
  double maxName = 0;
  std::vector<std::string> legends;
  // Beside a program the trace's paths are what the machine did.
  for (const Path& p : paths) legends.push_back((prog ? "actual: " : "") + p.x.name + ", " + p.y.name);
  for (const std::string& l : legends) maxName = std::max(maxName, textWidth(l));
  if (prog) maxName = std::max(maxName, textWidth("commanded (feed)"));
  double legend = std::clamp(maxName + 44, 150.0, 300.0);
  double width = left + side + 12 + legend + 8, height = top + side + 48;
  auto px = [&](double v) { return left + (v - xlo) / span * side; };
  auto py = [&](double v) { return top + side - (v - ylo) / span * side; };

  std::string subtitle;
  if (!paths.empty() || !prog) subtitle = windowText(w);
  if (prog) {
    std::string_view a = prog->axes;
    subtitle += fmt::format("{}program: {} moves ({} feed, {} rapid), {}/{} plane", subtitle.empty() ? "" : "; ",
                            prog->feeds + prog->rapids, prog->feeds, prog->rapids, a.substr(0, 1), a.substr(2, 1));
  }
  Svg s;
  openSvg(s, width, height, left, options.title, subtitle);
  s.add(R"(<g class="panel" data-kind="path">)");
  s.add(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="#ffffff" stroke="#999999"/>)", num(left), num(top), num(side), num(side));
  // One step on both axes keeps the grid square.
  TickRequest tr;
  tr.pixels = side;
  tr.minGap = 14;
  tr.horizontal = true;
  tr.pad = false;
  const double step = chooseStep(xlo, xhi, tr);
  const std::vector<double> xt = tickValues(xlo, xhi, step), yt = tickValues(ylo, yhi, step);
  const std::vector<std::string> xl = tickLabels(xt, step), yl = tickLabels(yt, step);
  for (size_t i = 0; i < xt.size(); ++i) xTick(s, px(xt[i]), top, top + side, "#e3e3e3", xl[i]);
  for (size_t i = 0; i < yt.size(); ++i) yTick(s, left, left + side, py(yt[i]), yl[i]);
  std::vector<const Column*> xs, ys;
  for (const Path& p : paths) xs.push_back(&p.x), ys.push_back(&p.y);
  std::string xlabel = pathAxisLabel(xs), ylabel = pathAxisLabel(ys);
  if (paths.empty() && prog) xlabel = prog->axes.substr(0, 1), ylabel = prog->axes.substr(2, 1);
  s.add(R"(<text class="xlabel" x="{}" y="{}" text-anchor="middle">{}</text>)", num(left + side / 2), num(top + side + 34),
        xmlEscape(fitText(xlabel, side)));
  s.add(R"s(<text class="ylabel" x="{0}" y="{1}" text-anchor="middle" transform="rotate(-90 {0} {1})">{2}</text>)s", num(16),
        num(top + side / 2), xmlEscape(fitText(ylabel, side)));
  s.add(R"(<clipPath id="clipxy"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath>)", num(left - 1), num(top - 1), num(side + 2),
        num(side + 2));

  double ly = top + 12, lx = left + side + 12;
  // The commanded path first, so the actual one is drawn over it: one <path>
  // per element (class feed|rapid, the block's line), points 0.1 px apart or more.
  const char* kFeedColor = "#555555";
  const char* kRapidColor = "#ff7f0e";
  const char* kDash = "6 4";
  if (prog) {
    s.add(R"s(<g class="program" data-file="{}" data-axes="{}" clip-path="url(#clipxy)">)s", xmlEscape(prog->file), prog->axes);
    for (const ProgramMove& m : prog->moves) {
      std::string d, last;
      for (auto [x, y] : m.pts) {
        std::string pt = num(px(x)) + ',' + num(py(y));
        if (pt == last) continue;
        d += (d.empty() ? "M" : " L") + pt;
        last = std::move(pt);
      }
      if (d.find('L') == std::string::npos) d += " L" + last;   // a move shorter than the resolution: a dot
      if (m.rapid)
        s.add(R"(<path class="rapid" data-line="{}" fill="none" stroke="{}" stroke-width="1.2" stroke-dasharray="{}" d="{}"/>)", m.line,
              kRapidColor, kDash, d);
      else
        s.add(R"(<path class="feed" data-line="{}" data-move="{}" fill="none" stroke="{}" stroke-width="1.2" stroke-linecap="round" stroke-linejoin="round" d="{}"/>)",
              m.line, cnc::toString(m.type), kFeedColor, d);
    }
    if (prog->moves.empty())
      s.add(R"(<text class="note" x="{}" y="{}" text-anchor="middle" fill="#666666">no moves in {}</text>)", num(left + side / 2),
            num(top + side / 2), xmlEscape(fitText(prog->file, side - 80)));
    s.add("</g>");
    legendEntry(s, lx, ly, kFeedColor, "commanded (feed)", legend - 12);
    ly += 16;
    legendEntry(s, lx, ly, kRapidColor, "rapid (G0)", legend - 12, kDash);
    ly += 16;
  }
  for (size_t i = 0; i < paths.size(); ++i) {
    const Path& p = paths[i];
    std::vector<std::pair<std::string, bool>> lines;   // points, drawn dashed (--rapid)
    std::string pts;
    double lastX = 0, lastY = 0;
    std::string pending;   // the latest point skipped by thinning: a run ends on it
    bool rapid = false;    // the run being collected is a G0 part
    std::optional<std::pair<double, double>> first, last;
    auto endLine = [&]() {
      if (!pending.empty()) pts += pending + ' ';
      pending.clear();
      if (!pts.empty()) {
        pts.pop_back();
        lines.emplace_back(std::move(pts), rapid);
      }
      pts.clear();
    };
    for (size_t r = w.r0; r < w.r1; ++r) {
      if (!finiteAt(p, r)) {
        endLine();
        continue;
      }
      double x = px(p.x.num[r]), y = py(p.y.num[r]);
      if (!first) first = {x, y};
      last = {x, y};
      std::string pt = num(x) + ',' + num(y);
      if (rapidAt(r) != rapid) {
        // The run ends here and the next one starts here: no gap between them.
        if (!pts.empty()) {
          pending.clear();
          pts += pt + ' ';
        }
        endLine();
        rapid = !rapid;
        pts += pt + ' ';
        lastX = x, lastY = y;
        continue;
      }
      if (!pts.empty() && std::fabs(x - lastX) < 0.5 && std::fabs(y - lastY) < 0.5) {
        pending = std::move(pt);
        continue;
      }
      pts += pt + ' ';
      pending.clear();
      lastX = x, lastY = y;
    }
    endLine();
    s.add(R"s(<g class="path" data-x="{}" data-y="{}" clip-path="url(#clipxy)">)s", xmlEscape(p.x.name), xmlEscape(p.y.name));
    for (const auto& [l, dashed] : lines) {
      if (dashed)
        s.add(R"(<polyline class="rapid" fill="none" stroke="{}" stroke-width="1.5" stroke-dasharray="{}" stroke-linejoin="round" points="{}"/>)",
              p.color, kDash, l);
      else
        s.add(R"(<polyline fill="none" stroke="{}" stroke-width="1.5" stroke-linejoin="round" points="{}"/>)", p.color, l);
    }
    if (first) {
      s.add(R"(<circle class="start" cx="{}" cy="{}" r="4" fill="#ffffff" stroke="{}" stroke-width="2"/>)", num(first->first),
            num(first->second), p.color);
      s.add(R"(<rect class="end" x="{}" y="{}" width="7" height="7" fill="{}"/>)", num(last->first - 3.5), num(last->second - 3.5), p.color);
    }
    s.add("</g>");
    legendEntry(s, lx, ly, p.color, legends[i], legend - 12);
    ly += 16;
  }
  if (rapidCol && !paths.empty()) {
    legendEntry(s, lx, ly, "#555555", "actual, G0 (" + rapidCol->name + ")", legend - 12, kDash);
    ly += 16;
  }
  if (!paths.empty()) {
    // What the markers mean.
    ly += 4;
    s.add(R"(<circle cx="{}" cy="{}" r="4" fill="#ffffff" stroke="#555555" stroke-width="2"/>)", num(lx + 8), num(ly - 4));
    s.add(R"(<text class="legend-marker" x="{}" y="{}">start</text>)", num(lx + 22), num(ly));
    ly += 16;
    s.add(R"(<rect x="{}" y="{}" width="7" height="7" fill="#555555"/>)", num(lx + 4.5), num(ly - 7.5));
    s.add(R"(<text class="legend-marker" x="{}" y="{}">end</text>)", num(lx + 22), num(ly));
  }
  s.add("</g>");
  s.add("</svg>");
  return std::move(s.out);
}

// ------------------------------------------------------------------ --compare

// Column `col` of `t` at the times of `grid`: a sample holds until the next
// one; before the first and after the last sample there is no value ("").
std::vector<std::string> resample(const TraceTable& t, size_t col, const std::vector<double>& grid) {
  std::vector<std::string> out(grid.size());
  if (col == std::string::npos || t.time.empty()) return out;
  size_t r = 0;
  for (size_t g = 0; g < grid.size(); ++g) {
    while (r + 1 < t.time.size() && t.time[r + 1] <= grid[g]) ++r;
    if (grid[g] >= t.time.front() && grid[g] <= t.time.back()) out[g] = t.columns[col][r];
  }
  return out;
}

// Whether an expected and an actual value differ: different text, unless
// both are numbers within the tolerance (|a - e| <= tol * max(1, |e|), as stc test).
bool valuesDiffer(const std::string& e, const std::string& a, double tol) {
  if (e == a) return false;
  double x, y;
  bool tx, ty;
  if (e.empty() || a.empty() || !literalNumber(e, x, tx) || !literalNumber(a, y, ty)) return true;
  if (std::isnan(x) || std::isnan(y)) return std::isnan(x) != std::isnan(y);
  if (std::isinf(x) || std::isinf(y)) return x != y;
  return !(std::fabs(y - x) <= tol * std::max(1.0, std::fabs(x)));
}

// One variable of a comparison: its expected and actual columns (either
// missing when only one trace has it) and the rows where they differ.
struct Compared {
  std::string name;
  std::optional<Column> expected, actual;
  std::vector<char> differs;   // per row of the merged time grid
  bool anyDiffers = false;     // in the window
};

// Per pixel column: whether a differing row covers it (a row lasts until the next one).
std::vector<char> diffColumns(const Layout& L, const std::vector<double>& time, const std::vector<char>& differs) {
  std::vector<char> out(static_cast<size_t>(L.pixels), 0);
  for (size_t r = L.r0 > 0 ? L.r0 - 1 : 0; r < L.r1; ++r) {
    if (!differs[r]) continue;
    int c0 = L.column(time[r]);
    int c1 = r + 1 < time.size() ? std::max(c0, L.column(time[r + 1]) - 1) : c0;
    if (time[r] > L.t1) continue;
    for (int c = c0; c <= c1; ++c) out[static_cast<size_t>(c)] = 1;
  }
  return out;
}

// Red shading over [top, top + height] where the pixel columns differ.
void drawDiffShading(Svg& s, const Layout& L, const std::vector<char>& cols, double top, double height, const std::string& var) {
  double px = L.plotW / L.pixels;
  for (int i = 0; i < L.pixels;) {
    if (!cols[static_cast<size_t>(i)]) {
      ++i;
      continue;
    }
    int j = i;
    while (j < L.pixels && cols[static_cast<size_t>(j)]) ++j;
    const double t0 = L.t0 + (L.t1 - L.t0) * i / L.pixels, t1 = L.t0 + (L.t1 - L.t0) * j / L.pixels;
    const double tol = std::max(5e-10, (L.t1 - L.t0) * 1e-6);
    s.add(R"(<rect class="diff" data-var="{}" data-from="{}" data-to="{}" x="{}" y="{}" width="{}" height="{}" fill="#d62728" fill-opacity="0.15" stroke="#d62728" stroke-opacity="0.6"/>)",
          xmlEscape(var), formatSeconds(t0, tol), formatSeconds(t1, tol), num(L.left + i * px), num(top), num((j - i) * px), num(height));
    i = j;
  }
}

std::string renderCompare(const TraceTable& exp, const TraceTable& act, const PlotOptions& options, double tol,
                          const std::string& expName, const std::string& actName) {
  // The merged time grid: every sample time of either trace.
  std::vector<double> grid;
  std::merge(exp.time.begin(), exp.time.end(), act.time.begin(), act.time.end(), std::back_inserter(grid));
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  // A trace sampled every D (a golden file) against one of every tick (stc run): the sampled
  // one's times are a subset of the other's, and between its samples its held value is not
  // the signal's.  Then the traces are compared only at the times both have.
  const size_t common = exp.time.size() + act.time.size() - grid.size();
  const bool subset = common == std::min(exp.time.size(), act.time.size()) && exp.time.size() != act.time.size();
  std::vector<char> inBoth(grid.size(), 1);
  if (subset) {
    const std::vector<double>& fewer = exp.time.size() < act.time.size() ? exp.time : act.time;
    for (size_t r = 0; r < grid.size(); ++r) inBoth[r] = std::binary_search(fewer.begin(), fewer.end(), grid[r]);
  }
  TraceTable merged;
  merged.time = grid;
  Window w = timeWindow(merged, options);

  // The variables: the expected trace's, then those only in the actual one (--vars: those, in order).
  std::vector<std::string> names;
  auto has = [&](const std::string& n) {
    return std::any_of(names.begin(), names.end(), [&](const std::string& x) { return lower(x) == lower(n); });
  };
  if (!options.vars.empty()) {
    for (const std::string& v : options.vars) {
      size_t i = findColumn(exp, v), j = findColumn(act, v);
      std::string n = i != std::string::npos ? exp.names[i] : j != std::string::npos ? act.names[j] : v;
      if (!has(n)) names.push_back(n);
    }
  } else {
    for (const std::string& n : exp.names)
      if (!has(n)) names.push_back(n);
    for (const std::string& n : act.names)
      if (!has(n)) names.push_back(n);
  }
  std::vector<Compared> vars;
  std::vector<std::string> onlyExpected, onlyActual;
  for (const std::string& n : names) {
    Compared v;
    v.name = n;
    size_t ei = findColumn(exp, n), ai = findColumn(act, n);
    std::vector<std::string> e = resample(exp, ei, grid), a = resample(act, ai, grid);
    // One classification for both, so that they share a kind and state colours.
    std::vector<std::string> both = e;
    both.insert(both.end(), a.begin(), a.end());
    Column c = classify(n, both);
    c.unit = ei != std::string::npos && ei < exp.units.size() && !exp.units[ei].empty() ? exp.units[ei]
             : ai != std::string::npos && ai < act.units.size()                          ? act.units[ai]
                                                                                          : "";
    auto half = [&](bool second, const char* role) {
      Column h = c;
      h.role = role;
      const size_t n0 = second ? grid.size() : 0;
      if (!h.num.empty()) h.num.assign(c.num.begin() + static_cast<long>(n0), c.num.begin() + static_cast<long>(n0 + grid.size()));
      if (!h.state.empty())
        h.state.assign(c.state.begin() + static_cast<long>(n0), c.state.begin() + static_cast<long>(n0 + grid.size()));
      return h;
    };
    if (ei != std::string::npos) v.expected = half(false, "expected");
    if (ai != std::string::npos) v.actual = half(true, "actual");
    if (v.expected) v.expected->dashed = true, v.expected->color = 0;
    if (v.actual) v.actual->color = 1;
    v.differs.resize(grid.size());
    for (size_t r = 0; r < grid.size(); ++r) {
      v.differs[r] = (ei == std::string::npos || ai == std::string::npos || !inBoth[r]) ? 0 : valuesDiffer(e[r], a[r], tol);
      if (v.differs[r] && r >= w.r0 && r < w.r1) v.anyDiffers = true;
    }
    if (ei == std::string::npos) onlyActual.push_back(n);
    if (ai == std::string::npos) onlyExpected.push_back(n);
    vars.push_back(std::move(v));
  }
  // A state column that was never sampled in either trace has no labels: no value anywhere.
  for (Compared& v : vars)
    for (std::optional<Column>* c : {&v.expected, &v.actual})
      if (*c && (*c)->kind == Kind::State)
        for (int& st : (*c)->state)
          if (st >= 0 && (*c)->labels[static_cast<size_t>(st)].empty()) st = -1;

  Layout L;
  double maxName = 0;
  for (const Compared& v : vars) maxName = std::max(maxName, textWidth(v.name + " (expected)"));
  L.legend = std::clamp(maxName + 44, 150.0, 300.0);
  L.plotW = L.width - L.left - L.legend - 8;
  L.pixels = static_cast<int>(L.plotW);
  L.t0 = w.t0, L.t1 = w.t1, L.r0 = w.r0, L.r1 = w.r1;

  // Blocks, top to bottom: a panel per number, two lanes per BOOL, two bands per state.
  const double panelH = 120, panelGap = 34, laneH = 22, laneGap = 4, bandH = 24;
  const bool notes = !onlyExpected.empty() || !onlyActual.empty();
  const double top0 = notes ? 88 : 72;
  struct Block {
    double top = 0, height = 0;   // of the data area (shaded where the values differ)
    double legendTop = 0;         // states: the legend under the bands
    StateLegend legend;
  };
  std::vector<Block> blocks;
  double y = top0;
  for (const Compared& v : vars) {
    const Column& c = v.expected ? *v.expected : *v.actual;
    const double n = (v.expected && v.actual) ? 2 : 1;
    Block b;
    if (c.kind == Kind::Number) {
      y += 14;   // the panel title
      b.top = y, b.height = panelH;
      y += panelH + panelGap - 14;
    } else if (c.kind == Kind::Bool) {
      b.top = y, b.height = n * (laneH + laneGap) - laneGap;
      y += b.height + laneGap + 12;
    } else {
      b.top = y, b.height = n * (bandH + laneGap) - laneGap;
      b.legend = stateLegend(c, L.plotW);
      b.legendTop = y + b.height + 2;
      y += b.height + 2 + kLegendRowH * static_cast<double>(b.legend.rows.size()) + laneGap + 12;
    }
    blocks.push_back(std::move(b));
  }
  const double bottom = vars.empty() ? top0 + 40 : y - 12;
  const double height = bottom + 48;

  size_t differing = 0;
  for (const Compared& v : vars) differing += (v.anyDiffers || !v.expected || !v.actual) ? 1 : 0;
  std::string title = options.title.empty() ? expName + " vs " + actName : options.title;
  title += differing ? fmt::format(": {} of {} variable{} differ{}", differing, vars.size(), vars.size() == 1 ? "" : "s", differing == 1 ? "s" : "")
                     : vars.empty() ? ": no variables" : ": no differences";
  Svg s;
  openSvg(s, L.width, height, L.left, title,
          fmt::format("{}; tolerance {}; expected dashed, actual solid, differences shaded", windowText(w), tol));
  if (notes) {
    std::string text;
    auto list = [](const std::vector<std::string>& v) {
      std::string out;
      for (const std::string& n : v) out += (out.empty() ? "" : ", ") + n;
      return out;
    };
    if (!onlyExpected.empty()) text += "only in expected: " + list(onlyExpected);
    if (!onlyActual.empty()) text += (text.empty() ? "" : "; ") + std::string("only in actual: ") + list(onlyActual);
    s.add(R"(<text class="only" x="{}" y="56" fill="#d62728">{}</text>)", num(L.left), xmlEscape(fitText(text, L.width - L.left - 8)));
  }
  if (vars.empty()) s.add(R"(<text x="{}" y="{}">no variables</text>)", num(L.left), num(top0 + 20));
  const std::vector<double> timeTicks = drawTimeAxis(s, L, top0, bottom, !options.to);
  for (size_t i = 0; i < vars.size(); ++i) {
    const Compared& v = vars[i];
    const Block& b = blocks[i];
    std::vector<Column> cols;
    if (v.expected) cols.push_back(*v.expected);
    if (v.actual) cols.push_back(*v.actual);
    s.add(R"(<g class="compare" data-var="{}" data-differs="{}">)", xmlEscape(v.name), v.anyDiffers ? "true" : "false");
    if (cols[0].kind == Kind::Number) {
      Panel p{kindOf(cols[0]), {}, unitOf(kindOf(cols[0]), cols[0]), v.name};
      for (size_t k = 0; k < cols.size(); ++k) p.series.push_back(k);
      drawNumeric(s, L, p, cols, grid, b.top, b.height, static_cast<int>(i), timeTicks);
    } else if (cols[0].kind == Kind::Bool) {
      for (size_t k = 0; k < cols.size(); ++k) drawBool(s, L, cols[k], grid, b.top + static_cast<double>(k) * (laneH + laneGap), laneH);
    } else {
      for (size_t k = 0; k < cols.size(); ++k) drawState(s, L, cols[k], grid, b.top + static_cast<double>(k) * (bandH + laneGap), bandH);
      drawStateLegend(s, L.left, b.legendTop, cols[0], b.legend);
    }
    if (v.anyDiffers) drawDiffShading(s, L, diffColumns(L, grid, v.differs), b.top, b.height, v.name);
    s.add("</g>");
  }
  s.add("</svg>");
  return std::move(s.out);
}

}  // namespace

bool readTraceCsv(const std::string& path, TraceTable& out, std::string& error, bool& missing) {
  missing = false;
  std::string why;
  if (!config::checkRegularFile(path, why)) {   // a FIFO would block
    missing = true;
    error = fmt::format("cannot open '{}': {}", path, why);
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    missing = true;
    error = fmt::format("cannot open '{}': {}", path, std::strerror(errno));
    return false;
  }
  std::string line;
  std::vector<std::string> fields, units;
  size_t lineNo = 0, unitsLine = 0;
  // Comments before the header; `#units,...` the columns' units.
  bool got = false;
  while ((got = static_cast<bool>(std::getline(in, line)))) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] != '#') break;
    if (line.compare(0, 7, "#units,") == 0 && splitCsv(line, units)) {
      units.erase(units.begin());
      unitsLine = lineNo;
    }
  }
  if (!got) {
    error = fmt::format("'{}' is empty; expected a trace CSV (header 'time,VAR,...')", path);
    return false;
  }
  if (!splitCsv(line, fields) || fields.empty() || lower(fields[0]) != "time") {
    error = fmt::format("'{}' is not a trace CSV: the header must start with 'time'", path);
    return false;
  }
  out.names.assign(fields.begin() + 1, fields.end());
  out.columns.assign(out.names.size(), {});
  if (unitsLine && units.size() != out.names.size()) {
    error = fmt::format("{}:{}: the #units line has {} units for the {} columns of the header", path, unitsLine, units.size(), out.names.size());
    return false;
  }
  out.units = unitsLine ? units : std::vector<std::string>(out.names.size());
  while (std::getline(in, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    double t;
    if (!splitCsv(line, fields) || fields.size() != out.names.size() + 1 || !parseDouble(fields[0], t)) {
      error = fmt::format("{}:{}: not a trace row (expected a time in seconds and {} values)", path, lineNo, out.names.size());
      return false;
    }
    if (!out.time.empty() && t < out.time.back()) {
      error = fmt::format("{}:{}: the time {} goes backwards", path, lineNo, fields[0]);
      return false;
    }
    out.time.push_back(t);
    for (size_t c = 0; c < out.names.size(); ++c) out.columns[c].push_back(std::move(fields[c + 1]));
  }
  return true;
}

std::string renderSvg(const TraceTable& trace, const PlotOptions& options) {
  if (!options.xy.empty()) return renderPathSvg(trace, options, nullptr);
  // The columns, in --vars order.
  std::vector<Column> cols;
  std::vector<size_t> pick;
  if (options.vars.empty()) {
    for (size_t i = 0; i < trace.names.size(); ++i) pick.push_back(i);
  } else {
    for (const std::string& v : options.vars)
      for (size_t i = 0; i < trace.names.size(); ++i)
        if (lower(trace.names[i]) == lower(v)) {
          pick.push_back(i);
          break;
        }
  }
  for (size_t i : pick) cols.push_back(columnOf(trace, i));

  Layout L;
  double maxName = 0;
  for (const Column& c : cols) maxName = std::max(maxName, textWidth(c.name));
  L.legend = std::clamp(maxName + 44, 150.0, 300.0);
  L.plotW = L.width - L.left - L.legend - 8;
  L.pixels = static_cast<int>(L.plotW);
  // The time window.
  Window w = timeWindow(trace, options);
  L.t0 = w.t0, L.t1 = w.t1, L.r0 = w.r0, L.r1 = w.r1;

  // Panels: one per kind; plain numbers one per variable when there are few.
  std::vector<Panel> panels;
  std::vector<size_t> bools, states;
  int colorIndex = 0;
  for (size_t i = 0; i < cols.size(); ++i) {
    if (cols[i].kind == Kind::Bool) bools.push_back(i);
    else if (cols[i].kind == Kind::State) states.push_back(i);
  }
  size_t others = 0;
  for (const Column& c : cols)
    if (c.kind == Kind::Number && kindOf(c) == 7) ++others;
  for (size_t i = 0; i < cols.size(); ++i) {
    Column& c = cols[i];
    if (c.kind != Kind::Number) continue;
    c.color = colorIndex++;
    // One panel per kind and unit: positions in mm and in degrees do not share an axis.
    int k = kindOf(c);
    std::string unit = unitOf(k, c);
    auto it = std::find_if(panels.begin(), panels.end(), [&](const Panel& p) { return p.kind == k && p.unit == unit; });
    if (it == panels.end() || (k == 7 && others <= 4)) panels.push_back({k, {i}, unit, {}});
    else it->series.push_back(i);
  }
  for (size_t i : bools) cols[i].color = colorIndex++;

  const double top0 = 72, panelGap = 34, laneH = 22, laneGap = 4, bandH = 24;
  double y = top0;
  std::vector<std::pair<double, double>> panelBoxes;
  for (const Panel& p : panels) {
    double h = std::max(170.0, 16.0 * static_cast<double>(p.series.size()) + 12);
    panelBoxes.push_back({y, h});
    y += h + panelGap;
  }
  double lanesTop = panels.empty() ? y - 10 : y - panelGap + 14;
  double yy = lanesTop;
  std::vector<double> laneTops, bandTops;
  for (size_t n = 0; n < bools.size(); ++n) laneTops.push_back(yy), yy += laneH + laneGap;
  double boolLegendTop = yy;
  if (!bools.empty()) yy += kLegendRowH + laneGap;
  std::vector<StateLegend> stateLegends;
  for (size_t n = 0; n < states.size(); ++n) {
    bandTops.push_back(yy);
    stateLegends.push_back(stateLegend(cols[states[n]], L.plotW));
    yy += bandH + 2 + kLegendRowH * static_cast<double>(stateLegends.back().rows.size()) + laneGap;
  }
  double bottom = (bools.empty() && states.empty()) ? lanesTop - 14 : yy - laneGap;
  if (cols.empty()) bottom = top0 + 40;
  double height = bottom + 48;

  Svg s;
  openSvg(s, L.width, height, L.left, options.title, windowText(w));
  if (cols.empty()) s.add(R"(<text x="{}" y="{}">no variables</text>)", num(L.left), num(top0 + 20));

  const std::vector<double> timeTicks = drawTimeAxis(s, L, top0, bottom, !options.to);
  // The grid is drawn first; panels paint their white background over it and
  // draw their own vertical grid below the series.
  for (size_t i = 0; i < panels.size(); ++i) {
    auto [top, h] = panelBoxes[i];
    drawNumeric(s, L, panels[i], cols, trace.time, top, h, static_cast<int>(i), timeTicks);
  }
  for (size_t n = 0; n < bools.size(); ++n) drawBool(s, L, cols[bools[n]], trace.time, laneTops[n], laneH);
  if (!bools.empty()) drawBoolLegend(s, L.left, boolLegendTop);
  for (size_t n = 0; n < states.size(); ++n) {
    drawState(s, L, cols[states[n]], trace.time, bandTops[n], bandH);
    drawStateLegend(s, L.left, bandTops[n] + bandH + 2, cols[states[n]], stateLegends[n]);
  }
  s.add("</svg>");
  return std::move(s.out);
}

namespace {
bool writeSvg(const std::string& path, const std::string& svg, std::string& error) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) {
    error = fmt::format("cannot open '{}': {}", path, std::strerror(errno));
    return false;
  }
  bool ok = std::fwrite(svg.data(), 1, svg.size(), f) == svg.size();
  ok = std::fclose(f) == 0 && ok;
  if (!ok) error = fmt::format("cannot write '{}': {}", path, std::strerror(errno));
  return ok;
}
}  // namespace

bool parseSeconds(const std::string& text, double& out) {
  vm::Time ns = 0;
  if (vm::parseIecDuration(text, ns)) {
    out = static_cast<double>(ns) / 1e9;
    return true;
  }
  return parseDouble(text, out) && std::isfinite(out);
}

int plotTraceFile(const std::string& csvPath, const std::string& svgPath, const PlotOptions& options, std::string& error) {
  std::string diagnostics;
  int rc = plotFiles(csvPath, svgPath, options, error, diagnostics);
  if (!diagnostics.empty()) error = diagnostics + error;
  return rc;
}

int plotFiles(const std::string& csvPath, const std::string& svgPath, const PlotOptions& options, std::string& error,
              std::string& diagnostics) {
  TraceTable t;
  bool missing = false;
  const bool haveTrace = !csvPath.empty();
  if (haveTrace && !readTraceCsv(csvPath, t, error, missing)) return missing ? 2 : 1;
  // A name that is not a column: the closest column and the list of them.
  auto unknown = [&](const char* option, const std::string& v) {
    std::string names;
    for (const std::string& n : t.names) names += (names.empty() ? "" : ", ") + n;
    std::string hint = config::closest(v, t.names);
    error = fmt::format("{}: no column '{}' in '{}'{} (columns: {})", option, v, csvPath,
                        hint.empty() ? "" : fmt::format("; did you mean '{}'?", hint), names.empty() ? "none" : names);
    return 2;
  };
  for (const std::string& v : options.vars)
    if (findColumn(t, v) == std::string::npos) return unknown("--vars", v);
  for (const auto& [x, y] : options.xy)
    for (const std::string* v : {&x, &y}) {
      size_t i = findColumn(t, *v);
      if (i == std::string::npos) return unknown("--xy", *v);
      if (columnOf(t, i).kind != Kind::Number) {
        error = fmt::format("--xy: '{}' in '{}' is not a numeric column", t.names[i], csvPath);
        return 2;
      }
    }
  if (!options.rapid.empty()) {
    size_t i = findColumn(t, options.rapid);
    if (i == std::string::npos) return unknown("--rapid", options.rapid);
    if (columnOf(t, i).kind == Kind::State) {
      error = fmt::format("--rapid: '{}' in '{}' is not a BOOL or numeric column", t.names[i], csvPath);
      return 2;
    }
  }
  if (options.from && options.to && *options.from >= *options.to) {
    error = "--from must be before --to";
    return 2;
  }
  Program prog;
  if (!options.gcode.empty()) {
    int rc = decodeProgram(options, prog, error, diagnostics);
    if (rc) return rc;
  }
  if (haveTrace && t.time.empty()) {
    error = fmt::format("'{}' has no samples", csvPath);
    return 1;
  }
  PlotOptions o = options;
  if (o.title.empty()) {
    const std::string& named = haveTrace ? csvPath : options.gcode;
    size_t slash = named.find_last_of('/');
    o.title = slash == std::string::npos ? named : named.substr(slash + 1);
  }
  std::string svg = options.gcode.empty() ? renderSvg(t, o) : renderPathSvg(t, o, &prog);
  return writeSvg(svgPath, svg, error) ? 0 : 1;
}

std::string renderCompareSvg(const TraceTable& expected, const TraceTable& actual, const PlotOptions& options, double tolerance,
                             const std::string& expectedName, const std::string& actualName) {
  return renderCompare(expected, actual, options, tolerance, expectedName, actualName);
}

int compareTraceFiles(const std::string& expectedCsv, const std::string& actualCsv, const std::string& svgPath, const PlotOptions& options,
                      double tolerance, std::string& error) {
  if (!(tolerance >= 0) || !std::isfinite(tolerance)) {
    error = fmt::format("--tolerance: {} is not a finite number >= 0", tolerance);
    return 2;
  }
  TraceTable e, a;
  bool missing = false;
  if (!readTraceCsv(expectedCsv, e, error, missing) || !readTraceCsv(actualCsv, a, error, missing)) return missing ? 2 : 1;
  for (const std::string& v : options.vars)
    if (findColumn(e, v) == std::string::npos && findColumn(a, v) == std::string::npos) {
      std::vector<std::string> all = e.names;
      all.insert(all.end(), a.names.begin(), a.names.end());
      std::string hint = config::closest(v, all);
      error = fmt::format("--vars: no column '{}' in '{}' or '{}'{}", v, expectedCsv, actualCsv,
                          hint.empty() ? "" : fmt::format("; did you mean '{}'?", hint));
      return 2;
    }
  if (options.from && options.to && *options.from >= *options.to) {
    error = "--from must be before --to";
    return 2;
  }
  for (const auto& [t, path] : {std::pair{&e, &expectedCsv}, std::pair{&a, &actualCsv}})
    if (t->time.empty()) {
      error = fmt::format("'{}' has no samples", *path);
      return 1;
    }
  auto base = [](const std::string& p) {
    size_t slash = p.find_last_of('/');
    return slash == std::string::npos ? p : p.substr(slash + 1);
  };
  std::string svg = renderCompare(e, a, options, tolerance, base(expectedCsv), base(actualCsv));
  return writeSvg(svgPath, svg, error) ? 0 : 1;
}

void PlotCommand::add(CLI::App& app) {
  cmd = app.add_subcommand("plot", "Draw a trace CSV (stc run --trace-out x.csv) or a G-code program's tool path as an SVG");
  cmd->add_option("trace", trace, "Trace CSV file (optional with --gcode)");
  cmd->add_option("-o,--output", output, "SVG file (default: the trace's name, else the program's, with .svg)");
  CLI::Option* varsOpt = cmd->add_option("--vars", vars, "Columns to draw: A,B,... (default: all)")->delimiter(',')->allow_extra_args(false);
  CLI::Option* xyOpt = cmd->add_option("--xy", xy, "Draw the path of Y over X (one square panel, equal scale); repeat for more paths")
                           ->type_name("X,Y")
                           ->allow_extra_args(false)
                           ->excludes(varsOpt);
  cmd->add_option("--title", title, "Title (default: the trace file's name)");
  cmd->add_option("--from", from, "Start of the time window (1.5s, 250ms, or seconds)");
  cmd->add_option("--to", to, "End of the time window");
  CLI::Option* gcodeOpt =
      cmd->add_option("--gcode", gcode,
                      "G-code program: draw its commanded tool path (feed solid, G0 dashed) under the --xy paths, or alone without a trace")
          ->type_name("FILE")
          ->excludes(varsOpt);
  cmd->add_option("--gcode-axes", gcodeAxes, "The program's axes drawn across and up (default X,Y; e.g. X,Z)")
      ->type_name("H,V")
      ->needs(gcodeOpt);
  cmd->add_option("--gcode-var", gcodeVars, "Value of $NAME$ in the program; repeat for more")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false)
      ->needs(gcodeOpt);
  cmd->add_option("--rapid", rapid, "Trace column that is TRUE while a G0 move runs: those parts of the --xy paths are dashed")
      ->type_name("COL")
      ->needs(xyOpt);
  CLI::Option* compareOpt =
      cmd->add_option("--compare", compare,
                      "Draw an expected and an actual trace over each other, the time spans where they differ shaded")
          ->type_name("EXPECTED ACTUAL")
          ->expected(2)
          ->allow_extra_args(false)
          ->excludes(xyOpt)
          ->excludes(gcodeOpt);
  cmd->add_option("--tolerance", tolerance, "With --compare: numbers within TOL x max(1, |expected|) are equal (default 1e-9)")
      ->type_name("TOL")
      ->needs(compareOpt);
  cmd->footer(
      "Examples:\n"
      "  stc plot trace.csv --vars Axis1.fSetPosition,Axis1.fSetVelocity\n"
      "  stc plot trace.csv --xy X.fActPosition,Y.fActPosition\n"
      "  stc plot --gcode part.cnc                   the program's X/Y tool path alone (part.svg)\n"
      "  stc plot --gcode part.cnc --gcode-axes X,Z  the X/Z plane\n"
      "  stc plot trace.csv --xy X.fActPosition,Y.fActPosition --gcode part.cnc --rapid MAIN.bRapid\n"
      "  stc plot --compare expected/run.csv actual.csv -o diff.svg --tolerance 1e-6\n"
      "G-code: feed moves solid, G0 dashed; decode errors are printed as by stc check (exit 1). See docs/cnc.md.");
}

bool parseXyPairs(const std::vector<std::string>& pairs, PlotOptions& options, std::string& error) {
  for (const std::string& pair : pairs) {
    size_t comma = pair.find(',');
    std::string x = comma == std::string::npos ? "" : pair.substr(0, comma), y = comma == std::string::npos ? "" : pair.substr(comma + 1);
    if (x.empty() || y.empty() || y.find(',') != std::string::npos) {
      error = "--xy: '" + pair + "' is not a pair of variables X,Y";
      return false;
    }
    options.xy.emplace_back(x, y);
  }
  return true;
}

bool PlotCommand::parseWindow(PlotOptions& o, std::string& error) const {
  for (auto [opt, text, dst] : {std::tuple{"--from", &from, &o.from}, std::tuple{"--to", &to, &o.to}}) {
    if (text->empty()) continue;
    double v;
    if (!parseSeconds(*text, v)) {
      error = fmt::format("{}: '{}' is not a time (e.g. 1.5s, 250ms, 2)", opt, *text);
      return false;
    }
    *dst = v;
  }
  return true;
}

int PlotCommand::runCompare() const {
  auto usage = [](const std::string& msg) {
    std::fprintf(stderr, "stc: error: %s\n", msg.c_str());
    return 2;
  };
  if (!trace.empty())
    return usage(fmt::format("--compare takes the two traces (EXPECTED ACTUAL); '{}' is one too many", trace));
  if (compare.size() != 2) return usage("--compare needs two traces: EXPECTED ACTUAL");
  if (!rapid.empty()) return usage("--rapid draws --xy paths; it does not go with --compare");
  double tol = 1e-9;
  if (!tolerance.empty() && (!parseDouble(tolerance, tol) || !std::isfinite(tol) || tol < 0))
    return usage(fmt::format("--tolerance: '{}' is not a finite number >= 0 (e.g. 1e-6)", tolerance));
  PlotOptions o;
  o.vars = vars;
  o.title = title;
  std::string err;
  if (!parseWindow(o, err)) return usage(err);
  std::string out = output;
  if (out.empty()) {
    // actual.csv -> actual.compare.svg
    out = compare[1];
    size_t dot = out.find_last_of('.'), slash = out.find_last_of('/');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) out.erase(dot);
    out += ".compare.svg";
  }
  int rc = compareTraceFiles(compare[0], compare[1], out, o, tol, err);
  if (rc) std::fprintf(stderr, "stc: error: %s\n", err.c_str());
  return rc;
}

int PlotCommand::run() const {
  auto usage = [](const std::string& msg) {
    std::fprintf(stderr, "stc: error: %s\n", msg.c_str());
    return 2;
  };
  if (!compare.empty()) return runCompare();
  if (trace.empty() && gcode.empty()) return usage("plot: give a trace CSV, --gcode FILE, or both (stc plot --help)");
  if (trace.empty())
    for (auto [opt, given] : {std::pair{"--xy", !xy.empty()}, std::pair{"--vars", !vars.empty()}, std::pair{"--from", !from.empty()},
                              std::pair{"--to", !to.empty()}, std::pair{"--rapid", !rapid.empty()}})
      if (given) return usage(fmt::format("{} needs a trace CSV (with --gcode alone only the program is drawn)", opt));
  if (!trace.empty() && !gcode.empty() && xy.empty())
    return usage("--gcode with a trace needs --xy X,Y: the trace's columns drawn over the program's path");
  PlotOptions o;
  o.vars = vars;
  o.title = title;
  o.gcode = gcode;
  o.rapid = rapid;
  std::string xyError;
  if (!parseXyPairs(xy, o, xyError)) return usage(xyError);
  if (!gcodeAxes.empty()) {
    // Two different axis letters of the program: X Y Z A B C P Q U V W.
    const std::string letters = "XYZABCPQUVW";
    std::string a = gcodeAxes;
    for (char& c : a) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (a.size() != 3 || a[1] != ',' || letters.find(a[0]) == std::string::npos || letters.find(a[2]) == std::string::npos || a[0] == a[2])
      return usage(fmt::format("--gcode-axes: '{}' is not two different axes H,V of X Y Z A B C P Q U V W (e.g. X,Z)", gcodeAxes));
    o.gcodeH = a[0], o.gcodeV = a[2];
  }
  for (const std::string& nv : gcodeVars) {
    size_t eq = nv.find('=');
    double v = 0;
    std::string name = eq == std::string::npos ? "" : nv.substr(0, eq);
    if (!name.empty() && name.front() == '$' && name.back() == '$' && name.size() > 2) name = name.substr(1, name.size() - 2);
    if (name.empty() || name.find('$') != std::string::npos || !parseDouble(nv.substr(eq + 1), v) || !std::isfinite(v))
      return usage(fmt::format("--gcode-var: '{}' is not NAME=VALUE with a finite number", nv));
    o.gcodeVars.emplace_back(name, v);
  }
  std::string windowError;
  if (!parseWindow(o, windowError)) return usage(windowError);
  std::string out = output;
  if (out.empty()) {
    out = trace.empty() ? gcode : trace;
    size_t dot = out.find_last_of('.'), slash = out.find_last_of('/');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) out.erase(dot);
    out += ".svg";
  }
  std::string err, diagnostics;
  int rc = plotFiles(trace, out, o, err, diagnostics);
  std::fputs(diagnostics.c_str(), stderr);
  if (rc) std::fprintf(stderr, "stc: error: %s\n", err.c_str());
  return rc;
}

}  // namespace stc::plot
