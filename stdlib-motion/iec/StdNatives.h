// The C++ side of the IEC standard library (stdlib-motion/iec/*.st).
#pragma once

#include "vm/Native.h"

namespace stc::stdlib {

class StandardLibrary : public vm::NativeLibrary {
public:
  StandardLibrary();
  std::string_view name() const override { return "iec"; }
  const std::vector<vm::NativeEntry>& natives() const override { return natives_; }

private:
  std::vector<vm::NativeEntry> natives_;
};

}  // namespace stc::stdlib
