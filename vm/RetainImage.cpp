// Saving and restoring the retained part of the image (docs/vm.md, "Retain"):
// the retained variables are split into leaves (RetainLeaf); a leaf whose type
// changed is converted where no value is lost; every restored value is checked
// against its subrange, enumeration and string capacity; what is dropped,
// converted or not restored is listed as notes.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <set>

#include "sema/Layout.h"
#include "sema/Model.h"
#include "sema/Types.h"
#include "vm/Controller.h"
#include "vm/Retain.h"

namespace stc::vm {
namespace {

const char* qualifier(bool persistent) { return persistent ? " PERSISTENT" : " RETAIN"; }

// "DINT RETAIN" -> "DINT"; the qualifier may change without a conversion.
std::string typeOfSignature(const std::string& sig) {
  for (const char* q : {" PERSISTENT", " RETAIN"}) {
    const size_t n = std::strlen(q);
    if (sig.size() >= n && sig.compare(sig.size() - n, n, q) == 0) return sig.substr(0, sig.size() - n);
  }
  return sig;
}

// ---- the old side of a conversion: a type known only by its signature
enum class Cls { None, Signed, Unsigned, Real, Bool, String, WString };
struct OldScalar {
  Cls cls = Cls::None;
  uint32_t size = 0;     // bytes
  uint32_t capacity = 0; // strings: characters
};

OldScalar oldScalar(const std::string& sig) {
  static const std::map<std::string, std::pair<Cls, uint32_t>> names = {
      {"BOOL", {Cls::Bool, 1}},    {"BIT", {Cls::Bool, 1}},        {"SINT", {Cls::Signed, 1}},   {"INT", {Cls::Signed, 2}},
      {"DINT", {Cls::Signed, 4}},  {"LINT", {Cls::Signed, 8}},     {"USINT", {Cls::Unsigned, 1}}, {"UINT", {Cls::Unsigned, 2}},
      {"UDINT", {Cls::Unsigned, 4}}, {"ULINT", {Cls::Unsigned, 8}}, {"BYTE", {Cls::Unsigned, 1}}, {"WORD", {Cls::Unsigned, 2}},
      {"DWORD", {Cls::Unsigned, 4}}, {"LWORD", {Cls::Unsigned, 8}}, {"REAL", {Cls::Real, 4}},     {"LREAL", {Cls::Real, 8}}};
  OldScalar o;
  if (auto it = names.find(sig); it != names.end()) {
    o.cls = it->second.first;
    o.size = it->second.second;
    return o;
  }
  for (auto [prefix, cls] : {std::pair{"STRING(", Cls::String}, std::pair{"WSTRING(", Cls::WString}}) {
    const size_t n = std::strlen(prefix);
    if (sig.compare(0, n, prefix) == 0 && sig.back() == ')') {
      try {
        o.capacity = static_cast<uint32_t>(std::stoul(sig.substr(n, sig.size() - n - 1)));
      } catch (...) {
        return OldScalar{};
      }
      o.cls = cls;
      o.size = (o.capacity + 1) * (cls == Cls::WString ? 2 : 1);
      return o;
    }
  }
  return o;
}

// "ARRAY[1..10,0..2] OF INT" -> dims and the element signature; false if not an array.
bool oldArray(const std::string& sig, std::vector<sema::Dim>& dims, std::string& element) {
  if (sig.compare(0, 6, "ARRAY[") != 0) return false;
  const size_t close = sig.find("] OF ");
  if (close == std::string::npos) return false;
  std::string d = sig.substr(6, close - 6);
  element = sig.substr(close + 5);
  dims.clear();
  size_t pos = 0;
  while (pos <= d.size()) {
    size_t comma = d.find(',', pos);
    std::string one = d.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    size_t dots = one.find("..");
    if (dots == std::string::npos) return false;
    try {
      sema::Dim dim;
      dim.lo = std::stoll(one.substr(0, dots));
      dim.hi = std::stoll(one.substr(dots + 2));
      if (dim.hi < dim.lo || dim.hi - dim.lo >= (int64_t(1) << 32)) return false;   // (a forged file)
      dims.push_back(dim);
    } catch (...) {
      return false;
    }
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  uint64_t n = 1;
  for (const sema::Dim& dim : dims) {
    n *= static_cast<uint64_t>(dim.hi - dim.lo + 1);
    if (n > (uint64_t(1) << 32)) return false;
  }
  return !dims.empty();
}

Cls newClass(const sema::Type* t) {
  const sema::Type* u = t->underlying();
  if (u->isBool()) return Cls::Bool;
  if (u->isSignedInt()) return Cls::Signed;
  if (u->isUnsignedInt() || u->isBitString()) return Cls::Unsigned;
  if (u->isReal()) return Cls::Real;
  if (u->kind == sema::TypeKind::String) return Cls::String;
  if (u->kind == sema::TypeKind::WString) return Cls::WString;
  return Cls::None;
}

int64_t readSigned(const uint8_t* p, uint32_t size) {
  uint64_t v = 0;
  std::memcpy(&v, p, size);
  if (size < 8 && (v >> (size * 8 - 1)) & 1) v |= ~uint64_t(0) << (size * 8);
  return static_cast<int64_t>(v);
}
uint64_t readUnsigned(const uint8_t* p, uint32_t size) {
  uint64_t v = 0;
  std::memcpy(&v, p, size);
  return v;
}

// Converts one old value into the new scalar type t at dst, when no value is lost.
bool convertScalar(const OldScalar& o, const uint8_t* src, const sema::Type* t, uint32_t newSize, uint8_t* dst) {
  const Cls to = newClass(t);
  if (o.cls == Cls::None || to == Cls::None) return false;
  const sema::Type* u = t->underlying();
  if (o.cls == Cls::Bool || to == Cls::Bool) {
    if (o.cls != to) return false;
    dst[0] = src[0] ? 1 : 0;
    return true;
  }
  if (o.cls == Cls::String || o.cls == Cls::WString || to == Cls::String || to == Cls::WString) {
    if (o.cls != to) return false;
    const uint32_t unit = o.cls == Cls::WString ? 2 : 1;
    uint32_t len = 0;
    while (len <= o.capacity && !(src[len * unit] == 0 && (unit == 1 || src[len * unit + 1] == 0))) ++len;
    if (len > o.capacity || len > u->length) return false;   // no terminator (damaged), or longer than the new capacity
    std::memset(dst, 0, newSize);
    std::memcpy(dst, src, len * unit);
    return true;
  }
  if (to == Cls::Real) {
    double v;
    if (o.cls == Cls::Real) {
      if (o.size == 4) { float f; std::memcpy(&f, src, 4); v = f; }
      else std::memcpy(&v, src, 8);
    } else if (o.cls == Cls::Signed) {
      const int64_t i = readSigned(src, o.size);
      v = static_cast<double>(i);
      if (static_cast<long double>(v) != static_cast<long double>(i)) return false;
    } else {
      const uint64_t i = readUnsigned(src, o.size);
      v = static_cast<double>(i);
      if (static_cast<long double>(v) != static_cast<long double>(i)) return false;
    }
    if (u->kind == sema::TypeKind::Real) {
      const float f = static_cast<float>(v);
      if (!std::isnan(v) && static_cast<double>(f) != v) return false;
      std::memcpy(dst, &f, 4);
    } else {
      std::memcpy(dst, &v, 8);
    }
    return true;
  }
  if (o.cls == Cls::Real) return false;   // REAL -> integer would round
  // Integer -> integer: in range of the new type.
  const unsigned bits = u->bits();
  if (o.cls == Cls::Signed) {
    const int64_t v = readSigned(src, o.size);
    if (to == Cls::Signed) {
      if (bits < 64 && (v < -(int64_t(1) << (bits - 1)) || v >= (int64_t(1) << (bits - 1)))) return false;
    } else if (v < 0 || (bits < 64 && static_cast<uint64_t>(v) >> bits)) {
      return false;
    }
    std::memcpy(dst, &v, newSize);
  } else {
    const uint64_t v = readUnsigned(src, o.size);
    if (to == Cls::Signed ? (bits < 64 ? v >= (uint64_t(1) << (bits - 1)) : v > uint64_t(INT64_MAX)) : (bits < 64 && v >> bits))
      return false;
    std::memcpy(dst, &v, newSize);
  }
  return true;
}

std::string indexText(const std::vector<sema::Dim>& dims, uint64_t linear) {
  std::vector<int64_t> idx(dims.size());
  for (size_t d = dims.size(); d-- > 0;) {
    const uint64_t n = static_cast<uint64_t>(dims[d].hi - dims[d].lo + 1);
    idx[d] = dims[d].lo + static_cast<int64_t>(linear % n);
    linear /= n;
  }
  std::string s = "[";
  for (size_t d = 0; d < idx.size(); ++d) s += (d ? ", " : "") + std::to_string(idx[d]);
  return s + "]";
}

uint64_t elementCount(const std::vector<sema::Dim>& dims) {
  uint64_t n = 1;
  for (const sema::Dim& d : dims) n *= static_cast<uint64_t>(d.hi - d.lo + 1);
  return n;
}

}  // namespace

std::vector<Controller::RetainLeaf> Controller::retainLeaves() const {
  const sema::Layout& layout = *model_.layout;
  std::vector<RetainLeaf> out;
  std::function<void(const std::string&, uint64_t, const sema::Type*, int, bool, int)> leaf =
      [&](const std::string& path, uint64_t off, const sema::Type* t, int bit, bool persistent, int depth) {
        if (!t || depth > 32) return;
        if (bit >= 0) return out.push_back({path, off, t, bit, persistent});
        const sema::Type* u = t->underlying();
        switch (u->kind) {
          case sema::TypeKind::Struct: case sema::TypeKind::FunctionBlock: case sema::TypeKind::Program:
            // Members one by one; the vtable pointer (no type) and VAR_IN_OUT / pointer members are not kept.
            for (const sema::FieldLayout& f : layout.of(u).fields)
              if (f.type && !f.indirect) leaf(path + "." + f.name, off + f.offset, f.type, f.bit, persistent, depth + 1);
            return;
          case sema::TypeKind::Array: {
            const sema::Type* e = u->element;
            while (e && e->underlying()->kind == sema::TypeKind::Array) e = e->underlying()->element;
            if (!e) return;
            const sema::Type* eu = e->underlying();
            if (eu->isPointer() || eu->isReference() || eu->kind == sema::TypeKind::Interface) return;
            if (eu->kind == sema::TypeKind::Struct || eu->kind == sema::TypeKind::FunctionBlock) {
              // An array of structures or FB instances: element by element.
              const uint64_t n = elementCount(u->dims), size = layout.sizeOf(u->element);
              for (uint64_t i = 0; i < n; ++i)
                leaf(path + indexText(u->dims, i), off + i * size, u->element, -1, persistent, depth + 1);
              return;
            }
            return out.push_back({path, off, t, -1, persistent});
          }
          case sema::TypeKind::Pointer: case sema::TypeKind::Reference: case sema::TypeKind::Interface:
            return;   // an address does not survive a restart
          default:
            return out.push_back({path, off, t, -1, persistent});
        }
      };
  for (const RetainRegion& r : retainRegions()) leaf(r.path, r.offset, r.type, -1, r.persistent, 0);
  return out;
}

std::string Controller::leafSignature(const RetainLeaf& l) const {
  return (l.bit >= 0 ? std::string("BIT") : model_.layout->signature(l.type)) + qualifier(l.persistent);
}

std::vector<uint8_t> Controller::leafBytes(const RetainLeaf& l) const {
  if (l.bit >= 0) return {static_cast<uint8_t>((image_[l.offset] >> l.bit) & 1)};
  const uint64_t n = model_.layout->sizeOf(l.type);
  return std::vector<uint8_t>(image_ + l.offset, image_ + l.offset + n);
}

bool Controller::saveRetain(const std::string& file, std::string& error) {
  std::vector<RetainEntry> entries;
  for (const RetainLeaf& l : retainLeaves()) entries.push_back({l.path, leafSignature(l), leafBytes(l)});
  return saveRetainFile(file, entries, error);
}

// The value checks of a restored leaf: a value outside its subrange or enumeration, a
// string without a terminator within its capacity, a BOOL that is neither 0 nor 1 gets
// its initial value back (from the cold image), with a note.
void Controller::checkRestored(const RetainLeaf& l, std::vector<std::string>& notes) {
  if (l.bit >= 0) return;
  const sema::Layout& layout = *model_.layout;
  const sema::Type* t = l.type;
  std::vector<sema::Dim> dims;
  const sema::Type* scalar = t;
  while (scalar->underlying()->kind == sema::TypeKind::Array) {
    const sema::Type* a = scalar->underlying();
    dims.insert(dims.end(), a->dims.begin(), a->dims.end());
    scalar = a->element;
  }
  const uint64_t n = dims.empty() ? 1 : elementCount(dims), size = layout.sizeOf(scalar);
  for (uint64_t i = 0; i < n; ++i) {
    uint8_t* p = image_ + l.offset + i * size;
    std::string problem;
    const sema::Type* u = scalar->underlying();
    if (scalar->kind == sema::TypeKind::Subrange || scalar->kind == sema::TypeKind::Enum) {
      const uint32_t bytes = std::max(1u, u->bits() / 8);
      const bool isSigned = u->isSignedInt();
      const int64_t sv = isSigned ? readSigned(p, bytes) : 0;
      const uint64_t uv = isSigned ? 0 : readUnsigned(p, bytes);
      const std::string text = isSigned ? std::to_string(sv) : std::to_string(uv);
      if (scalar->kind == sema::TypeKind::Subrange) {
        // (the bounds of an unsigned subrange are not negative)
        const bool in = isSigned ? sv >= scalar->lo && sv <= scalar->hi
                                 : uv >= static_cast<uint64_t>(std::max<int64_t>(scalar->lo, 0)) && scalar->hi >= 0 &&
                                       uv <= static_cast<uint64_t>(scalar->hi);
        if (!in) problem = text + " is outside " + scalar->name;
      } else {
        bool known = false;
        for (const auto& [name, value] : scalar->enumValues) known = known || (isSigned ? value == sv : static_cast<uint64_t>(value) == uv);
        if (!known) problem = text + " is not a value of " + scalar->name;
      }
    } else if (u->isString()) {
      const uint32_t unit = u->kind == sema::TypeKind::WString ? 2 : 1;
      bool terminated = false;
      for (uint32_t k = 0; k <= u->length && !terminated; ++k) terminated = p[k * unit] == 0 && (unit == 1 || p[k * unit + 1] == 0);
      if (!terminated) problem = "its length exceeds the capacity of " + layout.signature(u);
    } else if (u->isBool() && p[0] > 1) {
      problem = "the byte " + std::to_string(p[0]) + " is not a BOOL";
    }
    if (problem.empty()) continue;
    std::memcpy(p, coldSnapshot_.data() + (p - image_), size);
    notes.push_back("retained '" + l.path + (dims.empty() ? "" : indexText(dims, i)) + "' was not restored: " + problem +
                    "; it keeps its initial value");
  }
}

// Restores one leaf from an entry whose type differs: element by element for arrays (over
// the common index range), scalar conversions that lose nothing.  False: nothing restored.
bool Controller::convertLeaf(const RetainLeaf& l, const RetainEntry& e, std::string& how) {
  const sema::Layout& layout = *model_.layout;
  const std::string oldSig = typeOfSignature(e.signature);
  if (l.bit >= 0) {
    const OldScalar o = oldScalar(oldSig);
    if (o.cls != Cls::Bool || e.bytes.size() != 1) return false;
    image_[l.offset] = static_cast<uint8_t>((image_[l.offset] & ~(1u << l.bit)) | ((e.bytes[0] ? 1u : 0u) << l.bit));
    return true;
  }
  const sema::Type* u = l.type->underlying();
  std::vector<sema::Dim> oldDims;
  std::string oldElem;
  const bool wasArray = oldArray(oldSig, oldDims, oldElem);
  if (wasArray != (u->kind == sema::TypeKind::Array)) return false;
  if (!wasArray) {
    const OldScalar o = oldScalar(oldSig);
    if (o.cls == Cls::None || e.bytes.size() != o.size) return false;
    std::vector<uint8_t> tmp(layout.sizeOf(l.type));
    if (!convertScalar(o, e.bytes.data(), l.type, static_cast<uint32_t>(tmp.size()), tmp.data())) return false;
    std::memcpy(image_ + l.offset, tmp.data(), tmp.size());
    how = "converted from " + oldSig;
    return true;
  }
  const sema::Type* elem = u->element;
  if (oldDims.size() != u->dims.size() || elem->underlying()->kind == sema::TypeKind::Array) return false;
  const OldScalar o = oldScalar(oldElem);
  const uint64_t oldCount = elementCount(oldDims);
  if (o.cls == Cls::None || e.bytes.size() != oldCount * o.size) return false;
  const uint64_t newSize = layout.sizeOf(elem);
  uint64_t restored = 0, failed = 0;
  const uint64_t newCount = elementCount(u->dims);
  std::vector<uint8_t> tmp(newSize);
  for (uint64_t i = 0; i < newCount; ++i) {
    // The index of new element i, and its place in the old array if it is there.
    uint64_t rest = i, oldLinear = 0, stride = 1;
    bool inside = true;
    std::vector<int64_t> idx(u->dims.size());
    for (size_t d = u->dims.size(); d-- > 0;) {
      const uint64_t n = static_cast<uint64_t>(u->dims[d].hi - u->dims[d].lo + 1);
      idx[d] = u->dims[d].lo + static_cast<int64_t>(rest % n);
      rest /= n;
    }
    for (size_t d = oldDims.size(); d-- > 0;) {
      if (idx[d] < oldDims[d].lo || idx[d] > oldDims[d].hi) inside = false;
      oldLinear += static_cast<uint64_t>(idx[d] - oldDims[d].lo) * stride;
      stride *= static_cast<uint64_t>(oldDims[d].hi - oldDims[d].lo + 1);
    }
    if (!inside) continue;
    if (convertScalar(o, e.bytes.data() + oldLinear * o.size, elem, static_cast<uint32_t>(newSize), tmp.data())) {
      std::memcpy(image_ + l.offset + i * newSize, tmp.data(), newSize);
      ++restored;
    } else {
      ++failed;
    }
  }
  if (restored == 0) return false;
  how = "restored " + std::to_string(restored) + " of its " + std::to_string(oldCount) + " saved elements from " + oldSig;
  if (failed) how += " (" + std::to_string(failed) + " did not convert and keep their initial value)";
  return true;
}

Controller::RetainStart Controller::restoreRetain(const std::string& file, bool coldStart, bool reset, std::ostream& err) {
  std::vector<RetainEntry> entries;
  std::string error;
  uint32_t version = 0;
  const RetainLoad r = loadRetainFile(file, entries, version, error);
  const std::string keep = "; the file is left as it is and nothing ran";
  switch (r) {
    case RetainLoad::Missing: return RetainStart::Cold;
    case RetainLoad::Ok: break;
    case RetainLoad::Unreadable:
      err << "stc: error: retain file: " << error << keep << " (give --retain a file stc can read and replace)\n";
      return RetainStart::Refused;
    case RetainLoad::Foreign:
      err << "stc: error: retain file: " << error << keep << " (give --retain another file name, or remove it)\n";
      return RetainStart::Refused;
    case RetainLoad::Newer: case RetainLoad::Damaged:
      if (reset) {
        err << "stc: warning: retain file: " << error << "; --retain-reset: cold start, the file is replaced at the first save\n";
        return RetainStart::Cold;
      }
      err << "stc: error: retain file: " << error << keep
          << " (--retain-reset starts from the initial values and replaces it)\n";
      return RetainStart::Refused;
  }
  if (reset) return RetainStart::Cold;   // a valid file: not read, replaced at the first save

  const std::vector<RetainLeaf> leaves = retainLeaves();
  // Version 1 files hold whole variables: a structured one whose type is unchanged is
  // split into the leaves it holds; anything else is looked at as one leaf.
  std::vector<std::string> notes;
  if (version == 1) {
    std::map<std::string, const RetainRegion*> regions;
    const std::vector<RetainRegion> rs = retainRegions();
    for (const RetainRegion& reg : rs) regions[reg.path] = &reg;
    std::set<std::string> leafPaths;
    for (const RetainLeaf& l : leaves) leafPaths.insert(l.path);
    std::vector<RetainEntry> split;
    for (RetainEntry& e : entries) {
      auto it = regions.find(e.path);
      if (it == regions.end() || leafPaths.count(e.path)) {   // removed, or a variable that is one leaf
        split.push_back(std::move(e));
        continue;
      }
      const RetainRegion& reg = *it->second;
      if (coldStart && !reg.persistent) continue;
      if (typeOfSignature(e.signature) != model_.layout->signature(reg.type) || e.bytes.size() != model_.layout->sizeOf(reg.type)) {
        notes.push_back("retained '" + e.path + "' changed type (a file of the old format holds it whole); it starts from its initial value");
        continue;
      }
      const std::string prefix = reg.path;
      for (const RetainLeaf& l : leaves) {
        if (l.offset < reg.offset || l.offset >= reg.offset + e.bytes.size() || l.path.compare(0, prefix.size(), prefix) != 0 ||
            l.path.size() == prefix.size() || (l.path[prefix.size()] != '.' && l.path[prefix.size()] != '['))
          continue;
        RetainEntry le{l.path, leafSignature(l), {}};
        const uint8_t* p = e.bytes.data() + (l.offset - reg.offset);
        if (l.bit >= 0) le.bytes = {static_cast<uint8_t>((*p >> l.bit) & 1)};
        else le.bytes.assign(p, p + model_.layout->sizeOf(l.type));
        split.push_back(std::move(le));
      }
    }
    entries = std::move(split);
  }

  std::map<std::string, const RetainEntry*> byPath;
  for (const RetainEntry& e : entries) byPath[e.path] = &e;
  std::set<std::string> used, declared;
  std::vector<const RetainLeaf*> fresh;   // declared, not in the file
  bool restored = false;
  for (const RetainLeaf& l : leaves) {
    declared.insert(l.path);
    if (coldStart && !l.persistent) continue;
    auto it = byPath.find(l.path);
    if (it == byPath.end()) {
      fresh.push_back(&l);
      continue;
    }
    used.insert(l.path);
    const RetainEntry& e = *it->second;
    const std::string oldType = typeOfSignature(e.signature), newType = typeOfSignature(leafSignature(l));
    const uint64_t n = l.bit >= 0 ? 1 : model_.layout->sizeOf(l.type);
    if (oldType == newType && e.bytes.size() == n) {
      if (l.bit >= 0) image_[l.offset] = static_cast<uint8_t>((image_[l.offset] & ~(1u << l.bit)) | ((e.bytes[0] & 1u) << l.bit));
      else std::memcpy(image_ + l.offset, e.bytes.data(), n);
    } else {
      std::string how;
      if (!convertLeaf(l, e, how)) {
        notes.push_back("retained '" + l.path + "' changed type from " + oldType + " to " + newType +
                        " and cannot be converted without loss; it starts from its initial value");
        continue;
      }
      notes.push_back("retained '" + l.path + "' changed type to " + newType + ": " + how);
    }
    restored = true;
    checkRestored(l, notes);
  }
  // What the file holds that the program no longer declares.
  for (const RetainEntry& e : entries) {
    if (used.count(e.path) || declared.count(e.path)) continue;
    std::string hint;
    const std::string sig = typeOfSignature(e.signature);
    const RetainLeaf* same = nullptr;
    int candidates = 0;
    for (const RetainLeaf* l : fresh)
      if (typeOfSignature(leafSignature(*l)) == sig) same = l, ++candidates;
    if (candidates == 1) hint = " (renamed to '" + same->path + "'? a renamed variable starts from its initial value)";
    notes.push_back("retained '" + e.path + "' (" + sig + ") is no longer declared; its saved value is dropped at the next save" + hint);
  }
  if (restored || !entries.empty())
    for (const RetainLeaf* l : fresh)
      notes.push_back("retained '" + l->path + "' is not in the retain file; it starts from its initial value");
  const size_t shown = std::min<size_t>(notes.size(), 50);
  for (size_t i = 0; i < shown; ++i) err << "stc: note: " << notes[i] << "\n";
  if (notes.size() > shown) err << "stc: note: ... and " << notes.size() - shown << " more retain notes\n";
  return restored ? RetainStart::Warm : RetainStart::Cold;
}

}  // namespace stc::vm
