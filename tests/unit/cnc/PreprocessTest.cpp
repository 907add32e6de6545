// The path preprocessing cores (docs/cnc.md, "SMC_CheckVelocities", "SMC_SmoothPath",
// "SMC_CheckForLimits"): junction velocities against closed forms, corner splines and
// rounding arcs at their exact distances with tangent (and, between lines, curvature)
// continuity, exact bounding boxes of every element type.
#include <cmath>
#include <set>
#include <span>

#include "CncTestUtil.h"
#include "stdlib-motion/cnc/LimitsCheck.h"
#include "stdlib-motion/cnc/SmoothPath.h"
#include "stdlib-motion/cnc/VelocityCheck.h"

namespace stc::cnc::test {
namespace {

constexpr const char* kDyn = " F100 E1000 E-1000";

// Decodes `text` and runs the velocity check over all of it (end of list).
std::vector<Element> checked(const std::string& text, const VelocityCheckOptions& o = {}, size_t* finalized = nullptr,
                             bool* error = nullptr) {
  Decoded d(text);
  EXPECT_EQ(d.errors(), 0u) << d.all();
  std::vector<Element> els = d.els;
  VelocityCheckResult r = checkVelocities(els, true, false, o);
  if (finalized) *finalized = r.finalized;
  if (error) *error = r.error;
  if (!error) {
    EXPECT_FALSE(r.error);
    EXPECT_EQ(r.finalized, els.size());
  }
  return els;
}

// ---------------------------------------------------------------- velocity check

TEST(VelocityCheck, RightAngleCornerStops) {
  auto els = checked(std::string("G1 X10 Y0") + kDyn + "\nG1 X10 Y10\n");
  ASSERT_EQ(els.size(), 2u);
  EXPECT_EQ(els[0].velEnd, 0);
  EXPECT_EQ(els[1].velEnd, 0);   // end of the list
  for (const Element& e : els) EXPECT_TRUE(e.marks & MarkVelChecked);
}

TEST(VelocityCheck, CollinearLinesKeepTheSmallerVelocity) {
  auto els = checked(std::string("G1 X10") + kDyn + "\nG1 X20 F50\nG1 X30 F70\n");
  ASSERT_EQ(els.size(), 3u);
  EXPECT_EQ(els[0].velEnd, 50);
  EXPECT_EQ(els[1].velEnd, 50);
  EXPECT_EQ(els[2].velEnd, 0);
}

TEST(VelocityCheck, TangentLineArcJoin) {
  // The arc starts at (10,0) with centre (10,10), counter-clockwise: tangent +X.
  auto els = checked(std::string("G1 X10 Y0") + kDyn + "\nG3 X20 Y10 I0 J10 F80\nG1 X20 Y20\n");
  ASSERT_EQ(els.size(), 3u);
  EXPECT_EQ(els[0].velEnd, 80);
  EXPECT_EQ(els[1].velEnd, 80);   // the arc ends with tangent +Y: the line goes on along +Y
}

TEST(VelocityCheck, AngleToleranceInDegrees) {
  VelocityCheckOptions o;
  o.angleTolDeg = 1;
  auto program = [](double deg) {
    const double y = 10 * std::tan(deg * kPi / 180);
    return std::string("G1 X10 Y0") + kDyn + "\nG1 X20 Y" + std::to_string(y).substr(0, 14) + "\n";
  };
  EXPECT_EQ(checked(program(0.99), o)[0].velEnd, 100);
  EXPECT_EQ(checked(program(1.01), o)[0].velEnd, 0);
  EXPECT_NEAR(turnAngleDeg(checked(program(0.99), o)[0], checked(program(0.99), o)[1]), 0.99, 1e-5);
}

TEST(VelocityCheck, StopsAtG0MDwellSyncInitPos) {
  for (const char* mid : {"G0 X20", "M7", "G4 T1", "G75", "G92 X0"}) {
    auto els = checked(std::string("G1 X10") + kDyn + " FF100 EF1000 EF-1000\n" + mid + "\nG1 X30\n");
    ASSERT_GE(els.size(), 3u) << mid;
    EXPECT_EQ(els[0].velEnd, 0) << mid;
  }
}

TEST(VelocityCheck, PreAcknowledgedMIsPassedThrough) {
  Decoded d(std::string("G1 X10") + kDyn + "\nM7\nG1 X20 F60\n");
  ASSERT_EQ(d.els.size(), 3u);
  std::vector<Element> els = d.els;
  els[1].marks |= MarkMPreAcknowledged;
  // Without the successor of the M the line is not final yet.
  EXPECT_EQ(checkVelocities(std::span(els).first(2), false, false, {}).finalized, 0u);
  // With it, the junction is computed across the M.
  VelocityCheckResult r = checkVelocities(els, true, false, {});
  EXPECT_EQ(r.finalized, 3u);
  EXPECT_EQ(els[0].velEnd, 60);
  EXPECT_TRUE(els[1].marks & MarkVelChecked);
  // A full queue that ends in the pre-acknowledged M: stop rather than wait forever.
  std::vector<Element> two(d.els.begin(), d.els.begin() + 2);
  two[1].marks |= MarkMPreAcknowledged;
  EXPECT_EQ(checkVelocities(two, false, true, {}).finalized, 2u);
  EXPECT_EQ(two[0].velEnd, 0);
  // Not at the front of the queue (checked elements before it can be consumed): it waits.
  std::vector<Element> three(d.els.begin(), d.els.begin() + 2);
  three.insert(three.begin(), d.els[0]);
  three[2].marks |= MarkMPreAcknowledged;
  EXPECT_EQ(checkVelocities(std::span(three).subspan(1), false, false, {}).finalized, 0u);
}

TEST(VelocityCheck, StreamingWaitsForTheSuccessor) {
  Decoded d(std::string("G1 X10") + kDyn + "\nG1 X20\n");
  std::vector<Element> els = d.els;
  VelocityCheckResult r = checkVelocities(std::span(els).first(1), false, false, {});
  EXPECT_EQ(r.finalized, 0u);
  EXPECT_FALSE(els[0].marks & MarkVelChecked);
  r = checkVelocities(els, false, false, {});
  EXPECT_EQ(r.finalized, 1u);   // the last waits for its successor or the end of the list
  EXPECT_EQ(els[0].velEnd, 100);
  r = checkVelocities(std::span(els).subspan(1), true, false, {});
  EXPECT_EQ(r.finalized, 1u);
  EXPECT_EQ(els[1].velEnd, 0);
}

TEST(VelocityCheck, DryRunCapsEveryVelocity) {
  VelocityCheckOptions o;
  o.dryRunVelocity = 30;
  auto els = checked(std::string("G1 X10") + kDyn + "\nG1 X20 F20\nG1 X30 F100\n", o);
  EXPECT_EQ(els[0].vel, 30);
  EXPECT_EQ(els[0].velEnd, 20);
  EXPECT_EQ(els[1].vel, 20);
  EXPECT_EQ(els[1].velEnd, 20);
  EXPECT_EQ(els[2].vel, 30);
}

TEST(VelocityCheck, NonPositiveDynamicsIsError1100AtTheElement) {
  size_t fin = 99;
  bool err = false;
  // E- never programmed on the second element's block: its dec is 0.
  Decoded d("M5\nG1 X10 F100 E10\nG1 X20\n");
  std::vector<Element> els = d.els;
  VelocityCheckResult r = checkVelocities(els, true, false, {});
  EXPECT_TRUE(r.error);
  EXPECT_EQ(r.finalized, 1u);   // the M before it (no dynamics needed) is final
  EXPECT_EQ(els[r.finalized].line, 2);
  // G0 needs dynamics too.
  checked("G0 X10\n", {}, &fin, &err);
  EXPECT_TRUE(err);
  EXPECT_EQ(fin, 0u);
}

TEST(VelocityCheck, AdditionalAxisVelocityJump) {
  VelocityCheckOptions o;
  o.checkAddAxVelJump = true;
  o.maxAddAxVelDifference = 5;
  // A moves 1 per unit of path on the first line, 2 on the second: the jump at v is v x 1.
  auto els = checked(std::string("G1 X10 A10") + kDyn + "\nG1 X20 A30\n", o);
  EXPECT_NEAR(els[0].velEnd, 5, 1e-12);
  // Equal rates: no cap.
  EXPECT_EQ(checked(std::string("G1 X10 A10") + kDyn + "\nG1 X20 A20\n", o)[0].velEnd, 100);
  o.checkAddAxVelJump = false;
  EXPECT_EQ(checked(std::string("G1 X10 A10") + kDyn + "\nG1 X20 A30\n", o)[0].velEnd, 100);
}

TEST(VelocityCheck, InvalidOptions) {
  VelocityCheckOptions o;
  EXPECT_TRUE(validOptions(o));
  o.angleTolDeg = NAN;
  EXPECT_FALSE(validOptions(o));
  o = {};
  o.dryRunVelocity = -1;
  EXPECT_FALSE(validOptions(o));
  o = {};
  o.maxAddAxVelDifference = INFINITY;
  EXPECT_FALSE(validOptions(o));
}

// ---------------------------------------------------------------- smoothing

std::vector<Element> smoothed(const std::string& text, const SmoothOptions& o = {}) {
  Decoded d(text);
  EXPECT_EQ(d.errors(), 0u) << d.all();
  PathSmoother s(o);
  std::vector<Element> out;
  for (const Element& e : d.els) {
    const size_t before = out.size();
    s.push(e, out);
    EXPECT_LE(out.size() - before, 3u);
  }
  s.finish(out);
  for (size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].objNo, static_cast<int32_t>(i + 1));
    if (i > 0 && isMotion(out[i].type) && isMotion(out[i - 1].type)) {
      for (int k = 0; k < kAxisCount; ++k) EXPECT_NEAR(out[i].start[k], out[i - 1].end[k], 1e-12) << "gap before " << i;
    }
  }
  return out;
}

