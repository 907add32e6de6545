// Code generation and controller benchmarks (issue 3).  Prints a table:
//   1. compiled ST at -O2 against the same algorithms in C at -O2
//      (bench/st/kernels.st vs bench/c/kernels.c), with and without checks;
//   2. scheduler overhead per cycle of a trivial one-task program;
//   3. build time of the generated 30,000-line project at -O0 and -O2.
// Times are the best of several runs (this machine is shared and noisy).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <vector>

#include "codegen/CodeGen.h"
#include "driver/Driver.h"
#include "sema/Model.h"
#include "stdlib-motion/iec/StdNatives.h"
#include "vm/Controller.h"
#include "vm/Jit.h"
#include "vm/Runtime.h"
#include "vm/Scheduler.h"

extern "C" {
int32_t c_sieve(int32_t n, bool* flags);
int32_t c_bubble(int32_t* a);
double c_realmath(int32_t n);
int32_t c_strings(int32_t n);
int32_t c_stringfuncs(int32_t n);
int32_t c_conversions(int32_t n);
}

using namespace stc;
using Clock = std::chrono::steady_clock;

namespace {

double bestOf(int runs, const std::function<void()>& fn) {
  double best = 1e99;
  for (int i = 0; i < runs; ++i) {
    auto t0 = Clock::now();
    fn();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return best;
}

struct Jitted {
  Compilation comp;
  std::unique_ptr<codegen::CompiledModule> module;
  std::unique_ptr<vm::Jit> jit;
};

std::unique_ptr<Jitted> jitKernels(bool checks) {
  auto j = std::make_unique<Jitted>();
  j->comp.addPath(STC_BENCH_DIR "/st/kernels.st");
  if (!j->comp.check(CompileOptions{})) return nullptr;
  codegen::CodegenOptions o;
  o.optLevel = 2;
  o.checks = checks;
  o.exportFunctions = true;
  j->module = codegen::generate(*j->comp.model(), j->comp.sources(), j->comp.diags(), o, false);
  std::string err;
  j->jit = vm::Jit::create(*j->module, vm::runtimeSymbols(), err);
  if (!j->jit) std::fprintf(stderr, "jit: %s\n", err.c_str());
  return j;
}

void neverCalled() { std::abort(); }

}  // namespace

int main() {
  // ---------------------------------------------------------------- 1. ST vs C
  static bool flags[1000001];
  std::vector<int32_t> data(2000), work(2000);
  uint32_t seed = 12345;
  for (auto& v : data) v = static_cast<int32_t>((seed = seed * 1103515245u + 12345u) >> 8);
  std::printf("%-34s %12s %12s %12s %8s %8s\n", "kernel", "C -O2 (ms)", "ST checks", "ST no-chk", "ratio", "no-chk");
  auto withChecks = jitKernels(true);
  auto noChecks = jitKernels(false);
  if (!withChecks || !noChecks || !withChecks->jit || !noChecks->jit) return 1;
  std::string err;
  struct Row {
    const char* name;
    std::function<void()> c;
    std::function<void(vm::Jit&)> st;
  };
  int32_t sink = 0;
  double dsink = 0;
  std::vector<Row> rows = {
      {"sieve (n = 1,000,000)", [&] { sink += c_sieve(1000000, flags); },
       [&](vm::Jit& j) {
         auto f = reinterpret_cast<int32_t (*)(int32_t, bool*)>(j.lookup("st.Sieve", err));
         sink += f(1000000, flags);
       }},
      {"bubble sort (2,000 DINT)", [&] { work = data; sink += c_bubble(work.data()); },
       [&](vm::Jit& j) {
         auto f = reinterpret_cast<int32_t (*)(int32_t*)>(j.lookup("st.Bubble", err));
         work = data;
         sink += f(work.data());
       }},
      {"REAL math (1,000,000 iterations)", [&] { dsink += c_realmath(1000000); },
       [&](vm::Jit& j) {
         auto f = reinterpret_cast<double (*)(int32_t)>(j.lookup("st.RealMath", err));
         dsink += f(1000000);
       }},
      {"strings (1,000,000 iterations)", [&] { sink += c_strings(1000000); },
       [&](vm::Jit& j) {
         auto f = reinterpret_cast<int32_t (*)(int32_t)>(j.lookup("st.Strings", err));
         sink += f(1000000);
       }},
      {"string functions (10^6 iterations)", [&] { sink += c_stringfuncs(1000000); },
       [&](vm::Jit& j) {
         auto f = reinterpret_cast<int32_t (*)(int32_t)>(j.lookup("st.StringFuncs", err));
         sink += f(1000000);
       }},
      {"DINT<->STRING (10^6 iterations)", [&] { sink += c_conversions(1000000); },
       [&](vm::Jit& j) {
         auto f = reinterpret_cast<int32_t (*)(int32_t)>(j.lookup("st.Conversions", err));
         sink += f(1000000);
       }},
  };
  for (Row& r : rows) {
    double c = bestOf(7, r.c);
    double s1 = bestOf(7, [&] { r.st(*withChecks->jit); });
    double s2 = bestOf(7, [&] { r.st(*noChecks->jit); });
    std::printf("%-34s %12.3f %12.3f %12.3f %7.2fx %7.2fx\n", r.name, c * 1e3, s1 * 1e3, s2 * 1e3, s1 / c, s2 / c);
  }
  // Same answers from both sides.
  {
    auto f = reinterpret_cast<int32_t (*)(int32_t, bool*)>(withChecks->jit->lookup("st.Sieve", err));
    int32_t a = f(1000000, flags), b = c_sieve(1000000, flags);
    auto g = reinterpret_cast<double (*)(int32_t)>(withChecks->jit->lookup("st.RealMath", err));
    std::printf("check: primes below 1e6 ST %d C %d; REAL math ST %.17g C %.17g\n", a, b, g(1000), c_realmath(1000));
    auto sf = reinterpret_cast<int32_t (*)(int32_t)>(withChecks->jit->lookup("st.StringFuncs", err));
    auto cv = reinterpret_cast<int32_t (*)(int32_t)>(withChecks->jit->lookup("st.Conversions", err));
    std::printf("check: string functions ST %d C %d; conversions ST %d C %d\n", sf(1000), c_stringfuncs(1000), cv(1000), c_conversions(1000));
  }

  // ---------------------------------------------------------------- 2. scheduler overhead
  {
    Compilation comp;
    comp.addPath(STC_BENCH_DIR "/st/kernels.st");
    comp.check(CompileOptions{});
    codegen::CodegenOptions o;
    o.optLevel = 2;
    o.programs = {"Trivial"};
    auto m = codegen::generate(*comp.model(), comp.sources(), comp.diags(), o, true);
    vm::Controller ctl(*comp.model(), comp.diags());
    static stdlib::StandardLibrary iec;   // the standard library's natives (task clock for timers)
    ctl.addLibrary(iec);
    if (!ctl.load(std::move(m), err)) { std::fprintf(stderr, "%s\n", err.c_str()); return 1; }
    vm::RunOptions ro;
    const uint64_t cycles = 10'000'000;
    ro.cycles = cycles;
    std::ostringstream out, errs;
    double t = bestOf(3, [&] { ctl.run(ro, out, errs); });
    std::printf("\nscheduler: trivial one-task program, %llu cycles: %.1f ns per cycle (incl. the program)\n",
                static_cast<unsigned long long>(cycles), t / static_cast<double>(cycles) * 1e9);
  }

  // ---------------------------------------------------------------- 3. build time
  for (unsigned level : {0u, 2u}) {
    Compilation comp;
    comp.addPath(STC_BENCH_PROJECT);
    auto t0 = Clock::now();
    comp.check(CompileOptions{});
    auto t1 = Clock::now();
    codegen::CodegenOptions o;
    o.optLevel = level;
    auto m = codegen::generate(*comp.model(), comp.sources(), comp.diags(), o, true);
    auto t2 = Clock::now();
    if (!m) {
      std::printf("build -O%u: code generation failed:\n", level);
      for (const Diagnostic& d : comp.diags().diagnostics()) std::printf("%s", renderText(comp.sources(), d).c_str());
      continue;
    }
    // The project uses standard FBs (TON, CTU), native in issue 4: bind them
    // to a function that is never called, to measure machine-code generation.
    auto symbols = vm::runtimeSymbols();
    for (const auto& n : m->natives) symbols[n.symbol] = reinterpret_cast<void*>(&neverCalled);
    auto jit = vm::Jit::create(*m, symbols, err);
    void* img = jit ? jit->lookup("__stc_image", err) : nullptr;
    for (const auto& t : m->tasks)
      for (const auto& e : t.entries) img = img && jit->lookup(e, err) ? img : nullptr;
    if (!img) std::printf("JIT: %s\n", err.c_str());
    auto t3 = Clock::now();
    auto sec = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    std::printf("build 30k-line project -O%u: front end %.2f s, codegen+optimise %.2f s, JIT to machine code %.2f s, total %.2f s%s\n", level,
                sec(t0, t1), sec(t1, t2), sec(t2, t3), sec(t0, t3), img ? "" : " (JIT failed)");
  }

  // ---------------------------------------------------------------- 4. build time against body size
  // One PROGRAM body with N calls of a user FB and N TON calls (2N FB calls),
  // as a machine with N axes has: the time from source to machine code must
  // grow linearly with N (target: N = 3000 within 3x of N = 1000).
  {
    double at1000 = 0;
    for (int n : {100, 1000, 3000}) {
      std::string src = "FUNCTION_BLOCK Step\nVAR_INPUT en : BOOL; x : INT; END_VAR\nVAR_OUTPUT q : INT; END_VAR\n"
                        "IF en THEN q := q + x; END_IF\nEND_FUNCTION_BLOCK\nPROGRAM MAIN\nVAR\n";
      for (int i = 0; i < n; ++i) src += "  f" + std::to_string(i) + " : Step;\n  t" + std::to_string(i) + " : TON;\n";
      src += "END_VAR\n";
      for (int i = 0; i < n; ++i) {
        std::string k = std::to_string(i);
        src += "f" + k + "(en := TRUE, x := " + k + ");\nt" + k + "(IN := f" + k + ".q > 5, PT := T#10ms);\n";
      }
      src += "END_PROGRAM\n";
      double t = bestOf(2, [&] {
        Compilation comp;
        comp.addBuffer("calls.st", src);
        comp.check(CompileOptions{});
        codegen::CodegenOptions o;
        auto m = comp.model() ? codegen::generate(*comp.model(), comp.sources(), comp.diags(), o, true) : nullptr;
        if (!m) return;
        auto symbols = vm::runtimeSymbols();
        for (const auto& nat : m->natives) symbols[nat.symbol] = reinterpret_cast<void*>(&neverCalled);
        auto jit = vm::Jit::create(*m, symbols, err);
        for (const auto& task : m->tasks)
          for (const auto& e : task.entries)
            if (jit) jit->lookup(e, err);
      });
      if (n == 1000) at1000 = t;
      std::printf("build -O2, one body with %d FB calls: %.2f s%s\n", 2 * n, t,
                  n == 3000 && at1000 > 0 ? (" (" + std::to_string(t / at1000).substr(0, 4) + "x the 2000-call body)").c_str() : "");
    }
  }
  return sink == 42 && dsink == 0.5 ? 1 : 0;
}
