// Bad programs: every error at its exact line:col, rendered as ST errors are,
// several per run, and never a crash.
#include <cmath>
#include <limits>

#include "CncTestUtil.h"

namespace stc::cnc::test {
namespace {

// The first line of the only diagnostic of `text`.
std::string only(const std::string& text, VariableAccess* vars = nullptr) {
  Decoded r(text, {}, vars);
  auto h = r.heads();
  if (h.size() != 1) return "got " + std::to_string(h.size()) + " diagnostics:\n" + r.all();
  return h[0];
}

TEST(CncErrors, RenderedLikeSTDiagnostics) {
  Decoded r("N10 G1 X10 F1\nN20 G1 Q\n");
  ASSERT_EQ(r.errors(), 1u);
  EXPECT_EQ(r.all(),
            "prog.cnc:2:8: error: expected a number after 'Q', found end of line [gcode-syntax]\n"
            "  N20 G1 Q\n"
            "         ^\n");
}

TEST(CncErrors, Lexical) {
  EXPECT_EQ(only("G1 X1.2.3 F1\n"), "prog.cnc:1:4: error: malformed number '1.2.3' [gcode-syntax]");
  EXPECT_EQ(only("G1 X10-5 F1\n"), "prog.cnc:1:4: error: malformed number '10-5' [gcode-syntax]");
  EXPECT_EQ(only("G1 X. F1\n"), "prog.cnc:1:4: error: expected digits in the value of 'X' [gcode-syntax]");
  EXPECT_EQ(only("G1 X- F1\n"), "prog.cnc:1:4: error: expected a number after 'X', found ' ' [gcode-syntax]");
  EXPECT_EQ(only("G1 X10 (comment\n"),
            "prog.cnc:1:8: error: unterminated comment: '(' without ')' on this line [gcode-syntax]");
  EXPECT_EQ(only("G1 X$abc F1\n"),
            "prog.cnc:1:5: error: unterminated variable reference: '$' without a closing '$' [gcode-syntax]");
  EXPECT_EQ(only("G1 X$$ F1\n"), "prog.cnc:1:5: error: empty variable name [gcode-syntax]");
  EXPECT_EQ(only("G1 X10 #5 F1\n"), "prog.cnc:1:8: error: unexpected character '#' [gcode-syntax]");
  EXPECT_EQ(only("G1 X10 \xC3\xA9 F1\n"), "prog.cnc:1:8: error: unexpected character '\xC3\xA9' [gcode-syntax]");
  EXPECT_EQ(only("G1 XY10 F1\n"),
            "prog.cnc:1:4: error: unknown word 'XY10': a word is one address letter followed by a number "
            "[gcode-unknown-word]");
  EXPECT_EQ(only("N40 SubPrg{5}\n"),
            "prog.cnc:1:5: error: subprograms are not part of this G-code dialect (docs/cnc.md) [gcode-unsupported]");
  EXPECT_EQ(only("G1 X{1+2} F1\n"),
            "prog.cnc:1:5: error: expressions in braces are not part of this G-code dialect [gcode-unsupported]");
  EXPECT_EQ(only("G1 X10 / F1\n"),
            "prog.cnc:1:8: error: '/' (block skip) must be the first character of the block [gcode-syntax]");
  EXPECT_EQ(only("N10 G1 X1 F1\n%\nG1 X2\n"),
            "prog.cnc:3:1: warning: text after the closing '%' is ignored [-Wgcode-after-end]");
  EXPECT_EQ(only("N10 G1 X1 F1\n% late\n"),
            "prog.cnc:2:1: error: the program header '%name' must be the first line [gcode-syntax]");
  EXPECT_EQ(only("G1 X10 N5 F1\n"),
            "prog.cnc:1:8: error: the block number must be the first word of the block [gcode-syntax]");
  EXPECT_EQ(only("N020 G01 X7 Y10 N030 G01 X10 Y0\n"),
            "prog.cnc:1:17: error: a block has one block number N (start the next block on a new line) [gcode-syntax]");
  EXPECT_EQ(only("N1.5 G1 X1 F1\n"), "prog.cnc:1:1: error: a block number is 'N' followed by digits [gcode-syntax]");
  EXPECT_EQ(only("N99999999999 G1 X1 F1\n"),
            "prog.cnc:1:1: error: block number out of range (at most 2147483647) [gcode-range]");
}

TEST(CncErrors, WordValues) {
  EXPECT_EQ(only("G1 X1 F1 H40000\n"),
            "prog.cnc:1:10: error: H40000 is out of range (switch numbers are 1..32767, negative to switch off) "
            "[gcode-range]");
  EXPECT_EQ(only("M65534\n"),
            "prog.cnc:1:1: error: M65534 is reserved for internal functions (M functions are 1..65532) [gcode-range]");
  EXPECT_EQ(only("M70000\n"),
            "prog.cnc:1:1: error: M70000 is out of range (M functions are 1..65532) [gcode-range]");
  EXPECT_EQ(only("M0\n"), "prog.cnc:1:1: error: M0 is out of range (M functions are 1..65532) [gcode-range]");
  EXPECT_EQ(only("M1.5\n"), "prog.cnc:1:1: error: an M function number is an integer [gcode-range]");
  EXPECT_EQ(only("G1.5 X1\n"), "prog.cnc:1:1: error: a G code is a non-negative integer [gcode-range]");
  EXPECT_EQ(only("G944444444442 X1\n"), "prog.cnc:1:1: error: unknown G code 'G944444444442' [gcode-range]");
  EXPECT_EQ(only("G7 X1\n"), "prog.cnc:1:1: error: unknown G code 'G7' is not a G code of the dialect [gcode-unknown-code]");
  EXPECT_EQ(only("G43 X1\n"),
            "prog.cnc:1:1: error: unknown G code 'G43' (tool length) is a SoftMotion code this dialect does not "
            "include [gcode-unknown-code]");
  EXPECT_EQ(only("G1 X100000000000000000000 F1\n"),
            "prog.cnc:1:4: error: the value of 'X' (1e+20) is out of range (magnitude above 1e12) "
            "[gcode-range]");
  EXPECT_EQ(only("G1 X5000000000 F1\n"),
            "prog.cnc:1:4: error: coordinate X is out of range (magnitude above 1e9) [gcode-range]");
  EXPECT_EQ(only("G1 X1 F0\n"),
            "prog.cnc:1:7: error: the path velocity F must be > 0 and at most 1e9 (is 0) [gcode-range]");
  EXPECT_EQ(only("G1 X1 F1 E0\n"),
            "prog.cnc:1:10: error: the path acceleration E must be > 0 and at most 1e12 (is 0) [gcode-range]");
  EXPECT_EQ(only("G1 X1 F1 E-0\n"),
            "prog.cnc:1:10: error: the path deceleration E- must be > 0 and at most 1e12 (is 0) "
            "[gcode-range]");
  EXPECT_EQ(only("G4 T-1\n"), "prog.cnc:1:4: error: the dwell time T must be >= 0 and at most 1e6 s [gcode-range]");
  EXPECT_EQ(only("G3 I5 T0 F1\n"),
            "prog.cnc:1:7: error: the sweep T must be > 0 and at most 36000 degrees (is 0) [gcode-range]");
  EXPECT_EQ(only("G0 X10 Y0\nG98 G9 X0 Y5 I0 J0 R0 F1\n"),
            "prog.cnc:2:20: error: the axis ratio R must be in (0, 1] (is 0) [gcode-range]");
  EXPECT_EQ(only("G0 X10 Y0\nG98 G9 X0 Y5 I0 J0 R-0.5 F1\n"),
            "prog.cnc:2:20: error: the axis ratio R must be in (0, 1] (is -0.5) [gcode-range]");
  EXPECT_EQ(only("G1 X10 F1\nG1 X20 H1 O1.5\n"),
            "prog.cnc:2:11: error: the relative switch position O must be in [0, 1] (is 1.5) [gcode-range]");
  EXPECT_EQ(only("G2 X10 R0 F1\n"),
            "prog.cnc:1:8: error: the radius R must not be 0 and at most 1e9 in magnitude [gcode-range]");
  EXPECT_EQ(only("G41 D-1\n"), "prog.cnc:1:5: error: the tool radius D must be >= 0 and at most 1e9 [gcode-range]");
}

TEST(CncErrors, VariablesAreCheckedForFinitenessAndRange) {
  MapVars v;
  v.values = {{"nan", std::numeric_limits<double>::quiet_NaN()},
              {"inf", std::numeric_limits<double>::infinity()},
              {"big", 1e300},
              {"m", 65535},
              {"h", 0.5}};
  EXPECT_EQ(only("G1 X$nan$ F1\n", &v),
            "prog.cnc:1:4: error: the value of 'X' is not a finite number ($nan$ = nan) [gcode-range]");
  EXPECT_EQ(only("G1 X-$inf$ F1\n", &v),
            "prog.cnc:1:4: error: the value of 'X' is not a finite number ($inf$ = -inf) [gcode-range]");
  EXPECT_EQ(only("G1 X1 F$big$\n", &v),
            "prog.cnc:1:7: error: the value of 'F' (1e+300) is out of range (magnitude above 1e12) ($big$ = 1e+300) "
            "[gcode-range]");
  EXPECT_EQ(only("M$m$\n", &v),
            "prog.cnc:1:1: error: M65535 is reserved for internal functions (M functions are 1..65532) ($m$ = 65535) "
            "[gcode-range]");
  EXPECT_EQ(only("G1 X1 F1 H$h$\n", &v),
            "prog.cnc:1:10: error: a switch number H is an integer ($h$ = 0.5) [gcode-range]");
  EXPECT_EQ(only("G1 X$nope$ F1\n", &v), "prog.cnc:1:4: error: unknown variable '$nope$' [gcode-variable]");
  EXPECT_EQ(only("G1 X$x$ F1\n"),
            "prog.cnc:1:4: error: '$x$' needs a variable source (none was given to the decoder) [gcode-variable]");
  EXPECT_EQ(only("G$x$ X1\n", &v),
            "prog.cnc:1:1: error: a G code cannot come from a variable (the travel command is fixed at decode time) "
            "[gcode-syntax]");
}

TEST(CncErrors, DuplicatesAndConflicts) {
  Decoded dup("N10 G1 X1 F1\nN20 G1 X2\nN10 G1 X3\n");
  ASSERT_EQ(dup.heads().size(), 1u);
  EXPECT_EQ(dup.heads()[0], "prog.cnc:3:1: error: duplicate block number N10 [gcode-duplicate-n]");
  EXPECT_NE(dup.all().find("prog.cnc:1:1: note: N10 is first used on line 1"), std::string::npos) << dup.all();
  EXPECT_EQ(only("G1 X1 X2 F1\n"), "prog.cnc:1:7: error: duplicate word 'X' in one block [gcode-duplicate-word]");
  EXPECT_EQ(only("G1 G2 X10 R5 F1\n"), "prog.cnc:1:4: error: G2 conflicts with G1 in the same block [gcode-conflict]");
  EXPECT_EQ(only("G4 G1 X1 T1 F1\n"),
            "prog.cnc:1:4: error: G1 and G4 cannot be in the same block; write them in separate blocks "
            "[gcode-conflict]");
  EXPECT_EQ(only("G41 G51 D1\n"), "prog.cnc:1:9: error: 'D' is read by both G41 and G51; write them in separate blocks "
                                  "[gcode-conflict]");
  EXPECT_EQ(only("G20 L10 M5\nN10\n"),
            "prog.cnc:1:5: error: 'L' is read by both G20 and the M function; write them in separate blocks "
            "[gcode-conflict]");
  EXPECT_EQ(only("G2 X10 R5 I5 F1\n"),
            "prog.cnc:1:8: error: the radius R and the centre I/J/K cannot both describe an arc [gcode-conflict]");
  EXPECT_EQ(only("G3 X1 I5 T90 F1\n"),
            "prog.cnc:1:4: error: with a sweep T the end point follows from the centre and T; 'X' cannot be given "
            "[gcode-conflict]");
}

TEST(CncErrors, MissingWords) {
  EXPECT_EQ(only("G2 X10 Y0 F1\n"),
            "prog.cnc:1:1: error: G2 needs the centre (I/J/K), the radius R, or the centre and the sweep T "
            "[gcode-missing-word]");
  EXPECT_EQ(only("G3 X10 T90 F1\n"), "prog.cnc:1:8: error: the sweep T needs the arc's centre I/J/K [gcode-missing-word]");
  EXPECT_EQ(only("G4\n"), "prog.cnc:1:1: error: G4 needs the dwell time T (seconds) [gcode-missing-word]");
  EXPECT_EQ(only("G6 X10 Y10 F1\n"), "prog.cnc:1:1: error: G6 needs the parabola's vertex I/J [gcode-missing-word]");
  EXPECT_EQ(only("G8 X10 Y10 F1\n"), "prog.cnc:1:1: error: G8 needs the ellipse's centre I/J [gcode-missing-word]");
  EXPECT_EQ(only("G41\n"), "prog.cnc:1:1: error: G41 needs the tool radius D [gcode-missing-word]");
  EXPECT_EQ(only("G51\n"), "prog.cnc:1:1: error: G51 needs the corner distance D [gcode-missing-word]");
  EXPECT_EQ(only("G36\n"), "prog.cnc:1:1: error: G36 needs the value D [gcode-missing-word]");
  EXPECT_EQ(only("G20 K1\n"),
            "prog.cnc:1:1: error: G20 needs the jump target L (a block number or L?label) [gcode-missing-word]");
  EXPECT_EQ(only("X10 Y5\n"),
            "prog.cnc:1:1: error: axis words without a travel command: write G0, G1, G2 ... in this or an earlier "
            "block [gcode-missing-word]");
  EXPECT_EQ(only("G1 X1 F1\nH2 L5\n"),
            "prog.cnc:2:1: error: switch points (H) need a move in the same block [gcode-missing-word]");
}

TEST(CncErrors, GeometryAndPlanes) {
  EXPECT_EQ(only("G2 X10 Y0 I3 J0 F1\n"),
            "prog.cnc:1:1: error: the end point is not on the arc: it is 7 from the centre, the start 3 (the decoder "
            "corrects differences up to 10%) [gcode-arc]");
  EXPECT_EQ(only("G2 X10 Y0 R4 F1\n"),
            "prog.cnc:1:11: error: the radius 4 is smaller than half the chord (5): no arc of this radius joins the "
            "points [gcode-arc]");
  EXPECT_EQ(only("G2 R4 F1\n"),
            "prog.cnc:1:4: error: a full circle cannot be given by its radius; program the centre with I/J/K "
            "[gcode-arc]");
  EXPECT_EQ(only("G2 X1 I0 J0 F1\n"), "prog.cnc:1:1: error: the arc's centre is its start point (radius 0) [gcode-arc]");
  EXPECT_EQ(only("G18\nG6 X10 Y5 I2 J3 F1\n"),
            "prog.cnc:2:1: error: G6 works in the XY plane only (G17); the active plane is ZX [gcode-plane]");
  EXPECT_EQ(only("G16 I0 J0 K0\n"),
            "prog.cnc:1:1: error: G16 needs a plane normal I/J/K that is not zero [gcode-range]");
  EXPECT_EQ(only("G5 Z10 F1\n"),
            "prog.cnc:1:1: error: a G5 spline needs a move in X/Y (G10 is the 3D spline) [gcode-arc]");
}

TEST(CncErrors, Jumps) {
  EXPECT_EQ(only("N10 G20 L99\n"),
            "prog.cnc:1:9: error: jump to an unknown block: no block has N99 [gcode-jump]");
  EXPECT_EQ(only("N10 G1 X1 F1 L!3\nN20 G20 L?3\n"),
            "prog.cnc:2:9: error: L?3 jumps backwards to L!3 on line 1; label jumps only go forward [gcode-jump]");
  EXPECT_EQ(only("N10 G20 L?7\nN20 G1 X1 F1\n"),
            "prog.cnc:1:9: error: jump to an unknown label: no block has L!7 [gcode-jump]");
  EXPECT_EQ(only("G20 L1.5\n"),
            "prog.cnc:1:5: error: the jump target L is a block number (an integer from 0 to 2147483647) [gcode-jump]");
}

TEST(CncErrors, LoopGuardEndsAnEndlessJump) {
  DecoderOptions o;
  o.maxJumps = 1000;
  Decoded r("N10 G1 X1 F1\nN20 G1 X0\nN30 G20 L10\n", o);
  auto h = r.heads();
  ASSERT_EQ(h.size(), 1u) << r.all();
  EXPECT_EQ(h[0], "prog.cnc:3:5: error: more than 1000 jumps taken: the program loops without end (the decoder's "
                  "jump limit) [gcode-loop-limit]");
  EXPECT_EQ(r.els.size(), 2002u);
  // A loop that produces nothing is bounded the same way.
  Decoded silent("N10 G20 L10\n", o);
  EXPECT_EQ(silent.errors(), 1u);
  EXPECT_TRUE(silent.els.empty());
}

TEST(CncErrors, SeveralErrorsPerRunInLineOrder) {
  Decoded r("N10 G1 X1 F1\nN20 G1 X1..2\nN30 G2 X5\nN40 G1 Y$q\nN50 M70000\nN60 G1 X2\n");
  auto h = r.heads();
  ASSERT_EQ(h.size(), 4u) << r.all();
  EXPECT_EQ(h[0].substr(0, 14), "prog.cnc:2:8: ");
  EXPECT_EQ(h[1].substr(0, 14), "prog.cnc:3:5: ");
  EXPECT_EQ(h[2].substr(0, 14), "prog.cnc:4:9: ");
  EXPECT_EQ(h[3].substr(0, 14), "prog.cnc:5:5: ");
  // The good blocks still decode.
  ASSERT_EQ(r.els.size(), 2u);
  expectPos(r.els[1].end, {2, 0, 0});
}

TEST(CncErrors, StopAtFirstErrorAndSmcErrorIds) {
  SourceManager sm;
  DiagnosticsEngine diags(sm);
  uint32_t f = sm.addBuffer("p.cnc", "G1 X1 F1\nG1 X2 E0\nG1 X3\nG1 X4 E-0\n");
  DecoderOptions o;
  o.stopAtFirstError = true;
  Decoder dec(sm, f, diags, o);
  ElementQueue q(8);
  StepResult r = dec.step(q);
  EXPECT_EQ(r.status, StepStatus::Finished);
  EXPECT_EQ(dec.errorCount(), 1u);
  EXPECT_EQ(dec.firstError(), SmcError::AccTooLittle);
  EXPECT_EQ(q.size(), 1u);
  EXPECT_TRUE(q.endOfList);

  auto firstId = [](const char* text) {
    SourceManager s;
    DiagnosticsEngine d(s);
    Decoder x(s, s.addBuffer("p.cnc", text), d);
    ElementQueue q2(8);
    while (x.step(q2).status != StepStatus::Finished) q2.clear();
    return x.firstError();
  };
  EXPECT_EQ(firstId("G1 X1 F1 E-0\n"), SmcError::RetTooLittle);
  EXPECT_EQ(firstId("G20 L5\n"), SmcError::JumpToUnknownLine);
  EXPECT_EQ(firstId("G19\nG8 X1 Y1 I1 F1\n"), SmcError::ObjectNot3D);
  EXPECT_EQ(firstId("G1 B1 F1\nG1 V1\n"), SmcError::ExclusiveBV);
  EXPECT_EQ(firstId("G1 W1 F1 C2\n"), SmcError::ExclusiveCW);
  EXPECT_EQ(firstId("G1 X1 F1 #\n"), SmcError::InvalidSyntax);
  EXPECT_EQ(firstId("G1 X1 F1\n"), SmcError::NoError);
}

TEST(CncErrors, WarningsForUnusedWordsAndWordOrder) {
  Decoded r("G1 X10 R5 F1\nN2 X5 G1\nG1 X20\n");
  EXPECT_EQ(r.errors(), 0u);
  auto h = r.heads();
  ASSERT_EQ(h.size(), 2u) << r.all();
  EXPECT_EQ(h[0], "prog.cnc:1:8: warning: 'R' has no effect in a G1 block [-Wgcode-unused-word]");
  EXPECT_EQ(h[1], "prog.cnc:2:7: warning: G word after other words; the dialect writes N and G first "
                  "[-Wgcode-word-order]");
  Decoded nf("G1 X10\n");
  EXPECT_EQ(nf.heads()[0], "prog.cnc:1:1: warning: no path velocity: F is not programmed yet and the decoder has no "
                           "default velocity [-Wgcode-no-feed]");
}

TEST(CncErrors, HostileBytesNeverCrash) {
  std::string nasty;
  for (int i = 0; i < 256; ++i) nasty += static_cast<char>(i);
  nasty += "\nG1 X" + std::string(5000, '9') + "\nG2 I$" + std::string(300, 'a') + "\n((((\n$$$$\nN\nG\n%\n";
  Decoded r(nasty);
  EXPECT_GT(r.errors(), 0u);
  Decoded empty("");
  EXPECT_EQ(empty.errors(), 0u);
  EXPECT_TRUE(empty.els.empty());
  Decoded noNewline("G1 X5 F1");
  EXPECT_EQ(noNewline.els.size(), 1u);
}

}  // namespace
}  // namespace stc::cnc::test
