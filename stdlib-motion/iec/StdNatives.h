// The C++ side of the IEC standard library.
#pragma once

namespace stc::stdlib {
// Registers the standard library's natives (idempotent).
void registerStandardNatives();
}  // namespace stc::stdlib
