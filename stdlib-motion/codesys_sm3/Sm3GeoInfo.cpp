// cnc::Element <-> SMC_GEOINFO: see Sm3GeoInfo.h and docs/cnc.md ("SMC_GEOINFO").
#include "stdlib-motion/codesys_sm3/Sm3GeoInfo.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

namespace stc::motion::sm3face {

namespace sm3 = native::sm3;
using cnc::Element;
using cnc::MoveType;

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

void toPos(const cnc::Pos& p, uint16_t axes, sm3::SMC_POSINFO& o) {
  o.iFrame_Nr = 0;
  o.wAuxData = static_cast<uint16_t>(axes | 0x7u);
  o.wSProfile = 0;
  o.dX = p[cnc::AxX];
  o.dY = p[cnc::AxY];
  o.dZ = p[cnc::AxZ];
  o.dA = p[cnc::AxA];
  o.dB = p[cnc::AxB];
  o.dC = p[cnc::AxC];
  o.dA1 = p[cnc::AxP];
  o.dA2 = p[cnc::AxQ];
  o.dA3 = p[cnc::AxU];
  o.dA4 = p[cnc::AxV];
  o.dA5 = p[cnc::AxW];
  o.dA6 = 0;
}
void fromPos(const sm3::SMC_POSINFO& o, cnc::Pos& p) {
  p[cnc::AxX] = o.dX;
  p[cnc::AxY] = o.dY;
  p[cnc::AxZ] = o.dZ;
  p[cnc::AxA] = o.dA;
  p[cnc::AxB] = o.dB;
  p[cnc::AxC] = o.dC;
  p[cnc::AxP] = o.dA1;
  p[cnc::AxQ] = o.dA2;
  p[cnc::AxU] = o.dA3;
  p[cnc::AxV] = o.dA4;
  p[cnc::AxW] = o.dA5;
}
void toVec(const cnc::Vec3& v, sm3::SMC_VECTOR3D& o) {
  o.dX = v[0];
  o.dY = v[1];
  o.dZ = v[2];
}
cnc::Vec3 fromVec(const sm3::SMC_VECTOR3D& o) { return {o.dX, o.dY, o.dZ}; }

// dP1..dP18 as an array (they are consecutive LREALs).
double* params(sm3::SMC_GEOINFO& g) { return &g.dP1; }
const double* params(const sm3::SMC_GEOINFO& g) { return &g.dP1; }
static_assert(offsetof(sm3::SMC_GEOINFO, dP18) == offsetof(sm3::SMC_GEOINFO, dP1) + 17 * sizeof(double));

void put3(double* p, const cnc::Vec3& v) { std::copy(v.begin(), v.end(), p); }
cnc::Vec3 get3(const double* p) { return {p[0], p[1], p[2]}; }

bool knownType(int16_t t) {
  if (t < 0 || t > 255) return false;
  switch (static_cast<MoveType>(t)) {
  case MoveType::Lin: case MoveType::Clw: case MoveType::Cclw: case MoveType::Spline: case MoveType::Parabola:
  case MoveType::EllClw: case MoveType::EllCclw: case MoveType::LinPos: case MoveType::InitPos: case MoveType::MCommand:
  case MoveType::Dwell: case MoveType::Sync: return true;
  }
  return false;
}

}  // namespace

