// Two controllers in one process are independent: each has its own native
// sessions (motion kernel, axes, devices), so running two copies of the main
// demo at the same time, on two threads, gives byte for byte the trace that
// `stc run` gives in a process of its own.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "driver/Driver.h"
#include "codegen/CodeGen.h"
#include "sema/Model.h"
#include "tools/stc/Libraries.h"

using namespace stc;

namespace {

const std::string kProject = STC_SOURCE_DIR "/projects/pick_and_place";
const char* kTraced = "AxisX.fSetPosition,AxisZ.fSetPosition,AxisX.fActVelocity,GVL.bGripper";

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) out.push_back(x);
  return out;
}

// One compiled program and one controller with its own libraries.
struct Machine {
  tool::RunLibraries libs;
  std::unique_ptr<vm::Controller> ctl;
  vm::RunOptions ro;
  int rc = -1;
  std::string out, err;
  void run() {
    std::ostringstream o, e;
    rc = ctl->run(ro, o, e);
    out = o.str();
    err = e.str();
  }
};

}  // namespace

TEST(TwoControllers, SameTracesAsSeparateProcesses) {
  const std::string dir = ::testing::TempDir();
  const std::string ref = dir + "/pp_process.csv";
  const std::string cmd = std::string(STC_BINARY) + " run " + kProject + " --for 3s --trace " + kTraced + " --trace-out " + ref +
                          " > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  Compilation comp;
  ASSERT_TRUE(comp.addPath(kProject));
  bool ok = false;
  runWithLargeStack([&] { ok = comp.check(CompileOptions{}); });
  ASSERT_TRUE(ok && comp.model());
  Machine m[2];
  for (int i = 0; i < 2; ++i) {
    std::string err;
    ASSERT_TRUE(m[i].libs.motion.readProject(kProject, {}, err)) << err;
    codegen::CodegenOptions o;
    o.optLevel = 1;
    std::unique_ptr<codegen::CompiledModule> mod;
    runWithLargeStack([&] { mod = codegen::generate(*comp.model(), comp.sources(), comp.diags(), o, true); });
    ASSERT_TRUE(mod);
    m[i].ctl = std::make_unique<vm::Controller>(*comp.model(), comp.diags());
    m[i].libs.attachTo(*m[i].ctl);
    ASSERT_TRUE(m[i].ctl->load(std::move(mod), err)) << err;
    m[i].ro.duration = 3'000'000'000;
    m[i].ro.traces = split(kTraced);
    m[i].ro.traceOut = dir + "/pp_thread" + std::to_string(i) + ".csv";
  }
  std::thread a([&] { m[0].run(); }), b([&] { m[1].run(); });
  a.join();
  b.join();
  const std::string expected = slurp(ref);
  ASSERT_GT(expected.size(), 1000u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(m[i].rc, 0) << m[i].err;
    EXPECT_EQ(slurp(m[i].ro.traceOut), expected) << "controller " << i;
  }
}
