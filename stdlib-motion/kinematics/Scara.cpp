#include "stdlib-motion/kinematics/Scara.h"

#include <cmath>

namespace stc::motion::kin {

namespace {
bool goodLength(double l) { return std::isfinite(l) && l > 0 && l <= 1e12; }

// Planar forward of the first two arms: elbow and wrist points.
void twoLink(double a, double b, double l1, double l2, Eigen::Vector2d& elbow, Eigen::Vector2d& wrist) {
  elbow = {l1 * std::cos(a), l1 * std::sin(a)};
  wrist = elbow + Eigen::Vector2d(l2 * std::cos(a + b), l2 * std::sin(a + b));
}

// d(position)/d(joint) of a revolute joint about Z at `pivot`, for a point `p`.
Eigen::Matrix<double, 6, 1> zTwist(const Eigen::Vector2d& p, const Eigen::Vector2d& pivot) {
  Eigen::Matrix<double, 6, 1> t;
  t << -(p.y() - pivot.y()), p.x() - pivot.x(), 0, 0, 0, 1;
  return t;
}
}  // namespace

KinStatus solveTwoLink(double x, double y, double l1, double l2, int8_t elbow, const double* aNear, double& a,
                       double& b) {
  const double r2 = x * x + y * y;
  // sin^2 B from the factored form: no cancellation of 1 - cos^2 near the boundary.
  const double sum = l1 + l2, diff = l1 - l2;
  const double s2 = (sum * sum - r2) * (r2 - diff * diff) / (4 * l1 * l1 * l2 * l2);
  if (!std::isfinite(s2) || s2 < -1e-14) return KinStatus::Unreachable;
  KinStatus st = KinStatus::Ok;
  double sb = s2 > 0 ? std::sqrt(s2) : 0.0;
  if (sb < 1e-12) {
    sb = 0;
    st = KinStatus::Singular;
  }
  const double cb = (r2 - l1 * l1 - l2 * l2) / (2 * l1 * l2);
  b = std::atan2(branch(elbow) * sb, cb);
  if (std::sqrt(r2) < 1e-12 * sum) {   // l1 == l2 folded onto the base: A is free
    a = aNear ? *aNear : 0.0;
    return KinStatus::Singular;
  }
  a = std::atan2(y, x) - std::atan2(l2 * std::sin(b), l1 + l2 * std::cos(b));
  return st;
}

// ---- Scara2
Scara2::Scara2(const Scara2Params& p) : Kinematics(2, 0b11), p_(p) {
  if (!goodLength(p.l1) || !goodLength(p.l2)) invalidate();
}

Config Scara2::configOf(const double* q) const { return {signOf(wrapPi(q[1])), 1, 1}; }

KinStatus Scara2::solveForward(const double* q, Pose& out) const {
  Eigen::Vector2d e, w;
  twoLink(q[0], q[1], p_.l1, p_.l2, e, w);
  out.p = {w.x(), w.y(), 0};
  out.R = rotZ(q[0] + q[1]);
  return KinStatus::Ok;
}

KinStatus Scara2::solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const {
  return solveTwoLink(x.p.x(), x.p.y(), p_.l1, p_.l2, c.elbow, qNear, q[0], q[1]);
}

void Scara2::jacobianOf(const double* q, Jacobian& J) const {
  Eigen::Vector2d e, w;
  twoLink(q[0], q[1], p_.l1, p_.l2, e, w);
  J.col(0) = zTwist(w, {0, 0});
  J.col(1) = zTwist(w, e);
}

// ---- Scara3
Scara3::Scara3(const Scara3Params& p) : Kinematics(3, 0b111), p_(p) {
  if (!goodLength(p.l1) || !goodLength(p.l2) || !goodLength(p.l3)) invalidate();
}

Config Scara3::configOf(const double* q) const { return {signOf(wrapPi(q[1])), 1, 1}; }

KinStatus Scara3::solveForward(const double* q, Pose& out) const {
  Eigen::Vector2d e, w;
  twoLink(q[0], q[1], p_.l1, p_.l2, e, w);
  const double phi = q[0] + q[1] + q[2];
  out.p = {w.x() + p_.l3 * std::cos(phi), w.y() + p_.l3 * std::sin(phi), 0};
  out.R = rotZ(phi);
  return KinStatus::Ok;
}

KinStatus Scara3::solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const {
  const double phi = planarAngle(x.R);
  const double wx = x.p.x() - p_.l3 * std::cos(phi), wy = x.p.y() - p_.l3 * std::sin(phi);
  KinStatus s = solveTwoLink(wx, wy, p_.l1, p_.l2, c.elbow, qNear, q[0], q[1]);
  q[2] = phi - q[0] - q[1];
  return s;
}

void Scara3::jacobianOf(const double* q, Jacobian& J) const {
  Eigen::Vector2d e, w;
  twoLink(q[0], q[1], p_.l1, p_.l2, e, w);
  const double phi = q[0] + q[1] + q[2];
  const Eigen::Vector2d t = w + p_.l3 * Eigen::Vector2d(std::cos(phi), std::sin(phi));
  J.col(0) = zTwist(t, {0, 0});
  J.col(1) = zTwist(t, e);
  J.col(2) = zTwist(t, w);
}

// ---- Scara4
Scara4::Scara4(const Scara4Params& p) : Kinematics(4, 0b1011), p_(p) {
  if (!goodLength(p.l1) || !goodLength(p.l2) || !std::isfinite(p.z0) || (p.zSign != 1 && p.zSign != -1))
    invalidate();
}

Config Scara4::configOf(const double* q) const { return {signOf(wrapPi(q[1])), 1, 1}; }

KinStatus Scara4::solveForward(const double* q, Pose& out) const {
  Eigen::Vector2d e, w;
  twoLink(q[0], q[1], p_.l1, p_.l2, e, w);
  out.p = {w.x(), w.y(), p_.z0 + p_.zSign * q[2]};
  out.R = rotZ(q[0] + q[1] + q[3]);
  return KinStatus::Ok;
}

KinStatus Scara4::solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const {
  KinStatus s = solveTwoLink(x.p.x(), x.p.y(), p_.l1, p_.l2, c.elbow, qNear, q[0], q[1]);
  q[2] = (x.p.z() - p_.z0) * p_.zSign;
  q[3] = planarAngle(x.R) - q[0] - q[1];
  return s;
}

void Scara4::jacobianOf(const double* q, Jacobian& J) const {
  Eigen::Vector2d e, w;
  twoLink(q[0], q[1], p_.l1, p_.l2, e, w);
  J.col(0) = zTwist(w, {0, 0});
  J.col(1) = zTwist(w, e);
  J(2, 2) = p_.zSign;
  J(5, 3) = 1;
}

}  // namespace stc::motion::kin
