#include "vm/Runtime.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <algorithm>
#include <cstdlib>

#include "codegen/CodeGen.h"
#include "vm/Image.h"
#include "vm/Scheduler.h"
#include "vm/Time.h"

using stc::codegen::FaultKind;

namespace {

[[noreturn]] void raise(uint32_t site, FaultKind kind, std::string message) {
  stc::vm::FaultInfo info;
  info.site = site;
  info.code = stc::codegen::faultCode(kind);
  info.message = std::move(message);
  if (auto* s = stc::vm::Scheduler::current()) s->fault(std::move(info));
  // Outside a task (dynamic initialisation): nothing can be stopped safely.
  std::fprintf(stderr, "stc: runtime fault outside a task: %s\n", info.message.c_str());
  std::_Exit(3);
}

template <typename C>
size_t length(const C* s) {
  size_t n = 0;
  while (s[n]) ++n;
  return n;
}

}  // namespace

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
    default: break;
  }
  raise(site, k, msg);
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
// 1-based; out-of-range arguments clamp, as CODESYS does).
void __stc_str_left(char* dst, int64_t cap, const char* s, int64_t n) {
  size_t len = length(s);
  size_t k = n < 0 ? 0 : std::min<size_t>(static_cast<size_t>(n), len);
  k = std::min<size_t>(k, static_cast<size_t>(cap));
  std::memmove(dst, s, k);
  dst[k] = 0;
}
void __stc_str_right(char* dst, int64_t cap, const char* s, int64_t n) {
  size_t len = length(s);
  size_t k = n < 0 ? 0 : std::min<size_t>(static_cast<size_t>(n), len);
  size_t c = std::min<size_t>(k, static_cast<size_t>(cap));
  std::memmove(dst, s + len - k, c);
  dst[c] = 0;
}
void __stc_str_mid(char* dst, int64_t cap, const char* s, int64_t n, int64_t pos) {
  size_t len = length(s);
  if (pos < 1 || static_cast<size_t>(pos) > len || n <= 0) { dst[0] = 0; return; }
  size_t from = static_cast<size_t>(pos - 1);
  size_t k = std::min<size_t>(static_cast<size_t>(n), len - from);
  k = std::min<size_t>(k, static_cast<size_t>(cap));
  std::memmove(dst, s + from, k);
  dst[k] = 0;
}
int64_t __stc_str_find(const char* s1, const char* s2) {
  if (!*s2) return 0;
  const char* p = std::strstr(s1, s2);
  return p ? (p - s1) + 1 : 0;
}
// Builds the result in a scratch buffer: dst may alias an argument.
static void build(char* dst, int64_t cap, const std::string& r) {
  size_t k = std::min<size_t>(r.size(), static_cast<size_t>(cap));
  std::memcpy(dst, r.data(), k);
  dst[k] = 0;
}
void __stc_str_insert(char* dst, int64_t cap, const char* s1, const char* s2, int64_t pos) {
  std::string a(s1), b(s2);
  size_t p = pos < 0 ? 0 : std::min<size_t>(static_cast<size_t>(pos), a.size());
  build(dst, cap, a.substr(0, p) + b + a.substr(p));
}
void __stc_str_delete(char* dst, int64_t cap, const char* s, int64_t n, int64_t pos) {
  std::string a(s);
  if (pos < 1 || static_cast<size_t>(pos) > a.size() || n <= 0) { build(dst, cap, a); return; }
  a.erase(static_cast<size_t>(pos - 1), static_cast<size_t>(n));
  build(dst, cap, a);
}
void __stc_str_replace(char* dst, int64_t cap, const char* s1, const char* s2, int64_t n, int64_t pos) {
  std::string a(s1), b(s2);
  if (pos < 1) pos = 1;
  size_t p = std::min<size_t>(static_cast<size_t>(pos - 1), a.size());
  size_t k = n < 0 ? 0 : std::min<size_t>(static_cast<size_t>(n), a.size() - p);
  build(dst, cap, a.substr(0, p) + b + a.substr(p + k));
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
  return neg ? -static_cast<int64_t>(v) : static_cast<int64_t>(v);
}
double __stc_str_to_real(const char* s) { return std::strtod(s, nullptr); }

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
  STC_SYM(__stc_wstr_assign);
  STC_SYM(__stc_wstr_append);
  STC_SYM(__stc_wstr_cmp);
  STC_SYM(__stc_wstr_len);
  m["__stc_budget"] = &__stc_budget;
#undef STC_SYM
  // What LLVM lowers intrinsics and loops to.
  m["memcpy"] = reinterpret_cast<void*>(static_cast<void* (*)(void*, const void*, size_t)>(&std::memcpy));
  m["memmove"] = reinterpret_cast<void*>(static_cast<void* (*)(void*, const void*, size_t)>(&std::memmove));
  m["memset"] = reinterpret_cast<void*>(static_cast<void* (*)(void*, int, size_t)>(&std::memset));
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
