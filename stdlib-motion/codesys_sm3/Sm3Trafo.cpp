// The kinematic transformations of sm3_trafo.st over stdlib-motion/kinematics.
// The ST face speaks degrees and adds the axis offsets; the models work in
// radians.  A model is built per call from the inputs (a few hundred ns), so a
// changed parameter takes effect in the same call.  The forward blocks read
// the axes' set positions (what fSetPosition shows), from the kernel, not from
// the mirrored variable.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/kinematics/Cartesian.h"
#include "stdlib-motion/kinematics/Delta.h"
#include "stdlib-motion/kinematics/Scara.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180;
double deg(double rad) { return rad / kRadPerDeg; }

// Every number of a block: finite and within the plausibility bound of positions.
template <class... T>
bool plausible(T... v) {
  return (bounds::position(v) && ...);
}

// The set position of an axis in-out (reported like fSetPosition); false if
// the variable is missing or cannot be bound.
bool setPosition(sm3::AXIS_REF_SM3* ref, const CallCtx& c, double& out) {
  Axis* ax = bindMaster(ref, c);
  if (!ax) return false;
  out = ax->reportPosition(ax->set().p);
  return std::isfinite(out);
}

template <class T>
void fail(T* self) {
  self->bError = true;   // every other output keeps its last valid value
}

// v normed into [lo, hi] and limited to [0, 1]; 0 for an empty range.
double normed(double v, double lo, double hi) { return hi > lo ? std::clamp((v - lo) / (hi - lo), 0.0, 1.0) : 0.0; }

kin::Pose poseOf(const sm3::SMC_POSINFO& pi, double phi = 0) {
  kin::Pose x;
  x.p = {pi.dX, pi.dY, pi.dZ};
  x.R = kin::rotZ(phi);
  return x;
}

bool ok(kin::KinStatus s) { return s == kin::KinStatus::Ok || s == kin::KinStatus::Singular; }

// ---------------------------------------------------------------- gantries
void SMC_TRAFO_Gantry2(sm3::SMC_TRAFO_Gantry2* s) {
  if (!plausible(s->pi.dX, s->pi.dY, s->dOffsetX, s->dOffsetY)) return fail(s);
  s->dx = s->pi.dX + s->dOffsetX;
  s->dy = s->pi.dY + s->dOffsetY;
  s->bError = false;
}

void SMC_TRAFO_Gantry3(sm3::SMC_TRAFO_Gantry3* s) {
  if (!plausible(s->pi.dX, s->pi.dY, s->pi.dZ, s->dOffsetX, s->dOffsetY, s->dOffsetZ)) return fail(s);
  s->dx = s->pi.dX + s->dOffsetX;
  s->dy = s->pi.dY + s->dOffsetY;
  s->dz = s->pi.dZ + s->dOffsetZ;
  s->bError = false;
}

template <class T>
bool gantryRange(const T* s) {
  return plausible(s->minX, s->maxX, s->minY, s->maxY);
}

// The X/Y display outputs of the gantry forward blocks (normalised to the min/max range).
template <class T>
void gantryXYDisplay(T* s) {
  s->dnx = normed(s->dx, s->minX, s->maxX);
  s->dny = normed(s->dy, s->minY, s->maxY);
  s->dnOffsetX = normed(-s->dOffsetX, s->minX, s->maxX);
  s->dnOffsetY = normed(-s->dOffsetY, s->minY, s->maxY);
  s->ratio = s->maxX > s->minX && s->maxY > s->minY ? (s->maxX - s->minX) / (s->maxY - s->minY) : 0.0;
}

void SMC_TRAFOF_Gantry2(sm3::SMC_TRAFOF_Gantry2* s) {
  const CallCtx c = callContext();
  double ax, ay;
  if (!setPosition(s->DriveX, c, ax) || !setPosition(s->DriveY, c, ay) || !plausible(s->dOffsetX, s->dOffsetY) ||
      !gantryRange(s))
    return fail(s);
  s->dx = ax - s->dOffsetX;
  s->dy = ay - s->dOffsetY;
  gantryXYDisplay(s);
  s->bError = false;
}

