// The test-only native library (vm/testlib/testlib.st): blocking waits,
// a counter FB and a per-controller tick count, for the controller's tests.
#pragma once

#include "vm/Native.h"

namespace stc::vm {

class TestLibrary : public NativeLibrary {
public:
  TestLibrary();
  std::string_view name() const override { return "<testlib>"; }
  const std::vector<NativeEntry>& natives() const override { return natives_; }
  const void* sessionKey() const override;
  std::unique_ptr<NativeSession> newSession() const override;
  // The ST declarations to compile in (stc --testlib).
  static const char* source();

private:
  std::vector<NativeEntry> natives_;
};

}  // namespace stc::vm