void expectTangentContinuous(const Element& a, const Element& b) {
  expectVec(endTangent(a), startTangent(b), 1e-9);
}

TEST(SmoothPath, SplineAtDistanceDWithCurvatureContinuity) {
  auto out = smoothed(std::string("G51 D2\nG1 X10 Y0") + kDyn + "\nG1 X10 Y10\nG1 X20 Y10\nG50\nG1 X30 Y10\n");
  // line, spline, line, spline, line, line (after G50)
  ASSERT_EQ(out.size(), 6u);
  EXPECT_EQ(out[0].type, MoveType::Lin);
  EXPECT_EQ(out[1].type, MoveType::Spline);
  EXPECT_EQ(out[2].type, MoveType::Lin);
  EXPECT_EQ(out[3].type, MoveType::Spline);
  // Shortened lines keep their direction and their far ends.
  expectPos(out[0].start, {0, 0});
  expectPos(out[0].end, {8, 0}, 1e-12);
  expectPos(out[2].start, {10, 2}, 1e-12);
  expectPos(out[2].end, {10, 8}, 1e-12);
  expectPos(out[4].start, {12, 10}, 1e-12);
  expectPos(out[4].end, {20, 10});
  EXPECT_NEAR(out[0].length, 8, 1e-12);
  EXPECT_NEAR(out[2].length, 6, 1e-12);
  // The spline starts and ends exactly d = 2 from the corner on both lines.
  EXPECT_NEAR(norm(xyz(out[1].start) - Vec3{10, 0, 0}), 2, 1e-12);
  EXPECT_NEAR(norm(xyz(out[1].end) - Vec3{10, 0, 0}), 2, 1e-12);
  for (int i : {0, 1, 2, 3}) expectTangentContinuous(out[i], out[i + 1]);
  // Curvature 0 at both ends: the Bezier's inner control points are the corner.
  const Element& sp = out[1];
  expectVec(xyz(sp.start) + (sp.spline.chord / 3) * sp.spline.t0, {10, 0, 0}, 1e-12);
  expectVec(xyz(sp.end) - (sp.spline.chord / 3) * sp.spline.t1, {10, 0, 0}, 1e-12);
  EXPECT_EQ(out[5].type, MoveType::Lin);
  expectPos(out[5].start, {20, 10});
  // The spline sits inside the corner (its midpoint is the Bezier's (P0 + 6C + P3) / 8).
  expectPos(point(sp, 0.5), {(8 + 60 + 10) / 8.0, (0 + 0 + 2) / 8.0}, 1e-12);
}

