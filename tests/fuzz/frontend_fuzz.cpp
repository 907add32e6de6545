// Fuzz target for the whole front end: any byte sequence must give
// diagnostics, never a crash, hang or sanitizer report.
//   tools/fuzz.sh 600          (libFuzzer build with clang-19)
// The same entry point is replayed over tests/fuzz/regressions and the test
// sources by stc_fuzz_replay in the ordinary test suite.
#include <cstddef>
#include <cstdint>
#include <string>

#include "driver/Driver.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  for (stc::sema::Dialect d : {stc::sema::Dialect::IEC, stc::sema::Dialect::Codesys}) {
    stc::Compilation c;
    c.addBuffer("fuzz.st", text);
    stc::CompileOptions o;
    o.dialect = d;
    o.includeStdlib = false;
    o.parseThreads = 1;
    c.check(o);
    // Rendering touches every location and fix-it.
    for (const stc::Diagnostic& diag : c.diags().diagnostics()) (void)stc::renderText(c.sources(), diag);
    (void)stc::renderJson(c.sources(), c.diags().diagnostics());
  }
  return 0;
}
