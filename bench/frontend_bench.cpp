// Front-end throughput: parse + semantic analysis of a generated
// 30,000-line project (tools/gen_project.py), in lines per second.
//   build/bench/frontend_bench
// "cold" runs each iteration in a fresh process state as far as our code is
// concerned; ANTLR's prediction DFA cache is process-wide, so the first
// iteration also pays for warming it (reported separately as FirstRun).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "driver/Driver.h"

using namespace stc;

namespace {

struct Input {
  std::vector<std::pair<std::string, std::string>> files;
  size_t lines = 0;
};

const Input& input() {
  static Input in = [] {
    Input r;
    ProjectConfig pc;
    std::string err;
    if (!loadProject(STC_BENCH_PROJECT, pc, err)) throw std::runtime_error(err);
    for (const std::string& f : pc.sources) {
      std::ifstream s(f, std::ios::binary);
      std::stringstream ss;
      ss << s.rdbuf();
      std::string text = ss.str();
      r.lines += static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
      r.files.emplace_back(f, std::move(text));
    }
    return r;
  }();
  return in;
}

bool runOnce(double* parseS = nullptr, double* semaS = nullptr) {
  Compilation c;
  for (const auto& [name, text] : input().files) c.addBuffer(name, text);
  CompileOptions o;
  bool ok = c.check(o);
  if (parseS) *parseS = c.stats().parseSeconds;
  if (semaS) *semaS = c.stats().semaSeconds;
  return ok && c.diags().warningCount() == 0;
}

void FirstRun(benchmark::State& state) {
  for (auto _ : state) {
    double p = 0, s = 0;
    if (!runOnce(&p, &s)) state.SkipWithError("the generated project does not check clean");
    state.counters["parse_s"] = p;
    state.counters["sema_s"] = s;
    state.counters["lines_per_s"] = static_cast<double>(input().lines) / (p + s);
  }
}
BENCHMARK(FirstRun)->Iterations(1)->Unit(benchmark::kMillisecond);

void ParseAndSema(benchmark::State& state) {
  double parse = 0, sema = 0;
  int64_t n = 0;
  for (auto _ : state) {
    double p = 0, s = 0;
    if (!runOnce(&p, &s)) state.SkipWithError("the generated project does not check clean");
    parse += p;
    sema += s;
    ++n;
  }
  state.counters["lines"] = static_cast<double>(input().lines);
  state.counters["lines_per_s"] = benchmark::Counter(static_cast<double>(input().lines) * static_cast<double>(n), benchmark::Counter::kIsRate);
  state.counters["parse_ms"] = parse * 1e3 / static_cast<double>(n);
  state.counters["sema_ms"] = sema * 1e3 / static_cast<double>(n);
}
BENCHMARK(ParseAndSema)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
