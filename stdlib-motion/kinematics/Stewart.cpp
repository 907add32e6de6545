#include "stdlib-motion/kinematics/Stewart.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <numbers>

namespace stc::motion::kin {

StewartParams StewartParams::symmetric(double rb, double rp, double hb, double hp, double height) {
  StewartParams s;
  for (int k = 0; k < 3; ++k) {
    const double cb = k * 2 * std::numbers::pi / 3, cp = cb + std::numbers::pi / 3;
    for (int j = 0; j < 2; ++j) {
      const double sgn = j ? 1.0 : -1.0;
      s.base[2 * k + j] = {rb * std::cos(cb + sgn * hb), rb * std::sin(cb + sgn * hb), 0};
      // Each base pair's legs go to the two nearest platform joints.
      const double ap = sgn > 0 ? cp - hp : cp - 2 * std::numbers::pi / 3 + hp;
      s.platform[2 * k + j] = {rp * std::cos(ap), rp * std::sin(ap), 0};
    }
  }
  s.home.p = {0, 0, height};
  return s;
}

Stewart::Stewart(const StewartParams& p) : Kinematics(6, 0), p_(p) {
  bool ok = finite(p.home) && p.maxIterations > 0 && p.maxIterations <= 1000;
  double s = 0;
  for (int i = 0; i < 6; ++i) {
    ok = ok && p.base[i].allFinite() && p.platform[i].allFinite();
    s = std::max({s, p.base[i].norm(), p.platform[i].norm()});
  }
  scale_ = s > 0 && std::isfinite(s) ? s : 1;
  if (!ok || s > 1e12) invalidate();
  // A mechanism singular at home cannot be solved from there.
  if (ok && std::abs(legJacobian(p.home).determinant()) < 1e-12) invalidate();
}

Eigen::Matrix<double, 6, 6> Stewart::legJacobian(const Pose& x) const {
  Eigen::Matrix<double, 6, 6> A;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d m = x.R * p_.platform[i];
    const Eigen::Vector3d leg = x.p + m - p_.base[i];
    const double l = leg.norm();
    const Eigen::Vector3d n = l > 0 ? Eigen::Vector3d(leg / l) : Eigen::Vector3d::Zero();
    A.block<1, 3>(i, 0) = n.transpose();
    A.block<1, 3>(i, 3) = m.cross(n).transpose();
  }
  return A;
}

KinStatus Stewart::solveInverse(const Pose& x, const Config&, const double*, double* q) const {
  KinStatus s = KinStatus::Ok;
  for (int i = 0; i < 6; ++i) {
    q[i] = (x.p + x.R * p_.platform[i] - p_.base[i]).norm();
    if (q[i] < 1e-12 * scale_) s = KinStatus::Singular;   // a leg of length 0 has no direction
  }
  return s;
}

KinStatus Stewart::solveForward(const double* q, Pose& out) const { return forwardFrom(q, p_.home, out); }

KinStatus Stewart::forwardFrom(const double* q, const Pose& guess, Pose& out) const {
  if (!valid() || !finite(guess)) return KinStatus::InvalidParameters;
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(q[i]) || q[i] < 0) return KinStatus::Unreachable;
  Pose x = guess;
  const double tol = 16 * std::numeric_limits<double>::epsilon() * scale_;
  auto done = [&] {
    // Re-orthonormalise R (the exponential updates drift by rounding only).
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(x.R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    out.p = x.p;
    out.R = svd.matrixU() * svd.matrixV().transpose();
    return KinStatus::Ok;
  };
  for (int it = 0; it < p_.maxIterations; ++it) {
    Eigen::Matrix<double, 6, 1> f;
    for (int i = 0; i < 6; ++i) f[i] = (x.p + x.R * p_.platform[i] - p_.base[i]).norm() - q[i];
    if (f.cwiseAbs().maxCoeff() <= tol) return done();
    Eigen::PartialPivLU<Eigen::Matrix<double, 6, 6>> lu(legJacobian(x));
    if (!(std::abs(lu.determinant()) > 1e-14)) return KinStatus::Singular;
    const Eigen::Matrix<double, 6, 1> d = lu.solve(-f);
    if (!d.allFinite()) return KinStatus::NoConvergence;
    // Limit the step to a fraction of the mechanism's size: far starts stay bounded.
    double k = 1;
    const double lin = d.head<3>().norm(), ang = d.tail<3>().norm();
    if (lin > 0.5 * scale_) k = std::min(k, 0.5 * scale_ / lin);
    if (ang > 0.5) k = std::min(k, 0.5 / ang);
    x.p += k * d.head<3>();
    const Eigen::Vector3d w = k * d.tail<3>();
    if (w.norm() > 0) x.R = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * x.R;
    if (k == 1 && lin + ang * scale_ <= 1e-15 * scale_) return done();   // rounding level
  }
  return KinStatus::NoConvergence;
}

void Stewart::jacobianOf(const double* q, Jacobian& J) const {
  Pose x;
  if (forwardFrom(q, p_.home, x) != KinStatus::Ok) return;
  Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(legJacobian(x));
  if (!lu.isInvertible()) return;
  J = lu.inverse();
}

}  // namespace stc::motion::kin
