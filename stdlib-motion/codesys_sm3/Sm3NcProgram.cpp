// Sm3NcProgram.h: the SMC_CNC_REF check and the program file reader.
#include "stdlib-motion/codesys_sm3/Sm3NcProgram.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <iostream>

#include "vm/FileSandbox.h"

namespace stc::motion::sm3face {

bool usableCncRef(const MotionSession& s, const sm3::SMC_CNC_REF* p) {
  return p && s.inImage(p, sizeof *p) && p->wCNCREFStructID == kCncRefStructId && p->dwTextSize <= kMaxNcProgramBytes &&
         (p->dwTextSize == 0 || s.inImage(p->pText, p->dwTextSize) || s.inHeldProgram(p->pText, p->dwTextSize));
}

NcFileRead readNcFile(const MotionSession& s, const std::string& name, uint64_t maxBytes, std::string& text, uint64_t& size) {
  size = 0;
  std::string why;
  const int fd = name.empty() ? -1 : stc::vm::openInside(s.filesDir(), name, stc::vm::FileAccess::Read, why);
  if (fd < 0) return NcFileRead::Missing;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return NcFileRead::Missing;
  }
  size = static_cast<uint64_t>(st.st_size);
  switch (stc::vm::readAndClose(fd, maxBytes, text)) {
  case stc::vm::ReadResult::Ok: return NcFileRead::Ok;
  case stc::vm::ReadResult::TooBig: return NcFileRead::TooBig;
  case stc::vm::ReadResult::Failed: break;
  }
  return NcFileRead::Missing;
}

bool usableVarList(const MotionSession& s, const void* list) {
  const auto* p = static_cast<const sm3::SMC_VARLIST*>(list);
  if (!p || !s.inImage(p, sizeof *p) || p->wVarListID != kVarListId) return false;
  if (p->nNumberOfVariables < 0 || p->nNumberOfVariables > kMaxVarListEntries) return false;
  return p->nNumberOfVariables == 0 ||
         s.inImage(p->psvVarList, static_cast<uint64_t>(p->nNumberOfVariables) * sizeof(sm3::SMC_SINGLEVAR));
}

