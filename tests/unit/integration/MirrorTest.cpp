// Axis variables ({attribute 'mirrored'} AXIS_REF_SM3) are refreshed from the
// kernel only while someone reads them: ST code naming a field or taking an
// address (sema::Model::readsMirrored), a watch, a trace, a scenario check or a
// retain file.  These tests pin both halves: the compiler's verdict for each way
// of reading, and what the image holds after a run with and without a reader.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "codegen/CodeGen.h"
#include "driver/Driver.h"
#include "sema/Model.h"
#include "tools/stc/Libraries.h"
#include "vm/Image.h"

using namespace stc;

namespace {

// MC_Power + MC_MoveVelocity (100 u/s, acceleration 1e6: at speed after 1 cycle) on Ax;
// `extra` is appended to the program body, `decls` to its VAR block.
std::string program(const std::string& decls, const std::string& extra, const std::string& types = "") {
  return types + "VAR_GLOBAL\n  Ax : AXIS_REF_SM3;\n  Other : SMC_CAMXYVA;\nEND_VAR\n"
         "PROGRAM MAIN\nVAR\n  pw : MC_Power;\n  mv : MC_MoveVelocity;\n  x : LREAL;\n" + decls +
         "END_VAR\n"
         "pw(Axis := Ax, Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n"
         "mv(Axis := Ax, Execute := pw.Status, Velocity := 100, Acceleration := 1000000, Deceleration := 1000000);\n" +
         extra + "END_PROGRAM\n";
}

struct MirrorRun {
  Compilation comp;
  tool::RunLibraries libs;
  std::unique_ptr<vm::Controller> ctl;
  bool readsMirrored = false;
  std::string err;

  bool build(const std::string& source, const std::string& name) {
    const std::string file = ::testing::TempDir() + "/mirror_" + name + ".st";
    std::ofstream(file) << source;
    comp.addPath(file);
    CompileOptions co;
    co.libraryNames = {"codesys_sm3"};
    bool ok = false;
    runWithLargeStack([&] { ok = comp.check(co); });
    if (!ok || !comp.model()) return false;
    readsMirrored = comp.model()->readsMirrored;
    codegen::CodegenOptions o;
    o.optLevel = 0;
    std::unique_ptr<codegen::CompiledModule> m;
    runWithLargeStack([&] { m = codegen::generate(*comp.model(), comp.sources(), comp.diags(), o, true); });
    ctl = std::make_unique<vm::Controller>(*comp.model(), comp.diags());
    libs.attachTo(*ctl);
    return m && ctl->load(std::move(m), err);
  }
  int run(vm::RunOptions ro) {
    std::ostringstream out, e;
    const int rc = ctl->run(ro, out, e);
    err = e.str();
    return rc;
  }
  double lreal(const std::string& path) {
    vm::ValueRef r;
    std::string e;
    EXPECT_TRUE(vm::resolvePath(ctl->imageMap(), *comp.model()->layout, path, r, e)) << e;
    double v = 0;
    std::memcpy(&v, ctl->image() + r.offset, sizeof v);
    return v;
  }
};

bool reads(const std::string& decls, const std::string& extra, const std::string& name, const std::string& types = "") {
  MirrorRun r;
  EXPECT_TRUE(r.build(program(decls, extra, types), name)) << r.err;
  return r.readsMirrored;
}

}  // namespace

TEST(Mirror, CompilerFindsEveryWayStReadsAnAxisVariable) {
  EXPECT_FALSE(reads("", "", "none"));
  EXPECT_FALSE(reads("", "x := Other.dX;\n", "other_struct"));   // a struct that is not mirrored
  EXPECT_TRUE(reads("", "x := Ax.fSetPosition;\n", "field"));
  EXPECT_TRUE(reads("", "Ax.fSWLimitPositive := 5;\n", "field_write"));
  EXPECT_TRUE(reads("  p : POINTER TO BYTE;\n", "p := ADR(Ax);\n", "address"));
  EXPECT_TRUE(reads("  r : REFERENCE TO AXIS_REF_SM3;\n", "r REF= Ax;\nx := r.fActVelocity;\n", "reference"));
  // Inside a user FB that takes the axis as VAR_IN_OUT.
  EXPECT_TRUE(reads("  s : ShowState;\n", "s(A := Ax);\n", "in_out",
                    "FUNCTION_BLOCK ShowState\nVAR_IN_OUT\n  A : AXIS_REF_SM3;\nEND_VAR\nVAR_OUTPUT\n  n : SMC_AXIS_STATE;\nEND_VAR\n"
                    "n := A.nAxisState;\nEND_FUNCTION_BLOCK\n"));
  // A struct holding an axis: its address exposes the axis's bytes too.
  EXPECT_TRUE(reads("  h : Holder;\n  p : POINTER TO Holder;\n", "p := ADR(h);\n", "holder",
                    "TYPE Holder : STRUCT\n  n : INT;\n  a : AXIS_REF_SM3;\nEND_STRUCT\nEND_TYPE\n"));
}

TEST(Mirror, UnreadAxisVariablesAreLeftAlone) {
  MirrorRun r;
  ASSERT_TRUE(r.build(program("", ""), "unread")) << r.err;
  ASSERT_FALSE(r.readsMirrored);
  vm::RunOptions ro;
  ro.cycles = 100;
  ASSERT_EQ(r.run(ro), 0) << r.err;
  EXPECT_EQ(r.lreal("Ax.fSetPosition"), 0.0);   // the kernel's axis moved; nobody asked to see it
}

TEST(Mirror, AScenarioCheckOrAWatchMakesThemCurrent) {
  for (int how = 0; how < 3; ++how) {
    MirrorRun r;
    ASSERT_TRUE(r.build(program("", how == 2 ? "x := Ax.fSetPosition;\n" : ""), "read" + std::to_string(how))) << r.err;
    vm::RunOptions ro;
    ro.cycles = 100;
    if (how == 0) ro.observesMirrored = true;      // what stc test sets for a check on an axis field
    if (how == 1) ro.watches = {"Ax.fActVelocity"};
    ASSERT_EQ(r.run(ro), 0) << r.err;
    // Powered in cycle 1 (Status TRUE from cycle 2), moving at 100 u/s from cycle 2 on.
    const double p = r.lreal("Ax.fSetPosition");
    EXPECT_GT(p, 9.0) << how;
    EXPECT_LT(p, 10.0) << how;
  }
}