TEST(SmoothPath, EdgeDistanceAddsToD) {
  SmoothOptions o;
  o.edgeDistance = 1;
  auto out = smoothed(std::string("G51 D0.5\nG1 X10 Y0") + kDyn + "\nG1 X10 Y10\n", o);
  ASSERT_EQ(out.size(), 3u);
  expectPos(out[1].start, {8.5, 0}, 1e-12);
  expectPos(out[1].end, {10, 1.5}, 1e-12);
}

TEST(SmoothPath, NothingAroundG0OrWithDistanceZero) {
  auto out = smoothed(std::string("G51 D2\nG1 X10 Y0") + kDyn + "\nG0 X10 Y10\nG1 X20 Y10\n");
  ASSERT_EQ(out.size(), 3u);
  for (const Element& e : out) EXPECT_NE(e.type, MoveType::Spline);
  out = smoothed(std::string("G51 D0\nG1 X10 Y0") + kDyn + "\nG1 X10 Y10\n");
  ASSERT_EQ(out.size(), 2u);
  out = smoothed(std::string("G1 X10 Y0") + kDyn + "\nG1 X10 Y10\n");   // no G51
  ASSERT_EQ(out.size(), 2u);
  // Collinear lines: nothing to smooth.
  out = smoothed(std::string("G51 D2\nG1 X10") + kDyn + "\nG1 X20\n");
  ASSERT_EQ(out.size(), 2u);
}

