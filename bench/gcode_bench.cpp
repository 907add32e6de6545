// Decode speed of the G-code front end (stdlib-motion/cnc): blocks per second
// for plain "N.. G1 X.. Y.. Z.. F.." lines (target >= 1,000,000 blocks/s) and
// for a mixed program (arcs by centre and radius, helices, splines, offsets,
// G91, H switch points, M functions, a counted loop).  Each iteration decodes
// the whole program from scratch (new decoder, block index rebuilt) into a
// 64-element queue that is drained after every step, as the SMC_NCDecoder
// pipeline does.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/Decoder.h"

using namespace stc;
using namespace stc::cnc;

namespace {

std::string plainLines(int n) {
  std::string s;
  s.reserve(static_cast<size_t>(n) * 48);
  char line[96];
  for (int i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "N%d G1 X%.3f Y%.3f Z%.3f F%d\n", 10 * (i + 1), 100.0 + (i % 997) * 0.125,
                  -50.0 + (i % 331) * 0.375, (i % 17) * 0.5, 1000 + i % 7);
    s += line;
  }
  return s;
}

// One cycle of 16 blocks (two loop passes make 18 decoded blocks), repeated:
// an offset, G0, a line with two switch points, an arc by centre, a helix by
// radius, a G91 line with a relative switch point, two spline points, a line
// with an M function, a counted loop of G91 lines, G53.
std::string mixed(int n) {
  std::string s = "% mixed\n";
  char buf[768];
  int k = 0;
  for (int i = 0; s.size() < static_cast<size_t>(n) * 30; ++i) {
    int b = k;
    std::snprintf(buf, sizeof buf,
                  "N%d G90 G54 X%d Y%d\n"
                  "N%d G0 X0 Y0 Z5 F800 E2000 E-2000\n"
                  "N%d G1 X10 Y0 Z0 H1 L2.5 H-1 L-2.5\n"
                  "N%d G2 X20 Y0 I5 J0\n"
                  "N%d G3 X30 Y0 Z1 R6\n"
                  "N%d G91 G1 X2 Y-1 H2 O0.5\n"
                  "N%d G90 G5 X40 Y5\n"
                  "N%d G5 X50 Y0\n"
                  "N%d G1 X60 Y5 M%d K1.5 L2\n"
                  "N%d G36 D2\n"
                  "N%d G91 G1 X0.5 (loop body)\n"
                  "N%d G37 D-1\n"
                  "N%d G20 L%d\n"
                  "N%d G90 G53 G1 X0 Y0\n",
                  b + 10, i % 7 * 10, i % 5 * 3, b + 20, b + 30, b + 40, b + 50, b + 60, b + 70, b + 80, b + 90,
                  1 + i % 100, b + 100, b + 110, b + 120, b + 130, b + 110, b + 140);
    k = b + 140;
    s += buf;
  }
  return s;
}

void decode(benchmark::State& st, const std::string& text) {
  SourceManager sm;
  uint32_t file = sm.addBuffer("bench.cnc", text);
  ElementQueue q(64);
  uint64_t blocks = 0, elements = 0;
  for (auto _ : st) {
    DiagnosticsEngine diags(sm);
    Decoder dec(sm, file, diags);
    q.clear();
    for (;;) {
      StepResult r = dec.step(q);
      blocks += r.blocks;
      elements += r.elements;
      while (!q.empty()) {
        benchmark::DoNotOptimize(q.front().end[0]);
        q.pop();
      }
      if (r.status == StepStatus::Finished) break;
    }
    if (diags.errorCount()) {
      std::fputs(renderText(sm, diags.diagnostics().front()).c_str(), stderr);
      st.SkipWithError("the benchmark program has errors");
      break;
    }
  }
  st.counters["blocks/s"] = benchmark::Counter(static_cast<double>(blocks), benchmark::Counter::kIsRate);
  st.counters["elements/s"] = benchmark::Counter(static_cast<double>(elements), benchmark::Counter::kIsRate);
}

void BM_DecodePlainG1(benchmark::State& st) { decode(st, plainLines(static_cast<int>(st.range(0)))); }
BENCHMARK(BM_DecodePlainG1)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_DecodeMixed(benchmark::State& st) { decode(st, mixed(static_cast<int>(st.range(0)))); }
BENCHMARK(BM_DecodeMixed)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
