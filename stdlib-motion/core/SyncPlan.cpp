// Time-synchronised multi-axis plans (see SyncPlan.h and docs/motion.md,
// "Synchronised plans").
#include "stdlib-motion/core/SyncPlan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <type_traits>

#include "stdlib-motion/core/TrajectoryFamily.h"

namespace stc::motion {

namespace {

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

// planVelocity's checks of the limits and the start state, without planning
// (a Profile per axis only to validate was a sixth of a phase-synchronised plan).
PlanStatus checkAxis(const SyncAxis& a) {
  const Limits& l = a.lim;
  auto pos = [](double x) { return std::isfinite(x) && x > 0; };
  if (!pos(l.vel) || !pos(l.acc) || !pos(l.dec) || std::isnan(l.jerk) || l.jerk < 0) return PlanStatus::InvalidLimits;
  if (!std::isfinite(a.start.p) || !std::isfinite(a.start.v) || !std::isfinite(a.start.a)) return PlanStatus::InvalidState;
  return PlanStatus::Ok;
}

inline bool closeTo(double a, double b) {   // (as TimedFamily: the same tolerance)
  return std::isfinite(b) && std::fabs(a - b) <= 1e-12 * std::max(1.0, std::fabs(b));
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
  // (the segments with duration > 0, the state snapped to (vp, 0) before the cruise)
  if (jm) {
    const double dur[7] = {d1[0], d1[1], d1[2], tc, d2[0], d2[1], d2[2]};
    const double val[7] = {j1[0], j1[1], j1[2], 0.0, j2[0], j2[1], j2[2]};
    out.pushSegments(dur, val, 7, false, 3, dir * vp);
  } else {
    const double dur[3] = {T1, tc, T2}, val[3] = {dir * acc, 0.0, -dir * dec};
    out.pushSegments(dur, val, 3, true, 1, dir * vp);
  }
  out.finish({ax.target, ax.vEnd, 0.0});
  return std::fabs(out.duration() - T) <= 1e-10 * std::max(1.0, T);
}

// TimedFamily objects built only for the axes that need one (each is ~1.6 KB and
// zeroes a Profile on construction; an array of kMaxSyncAxes built them all).
static_assert(std::is_trivially_destructible_v<detail::TimedFamily>);
class Families {
public:
  PlanStatus make(int i, const SyncAxis& a) {
    f_[i] = new (&slot_[i]) detail::TimedFamily;
    return f_[i]->init(a.start, a.target, a.vEnd, a.lim);
  }
  bool has(int i) const { return f_[i] != nullptr; }
  detail::TimedFamily& operator[](int i) { return *f_[i]; }

private:
  struct alignas(detail::TimedFamily) Slot {
    unsigned char b[sizeof(detail::TimedFamily)];
  };
  Slot slot_[kMaxSyncAxes];
  detail::TimedFamily* f_[kMaxSyncAxes] = {};
};

}  // namespace

SyncResult planSynchronized(const SyncAxis* axes, int n, Profile* out) {
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
      st = planPosition(a.start, a.target, a.vEnd, a.lim, out[i]);
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
      if (!optIn[i]) planPosition(axes[i].start, axes[i].target, axes[i].vEnd, axes[i].lim, out[i]);
      optIn[i] = true;
      return true;
    }
    optIn[i] = false;
    if (restTimed(axes[i], T, out[i])) return true;
    // (rounding beyond the tolerance: the general family decides, as before)
    if (!fams.has(i)) fams.make(i, axes[i]);
    return fams[i].plan(T, out[i]);
  };
  // every axis' plan of duration t (the cheap test first)
  auto allAt = [&](double t) {
    bool all = true;
    for (int i = 0; i < n && all; ++i) all = rest[i] || fams[i].feasible(t);
    for (int i = 0; i < n && all; ++i) all = planAxis(i, t);
    return all;
  };
  // The candidates are tLow and, after it, the starts of the families' feasible
  // intervals; the first at which every axis has a plan is T.  tLow is tried
  // first, before the others are collected: it is the answer in most sets (every
  // axis without a family accepts every T >= tLow; rest-to-rest sets have no
  // other candidate).
  double T = tLow;
  if (!allAt(tLow)) {
    constexpr int kCap = kMaxSyncAxes * (detail::TimedFamily::kMaxPoints + 2) + 1;
    double cand[kCap];
    int nc = 0;
    cand[nc++] = tLow;
    for (int i = 0; i < n && nFam > 0; ++i) {
      if (rest[i]) continue;
      double s[detail::TimedFamily::kMaxPoints + 2];
      const int k = fams[i].starts(s, detail::TimedFamily::kMaxPoints + 2);
      for (int j = 0; j < k; ++j)
        if (s[j] > tLow && nc < kCap) cand[nc++] = s[j];
    }
    if (nc > 1) std::sort(cand, cand + nc);
    bool all = false;
    for (int c = 1; c < nc && !all; ++c) {
      all = allAt(cand[c]);
      if (all) T = cand[c];
    }
    if (!all) {
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
          if (rest[i]) planPosition(axes[i].start, axes[i].target, axes[i].vEnd, axes[i].lim, out[i]);
          else out[i] = fams[i].optimal();
          T = std::max(T, tMin[i]);
        }
      }
    }
  }
  res.duration = T;
  return res;
}

SyncResult planPhaseSynchronized(const SyncAxis* axes, int n, Profile* out) {
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
  if (planPosition({0, 0, 0}, 1, 0, path, s) != PlanStatus::Ok) {
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
    double dur[Profile::kMaxSegments], val[Profile::kMaxSegments];
    const int ns = s.segmentCount();
    for (int k = 0; k < ns; ++k) {
      const Profile::Segment& g = s.segment(k);
      dur[k] = g.dur;   // (> 0: planPosition pushes no empty segment)
      val[k] = jerkMode ? g.j * d : g.a * d;
    }
    o.pushSegments(dur, val, ns, !jerkMode);
    if (d != 0) o.finish({a.target, 0, 0});
    else {
      o.finish(a.start);
    }
  }
  res.duration = s.duration();
  return res;
}

}  // namespace stc::motion
