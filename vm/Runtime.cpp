#include "vm/Runtime.h"

#include <pthread.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <string>
#include <algorithm>
#include <cstdlib>
#include <initializer_list>
#include <vector>

#include "codegen/CodeGen.h"
#include "basic/SourceManager.h"
#include "vm/Fiber.h"
#include "vm/Image.h"
#include "vm/Scheduler.h"
#include "vm/Time.h"

using stc::codegen::FaultKind;

namespace {

thread_local stc::vm::OutsideTaskFaultHandler tOutsideHandler = nullptr;

[[noreturn]] void raise(uint32_t site, FaultKind kind, std::string message) {
  stc::vm::raiseFault(site, stc::codegen::faultCode(kind), std::move(message));
}

}  // namespace

uint32_t __stc_site = 0;

namespace {
thread_local uintptr_t tImageLo = 0, tImageHi = 0;

// The running code's stack: the fiber's, else this thread's.
std::pair<uintptr_t, uintptr_t> currentStack() {
  if (const stc::vm::Fiber* f = stc::vm::Fiber::current()) {
    auto [b, n] = f->stackRange();
    return {reinterpret_cast<uintptr_t>(b), reinterpret_cast<uintptr_t>(b) + n};
  }
  thread_local std::pair<uintptr_t, uintptr_t> main = [] {
    std::pair<uintptr_t, uintptr_t> r{0, 0};
    pthread_attr_t a;
    if (pthread_getattr_np(pthread_self(), &a) == 0) {
      void* addr = nullptr;
      size_t size = 0;
      if (pthread_attr_getstack(&a, &addr, &size) == 0) r = {reinterpret_cast<uintptr_t>(addr), reinterpret_cast<uintptr_t>(addr) + size};
      pthread_attr_destroy(&a);
    }
    return r;
  }();
  return main;
}
}  // namespace

namespace stc::vm {
void setProgramMemory(const void* image, uint64_t bytes) {
  tImageLo = reinterpret_cast<uintptr_t>(image);
  tImageHi = tImageLo + bytes;
}
}  // namespace stc::vm

namespace stc::vm {
[[noreturn]] void raiseFault(uint32_t site, const char* code, std::string message) {
  stc::vm::FaultInfo info;
  info.site = site;
  info.code = code;
  info.message = std::move(message);
  // The callers, innermost first, from the task's call chain.
  const stc::vm::CallChain& chain = *__stc_calls;
  for (uint32_t k = 0; k < chain.depth && k < 64; ++k) info.callers.push_back(chain.sites[(chain.depth - 1 - k) % 64]);
  if (auto* s = stc::vm::Scheduler::current()) s->fault(std::move(info));
  if (tOutsideHandler) tOutsideHandler(std::move(info));
  // Outside a task with no handler: nothing can be stopped safely.
  std::fprintf(stderr, "stc: runtime fault outside a task: %s\n", info.message.c_str());
  std::_Exit(3);
}
}  // namespace stc::vm

namespace {

template <typename C>
size_t length(const C* s) {
  return std::char_traits<C>::length(s);   // strlen for STRING: vectorised by libc
}
}  // namespace

namespace stc::vm {
bool outsideTaskFaultHandlerSet() { return tOutsideHandler != nullptr; }
OutsideTaskFaultHandler setOutsideTaskFaultHandler(OutsideTaskFaultHandler h) {
  OutsideTaskFaultHandler prev = tOutsideHandler;
  tOutsideHandler = h;
  return prev;
}
}  // namespace stc::vm

