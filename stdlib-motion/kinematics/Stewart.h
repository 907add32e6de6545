// Stewart-Gough platform: six legs of variable length between base joints
// b_i (base frame) and platform joints m_i (platform frame); the joint
// values are the leg lengths.  Inverse: l_i = |p + R m_i - b_i| (closed form,
// reads the whole pose).  Forward: Newton-Raphson on the pose from a start
// pose (the home pose, or the caller's guess) with an iteration limit;
// NoConvergence when it is reached, Singular when the legs' Jacobian is
// (numerically) rank deficient at the solution.
#pragma once

#include <array>

#include "stdlib-motion/kinematics/Kinematics.h"

namespace stc::motion::kin {

struct StewartParams {
  std::array<Eigen::Vector3d, 6> base, platform;
  Pose home;               // Newton start of forward()
  int maxIterations = 30;
  // The usual layout: joint pairs at +-halfAngle around 0/120/240 deg (base)
  // and 60/180/300 deg (platform), the platform `height` above the base at home.
  static StewartParams symmetric(double baseRadius, double platformRadius, double baseHalfAngle,
                                 double platformHalfAngle, double height);
};

class Stewart final : public Kinematics {
 public:
  explicit Stewart(const StewartParams& p);
  const StewartParams& params() const { return p_; }
  // forward() started from `guess` (e.g. the previous cycle's pose).
  KinStatus forwardFrom(const double* q, const Pose& guess, Pose& out) const;
  // d(leg lengths)/d(v, w) at a pose: the inverse Jacobian.
  Eigen::Matrix<double, 6, 6> legJacobian(const Pose& x) const;

 protected:
  KinStatus solveForward(const double* q, Pose& out) const override;
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  void jacobianOf(const double* q, Jacobian& J) const override;

 private:
  StewartParams p_;
  double scale_ = 1;   // size of the mechanism (for tolerances)
};

}  // namespace stc::motion::kin
