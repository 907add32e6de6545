// Time-synchronised multi-axis plans (see SyncPlan.h and docs/motion.md,
// "Synchronised plans").
#include "stdlib-motion/core/SyncPlan.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

}  // namespace

SyncResult planSynchronized(const SyncAxis* axes, int n, Profile* out) {
  SyncResult res;
  if (n < 1 || n > kMaxSyncAxes) {
    res.status = SyncStatus::BadAxisCount;
    if (n > 0) holdAll(axes, std::min(n, kMaxSyncAxes), out);
    return res;
  }
  detail::TimedFamily fam[kMaxSyncAxes];
  double tLow = 0;
  for (int i = 0; i < n; ++i) {
    const PlanStatus st = fam[i].init(axes[i].start, axes[i].target, axes[i].vEnd, axes[i].lim);
    if (st != PlanStatus::Ok) {
      res.status = fromPlan(st);
      res.axis = i;
      holdAll(axes, n, out);
      return res;
    }
    tLow = std::max(tLow, fam[i].minimum());
  }
  // candidates: the latest minimum and every start of a feasible interval after it
  constexpr int kCap = kMaxSyncAxes * (detail::TimedFamily::kMaxPoints + 2) + 1;
  double cand[kCap];
  int nc = 0;
  cand[nc++] = tLow;
  for (int i = 0; i < n; ++i) {
    double s[detail::TimedFamily::kMaxPoints + 2];
    const int k = fam[i].starts(s, detail::TimedFamily::kMaxPoints + 2);
    for (int j = 0; j < k; ++j)
      if (s[j] > tLow && nc < kCap) cand[nc++] = s[j];
  }
  std::sort(cand, cand + nc);
  // the first candidate at which every axis has a plan (cheap test first)
  double T = cand[nc - 1];
  for (int c = 0; c < nc; ++c) {
    bool all = true;
    for (int i = 0; i < n && all; ++i) all = fam[i].feasible(cand[c]);
    for (int i = 0; i < n && all; ++i) all = fam[i].plan(cand[c], out[i]);
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
        for (int i = 0; i < n && all; ++i) all = fam[i].plan(t, out[i]);
      }
      T = t;
      if (!all) {   // (not seen in the tests) the optimal plans, not synchronised
        T = 0;
        for (int i = 0; i < n; ++i) {
          out[i] = fam[i].optimal();
          T = std::max(T, fam[i].minimum());
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
  // validate each axis as the one-axis planner does (a hold plan: cheap)
  Limits path{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
              std::numeric_limits<double>::infinity(), 0};
  double jerkBound = std::numeric_limits<double>::infinity();
  bool anyTrap = false, anyMove = false;
  for (int i = 0; i < n; ++i) {
    const SyncAxis& a = axes[i];
    Profile tmp;
    const PlanStatus st = planVelocity(a.start, 0, a.lim, tmp);
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

}  // namespace stc::motion