void toGeoInfo(const Element& e, sm3::SMC_GEOINFO& g) {
  std::memset(&g, 0, sizeof g);
  g.iObjNo = static_cast<int16_t>(static_cast<uint16_t>(e.objNo));
  g.iSourceLine_No = static_cast<int16_t>(std::clamp(e.line - 1, -1, 32767));
  g.diSentenceNo = e.blockNo;
  g.iMoveType = static_cast<int16_t>(e.type);
  toPos(e.start, e.axesUsed, g.piStartPos);
  toPos(e.end, e.axesUsed, g.piDestPos);
  double* p = params(g);
  g.vX = {1, 0, 0};
  g.vY = {0, 1, 0};
  g.vN = {0, 0, 1};
  g.dT1 = 0;
  g.dT2 = 1;
  switch (e.type) {
  case MoveType::Clw:
  case MoveType::Cclw: {
    const cnc::ArcGeo& a = e.arc;
    p[0] = a.centre[0];
    p[1] = a.centre[1];
    p[2] = a.radius;
    p[3] = a.centre[2];
    p[4] = a.startAngle;
    p[5] = a.sweep;
    p[6] = a.rise;
    toVec(a.u, g.vX);
    toVec(a.v, g.vY);
    toVec(a.normal, g.vN);
    g.dT1 = a.startAngle * kDeg;
    g.dT2 = a.sweep * kDeg;
    break;
  }
  case MoveType::EllClw:
  case MoveType::EllCclw: {
    const cnc::EllipseGeo& el = e.ellipse;
    p[0] = el.centre[0];
    p[1] = el.centre[1];
    p[2] = el.major[0];
    p[3] = el.major[1];
    p[4] = el.a;
    p[5] = el.b;
    p[6] = el.majorAngle;
    p[7] = el.a != 0 ? el.b / el.a : 0;
    p[8] = el.centre[2];
    p[9] = el.major[2];
    p[10] = el.startPhi;
    p[11] = el.sweepPhi;
    p[12] = el.rise;
    g.dT1 = el.startPhi * kDeg;
    g.dT2 = el.sweepPhi * kDeg;
    break;
  }
  case MoveType::Spline:
    put3(p, e.spline.t0);
    put3(p + 3, e.spline.t1);
    p[6] = e.spline.chord;
    p[7] = e.spline.dims;
    break;
  case MoveType::Parabola:
    put3(p, e.parabola.vertex);
    put3(p + 3, e.parabola.control);
    break;
  case MoveType::MCommand:
  case MoveType::Sync:
    p[0] = e.m;   // SoftMotion: the M number in dP1
    break;
  default: break;
  }
  p[14] = e.m;
  p[15] = e.k;
  p[16] = e.l;
  p[17] = e.dwell;
  g.dVel = e.vel;
  g.dVelEnd = e.velEnd;
  g.dAccel = e.acc;
  g.dDecel = e.dec;
  g.dLength = e.length;
  g.dS = e.s;
  g.dToolRadius = e.toolRadius;
  g.dSmoothDistance = e.smoothDist;
  g.wIntMark = e.marks;
  g.wAxesUsed = e.axesUsed;
  g.byPlane = static_cast<uint8_t>(e.plane);
  g.byToolCorr = static_cast<uint8_t>(e.toolSide);
  g.bySmoothing = static_cast<uint8_t>(e.smoothing);
  g.bLoopAvoid = e.loopAvoid;
  g.byNumHSwitches = e.switchCount;
  g.diObjNo = e.objNo;
  g.diSourceLine = e.line;
  g.diSourceColumn = e.column;
  for (int i = 0; i < cnc::kMaxSwitches; ++i) {
    g.aHSwitches[i].iSwitch = e.switches[i].sw;
    g.aHSwitches[i].bRelative = e.switches[i].relative;
    g.aHSwitches[i].dPos = e.switches[i].pos;
  }
}

bool fromGeoInfo(const sm3::SMC_GEOINFO& g, Element& e) {
  if (!knownType(g.iMoveType) || g.byNumHSwitches > cnc::kMaxSwitches || g.byPlane > 3 || g.byToolCorr > 2 ||
      g.bySmoothing > 2)
    return false;
  e = Element();
  e.objNo = g.diObjNo;
  e.line = g.diSourceLine;
  e.column = g.diSourceColumn;
  e.blockNo = g.diSentenceNo;
  e.type = static_cast<MoveType>(g.iMoveType);
  e.plane = static_cast<cnc::Plane>(g.byPlane);
  e.marks = g.wIntMark;
  e.axesUsed = g.wAxesUsed;
  fromPos(g.piStartPos, e.start);
  fromPos(g.piDestPos, e.end);
  e.vel = g.dVel;
  e.velEnd = g.dVelEnd;
  e.acc = g.dAccel;
  e.dec = g.dDecel;
  e.s = g.dS;
  e.length = g.dLength;
  e.toolSide = static_cast<cnc::ToolSide>(g.byToolCorr);
  e.smoothing = static_cast<cnc::Smoothing>(g.bySmoothing);
  e.loopAvoid = g.bLoopAvoid;
  e.toolRadius = g.dToolRadius;
  e.smoothDist = g.dSmoothDistance;
  const double* p = params(g);
  switch (e.type) {
  case MoveType::Clw:
  case MoveType::Cclw:
    e.arc.centre = {p[0], p[1], p[3]};
    e.arc.radius = p[2];
    e.arc.startAngle = p[4];
    e.arc.sweep = p[5];
    e.arc.rise = p[6];
    e.arc.u = fromVec(g.vX);
    e.arc.v = fromVec(g.vY);
    e.arc.normal = fromVec(g.vN);
    break;
  case MoveType::EllClw:
  case MoveType::EllCclw:
    e.ellipse.centre = {p[0], p[1], p[8]};
    e.ellipse.major = {p[2], p[3], p[9]};
    e.ellipse.a = p[4];
    e.ellipse.b = p[5];
    e.ellipse.majorAngle = p[6];
    e.ellipse.startPhi = p[10];
    e.ellipse.sweepPhi = p[11];
    e.ellipse.rise = p[12];
    break;
  case MoveType::Spline:
    if (p[7] != 2 && p[7] != 3) return false;
    e.spline.t0 = get3(p);
    e.spline.t1 = get3(p + 3);
    e.spline.chord = p[6];
    e.spline.dims = static_cast<uint8_t>(p[7]);
    break;
  case MoveType::Parabola:
    e.parabola.vertex = get3(p);
    e.parabola.control = get3(p + 3);
    break;
  default: break;
  }
  if (!(p[14] >= 0 && p[14] <= 65535)) return false;
  e.m = static_cast<uint16_t>(p[14]);
  e.k = p[15];
  e.l = p[16];
  e.dwell = p[17];
  e.switchCount = g.byNumHSwitches;
  for (int i = 0; i < cnc::kMaxSwitches; ++i) {
    e.switches[i].sw = g.aHSwitches[i].iSwitch;
    e.switches[i].relative = g.aHSwitches[i].bRelative;
    e.switches[i].pos = g.aHSwitches[i].dPos;
  }
  return true;
}

