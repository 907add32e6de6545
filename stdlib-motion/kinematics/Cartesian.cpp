#include "stdlib-motion/kinematics/Cartesian.h"

#include <cmath>

namespace stc::motion::kin {

namespace {
Eigen::Matrix3d rotY(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d R;
  R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}
Eigen::Matrix3d rotX(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, c, -s, 0, s, c;
  return R;
}
unsigned rotaryMask(int axes) { return axes > 3 ? ((1u << axes) - 1u) & ~7u : 0u; }
}  // namespace

Cartesian::Cartesian(int axes) : Kinematics(axes < 1 || axes > 6 ? 1 : axes, rotaryMask(axes)) {
  if (axes < 1 || axes > 6) invalidate();
}

KinStatus Cartesian::solveForward(const double* q, Pose& out) const {
  const int n = joints();
  for (int i = 0; i < 3; ++i) out.p[i] = i < n ? q[i] : 0.0;
  const double a = n > 3 ? q[3] : 0, b = n > 4 ? q[4] : 0, c = n > 5 ? q[5] : 0;
  out.R = rotZ(a) * rotY(b) * rotX(c);
  return KinStatus::Ok;
}

KinStatus Cartesian::solveInverse(const Pose& x, const Config&, const double* qNear, double* q) const {
  const int n = joints();
  for (int i = 0; i < n && i < 3; ++i) q[i] = x.p[i];
  if (n <= 3) return KinStatus::Ok;
  const Eigen::Matrix3d& R = x.R;
  if (n == 4) {
    q[3] = planarAngle(R);
    return KinStatus::Ok;
  }
  const double cb = std::hypot(R(0, 0), R(1, 0));
  const double b = std::atan2(-R(2, 0), cb);
  KinStatus s = KinStatus::Ok;
  double a;
  if (cb < 1e-12) {   // gimbal lock: only A - C (or A + C) is defined
    a = qNear ? qNear[3] : 0.0;
    s = n == 6 ? KinStatus::Singular : KinStatus::Ok;
  } else {
    a = std::atan2(R(1, 0), R(0, 0));
  }
  q[3] = a;
  q[4] = b;
  if (n == 6) {
    const Eigen::Matrix3d M = rotY(b).transpose() * rotZ(a).transpose() * R;   // = Rx(C)
    q[5] = std::atan2(M(2, 1), M(1, 1));
  }
  return s;
}

void Cartesian::jacobianOf(const double* q, Jacobian& J) const {
  const int n = joints();
  for (int i = 0; i < n && i < 3; ++i) J(i, i) = 1;
  if (n > 3) J.block<3, 1>(3, 3) = Eigen::Vector3d::UnitZ();
  if (n > 4) J.block<3, 1>(3, 4) = rotZ(q[3]) * Eigen::Vector3d::UnitY();
  if (n > 5) J.block<3, 1>(3, 5) = rotZ(q[3]) * rotY(q[4]) * Eigen::Vector3d::UnitX();
}

Gantry::Gantry(const GantryParams& p) : Kinematics(p.axes == 2 ? 2 : 3, 0), p_(p) {
  if ((p.axes != 2 && p.axes != 3) || !p.offset.allFinite() || !std::isfinite(p.rotation)) invalidate();
  Rz_ = rotZ(std::isfinite(p.rotation) ? p.rotation : 0.0);
}

KinStatus Gantry::solveForward(const double* q, Pose& out) const {
  Eigen::Vector3d a(q[0] - p_.offset.x(), q[1] - p_.offset.y(), joints() == 3 ? q[2] - p_.offset.z() : 0.0);
  out.p = Rz_ * a;
  out.R.setIdentity();
  return KinStatus::Ok;
}

KinStatus Gantry::solveInverse(const Pose& x, const Config&, const double*, double* q) const {
  Eigen::Vector3d p = x.p;
  if (joints() == 2) p.z() = 0;
  const Eigen::Vector3d a = Rz_.transpose() * p + p_.offset;
  for (int i = 0; i < joints(); ++i) q[i] = a[i];
  return KinStatus::Ok;
}

void Gantry::jacobianOf(const double*, Jacobian& J) const {
  for (int i = 0; i < joints(); ++i) J.block<3, 1>(0, i) = Rz_.col(i);
}

}  // namespace stc::motion::kin
