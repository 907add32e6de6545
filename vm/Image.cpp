#include "vm/Image.h"

#include <charconv>
#include <cmath>
#include <cstring>

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

std::string formatReal(double v, bool single) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  char buf[64];
  std::to_chars_result r = single ? std::to_chars(buf, buf + sizeof buf, static_cast<float>(v)) : std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  // The shortest round-trip form, but as an ST literal: plain digits for
  // magnitudes a reader takes in at a glance (100000.0, not 1E+05), and a
  // mantissa with a fraction in exponent form (1.0E+19).
  const double mag = std::fabs(v);
  if (s.find('e') != std::string::npos && mag >= 1e-5 && mag < 1e16) {
    r = single ? std::to_chars(buf, buf + sizeof buf, static_cast<float>(v), std::chars_format::fixed)
               : std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
    s.assign(buf, r.ptr);
  }
  for (char& c : s)
    if (c == 'e') c = 'E';
  const size_t e = s.find('E');
  if (s.find('.') == std::string::npos) s.insert(e == std::string::npos ? s.size() : e, ".0");
  return s;
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
    case TypeKind::Pointer: case TypeKind::Reference: return hex(readUnsigned(p, 8));
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
      for (const sema::FieldLayout& f : layout.of(t).fields) {
        if (!f.type) continue;   // the vptr
        out += (first ? "" : ", ") + f.name + " := " + (f.indirect ? hex(readUnsigned(p + f.offset, 8)) : formatValue(p + f.offset, f.type, layout));
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
    std::vector<std::string> names;
    for (const auto& r : map.roots) names.push_back(r.path);
    std::string hint = closest(segs[0].name, names);
    error = "no variable named '" + segs[0].name + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?");
    return false;
  }
  uint64_t off = root->offset;
  const Type* t = root->type;
  out.retain = root->retain;
  out.persistent = root->persistent;
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
    if (!(st->kind == TypeKind::Struct || st->kind == TypeKind::Union || st->kind == TypeKind::FunctionBlock || st->kind == TypeKind::Program)) {
      error = "'" + segs[k - 1].name + "' has no members (it is " + st->name + ")";
      return false;
    }
    const sema::FieldLayout* f = layout.field(st, segs[k].name);
    if (!f || !f->type) {
      std::vector<std::string> names;
      for (const auto& fl : layout.of(st).fields)
        if (fl.type) names.push_back(fl.name);
      std::string hint = closest(segs[k].name, names);
      error = "no member named '" + segs[k].name + "' in '" + st->name + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?");
      return false;
    }
    if (f->indirect) { error = "'" + segs[k].name + "' is a VAR_IN_OUT and cannot be watched"; return false; }
    off += f->offset;
    t = f->type;
    if (!applyIndex(segs[k])) return false;
  }
  out.offset = off;
  out.type = t;
  return true;
}

}  // namespace stc::vm
