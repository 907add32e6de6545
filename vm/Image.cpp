#include "vm/Image.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "ast/AST.h"
#include "basic/Text.h"
#include "sema/Layout.h"
#include "sema/Types.h"
#include "vm/Time.h"

namespace stc::vm {

using sema::Type;
using sema::TypeKind;

namespace {

const Type* strip(const Type* t) {
  while (t && (t->kind == TypeKind::Subrange) && t->element) t = t->element;
  return t;
}

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (asciiUpper(a[i - 1]) == asciiUpper(b[j - 1]) ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closest(const std::string& name, const std::vector<std::string>& cands) {
  std::string best;
  size_t bestD = std::max<size_t>(2, name.size() / 3) + 1;
  for (const std::string& c : cands) {
    size_t d = editDistance(name, c);
    if (d < bestD) { bestD = d; best = c; }
  }
  return best;
}

uint64_t readUnsigned(const uint8_t* p, unsigned n) {
  uint64_t v = 0;
  for (unsigned i = 0; i < n; ++i) v |= static_cast<uint64_t>(p[i]) << (8 * i);
  return v;
}

int64_t readSigned(const uint8_t* p, unsigned n) {
  uint64_t v = readUnsigned(p, n);
  if (n < 8 && (v >> (8 * n - 1)) & 1) v |= ~0ull << (8 * n);
  return static_cast<int64_t>(v);
}

}  // namespace

// Days since 1970-01-01 to a civil date (proleptic Gregorian).
void civilFromDays(int64_t days, int64_t& y, unsigned& m, unsigned& d) {
  days += 719468;
  int64_t era = (days >= 0 ? days : days - 146096) / 146097;
  auto doe = static_cast<unsigned>(days - era * 146097);
  unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  y = static_cast<int64_t>(yoe) + era * 400;
  unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  unsigned mp = (5 * doy + 2) / 153;
  d = doy - (153 * mp + 2) / 5 + 1;
  m = mp < 10 ? mp + 3 : mp - 9;
  if (m <= 2) ++y;
}

int64_t daysFromCivil(int64_t y, unsigned m, unsigned d) {
  y -= m <= 2;
  int64_t era = (y >= 0 ? y : y - 399) / 400;
  auto yoe = static_cast<unsigned>(y - era * 400);
  unsigned doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
  unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

namespace {

std::string two(unsigned v) { return (v < 10 ? "0" : "") + std::to_string(v); }

std::string dateText(int64_t ns) {
  int64_t days = ns >= 0 ? ns / 86'400'000'000'000 : -((-ns + 86'399'999'999'999) / 86'400'000'000'000);
  int64_t y;
  unsigned m, d;
  civilFromDays(days, y, m, d);
  return std::to_string(y) + "-" + two(m) + "-" + two(d);
}

std::string todText(int64_t ns) {
  ns %= 86'400'000'000'000;
  if (ns < 0) ns += 86'400'000'000'000;
  auto s = static_cast<unsigned>(ns / 1'000'000'000);
  std::string out = two(s / 3600) + ":" + two(s / 60 % 60) + ":" + two(s % 60);
  int64_t frac = ns % 1'000'000'000;
  if (frac) {
    std::string f = std::to_string(frac + 1'000'000'000).substr(1);
    while (!f.empty() && f.back() == '0') f.pop_back();
    out += "." + f;
  }
  return out;
}

bool validUtf8(const std::string& s) {
  for (size_t i = 0; i < s.size();) {
    auto c = static_cast<unsigned char>(s[i]);
    int n = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (n < 0 || i + static_cast<size_t>(n) >= s.size() + (n == 0 ? 1 : 0)) return false;
    for (int k = 1; k <= n; ++k)
      if ((static_cast<unsigned char>(s[i + static_cast<size_t>(k)]) >> 6) != 2) return false;
    i += static_cast<size_t>(n) + 1;
  }
  return true;
}

void appendUtf8(std::string& out, uint32_t cp) {
  if (cp < 0x80) out.push_back(static_cast<char>(cp));
  else if (cp < 0x800) { out.push_back(static_cast<char>(0xC0 | (cp >> 6))); out.push_back(static_cast<char>(0x80 | (cp & 63))); }
  else if (cp < 0x10000) {
    out.push_back(static_cast<char>(0xE0 | (cp >> 12)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 63)));
    out.push_back(static_cast<char>(0x80 | (cp & 63)));
  } else {
    out.push_back(static_cast<char>(0xF0 | (cp >> 18)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 12) & 63)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 63)));
    out.push_back(static_cast<char>(0x80 | (cp & 63)));
  }
}

// IEC string literal escapes: $' $$ $N $T $R $L and $hh for other controls.
std::string quote(const std::vector<uint32_t>& cps, char q) {
  std::string out(1, q);
  for (uint32_t cp : cps) {
    if (cp == static_cast<uint32_t>(q)) { out += '$'; out += q; }
    else if (cp == '$') out += "$$";
    else if (cp == '\n') out += "$N";
    else if (cp == '\t') out += "$T";
    else if (cp == '\r') out += "$R";
    else if (cp < 0x20 || cp == 0x7F) {
      char buf[8];
      std::snprintf(buf, sizeof buf, q == '"' ? "$%04X" : "$%02X", cp);
      out += buf;
    } else appendUtf8(out, cp);
  }
  out += q;
  return out;
}

std::string stringText(const uint8_t* p, uint32_t cap) {
  std::string raw;
  for (uint32_t i = 0; i < cap && p[i]; ++i) raw.push_back(static_cast<char>(p[i]));
  std::vector<uint32_t> cps;
  if (validUtf8(raw)) {
    for (size_t i = 0; i < raw.size();) {
      auto c = static_cast<unsigned char>(raw[i]);
      uint32_t cp = c;
      int n = c < 0x80 ? 0 : c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : 1;
      if (n) cp = c & (0x3F >> n);
      ++i;
      for (int k = 0; k < n; ++k, ++i) cp = (cp << 6) | (static_cast<unsigned char>(raw[i]) & 63);
      cps.push_back(cp);
    }
  } else {
    for (char c : raw) cps.push_back(static_cast<unsigned char>(c));   // Latin-1
  }
  return quote(cps, '\'');
}

std::string wstringText(const uint8_t* p, uint32_t cap) {
  std::vector<uint32_t> cps;
  for (uint32_t i = 0; i < cap; ++i) {
    uint32_t u = static_cast<uint32_t>(readUnsigned(p + 2 * i, 2));
    if (!u) break;
    if (u >= 0xD800 && u < 0xDC00 && i + 1 < cap) {
      uint32_t lo = static_cast<uint32_t>(readUnsigned(p + 2 * (i + 1), 2));
      if (lo >= 0xDC00 && lo < 0xE000) { u = 0x10000 + ((u - 0xD800) << 10) + (lo - 0xDC00); ++i; }
    }
    cps.push_back(u);
  }
  return quote(cps, '"');
}

std::string hex(uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "16#%llX", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

std::string formatDate(int64_t ns) { return dateText(ns); }
std::string formatTimeOfDay(int64_t ns) { return todText(ns); }

bool parseDateText(std::string_view text, char kind, int64_t& ns) {
  std::string t = asciiUpper(text);
  size_t hash = t.find('#');
  if (hash != std::string::npos) {
    std::string pre = t.substr(0, hash);
    if (pre == "D" || pre == "DATE" || pre == "LDATE" || pre == "LD") kind = 'D';
    else if (pre == "TOD" || pre == "TIME_OF_DAY" || pre == "LTOD" || pre == "LTIME_OF_DAY") kind = 'T';
    else if (pre == "DT" || pre == "DATE_AND_TIME" || pre == "LDT" || pre == "LDATE_AND_TIME") kind = 'S';
    else return false;
    t = t.substr(hash + 1);
  }
  auto number = [&](size_t& i, int64_t& v) {
    size_t start = i;
    v = 0;
    while (i < t.size() && t[i] >= '0' && t[i] <= '9') v = v * 10 + (t[i++] - '0');
    return i > start;
  };
  size_t i = 0;
  int64_t days = 0, tod = 0;
  if (kind == 'D' || kind == 'S') {
    int64_t y, m, d;
    if (!number(i, y) || i >= t.size() || t[i++] != '-' || !number(i, m) || i >= t.size() || t[i++] != '-' || !number(i, d)) return false;
    if (m < 1 || m > 12 || d < 1 || d > 31) return false;
    days = daysFromCivil(y, static_cast<unsigned>(m), static_cast<unsigned>(d));
    if (kind == 'S' && (i >= t.size() || t[i++] != '-')) return false;
  }
  if (kind == 'T' || kind == 'S') {
    int64_t h, mi, sec = 0;
    if (!number(i, h) || i >= t.size() || t[i++] != ':' || !number(i, mi)) return false;
    if (i < t.size() && t[i] == ':') { ++i; if (!number(i, sec)) return false; }
    int64_t frac = 0, scale = 1'000'000'000;
    if (i < t.size() && t[i] == '.') {
      ++i;
      while (i < t.size() && t[i] >= '0' && t[i] <= '9') {
        scale /= 10;
        frac += (t[i++] - '0') * scale;
      }
    }
    if (h > 23 || mi > 59 || sec > 59) return false;
    tod = ((h * 60 + mi) * 60 + sec) * 1'000'000'000 + frac;
  }
  if (i != t.size()) return false;
  ns = days * 86'400'000'000'000 + tod;
  return true;
}

// formatReal: vm/Trace.cpp (in stc_vmcore, which the trace writer is part of).

// An {attribute 'internal'} field of a function block or structure: the
// binding of the instance to its native implementation, not shown or resolved.
static bool isInternalField(const Type* owner, const sema::FieldLayout& f) {
  return owner->kind != TypeKind::Program && f.decl && ast::hasAttribute(f.decl->attributes, "internal");
}

std::string formatValue(const uint8_t* p, const Type* t, const sema::Layout& layout) {
  t = strip(t);
  switch (t->kind) {
    case TypeKind::Bool: case TypeKind::Bit: return p[0] ? "TRUE" : "FALSE";
    case TypeKind::SInt: case TypeKind::Int: case TypeKind::DInt: case TypeKind::LInt:
      return std::to_string(readSigned(p, t->bits() / 8));
    case TypeKind::USInt: case TypeKind::UInt: case TypeKind::UDInt: case TypeKind::ULInt:
      return std::to_string(readUnsigned(p, t->bits() / 8));
    case TypeKind::Byte: case TypeKind::Word: case TypeKind::DWord: case TypeKind::LWord:
      return hex(readUnsigned(p, t->bits() / 8));
    case TypeKind::Real: {
      float f;
      std::memcpy(&f, p, 4);
      return formatReal(f, true);
    }
    case TypeKind::LReal: {
      double d;
      std::memcpy(&d, p, 8);
      return formatReal(d, false);
    }
    case TypeKind::Time: return formatIecTime(readSigned(p, 8), "T#");
    case TypeKind::LTime: return formatIecTime(readSigned(p, 8), "LTIME#");
    case TypeKind::Date: return "D#" + dateText(readSigned(p, 8));
    case TypeKind::LDate: return "LDATE#" + dateText(readSigned(p, 8));
    case TypeKind::Tod: return "TOD#" + todText(readSigned(p, 8));
    case TypeKind::LTod: return "LTOD#" + todText(readSigned(p, 8));
    case TypeKind::DT: case TypeKind::LDT: {
      int64_t v = readSigned(p, 8);
      return std::string(t->kind == TypeKind::DT ? "DT#" : "LDT#") + dateText(v) + "-" + todText(v);
    }
    case TypeKind::String: return stringText(p, t->length);
    case TypeKind::WString: return wstringText(p, t->length);
    case TypeKind::Char: return quote({p[0]}, '\'');
    case TypeKind::WChar: return quote({static_cast<uint32_t>(readUnsigned(p, 2))}, '"');
    case TypeKind::Enum: {
      const Type* base = t->element;
      unsigned n = base ? base->bits() / 8 : 2;
      int64_t v = base && base->isSignedInt() ? readSigned(p, n) : static_cast<int64_t>(readUnsigned(p, n));
      for (auto& [name, val] : t->enumValues)
        if (val == v) return t->name + "#" + name;
      return t->name + "#" + std::to_string(v);
    }
    case TypeKind::Pointer: case TypeKind::Reference: return hex(readUnsigned(p, static_cast<unsigned>(layout.sizeOf(t))));
    case TypeKind::Interface: return hex(readUnsigned(p, 8));
    case TypeKind::Array: {
      uint64_t stride = layout.sizeOf(t->element);
      uint64_t a = layout.alignOf(t->element);
      stride = (stride + a - 1) / a * a;
      uint64_t count = stride ? layout.sizeOf(t) / stride : 0;
      std::string out = "[";
      for (uint64_t i = 0; i < count; ++i) out += (i ? ", " : "") + formatValue(p + i * stride, t->element, layout);
      return out + "]";
    }
    case TypeKind::Struct: case TypeKind::Union: case TypeKind::FunctionBlock: case TypeKind::Program: {
      std::string out = "(";
      bool first = true;
      // A function block with inputs or outputs shows that interface, not its inner state
      // (which stays reachable by path: `fb.inner`); one without (a class with methods)
      // shows its variables.
      auto isInterface = [](const sema::FieldLayout& f) {
        return f.decl && (f.decl->section == ast::VarSection::Input || f.decl->section == ast::VarSection::Output);
      };
      const auto& fields = layout.of(t).fields;
      const bool interfaceOnly = t->kind == TypeKind::FunctionBlock && std::any_of(fields.begin(), fields.end(), isInterface);
      for (const sema::FieldLayout& f : fields) {
        if (!f.type) continue;   // the vptr
        if (isInternalField(t, f)) continue;   // the native implementation's binding
        if (interfaceOnly && !isInterface(f)) continue;
        out += (first ? "" : ", ") + f.name + " := " +
               (f.indirect ? hex(readUnsigned(p + f.offset, 8))
                : f.bit >= 0 ? std::string((p[f.offset] >> f.bit) & 1 ? "TRUE" : "FALSE")
                             : formatValue(p + f.offset, f.type, layout));
        first = false;
      }
      return out + ")";
    }
    default:
      return "?";
  }
}

bool resolvePath(const codegen::ImageMap& map, const sema::Layout& layout, const std::string& path, ValueRef& out, std::string& error) {
  // Split into segments: names and [i, j] index groups.
  struct Seg { std::string name; std::vector<int64_t> idx; };
  std::vector<Seg> segs;
  size_t i = 0;
  while (i < path.size()) {
    Seg s;
    while (i < path.size() && path[i] != '.' && path[i] != '[') s.name += path[i++];
    while (i < path.size() && path[i] == '[') {
      size_t close = path.find(']', i);
      if (close == std::string::npos) { error = "missing ']' in '" + path + "'"; return false; }
      std::string inside = path.substr(i + 1, close - i - 1);
      size_t pos = 0;
      while (pos <= inside.size()) {
        size_t comma = inside.find(',', pos);
        std::string num = inside.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
        try {
          s.idx.push_back(std::stoll(num));
        } catch (...) {
          error = "index '" + num + "' in '" + path + "' is not an integer";
          return false;
        }
        if (comma == std::string::npos) break;
        pos = comma + 1;
      }
      i = close + 1;
    }
    if (s.name.empty()) { error = "empty name in '" + path + "'"; return false; }
    segs.push_back(s);
    if (i < path.size() && path[i] == '.') ++i;
  }
  if (segs.empty()) { error = "empty path"; return false; }
  // The longest root that matches the leading names.
  const codegen::ImageRoot* root = nullptr;
  size_t used = 0;
  std::string joined;
  for (size_t k = 0; k < segs.size(); ++k) {
    joined += (k ? "." : "") + asciiUpper(segs[k].name);
    if (const codegen::ImageRoot* r = map.find(joined)) { root = r; used = k + 1; }
    if (!segs[k].idx.empty()) break;
  }
  if (!root) {
    // `GVL.Vell`: GVL is a namespace of roots (a GVL, a namespace), so the name after it is the
    // one that is wrong and the hint comes from that namespace.
    const std::string prefix = asciiUpper(segs[0].name) + ".";
    std::vector<std::string> inside;
    for (const auto& r : map.roots)
      if (asciiUpper(r.path).compare(0, prefix.size(), prefix) == 0) inside.push_back(r.path);
    if (segs.size() >= 2 && !inside.empty()) {
      std::string hint = closest(segs[0].name + "." + segs[1].name, inside);
      error = "'" + segs[0].name + "' has no variable named '" + segs[1].name + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?");
      return false;
    }
    std::vector<std::string> names;
    for (const auto& r : map.roots) names.push_back(r.path);
    std::string hint = closest(segs[0].name, names);
    error = "no variable named '" + segs[0].name + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?");
    return false;
  }
  if (!root->runsAs.empty()) {
    error = "'" + root->path + "' is the PROGRAM's own instance, which never runs: the configuration runs it as '" +
            root->runsAs + "' (e.g. '" + root->runsAs.substr(0, root->runsAs.find(',')) +
            path.substr(std::min(path.size(), root->path.size())) + "')";
    return false;
  }
  uint64_t off = root->offset;
  const Type* t = root->type;
  bool mirrored = false;
  out.retain = root->retain;
  out.persistent = root->persistent;
  out.constant = root->constant;
  out.bit = root->bit;
  auto applyIndex = [&](const Seg& s) -> bool {
    const Type* at = strip(t);
    if (s.idx.empty()) return true;
    if (at->kind != TypeKind::Array || at->dims.size() != s.idx.size()) {
      error = "'" + s.name + "' is not an array of " + std::to_string(s.idx.size()) + " dimension(s)";
      return false;
    }
    uint64_t stride = layout.sizeOf(at->element);
    uint64_t a = layout.alignOf(at->element);
    stride = (stride + a - 1) / a * a;
    uint64_t rel = 0;
    for (size_t k = 0; k < s.idx.size(); ++k) {
      const sema::Dim& d = at->dims[k];
      if (s.idx[k] < d.lo || s.idx[k] > d.hi) {
        error = "index " + std::to_string(s.idx[k]) + " is outside " + std::to_string(d.lo) + ".." + std::to_string(d.hi) + " of '" + s.name + "'";
        return false;
      }
      rel = rel * static_cast<uint64_t>(d.hi - d.lo + 1) + static_cast<uint64_t>(s.idx[k] - d.lo);
    }
    off += rel * stride;
    t = at->element;
    return true;
  };
  if (!applyIndex(segs[used - 1])) return false;
  for (size_t k = used; k < segs.size(); ++k) {
    const Type* st = strip(t);
    mirrored = mirrored || sema::isMirrored(st);
    if (!(st->kind == TypeKind::Struct || st->kind == TypeKind::Union || st->kind == TypeKind::FunctionBlock || st->kind == TypeKind::Program)) {
      error = "'" + segs[k - 1].name + "' has no members (it is " + st->name + ")";
      return false;
    }
    const sema::FieldLayout* f = layout.field(st, segs[k].name);
    if (!f || !f->type) {
      std::vector<std::string> names;
      for (const auto& fl : layout.of(st).fields)
        if (fl.type && !isInternalField(st, fl)) names.push_back(fl.name);
      std::string hint = closest(segs[k].name, names);
      error = "no member named '" + segs[k].name + "' in '" + st->name + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?");
      return false;
    }
    if (f->indirect) { error = "'" + segs[k].name + "' is a VAR_IN_OUT and cannot be watched"; return false; }
    if (isInternalField(st, *f)) {
      error = "'" + f->name + "' is internal to '" + st->name + "': it binds the instance to its native implementation and cannot be watched, traced or written";
      return false;
    }
    off += f->offset;
    t = f->type;
    out.bit = f->bit;   // a packed BIT member
    if (!applyIndex(segs[k])) return false;
  }
  out.offset = off;
  out.type = t;
  out.mirrored = mirrored || sema::holdsMirrored(strip(t));
  return true;
}

}  // namespace stc::vm

// ---------------------------------------------------------------- parseValue

namespace stc::vm {

namespace {

std::string trimmed(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return std::string(s.substr(b, e - b));
}

// Drops a `PREFIX#` type prefix (INT#, REAL#, BOOL#, ...) when it names an
// elementary type; keeps `16#`, `T#` and the like.
std::string_view dropTypePrefix(std::string_view s) {
  size_t hash = s.find('#');
  if (hash == std::string_view::npos) return s;
  static const char* const names[] = {"BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "BYTE",
                                      "WORD", "DWORD", "LWORD", "REAL", "LREAL", "STRING", "WSTRING", "CHAR", "WCHAR"};
  std::string head = asciiUpper(s.substr(0, hash));
  for (const char* n : names)
    if (head == n) return s.substr(hash + 1);
  return s;
}

// An integer literal: [+-] digits, or base#digits (2, 8, 16), underscores allowed.
bool parseIntText(std::string_view s, bool& negative, uint64_t& mag) {
  negative = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    negative = s[0] == '-';
    s.remove_prefix(1);
  }
  unsigned base = 10;
  if (size_t hash = s.find('#'); hash != std::string_view::npos) {
    std::string b(s.substr(0, hash));
    if (b == "2") base = 2;
    else if (b == "8") base = 8;
    else if (b == "16") base = 16;
    else return false;
    s.remove_prefix(hash + 1);
  }
  if (s.empty() || s[0] == '_') return false;
  mag = 0;
  bool any = false;
  for (char c : s) {
    if (c == '_') continue;
    unsigned d;
    if (c >= '0' && c <= '9') d = static_cast<unsigned>(c - '0');
    else if (c >= 'a' && c <= 'f') d = static_cast<unsigned>(c - 'a' + 10);
    else if (c >= 'A' && c <= 'F') d = static_cast<unsigned>(c - 'A' + 10);
    else return false;
    if (d >= base) return false;
    if (mag > (UINT64_MAX - d) / base) return false;
    mag = mag * base + d;
    any = true;
  }
  return any;
}

void writeUnsigned(uint8_t* p, unsigned n, uint64_t v) {
  for (unsigned i = 0; i < n; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}

// 'text' or "text" with $ escapes ($$, $', $", $L, $N, $P, $R, $T, $hh / $hhhh).
bool parseQuoted(std::string_view s, char q, std::vector<uint32_t>& cps) {
  if (s.size() < 2 || s.front() != q || s.back() != q) return false;
  s = s.substr(1, s.size() - 2);
  for (size_t i = 0; i < s.size();) {
    auto c = static_cast<unsigned char>(s[i]);
    if (c == '$') {
      if (i + 1 >= s.size()) return false;
      char e = asciiUpper(s[i + 1]);
      if (e == '$' || e == '\'' || e == '"') cps.push_back(static_cast<unsigned char>(e)), i += 2;
      else if (e == 'L' || e == 'N') cps.push_back('\n'), i += 2;
      else if (e == 'P') cps.push_back('\f'), i += 2;
      else if (e == 'R') cps.push_back('\r'), i += 2;
      else if (e == 'T') cps.push_back('\t'), i += 2;
      else {
        size_t n = q == '"' ? 4 : 2;
        if (i + 1 + n > s.size()) return false;
        uint64_t v = 0;
        bool neg = false;
        if (!parseIntText("16#" + std::string(s.substr(i + 1, n)), neg, v)) return false;
        cps.push_back(static_cast<uint32_t>(v));
        i += 1 + n;
      }
      continue;
    }
    if (c == static_cast<unsigned char>(q)) return false;   // an unescaped quote inside
    // UTF-8 decode.
    uint32_t cp = c;
    int n = c < 0x80 ? 0 : c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : 1;
    if (n) cp = c & (0x3F >> n);
    ++i;
    for (int k = 0; k < n && i < s.size(); ++k, ++i) cp = (cp << 6) | (static_cast<unsigned char>(s[i]) & 63);
    cps.push_back(cp);
  }
  return true;
}

}  // namespace

bool parseValue(std::string_view textIn, uint8_t* p, const Type* t0, const sema::Layout& layout, std::string& error) {
  (void)layout;
  const std::string text = trimmed(textIn);
  const Type* t = strip(t0);
  auto bad = [&](const std::string& what) {
    error = "'" + text + "' is not " + what;
    return false;
  };
  auto intoInteger = [&](const Type* it, std::string_view s, int64_t lo, int64_t hi, bool range) -> bool {
    bool neg = false;
    uint64_t mag = 0;
    if (!parseIntText(dropTypePrefix(s), neg, mag)) return bad("an integer literal");
    unsigned bytes = std::max(1u, it->bits() / 8);
    if (it->isSignedInt()) {
      unsigned bits = bytes * 8;
      uint64_t limit = bits == 64 ? (1ull << 63) : (1ull << (bits - 1));
      if (mag > limit - (neg ? 0 : 1)) return bad("in the range of " + it->name);
      int64_t v = neg ? static_cast<int64_t>(0 - mag) : static_cast<int64_t>(mag);
      if (range && (v < lo || v > hi)) return bad("in the subrange " + std::to_string(lo) + ".." + std::to_string(hi));
      writeUnsigned(p, bytes, static_cast<uint64_t>(v));
    } else {
      if (neg && mag) return bad("in the range of " + it->name);
      if (bytes < 8 && mag >> (bytes * 8)) return bad("in the range of " + it->name);
      if (range && (static_cast<int64_t>(mag) < lo || static_cast<int64_t>(mag) > hi))
        return bad("in the subrange " + std::to_string(lo) + ".." + std::to_string(hi));
      writeUnsigned(p, bytes, mag);
    }
    return true;
  };
  if (t0 && t0->kind == TypeKind::Subrange && t->isInteger()) return intoInteger(t, text, t0->lo, t0->hi, true);
  switch (t->kind) {
    case TypeKind::Bool: case TypeKind::Bit: {
      std::string u = asciiUpper(dropTypePrefix(text));
      if (u == "TRUE" || u == "1") p[0] = 1;
      else if (u == "FALSE" || u == "0") p[0] = 0;
      else return bad("a BOOL literal (TRUE, FALSE)");
      return true;
    }
    case TypeKind::SInt: case TypeKind::Int: case TypeKind::DInt: case TypeKind::LInt:
    case TypeKind::USInt: case TypeKind::UInt: case TypeKind::UDInt: case TypeKind::ULInt:
    case TypeKind::Byte: case TypeKind::Word: case TypeKind::DWord: case TypeKind::LWord:
      return intoInteger(t, text, 0, 0, false);
    case TypeKind::Real: case TypeKind::LReal: {
      std::string s;
      for (char c : dropTypePrefix(text))
        if (c != '_') s.push_back(c);
      if (s.empty()) return bad("a REAL literal");
      double d = 0;
      const char* b = s.data() + (s[0] == '+' ? 1 : 0);
      auto [end, ec] = std::from_chars(b, s.data() + s.size(), d);
      if (ec != std::errc() || end != s.data() + s.size()) return bad("a REAL literal");
      if (t->kind == TypeKind::Real) {
        float f = static_cast<float>(d);
        std::memcpy(p, &f, 4);
      } else {
        std::memcpy(p, &d, 8);
      }
      return true;
    }
    case TypeKind::Time: case TypeKind::LTime: {
      Time v = 0;
      if (!parseIecDuration(text, v)) return bad("a duration (T#1s500ms, 250ms)");
      writeUnsigned(p, 8, static_cast<uint64_t>(v));
      return true;
    }
    case TypeKind::Date: case TypeKind::LDate: case TypeKind::Tod: case TypeKind::LTod: case TypeKind::DT: case TypeKind::LDT: {
      char kind = t->kind == TypeKind::Date || t->kind == TypeKind::LDate ? 'D' : t->kind == TypeKind::Tod || t->kind == TypeKind::LTod ? 'T' : 'S';
      int64_t v = 0;
      if (!parseDateText(text, kind, v)) return bad("a " + t->name + " literal");
      writeUnsigned(p, 8, static_cast<uint64_t>(v));
      return true;
    }
    case TypeKind::String: case TypeKind::Char: {
      std::vector<uint32_t> cps;
      if (!parseQuoted(dropTypePrefix(text), '\'', cps)) return bad("a STRING literal ('text')");
      std::string bytes;
      for (uint32_t cp : cps) appendUtf8(bytes, cp);
      if (t->kind == TypeKind::Char) {
        if (cps.size() != 1 || cps[0] > 0xFF) return bad("one CHAR");
        p[0] = static_cast<uint8_t>(cps[0]);
        return true;
      }
      if (bytes.size() > t->length) return bad("at most " + std::to_string(t->length) + " bytes long");
      std::memset(p, 0, t->length + 1);
      std::memcpy(p, bytes.data(), bytes.size());
      return true;
    }
    case TypeKind::WString: case TypeKind::WChar: {
      std::vector<uint32_t> cps;
      if (!parseQuoted(dropTypePrefix(text), '"', cps)) return bad("a WSTRING literal (\"text\")");
      std::vector<uint16_t> units;
      for (uint32_t cp : cps) {
        if (cp >= 0x10000) {
          units.push_back(static_cast<uint16_t>(0xD800 + ((cp - 0x10000) >> 10)));
          units.push_back(static_cast<uint16_t>(0xDC00 + ((cp - 0x10000) & 0x3FF)));
        } else {
          units.push_back(static_cast<uint16_t>(cp));
        }
      }
      if (t->kind == TypeKind::WChar) {
        if (units.size() != 1) return bad("one WCHAR");
        writeUnsigned(p, 2, units[0]);
        return true;
      }
      if (units.size() > t->length) return bad("at most " + std::to_string(t->length) + " characters long");
      std::memset(p, 0, 2 * (t->length + 1));
      for (size_t i = 0; i < units.size(); ++i) writeUnsigned(p + 2 * i, 2, units[i]);
      return true;
    }
    case TypeKind::Enum: {
      std::string_view s = text;
      if (size_t hash = s.find('#'); hash != std::string_view::npos) {
        if (!equalsIgnoreCase(s.substr(0, hash), t->name)) return bad("a value of " + t->name);
        s.remove_prefix(hash + 1);
      }
      const Type* base = t->element;
      unsigned n = base ? base->bits() / 8 : 2;
      for (auto& [name, val] : t->enumValues)
        if (equalsIgnoreCase(s, name)) {
          writeUnsigned(p, n, static_cast<uint64_t>(val));
          return true;
        }
      bool neg = false;
      uint64_t mag = 0;
      if (parseIntText(s, neg, mag)) {
        writeUnsigned(p, n, neg ? 0 - mag : mag);
        return true;
      }
      std::string names;
      for (auto& [name, val] : t->enumValues) names += (names.empty() ? "" : ", ") + t->name + "#" + name;
      return bad("a value of " + t->name + " (" + names + ")");
    }
    default:
      error = "values of type " + t->name + " cannot be given as a literal (only elementary types, enums and subranges)";
      return false;
  }
}

}  // namespace stc::vm
