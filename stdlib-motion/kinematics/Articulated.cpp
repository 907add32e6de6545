#include "stdlib-motion/kinematics/Articulated.h"

#include <cmath>
#include <numbers>

#include "stdlib-motion/kinematics/Scara.h"   // solveTwoLink

namespace stc::motion::kin {

namespace {
constexpr double kHalfPi = std::numbers::pi / 2;

Eigen::Isometry3d link(const DhLink& l, double q) {
  const double th = q + l.thetaOffset;
  const double ct = std::cos(th), st = std::sin(th), ca = std::cos(l.alpha), sa = std::sin(l.alpha);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0, sa, ca;
  T.translation() << l.a * ct, l.a * st, l.d;
  return T;
}

// +1 / -1 for alpha = +-90 deg, 0 otherwise.
int rightAngle(double alpha) {
  if (std::abs(alpha - kHalfPi) < 1e-12) return 1;
  if (std::abs(alpha + kHalfPi) < 1e-12) return -1;
  return 0;
}

Eigen::Matrix3d rotY(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d R;
  R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}
}  // namespace

Articulated6::Articulated6(const DhTable& dh) : Kinematics(6, 0b111111), dh_(dh) {
  bool ok = true;
  for (const DhLink& l : dh)
    ok = ok && std::isfinite(l.a) && std::isfinite(l.alpha) && std::isfinite(l.d) && std::isfinite(l.thetaOffset) &&
         std::abs(l.a) <= 1e12 && std::abs(l.d) <= 1e12;
  s1_ = rightAngle(dh[0].alpha);
  s3_ = rightAngle(dh[2].alpha);
  s4_ = rightAngle(dh[3].alpha);
  s5_ = rightAngle(dh[4].alpha);
  ok = ok && s1_ && s3_ && s4_ && s5_ && dh[1].alpha == 0 && dh[3].a == 0 && dh[4].a == 0 && dh[4].d == 0 &&
       dh[1].a > 0 && std::hypot(dh[2].a, dh[3].d) > 0;
  if (!ok) invalidate();
  l3_ = std::hypot(dh[2].a, dh[3].d);
  beta_ = std::atan2(-s3_ * dh[3].d, dh[2].a);
  // Frame 5's origin seen from frame 6: -R56^T t56 = -Rx(-alpha6) (a6, 0, d6).
  const double a6 = dh[5].a, d6 = dh[5].d, al = dh[5].alpha;
  wristToFlange_ = -Eigen::Vector3d(a6, d6 * std::sin(al), d6 * std::cos(al));
}

void Articulated6::frames(const double* q, std::array<Eigen::Isometry3d, 7>& T) const {
  T[0] = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) T[i + 1] = T[i] * link(dh_[i], q[i]);
}

KinStatus Articulated6::solveForward(const double* q, Pose& out) const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) T = T * link(dh_[i], q[i]);
  out.p = T.translation();
  out.R = T.linear();
  return KinStatus::Ok;
}

Config Articulated6::configOf(const double* q) const {
  const double th2 = q[1] + dh_[1].thetaOffset, th3 = q[2] + dh_[2].thetaOffset;
  const double g = th3 + beta_;
  const double x1 = dh_[1].a * std::cos(th2) + l3_ * std::cos(th2 + g);
  return {signOf(std::sin(g)), signOf(x1 + dh_[0].a), signOf(wrapPi(q[4] + dh_[4].thetaOffset))};
}

KinStatus Articulated6::solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const {
  KinStatus st = KinStatus::Ok;
  const Eigen::Vector3d w = x.p + x.R * wristToFlange_;   // wrist centre
  // Axis 1: the wrist centre seen from above is (rho, -s1 D) turned by theta1.
  const double dl = dh_[1].d + dh_[2].d;
  const double h2 = w.x() * w.x() + w.y() * w.y();
  const double disc = h2 - dl * dl;
  const double scale = h2 + dl * dl + 1e-300;
  if (disc < -1e-14 * scale) return KinStatus::Unreachable;
  double rho = branch(c.shoulder) * std::sqrt(std::max(disc, 0.0));
  double th[6];
  if (std::abs(rho) < 1e-12 * (std::sqrt(scale) + dh_[1].a)) st = KinStatus::Singular;
  if (h2 < 1e-24 * (dh_[1].a * dh_[1].a)) {   // on axis 1 (no lateral offset): theta1 free
    th[0] = qNear ? qNear[0] + dh_[0].thetaOffset : 0.0;
    rho = 0;
  } else {
    th[0] = std::atan2(w.y(), w.x()) - std::atan2(-s1_ * dl, rho);
  }
  // Axes 2, 3: a planar two-link arm (a2, l3) in frame 1.
  const double x1 = rho - dh_[0].a, y1 = s1_ * (w.z() - dh_[0].d);
  const double near2 = qNear ? qNear[1] + dh_[1].thetaOffset : 0.0;
  double g;
  KinStatus s2 = solveTwoLink(x1, y1, dh_[1].a, l3_, c.elbow, &near2, th[1], g);
  if (s2 == KinStatus::Unreachable) return s2;
  if (s2 == KinStatus::Singular) st = s2;
  th[2] = g - beta_;
  // Wrist: N = R03^T R Rx(alpha6)^T [Rx(pi)] = Rz(theta4) Ry(-s4 theta5) Rz(+-theta6).
  Eigen::Isometry3d T03 = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i) T03 = T03 * link(dh_[i], th[i] - dh_[i].thetaOffset);
  const double al6 = dh_[5].alpha;
  Eigen::Matrix3d rx6;
  rx6 << 1, 0, 0, 0, std::cos(al6), -std::sin(al6), 0, std::sin(al6), std::cos(al6);
  Eigen::Matrix3d N = T03.linear().transpose() * x.R * rx6.transpose();
  const bool flip = s5_ == s4_;   // Rx(alpha4) Rx(alpha5) = Rx(pi): theta6 enters negated
  if (flip) N.col(1) = -N.col(1), N.col(2) = -N.col(2);   // N * Rx(pi)
  const double ws = -s4_ * branch(c.wrist);                // sign of psi
  const double sp = std::hypot(N(0, 2), N(1, 2));
  double phi, psi, chi;
  if (sp < 1e-12) {   // theta5 = 0 or pi: only theta4 +- theta6 is defined
    st = KinStatus::Singular;
    psi = std::atan2(0.0, N(2, 2));
    phi = qNear ? qNear[3] + dh_[3].thetaOffset : 0.0;
    const Eigen::Matrix3d K = rotY(psi).transpose() * rotZ(phi).transpose() * N;
    chi = std::atan2(K(1, 0), K(0, 0));
  } else {
    psi = std::atan2(ws * sp, N(2, 2));
    phi = std::atan2(ws * N(1, 2), ws * N(0, 2));
    chi = std::atan2(ws * N(2, 1), -ws * N(2, 0));
  }
  th[3] = phi;
  th[4] = -s4_ * psi;
  th[5] = flip ? -chi : chi;
  for (int i = 0; i < 6; ++i) q[i] = th[i] - dh_[i].thetaOffset;
  return st;
}

void Articulated6::jacobianOf(const double* q, Jacobian& J) const {
  std::array<Eigen::Isometry3d, 7> T;
  frames(q, T);
  const Eigen::Vector3d pe = T[6].translation();
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d z = T[i].linear().col(2);
    J.block<3, 1>(0, i) = z.cross(pe - T[i].translation());
    J.block<3, 1>(3, i) = z;
  }
}

}  // namespace stc::motion::kin
