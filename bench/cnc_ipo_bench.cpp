// Per-cycle cost of the CNC interpolator (stdlib-motion/cnc/Interpolator, the core of
// SMC_Interpolator; target < 5 us per cycle for a 3-axis path with look-ahead).
//
// The path: 2,000 blocks of tangent-continuous G5 splines, arcs and helices in X/Y/Z
// (so the look-ahead spans up to the 64 elements in flight), fed from a decoded program
// with the junction rule of SMC_CheckVelocities, run at 1 ms.  Printed: the mean cost per
// cycle over the whole run (feeding, appending with look-ahead, sampling, switches) and the
// worst single cycle.  A second run: 2,000 short G1 lines meeting at sharp corners (a stop
// at every element: the append-and-start path every few cycles).  Both again with
// Interpolator2Dir (SMC_Interpolator2Dir, forwards, 10 elements of history).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/cnc/Geometry.h"
#include "stdlib-motion/cnc/Interpolator.h"
#include "stdlib-motion/cnc/Interpolator2Dir.h"

using namespace stc;
using namespace stc::cnc;

namespace {

std::string smoothProgram(int blocks) {
  std::string s = "G1 X0 Y10 F200 E2000 E-2000\n";
  char buf[160];
  for (int i = 0; static_cast<int>(s.size()) < blocks * 24;) {
    // a spline run, a helix quarter turn and a tangent arc back, repeated
    for (int k = 1; k <= 6; ++k, ++i) {
      std::snprintf(buf, sizeof buf, "G5 X%.4f Y%.4f\n", 10.0 * k, 10.0 + 3.0 * std::sin(k * 0.9));
      s += buf;
    }
    s += "G1 X70 Y10\nG2 X80 Y0 Z1 I0 J-10\nG3 X90 Y-10 I10 J0\nG1 X90 Y-20\nG2 X70 Y-40 I-20 J0 Z0\nG1 X0 Y-40\n";
    s += "G2 X-20 Y-20 I0 J20\nG1 X-20 Y-10\nG2 X0 Y10 I20 J0\n";
  }
  return s;
}

std::string cornerProgram(int blocks) {
  std::string s = "G1 X0 Y0 F200 E2000 E-2000\n";
  char buf[96];
  for (int i = 0; i < blocks; ++i) {
    std::snprintf(buf, sizeof buf, "G1 X%.3f Y%.3f Z%.3f\n", (i % 2) * 2.0, (i / 2 % 2) * 2.0 + 0.5, (i % 3) * 0.25);
    s += buf;
  }
  return s;
}

void markJunctions(std::vector<Element>& els) {
  for (size_t i = 0; i < els.size(); ++i) {
    Element& e = els[i];
    e.marks |= MarkVelChecked;
    e.velEnd = 0;
    if (i + 1 < els.size() && isToolPath(e.type) && isToolPath(els[i + 1].type) &&
        dot(endTangent(e), startTangent(els[i + 1])) > std::cos(0.001 * M_PI / 180))
      e.velEnd = std::min(e.vel, els[i + 1].vel);
  }
}

template <class Ipo>
void run(const char* name, const std::string& text) {
  SourceManager sm;
  DiagnosticsEngine diags(sm);
  const uint32_t file = sm.addBuffer("bench.cnc", text);
  std::vector<Element> els = decodeAll(sm, file, diags, {}, nullptr);
  if (diags.errorCount() > 0) {
    std::fprintf(stderr, "decode errors\n");
    return;
  }
  markJunctions(els);
  double best = 1e300, worstCycle = 0;
  uint64_t cycles = 0;
  double length = 0;
  for (const Element& e : els) length += e.length;
  for (int rep = 0; rep < 3; ++rep) {
    IpoSettings cfg;
    cfg.cycle = 0.001;
    int16_t err = 0;
    auto settings = [&] {
      if constexpr (std::is_same_v<Ipo, Interpolator2Dir>) {
        Ipo2DirSettings c2;
        c2.ipo = cfg;
        c2.history = 10;
        return c2;
      } else {
        return cfg;
      }
    };
    Ipo ipo(settings(), err);
    IpoControls ctl;
    size_t fed = 0;
    uint64_t n = 0;
    double worst = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (;;) {
      const auto c0 = std::chrono::steady_clock::now();
      while (fed < els.size() && ipo.wantsMore()) ipo.feed(els[fed++]);
      if (fed == els.size()) ipo.endOfList();
      const IpoOutput& o = ipo.step(ctl);
      if constexpr (std::is_same_v<Ipo, Interpolator2Dir>) ipo.takeReleased();
      else ipo.takeFinished();
      const double dc = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
      worst = std::max(worst, dc);
      ++n;
      if (o.finished || ipo.error() != 0 || n > 50000000) break;
    }
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (ipo.error() != 0) std::fprintf(stderr, "interpolator error %d\n", ipo.error());
    if (total / n < best) {
      best = total / n;
      worstCycle = worst;
      cycles = n;
    }
  }
  std::printf("%-34s %5zu elements, %8.1f units, %7llu cycles: %6.3f us per cycle (mean, best of 3), worst cycle %7.2f us\n",
              name, els.size(), length, static_cast<unsigned long long>(cycles), best * 1e6, worstCycle * 1e6);
}

}  // namespace

int main() {
  run<Interpolator>("tangent splines/arcs/helices", smoothProgram(2000));
  run<Interpolator>("G1 lines, sharp corners", cornerProgram(2000));
  run<Interpolator2Dir>("2Dir: tangent splines/arcs/helices", smoothProgram(2000));
  run<Interpolator2Dir>("2Dir: G1 lines, sharp corners", cornerProgram(2000));
  return 0;
}