void SMC_TRAFOF_Gantry3(sm3::SMC_TRAFOF_Gantry3* s) {
  const CallCtx c = callContext();
  double ax, ay, az;
  if (!setPosition(s->DriveX, c, ax) || !setPosition(s->DriveY, c, ay) || !setPosition(s->DriveZ, c, az) ||
      !plausible(s->dOffsetX, s->dOffsetY, s->dOffsetZ) || !gantryRange(s))
    return fail(s);
  s->dx = ax - s->dOffsetX;
  s->dy = ay - s->dOffsetY;
  s->dz = az - s->dOffsetZ;
  gantryXYDisplay(s);
  s->bError = false;
}

void SMC_TRAFOF_Gantry3D(sm3::SMC_TRAFOF_Gantry3D* s) {
  const CallCtx c = callContext();
  double ax, ay, az;
  if (!setPosition(s->DriveX, c, ax) || !setPosition(s->DriveY, c, ay) || !setPosition(s->DriveZ, c, az) ||
      !plausible(s->dOffsetX, s->dOffsetY, s->dOffsetZ, s->minZ, s->maxZ) || !gantryRange(s))
    return fail(s);
  s->dx = ax - s->dOffsetX;
  s->dy = ay - s->dOffsetY;
  s->dz = az - s->dOffsetZ;
  s->dnx = normed(s->dx, s->minX, s->maxX);
  s->dny = normed(s->dy, s->minY, s->maxY);
  s->dnz = normed(s->dz, s->minZ, s->maxZ);
  s->dm = std::max({s->maxX - s->minX, s->maxY - s->minY, s->maxZ - s->minZ, 0.0});
  s->bError = false;
}

// ---------------------------------------------------------------- SCARA
int8_t elbowOf(bool low) { return low ? 1 : -1; }

void SMC_TRAFO_Scara2(sm3::SMC_TRAFO_Scara2* s) {
  if (!plausible(s->pi.dX, s->pi.dY, s->dOffsetA, s->dOffsetB, s->dArmLength1, s->dArmLength2)) return fail(s);
  const kin::Scara2 k({s->dArmLength1, s->dArmLength2});
  const double near[2] = {(s->__lastA - s->dOffsetA) * kRadPerDeg, (s->__lastB - s->dOffsetB) * kRadPerDeg};
  double q[2];
  if (!ok(k.inverse(poseOf(s->pi), {elbowOf(s->bElbowLow), 1, 1}, s->__primed ? near : nullptr, q))) return fail(s);
  s->dA = s->__lastA = deg(q[0]) + s->dOffsetA;
  s->dB = s->__lastB = deg(q[1]) + s->dOffsetB;
  s->__primed = true;
  s->bError = false;
}

void SMC_TRAFOF_Scara2(sm3::SMC_TRAFOF_Scara2* s) {
  const CallCtx c = callContext();
  double a, b;
  if (!setPosition(s->DriveA, c, a) || !setPosition(s->DriveB, c, b) ||
      !plausible(s->dOffsetA, s->dOffsetB, s->dArmLength1, s->dArmLength2))
    return fail(s);
  const kin::Scara2 k({s->dArmLength1, s->dArmLength2});
  const double q[2] = {(a - s->dOffsetA) * kRadPerDeg, (b - s->dOffsetB) * kRadPerDeg};
  kin::Pose x;
  if (!ok(k.forward(q, x))) return fail(s);
  const double reach = s->dArmLength1 + s->dArmLength2;
  s->dx = x.p.x();
  s->dy = x.p.y();
  s->dAlpha = a - s->dOffsetA;
  s->dBeta = b - s->dOffsetB;
  s->dpx = s->dArmLength1 * std::cos(q[0]) / reach;
  s->dpy = s->dArmLength1 * std::sin(q[0]) / reach;
  s->dnx = x.p.x() / reach;
  s->dny = x.p.y() / reach;
  s->dR1 = s->dArmLength1 / reach;
  s->dR2 = s->dArmLength2 / reach;
  s->bError = false;
}

void SMC_TRAFO_Scara3(sm3::SMC_TRAFO_Scara3* s) {
  if (!plausible(s->pi.dX, s->pi.dY, s->dDirection, s->dOffsetA, s->dOffsetB, s->dOffsetC, s->dArmLength1,
                 s->dArmLength2, s->dArmLength3))
    return fail(s);
  const kin::Scara3 k({s->dArmLength1, s->dArmLength2, s->dArmLength3});
  const double near[3] = {(s->__lastA - s->dOffsetA) * kRadPerDeg, (s->__lastB - s->dOffsetB) * kRadPerDeg,
                          (s->__lastC - s->dOffsetC) * kRadPerDeg};
  double q[3];
  const kin::Pose x = poseOf(s->pi, s->dDirection * kRadPerDeg);
  if (!ok(k.inverse(x, {elbowOf(s->bElbowLow), 1, 1}, s->__primed ? near : nullptr, q))) return fail(s);
  s->dA = s->__lastA = deg(q[0]) + s->dOffsetA;
  s->dB = s->__lastB = deg(q[1]) + s->dOffsetB;
  s->dC = s->__lastC = deg(q[2]) + s->dOffsetC;
  s->__primed = true;
  s->bError = false;
}

