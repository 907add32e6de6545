// Benchmarks of the motion core's one-axis trajectory planner.
#include <benchmark/benchmark.h>

#include <cmath>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "stdlib-motion/core/Cam.h"
#include "stdlib-motion/core/Kernel.h"
#include "stdlib-motion/core/SyncPlan.h"
#include "stdlib-motion/core/Trajectory.h"

using namespace stc::motion;

namespace {

struct Rng {
  std::mt19937_64 g{12345};
  double u01() { return double(g() >> 11) * 0x1.0p-53; }
  double uni(double a, double b) { return a + (b - a) * u01(); }
};

struct Case {
  Kinematic s;
  double target, vEnd;
};

// Random states inside the limits (v, a nonzero), targets, end velocities.
std::vector<Case> makeCases(const Limits& l, int n) {
  Rng r;
  std::vector<Case> cs(n);
  for (auto& c : cs) {
    c.s.p = r.uni(-100, 100);
    c.s.v = r.uni(-1, 1) * l.vel;
    const double x = r.uni(-1, 1);
    c.s.a = x * (x * c.s.v > 0 ? l.acc : l.dec);
    c.target = r.uni(-100, 100) * (r.u01() < 0.2 ? 0.01 : 1);
    c.vEnd = r.u01() < 0.5 ? 0 : r.uni(-1, 1) * l.vel;
  }
  return cs;
}

const Limits kJerk{10, 20, 30, 200};
const Limits kTrap{10, 20, 30, 0};

void BM_PlanJerkRestToRest(benchmark::State& st) {
  Profile p;
  double target = 100;
  for (auto _ : st) {
    benchmark::DoNotOptimize(planPosition({0, 0, 0}, target, 0, kJerk, p));
    benchmark::DoNotOptimize(p);
    target = target == 100 ? 3.7 : 100;   // alternate a long (cruise) and a short move
  }
}
BENCHMARK(BM_PlanJerkRestToRest);
// (labels: the previous planner on this machine, commit c0175b8, and Ruckig's figure
// from the references; docs/motion.md "Benchmarks")
static const int kLabelled = [] {
  benchmark::RegisterBenchmark("BM_PlanJerkRestToRest/reference", [](benchmark::State& st) {
    Profile p;
    double target = 100;
    for (auto _ : st) {
      benchmark::DoNotOptimize(planPosition({0, 0, 0}, target, 0, kJerk, p));
      benchmark::DoNotOptimize(p);
      target = target == 100 ? 3.7 : 100;
    }
    st.SetLabel("previous planner 226 ns, Ruckig 320 ns (REFERENCES.md)");
  });
  return 0;
}();

void BM_PlanTrapezoidalRestToRest(benchmark::State& st) {
  Profile p;
  double target = 100;
  for (auto _ : st) {
    benchmark::DoNotOptimize(planPosition({0, 0, 0}, target, 0, kTrap, p));
    benchmark::DoNotOptimize(p);
    target = target == 100 ? 3.7 : 100;
  }
}
BENCHMARK(BM_PlanTrapezoidalRestToRest);

// 6 axes with different limits and distances, all finishing together
void sync6(benchmark::State& st, bool moving, bool phase) {
  Rng r;
  std::vector<std::array<SyncAxis, 6>> sets(256);
  for (auto& set : sets) {
    for (int i = 0; i < 6; ++i) {
      SyncAxis& a = set[i];
      a.lim = {r.uni(5, 15), r.uni(10, 40), r.uni(10, 40), r.uni(100, 400)};
      a.start.p = r.uni(-10, 10);
      a.target = r.uni(-100, 100);
      if (moving) {
        a.start.v = r.uni(-1, 1) * a.lim.vel;
        const double x = r.uni(-0.5, 0.5);
        a.start.a = x * std::min(a.lim.acc, a.lim.dec);
        a.vEnd = r.u01() < 0.5 ? 0 : r.uni(-1, 1) * a.lim.vel;
      }
    }
  }
  Profile out[6];
  size_t i = 0;
  for (auto _ : st) {
    const SyncResult res = phase ? planPhaseSynchronized(sets[i].data(), 6, out) : planSynchronized(sets[i].data(), 6, out);
    benchmark::DoNotOptimize(res);
    benchmark::DoNotOptimize(out);
    i = (i + 1) & 255;
  }
}
void BM_Sync6RestToRest(benchmark::State& st) { sync6(st, false, false); }
void BM_Sync6ArbitraryStates(benchmark::State& st) { sync6(st, true, false); }
void BM_PhaseSync6RestToRest(benchmark::State& st) { sync6(st, false, true); }
BENCHMARK(BM_Sync6RestToRest);
BENCHMARK(BM_Sync6ArbitraryStates);
BENCHMARK(BM_PhaseSync6RestToRest);

// Cam lookup (y, y', y'') at random master positions vs the number of points:
// XYVA and 2-D tables search their segment (O(log n)), 1-D tables index it (O(1)).
static void camLookup(benchmark::State& st, int kind) {
  const int n = static_cast<int>(st.range(0));
  stc::motion::Cam cam;
  std::string err;
  std::vector<stc::motion::CamXYVA> xyva;
  std::vector<std::array<double, 2>> xy;
  std::vector<double> ys;
  for (int i = 0; i < n; ++i) {
    const double x = 360.0 * i / (n - 1);
    xyva.push_back({x, std::sin(x / 57.3), std::cos(x / 57.3) / 57.3, 0});
    xy.push_back({x, std::sin(x / 57.3)});
    ys.push_back(std::sin(x / 57.3));
  }
  if (kind == 0) stc::motion::Cam::xyva(xyva, {}, cam, err);
  else if (kind == 1) stc::motion::Cam::table2D(xy, {}, cam, err);
  else stc::motion::Cam::table1D(0, 360, ys, {}, cam, err);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> d(0, 360);
  std::vector<double> q(4096);
  for (double& v : q) v = d(rng);
  size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(cam.at(q[i++ & 4095]));
  }
}
static void BM_CamLookupXYVA(benchmark::State& st) { camLookup(st, 0); }
static void BM_CamLookupTable2D(benchmark::State& st) { camLookup(st, 1); }
static void BM_CamLookupTable1D(benchmark::State& st) { camLookup(st, 2); }
BENCHMARK(BM_CamLookupXYVA)->RangeMultiplier(16)->Range(16, 65536);
BENCHMARK(BM_CamLookupTable2D)->RangeMultiplier(16)->Range(16, 65536);
BENCHMARK(BM_CamLookupTable1D)->RangeMultiplier(16)->Range(16, 65536);

