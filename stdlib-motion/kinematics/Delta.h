// Delta (tripod) robots: three arms 120 deg apart carry parallelogram rods to
// a tool plate that stays parallel to the base; three translational degrees
// of freedom.  Base frame: Z up, origin and arm azimuths per model below; arm
// i (0, 1, 2 = A, B, C) lies at azimuth rotation + i * 120 deg, counter-clockwise.
// Reads p only; forward gives R = identity.  Config::elbow selects the branch
// of every arm (+1: the physical one, documented per model).
#pragma once

#include "stdlib-motion/kinematics/Kinematics.h"

namespace stc::motion::kin {

class Delta : public Kinematics {
 public:
  Config configOf(const double* q) const override;

 protected:
  Delta(unsigned revoluteMask) : Kinematics(3, revoluteMask) {}
  void setup(double rotation, double platformRadius, double rod);
  // The rod's upper joint of arm i at joint value v, and its derivative.
  virtual Eigen::Vector3d upper(int i, double v) const = 0;
  virtual Eigen::Vector3d upperDerivative(int i, double v) const = 0;
  // Branch (+1/-1) of arm i at joint value v for plate position p.
  virtual int8_t branchOf(int i, double v, const Eigen::Vector3d& p) const = 0;

  KinStatus solveForward(const double* q, Pose& out) const override;
  void jacobianOf(const double* q, Jacobian& J) const override;

  Eigen::Vector3d e_[3], t_[3];   // radial and tangential unit vectors per arm
  double r_ = 0, rod_ = 0;        // plate joint radius, rod length
};

// Rotary arms ("Tripod_Arm"): arm pivots on a circle of radius `baseRadius` in
// the plane z = H; arm angle theta = 0 horizontal pointing outward, positive
// downward.  Origin: the plate centre when all arms are horizontal, so H =
// sqrt(rod^2 - (baseRadius + upperArm - platformRadius)^2) (the model is
// invalid if that is not positive).  elbow +1: the elbow outside the line from
// the pivot to the plate joint (theta = 0 at the origin).
struct DeltaRotaryParams {
  double baseRadius = 0;        // pivot circle radius
  double upperArm = 1;          // driven arm length
  double rod = 1;               // parallelogram rod length
  double platformRadius = 0;    // plate joint circle radius
  double rotation = 0;          // azimuth of arm A [rad]
  double maxBallJointAngle = 0; // rod tilt out of the arm's plane [rad]; 0 = unchecked
};
class DeltaRotary final : public Delta {
 public:
  explicit DeltaRotary(const DeltaRotaryParams& p);
  double baseHeight() const { return h_; }

 protected:
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  Eigen::Vector3d upper(int i, double v) const override;
  Eigen::Vector3d upperDerivative(int i, double v) const override;
  int8_t branchOf(int i, double v, const Eigen::Vector3d& p) const override;

 private:
  DeltaRotaryParams p_;
  double h_ = 0;
};

// Linear carriages ("Tripod_Lin"): rail i passes through the point at radius
// `railRadius` on azimuth i in the plane z = 0 and is tilted outward by
// `railAngle` from +Z; the joint value is the carriage's distance along the
// rail from that point (positive upward).  With railAngle 0:
// s_i = z + sqrt(rod^2 - |(x, y) - (R - r) e_i|^2).  elbow +1: the carriage
// above the plate joint (the upper root).
struct DeltaLinearParams {
  double railRadius = 1;
  double rod = 1;
  double platformRadius = 0;
  double railAngle = 0;   // [rad], |railAngle| < 90 deg
  double rotation = 0;    // azimuth of rail A [rad]
};
class DeltaLinear final : public Delta {
 public:
  explicit DeltaLinear(const DeltaLinearParams& p);

 protected:
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  Eigen::Vector3d upper(int i, double v) const override;
  Eigen::Vector3d upperDerivative(int i, double v) const override;
  int8_t branchOf(int i, double v, const Eigen::Vector3d& p) const override;

 private:
  DeltaLinearParams p_;
  Eigen::Vector3d u_[3];   // rail directions
};

}  // namespace stc::motion::kin
