// The native libraries the stc tool hands to every controller it builds:
// the IEC standard library, the motion library (configured from project.toml)
// and the controller's test library.  vm/ knows none of them by name.
#pragma once

#include "stdlib-motion/MotionNatives.h"
#include "stdlib-motion/iec/StdNatives.h"
#include "vm/Controller.h"
#include "vm/testlib/TestLib.h"

namespace stc::tool {

struct RunLibraries {
  stdlib::StandardLibrary iec;
  motion::MotionLibrary motion;
  vm::TestLibrary test;
  void attachTo(vm::Controller& c) const {
    c.addLibrary(iec);
    c.addLibrary(motion);
    c.addLibrary(test);
  }
};

}  // namespace stc::tool
