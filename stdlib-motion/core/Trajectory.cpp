// One-axis trajectory planner (see Trajectory.h and docs/motion.md, "Trajectories").
//
// Model (what "time-optimal" means here)
// --------------------------------------
// A velocity plan is one *velocity transition* from (v0, a0) to (vTarget, a = 0).
// A position plan is
//     [transition (v0, a0) -> (vp, 0)] + [cruise at vp for tc >= 0] + [transition (vp, 0) -> (vEnd, 0)]
// with a peak velocity |vp| <= vel; it is the fastest plan of that shape (vp and tc
// chosen optimally).  Overshoot-and-return is the case where vp points away from
// the target.  Each transition is the time-optimal change of velocity under the
// bounds below.  The optimum is a plan with |vp| = vel and a cruise, or a root of
// D(vp) = target - p0 (D: displacement of the two transitions, no cruise): both
// are enumerated over the pieces of vp between the breakpoints -vel, 0-, 0+,
// vNat, vEnd, vel and the fastest is taken.
//
// Acceleration bounds and the crossing of v = 0:
//  - Trapezoidal (jerk == 0 or +inf): a transition is a constant-acceleration ramp.
//    If it keeps the sign of v it uses acc when |v| grows and dec when |v| falls.
//    If it crosses v = 0 it is split at v = 0: dec down to v = 0, then acc up to the
//    new velocity (exact in the model, no conservatism).  The start acceleration is
//    ignored: the profile's start() keeps the given state (with its a), segment 0
//    starts with the acceleration the first ramp needs (a jumps at t = 0+).
//  - Jerk-limited: a transition is the time-optimal acceleration trapezoid or
//    triangle (|j| = jerk on the ramps) with plateau bound A, chosen per transition:
//       A = acc            if v >= 0 throughout (mirrored so that the transition
//                          raises v: |v| only grows while a > 0),
//       A = dec            if it ends at v <= 0 (|v| only falls while a > 0),
//       A = min(acc, dec)  if v crosses 0 during the transition (the whole
//                          transition, not only the part after the crossing).
//    Formally, mirrored so that the transition raises v: A = acc when
//    min(v0, vNat) >= 0, else dec when the target velocity <= 0, else min(acc, dec);
//    vNat = v0 + a0|a0|/(2 jerk) is the velocity reached by ramping the start
//    acceleration to 0 at full jerk.  A transition that starts or ends exactly at
//    v = 0 does not cross it (a plan may stop exactly at v = 0 and restart).
//  - Start acceleration (jerk-limited): it is changed at full jerk from the first
//    instant.  If it exceeds the plateau bound A in the direction of the transition
//    it is first ramped down to A at full jerk.  While the start acceleration is
//    ramped towards 0, |a| never exceeds |a0|; excursions the start state makes
//    unavoidable are not corrected further: |a0| above the bound of the side v is on
//    (e.g. v crosses 0 during that first ramp), and |v| above vel while a0 pushes
//    outwards (|v| then peaks at |vNat|).
//  - A start with |v| > vel: the first transition goes to |vp| <= vel with the
//    falling-speed bound; it never speeds up beyond vel (beyond |vNat| when a0 pushes).
//
// Besides that shape, jerk-limited position plans from a start acceleration that
// pushes towards vEnd's side of vNat are also searched in the "eased" shape (see
// EaseProblem): the acceleration does not pass 0 at a velocity peak there, and
// such plans can be much faster than any peak-velocity plan.  Rest-to-rest plans
// are closed-form (planRestToRestJerk).  The min(acc, dec) rule for transitions
// that cross v = 0 is part of the model (docs/motion.md, "Trajectories").
#include "stdlib-motion/core/Trajectory.h"
#include "stdlib-motion/core/TrajectoryFamily.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stc::motion {

