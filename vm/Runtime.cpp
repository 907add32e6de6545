#include "vm/Runtime.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "codegen/CodeGen.h"
#include "vm/Scheduler.h"

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
    case FaultKind::DivisionByZero: msg = "integer division by zero"; break;
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