TEST(SmoothPath, ShortElementsClampToHalfTheirLength) {
  // The middle line is 2 long: each of its corners may take 1.
  auto out = smoothed(std::string("G51 D3\nG1 X10 Y0") + kDyn + "\nG1 X10 Y2\nG1 X20 Y2\n");
  // line, spline, (middle line used up), spline, line
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[1].type, MoveType::Spline);
  EXPECT_EQ(out[2].type, MoveType::Spline);
  expectPos(out[0].end, {7, 0}, 1e-12);        // 3 before the first corner
  expectPos(out[1].end, {10, 1}, 1e-12);       // 1 after it (half the middle line)
  expectPos(out[2].end, {13, 2}, 1e-12);
  expectTangentContinuous(out[1], out[2]);
  // Symmetric distances: 1 on both sides of each corner.
  SmoothOptions o;
  o.symmetric = true;
  out = smoothed(std::string("G51 D3\nG1 X10 Y0") + kDyn + "\nG1 X10 Y2\nG1 X20 Y2\n", o);
  ASSERT_EQ(out.size(), 4u);
  expectPos(out[0].end, {9, 0}, 1e-12);
  expectPos(out[2].end, {11, 2}, 1e-12);
}

TEST(SmoothPath, LineArcCornerIsTangentContinuous) {
  // A line along +X into an arc that starts along +Y.
  auto out = smoothed(std::string("G51 D1\nG1 X10 Y0") + kDyn + "\nG3 X0 Y10 I-10 J0\n");
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[1].type, MoveType::Spline);
  EXPECT_EQ(out[2].type, MoveType::Cclw);
  expectTangentContinuous(out[0], out[1]);
  expectTangentContinuous(out[1], out[2]);
  // The arc was cut by an arc length of 1: its sweep lost 1 / r = 0.1 rad.
  EXPECT_NEAR(out[2].arc.sweep, kPi / 2 - 0.1, 1e-12);
  EXPECT_NEAR(out[2].arc.radius, 10, 1e-12);
  expectPos(out[2].end, {0, 10}, 1e-12);
  EXPECT_NEAR(norm(xyz(out[2].start) - Vec3{0, 0, 0}), 10, 1e-12);   // on the circle
}

TEST(SmoothPath, RoundingArcTangentToBothLines) {
  auto out = smoothed(std::string("G52 D2\nG1 X10 Y0") + kDyn + "\nG1 X10 Y10\n");
  ASSERT_EQ(out.size(), 3u);
  const Element& a = out[1];
  ASSERT_EQ(a.type, MoveType::Cclw);
  EXPECT_NEAR(a.arc.radius, 2, 1e-12);   // d / tan(45 deg)
  expectVec(a.arc.centre, {8, 2, 0}, 1e-12);
  EXPECT_NEAR(a.arc.sweep, kPi / 2, 1e-12);
  expectPos(a.start, {8, 0}, 1e-12);
  expectPos(a.end, {10, 2}, 1e-12);
  expectPos(point(a, 1), {10, 2}, 1e-12);
  expectTangentContinuous(out[0], a);
  expectTangentContinuous(a, out[2]);
  EXPECT_NEAR(a.length, kPi, 1e-12);
  // A clockwise 60 degree turn: r = d / tan(30 deg).
  out = smoothed(std::string("G52 D1\nG1 X10 Y0") + kDyn + "\nG1 X15 Y-8.660254037844386\n");
  ASSERT_EQ(out.size(), 3u);
  ASSERT_EQ(out[1].type, MoveType::Clw);
  EXPECT_NEAR(out[1].arc.radius, 1 / std::tan(kPi / 6), 1e-9);
  expectTangentContinuous(out[0], out[1]);
  expectTangentContinuous(out[1], out[2]);
  EXPECT_NEAR(norm(xyz(out[1].end) - Vec3{10, 0, 0}), 1, 1e-12);
}