extern "C" {

// libgcc's helpers for llvm.powi.
double __powidf2(double, int);
float __powisf2(float, int);

[[noreturn]] void __stc_fault(uint32_t site, uint32_t kind) {
  auto k = static_cast<FaultKind>(kind);
  const char* msg = "runtime fault";
  switch (k) {
    case FaultKind::DivisionByZero: msg = "division by zero"; break;
    case FaultKind::NullPointer: msg = "dereference of a NULL pointer"; break;
    case FaultKind::NullReference: msg = "use of an unassigned reference"; break;
    case FaultKind::NullInterface: msg = "call through a NULL interface"; break;
    case FaultKind::UnboundInOut: msg = "VAR_IN_OUT is not bound"; break;
    case FaultKind::ForStepZero: msg = "FOR loop with step 0 would never end"; break;
    case FaultKind::BadVtable:
      msg = "call through a corrupted function block instance (its hidden vtable pointer is not one of the program's)";
      break;
    default: break;
  }
  raise(site, k, msg);
}

// MEMCPY & co. (always) and dereferences (--check-pointers): [p, p + n) must lie in
// the program's image or in the running task's stack.
void __stc_check_ptr(uint32_t site, const uint8_t* p, uint64_t n) {
  auto a = reinterpret_cast<uintptr_t>(p);
  if (!p) raise(site, FaultKind::NullPointer, "dereference of a NULL pointer");
  auto inside = [&](uintptr_t lo, uintptr_t hi) { return a >= lo && a <= hi && n <= hi - a; };
  if (inside(tImageLo, tImageHi)) return;
  auto [slo, shi] = currentStack();
  if (inside(slo, shi)) return;
  char hex[32];
  std::snprintf(hex, sizeof hex, "16#%llX", static_cast<unsigned long long>(a));
  raise(site, FaultKind::PointerRange,
        std::string("pointer ") + hex + " to " + std::to_string(n) + " bytes lies outside the program's memory (its image and the task's stack)");
}

[[noreturn]] void __stc_fault_index(uint32_t site, int64_t v, int64_t lo, int64_t hi) {
  raise(site, FaultKind::Index, "index " + std::to_string(v) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
}

[[noreturn]] void __stc_fault_range(uint32_t site, int64_t v, int64_t lo, int64_t hi) {
  raise(site, FaultKind::Subrange, "value " + std::to_string(v) + " is outside the subrange " + std::to_string(lo) + ".." + std::to_string(hi));
}

void __stc_safepoint(uint32_t site) {
  if (auto* s = stc::vm::Scheduler::current()) s->safepoint(site);
  else __stc_budget = INT64_MAX / 2;   // outside a task (dynamic initialisation)
}

// STRING(cap): at most cap bytes and a NUL.  Assignment truncates.
void __stc_str_assign(char* dst, int64_t cap, const char* src) {
  size_t n = std::min<size_t>(length(src), static_cast<size_t>(cap));
  std::memmove(dst, src, n);
  dst[n] = 0;
}
void __stc_str_append(char* dst, int64_t cap, const char* src) {
  size_t have = length(dst);
  size_t n = std::min<size_t>(length(src), static_cast<size_t>(cap) - std::min<size_t>(have, static_cast<size_t>(cap)));
  std::memmove(dst + have, src, n);
  dst[have + n] = 0;
}
int32_t __stc_str_cmp(const char* a, const char* b) {
  int c = std::strcmp(a, b);
  return c < 0 ? -1 : c > 0 ? 1 : 0;
}
int64_t __stc_str_len(const char* s) { return static_cast<int64_t>(length(s)); }

// The standard string functions (IEC 61131-3 table 29; positions are
// 1-based; out-of-range arguments clamp, as CODESYS does).  Results are
// composed from pieces of the arguments; the destination may alias an
// argument (t := INSERT(t, ...)), so overlapping pieces are staged first.
}  // extern "C"

namespace {
template <typename C>
struct Piece {
  const C* p;
  size_t n;
};

template <typename C>
void compose(C* dst, int64_t cap, std::initializer_list<Piece<C>> parts) {
  size_t total = 0;
  bool overlap = false;
  for (const Piece<C>& x : parts) {
    total += x.n;
    overlap = overlap || (x.n && x.p < dst + cap + 1 && dst < x.p + x.n);
  }
  size_t keep = std::min<size_t>(total, static_cast<size_t>(cap));
  C stage[512];
  std::basic_string<C> big;
  C* out = dst;
  if (overlap) {
    if (keep <= 512) out = stage;
    else { big.resize(keep); out = big.data(); }
  }
  size_t at = 0;
  for (const Piece<C>& x : parts) {
    size_t k = std::min(x.n, keep - at);
    std::memmove(out + at, x.p, k * sizeof(C));
    at += k;
  }
  if (overlap) std::memcpy(dst, out, keep * sizeof(C));
  dst[keep] = 0;
}

template <typename C>
void strLeft(C* dst, int64_t cap, const C* s, int64_t n) {
  size_t len = length(s);
  compose<C>(dst, cap, {{s, n < 0 ? 0 : std::min<size_t>(static_cast<size_t>(n), len)}});
}
template <typename C>
void strRight(C* dst, int64_t cap, const C* s, int64_t n) {
  size_t len = length(s);
  size_t k = n < 0 ? 0 : std::min<size_t>(static_cast<size_t>(n), len);
  compose<C>(dst, cap, {{s + len - k, k}});
}
template <typename C>
void strMid(C* dst, int64_t cap, const C* s, int64_t n, int64_t pos) {
  size_t len = length(s);
  if (pos < 1 || static_cast<size_t>(pos) > len || n <= 0) { dst[0] = 0; return; }
  size_t from = static_cast<size_t>(pos - 1);
  compose<C>(dst, cap, {{s + from, std::min<size_t>(static_cast<size_t>(n), len - from)}});
}
template <typename C>
int64_t strFind(const C* s1, const C* s2) {
  size_t l1 = length(s1), l2 = length(s2);
  if (!l2 || l2 > l1) return 0;
  if constexpr (sizeof(C) == 1) {
    const char* p = std::strstr(s1, s2);
    return p ? p - s1 + 1 : 0;
  }
  for (size_t i = 0; i + l2 <= l1; ++i)
    if (s1[i] == s2[0] && std::memcmp(s1 + i, s2, l2 * sizeof(C)) == 0) return static_cast<int64_t>(i) + 1;
  return 0;
}
template <typename C>
void strInsert(C* dst, int64_t cap, const C* a, const C* b, int64_t pos) {
  size_t la = length(a), lb = length(b);
  size_t p = pos < 0 ? 0 : std::min<size_t>(static_cast<size_t>(pos), la);
  compose<C>(dst, cap, {{a, p}, {b, lb}, {a + p, la - p}});
}
template <typename C>
void strDelete(C* dst, int64_t cap, const C* s, int64_t n, int64_t pos) {
  size_t len = length(s);
  if (pos < 1 || static_cast<size_t>(pos) > len || n <= 0) { compose<C>(dst, cap, {{s, len}}); return; }
  size_t p = static_cast<size_t>(pos - 1);
  size_t k = std::min<size_t>(static_cast<size_t>(n), len - p);
  compose<C>(dst, cap, {{s, p}, {s + p + k, len - p - k}});
}
template <typename C>
void strReplace(C* dst, int64_t cap, const C* a, const C* b, int64_t n, int64_t pos) {
  size_t la = length(a), lb = length(b);
  if (pos < 1) pos = 1;
  size_t p = std::min<size_t>(static_cast<size_t>(pos - 1), la);
  size_t k = n < 0 ? 0 : std::min<size_t>(static_cast<size_t>(n), la - p);
  compose<C>(dst, cap, {{a, p}, {b, lb}, {a + p + k, la - p - k}});
}

}  // namespace

extern "C" {

void __stc_str_left(char* dst, int64_t cap, const char* s, int64_t n) { strLeft(dst, cap, s, n); }
void __stc_str_right(char* dst, int64_t cap, const char* s, int64_t n) { strRight(dst, cap, s, n); }
void __stc_str_mid(char* dst, int64_t cap, const char* s, int64_t n, int64_t pos) { strMid(dst, cap, s, n, pos); }
int64_t __stc_str_find(const char* s1, const char* s2) { return strFind(s1, s2); }
void __stc_str_insert(char* dst, int64_t cap, const char* s1, const char* s2, int64_t pos) { strInsert(dst, cap, s1, s2, pos); }
void __stc_str_delete(char* dst, int64_t cap, const char* s, int64_t n, int64_t pos) { strDelete(dst, cap, s, n, pos); }
void __stc_str_replace(char* dst, int64_t cap, const char* s1, const char* s2, int64_t n, int64_t pos) { strReplace(dst, cap, s1, s2, n, pos); }

// Builds the result in a scratch buffer: dst may alias an argument.
static void build(char* dst, int64_t cap, const std::string& r) {
  size_t k = std::min<size_t>(r.size(), static_cast<size_t>(cap));
  std::memcpy(dst, r.data(), k);
  dst[k] = 0;
}
void __stc_int_to_str(char* dst, int64_t cap, int64_t v, int32_t isSigned) {
  build(dst, cap, isSigned ? std::to_string(v) : std::to_string(static_cast<uint64_t>(v)));
}
void __stc_real_to_str(char* dst, int64_t cap, double v, int32_t single) { build(dst, cap, stc::vm::formatReal(v, single != 0)); }
void __stc_bool_to_str(char* dst, int64_t cap, int32_t v) { build(dst, cap, v ? "TRUE" : "FALSE"); }
void __stc_time_to_str(char* dst, int64_t cap, int64_t v, int32_t isLong) { build(dst, cap, stc::vm::formatIecTime(v, isLong ? "LTIME#" : "T#")); }
// STRING_TO_<int>: leading blanks, an optional sign, decimal digits (or a
// 16#/8#/2# prefix); anything else ends the number.  No digits: 0.
int64_t __stc_str_to_int(const char* s) {
  while (*s == ' ' || *s == '\t') ++s;
  bool neg = false;
  if (*s == '+' || *s == '-') neg = *s++ == '-';
  int base = 10;
  if ((s[0] == '1' && s[1] == '6' && s[2] == '#')) { base = 16; s += 3; }
  else if (s[0] == '8' && s[1] == '#') { base = 8; s += 2; }
  else if (s[0] == '2' && s[1] == '#') { base = 2; s += 2; }
  uint64_t v = 0;
  for (;; ++s) {
    int d = *s >= '0' && *s <= '9' ? *s - '0' : *s >= 'a' && *s <= 'f' ? *s - 'a' + 10 : *s >= 'A' && *s <= 'F' ? *s - 'A' + 10 : *s == '_' ? -2 : -1;
    if (d == -2) continue;
    if (d < 0 || d >= base) break;
    v = v * static_cast<uint64_t>(base) + static_cast<uint64_t>(d);
  }
  // Negated as unsigned (C++20: modular conversion): '-9223372036854775808' is LINT's minimum.
  return static_cast<int64_t>(neg ? 0 - v : v);
}
double __stc_str_to_real(const char* s) { return std::strtod(s, nullptr); }
int32_t __stc_str_is_true(const char* s) {
  while (*s == ' ') ++s;
  return (s[0] == 'T' || s[0] == 't') && (s[1] == 'R' || s[1] == 'r') && (s[2] == 'U' || s[2] == 'u') && (s[3] == 'E' || s[3] == 'e') && !s[4];
}

// ---- BCD: one decimal digit per nibble ----
uint64_t __stc_to_bcd(uint64_t v) {
  uint64_t r = 0;
  for (int shift = 0; v && shift < 64; shift += 4, v /= 10) r |= (v % 10) << shift;
  return r;
}
uint64_t __stc_from_bcd(uint64_t v) {
  uint64_t r = 0, scale = 1;
  for (; v; v >>= 4, scale *= 10) r += (v & 15) * scale;
  return r;
}
int32_t __stc_is_valid_bcd(uint64_t v) {
  for (; v; v >>= 4)
    if ((v & 15) > 9) return 0;
  return 1;
}

// ---- dates (ns since 1970-01-01) ----
int64_t __stc_date_make(int64_t y, int64_t m, int64_t d) {
  return stc::vm::daysFromCivil(y, static_cast<unsigned>(m), static_cast<unsigned>(d)) * 86'400'000'000'000;
}
int64_t __stc_tod_make(int64_t h, int64_t m, int64_t s, int64_t ms) { return (((h * 60 + m) * 60 + s) * 1000 + ms) * 1'000'000; }
// out: year, month, day, hour, minute, second, millisecond
void __stc_date_split(int64_t ns, int64_t* out) {
  const int64_t day = 86'400'000'000'000;
  int64_t days = ns >= 0 ? ns / day : -((-ns + day - 1) / day);
  int64_t rest = ns - days * day;
  int64_t y;
  unsigned m, d;
  stc::vm::civilFromDays(days, y, m, d);
  out[0] = y;
  out[1] = m;
  out[2] = d;
  out[3] = rest / 3'600'000'000'000;
  out[4] = rest / 60'000'000'000 % 60;
  out[5] = rest / 1'000'000'000 % 60;
  out[6] = rest / 1'000'000 % 1000;
}
// 0 = Sunday (IEC 61131-3).
int64_t __stc_day_of_week(int64_t ns) {
  const int64_t day = 86'400'000'000'000;
  int64_t days = ns >= 0 ? ns / day : -((-ns + day - 1) / day);
  int64_t w = (days + 4) % 7;   // 1970-01-01 was a Thursday
  return w < 0 ? w + 7 : w;
}
// kind: 'D' date, 'T' time of day, 'S' date and time; isLong: the L* prefix.
void __stc_date_to_str(char* dst, int64_t cap, int64_t ns, int32_t kind, int32_t isLong) {
  std::string r = kind == 'D' ? std::string(isLong ? "LDATE#" : "D#") + stc::vm::formatDate(ns)
                  : kind == 'T' ? std::string(isLong ? "LTOD#" : "TOD#") + stc::vm::formatTimeOfDay(ns)
                                : std::string(isLong ? "LDT#" : "DT#") + stc::vm::formatDate(ns) + "-" + stc::vm::formatTimeOfDay(ns);
  build(dst, cap, r);
}
int64_t __stc_str_to_date(const char* s, int32_t kind) {
  int64_t ns = 0;
  return stc::vm::parseDateText(s, static_cast<char>(kind), ns) ? ns : 0;
}
int64_t __stc_str_to_time(const char* s) {
  int64_t ns = 0;
  return stc::vm::parseIecDuration(s, ns) ? ns : 0;
}

// ---- STRING <-> WSTRING ----
// STRING bytes are UTF-8 when valid, else Latin-1; WSTRING is UTF-16.
void __stc_str_to_wstr(char16_t* dst, int64_t cap, const char* src) {
  std::string b(src);
  std::vector<uint32_t> cps;
  bool utf8 = stc::isValidUtf8(b);
  for (size_t i = 0; i < b.size();) {
    auto c = static_cast<unsigned char>(b[i]);
    uint32_t cp = c;
    int n = (!utf8 || c < 0x80) ? 0 : c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : 1;
    if (n) cp = c & (0x3F >> n);
    ++i;
    for (int k = 0; k < n && i < b.size(); ++k, ++i) cp = (cp << 6) | (static_cast<unsigned char>(b[i]) & 63);
    cps.push_back(cp);
  }
  std::u16string w;
  for (uint32_t cp : cps) {
    if (cp >= 0x10000) { cp -= 0x10000; w.push_back(static_cast<char16_t>(0xD800 + (cp >> 10))); w.push_back(static_cast<char16_t>(0xDC00 + (cp & 0x3FF))); }
    else w.push_back(static_cast<char16_t>(cp));
  }
  size_t k = std::min<size_t>(w.size(), static_cast<size_t>(cap));
  std::memcpy(dst, w.data(), k * 2);
  dst[k] = 0;
}
void __stc_wstr_to_str(char* dst, int64_t cap, const char16_t* src) {
  std::vector<uint32_t> cps;
  for (size_t i = 0; src[i]; ++i) {
    uint32_t u = src[i];
    if (u >= 0xD800 && u < 0xDC00 && src[i + 1] >= 0xDC00 && src[i + 1] < 0xE000) { u = 0x10000 + ((u - 0xD800) << 10) + (src[i + 1] - 0xDC00); ++i; }
    cps.push_back(u);
  }
  bool latin1 = true;
  for (uint32_t cp : cps) latin1 = latin1 && cp <= 0xFF;
  std::string r;
  for (uint32_t cp : cps) {
    if (latin1) { r.push_back(static_cast<char>(cp)); continue; }
    if (cp < 0x80) r.push_back(static_cast<char>(cp));
    else if (cp < 0x800) { r.push_back(static_cast<char>(0xC0 | (cp >> 6))); r.push_back(static_cast<char>(0x80 | (cp & 63))); }
    else if (cp < 0x10000) { r.push_back(static_cast<char>(0xE0 | (cp >> 12))); r.push_back(static_cast<char>(0x80 | ((cp >> 6) & 63))); r.push_back(static_cast<char>(0x80 | (cp & 63))); }
    else { r.push_back(static_cast<char>(0xF0 | (cp >> 18))); r.push_back(static_cast<char>(0x80 | ((cp >> 12) & 63))); r.push_back(static_cast<char>(0x80 | ((cp >> 6) & 63))); r.push_back(static_cast<char>(0x80 | (cp & 63))); }
  }
  build(dst, cap, r);
}

// ---- WSTRING functions: the same rules as the STRING ones, in UTF-16 units ----
void __stc_wstr_left(char16_t* dst, int64_t cap, const char16_t* s, int64_t n) { strLeft(dst, cap, s, n); }
void __stc_wstr_right(char16_t* dst, int64_t cap, const char16_t* s, int64_t n) { strRight(dst, cap, s, n); }
void __stc_wstr_mid(char16_t* dst, int64_t cap, const char16_t* s, int64_t n, int64_t pos) { strMid(dst, cap, s, n, pos); }
int64_t __stc_wstr_find(const char16_t* s1, const char16_t* s2) { return strFind(s1, s2); }
void __stc_wstr_insert(char16_t* dst, int64_t cap, const char16_t* s1, const char16_t* s2, int64_t pos) { strInsert(dst, cap, s1, s2, pos); }
void __stc_wstr_delete(char16_t* dst, int64_t cap, const char16_t* s, int64_t n, int64_t pos) { strDelete(dst, cap, s, n, pos); }
void __stc_wstr_replace(char16_t* dst, int64_t cap, const char16_t* s1, const char16_t* s2, int64_t n, int64_t pos) {
  strReplace(dst, cap, s1, s2, n, pos);
}

void __stc_wstr_assign(char16_t* dst, int64_t cap, const char16_t* src) {
  size_t n = std::min<size_t>(length(src), static_cast<size_t>(cap));
  std::memmove(dst, src, n * 2);
  dst[n] = 0;
}
void __stc_wstr_append(char16_t* dst, int64_t cap, const char16_t* src) {
  size_t have = length(dst);
  size_t n = std::min<size_t>(length(src), static_cast<size_t>(cap) - std::min<size_t>(have, static_cast<size_t>(cap)));
  std::memmove(dst + have, src, n * 2);
  dst[have + n] = 0;
}
int32_t __stc_wstr_cmp(const char16_t* a, const char16_t* b) {
  for (;; ++a, ++b) {
    if (*a != *b) return *a < *b ? -1 : 1;
    if (!*a) return 0;
  }
}
int64_t __stc_wstr_len(const char16_t* s) { return static_cast<int64_t>(length(s)); }

}  // extern "C"

namespace stc::vm {

std::map<std::string, void*> runtimeSymbols() {
  std::map<std::string, void*> m;
#define STC_SYM(name) m[#name] = reinterpret_cast<void*>(&name)
  STC_SYM(__stc_fault);
  STC_SYM(__stc_fault_index);
  STC_SYM(__stc_fault_range);
  STC_SYM(__stc_safepoint);
  STC_SYM(__stc_str_assign);
  STC_SYM(__stc_str_append);
  STC_SYM(__stc_str_cmp);
  STC_SYM(__stc_str_len);
  STC_SYM(__stc_str_left);
  STC_SYM(__stc_str_right);
  STC_SYM(__stc_str_mid);
  STC_SYM(__stc_str_find);
  STC_SYM(__stc_str_insert);
  STC_SYM(__stc_str_delete);
  STC_SYM(__stc_str_replace);
  STC_SYM(__stc_int_to_str);
  STC_SYM(__stc_real_to_str);
  STC_SYM(__stc_bool_to_str);
  STC_SYM(__stc_time_to_str);
  STC_SYM(__stc_str_to_int);
  STC_SYM(__stc_str_to_real);
  STC_SYM(__stc_str_is_true);
  STC_SYM(__stc_to_bcd);
  STC_SYM(__stc_from_bcd);
  STC_SYM(__stc_is_valid_bcd);
  STC_SYM(__stc_date_make);
  STC_SYM(__stc_tod_make);
  STC_SYM(__stc_date_split);
  STC_SYM(__stc_day_of_week);
  STC_SYM(__stc_date_to_str);
  STC_SYM(__stc_str_to_date);
  STC_SYM(__stc_str_to_time);
  STC_SYM(__stc_str_to_wstr);
  STC_SYM(__stc_wstr_to_str);
  STC_SYM(__stc_wstr_left);
  STC_SYM(__stc_wstr_right);
  STC_SYM(__stc_wstr_mid);
  STC_SYM(__stc_wstr_find);
  STC_SYM(__stc_wstr_insert);
  STC_SYM(__stc_wstr_delete);
  STC_SYM(__stc_wstr_replace);
  STC_SYM(__stc_wstr_assign);
  STC_SYM(__stc_wstr_append);
  STC_SYM(__stc_wstr_cmp);
  STC_SYM(__stc_wstr_len);
  m["__stc_budget"] = &__stc_budget;
  m["__stc_calls"] = &__stc_calls;
  m["__stc_site"] = &__stc_site;
  STC_SYM(__stc_check_ptr);
#undef STC_SYM
  // What LLVM lowers intrinsics and loops to.
  m["memcpy"] = reinterpret_cast<void*>(static_cast<void* (*)(void*, const void*, size_t)>(&std::memcpy));
  m["memmove"] = reinterpret_cast<void*>(static_cast<void* (*)(void*, const void*, size_t)>(&std::memmove));
  m["memset"] = reinterpret_cast<void*>(static_cast<void* (*)(void*, int, size_t)>(&std::memset));
  m["memcmp"] = reinterpret_cast<void*>(static_cast<int (*)(const void*, const void*, size_t)>(&std::memcmp));
  using F = float (*)(float);
  using D = double (*)(double);
  using F2 = float (*)(float, float);
  using D2 = double (*)(double, double);
#define STC_MATH(name) m[#name] = reinterpret_cast<void*>(static_cast<D>(&::name)); m[#name "f"] = reinterpret_cast<void*>(static_cast<F>(&::name##f))
  STC_MATH(sin); STC_MATH(cos); STC_MATH(tan); STC_MATH(asin); STC_MATH(acos); STC_MATH(atan);
  STC_MATH(exp); STC_MATH(exp2); STC_MATH(log); STC_MATH(log10); STC_MATH(log2); STC_MATH(sqrt);
  STC_MATH(round); STC_MATH(trunc); STC_MATH(floor); STC_MATH(ceil); STC_MATH(fabs);
#undef STC_MATH
  m["pow"] = reinterpret_cast<void*>(static_cast<D2>(&::pow));
  m["powf"] = reinterpret_cast<void*>(static_cast<F2>(&::powf));
  m["atan2"] = reinterpret_cast<void*>(static_cast<D2>(&::atan2));
  m["atan2f"] = reinterpret_cast<void*>(static_cast<F2>(&::atan2f));
  m["sincos"] = reinterpret_cast<void*>(static_cast<void (*)(double, double*, double*)>(&::sincos));
  m["sincosf"] = reinterpret_cast<void*>(static_cast<void (*)(float, float*, float*)>(&::sincosf));
  m["__powidf2"] = reinterpret_cast<void*>(&__powidf2);
  m["__powisf2"] = reinterpret_cast<void*>(&__powisf2);
  m["fmod"] = reinterpret_cast<void*>(static_cast<D2>(&::fmod));
  m["fmodf"] = reinterpret_cast<void*>(static_cast<F2>(&::fmodf));
  return m;
}

}  // namespace stc::vm
