// cnc::Element <-> SMC_GEOINFO (stdlib-motion/codesys_sm3/Sm3GeoInfo.h): every element
// type the decoder makes survives the round trip bit for bit, and the SoftMotion-visible
// members carry what docs/cnc.md ("SMC_GEOINFO") says.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "CncTestUtil.h"
#include "stdlib-motion/codesys_sm3/Sm3GeoInfo.h"

using namespace stc::cnc;
using namespace stc::cnc::test;
using stc::motion::sm3face::fromGeoInfo;
using stc::motion::sm3face::sameElement;
using stc::motion::sm3face::toGeoInfo;
namespace sm3 = stc::native::sm3;

namespace {

// Every element type, every plane, marks, switch points, M with K/L, dwell, G92, G75.
const char* kProgram =
    "%roundtrip\n"
    "N10 G0 X10 Y0 Z1 F100 E1000 E-2000 S300\n"
    "N20 G1 X20 Y5 Z2 A3 H1 L2 H-2 O0.5 H3\n"
    "N30 G2 X30 Y15 I10 J0\n"                       // arc by centre (G99: relative)
    "N40 G3 X20 Y25 Z5 R10\n"                       // helix by radius
    "G18 G2 X30 Z15 R12\n"                          // ZX plane
    "G19 G3 Y30 Z20 R8\n"                           // YZ plane
    "G16 I1 J1 K1\n"
    "G2 I2 J-1 K-1 T90\n"                           // free plane, by sweep
    "G17 G5 X40 Y30\n"                              // 2D splines
    "G5 X50 Y35\n"
    "G10 X60 Y40 Z25\n"                             // 3D spline
    "G1 X70 Y40\n"
    "G6 X90 Y40 I80 J50\n"                          // parabola (vertex relative)
    "G0 X100 Y40\n"
    "G98 G8 X90 Y50 I90 J40 K0\n"                   // ellipse
    "G9 X80 Y40 I90 J40 K30 R0.5\n"
    "G99 G41 D2.5\n"
    "G51 D1\n"
    "G61\n"
    "G1 X90 Y45\n"
    "M7 K1.5 L-2.25\n"
    "G4 T1.5\n"
    "G75\n"
    "G92 X0 Y0\n"
    "G40\n"
    "G50\n"
    "G60\n"
    "G1 X1 Y1 W4\n";

TEST(GeoInfoRoundTrip, EveryElementTypeIsExact) {
  Decoded d(kProgram);
  for (const std::string& h : d.heads()) ADD_FAILURE() << h;
  ASSERT_EQ(d.errors(), 0u);
  std::set<MoveType> types;
  for (const Element& e : d.els) {
    types.insert(e.type);
    sm3::SMC_GEOINFO g;
    toGeoInfo(e, g);
    Element back;
    ASSERT_TRUE(fromGeoInfo(g, back)) << toString(e.type);
    EXPECT_TRUE(sameElement(e, back)) << "object " << e.objNo << " " << toString(e.type);
    // The SoftMotion members.
    EXPECT_EQ(g.iObjNo, e.objNo);
    EXPECT_EQ(g.iSourceLine_No, e.line - 1);
    EXPECT_EQ(g.diSentenceNo, e.blockNo);
    EXPECT_EQ(g.iMoveType, static_cast<int16_t>(e.type));
    EXPECT_EQ(g.piDestPos.dX, e.end[AxX]);
    EXPECT_EQ(g.piDestPos.dA, e.end[AxA]);
    EXPECT_EQ(g.piDestPos.dA5, e.end[AxW]);
    EXPECT_EQ(g.piStartPos.dY, e.start[AxY]);
    if (e.type == MoveType::Clw || e.type == MoveType::Cclw) {
      EXPECT_EQ(g.dP1, e.arc.centre[0]);
      EXPECT_EQ(g.dP2, e.arc.centre[1]);
      EXPECT_EQ(g.dP3, e.arc.radius);
      EXPECT_EQ(g.dP4, e.arc.centre[2]);
      EXPECT_EQ(g.vN.dZ, e.arc.normal[2]);
      EXPECT_NEAR(g.dT2, e.arc.sweep * 180 / std::numbers::pi, 1e-9);
    }
    if (e.type == MoveType::EllClw || e.type == MoveType::EllCclw) {
      EXPECT_EQ(g.dP5, e.ellipse.a);
      EXPECT_EQ(g.dP6, e.ellipse.b);
      EXPECT_DOUBLE_EQ(g.dP8, e.ellipse.b / e.ellipse.a);
    }
    if (e.type == MoveType::MCommand) {
      EXPECT_EQ(g.dP1, 7);
      EXPECT_EQ(g.dP16, 1.5);
      EXPECT_EQ(g.dP17, -2.25);
    }
  }
  const std::set<MoveType> all{MoveType::Lin,    MoveType::Clw,     MoveType::Cclw,   MoveType::Spline,
                               MoveType::Parabola, MoveType::EllClw, MoveType::EllCclw, MoveType::LinPos,
                               MoveType::InitPos, MoveType::MCommand, MoveType::Dwell,  MoveType::Sync};
  EXPECT_EQ(types, all);
  // Planes, marks and switch points made it into the program's elements.
  bool zx = false, yz = false, freePlane = false, marks = false, switches = false, spline3 = false;
  for (const Element& e : d.els) {
    zx |= e.plane == Plane::ZX && e.type == MoveType::Clw;
    yz |= e.plane == Plane::YZ && e.type == MoveType::Cclw;
    freePlane |= e.plane == Plane::Free && e.type == MoveType::Clw;
    marks |= e.marks != 0 && e.toolSide == ToolSide::Left && e.smoothing == Smoothing::Smooth && e.loopAvoid;
    switches |= e.switchCount == 3;
    spline3 |= e.type == MoveType::Spline && e.spline.dims == 3;
  }
  EXPECT_TRUE(zx && yz && freePlane && marks && switches && spline3);
}

TEST(GeoInfoRoundTrip, ExtremeValuesAndLongPrograms) {
  Element e;
  e.objNo = 70000;   // beyond INT: iObjNo wraps, diObjNo is exact
  e.line = 100000;   // iSourceLine_No saturates
  e.column = 12;
  e.type = MoveType::Lin;
  e.start[AxW] = -0.0;
  e.end[AxW] = 1e10;
  e.vel = 1e-300;
  sm3::SMC_GEOINFO g;
  toGeoInfo(e, g);
  EXPECT_EQ(g.iSourceLine_No, 32767);
  Element back;
  ASSERT_TRUE(fromGeoInfo(g, back));
  EXPECT_TRUE(sameElement(e, back));
}

TEST(GeoInfoRoundTrip, RefusesWhatItCannotHaveWritten) {
  Element e;
  sm3::SMC_GEOINFO g;
  toGeoInfo(e, g);
  Element back;
  g.iMoveType = 4;
  EXPECT_FALSE(fromGeoInfo(g, back));
  g.iMoveType = 356;   // 100 + 256: must not alias LINPOS
  EXPECT_FALSE(fromGeoInfo(g, back));
  g.iMoveType = 1;
  g.byNumHSwitches = 9;
  EXPECT_FALSE(fromGeoInfo(g, back));
  g.byNumHSwitches = 0;
  g.dP15 = std::nan("");
  EXPECT_FALSE(fromGeoInfo(g, back));
  g.dP15 = 0;
  g.iMoveType = static_cast<int16_t>(MoveType::Spline);
  g.dP8 = 4;
  EXPECT_FALSE(fromGeoInfo(g, back));
}

}  // namespace
