// The synchronised planner as it was before the speed work on branch sync6
// (commit 2ada7ef): TimedFamily recomputed the breakpoints and roots of the
// peak-velocity family that planPosition had already found, and plan() solved
// each candidate from scratch.  Frozen here, test-only, as the reference the
// faster planner must reproduce (SyncPlanLegacyTest.cpp), with the one-axis
// planner of that commit (planPosition, planVelocity) it used.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <type_traits>

#include "stdlib-motion/core/SyncPlan.h"
#include "stdlib-motion/core/Trajectory.h"

namespace stc::motion::legacy {
namespace {   // (one translation unit: SyncPlanLegacyTest.cpp)

class TimedFamily {
public:
  PlanStatus init(const Kinematic& start, double target, double vEnd, const Limits& lim);
  double minimum() const { return opt_.duration(); }
  const Profile& optimal() const { return opt_; }
  int starts(double* out, int cap) const;
  bool feasible(double T) const;
  bool plan(double T, Profile& out) const;
  static constexpr int kMaxPoints = 16;

private:
  Limits lim_;
  Kinematic start_;
  double target_ = 0, vEnd_ = 0, delta_ = 0, v0_ = 0, a0_ = 0;
  Profile opt_;
  int n_ = 0;
  double x_[kMaxPoints];
  int zs_[kMaxPoints];
  double f_[kMaxPoints], tt_[kMaxPoints], g_[kMaxPoints];
  bool inS_[kMaxPoints];
  bool wait_ = false;
  int waitSide_ = 0;
  double waitT_ = 0;
};


inline Kinematic integrate(const Kinematic& s, double j, double dt) {
  return {s.p + dt * (s.v + dt * (s.a * 0.5 + dt * j * (1.0 / 6.0))), s.v + dt * (s.a + dt * j * 0.5),
          s.a + dt * j};
}

struct Ctx {
  double J;       // jerk (jerk mode only)
  double acc, dec, vel;
  bool jerkMode;
  // reciprocals (jerk mode): 1/J and 1/acc, 1/dec, 1/min(acc, dec)
  double iJ, iAcc, iDec, amin, iAmin;
};

// A velocity transition: up to 3 phases (jerk mode: constant jerk; trapezoidal
// mode: constant acceleration), total time T and displacement D.
struct Trans {
  int n = 0;
  double dur[3];
  double val[3];
  double T = 0, D = 0;
  double s = 1;        // jerk-limited: +1 if the transition raises v (after a0 is ramped out), else -1
  double A = 0;        // jerk-limited: the plateau bound used
  bool over = false;   // jerk-limited: the start acceleration exceeded the plateau bound
};

// uz, wz: which side of 0 a zero start / end velocity stands for (-1: 0-, +1: 0+,
// 0: exactly 0); they only matter when u or w is 0 (the bound A changes there).
inline void transJerk(double u, double a0, double w, const Ctx& c, Trans& r, int uz = 0, int wz = 0) {
  const double J = c.J, iJ = c.iJ;
  const double unat = u + a0 * std::fabs(a0) * (0.5 * iJ);
  const double s = (w >= unat) ? 1.0 : -1.0;
  const double up = s * u, a = s * a0, wp = s * w, unp = s * unat;
  const double umin = std::min(up, unp);
  // all v >= 0 (mirrored): acc; ends at v <= 0: dec; crosses 0: min(acc, dec)
  const bool startsNonNeg = umin > 0 || (umin == 0 && (unp > 0 || s * uz >= 0));
  const bool endsNonPos = wp < 0 || (wp == 0 && s * wz <= 0);
  const double A = startsNonNeg ? c.acc : (endsNonPos ? c.dec : c.amin);
  const double iA = startsNonNeg ? c.iAcc : (endsNonPos ? c.iDec : c.iAmin);
  double t1, j1, t2, t3, ap;
  r.s = s;
  r.A = A;
  r.over = a > A;
  if (a > A) {
    t1 = (a - A) * iJ;
    j1 = -J;
    ap = A;
    t2 = std::max(0.0, (wp - unp) * iA);
    t3 = A * iJ;
  } else {
    j1 = J;
    const double ap2 = J * (wp - up) + 0.5 * a * a;
    if (ap2 <= A * A) {
      ap = std::sqrt(std::max(ap2, 0.0));
      t1 = std::max(0.0, (ap - a) * iJ);
      t2 = 0;
      t3 = ap * iJ;
    } else {
      ap = A;
      t1 = (A - a) * iJ;
      t2 = std::max(0.0, (wp - up) * iA - (2 * A * A - a * a) * (0.5 * iJ * iA));
      t3 = A * iJ;
    }
  }
  // displacement in the mirrored frame
  const double x1 = t1 * (up + t1 * (a * 0.5 + t1 * j1 * (1.0 / 6.0)));
  const double v1 = up + t1 * (a + t1 * j1 * 0.5);
  const double v2 = wp - ap * t3 * 0.5;   // velocity where the final ramp starts
  const double x2 = 0.5 * (v1 + v2) * t2;
  const double x3 = t3 * (wp - J * t3 * t3 * (1.0 / 6.0));
  r.n = 3;
  r.dur[0] = t1; r.val[0] = s * j1;
  r.dur[1] = t2; r.val[1] = 0;
  r.dur[2] = t3; r.val[2] = -s * J;
  r.T = t1 + t2 + t3;
  r.D = s * (x1 + x2 + x3);
}

inline void transTrap(double u, double w, const Ctx& c, Trans& r) {
  if (u == w) {
    r.n = 0; r.T = 0; r.D = 0;
  } else if (u * w >= 0) {
    const double A = std::fabs(w) > std::fabs(u) ? c.acc : c.dec;
    const double t = std::fabs(w - u) / A;
    r.n = 1;
    r.dur[0] = t; r.val[0] = w > u ? A : -A;
    r.T = t;
    r.D = 0.5 * (u + w) * t;
  } else {
    const double t1 = std::fabs(u) / c.dec, t2 = std::fabs(w) / c.acc;
    r.n = 2;
    r.dur[0] = t1; r.val[0] = u > 0 ? -c.dec : c.dec;
    r.dur[1] = t2; r.val[1] = w > 0 ? c.acc : -c.acc;
    r.T = t1 + t2;
    r.D = 0.5 * (u * t1 + w * t2);
  }
}

inline void trans(double u, double a0, double w, const Ctx& c, Trans& r, int uz = 0, int wz = 0) {
  if (c.jerkMode) transJerk(u, a0, w, c, r, uz, wz);
  else transTrap(u, w, c, r);
}

void pushTrans(Profile& out, const Trans& r, bool jerkMode) {
  for (int i = 0; i < r.n; ++i) {
    if (!(r.dur[i] > 0)) continue;
    if (jerkMode) out.push(r.dur[i], r.val[i]);
    else out.pushAcc(r.dur[i], r.val[i]);
  }
}

inline bool finite(double x) { return std::isfinite(x); }
Ctx makeCtx(const Limits& lim) {
  Ctx c;
  c.acc = lim.acc; c.dec = lim.dec; c.vel = lim.vel;
  c.jerkMode = lim.jerk > 0 && finite(lim.jerk);
  c.J = c.jerkMode ? lim.jerk : 0;
  c.iJ = c.jerkMode ? 1 / c.J : 0;
  c.iAcc = 1 / c.acc;
  c.iDec = 1 / c.dec;
  c.amin = std::min(c.acc, c.dec);
  c.iAmin = 1 / c.amin;
  return c;
}


// The position problem: displacement as a function of the peak velocity.
struct PosProblem {
  Ctx c;
  double v0, a0, vEnd, delta;
  // D(vp) - delta, and the total transition time
  // (mag: the size of the terms, i.e. the scale of the rounding error of f)
  // (zs: the side of 0 that vp == 0 stands for, see transJerk)
  inline double f(double vp, double* T = nullptr, double* mag = nullptr, int zs = 0) const {
    Trans r1, r2;
    trans(v0, a0, vp, c, r1, 0, zs);
    trans(vp, 0, vEnd, c, r2, zs, 0);
    if (T) *T = r1.T + r2.T;
    if (mag) *mag = std::fabs(r1.D) + std::fabs(r2.D) + std::fabs(delta);
    return (r1.D + r2.D) - delta;
  }
};

// The "eased" family of position plans: from a start acceleration a0 != 0 the
// jerk first eases a0 towards 0 (at -sign(a0) J for te <= |a0| / J, without
// reaching 0), then one time-optimal transition hardens it again and ends at
// (vEnd, 0).  The velocity is monotone: such a plan has no interior peak, so it
// is not a member of the peak-velocity family (which passes a = 0 at vp) and is
// faster than it when the start is already accelerating towards the end velocity
// too strongly for the distance (e.g. braking, target a little further away).
// Residual D(te) - delta; NaN where the transition would start above its bound.
struct EaseProblem {
  Ctx c;
  double v0, a0, vEnd, delta;
  inline double f(double te, double* T = nullptr, double* mag = nullptr, Trans* keep = nullptr) const {
    const double g = a0 > 0 ? 1.0 : -1.0;
    const Kinematic e = integrate({0, v0, a0}, -g * c.J, te);
    Trans r;
    transJerk(e.v, e.a, vEnd, c, r);
    // (at the breakpoint where a(te) = A the start may be above A by rounding)
    if (r.s != g || (r.over && std::fabs(e.a) > r.A * (1 + 1e-12))) return std::numeric_limits<double>::quiet_NaN();
    if (T) *T = te + r.T;
    if (mag) *mag = std::fabs(e.p) + std::fabs(r.D) + std::fabs(delta);
    if (keep) *keep = r;
    return (e.p + r.D) - delta;
  }
};

// Root of p.f on the piece [lo, hi] with f(lo) * f(hi) < 0.  The search runs on
// u in [0, 1] with vp = lo + (hi - lo) * s(u), s the smoothstep 3u^2 - 2u^3: the
// transition times behave like sqrt(|vp - end|) next to a breakpoint (a vanishing
// triangle), s removes that singularity at both ends, so the iteration converges
// fast and the root is resolved far below the spacing of doubles near lo or hi.
// Illinois variant of regula falsi.
inline double mapPiece(double lo, double hi, double u) {
  if (u <= 0.5) return lo + (hi - lo) * (u * u * (3 - 2 * u));
  const double w = 1 - u;
  return hi - (hi - lo) * (w * w * (3 - 2 * w));
}

// fn(x, T*, mag*, zs) is the residual at x on the piece [lo, hi].
template <class Fn>
double solveRootOn(const Fn& fn, double lo, double flo, double hi, double fhi, int zs) {
  double u0 = 0, f0 = flo, u1 = 1, f1 = fhi;
  for (int it = 0; it < 100; ++it) {
    double u = u1 - f1 * (u1 - u0) / (f1 - f0);
    const double a = std::min(u0, u1), b = std::max(u0, u1);
    if (!(u > a && u < b)) {
      u = 0.5 * (u0 + u1);
      if (!(u > a && u < b)) break;
    }
    double mag;
    const double fu = fn(mapPiece(lo, hi, u), nullptr, &mag, zs);
    if (std::isnan(fu)) return fu;
    if (std::fabs(fu) <= 4e-16 * mag) return mapPiece(lo, hi, u);
    if ((fu < 0) != (f1 < 0)) {
      u0 = u1; f0 = f1;
    } else {
      f0 *= 0.5;
    }
    u1 = u; f1 = fu;
  }
  return mapPiece(lo, hi, std::fabs(f0) < std::fabs(f1) ? u0 : u1);
}

double solveRoot(const PosProblem& p, double lo, double flo, double hi, double fhi) {
  const int zs = lo == 0 ? 1 : hi == 0 ? -1 : 0;   // a piece next to 0 is on one side of it
  auto fn = [&p](double x, double* T, double* mag, int z) { return p.f(x, T, mag, z); };
  return solveRootOn(fn, lo, flo, hi, fhi, zs);
}


inline PlanStatus checkLimits(const Limits& lim) {
  auto pos = [](double x) { return finite(x) && x > 0; };
  if (!pos(lim.vel) || !pos(lim.acc) || !pos(lim.dec)) return PlanStatus::InvalidLimits;
  if (std::isnan(lim.jerk) || lim.jerk < 0) return PlanStatus::InvalidLimits;
  return PlanStatus::Ok;
}

inline bool validState(const Kinematic& s) { return finite(s.p) && finite(s.v) && finite(s.a); }

inline void hold(const Kinematic& start, Profile& out) {
  out.clear(start);
  out.finish(start);
}

// Rest-to-rest (v0 = a0 = vEnd = 0), jerk-limited, closed form.  The rising
// transition uses acc (A1), the falling one dec (A2); each is a triangle of time
// 2 sqrt(vp/J) below vp = A^2/J, else a trapezoid of time vp/A + A/J, and the
// distance of both together is vp (T1 + T2) / 2.  D(vp) grows with vp, so the
// piece holding the root follows from D at the two breakpoints; on it the root
// is explicit (both triangles: D = 2 vp^1.5 / sqrt(J); both trapezoids: a
// quadratic in vp) or, one of each, the positive root of a quartic in
// s = sqrt(vp) by Newton from the right end (increasing and convex: monotone).
inline void planRestToRestJerk(const Kinematic& start, double target, const Ctx& c, Profile& out) {
  const double delta = target - start.p;
  const double dir = delta > 0 ? 1.0 : -1.0, D = std::fabs(delta);
  const double J = c.J, iJ = c.iJ, A1 = c.acc, A2 = c.dec;
  auto tOf = [&](double vp, double A) { return vp * J >= A * A ? vp / A + A * iJ : 2 * std::sqrt(vp * iJ); };
  auto dOf = [&](double vp) { return 0.5 * vp * (tOf(vp, A1) + tOf(vp, A2)); };
  double vp, tc = 0;
  const double dVel = dOf(c.vel);
  if (dVel <= D) {
    vp = c.vel;
    tc = (D - dVel) / c.vel;
  } else {
    const double b1 = std::min(A1, A2), b2 = std::max(A1, A2);
    const double vLo = b1 * b1 * iJ, vHi = b2 * b2 * iJ;
    if (vLo >= c.vel || D <= dOf(vLo)) {
      vp = std::cbrt(0.25 * D * D * J);   // (D sqrt(J) / 2)^(2/3)
    } else if (vHi >= c.vel || D <= dOf(vHi)) {
      // s^4 / (2 b1) + s^3 / sqrt(J) + s^2 b1 / (2 J) - D = 0
      const double k4 = 0.5 / b1, k3 = std::sqrt(iJ), k2 = 0.5 * b1 * iJ;
      double sq = std::sqrt(std::min(vHi, c.vel));
      for (int it = 0; it < 60; ++it) {
        const double s2 = sq * sq;
        const double h = s2 * (s2 * k4 + sq * k3 + k2) - D;
        const double dh = sq * (4 * s2 * k4 + 3 * sq * k3 + 2 * k2);
        const double step = h / dh;
        sq -= step;
        if (!(std::fabs(step) > 1e-16 * sq)) break;
      }
      vp = sq * sq;
    } else {
      // vp^2 (1/A1 + 1/A2) / 2 + vp (A1 + A2) / (2 J) - D = 0
      const double qa = 0.5 * (1 / A1 + 1 / A2), qb = 0.5 * (A1 + A2) * iJ;
      vp = 2 * D / (qb + std::sqrt(qb * qb + 4 * qa * D));
    }
    vp = std::min(vp, c.vel);
  }
  Trans r1, r2;
  transJerk(0, 0, dir * vp, c, r1);
  transJerk(dir * vp, 0, 0, c, r2);
  out.clear(start);
  pushTrans(out, r1, true);
  out.snap(dir * vp, 0.0);
  if (tc > 0) out.push(tc, 0.0);
  pushTrans(out, r2, true);
  out.finish({target, 0.0, 0.0});
}

inline PlanStatus oldPlanVelocity(const Kinematic& start, double vTarget, const Limits& lim, Profile& out) {
  PlanStatus st = checkLimits(lim);
  if (st == PlanStatus::Ok && (!finite(vTarget) || std::fabs(vTarget) > lim.vel)) st = PlanStatus::InvalidTarget;
  if (st == PlanStatus::Ok && !validState(start)) st = PlanStatus::InvalidState;
  if (st != PlanStatus::Ok) {
    hold(start, out);
    return st;
  }
  const Ctx c = makeCtx(lim);
  Trans r;
  trans(start.v, c.jerkMode ? start.a : 0.0, vTarget, c, r);
  out.clear(start);
  pushTrans(out, r, c.jerkMode);
  // integrated end position (position is free)
  double pEnd = start.p;
  if (out.segmentCount() > 0) {
    const auto& s = out.segment(out.segmentCount() - 1);
    pEnd = integrate({s.p, s.v, s.a}, s.j, out.duration() - s.t0).p;
  }
  out.finish({pEnd, vTarget, 0.0});
  return PlanStatus::Ok;
}

inline PlanStatus oldPlanPosition(const Kinematic& start, double target, double vEnd, const Limits& lim, Profile& out) {
  PlanStatus st = checkLimits(lim);
  if (st == PlanStatus::Ok && (!finite(target) || !finite(vEnd) || std::fabs(vEnd) > lim.vel))
    st = PlanStatus::InvalidTarget;
  if (st == PlanStatus::Ok && !validState(start)) st = PlanStatus::InvalidState;
  if (st != PlanStatus::Ok) {
    hold(start, out);
    return st;
  }
  PosProblem P;
  P.c = makeCtx(lim);
  if (P.c.jerkMode && start.v == 0 && start.a == 0 && vEnd == 0) {
    if (target == start.p) hold(start, out);
    else planRestToRestJerk(start, target, P.c, out);
    return PlanStatus::Ok;
  }
  const Ctx& c = P.c;
  P.v0 = start.v;
  P.a0 = c.jerkMode ? start.a : 0.0;
  P.vEnd = vEnd;
  P.delta = target - start.p;
  const double vel = c.vel;
  const double vnat = c.jerkMode ? P.v0 + P.a0 * std::fabs(P.a0) / (2 * c.J) : P.v0;

  // Breakpoints of the peak velocity: the pieces between them are searched for
  // roots of D(vp) = delta (plans without cruise).  v = 0 is a breakpoint with two
  // sides: the bound of a jerk-limited transition that crosses 0 differs from that
  // of one that ends or starts at 0, so D jumps there and no root is searched across.
  double bp[8];
  int zs[8];   // side of 0 used to evaluate a breakpoint at 0
  int nb = 0;
  auto addBp = [&](double x, int side) {   // insertion into the sorted list
    if (!(x > -vel && x < vel) || (x == 0 && side == 0)) return;
    int k = nb++;
    while (k > 0 && bp[k - 1] > x) { bp[k] = bp[k - 1]; zs[k] = zs[k - 1]; --k; }
    bp[k] = x;
    zs[k] = side;
  };
  bp[nb] = -vel; zs[nb++] = 0;
  addBp(0.0, -1);
  addBp(0.0, 1);   // (inserted after 0-, the sort is stable)
  addBp(vnat, 0);
  addBp(vEnd, 0);
  bp[nb] = vel; zs[nb++] = 0;

  double bestT = std::numeric_limits<double>::infinity();
  double bestVp = 0, bestTc = 0;
  int bestZs = 0;

  double fv[8], Tv[8];
  for (int i = 0; i < nb; ++i) fv[i] = P.f(bp[i], &Tv[i], nullptr, zs[i]);
  // cruise at +-vel
  if (fv[nb - 1] <= 0) {
    const double tc = -fv[nb - 1] / vel;
    const double T = Tv[nb - 1] + tc;
    if (T < bestT) { bestT = T; bestVp = vel; bestTc = tc; }
  }
  if (fv[0] >= 0) {
    const double tc = fv[0] / vel;
    const double T = Tv[0] + tc;
    if (T < bestT) { bestT = T; bestVp = -vel; bestTc = tc; }
  }
  if (c.jerkMode) {
    // vp = 0 exactly (stop, then restart; D(0) may differ from both one-sided
    // limits): a root only if it is exact, possible only next to a sign change at 0
    int i0 = 0;
    while (i0 < nb && !(bp[i0] == 0)) ++i0;
    if (i0 + 1 < nb && bp[i0 + 1] == 0 && !((fv[i0] < 0 && fv[i0 + 1] < 0) || (fv[i0] > 0 && fv[i0 + 1] > 0))) {
      double T0;
      if (P.f(0.0, &T0) == 0 && T0 < bestT) { bestT = T0; bestVp = 0; bestTc = 0; }
    }
  }
  for (int i = 0; i < nb; ++i) {
    if (fv[i] == 0 && Tv[i] < bestT) { bestT = Tv[i]; bestVp = bp[i]; bestTc = 0; bestZs = zs[i]; }
    if (i + 1 < nb && !(bp[i] == 0 && bp[i + 1] == 0) &&
        ((fv[i] < 0 && fv[i + 1] > 0) || (fv[i] > 0 && fv[i + 1] < 0))) {
      const double x = solveRoot(P, bp[i], fv[i], bp[i + 1], fv[i + 1]);
      const int side = x != 0 ? 0 : bp[i] == 0 ? 1 : -1;
      double T;
      P.f(x, &T, nullptr, side);
      if (T < bestT) { bestT = T; bestVp = x; bestTc = 0; bestZs = side; }
    }
  }

  // the eased family (jerk-limited, a0 pushing beyond vEnd's side of vNat)
  bool eased = false;
  double bestTe = 0;
  if (c.jerkMode && P.a0 != 0 && (P.a0 > 0 ? vEnd > vnat : vEnd < vnat)) {
    const EaseProblem E{c, P.v0, P.a0, vEnd, P.delta};
    const double aa = std::fabs(P.a0), g = P.a0 > 0 ? 1.0 : -1.0;
    const double tm = aa * c.iJ;
    double tb[16];
    int nt = 0;
    double tCross = -1;   // where v crosses 0 during the ease: the bound A (and D) jump there
    auto addT = [&](double t) {
      if (!(t > 0 && t < tm)) return;
      int k = nt++;
      while (k > 0 && tb[k - 1] > t) { tb[k] = tb[k - 1]; --k; }
      tb[k] = t;
    };
    tb[nt++] = 0;
    // v crosses 0 during the ease: g v(te) = g v0 + |a0| te - J te^2 / 2 = 0
    const double disc = aa * aa + 2 * c.J * g * P.v0;
    if (g * P.v0 < 0 && disc >= 0) {
      tCross = (aa - std::sqrt(disc)) * c.iJ;
      addT(tCross);
    }
    // the transition reaches its plateau bound A: a(te)^2 + J g (vEnd - vNat) = A^2,
    // and the start of the transition is at A
    const double K = c.J * g * (vEnd - vnat);
    for (double A : {c.acc, c.dec}) {
      if (A * A > K) addT((aa - std::sqrt(A * A - K)) * c.iJ);
      addT((aa - A) * c.iJ);
    }
    // D(te) is not monotone: its stationary points (a1 = |a0| - J te, mirrored so
    // that a0 > 0; vn = g vNat) are, without plateau (ap^2 = a1^2 + K),
    // 2 a1^2 - 2 J vn = a1 ap, i.e. 3 a1^4 - (8 J vn + K) a1^2 + 4 J^2 vn^2 = 0, and
    // with a plateau at A, 2 a1^2 - A a1 - 2 J vn = 0.  The total time grows with te.
    const double vn = g * vnat;
    {
      const double b = 8 * c.J * vn + K, q = 4 * c.J * c.J * vn * vn;
      const double d2 = b * b - 12 * q;
      if (d2 >= 0) {
        const double sq = std::sqrt(d2);
        for (double x2 : {(b + sq) / 6, (b - sq) / 6})
          if (x2 > 0) addT((aa - std::sqrt(x2)) * c.iJ);
      }
      for (double A : {c.acc, c.dec}) {
        const double d3 = A * A + 16 * c.J * vn;
        if (d3 >= 0) {
          const double sq = std::sqrt(d3);
          addT((aa - (A + sq) * 0.25) * c.iJ);
          addT((aa - (A - sq) * 0.25) * c.iJ);
        }
      }
    }
    tb[nt++] = tm;
    // fe: the value at a point, fl: the limit from the left (differs at tCross)
    double fe[16], fl[16], Te[16];
    for (int i = 0; i < nt; ++i) {
      fe[i] = fl[i] = E.f(tb[i], &Te[i]);
      if (tb[i] == tCross) fl[i] = E.f(std::nextafter(tb[i], 0.0));
      if (fe[i] == 0 && Te[i] < bestT) { bestT = Te[i]; eased = true; bestTe = tb[i]; }
    }
    auto fn = [&E](double x, double* T, double* mag, int) { return E.f(x, T, mag); };
    for (int i = 0; i + 1 < nt; ++i) {
      if ((fe[i] < 0 && fl[i + 1] > 0) || (fe[i] > 0 && fl[i + 1] < 0)) {
        const double x = solveRootOn(fn, tb[i], fe[i], tb[i + 1], fl[i + 1], 0);
        double T = std::numeric_limits<double>::infinity(), mag = 0;
        const double fx = E.f(x, &T, &mag);
        if (std::fabs(fx) <= 1e-10 * mag && T < bestT) { bestT = T; eased = true; bestTe = x; }
      }
    }
    if (eased) {
      Trans r;
      E.f(bestTe, nullptr, nullptr, &r);
      out.clear(start);
      if (bestTe > 0) out.push(bestTe, -g * c.J);
      pushTrans(out, r, true);
      out.finish({target, vEnd, 0.0});
      return PlanStatus::Ok;
    }
  }

  Trans r1, r2;
  trans(P.v0, P.a0, bestVp, c, r1, 0, bestZs);
  trans(bestVp, 0, vEnd, c, r2, bestZs, 0);
  out.clear(start);
  pushTrans(out, r1, c.jerkMode);
  out.snap(bestVp, 0.0);
  if (bestTc > 0) {
    if (c.jerkMode) out.push(bestTc, 0.0);
    else out.pushAcc(bestTc, 0.0);
  }
  pushTrans(out, r2, c.jerkMode);
  out.finish({target, vEnd, 0.0});
  return PlanStatus::Ok;
}


inline bool closeTo(double a, double b) {
  return std::isfinite(b) && std::fabs(a - b) <= 1e-12 * std::max(1.0, std::fabs(b));
}


inline PlanStatus TimedFamily::init(const Kinematic& start, double target, double vEnd, const Limits& lim) {
  n_ = 0;
  wait_ = false;
  const PlanStatus st = oldPlanPosition(start, target, vEnd, lim, opt_);
  if (st != PlanStatus::Ok) return st;
  lim_ = lim;
  start_ = start;
  target_ = target;
  vEnd_ = vEnd;
  PosProblem P;
  P.c = makeCtx(lim);
  P.v0 = v0_ = start.v;
  P.a0 = a0_ = P.c.jerkMode ? start.a : 0.0;
  P.vEnd = vEnd;
  P.delta = delta_ = target - start.p;
  const double vel = P.c.vel;
  const double vnat = P.c.jerkMode ? P.v0 + P.a0 * std::fabs(P.a0) / (2 * P.c.J) : P.v0;
  // points: the breakpoints of vp (as in planPosition), then the roots of D = delta
  auto add = [&](double x, int side) {
    if (n_ >= kMaxPoints) return;
    int k = n_++;
    while (k > 0 && (x_[k - 1] > x || (x_[k - 1] == x && zs_[k - 1] > side))) {
      x_[k] = x_[k - 1]; zs_[k] = zs_[k - 1]; f_[k] = f_[k - 1]; tt_[k] = tt_[k - 1];
      --k;
    }
    x_[k] = x;
    zs_[k] = side;
    f_[k] = P.f(x, &tt_[k], nullptr, side);
  };
  const double inf = std::numeric_limits<double>::infinity();
  if (start.v == 0 && P.a0 == 0 && vEnd == 0 && delta_ != 0) {
    // rest to rest: the durations are [minimum, inf), cruising at 0 < |vp| <= the
    // optimal peak (G falls from inf to the minimum there)
    double peak = 0;
    for (int i = 0; i < opt_.segmentCount(); ++i) peak = std::max(peak, std::fabs(opt_.segment(i).v));
    const double dir = delta_ > 0 ? 1.0 : -1.0;
    if (dir > 0) { add(0.0, 1); add(peak, 0); }
    else { add(-peak, 0); add(0.0, -1); }
    const int k0 = dir > 0 ? 0 : 1;
    g_[k0] = inf;
    g_[1 - k0] = minimum();
    inS_[0] = true;
    inS_[1] = false;
    return PlanStatus::Ok;
  }
  add(-vel, 0);
  add(0.0, -1);
  add(0.0, 1);
  if (vnat > -vel && vnat < vel && vnat != 0) add(vnat, 0);
  if (vEnd > -vel && vEnd < vel && vEnd != 0 && vEnd != vnat) add(vEnd, 0);
  add(vel, 0);
  double roots[8];
  int nr = 0;
  for (int i = 0; i + 1 < n_; ++i) {
    if (x_[i] == 0 && x_[i + 1] == 0) continue;
    if ((f_[i] < 0 && f_[i + 1] > 0) || (f_[i] > 0 && f_[i + 1] < 0))
      roots[nr++] = solveRoot(P, x_[i], f_[i], x_[i + 1], f_[i + 1]);
  }
  for (int i = 0; i < nr; ++i) add(roots[i], roots[i] == 0 ? 1 : 0);
  // stop and wait: D(0) = delta on one side of 0
  for (int i = 0; i < n_; ++i) {
    if (x_[i] == 0 && f_[i] == 0 && (!wait_ || tt_[i] < waitT_)) {
      wait_ = true;
      waitSide_ = zs_[i];
      waitT_ = tt_[i];
    }
  }
  // durations at the points and the pieces that admit a cruise
  for (int i = 0; i < n_; ++i) {
    const double x = x_[i];
    g_[i] = x == 0 ? inf : tt_[i] + std::max(0.0, -f_[i] / x);
  }
  for (int i = 0; i + 1 < n_; ++i) {
    inS_[i] = false;
    if (x_[i] == 0 && x_[i + 1] == 0) continue;
    const double side = x_[i] < 0 || (x_[i] == 0 && x_[i + 1] < 0) ? -1.0 : 1.0;   // (0 is a breakpoint)
    // (f has one sign inside a piece; an endpoint may be a root, f ~ 0 of either sign)
    const double fs = std::fabs(f_[i]) >= std::fabs(f_[i + 1]) ? f_[i] : f_[i + 1];
    inS_[i] = side > 0 ? fs <= 0 : fs >= 0;
  }
  if (n_ > 0) inS_[n_ - 1] = false;
  return PlanStatus::Ok;
}

inline int TimedFamily::starts(double* out, int cap) const {
  int k = 0;
  if (k < cap) out[k++] = minimum();
  if (wait_ && k < cap) out[k++] = waitT_;
  for (int i = 0; i < n_ && k < cap; ++i) {
    const bool edge = (i + 1 < n_ && inS_[i]) || (i > 0 && inS_[i - 1]);
    if (edge && std::isfinite(g_[i])) out[k++] = g_[i];
  }
  return k;
}


inline bool TimedFamily::feasible(double T) const {
  if (closeTo(T, minimum())) return true;
  if (wait_ && T >= waitT_) return true;
  for (int i = 0; i + 1 < n_; ++i) {
    if (!inS_[i]) continue;
    const double lo = std::min(g_[i], g_[i + 1]), hi = std::max(g_[i], g_[i + 1]);
    if ((T >= lo && T <= hi) || closeTo(T, lo) || closeTo(T, hi)) return true;
  }
  return false;
}

inline bool TimedFamily::plan(double T, Profile& out) const {
  out = opt_;
  if (closeTo(T, minimum())) return true;
  PosProblem P;
  P.c = makeCtx(lim_);
  P.v0 = v0_;
  P.a0 = a0_;
  P.vEnd = vEnd_;
  P.delta = delta_;
  const Ctx& c = P.c;
  double vp = 0;
  int side = 0;
  bool found = false;
  if (wait_ && T >= waitT_) {
    vp = 0;
    side = waitSide_;
    found = true;
  }
  // h(vp) = vp (T1 + T2 - T) - (D(vp) - delta): zero where the cruise makes the time T
  auto h = [&](double x, double* Tt, double* mag, int z) {
    double tr, m;
    const double fx = P.f(x, &tr, &m, z);
    if (Tt) *Tt = tr;
    if (mag) *mag = m + std::fabs(x) * (tr + T);
    return x * (tr - T) - fx;
  };
  for (int i = 0; i + 1 < n_ && !found; ++i) {
    if (!inS_[i]) continue;
    const double lo = std::min(g_[i], g_[i + 1]), hi = std::max(g_[i], g_[i + 1]);
    if (!(T >= lo && T <= hi) && !closeTo(T, lo) && !closeTo(T, hi)) continue;
    if (closeTo(T, g_[i]) && x_[i] != 0) { vp = x_[i]; side = zs_[i]; found = true; break; }
    if (closeTo(T, g_[i + 1]) && x_[i + 1] != 0) { vp = x_[i + 1]; side = zs_[i + 1]; found = true; break; }
    const double hlo = h(x_[i], nullptr, nullptr, zs_[i]), hhi = h(x_[i + 1], nullptr, nullptr, zs_[i + 1]);
    if (!((hlo <= 0 && hhi >= 0) || (hlo >= 0 && hhi <= 0))) continue;
    const int z = x_[i] == 0 ? 1 : x_[i + 1] == 0 ? -1 : 0;
    vp = solveRootOn(h, x_[i], hlo, x_[i + 1], hhi, z);
    side = vp != 0 ? 0 : z;
    double mag = 0;
    found = !std::isnan(vp) && std::fabs(h(vp, nullptr, &mag, side)) <= 1e-11 * mag;
  }
  if (!found) return false;
  Trans r1, r2;
  trans(P.v0, P.a0, vp, c, r1, 0, side);
  trans(vp, 0, vEnd_, c, r2, side, 0);
  const double tc = std::max(0.0, T - r1.T - r2.T);
  out.clear(start_);
  pushTrans(out, r1, c.jerkMode);
  out.snap(vp, 0.0);
  if (tc > 0) {
    if (c.jerkMode) out.push(tc, 0.0);
    else out.pushAcc(tc, 0.0);
  }
  pushTrans(out, r2, c.jerkMode);
  out.finish({target_, vEnd_, 0.0});
  // (G is not always monotone between the points: a piece whose end values
  // bracket T may not hold a plan of duration T)
  if (!(std::fabs(out.duration() - T) <= 1e-10 * std::max(1.0, T))) {
    out = opt_;
    return false;
  }
  return true;
}


SyncStatus fromPlan(PlanStatus s) {
  switch (s) {
    case PlanStatus::Ok: return SyncStatus::Ok;
    case PlanStatus::InvalidLimits: return SyncStatus::InvalidLimits;
    case PlanStatus::InvalidTarget: return SyncStatus::InvalidTarget;
    case PlanStatus::InvalidState: return SyncStatus::InvalidState;
  }
  return SyncStatus::InvalidState;
}

void holdAll(const SyncAxis* axes, int n, Profile* out) {
  for (int i = 0; i < n; ++i) {
    out[i].clear(axes[i].start);
    out[i].finish(axes[i].start);
  }
}



inline bool jerkMode(const Limits& l) { return l.jerk > 0 && std::isfinite(l.jerk); }

// An axis that starts and ends at rest (v = 0, a = 0 where the jerk is limited,
// vEnd = 0): its feasible durations are [minimum, inf) (no blocked interval), so
// it needs no TimedFamily.  (Invalid inputs are caught by planPosition.)
inline bool restLike(const SyncAxis& a) {
  return a.start.v == 0 && a.vEnd == 0 && (!jerkMode(a.lim) || a.start.a == 0);
}

// The plan of duration T > minimum of a rest axis: the member of TimedFamily's
// family with peak velocity vp, built with the same arithmetic as TimedFamily::plan
// (transitions 0 -> vp with acc, vp -> 0 with dec, cruise T - T1 - T2).  For
// rest to rest D(vp) = vp (T1 + T2) / 2, so G(vp) = (T1 + T2) / 2 + |delta| / vp;
// in y = 1 / vp each transition time is convex (trapezoid 1/(A y) + A/J, triangle
// 2/sqrt(J y), C1 where they meet), so G(y) is convex and Newton from
// y0 = T/|delta| (G(y0) > T) falls monotonically onto the root on the branch
// where G rises, i.e. vp below the optimal peak; no bracketing, no family.
// A target equal to the start: stand still for T (the family's stop-and-wait plan).
// False when the result does not last T within TimedFamily's tolerance.
bool restTimed(const SyncAxis& ax, double T, Profile& out) {
  const bool jm = jerkMode(ax.lim);
  const double delta = ax.target - ax.start.p;
  out.clear(ax.start);
  if (delta == 0) {
    out.snap(0.0, 0.0);
    if (T > 0) {
      if (jm) out.push(T, 0.0);
      else out.pushAcc(T, 0.0);
    }
    out.finish({ax.target, ax.vEnd, 0.0});
    return std::fabs(out.duration() - T) <= 1e-10 * std::max(1.0, T);
  }
  const double dir = delta > 0 ? 1.0 : -1.0, D = std::fabs(delta);
  const double acc = ax.lim.acc, dec = ax.lim.dec;
  const double J = jm ? ax.lim.jerk : 0, iJ = jm ? 1 / J : 0, iAcc = 1 / acc, iDec = 1 / dec;
  // one transition's time and its derivative in y
  auto tr = [&](double y, double A, double iA, double& dt) {
    if (!jm || J >= A * A * y) {   // trapezoid (J vp >= A^2)
      dt = -iA / (y * y);
      return iA / y + A * iJ;
    }
    const double r = 1 / std::sqrt(J * y);   // triangle 2 / sqrt(J y)
    dt = -r / y;
    return 2 * r;
  };
  double y = T / D;
  for (int it = 0; it < 100; ++it) {
    double d1, d2;
    const double g = 0.5 * (tr(y, acc, iAcc, d1) + tr(y, dec, iDec, d2)) + D * y - T;
    const double dg = 0.5 * (d1 + d2) + D;
    if (!(g > 0 && dg > 0)) break;
    const double step = g / dg;
    y -= step;
    if (!(step > 1e-16 * y)) break;
  }
  const double vp = std::min(1 / y, ax.lim.vel);
  // the two transitions exactly as the one-axis planner builds them
  double d1[3], d2[3], j1[3] = {dir * J, 0, -dir * J}, j2[3] = {-dir * J, 0, dir * J};
  auto jerkTrans = [&](double A, double iA, double* d) {
    const double ap2 = J * vp;
    if (ap2 <= A * A) {
      const double ap = std::sqrt(std::max(ap2, 0.0));
      d[0] = std::max(0.0, ap * iJ);
      d[1] = 0;
      d[2] = ap * iJ;
    } else {
      d[0] = A * iJ;
      d[1] = std::max(0.0, vp * iA - (2 * A * A) * (0.5 * iJ * iA));
      d[2] = A * iJ;
    }
    return d[0] + d[1] + d[2];
  };
  double T1, T2;
  if (jm) {
    T1 = jerkTrans(acc, iAcc, d1);
    T2 = jerkTrans(dec, iDec, d2);
  } else {
    T1 = vp / acc;
    T2 = vp / dec;
  }
  const double tc = std::max(0.0, T - T1 - T2);
  if (jm) {
    for (int k = 0; k < 3; ++k)
      if (d1[k] > 0) out.push(d1[k], j1[k]);
  } else if (T1 > 0) {
    out.pushAcc(T1, dir * acc);
  }
  out.snap(dir * vp, 0.0);
  if (tc > 0) {
    if (jm) out.push(tc, 0.0);
    else out.pushAcc(tc, 0.0);
  }
  if (jm) {
    for (int k = 0; k < 3; ++k)
      if (d2[k] > 0) out.push(d2[k], j2[k]);
  } else if (T2 > 0) {
    out.pushAcc(T2, -dir * dec);
  }
  out.finish({ax.target, ax.vEnd, 0.0});
  return std::fabs(out.duration() - T) <= 1e-10 * std::max(1.0, T);
}

// TimedFamily objects built only for the axes that need one (each is ~1.6 KB and
// zeroes a Profile on construction; an array of kMaxSyncAxes built them all).
static_assert(std::is_trivially_destructible_v<TimedFamily>);
class Families {
public:
  PlanStatus make(int i, const SyncAxis& a) {
    f_[i] = new (&slot_[i]) TimedFamily;
    return f_[i]->init(a.start, a.target, a.vEnd, a.lim);
  }
  bool has(int i) const { return f_[i] != nullptr; }
  TimedFamily& operator[](int i) { return *f_[i]; }

private:
  struct alignas(TimedFamily) Slot {
    unsigned char b[sizeof(TimedFamily)];
  };
  Slot slot_[kMaxSyncAxes];
  TimedFamily* f_[kMaxSyncAxes] = {};
};


inline SyncResult planSynchronized(const SyncAxis* axes, int n, Profile* out) {
  SyncResult res;
  if (n < 1 || n > kMaxSyncAxes) {
    res.status = SyncStatus::BadAxisCount;
    if (n > 0) holdAll(axes, std::min(n, kMaxSyncAxes), out);
    return res;
  }
  // Axes at rest (and axes that stay) can arrive at any time after their minimum:
  // their optimal plan goes straight into out[i] and no family is built.  The
  // others get a TimedFamily, constructed only for them.
  Families fams;
  bool rest[kMaxSyncAxes];
  bool optIn[kMaxSyncAxes];   // out[i] holds axis i's optimal plan
  double tMin[kMaxSyncAxes];
  double tLow = 0;
  int nFam = 0;
  for (int i = 0; i < n; ++i) {
    const SyncAxis& a = axes[i];
    rest[i] = restLike(a);
    PlanStatus st;
    if (rest[i]) {
      st = oldPlanPosition(a.start, a.target, a.vEnd, a.lim, out[i]);
      tMin[i] = out[i].duration();
    } else {
      st = fams.make(i, a);
      tMin[i] = fams[i].minimum();
      ++nFam;
    }
    if (st != PlanStatus::Ok) {
      res.status = fromPlan(st);
      res.axis = i;
      holdAll(axes, n, out);
      return res;
    }
    optIn[i] = rest[i];
    tLow = std::max(tLow, tMin[i]);
  }
  // axis i's plan of duration T (false: none; then out[i] may hold anything)
  auto planAxis = [&](int i, double T) {
    if (!rest[i]) return fams[i].plan(T, out[i]);
    if (closeTo(T, tMin[i])) {
      if (!optIn[i]) oldPlanPosition(axes[i].start, axes[i].target, axes[i].vEnd, axes[i].lim, out[i]);
      optIn[i] = true;
      return true;
    }
    optIn[i] = false;
    if (restTimed(axes[i], T, out[i])) return true;
    // (rounding beyond the tolerance: the general family decides, as before)
    if (!fams.has(i)) fams.make(i, axes[i]);
    return fams[i].plan(T, out[i]);
  };
  // Every axis without a family accepts every T >= tLow.  When no family has a
  // start after tLow, tLow is the only candidate (rest-to-rest sets).
  constexpr int kCap = kMaxSyncAxes * (TimedFamily::kMaxPoints + 2) + 1;
  double cand[kCap];
  int nc = 0;
  cand[nc++] = tLow;
  for (int i = 0; i < n && nFam > 0; ++i) {
    if (rest[i]) continue;
    double s[TimedFamily::kMaxPoints + 2];
    const int k = fams[i].starts(s, TimedFamily::kMaxPoints + 2);
    for (int j = 0; j < k; ++j)
      if (s[j] > tLow && nc < kCap) cand[nc++] = s[j];
  }
  if (nc > 1) std::sort(cand, cand + nc);
  // the first candidate at which every axis has a plan (cheap test first)
  double T = cand[nc - 1];
  for (int c = 0; c < nc; ++c) {
    bool all = true;
    for (int i = 0; i < n && all; ++i) all = rest[i] || fams[i].feasible(cand[c]);
    for (int i = 0; i < n && all; ++i) all = planAxis(i, cand[c]);
    if (all) {
      T = cand[c];
      break;
    }
    if (c == nc - 1) {
      // G(vp) is not monotone on every piece, so an interval may begin between
      // the candidates: go later (every axis' last interval is unbounded)
      double t = cand[nc - 1];
      for (int k = 0; k < 200 && !all; ++k) {
        t = t * 1.0625 + 1e-9;
        all = true;
        for (int i = 0; i < n && all; ++i) all = planAxis(i, t);
      }
      T = t;
      if (!all) {   // (not seen in the tests) the optimal plans, not synchronised
        T = 0;
        for (int i = 0; i < n; ++i) {
          if (rest[i]) oldPlanPosition(axes[i].start, axes[i].target, axes[i].vEnd, axes[i].lim, out[i]);
          else out[i] = fams[i].optimal();
          T = std::max(T, tMin[i]);
        }
      }
    }
  }
  res.duration = T;
  return res;
}


inline PlanStatus checkAxis(const SyncAxis& a) {
  const Limits& l = a.lim;
  auto pos = [](double x) { return std::isfinite(x) && x > 0; };
  if (!pos(l.vel) || !pos(l.acc) || !pos(l.dec) || std::isnan(l.jerk) || l.jerk < 0) return PlanStatus::InvalidLimits;
  if (!std::isfinite(a.start.p) || !std::isfinite(a.start.v) || !std::isfinite(a.start.a)) return PlanStatus::InvalidState;
  return PlanStatus::Ok;
}

inline SyncResult oldPlanPhaseSynchronized(const SyncAxis* axes, int n, Profile* out) {
  SyncResult res;
  if (n < 1 || n > kMaxSyncAxes) {
    res.status = SyncStatus::BadAxisCount;
    if (n > 0) holdAll(axes, std::min(n, kMaxSyncAxes), out);
    return res;
  }
  // validate each axis as the one-axis planner does
  Limits path{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
              std::numeric_limits<double>::infinity(), 0};
  double jerkBound = std::numeric_limits<double>::infinity();
  bool anyTrap = false, anyMove = false;
  for (int i = 0; i < n; ++i) {
    const SyncAxis& a = axes[i];
    const PlanStatus st = checkAxis(a);
    PlanStatus st2 = PlanStatus::Ok;
    if (st == PlanStatus::Ok && (!std::isfinite(a.target) || !std::isfinite(a.vEnd))) st2 = PlanStatus::InvalidTarget;
    if (st != PlanStatus::Ok || st2 != PlanStatus::Ok) {
      res.status = fromPlan(st != PlanStatus::Ok ? st : st2);
      res.axis = i;
      holdAll(axes, n, out);
      return res;
    }
    if (a.start.v != 0 || a.start.a != 0 || a.vEnd != 0) {
      res.status = SyncStatus::NotAtRest;
      res.axis = i;
      holdAll(axes, n, out);
      return res;
    }
    const double d = std::fabs(a.target - a.start.p);
    if (d == 0) continue;
    anyMove = true;
    path.vel = std::min(path.vel, a.lim.vel / d);
    path.acc = std::min(path.acc, a.lim.acc / d);
    path.dec = std::min(path.dec, a.lim.dec / d);
    const bool jerkMode = a.lim.jerk > 0 && std::isfinite(a.lim.jerk);
    if (jerkMode) jerkBound = std::min(jerkBound, a.lim.jerk / d);
    else anyTrap = true;
  }
  if (!anyMove) {
    holdAll(axes, n, out);
    return res;
  }
  // an axis without a jerk limit does not constrain the path's jerk; the path is
  // jerk-limited if any axis is (an axis with jerk 0 accepts any jerk)
  (void)anyTrap;
  path.jerk = std::isfinite(jerkBound) ? jerkBound : 0;
  Profile s;
  if (oldPlanPosition({0, 0, 0}, 1, 0, path, s) != PlanStatus::Ok) {
    res.status = SyncStatus::InvalidLimits;   // (scaled limits out of range)
    holdAll(axes, n, out);
    return res;
  }
  const bool jerkMode = path.jerk > 0;
  for (int i = 0; i < n; ++i) {
    const SyncAxis& a = axes[i];
    const double d = a.target - a.start.p;
    Profile& o = out[i];
    o.clear(a.start);
    for (int k = 0; k < s.segmentCount(); ++k) {
      const Profile::Segment& g = s.segment(k);
      if (jerkMode) o.push(g.dur, g.j * d);
      else o.pushAcc(g.dur, g.a * d);
    }
    if (d != 0) o.finish({a.target, 0, 0});
    else {
      o.finish(a.start);
    }
  }
  res.duration = s.duration();
  return res;
}

}  // namespace
}  // namespace stc::motion::legacy
