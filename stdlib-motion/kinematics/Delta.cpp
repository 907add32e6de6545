#include "stdlib-motion/kinematics/Delta.h"

#include <Eigen/LU>
#include <cmath>
#include <numbers>

namespace stc::motion::kin {

namespace {
bool nonNegative(double v) { return std::isfinite(v) && v >= 0 && v <= 1e12; }
bool positive(double v) { return std::isfinite(v) && v > 0 && v <= 1e12; }
}  // namespace

void Delta::setup(double rotation, double platformRadius, double rod) {
  for (int i = 0; i < 3; ++i) {
    const double az = rotation + i * 2 * std::numbers::pi / 3;
    e_[i] = {std::cos(az), std::sin(az), 0};
    t_[i] = {-std::sin(az), std::cos(az), 0};
  }
  r_ = platformRadius;
  rod_ = rod;
}

// The plate centre p satisfies |p - c_i| = rod with c_i = upper_i - r e_i:
// the intersection of three spheres, the lower of its two points.
KinStatus Delta::solveForward(const double* q, Pose& out) const {
  Eigen::Vector3d c[3];
  for (int i = 0; i < 3; ++i) c[i] = upper(i, q[i]) - r_ * e_[i];
  const Eigen::Vector3d u = c[1] - c[0], v = c[2] - c[0], n = u.cross(v);
  const double nn = n.squaredNorm(), scale = u.squaredNorm() + v.squaredNorm();
  if (!(nn > 1e-24 * scale * scale)) return KinStatus::Unreachable;   // centres (nearly) collinear
  // w0 = alpha u + beta v on the perpendicular bisector planes of c0c1 and c0c2.
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), det = uu * vv - uv * uv;
  const double alpha = (0.5 * uu * vv - 0.5 * vv * uv) / det;
  const double beta = (0.5 * vv * uu - 0.5 * uu * uv) / det;
  const Eigen::Vector3d w0 = alpha * u + beta * v;
  const double rest = rod_ * rod_ - w0.squaredNorm();
  if (rest < -1e-12 * rod_ * rod_) return KinStatus::Unreachable;
  KinStatus s = KinStatus::Ok;
  double t = rest > 0 ? std::sqrt(rest / nn) : 0.0;
  if (t * std::sqrt(nn) < 1e-9 * rod_) s = KinStatus::Singular;   // both points coincide
  if (n.z() > 0) t = -t;
  out.p = c[0] + w0 + t * n;
  out.R.setIdentity();
  return s;
}

// f_i = |p + r e_i - upper_i(q_i)|^2 - rod^2 = 0  =>  A dp = B dq.
void Delta::jacobianOf(const double* q, Jacobian& J) const {
  Pose x;
  if (solveForward(q, x) == KinStatus::Unreachable) return;
  Eigen::Matrix3d A, B = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d g = x.p + r_ * e_[i] - upper(i, q[i]);
    A.row(i) = g.transpose();
    B(i, i) = g.dot(upperDerivative(i, q[i]));
  }
  Eigen::FullPivLU<Eigen::Matrix3d> lu(A);
  if (!lu.isInvertible()) return;
  J.topRows<3>() = lu.solve(B);
}

Config Delta::configOf(const double* q) const {
  Pose x;
  if (solveForward(q, x) == KinStatus::Unreachable) return {};
  return {branchOf(0, q[0], x.p), 1, 1};
}

// ---- rotary arms
DeltaRotary::DeltaRotary(const DeltaRotaryParams& p) : Delta(0b111), p_(p) {
  const bool ok = nonNegative(p.baseRadius) && positive(p.upperArm) && positive(p.rod) &&
                  nonNegative(p.platformRadius) && std::isfinite(p.rotation) && nonNegative(p.maxBallJointAngle) &&
                  p.maxBallJointAngle <= std::numbers::pi / 2;
  const double reach = p.baseRadius + p.upperArm - p.platformRadius;
  const double h2 = ok ? p.rod * p.rod - reach * reach : -1;
  if (!(h2 > 0)) invalidate();
  h_ = h2 > 0 ? std::sqrt(h2) : 0;
  setup(std::isfinite(p.rotation) ? p.rotation : 0, p.platformRadius, p.rod);
}

Eigen::Vector3d DeltaRotary::upper(int i, double th) const {
  return (p_.baseRadius + p_.upperArm * std::cos(th)) * e_[i] + Eigen::Vector3d(0, 0, h_ - p_.upperArm * std::sin(th));
}