namespace {

inline Kinematic integrate(const Kinematic& s, double j, double dt) {
  return {s.p + dt * (s.v + dt * (s.a * 0.5 + dt * j * (1.0 / 6.0))), s.v + dt * (s.a + dt * j * 0.5),
          s.a + dt * j};
}

using detail::Ctx;

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

void pushTrans(Profile& out, const Trans& r, bool jerkMode) { out.pushSegments(r.dur, r.val, r.n, !jerkMode); }

// The segments of a plan of the peak-velocity shape: transition r1 into vp,
// (snapped to vp, a = 0) cruise for tc (if > 0), transition r2; as pushTrans(r1),
// snap(vp, 0), push(tc, 0), pushTrans(r2) (trapezoidal mode: pushAcc).
void peakSegs(const Trans& r1, double vp, double tc, const Trans& r2, bool jerkMode, detail::PlanSegs& sg) {
  int n = 0;
  for (int i = 0; i < r1.n; ++i) { sg.dur[n] = r1.dur[i]; sg.val[n++] = r1.val[i]; }
  sg.snapAt = n;
  sg.snapV = vp;
  sg.dur[n] = tc; sg.val[n++] = 0.0;
  for (int i = 0; i < r2.n; ++i) { sg.dur[n] = r2.dur[i]; sg.val[n++] = r2.val[i]; }
  sg.n = n;
  sg.acc = !jerkMode;
}

void pushPeakPlan(Profile& out, const Trans& r1, double vp, double tc, const Trans& r2, bool jerkMode) {
  detail::PlanSegs sg;
  peakSegs(r1, vp, tc, r2, jerkMode, sg);
  out.pushSegments(sg.dur, sg.val, sg.n, sg.acc, sg.snapAt, sg.snapV);
}

inline bool finite(double x) { return std::isfinite(x); }

PlanStatus checkLimits(const Limits& lim) {
  auto pos = [](double x) { return finite(x) && x > 0; };
  if (!pos(lim.vel) || !pos(lim.acc) || !pos(lim.dec)) return PlanStatus::InvalidLimits;
  if (std::isnan(lim.jerk) || lim.jerk < 0) return PlanStatus::InvalidLimits;
  return PlanStatus::Ok;
}

bool validState(const Kinematic& s) { return finite(s.p) && finite(s.v) && finite(s.a); }

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

void hold(const Kinematic& start, Profile& out) {
  out.clear(start);
  out.finish(start);
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
// (converged: set to true when the result is a point where |fn| <= 4e-16 mag)
template <class Fn>
double solveRootOn(const Fn& fn, double lo, double flo, double hi, double fhi, int zs, bool* converged = nullptr) {
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
    if (std::fabs(fu) <= 4e-16 * mag) {
      if (converged) *converged = true;
      return mapPiece(lo, hi, u);
    }
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

// The cruise equation of TimedFamily::plan: h(x) = x (T1 + T2 - T) - (D(x) - delta)
// is zero where the family member with peak velocity x, cruising for the rest of
// T, ends at the target (T1, T2: the transitions into and out of x; D: their
// displacement).  With its derivatives in x: inside a piece the transitions keep
// their direction and bound, and, for the transition into x (mirrored frame: end
// velocity wp = s x, final ramp at acceleration ap for t3), dT1/dx = s / ap and
// dD1/dx = wp / ap + t3 / 2; for the one out of x (start up = s x, first ramp at
// ap for t1), dT2/dx = -s / ap and dD2/dx = t1 / 2 - up / ap.  When both have a
// plateau (trapezoidal mode: always) T1 + T2 is linear and D quadratic in x, so h
// is a quadratic with h'' = d(T1 + T2)/dx; a triangle's ap moves with x (second
// derivatives below).
struct CruiseEval {
  double x = 0, h = 0, dh = 0, d2h = 0, mag = 0;
  double dTabs = 0;    // |dT1/dx| + |dT2/dx|
  bool quad = false;   // h is the quadratic h + dh d + d2h d^2 / 2 around x
  Trans r1, r2;
};

inline void cruiseEval(const Ctx& c, double v0, double a0, double vEnd, double delta, double T, double x, int z,
                       CruiseEval& e) {
  trans(v0, a0, x, c, e.r1, 0, z);
  trans(x, 0, vEnd, c, e.r2, z, 0);
  const Trans &a = e.r1, &b = e.r2;
  // (the arithmetic of PosProblem::f and of the residual as TimedFamily::plan had it)
  const double tr = a.T + b.T;
  const double fx = (a.D + b.D) - delta;
  e.x = x;
  e.mag = (std::fabs(a.D) + std::fabs(b.D) + std::fabs(delta)) + std::fabs(x) * (tr + T);
  e.h = x * (tr - T) - fx;
  double dT, dD, d2T = 0, d2D;
  if (c.jerkMode) {
    const double ia = c.iJ / a.dur[2], ib = c.iJ / b.dur[0];   // 1 / ap of each
    dT = a.s * ia - b.s * ib;
    e.dTabs = std::fabs(ia) + std::fabs(ib);
    dD = (a.s * x * ia + 0.5 * a.dur[2]) + (0.5 * b.dur[0] - b.s * x * ib);
    // second derivatives: with a plateau ap is fixed (T'' = 0, D1'' = s / A,
    // D2'' = -s / A); a triangle's ap = sqrt(J |x - x0| + ...) moves with x:
    // T'' = -J / (2 ap^3), D1'' = 5 s / (4 ap) - x J / (2 ap^3), D2'' = -5 s / (4 ap) - x J / (2 ap^3)
    const bool triA = !a.over && !(a.dur[1] > 0), triB = !(b.dur[1] > 0);
    d2D = triA ? 1.25 * a.s * ia : a.s * ia;
    d2D -= triB ? 1.25 * b.s * ib : b.s * ib;
    if (triA) {
      const double k = -0.5 * c.J * ia * ia * ia;
      d2T += k;
      d2D += x * k;
    }
    if (triB) {
      const double k = -0.5 * c.J * ib * ib * ib;
      d2T += k;
      d2D += x * k;
    }
    e.quad = !triA && !triB;
  } else {
    // ramps at the accelerations val[]: T1 = (x - v0) / val, D1 = (x^2 - v0^2) / (2 val), and
    // crossing 0: T1 = |v0| / dec + x / val[1], D1 = (v0 t1 + x t2) / 2; likewise out of x
    double dT1 = 0, dD1 = 0, dT2 = 0, dD2 = 0;
    if (a.n == 1) { dT1 = 1 / a.val[0]; dD1 = 0.5 * a.T + 0.5 * (v0 + x) * dT1; }
    else if (a.n == 2) { dT1 = 1 / a.val[1]; dD1 = 0.5 * (a.dur[1] + x * dT1); }
    if (b.n == 1) { dT2 = -1 / b.val[0]; dD2 = 0.5 * b.T + 0.5 * (x + vEnd) * dT2; }
    else if (b.n == 2) { dT2 = -1 / b.val[0]; dD2 = 0.5 * (b.dur[0] + x * dT2); }
    dT = dT1 + dT2;
    dD = dD1 + dD2;
    d2D = dT;   // (D1'' = 1 / val = T1', likewise D2'')
    e.dTabs = std::fabs(dT1) + std::fabs(dT2);
    e.quad = true;
  }
  e.dh = (tr - T) + x * dT - dD;
  e.d2h = 2 * dT + x * d2T - d2D;
}

// A root of h on (lo, hi), h(lo) and h(hi) of opposite signs (neither 0): steps
// to the nearer root of the local quadratic h + h' d + h'' d^2 / 2 (exact up to
// rounding with a plateau in both transitions, else third-order convergence;
// Newton where it has no real root), kept inside the bracket (else an Illinois
// step).  True with e at a point where |h| <= 4e-16 mag (solveRootOn's test);
// false after kMaxEvals evaluations (e: the last one).  2.7 evaluations per
// root on BM_Sync6ArbitraryStates' sets (solveRootOn took about 6).
inline bool cruiseRoot(const Ctx& c, double v0, double a0, double vEnd, double delta, double T, double lo,
                       double hlo, double hi, double hhi, int z, CruiseEval& e) {
  constexpr int kMaxEvals = 12;
  double xa = lo, ha = hlo, xb = hi, hb = hhi;   // the bracket, ha * hb < 0
  // first point: solveRootOn's first step (secant in its smoothstep variable)
  double x = mapPiece(lo, hi, hlo / (hlo - hhi));
  int side = 0;   // the end the last bracket steps kept (Illinois)
  for (int it = 0; it < kMaxEvals; ++it) {
    if (!(x > std::min(xa, xb) && x < std::max(xa, xb))) x = 0.5 * (xa + xb);
    cruiseEval(c, v0, a0, vEnd, delta, T, x, z, e);
    if (std::isnan(e.h)) return false;
    if (std::fabs(e.h) <= 4e-16 * e.mag) return true;
    if ((e.h < 0) == (ha < 0)) { xa = x; ha = e.h; }
    else { xb = x; hb = e.h; }
    // the model's step (the root of the local quadratic, exact if e.quad)
    double d = std::numeric_limits<double>::quiet_NaN();
    if (e.d2h != 0) {
      const double disc = e.dh * e.dh - 2 * e.d2h * e.h;
      if (disc >= 0) d = -2 * e.h / (e.dh + std::copysign(std::sqrt(disc), e.dh));   // (the smaller root)
    }
    if (!std::isfinite(d)) d = -e.h / e.dh;
    double xn = x + d;
    if (!(xn > std::min(xa, xb) && xn < std::max(xa, xb))) {
      // regula falsi on the bracket, halving the value at the end kept twice
      const int keep = (x == xa) ? 2 : 1;
      if (side == keep) { if (keep == 1) ha *= 0.5; else hb *= 0.5; }
      side = keep;
      xn = xb - hb * (xb - xa) / (hb - ha);
    } else {
      side = 0;
    }
    if (xn == x) return false;
    x = xn;
  }
  return false;
}

// Rest-to-rest (v0 = a0 = vEnd = 0), jerk-limited, closed form.  The rising
// transition uses acc (A1), the falling one dec (A2); each is a triangle of time
// 2 sqrt(vp/J) below vp = A^2/J, else a trapezoid of time vp/A + A/J, and the
// distance of both together is vp (T1 + T2) / 2.  D(vp) grows with vp, so the
// piece holding the root follows from D at the two breakpoints; on it the root
// is explicit (both triangles: D = 2 vp^1.5 / sqrt(J); both trapezoids: a
// quadratic in vp) or, one of each, the positive root of a quartic in
// s = sqrt(vp) by Newton from the right end (increasing and convex: monotone).
void planRestToRestJerk(const Kinematic& start, double target, const Ctx& c, Profile& out) {
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
  pushPeakPlan(out, r1, dir * vp, tc, r2, true);
  out.finish({target, 0.0, 0.0});
}

}  // namespace

// ---------------------------------------------------------------- Profile

void Profile::clear(const Kinematic& start) {
  count_ = 0;
  duration_ = 0;
  start_ = end_ = cur_ = start;
}

void Profile::push(double duration, double jerk) {
  if (count_ >= kMaxSegments) return;
  segs_[count_++] = {duration_, cur_.p, cur_.v, cur_.a, jerk, duration};
  cur_ = integrate(cur_, jerk, duration);
  duration_ += duration;
}

void Profile::pushAcc(double duration, double acc) {
  if (count_ >= kMaxSegments) return;
  cur_.a = acc;
  segs_[count_++] = {duration_, cur_.p, cur_.v, acc, 0.0, duration};
  cur_ = integrate(cur_, 0.0, duration);
  duration_ += duration;
}

void Profile::pushSegments(const double* dur, const double* val, int n, bool acc, int snapAt, double snapV) {
  Kinematic c = cur_;
  double t = duration_;
  int k = count_;
  for (int i = 0; i < n; ++i) {
    if (i == snapAt) { c.v = snapV; c.a = 0.0; }
    if (!(dur[i] > 0) || k >= kMaxSegments) continue;
    const double j = acc ? 0.0 : val[i];
    if (acc) c.a = val[i];
    segs_[k++] = {t, c.p, c.v, c.a, j, dur[i]};
    c = integrate(c, j, dur[i]);
    t += dur[i];
  }
  if (snapAt >= n) { c.v = snapV; c.a = 0.0; }
  cur_ = c;
  duration_ = t;
  count_ = k;
}

void Profile::finish(const Kinematic& exactEnd) {
  end_ = exactEnd;
  cur_ = exactEnd;
}

Kinematic Profile::at(double t) const {
  if (!(t > 0)) return start_;
  if (t >= duration_) return {end_.p + end_.v * (t - duration_), end_.v, end_.a};
  int i = count_ - 1;
  while (i > 0 && t < segs_[i].t0) --i;
  const Segment& s = segs_[i];
  // (t - t0 may exceed the exact duration by the rounding of the stored times)
  const double dt = std::min(t - s.t0, s.dur);
  return integrate({s.p, s.v, s.a}, s.j, dt);
}

// ---------------------------------------------------------------- planners

PlanStatus planVelocity(const Kinematic& start, double vTarget, const Limits& lim, Profile& out) {
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

namespace {

// What planPosition found about the peak-velocity family on its way to the
// optimum (TimedFamily::init starts from it instead of finding it again): the
// breakpoints of vp with D - delta and the transition time there, and the roots
// of D = delta between them with D - delta and the time at the root.  Not
// filled (valid false) for the closed-form rest-to-rest plans.
struct PosScan {
  bool defer = false;   // (in) describe the optimal plan in segs (and duration), do not build it
  bool deferred = false;
  detail::PlanSegs segs;
  double duration = 0;
  bool valid = false;
  Ctx c;          // makeCtx(lim)
  double vnat;    // the velocity at which ramping a0 out ends
  int nb = 0, nr = 0;
  double bp[8], fv[8], Tv[8];
  int zs[8];
  double root[8], rootF[8], rootT[8];
  int rootSide[8];
};

PlanStatus planPositionImpl(const Kinematic& start, double target, double vEnd, const Limits& lim, Profile& out,
                            PosScan* scan);

// The optimal plan found: built into out, or (scan->defer) described in scan with
// the duration the Profile would have (the same sum in the same order).
void finishPlan(const Kinematic& start, const detail::PlanSegs& sg, Profile& out, PosScan* scan) {
  if (scan && scan->defer) {
    scan->deferred = true;
    scan->segs = sg;
    double t = 0;
    int k = 0;
    for (int i = 0; i < sg.n; ++i)
      if (sg.dur[i] > 0 && k < Profile::kMaxSegments) { t += sg.dur[i]; ++k; }
    scan->duration = t;
    return;
  }
  sg.build(start, out);
}

}  // namespace

PlanStatus planPosition(const Kinematic& start, double target, double vEnd, const Limits& lim, Profile& out) {
  return planPositionImpl(start, target, vEnd, lim, out, nullptr);
}

namespace {

PlanStatus planPositionImpl(const Kinematic& start, double target, double vEnd, const Limits& lim, Profile& out,
                            PosScan* scan) {
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
      const double fx = P.f(x, &T, nullptr, side);
      if (T < bestT) { bestT = T; bestVp = x; bestTc = 0; bestZs = side; }
      if (scan) {
        const int k = scan->nr++;
        scan->root[k] = x; scan->rootF[k] = fx; scan->rootT[k] = T; scan->rootSide[k] = side;
      }
    }
  }
  if (scan) {
    scan->valid = true;
    scan->c = c;
    scan->vnat = vnat;
    scan->nb = nb;
    for (int i = 0; i < nb; ++i) {
      scan->bp[i] = bp[i]; scan->zs[i] = zs[i]; scan->fv[i] = fv[i]; scan->Tv[i] = Tv[i];
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
      detail::PlanSegs sg;
      sg.dur[0] = bestTe;
      sg.val[0] = -g * c.J;
      for (int i = 0; i < r.n; ++i) { sg.dur[1 + i] = r.dur[i]; sg.val[1 + i] = r.val[i]; }
      sg.n = 1 + r.n;
      sg.end = {target, vEnd, 0.0};
      finishPlan(start, sg, out, scan);
      return PlanStatus::Ok;
    }
  }

  Trans r1, r2;
  trans(P.v0, P.a0, bestVp, c, r1, 0, bestZs);
  trans(bestVp, 0, vEnd, c, r2, bestZs, 0);
  detail::PlanSegs sg;
  peakSegs(r1, bestVp, bestTc, r2, c.jerkMode, sg);
  sg.end = {target, vEnd, 0.0};
  finishPlan(start, sg, out, scan);
  return PlanStatus::Ok;
}

}  // namespace

}  // namespace stc::motion

