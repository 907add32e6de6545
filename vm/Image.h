// The memory image seen from outside: symbolic paths (MAIN.fb.Q, GVL.x,
// arr[3].x) resolved to offsets and types, and values printed as IEC
// literals.  Used by --watch, traces and retain.
#pragma once

#include <cstdint>
#include <string>

#include "codegen/CodeGen.h"

namespace stc::sema { class Layout; class Type; }

namespace stc::vm {

struct ValueRef {
  uint64_t offset = 0;                 // from the image base
  const sema::Type* type = nullptr;
  bool retain = false, persistent = false;
  int bit = -1;                        // a BOOL view of one bit
};

// Resolves `path` (case-insensitive).  On failure `error` says why, with a
// "did you mean" when a close name exists.
bool resolvePath(const codegen::ImageMap& map, const sema::Layout& layout, const std::string& path, ValueRef& out, std::string& error);

// The value at `p` as an IEC literal: TRUE, 42, 16#FF, 3.5, T#1s500ms,
// 'text', Color#Red, [1, 2], (x := 1, y := 2).
std::string formatValue(const uint8_t* p, const sema::Type* t, const sema::Layout& layout);

// Shortest round-trip text of a REAL/LREAL with a '.' or an exponent.
std::string formatReal(double v, bool single);

}  // namespace stc::vm