namespace {

using Kind = NcVariables::Kind;

std::string lower(std::string_view t) {
  std::string r(t);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

struct KindInfo {
  Kind kind;
  const char* type;       // the IEC name
  unsigned size;          // bytes
  double lo, hi;          // the values it holds (integers: exactly)
};
constexpr KindInfo kKinds[] = {
    {Kind::Bool, "BOOL", 1, 0, 1},
    {Kind::S8, "SINT", 1, -128, 127},
    {Kind::S16, "INT", 2, -32768, 32767},
    {Kind::S32, "DINT", 4, -2147483648.0, 2147483647.0},
    {Kind::S64, "LINT", 8, -9223372036854775808.0, 9223372036854774784.0},   // the largest double below 2^63
    {Kind::U8, "USINT", 1, 0, 255},
    {Kind::U16, "UINT", 2, 0, 65535},
    {Kind::U32, "UDINT", 4, 0, 4294967295.0},
    {Kind::U64, "ULINT", 8, 0, 18446744073709549568.0},                      // the largest double below 2^64
    {Kind::F32, "REAL", 4, -FLT_MAX, FLT_MAX},
    {Kind::F64, "LREAL", 8, -DBL_MAX, DBL_MAX},
};
const KindInfo& info(Kind k) {
  for (const KindInfo& i : kKinds)
    if (i.kind == k) return i;
  return kKinds[0];
}

// The kind of a declared type name; the bit-string types read as the unsigned of their size.
Kind kindOfType(const std::string& t) {
  static const std::pair<const char*, Kind> names[] = {
      {"BOOL", Kind::Bool}, {"SINT", Kind::S8},  {"INT", Kind::S16},   {"DINT", Kind::S32}, {"LINT", Kind::S64},
      {"USINT", Kind::U8},  {"UINT", Kind::U16}, {"UDINT", Kind::U32}, {"ULINT", Kind::U64}, {"BYTE", Kind::U8},
      {"WORD", Kind::U16},  {"DWORD", Kind::U32}, {"LWORD", Kind::U64}, {"REAL", Kind::F32}, {"LREAL", Kind::F64}};
  for (const auto& [n, k] : names)
    if (t == n) return k;
  return Kind::None;
}

// SMC_TYPECLASS (sm3_cnc_types.st) -> kind.
Kind kindOfClass(int c) {
  switch (c) {
  case 0: return Kind::Bool;
  case 2: return Kind::U8;
  case 3: return Kind::U16;
  case 4: return Kind::U32;
  case 5: return Kind::U64;
  case 6: return Kind::S8;
  case 7: return Kind::S16;
  case 8: return Kind::S32;
  case 9: return Kind::S64;
  case 10: return Kind::U8;
  case 11: return Kind::U16;
  case 12: return Kind::U32;
  case 13: return Kind::U64;
  case 14: return Kind::F32;
  case 15: return Kind::F64;
  default: return Kind::None;
  }
}

template <class T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class T>
void store(uint8_t* p, T v) {
  std::memcpy(p, &v, sizeof v);
}

}  // namespace

NcVariables::NcVariables(const MotionSession& s, const void* vl) : session_(s) {
  const auto* list = static_cast<const sm3::SMC_VARLIST*>(vl);
  if (!list) return;
  const auto* e = static_cast<const sm3::SMC_SINGLEVAR*>(list->psvVarList);
  for (int i = 0; i < list->nNumberOfVariables; ++i) {
    const std::string name(e[i].strVarName, strnlen(e[i].strVarName, sizeof e[i].strVarName));
    Var v;
    v.kind = kindOfClass(static_cast<int>(e[i].eVarType));
    v.address = static_cast<uint8_t*>(e[i].pAdr);
    if (v.kind == Kind::None) {
      v.problem = "its SMC_VARLIST entry has the type class " + std::to_string(static_cast<int>(e[i].eVarType)) +
                  ", not a number (TYPE_BOOL, the integers, TYPE_REAL or TYPE_LREAL)";
    } else if (!s.inImage(v.address, info(v.kind).size)) {
      v.kind = Kind::None;
      v.problem = "its SMC_VARLIST entry points outside the controller's static memory";
    }
    list_.emplace_back(lower(name), std::move(v));
  }
}

const NcVariables::Var& NcVariables::find(std::string_view name) {
  std::string key = lower(name);
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  for (const auto& [n, v] : list_)
    if (n == key) return cache_.emplace(key, v).first->second;
  Var v;
  vm::StartCtx::Variable found;
  std::string error;
  if (!session_.findVariable(std::string(name), found, error)) {
    // "no variable named 'x'; did you mean 'y'?" is an unknown name; anything else (a bad
    // index, a member that does not exist) is the reason.
    if (error.rfind("no variable named", 0) == 0) {
      if (size_t at = error.find("did you mean '"); at != std::string::npos) {
        at += 14;
        v.hint = error.substr(at, error.find('\'', at) - at);
      }
    } else {
      v.problem = error;
    }
  } else {
    v.kind = kindOfType(found.typeName);
    v.address = found.address;
    v.bit = found.bit;
    v.constant = found.constant;
    if (v.kind == Kind::None) v.problem = "its type " + found.typeName + " is not a number (BOOL, the integers, REAL or LREAL)";
  }
  return cache_.emplace(std::move(key), std::move(v)).first->second;
}

bool NcVariables::read(std::string_view name, double& out) {
  const Var& v = find(name);
  problem_ = v.problem;
  if (v.kind == Kind::None) return false;
  const uint8_t* p = v.address;
  switch (v.kind) {
  case Kind::Bool: out = v.bit >= 0 ? ((*p >> v.bit) & 1) : (*p != 0); break;
  case Kind::S8: out = load<int8_t>(p); break;
  case Kind::S16: out = load<int16_t>(p); break;
  case Kind::S32: out = load<int32_t>(p); break;
  case Kind::S64: out = static_cast<double>(load<int64_t>(p)); break;
  case Kind::U8: out = load<uint8_t>(p); break;
  case Kind::U16: out = load<uint16_t>(p); break;
  case Kind::U32: out = load<uint32_t>(p); break;
  case Kind::U64: out = static_cast<double>(load<uint64_t>(p)); break;
  case Kind::F32: out = load<float>(p); break;
  case Kind::F64: out = load<double>(p); break;
  case Kind::None: return false;
  }
  return true;
}

bool NcVariables::write(std::string_view name, double d) {
  const Var& v = find(name);
  problem_ = v.problem;
  if (v.kind == Kind::None) return false;
  if (v.constant) {
    problem_ = "it is a CONSTANT or a process input";
    return false;
  }
  const KindInfo& k = info(v.kind);
  const bool integral = v.kind != Kind::F32 && v.kind != Kind::F64;
  if (!std::isfinite(d) || d < k.lo || d > k.hi || (integral && d != std::trunc(d))) {
    problem_ = std::string(k.type) + (integral ? " holds the integers from " : " holds the values from ") + stc::cnc::formatNumber(k.lo) +
               " to " + stc::cnc::formatNumber(k.hi) + ", not " + stc::cnc::formatNumber(d);
    return false;
  }
  uint8_t* p = v.address;
  switch (v.kind) {
  case Kind::Bool:
    if (v.bit >= 0) *p = static_cast<uint8_t>(d != 0 ? (*p | (1u << v.bit)) : (*p & ~(1u << v.bit)));
    else *p = d != 0;
    break;
  case Kind::S8: store(p, static_cast<int8_t>(d)); break;
  case Kind::S16: store(p, static_cast<int16_t>(d)); break;
  case Kind::S32: store(p, static_cast<int32_t>(d)); break;
  case Kind::S64: store(p, static_cast<int64_t>(d)); break;
  case Kind::U8: store(p, static_cast<uint8_t>(d)); break;
  case Kind::U16: store(p, static_cast<uint16_t>(d)); break;
  case Kind::U32: store(p, static_cast<uint32_t>(d)); break;
  case Kind::U64: store(p, static_cast<uint64_t>(d)); break;
  case Kind::F32: store(p, static_cast<float>(d)); break;
  case Kind::F64: store(p, d); break;
  case Kind::None: return false;
  }
  return true;
}

std::string NcVariables::suggest(std::string_view name) { return find(name).hint; }

void printNewDiagnostics(const DiagnosticsEngine& diags, size_t& printed) {
  const auto& ds = diags.diagnostics();
  if (printed >= ds.size()) return;
  for (; printed < ds.size(); ++printed) std::cerr << stc::renderText(diags.sourceManager(), ds[printed]);
  std::cerr.flush();
}

}  // namespace stc::motion::sm3face
