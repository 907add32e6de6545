// Six-axis articulated arm from Denavit-Hartenberg parameters (standard
// convention: link i transforms by Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i),
// theta_i = q_i + thetaOffset_i).  The closed-form inverse needs the usual
// industrial structure, checked at construction: alpha = (+-90, 0, +-90, +-90,
// +-90, any) deg, a4 = a5 = d5 = 0 (a spherical wrist whose centre is the
// origin of frame 4), a2 > 0 and (a3, d4) not both 0.  a1, d1..d4, a6, d6 are free.
//
// Eight configurations: shoulder = sign of the wrist centre's reach in front
// of axis 1 (+1: in front), elbow = sign of sin of the elbow angle of the
// (a2, |(a3, d4)|) triangle, wrist = sign of q5 (theta5 in (-pi, pi]).
// Singular: the wrist centre on axis 1 (q1 from qNear), the arm stretched or
// folded, q5 = 0 (q4 from qNear).
#pragma once

#include <array>

#include "stdlib-motion/kinematics/Kinematics.h"

namespace stc::motion::kin {

struct DhLink {
  double a = 0, alpha = 0, d = 0, thetaOffset = 0;
};
using DhTable = std::array<DhLink, 6>;

class Articulated6 final : public Kinematics {
 public:
  explicit Articulated6(const DhTable& dh);
  const DhTable& dh() const { return dh_; }
  Config configOf(const double* q) const override;
  // The frames 0..6 (frame 0 = base) of the chain at q.
  void frames(const double* q, std::array<Eigen::Isometry3d, 7>& T) const;

 protected:
  KinStatus solveForward(const double* q, Pose& out) const override;
  KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const override;
  void jacobianOf(const double* q, Jacobian& J) const override;

 private:
  DhTable dh_;
  int s1_ = 1, s3_ = 1, s4_ = 1, s5_ = 1;   // signs of alpha1, alpha3, alpha4, alpha5
  double l3_ = 0, beta_ = 0;                // the forearm as one planar link
  Eigen::Vector3d wristToFlange_;           // in frame 6: origin of frame 5
};

}  // namespace stc::motion::kin
