// Motion through the path users take: an ST program, compiled and JIT-run on
// the controller, with N axes (ARRAY OF AXIS_REF_SM3), each with an MC_Power
// and an MC_MoveAbsolute called from ST in every 1 ms cycle (re-commanded
// every 700 cycles).  Prints the wall time per cycle: programs + FB bodies +
// kernel + mirrors.  Target (issue 12): < 100 us per cycle for 1000 axes.
// Second figure: 500 cam-coupled master/slave pairs (MC_MoveVelocity masters,
// MC_CamIn slaves on a 33-point XYVA cycloid cam, selected once with
// MC_CamTableSelect), every other FB called from ST in every cycle.  Target: < 100 us.
// Third figure (issue 15): N axis groups of 3 axes, each running a blended square path
// (4 MC_MoveLinearRelative, BlendingLow + TMCornerDistance) re-queued whenever it ends, every FB
// called from ST in every cycle.  Target: < 100 us per cycle for 100 groups.
// Also with kinematics: N SCARA groups (TRAFO.Kin_Scara2_Z, joints in degrees) running the same
// blended squares in MCS: every step maps the path point through the inverse kinematics.
// Fourth figure: N SMC_TRAFO_Scara2 inverse transformations per cycle from ST (the tool point
// on a circle), the kinematics face's cost through the path users take.
// Each figure twice: the programs above never read a field of an axis variable,
// so the kernel leaves them alone (docs/motion.md, "Mirrors"); the "reads" variant
// adds one field read per axis, which makes every axis variable mirrored in every cycle.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "codegen/CodeGen.h"
#include "driver/Driver.h"
#include "sema/Model.h"
#include "tools/stc/Libraries.h"

using namespace stc;