// Plans `plan(case, profile)` over 4096 pre-generated random cases, round robin.
template <class Plan>
void planCases(benchmark::State& st, const Limits& lim, Plan plan) {
  const auto cs = makeCases(lim, 4096);
  Profile p;
  size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(plan(cs[i], p));
    benchmark::DoNotOptimize(p);
    i = (i + 1) & 4095;
  }
}

void BM_PlanJerkArbitraryState(benchmark::State& st) {
  planCases(st, kJerk, [](const Case& c, Profile& p) { return planPosition(c.s, c.target, c.vEnd, kJerk, p); });
}
BENCHMARK(BM_PlanJerkArbitraryState);

void BM_PlanJerkVelocity(benchmark::State& st) {
  planCases(st, kJerk, [](const Case& c, Profile& p) { return planVelocity(c.s, c.vEnd, kJerk, p); });
}
BENCHMARK(BM_PlanJerkVelocity);

void BM_PlanTrapezoidal(benchmark::State& st) {
  planCases(st, kTrap, [](const Case& c, Profile& p) { return planPosition(c.s, c.target, c.vEnd, kTrap, p); });
}
BENCHMARK(BM_PlanTrapezoidal);

void BM_SampleProfile(benchmark::State& st) {
  Profile p;
  planPosition({0, 1, 5}, 100, 2, kJerk, p);
  const double dt = p.duration() / 1000;
  double t = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(p.at(t));
    t += dt;
    if (t > p.duration()) t = 0;
  }
}
BENCHMARK(BM_SampleProfile);

}  // namespace

// The kernel's cycle with 1000 virtual axes, each running a MoveAbsolute
// (trapezoidal, re-commanded whenever it finishes): time per 1 ms cycle.
// Target: < 250 us (25 % of a core) for 1000 axes.
static void BM_KernelCycle1000Axes(benchmark::State& state) {
  using namespace stc::motion;
  const int n = static_cast<int>(state.range(0));
  Kernel k;
  k.reset();
  std::vector<uint64_t> handles(2 * n, 0);
  std::vector<FbSlot*> moves;
  for (int i = 0; i < n; ++i) {
    Axis& ax = k.addAxis(AxisConfig{});
    ax.task = 0;
    FbSlot& p = k.slot(handles[2 * i], &handles[2 * i], FbKind::Power, nullptr);
    k.callPower(p, ax, true, true, true, CallCtx{0, 1, 0, 1000000});
    moves.push_back(&k.slot(handles[2 * i + 1], &handles[2 * i + 1], FbKind::MoveAbsolute, nullptr));
  }
  uint64_t cycle = 1;
  int64_t now = 0;
  for (auto _ : state) {
    CallCtx c{0, cycle, now, 1000000};
    for (int i = 0; i < n; ++i) {
      MoveInputs in;
      in.position = (cycle / 700) % 2 ? 0.0 : 100.0 + i;
      in.velocity = 200;
      in.acceleration = in.deceleration = 1000;
      in.jerk = 10000;
      k.callMove(*moves[i], *k.axis(i), (cycle % 700) != 0, in, c);
    }
    k.cycle(0, now, 1000000, cycle);
    ++cycle;
    now += 1000000;
  }
  state.counters["axes"] = n;
}
BENCHMARK(BM_KernelCycle1000Axes)->Arg(1000)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
