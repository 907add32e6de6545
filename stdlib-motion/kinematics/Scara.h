// SCARA arms: planar chains of revolute joints about Z.  Joint angles are
// relative (B is measured from arm 1, C from arm 2), 0 = arm stretched along
// the previous arm; A = 0 points arm 1 along +X.  Elbow branch: Config::elbow
// +1 gives B in [0, pi], -1 gives B in [-pi, 0].
#pragma once

#include "stdlib-motion/kinematics/Kinematics.h"

namespace stc::motion::kin {

// The two-link planar solution of (x, y): shared by the SCARA models and
// usable on its own.  Unreachable when |(x, y)| is outside [|l1 - l2|, l1 + l2];
// Singular on that boundary (arm stretched or folded) and at the origin when
// l1 == l2 (A is then taken from aNear, or 0).
KinStatus solveTwoLink(double x, double y, double l1, double l2, int8_t elbow, const double* aNear, double& a,
                       double& b);

// Two joints A, B.  Reads p.x, p.y; forward gives z = 0 and R = Rz(A + B).
struct Scara2Params {
  double l1 = 1, l2 = 1;
};
class Scara2 final : public Kinematics {
 public:
  explicit Scara2(const Scara2Params& p);
  Config configOf(const double* q) const override;

 protected:
  KinStatus solveForward(const double* q, Pose& out) const override;
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  void jacobianOf(const double* q, Jacobian& J) const override;

 private:
  Scara2Params p_;
};

// Three joints A, B, C; the last arm points in the direction phi = A + B + C
// (the approach direction).  Reads p.x, p.y and phi = the angle of R's x axis
// in the XY plane; forward gives z = 0, R = Rz(phi).
struct Scara3Params {
  double l1 = 1, l2 = 1, l3 = 1;
};
class Scara3 final : public Kinematics {
 public:
  explicit Scara3(const Scara3Params& p);
  Config configOf(const double* q) const override;

 protected:
  KinStatus solveForward(const double* q, Pose& out) const override;
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  void jacobianOf(const double* q, Jacobian& J) const override;

 private:
  Scara3Params p_;
};

// The four-axis serial SCARA: joints A, B (rad), Z (length), C (tool rotation,
// rad).  Tool position (x, y, z0 + zSign * Z), orientation Rz(A + B + C).
// Reads p and the planar angle of R.
struct Scara4Params {
  double l1 = 1, l2 = 1;
  double z0 = 0;      // tool height at Z = 0
  int zSign = 1;      // +1: the Z axis moves the tool up (+z); -1: down
};
class Scara4 final : public Kinematics {
 public:
  explicit Scara4(const Scara4Params& p);
  Config configOf(const double* q) const override;

 protected:
  KinStatus solveForward(const double* q, Pose& out) const override;
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  void jacobianOf(const double* q, Jacobian& J) const override;

 private:
  Scara4Params p_;
};

}  // namespace stc::motion::kin