void SMC_TRAFOF_Scara3(sm3::SMC_TRAFOF_Scara3* s) {
  const CallCtx c = callContext();
  double a, b, g;
  if (!setPosition(s->DriveA, c, a) || !setPosition(s->DriveB, c, b) || !setPosition(s->DriveC, c, g) ||
      !plausible(s->dOffsetA, s->dOffsetB, s->dOffsetC, s->dArmLength1, s->dArmLength2, s->dArmLength3))
    return fail(s);
  const kin::Scara3 k({s->dArmLength1, s->dArmLength2, s->dArmLength3});
  const double q[3] = {(a - s->dOffsetA) * kRadPerDeg, (b - s->dOffsetB) * kRadPerDeg, (g - s->dOffsetC) * kRadPerDeg};
  kin::Pose x;
  if (!ok(k.forward(q, x))) return fail(s);
  const double reach = s->dArmLength1 + s->dArmLength2 + s->dArmLength3;
  const double e1x = s->dArmLength1 * std::cos(q[0]), e1y = s->dArmLength1 * std::sin(q[0]);
  s->dx = x.p.x();
  s->dy = x.p.y();
  s->dAlpha = a - s->dOffsetA;
  s->dBeta = b - s->dOffsetB;
  s->dGamma = g - s->dOffsetC;
  s->dDirection = deg(kin::wrapPi(q[0] + q[1] + q[2]));
  s->dpx = e1x / reach;
  s->dpy = e1y / reach;
  s->dp2x = (e1x + s->dArmLength2 * std::cos(q[0] + q[1])) / reach;
  s->dp2y = (e1y + s->dArmLength2 * std::sin(q[0] + q[1])) / reach;
  s->dnx = x.p.x() / reach;
  s->dny = x.p.y() / reach;
  s->dR1 = s->dArmLength1 / reach;
  s->dR2 = s->dArmLength2 / reach;
  s->dR3 = s->dArmLength3 / reach;
  s->bError = false;
}

// ---------------------------------------------------------------- delta robots
template <class T>
kin::DeltaRotaryParams rotaryParams(const T* s) {
  kin::DeltaRotaryParams p;
  p.upperArm = s->dArmLength1;
  p.rod = s->dArmLength2;
  p.baseRadius = s->dArm1Radius;
  p.platformRadius = s->dStewartRadius;
  p.rotation = s->dRotationOffset * kRadPerDeg;
  return p;
}

template <class T>
bool rotaryInputs(const T* s) {
  return plausible(s->dArmLength1, s->dArmLength2, s->dArm1Radius, s->dStewartRadius, s->dDistance,
                   s->dRotationOffset, s->dOffsetA, s->dOffsetB, s->dOffsetC) &&
         s->dDistance >= 0;
}

template <class T>
void setJoints(T* s, const double* q, bool angles) {
  const double f = angles ? 1 / kRadPerDeg : 1.0;
  s->dA = q[0] * f + s->dOffsetA;
  s->dB = q[1] * f + s->dOffsetB;
  s->dC = q[2] * f + s->dOffsetC;
  s->bError = false;
}

template <class T>
bool readJoints(T* s, double* q, double f) {
  const CallCtx c = callContext();
  double a, b, g;
  if (!setPosition(s->DriveA, c, a) || !setPosition(s->DriveB, c, b) || !setPosition(s->DriveC, c, g)) return false;
  q[0] = (a - s->dOffsetA) * f;
  q[1] = (b - s->dOffsetB) * f;
  q[2] = (g - s->dOffsetC) * f;
  return true;
}

template <class T>
void setPlate(T* s, const kin::Pose& x) {
  s->dx = x.p.x();
  s->dy = x.p.y();
  s->dz = x.p.z();
  s->bError = false;
}

