// Cartesian mechanisms: joints are the tool coordinates themselves.
#pragma once

#include "stdlib-motion/kinematics/Kinematics.h"

namespace stc::motion::kin {

// 1-6 axes: x, y, z [length], then A, B, C [rad] with R = Rz(A) Ry(B) Rx(C).
// Unused coordinates are 0 in forward() and ignored by inverse().  With 6 axes
// B = +-90 deg is the gimbal-lock singularity (A taken from qNear, or 0).
class Cartesian final : public Kinematics {
 public:
  explicit Cartesian(int axes);

 protected:
  KinStatus solveForward(const double* q, Pose& out) const override;
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  void jacobianOf(const double* q, Jacobian& J) const override;
};

// 2- or 3-axis gantry: machine axes parallel to the base axes, turned by
// `rotation` about Z, shifted by `offset`: q = Rz(rotation)^T p + offset (the
// CODESYS "axis = path + offset" with rotation 0).  Orientation is not
// controlled (identity); with 2 axes z is 0 and ignored.
struct GantryParams {
  int axes = 3;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  double rotation = 0;   // [rad]
};

class Gantry final : public Kinematics {
 public:
  explicit Gantry(const GantryParams& p);
  const GantryParams& params() const { return p_; }

 protected:
  KinStatus solveForward(const double* q, Pose& out) const override;
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  void jacobianOf(const double* q, Jacobian& J) const override;

 private:
  GantryParams p_;
  Eigen::Matrix3d Rz_;
};

}  // namespace stc::motion::kin
