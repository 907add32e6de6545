// Benchmarks of the axis-group path layer (stdlib-motion/path): the look-ahead
// cost of appending a blended segment, and one 1 ms cycle of 100 planners each
// running a blended 3-axis path that is refilled as it drains.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "stdlib-motion/path/Planner.h"

using namespace stc::motion::path;

namespace {

MoveSpec zigzag(int i, double z) {
  MoveSpec m;
  m.kind = (i % 5 == 4) ? MoveKind::ArcBorder : MoveKind::Line;
  m.end = {};
  m.end[0] = 10.0 * (i + 1);
  m.end[1] = (i % 2) ? 0.0 : 4.0;
  m.end[2] = z;
  if (m.kind == MoveKind::ArcBorder) {
    m.aux = m.end;
    m.aux[0] -= 5;
    m.aux[1] += 2.5;
  }
  m.dyn = {100, 1000, 1000, 20000};
  m.buffer = i == 0 ? BufferMode::Aborting : BufferMode::BlendingNext;
  m.transition = i == 0 ? TransitionMode::None : TransitionMode::CornerDistance;
  m.transitionParam = 1.5;
  return m;
}

// Appending one blended segment to a queue of `range` segments (geometry, blend,
// caps, backward pass, replan of the running plan).
void BM_AppendBlendedSegment(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  PlannerConfig cfg;
  cfg.capacity = n + 8;
  Planner p(cfg);
  int i = 0;
  for (auto _ : st) {
    st.PauseTiming();
    if (p.queued() >= n) {
      p.clear();
      p.setPosition({});
      i = 0;
    }
    st.ResumeTiming();
    benchmark::DoNotOptimize(p.append(zigzag(i++, 0.0)));
    p.clearEvents();
  }
}
BENCHMARK(BM_AppendBlendedSegment)->Arg(16)->Arg(128);

// One 1 ms cycle of 100 planners, each on a blended 3-axis path; the queues are
// topped up to 16 segments every cycle (the append cost is included).
void BM_Cycle100Planners(benchmark::State& st) {
  constexpr int N = 100;
  std::vector<std::unique_ptr<Planner>> ps;
  std::vector<int> next(N, 0);
  PlannerConfig cfg;
  cfg.capacity = 32;
  for (int k = 0; k < N; ++k) ps.push_back(std::make_unique<Planner>(cfg));
  auto top = [&](int k) {
    while (ps[k]->queued() < 16) ps[k]->append(zigzag(next[k]++, 0.01 * k));
  };
  for (int k = 0; k < N; ++k) {
    top(k);
    for (int c = 0; c < 37 * k; ++c) ps[k]->advance(0.001);   // spread the phases
  }
  for (auto _ : st) {
    for (int k = 0; k < N; ++k) {
      benchmark::DoNotOptimize(ps[k]->advance(0.001));
      ps[k]->clearEvents();
      top(k);
    }
  }
}
BENCHMARK(BM_Cycle100Planners)->Unit(benchmark::kMicrosecond);

// The same cycle without appends (sampling and replans only).
void BM_Cycle100PlannersSampleOnly(benchmark::State& st) {
  constexpr int N = 100;
  std::vector<std::unique_ptr<Planner>> ps;
  PlannerConfig cfg;
  cfg.capacity = 200;
  for (int k = 0; k < N; ++k) {
    ps.push_back(std::make_unique<Planner>(cfg));
    for (int i = 0; i < 190; ++i) ps[k]->append(zigzag(i, 0.01 * k));
  }
  for (auto _ : st) {
    for (int k = 0; k < N; ++k) {
      if (ps[k]->idle()) {
        st.PauseTiming();
        ps[k]->setPosition({});
        for (int i = 0; i < 190; ++i) ps[k]->append(zigzag(i, 0.01 * k));
        st.ResumeTiming();
      }
      benchmark::DoNotOptimize(ps[k]->advance(0.001));
      ps[k]->clearEvents();
    }
  }
}
BENCHMARK(BM_Cycle100PlannersSampleOnly)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