Eigen::Vector3d DeltaRotary::upperDerivative(int i, double th) const {
  return -p_.upperArm * std::sin(th) * e_[i] - Eigen::Vector3d(0, 0, p_.upperArm * std::cos(th));
}

// In the arm's plane, with a = R - r - x', b = H - z:  a cos(th) - b sin(th) = K,
// i.e. rho cos(th + delta) = K.
int8_t DeltaRotary::branchOf(int i, double th, const Eigen::Vector3d& p) const {
  const double a = p_.baseRadius - r_ - p.dot(e_[i]), b = h_ - p.z();
  return signOf(std::sin(th + std::atan2(b, a)));
}

KinStatus DeltaRotary::solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const {
  const double l1 = p_.upperArm;
  KinStatus st = KinStatus::Ok;
  for (int i = 0; i < 3; ++i) {
    const double xp = x.p.dot(e_[i]), yp = x.p.dot(t_[i]);
    if (p_.maxBallJointAngle > 0 && std::abs(yp) > rod_ * std::sin(p_.maxBallJointAngle))
      return std::abs(yp) > rod_ ? KinStatus::Unreachable : KinStatus::JointLimit;
    const double a = p_.baseRadius - r_ - xp, b = h_ - x.p.z();
    const double k = (rod_ * rod_ - yp * yp - a * a - b * b - l1 * l1) / (2 * l1);
    const double rho2 = a * a + b * b, d2 = rho2 - k * k;
    if (!std::isfinite(d2) || d2 < -1e-12 * rho2) return KinStatus::Unreachable;
    double sn = d2 > 0 ? std::sqrt(d2) : 0.0;
    if (sn < 1e-12 * l1) {   // the rod in line with the arm (or rho = 0)
      sn = 0;
      st = KinStatus::Singular;
      if (rho2 < 1e-24 * l1 * l1) {
        q[i] = qNear ? qNear[i] : 0.0;
        continue;
      }
    }
    q[i] = std::atan2(branch(c.elbow) * sn, k) - std::atan2(b, a);
  }
  return st;
}

// ---- linear carriages
DeltaLinear::DeltaLinear(const DeltaLinearParams& p) : Delta(0), p_(p) {
  if (!nonNegative(p.railRadius) || !positive(p.rod) || !nonNegative(p.platformRadius) ||
      !std::isfinite(p.railAngle) || !(std::abs(p.railAngle) < std::numbers::pi / 2 - 1e-9) ||
      !std::isfinite(p.rotation))
    invalidate();
  setup(std::isfinite(p.rotation) ? p.rotation : 0, p.platformRadius, p.rod);
  const double sa = std::isfinite(p.railAngle) ? std::sin(p.railAngle) : 0;
  const double ca = std::isfinite(p.railAngle) ? std::cos(p.railAngle) : 1;
  for (int i = 0; i < 3; ++i) u_[i] = sa * e_[i] + Eigen::Vector3d(0, 0, ca);
}

Eigen::Vector3d DeltaLinear::upper(int i, double s) const { return p_.railRadius * e_[i] + s * u_[i]; }
Eigen::Vector3d DeltaLinear::upperDerivative(int i, double) const { return u_[i]; }

int8_t DeltaLinear::branchOf(int i, double s, const Eigen::Vector3d& p) const {
  return signOf((upper(i, s) - p - r_ * e_[i]).dot(u_[i]));
}

// |d + s u|^2 = rod^2 with d = (R - r) e_i - p.
KinStatus DeltaLinear::solveInverse(const Pose& x, const Config& c, const double*, double* q) const {
  KinStatus st = KinStatus::Ok;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d d = (p_.railRadius - r_) * e_[i] - x.p;
    const double du = d.dot(u_[i]);
    const double disc = du * du - d.squaredNorm() + rod_ * rod_;
    if (!std::isfinite(disc) || disc < -1e-12 * rod_ * rod_) return KinStatus::Unreachable;
    double sq = disc > 0 ? std::sqrt(disc) : 0.0;
    if (sq < 1e-12 * rod_) {
      sq = 0;
      st = KinStatus::Singular;   // the rod perpendicular to the rail
    }
    q[i] = -du + branch(c.elbow) * sq;
  }
  return st;
}

}  // namespace stc::motion::kin
