#include "stdlib-motion/kinematics/Kinematics.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace stc::motion::kin {

const char* statusName(KinStatus s) {
  switch (s) {
    case KinStatus::Ok: return "Ok";
    case KinStatus::Unreachable: return "Unreachable";
    case KinStatus::Singular: return "Singular";
    case KinStatus::JointLimit: return "JointLimit";
    case KinStatus::NoConvergence: return "NoConvergence";
    case KinStatus::InvalidParameters: return "InvalidParameters";
  }
  return "?";
}

double wrapPi(double a) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  if (a > -std::numbers::pi && a <= std::numbers::pi) return a;   // the usual case, without the division
  double r = std::remainder(a, kTwoPi);   // [-pi, pi]
  return r <= -std::numbers::pi ? r + kTwoPi : r;
}

double nearestTurn(double a, double ref) { return ref + wrapPi(a - ref); }

bool finite(const Pose& x) { return x.p.allFinite() && x.R.allFinite(); }

Eigen::Matrix3d rotZ(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}

Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R) {
  // AngleAxis handles the angle-near-pi case from the symmetric part.
  Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

static bool allFinite(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

KinStatus Kinematics::forward(const double* q, Pose& out) const {
  if (!valid_ || !q || !allFinite(q, joints_)) return KinStatus::InvalidParameters;
  Pose x;
  KinStatus s = solveForward(q, x);
  if ((s == KinStatus::Ok || s == KinStatus::Singular) && !finite(x)) s = KinStatus::Unreachable;
  if (s == KinStatus::Ok || s == KinStatus::Singular) out = x;
  return s;
}

KinStatus Kinematics::inverse(const Pose& x, const Config& c, const double* qNear, double* q) const {
  if (!valid_ || !q || !finite(x) || (qNear && !allFinite(qNear, joints_))) return KinStatus::InvalidParameters;
  std::array<double, kMaxJoints> r{};
  KinStatus s = solveInverse(x, c, qNear, r.data());
  if (s != KinStatus::Ok && s != KinStatus::Singular) return s;
  if (!allFinite(r.data(), joints_)) return KinStatus::Unreachable;
  for (int i = 0; i < joints_; ++i)
    if (revolute(i)) r[i] = qNear ? nearestTurn(r[i], qNear[i]) : wrapPi(r[i]);
  if (limited_) {
    for (int i = 0; i < joints_; ++i) {
      if (r[i] >= lo_[i] && r[i] <= hi_[i]) continue;
      // A revolute joint may still fit one turn away.
      if (revolute(i)) {
        constexpr double kTwoPi = 2 * std::numbers::pi;
        if (r[i] + kTwoPi >= lo_[i] && r[i] + kTwoPi <= hi_[i]) { r[i] += kTwoPi; continue; }
        if (r[i] - kTwoPi >= lo_[i] && r[i] - kTwoPi <= hi_[i]) { r[i] -= kTwoPi; continue; }
      }
      return KinStatus::JointLimit;
    }
  }
  for (int i = 0; i < joints_; ++i) q[i] = r[i];
  return s;
}

void Kinematics::jacobian(const double* q, Jacobian& J) const {
  J.setZero(6, joints_);
  if (!valid_ || !q || !allFinite(q, joints_)) return;
  jacobianOf(q, J);
}

void Kinematics::numericJacobian(const double* q, Jacobian& J, double h) const {
  J.setZero(6, joints_);
  std::array<double, kMaxJoints> qp{}, qm{};
  for (int i = 0; i < joints_; ++i) qp[i] = qm[i] = q[i];
  for (int i = 0; i < joints_; ++i) {
    qp[i] = q[i] + h;
    qm[i] = q[i] - h;
    Pose a, b;
    if (solveForward(qp.data(), a) != KinStatus::Unreachable &&
        solveForward(qm.data(), b) != KinStatus::Unreachable) {
      J.block<3, 1>(0, i) = (a.p - b.p) / (2 * h);
      J.block<3, 1>(3, i) = rotationVector(a.R * b.R.transpose()) / (2 * h);
    }
    qp[i] = qm[i] = q[i];
  }
}

bool Kinematics::setJointLimits(const double* lo, const double* hi) {
  for (int i = 0; i < joints_; ++i)
    if (std::isnan(lo[i]) || std::isnan(hi[i]) || lo[i] > hi[i]) return false;
  for (int i = 0; i < joints_; ++i) {
    lo_[i] = lo[i];
    hi_[i] = hi[i];
  }
  limited_ = true;
  return true;
}

}  // namespace stc::motion::kin