namespace {

std::string program(int n, bool reads) {
  std::ostringstream s;
  s << "VAR_GLOBAL\n  Axes : ARRAY[1.." << n << "] OF AXIS_REF_SM3;\nEND_VAR\n"
    << "PROGRAM MAIN\nVAR\n  power : ARRAY[1.." << n << "] OF MC_Power;\n  move : ARRAY[1.." << n
    << "] OF MC_MoveAbsolute;\n  i : DINT;\n  cycle : DINT;\n  sum : LREAL;\nEND_VAR\n"
    << "FOR i := 1 TO " << n << " DO\n"
    << "  power[i](Axis := Axes[i], Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n"
    << "  move[i](Axis := Axes[i], Execute := power[i].Status AND (cycle MOD 700) <> 0,\n"
    << "          Position := SEL((cycle / 700) MOD 2 = 1, 100.0 + DINT_TO_LREAL(i), 0.0),\n"
    << "          Velocity := 200, Acceleration := 1000, Deceleration := 1000);\n"
    << (reads ? "  sum := sum + Axes[i].fActPosition;\n" : "")
    << "END_FOR\ncycle := cycle + 1;\nEND_PROGRAM\n";
  return s.str();
}

std::string camProgram(int n, bool reads) {
  std::ostringstream s;
  s << "VAR_GLOBAL\n  M, S : ARRAY[1.." << n << "] OF AXIS_REF_SM3;\n  pts : ARRAY[0..32] OF SMC_CAMXYVA;\n  cam : MC_CAM_REF;\nEND_VAR\n"
    << "PROGRAM MAIN\nVAR\n  pm, ps : ARRAY[1.." << n << "] OF MC_Power;\n  mv : ARRAY[1.." << n << "] OF MC_MoveVelocity;\n"
    << "  sel : ARRAY[1.." << n << "] OF MC_CamTableSelect;\n  cin : ARRAY[1.." << n << "] OF MC_CamIn;\n  i : DINT;\n  u : LREAL;\n"
    << "  cycle : DINT;\n  sum : LREAL;\nEND_VAR\n"
    << "IF cycle = 0 THEN\n  FOR i := 0 TO 32 DO\n    u := DINT_TO_LREAL(i) / 32.0;\n"
    << "    pts[i].dX := 360.0 * u;\n    pts[i].dY := 100.0 * (u - SIN(6.283185307179586 * u) / 6.283185307179586);\n"
    << "    pts[i].dV := 100.0 / 360.0 * (1.0 - COS(6.283185307179586 * u));\n"
    << "    pts[i].dA := 100.0 / 129600.0 * 6.283185307179586 * SIN(6.283185307179586 * u);\n  END_FOR\n"
    << "  cam.nElements := 33; cam.xStart := 0; cam.xEnd := 360; cam.pce := ADR(pts);\nEND_IF\n"
    << "FOR i := 1 TO " << n << " DO\n"
    << "  pm[i](Axis := M[i], Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n"
    << "  ps[i](Axis := S[i], Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n"
    << "  mv[i](Axis := M[i], Execute := pm[i].Status, Velocity := 360, Acceleration := 3600, Deceleration := 3600);\n"
    << "  IF NOT sel[i].Done THEN sel[i](Master := M[i], Slave := S[i], CamTable := cam, Execute := TRUE); END_IF\n"
    << "  cin[i](Master := M[i], Slave := S[i], Execute := sel[i].Done AND ps[i].Status, CamTableID := sel[i].CamTableID);\n"
    << (reads ? "  sum := sum + S[i].fSetPosition;\n" : "")
    << "END_FOR\ncycle := cycle + 1;\nEND_PROGRAM\n";
  return s.str();
}

std::string groupProgram(int n, bool scara) {
  std::ostringstream s;
  s << "VAR_GLOBAL\n  Axes : ARRAY[1.." << 3 * n
    << "] OF AXIS_REF_SM3 := [" << 3 * n << "((fMaxVelocity := 500, fMaxAcceleration := 5000))];\n  Groups : ARRAY[1.." << n
    << "] OF AXIS_GROUP_REF_SM3;\nEND_VAR\n"
    << "PROGRAM MAIN\nVAR\n  add : ARRAY[1.." << 3 * n << "] OF MC_AddAxisToGroup;\n  power : ARRAY[1.." << n
    << "] OF SMC_GroupPower;\n  enable : ARRAY[1.." << n << "] OF MC_GroupEnable;\n  mv : ARRAY[1.." << n
    << ", 1..4] OF MC_MoveLinearRelative;\n  run : ARRAY[1.." << n << "] OF BOOL;\n  d : ARRAY[1..4] OF SMC_POS_REF;\n"
    << "  blend : SMC_TRANSITION_PARAMETERS := [2, 0, 0, 0, 0];\n  g, j : DINT;\n";
  // SCARA: arms 200 / 150, every group set to joints (0, 90, 0): the tool at (200, 150, 0).
  if (scara)
    s << "  kin : TRAFO.Kin_Scara2_Z := (dArmLength1 := 200, dArmLength2 := 150);\n  setKin : ARRAY[1.." << n
      << "] OF MC_SetKinTransform;\n  setPos : ARRAY[1.." << n << "] OF MC_GroupSetPosition;\n  p0 : SMC_POS_REF;\n";
  s << "END_VAR\n"
    << (scara ? "p0.a.a1 := 90;\n" : "")
    << "d[1].c.X := 20; d[1].c.Z := 5; d[2].c.Y := 20; d[2].c.Z := -5; d[3].c.X := -20; d[3].c.Z := 5; d[4].c.Y := -20; d[4].c.Z := -5;\n"
    << "FOR g := 1 TO " << n << " DO\n"
    << "  FOR j := 1 TO 3 DO add[(g - 1) * 3 + j](AxisGroup := Groups[g], Axis := Axes[(g - 1) * 3 + j], Execute := TRUE); END_FOR\n"
    << "  power[g](AxisGroup := Groups[g], Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n"
    << (scara ? "  setKin[g](AxisGroup := Groups[g], Execute := TRUE, KinTransform := kin);\n" : "")
    << "  enable[g](AxisGroup := Groups[g], Execute := power[g].Status" << (scara ? " AND setKin[g].Done" : "") << ");\n"
    << (scara ? "  setPos[g](AxisGroup := Groups[g], Execute := enable[g].Done, Position := p0);\n" : "")
    << "  IF mv[g, 4].Done THEN run[g] := FALSE; ELSIF " << (scara ? "setPos[g].Done" : "enable[g].Done") << " AND NOT mv[g, 1].Busy AND NOT mv[g, 4].Busy THEN run[g] := TRUE; END_IF\n"
    << "  mv[g, 1](AxisGroup := Groups[g], Execute := run[g], Distance := d[1], Velocity := 100, Acceleration := 1000, Deceleration := 1000,\n"
    << "           BufferMode := MC_BUFFER_MODE.Buffered" << (scara ? ", CoordSystem := SMC_COORD_SYSTEM.MCS" : "") << ");\n"
    << "  FOR j := 2 TO 4 DO\n"
    << "    mv[g, j](AxisGroup := Groups[g], Execute := run[g], Distance := d[j], Velocity := 100, Acceleration := 1000, Deceleration := 1000,\n"
    << "             BufferMode := MC_BUFFER_MODE.BlendingLow, TransitionMode := MC_TRANSITION_MODE.TMCornerDistance, TransitionParameter := blend"
    << (scara ? ", CoordSystem := SMC_COORD_SYSTEM.MCS" : "") << ");\n"
    << "  END_FOR\nEND_FOR\nEND_PROGRAM\n";
  return s.str();
}

std::string trafoProgram(int n) {
  std::ostringstream s;
  s << "PROGRAM MAIN\nVAR\n  inv : ARRAY[1.." << n << "] OF SMC_TRAFO_Scara2;\n  i : DINT;\n  cycle : DINT;\n  u : LREAL;\n  sum : LREAL;\nEND_VAR\n"
    << "cycle := cycle + 1;\nFOR i := 1 TO " << n << " DO\n"
    << "  u := 0.001 * DINT_TO_LREAL(cycle + i);\n"
    << "  inv[i].pi.dX := 100.0 + 50.0 * COS(u); inv[i].pi.dY := 50.0 * SIN(u);\n"
    << "  inv[i](dArmLength1 := 100, dArmLength2 := 100);\n  sum := sum + inv[i].dA;\nEND_FOR\nEND_PROGRAM\n";
  return s.str();
}

// Issue 16: the CNC pipeline as users write it, all from ST in one 1 ms task: SMC_NCDecoder
// (a G-code loop of tangent splines, arcs and helices, 1000 passes: a path of some 20,000
// elements) -> SMC_CheckVelocities -> SMC_Interpolator -> 3 x SMC_ControlAxisByPos.  With
// twoDir: SMC_QueueSetReservedEntries (13) -> SMC_Interpolator2Dir + its slow-task block.
std::string cncProgram(bool twoDir) {
  std::ostringstream s;
  s << "VAR_GLOBAL AxisX, AxisY, AxisZ : AXIS_REF_SM3; END_VAR\n"
    << "PROGRAM MAIN\nVAR\n  px, py, pz : MC_Power;\n  dec : SMC_NCDecoder;\n  cv : SMC_CheckVelocities;\n"
    << (twoDir ? "  ipo : SMC_Interpolator2Dir;\n  res : SMC_QueueSetReservedEntries;\n  slow : SMC_Interpolator2Dir_SlowTask;\n"
               : "  ipo : SMC_Interpolator;\n")
    << "  cx, cy, cz : SMC_ControlAxisByPos;\n  prog : SMC_CNC_REF;\n"
    << "  ring : ARRAY[0..99] OF SMC_GEOINFO;\n  cycle : DINT;\n"
    << "  text : STRING(1000) := 'N10 G1 X0 Y10 F200 E2000 E-2000$NN20 G36 D1000$N"
       "N30 G5 X10 Y12.35$NN31 G5 X20 Y12.92$NN32 G5 X30 Y11.28$NN33 G5 X40 Y9.37$NN34 G5 X50 Y10.29$NN35 G5 X60 Y12.21$N"
       "N40 G1 X70 Y10$NN41 G2 X80 Y0 Z1 I0 J-10$NN42 G3 X90 Y-10 I10 J0$NN43 G1 X90 Y-20$NN44 G2 X70 Y-40 I-20 J0 Z0$N"
       "N45 G1 X0 Y-40$NN46 G2 X-20 Y-20 I0 J20$NN47 G1 X-20 Y-10$NN48 G2 X0 Y10 I20 J0$NN50 G37 D-1$NN60 G20 L30$N';\n"
    << "END_VAR\n"
    << "IF cycle = 0 THEN prog.pText := ADR(text); prog.dwTextSize := INT_TO_UDINT(LEN(text)); END_IF\n"
    << "cycle := cycle + 1;\n"
    << "px(Axis := AxisX, Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n"
    << "py(Axis := AxisY, Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n"
    << "pz(Axis := AxisZ, Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n"
    << "dec(ncprog := prog, bExecute := TRUE, nSizeOutQueue := SIZEOF(ring), pbyBufferOutQueue := ADR(ring));\n"
    << "cv(bExecute := TRUE, poqDataIn := dec.poqDataOut);\n"
    << (twoDir ? "res(bExecute := TRUE, poqDataIn := cv.poqDataOut, nNumReservedEntries := 13);\nslow(Interpolator2Dir := ipo);\n" : "")
    << "ipo(bExecute := cycle > 2, poqDataIn := " << (twoDir ? "res" : "cv") << ".poqDataOut, dwIpoTime := 1000, bEmergency_Stop := cx.bStopIpo OR cy.bStopIpo OR cz.bStopIpo);\n"
    << "cx(Axis := AxisX, iStatus := ipo.iStatus, bEnable := ipo.bWorking, fSetPosition := ipo.piSetPosition.dX, fGapVelocity := 100, fGapAcceleration := 1000);\n"
    << "cy(Axis := AxisY, iStatus := ipo.iStatus, bEnable := ipo.bWorking, fSetPosition := ipo.piSetPosition.dY, fGapVelocity := 100, fGapAcceleration := 1000);\n"
    << "cz(Axis := AxisZ, iStatus := ipo.iStatus, bEnable := ipo.bWorking, fSetPosition := ipo.piSetPosition.dZ, fGapVelocity := 100, fGapAcceleration := 1000);\n"
    << "END_PROGRAM\n";
  return s.str();
}

// Seconds of wall time per cycle over `cycles` cycles (after a warm-up).
double perCycle(int n, uint64_t cycles, bool cams, bool reads, bool groups = false, bool trafo = false, bool scara = false,
                bool cnc = false) {
  const std::string file = "/tmp/stc_st_motion_bench_" + std::string(cnc ? "cnc_" : trafo ? "trafo_" : scara ? "scara_" : groups ? "group_" : cams ? "cam_" : "") +
                           (reads ? "reads_" : "") + std::to_string(n) + ".st";
  std::ofstream(file) << (cnc ? cncProgram(n == 2) : trafo ? trafoProgram(n) : groups ? groupProgram(n, scara) : cams ? camProgram(n, reads) : program(n, reads));
  Compilation comp;
  comp.addPath(file);
  CompileOptions co;
  co.libraryNames = {"codesys_sm3"};
  bool ok = false;
  runWithLargeStack([&] { ok = comp.check(co); });
  if (!ok || !comp.model()) return -1;
  codegen::CodegenOptions o;
  o.optLevel = 2;
  std::unique_ptr<codegen::CompiledModule> m;
  runWithLargeStack([&] { m = codegen::generate(*comp.model(), comp.sources(), comp.diags(), o, true); });
  tool::RunLibraries libs;
  vm::Controller ctl(*comp.model(), comp.diags());
  libs.attachTo(ctl);
  std::string err;
  if (!m || !ctl.load(std::move(m), err)) {
    std::fprintf(stderr, "%s\n", err.c_str());
    return -1;
  }
  std::ostringstream out, errs;
  vm::RunOptions warm;
  warm.cycles = 100;
  ctl.run(warm, out, errs);
  vm::RunOptions ro;
  ro.cycles = cycles;
  const auto t0 = std::chrono::steady_clock::now();
  ctl.run(ro, out, errs);
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(t1 - t0).count() / static_cast<double>(cycles);
}

}  // namespace