TEST(SmoothPath, SwitchPointsStayOnThePath) {
  // H1 at 9 from the start of a 10 long line: the line is cut at 8, the switch moves to its end.
  auto out = smoothed(std::string("G51 D2\nG1 X10 Y0 H1 L9 H2 L1") + kDyn + "\nG1 X10 Y10\n");
  ASSERT_EQ(out.size(), 3u);
  ASSERT_EQ(out[0].switchCount, 2);
  EXPECT_NEAR(out[0].switches[0].pos, 8, 1e-12);
  EXPECT_NEAR(out[0].switches[1].pos, 1, 1e-12);
}

TEST(SmoothPath, InvalidOptions) {
  SmoothOptions o;
  EXPECT_TRUE(validOptions(o));
  o.edgeDistance = -1;
  EXPECT_FALSE(validOptions(o));
  o.edgeDistance = NAN;
  EXPECT_FALSE(validOptions(o));
  o.edgeDistance = 1e10;
  EXPECT_FALSE(validOptions(o));
}

// ---------------------------------------------------------------- limits

TEST(LimitsCheck, ArcBulgingBeyondMaxYIsCaughtAtItsLine) {
  Decoded d(std::string("G1 X-10 Y0") + kDyn + "\nG2 X10 Y0 R10\nG1 X30\n");
  ASSERT_EQ(d.els.size(), 3u);
  Pos lo{}, hi{};
  lo.fill(-100);
  hi.fill(100);
  hi[AxY] = 9.5;
  const uint16_t xyz = 0b111;
  EXPECT_EQ(axesOutOfLimits(d.els[0], lo, hi, xyz), 0);
  EXPECT_EQ(axesOutOfLimits(d.els[1], lo, hi, xyz), 1u << AxY);
  EXPECT_EQ(d.els[1].line, 2);
  // Exactly at the limit passes.
  hi[AxY] = 10;
  EXPECT_EQ(axesOutOfLimits(d.els[1], lo, hi, xyz), 0);
  // Additional axes only when selected.
  Decoded a(std::string("G1 X1 A50") + kDyn + "\n");
  hi[AxA] = 40;
  EXPECT_EQ(axesOutOfLimits(a.els[0], lo, hi, xyz), 0);
  EXPECT_EQ(axesOutOfLimits(a.els[0], lo, hi, xyz | (1u << AxA)), 1u << AxA);
}

// The exact box against a dense sampling for every curved type.
TEST(LimitsCheck, BoundsMatchDenseSampling) {
  const char* programs[] = {
      "G1 X5 Y5 F1 E1 E-1\nG2 X-5 Y-5 I-5 J-5 Z7\n",                   // helix, more than half a turn
      "G1 X5 Y0 F1 E1 E-1\nG3 I-5 J0 Z30 T1080\n",               // three turns up
      "G18\nG1 X5 Z0 F1 E1 E-1\nG2 X-5 Z0 I-5 K0\n",                   // ZX plane
      "G1 X5 Y0 F1 E1 E-1\nG8 X-3 Y4 I-5 J0 K1 R0.4\n",                // ellipse
      "G1 X0 Y0 F1 E1 E-1\nG6 X10 Y0 I5 J8\n",                          // parabola
      "G1 X0 Y0 F1 E1 E-1\nG5 X10 Y5\nG5 X0 Y10\nG5 X3 Y-4\nG1 X4\n",   // splines
  };
  std::set<MoveType> seen;
  for (const char* p : programs) {
    Decoded d(p);
    ASSERT_EQ(d.errors(), 0u) << p << d.all();
    for (const Element& e : d.els) {
      if (!isMotion(e.type)) continue;
      seen.insert(e.type);
      Pos lo, hi;
      elementBounds(e, lo, hi);
      Pos slo = e.start, shi = e.start;
      for (int i = 0; i <= 20000; ++i) {
        Pos q = point(e, i / 20000.0);
        for (int k = 0; k < kAxisCount; ++k) {
          slo[k] = std::min(slo[k], q[k]);
          shi[k] = std::max(shi[k], q[k]);
          EXPECT_GE(q[k], lo[k] - 1e-9) << p << " axis " << k;
          EXPECT_LE(q[k], hi[k] + 1e-9) << p << " axis " << k;
        }
      }
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(lo[k], slo[k], 1e-5) << p << " " << toString(e.type) << " axis " << k;
        EXPECT_NEAR(hi[k], shi[k], 1e-5) << p << " " << toString(e.type) << " axis " << k;
      }
    }
  }
  for (MoveType t : {MoveType::Clw, MoveType::Cclw, MoveType::EllClw, MoveType::Parabola, MoveType::Spline})
    EXPECT_TRUE(seen.count(t)) << toString(t);
}

}  // namespace
}  // namespace stc::cnc::test
