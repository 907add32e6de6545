// The test-only native library (vm/testlib/testlib.st).
#pragma once

namespace stc::vm {
// Registers the natives; returns the ST declarations to compile in.
const char* registerTestLib();
}  // namespace stc::vm