// ---------------------------------------------------------------- timed family

namespace stc::motion::detail {

PlanStatus TimedFamily::init(const Kinematic& start, double target, double vEnd, const Limits& lim) {
  n_ = 0;
  wait_ = false;
  PosScan scan;
  scan.defer = true;
  const PlanStatus st = planPositionImpl(start, target, vEnd, lim, opt_, &scan);
  optBuilt_ = !scan.deferred;   // (else opt_ holds the plan: the closed forms, an invalid input)
  if (scan.deferred) {
    optSegs_ = scan.segs;
    tMin_ = scan.duration;
  } else {
    tMin_ = opt_.duration();
  }
  if (st != PlanStatus::Ok) return st;
  start_ = start;
  target_ = target;
  vEnd_ = vEnd;
  PosProblem P;
  P.c = c_ = scan.valid ? scan.c : makeCtx(lim);
  P.v0 = v0_ = start.v;
  P.a0 = a0_ = P.c.jerkMode ? start.a : 0.0;
  P.vEnd = vEnd;
  P.delta = delta_ = target - start.p;
  const double vel = P.c.vel;
  const double vnat = scan.valid ? scan.vnat : P.c.jerkMode ? P.v0 + P.a0 * std::fabs(P.a0) / (2 * P.c.J) : P.v0;
  // points: the breakpoints of vp (as in planPosition), then the roots of D = delta
  // (x, side) with its D - delta and transition time, into the sorted points
  auto addKnown = [&](double x, int side, double f, double tt) {
    if (n_ >= kMaxPoints) return;
    int k = n_++;
    while (k > 0 && (x_[k - 1] > x || (x_[k - 1] == x && zs_[k - 1] > side))) {
      x_[k] = x_[k - 1]; zs_[k] = zs_[k - 1]; f_[k] = f_[k - 1]; tt_[k] = tt_[k - 1];
      --k;
    }
    x_[k] = x;
    zs_[k] = side;
    f_[k] = f;
    tt_[k] = tt;
  };
  auto add = [&](double x, int side) {
    double tt;
    const double f = P.f(x, &tt, nullptr, side);
    addKnown(x, side, f, tt);
  };
  const double inf = std::numeric_limits<double>::infinity();
  if (start.v == 0 && P.a0 == 0 && vEnd == 0 && delta_ != 0) {
    // rest to rest: the durations are [minimum, inf), cruising at 0 < |vp| <= the
    // optimal peak (G falls from inf to the minimum there)
    double peak = 0;
    const Profile& opt = optimal();
    for (int i = 0; i < opt.segmentCount(); ++i) peak = std::max(peak, std::fabs(opt.segment(i).v));
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
  if (scan.valid) {
    // planPosition's breakpoints (sorted; vNat = vEnd twice) and roots, with the
    // values it computed (the same arithmetic as evaluating them here)
    for (int i = 0; i < scan.nb; ++i)
      if (i == 0 || scan.bp[i] != scan.bp[i - 1] || scan.zs[i] != scan.zs[i - 1])
        addKnown(scan.bp[i], scan.zs[i], scan.fv[i], scan.Tv[i]);
    for (int i = 0; i < scan.nr; ++i) {
      const double x = scan.root[i];
      if (x != 0 || scan.rootSide[i] == 1) addKnown(x, x == 0 ? 1 : 0, scan.rootF[i], scan.rootT[i]);
      else add(x, 1);   // (a root at 0 from the left: the points use 0+)
    }
  } else {
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
  }
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

int TimedFamily::starts(double* out, int cap) const {
  int k = 0;
  if (k < cap) out[k++] = minimum();
  if (wait_ && k < cap) out[k++] = waitT_;
  for (int i = 0; i < n_ && k < cap; ++i) {
    const bool edge = (i + 1 < n_ && inS_[i]) || (i > 0 && inS_[i - 1]);
    if (edge && std::isfinite(g_[i])) out[k++] = g_[i];
  }
  return k;
}

namespace {
inline bool closeTo(double a, double b) {
  return std::isfinite(b) && std::fabs(a - b) <= 1e-12 * std::max(1.0, std::fabs(b));
}
}  // namespace

bool TimedFamily::feasible(double T) const {
  if (closeTo(T, minimum())) return true;
  if (wait_ && T >= waitT_) return true;
  for (int i = 0; i + 1 < n_; ++i) {
    if (!inS_[i]) continue;
    const double lo = std::min(g_[i], g_[i + 1]), hi = std::max(g_[i], g_[i + 1]);
    if ((T >= lo && T <= hi) || closeTo(T, lo) || closeTo(T, hi)) return true;
  }
  return false;
}

const Profile& TimedFamily::optimal() const {
  if (!optBuilt_) {
    optSegs_.build(start_, opt_);
    optBuilt_ = true;
  }
  return opt_;
}

bool TimedFamily::plan(double T, Profile& out) const {
  if (closeTo(T, minimum())) {
    if (optBuilt_) out = opt_;
    else optSegs_.build(start_, out);
    return true;
  }
  PosProblem P;
  P.c = c_;
  P.v0 = v0_;
  P.a0 = a0_;
  P.vEnd = vEnd_;
  P.delta = delta_;
  const Ctx& c = P.c;
  double vp = 0;
  int side = 0;
  bool found = false, haveTrans = false;
  CruiseEval ev;   // (haveTrans: the transitions at vp)
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
    // h at the points from their stored D - delta and transition time (as h computes it)
    const double hlo = x_[i] * (tt_[i] - T) - f_[i], hhi = x_[i + 1] * (tt_[i + 1] - T) - f_[i + 1];
    if (!((hlo <= 0 && hhi >= 0) || (hlo >= 0 && hhi <= 0))) continue;
    const int z = x_[i] == 0 ? 1 : x_[i + 1] == 0 ? -1 : 0;
    if (hlo != 0 && hhi != 0 && cruiseRoot(c, v0_, a0_, vEnd_, delta_, T, x_[i], hlo, x_[i + 1], hhi, z, ev)) {
      // Accepted where the root is well resolved: |h| <= 4e-16 mag leaves vp
      // uncertain by about kappa, negligible against vp, against its distance to
      // the piece's ends (where a transition shrinks to nothing, its times and
      // acceleration ~ sqrt of that distance), in the transition times, and in
      // the position after cruising (kappa T) against the distance to go and the
      // target (the positions after the cruise).
      // Otherwise (a tiny transition, a flat h, a long cruise far out and back)
      // the bracketing solver below, as before: its result there depends on where
      // it stops inside that uncertainty, and it is kept.
      const double kappa = 4e-16 * ev.mag / std::fabs(ev.dh);
      const double dist = std::min(std::fabs(ev.x - x_[i]), std::fabs(x_[i + 1] - ev.x));
      if (kappa <= 1e-12 * dist && kappa <= 1e-13 * std::max(1.0, std::fabs(ev.x)) && kappa * ev.dTabs <= 1e-12 &&
          kappa * T <= 1e-12 * std::max(1.0, std::min(std::fabs(delta_), std::fabs(target_)))) {
        vp = ev.x;   // (inside the piece: not 0, and its transitions are those of side 0)
        side = 0;
        found = haveTrans = true;
        break;
      }
    }
    // (rare: the bracketing solver of the breakpoints' roots, as before)
    bool converged = false;
    vp = solveRootOn(h, x_[i], hlo, x_[i + 1], hhi, z, &converged);
    side = vp != 0 ? 0 : z;
    if (converged) {   // (|h| <= 4e-16 mag there: well inside the check below)
      found = true;
    } else {
      double mag = 0;
      found = !std::isnan(vp) && std::fabs(h(vp, nullptr, &mag, side)) <= 1e-11 * mag;
    }
  }
  if (!found) return false;
  if (!haveTrans) {
    trans(P.v0, P.a0, vp, c, ev.r1, 0, side);
    trans(vp, 0, vEnd_, c, ev.r2, side, 0);
  }
  const Trans &r1 = ev.r1, &r2 = ev.r2;
  const double tc = std::max(0.0, T - r1.T - r2.T);
  out.clear(start_);
  pushPeakPlan(out, r1, vp, tc, r2, c.jerkMode);
  out.finish({target_, vEnd_, 0.0});
  // (G is not always monotone between the points: a piece whose end values
  // bracket T may not hold a plan of duration T)
  return std::fabs(out.duration() - T) <= 1e-10 * std::max(1.0, T);
}

}  // namespace stc::motion::detail