int main(int argc, char** argv) {
  const uint64_t cycles = argc > 1 ? std::stoull(argv[1]) : 5000;
  const std::string only = argc > 2 ? argv[2] : "";   // "axes", "cams", "groups", "scara", "cnc" or "trafo": one scenario
  for (bool reads : {false, true})
    for (int n : {1, 100, 1000}) {
      if ((!only.empty() && only != "axes") || (reads && n != 1000)) continue;
      double best = 1e9;
      for (int rep = 0; rep < 3; ++rep) best = std::min(best, perCycle(n, cycles, false, reads));
      std::printf("%5d axes (MC_Power + MC_MoveAbsolute from ST%s, 1 ms cycle): %8.2f us per cycle (best of 3, %llu cycles)\n", n,
                  reads ? ", reads fActPosition" : "", best * 1e6, static_cast<unsigned long long>(cycles));
    }
  for (bool reads : {false, true})
    for (int n : {1, 500}) {
      if ((!only.empty() && only != "cams") || (reads && n != 500)) continue;
      double best = 1e9;
      for (int rep = 0; rep < 3; ++rep) best = std::min(best, perCycle(n, cycles, true, reads));
      std::printf("%5d cam pairs (2 MC_Power, MC_MoveVelocity, MC_CamTableSelect, MC_CamIn from ST%s): %8.2f us per cycle (best of 3, %llu cycles)\n",
                  n, reads ? ", reads fSetPosition" : "", best * 1e6, static_cast<unsigned long long>(cycles));
    }
  for (int n : {1, 100}) {
    if (!only.empty() && only != "groups") continue;
    double best = 1e9;
    for (int rep = 0; rep < 3; ++rep) best = std::min(best, perCycle(n, cycles, false, false, true));
    std::printf("%5d groups of 3 axes (blended MC_MoveLinearRelative squares from ST): %8.2f us per cycle (best of 3, %llu cycles)\n", n,
                best * 1e6, static_cast<unsigned long long>(cycles));
  }
  for (int n : {1, 100}) {
    if (!only.empty() && only != "scara") continue;
    double best = 1e9;
    for (int rep = 0; rep < 3; ++rep) best = std::min(best, perCycle(n, cycles, false, false, true, false, true));
    std::printf("%5d SCARA groups (Kin_Scara2_Z, the same squares in MCS through the inverse kinematics): %8.2f us per cycle (best of 3, %llu cycles)\n",
                n, best * 1e6, static_cast<unsigned long long>(cycles));
  }
  if (only.empty() || only == "cnc") {
    for (int twoDir = 0; twoDir < 2; ++twoDir) {   // n = 2 selects SMC_Interpolator2Dir
      double best = 1e9;
      for (int rep = 0; rep < 3; ++rep) best = std::min(best, perCycle(twoDir ? 2 : 1, cycles, false, false, false, false, false, true));
      std::printf("    1 CNC pipeline (SMC_NCDecoder -> SMC_CheckVelocities -> %s -> 3 x SMC_ControlAxisByPos from ST): %8.2f us per cycle (best of 3, %llu cycles)\n",
                  twoDir ? "SMC_QueueSetReservedEntries -> SMC_Interpolator2Dir (+ _SlowTask)" : "SMC_Interpolator", best * 1e6,
                  static_cast<unsigned long long>(cycles));
    }
  }
  if (only.empty() || only == "trafo") {
    const int n = 1000;
    double best = 1e9;
    for (int rep = 0; rep < 3; ++rep) best = std::min(best, perCycle(n, cycles, false, false, false, true));
    std::printf("%5d SMC_TRAFO_Scara2 calls from ST: %8.2f us per cycle, %.0f ns per call (best of 3, %llu cycles)\n", n, best * 1e6,
                best * 1e9 / n, static_cast<unsigned long long>(cycles));
  }
  return 0;
}