void SMC_TRAFO_Tripod_Arm(sm3::SMC_TRAFO_Tripod_Arm* s) {
  if (!rotaryInputs(s) || !plausible(s->pi.dX, s->pi.dY, s->pi.dZ) ||
      !(s->dMaxAngleBallJoint >= 0 && s->dMaxAngleBallJoint <= 90))
    return fail(s);
  kin::DeltaRotaryParams p = rotaryParams(s);
  p.maxBallJointAngle = s->dMaxAngleBallJoint * kRadPerDeg;
  const kin::DeltaRotary k(p);
  double q[3];
  if (!ok(k.inverse(poseOf(s->pi), {}, nullptr, q))) return fail(s);
  setJoints(s, q, true);
}

void SMC_TRAFOF_Tripod_Arm(sm3::SMC_TRAFOF_Tripod_Arm* s) {
  double q[3];
  if (!rotaryInputs(s) || !readJoints(s, q, kRadPerDeg)) return fail(s);
  const kin::DeltaRotary k(rotaryParams(s));
  kin::Pose x;
  if (!ok(k.forward(q, x))) return fail(s);
  setPlate(s, x);
}

template <class T>
bool linearInputs(const T* s) {
  return plausible(s->dOuterRadius, s->dInnerRadius, s->dLength, s->dDistance, s->dAxisAngle, s->dRotationOffset,
                   s->dOffsetA, s->dOffsetB, s->dOffsetC) &&
         s->dDistance >= 0;
}

template <class T>
kin::DeltaLinearParams linearParams(const T* s) {
  kin::DeltaLinearParams p;
  p.railRadius = s->dOuterRadius;
  p.platformRadius = s->dInnerRadius;
  p.rod = s->dLength;
  p.railAngle = s->dAxisAngle * kRadPerDeg;
  p.rotation = s->dRotationOffset * kRadPerDeg;
  return p;
}

void SMC_TRAFO_Tripod_Lin(sm3::SMC_TRAFO_Tripod_Lin* s) {
  if (!linearInputs(s) || !plausible(s->pi.dX, s->pi.dY, s->pi.dZ)) return fail(s);
  const kin::DeltaLinear k(linearParams(s));
  double q[3];
  if (!ok(k.inverse(poseOf(s->pi), {}, nullptr, q))) return fail(s);
  setJoints(s, q, false);
}

void SMC_TRAFOF_Tripod_Lin(sm3::SMC_TRAFOF_Tripod_Lin* s) {
  double q[3];
  if (!linearInputs(s) || !readJoints(s, q, 1.0)) return fail(s);
  const kin::DeltaLinear k(linearParams(s));
  kin::Pose x;
  if (!ok(k.forward(q, x))) return fail(s);
  setPlate(s, x);
}

}  // namespace

namespace stc::motion {

void registerSm3TrafoNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(SMC_TRAFO_Gantry2, SMC_TRAFO_Gantry2)
  STC_SM3_NATIVE(SMC_TRAFO_Gantry3, SMC_TRAFO_Gantry3)
  STC_SM3_NATIVE(SMC_TRAFOF_Gantry2, SMC_TRAFOF_Gantry2)
  STC_SM3_NATIVE(SMC_TRAFOF_Gantry3, SMC_TRAFOF_Gantry3)
  STC_SM3_NATIVE(SMC_TRAFOF_Gantry3D, SMC_TRAFOF_Gantry3D)
  STC_SM3_NATIVE(SMC_TRAFO_Scara2, SMC_TRAFO_Scara2)
  STC_SM3_NATIVE(SMC_TRAFOF_Scara2, SMC_TRAFOF_Scara2)
  STC_SM3_NATIVE(SMC_TRAFO_Scara3, SMC_TRAFO_Scara3)
  STC_SM3_NATIVE(SMC_TRAFOF_Scara3, SMC_TRAFOF_Scara3)
  STC_SM3_NATIVE(SMC_TRAFO_Tripod_Arm, SMC_TRAFO_Tripod_Arm)
  STC_SM3_NATIVE(SMC_TRAFOF_Tripod_Arm, SMC_TRAFOF_Tripod_Arm)
  STC_SM3_NATIVE(SMC_TRAFO_Tripod_Lin, SMC_TRAFO_Tripod_Lin)
  STC_SM3_NATIVE(SMC_TRAFOF_Tripod_Lin, SMC_TRAFOF_Tripod_Lin)
}

}  // namespace stc::motion