namespace {
template <size_t N>
bool same(const std::array<double, N>& a, const std::array<double, N>& b) {
  for (size_t i = 0; i < N; ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(double)) != 0) return false;
  return true;
}
bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }   // bit-exact (also -0, NaN)
}  // namespace

bool sameElement(const Element& a, const Element& b) {
  bool ok = a.objNo == b.objNo && a.line == b.line && a.column == b.column && a.blockNo == b.blockNo && a.type == b.type &&
            a.plane == b.plane && a.marks == b.marks && a.axesUsed == b.axesUsed && same(a.start, b.start) && same(a.end, b.end) &&
            same(a.vel, b.vel) && same(a.velEnd, b.velEnd) && same(a.acc, b.acc) && same(a.dec, b.dec) && same(a.s, b.s) && same(a.length, b.length) &&
            a.toolSide == b.toolSide && a.smoothing == b.smoothing && a.loopAvoid == b.loopAvoid && same(a.toolRadius, b.toolRadius) &&
            same(a.smoothDist, b.smoothDist) && a.m == b.m && same(a.k, b.k) && same(a.l, b.l) && same(a.dwell, b.dwell) &&
            a.switchCount == b.switchCount;
  for (int i = 0; ok && i < cnc::kMaxSwitches; ++i)
    ok = a.switches[i].sw == b.switches[i].sw && a.switches[i].relative == b.switches[i].relative && same(a.switches[i].pos, b.switches[i].pos);
  if (!ok) return false;
  switch (a.type) {
  case MoveType::Clw:
  case MoveType::Cclw:
    return same(a.arc.centre, b.arc.centre) && same(a.arc.u, b.arc.u) && same(a.arc.v, b.arc.v) && same(a.arc.normal, b.arc.normal) &&
           same(a.arc.radius, b.arc.radius) && same(a.arc.startAngle, b.arc.startAngle) && same(a.arc.sweep, b.arc.sweep) &&
           same(a.arc.rise, b.arc.rise);
  case MoveType::EllClw:
  case MoveType::EllCclw:
    return same(a.ellipse.centre, b.ellipse.centre) && same(a.ellipse.major, b.ellipse.major) && same(a.ellipse.a, b.ellipse.a) &&
           same(a.ellipse.b, b.ellipse.b) && same(a.ellipse.majorAngle, b.ellipse.majorAngle) &&
           same(a.ellipse.startPhi, b.ellipse.startPhi) && same(a.ellipse.sweepPhi, b.ellipse.sweepPhi) && same(a.ellipse.rise, b.ellipse.rise);
  case MoveType::Spline:
    return same(a.spline.t0, b.spline.t0) && same(a.spline.t1, b.spline.t1) && same(a.spline.chord, b.spline.chord) &&
           a.spline.dims == b.spline.dims;
  case MoveType::Parabola:
    return same(a.parabola.vertex, b.parabola.vertex) && same(a.parabola.control, b.parabola.control);
  default: return true;
  }
}

}  // namespace stc::motion::sm3face
