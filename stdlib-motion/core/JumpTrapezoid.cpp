// The start/creep-velocity trapezoid (JumpTrapezoid.h).
#include "stdlib-motion/core/JumpTrapezoid.h"

#include <algorithm>
#include <cmath>

namespace stc::motion {

std::shared_ptr<JumpTrapezoid> JumpTrapezoid::position(double p0, double distance, double vStart, double vMax,
                                                       double vCreep, double acc, double dec) {
  auto g = std::make_shared<JumpTrapezoid>();
  g->p0_ = p0;
  g->sign_ = distance < 0 ? -1 : 1;
  const double D = std::fabs(distance);
  g->a_ = acc;
  g->d_ = dec;
  double v0 = std::min(vStart, vMax), ve = std::min(vCreep, vMax);
  if (D == 0) return g;
  // Distances of full ramps to vMax (a ramp of rate 0 is a jump).
  const double da = acc > 0 ? (vMax * vMax - v0 * v0) / (2 * acc) : 0;
  const double dd = dec > 0 ? (vMax * vMax - ve * ve) / (2 * dec) : 0;
  double vp = vMax;
  if (da + dd > D) {
    // No cruise: the peak where both ramps meet.  With one ramp a jump, the other ramp alone covers D.
    if (acc > 0 && dec > 0) vp = std::sqrt((2 * acc * dec * D + dec * v0 * v0 + acc * ve * ve) / (acc + dec));
    else if (acc > 0) vp = std::sqrt(v0 * v0 + 2 * acc * D);
    else vp = std::sqrt(ve * ve + 2 * dec * D);
    vp = std::min(vp, vMax);
    // Too short even for one ramp: keep the rates, the arrival speed adapts.
    if (dec > 0 && vp < v0) {
      vp = v0;
      ve = std::sqrt(std::max(0.0, v0 * v0 - 2 * dec * D));
    } else if (acc > 0 && vp < ve) {
      vp = ve = std::sqrt(v0 * v0 + 2 * acc * D);
    }
  }
  g->v0_ = v0;
  g->vp_ = vp;
  g->ve_ = ve;
  g->t1_ = acc > 0 ? (vp - v0) / acc : 0;
  g->t3_ = dec > 0 ? (vp - ve) / dec : 0;
  const double s1 = (v0 + vp) / 2 * g->t1_, s3 = (vp + ve) / 2 * g->t3_;
  g->t2_ = std::max(0.0, D - s1 - s3) / vp;
  return g;
}

std::shared_ptr<JumpTrapezoid> JumpTrapezoid::velocity(double p0, double v, double vStart, double acc) {
  auto g = std::make_shared<JumpTrapezoid>();
  g->p0_ = p0;
  g->sign_ = v < 0 ? -1 : 1;
  g->stops_ = false;
  const double vt = std::fabs(v);
  g->v0_ = std::min(vStart, vt);
  g->vp_ = g->ve_ = vt;
  g->a_ = acc;
  g->t1_ = acc > 0 ? (vt - g->v0_) / acc : 0;
  return g;
}

Kinematic JumpTrapezoid::at(double t) const {
  const double T = duration();
  double s = 0, v = 0, a = 0;
  if (t >= T) {
    // The end: at the target and stopped, or at the target velocity.
    s = (v0_ + vp_) / 2 * t1_ + vp_ * t2_ + (vp_ + ve_) / 2 * t3_;
    v = stops_ ? 0 : vp_;
    if (!stops_) s += vp_ * (t - T);
  } else if (t < t1_) {
    s = v0_ * t + a_ * t * t / 2;
    v = v0_ + a_ * t;
    a = a_;
  } else if (t < t1_ + t2_) {
    s = (v0_ + vp_) / 2 * t1_ + vp_ * (t - t1_);
    v = vp_;
  } else {
    const double u = t - t1_ - t2_;
    s = (v0_ + vp_) / 2 * t1_ + vp_ * t2_ + vp_ * u - d_ * u * u / 2;
    v = vp_ - d_ * u;
    a = -d_;
  }
  return Kinematic{p0_ + sign_ * s, sign_ * v, sign_ * a};
}


}  // namespace stc::motion
