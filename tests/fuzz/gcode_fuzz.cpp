// Fuzz target for the G-code front end (stdlib-motion/cnc): any byte sequence
// must give diagnostics and well-formed elements, never a crash, hang,
// sanitizer report, non-finite coordinate or an overfull queue.
//   libFuzzer build: see docs/cnc.md ("Fuzzing")
// The same entry point is replayed over tests/fuzz/gcode_regressions by
// stc_fuzz_gcode_replay in the ordinary test suite.
//
// The first byte selects the options (block skip, N required, stop at the
// first error, G98/G99 defaults do not exist: those come from the text), the
// queue capacity and the step budget; the rest is the program.  $variables$
// resolve to a fixed table that includes NaN, infinities and huge values.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/cnc/Geometry.h"

namespace {

using namespace stc;
using namespace stc::cnc;

class FuzzVars : public VariableAccess {
public:
  double stored[8] = {0, 1, -1, 2.5, 65534, 32768, 1e300, 0};
  bool read(std::string_view name, double& v) override {
    if (name.empty()) return false;
    unsigned h = 0;
    for (char c : name) h = h * 31 + static_cast<unsigned char>(c);
    switch (h % 11) {
      case 0: v = std::nan(""); return true;
      case 1: v = INFINITY; return true;
      case 2: v = -INFINITY; return true;
      case 3: return false;
      default: v = stored[h % 8]; return true;
    }
  }
  bool write(std::string_view name, double v) override {
    if (name.size() % 5 == 0) return false;
    unsigned h = 0;
    for (char c : name) h = h * 31 + static_cast<unsigned char>(c);
    stored[h % 8] = v;
    return true;
  }
};

void check(bool ok) {
  if (!ok) __builtin_trap();
}

bool finite(const Pos& p) {
  for (double v : p)
    if (!std::isfinite(v)) return false;
  return true;
}

void inspect(const Element& e) {
  check(finite(e.start) && finite(e.end));
  check(std::isfinite(e.length) && e.length >= 0);
  check(std::isfinite(e.vel) && std::isfinite(e.acc) && std::isfinite(e.dec));
  check(e.switchCount <= kMaxSwitches);
  for (double u : {0.0, 0.3, 0.5, 1.0}) check(finite(point(e, u)));
  check(point(e, 1) == e.end);
  if (e.type == MoveType::Clw || e.type == MoveType::Cclw) {
    check(std::isfinite(e.arc.radius) && e.arc.radius > 0 && std::isfinite(e.arc.sweep));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  uint8_t sel = size ? data[0] : 0;
  std::string text(reinterpret_cast<const char*>(data) + (size ? 1 : 0), size ? size - 1 : 0);
  SourceManager sm;
  DiagnosticsEngine diags(sm);
  uint32_t file = sm.addBuffer("fuzz.cnc", text);
  DecoderOptions o;
  o.skipSlashBlocks = sel & 1;
  o.requireBlockNumbers = sel & 2;
  o.stopAtFirstError = sel & 4;
  o.defaultVel = (sel & 8) ? 100 : 0;
  o.maxJumps = 50;
  FuzzVars vars;
  Decoder dec(sm, file, diags, o, (sel & 16) ? &vars : nullptr);
  ElementQueue q(4 + (sel >> 5));
  uint32_t budget = 1 + (sel >> 6) * 7;
  for (int calls = 0;; ++calls) {
    check(calls < 10000000);
    StepResult r = dec.step(q, budget);
    check(q.size() <= q.capacity());
    while (!q.empty()) {
      inspect(q.front());
      q.pop();
    }
    if (r.status == StepStatus::Finished) break;
  }
  for (const Diagnostic& d : diags.diagnostics()) (void)renderText(sm, d);
  (void)renderJson(sm, diags.diagnostics());
  return 0;
}
