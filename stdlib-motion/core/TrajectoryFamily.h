// Internal to the motion core (Trajectory.cpp, SyncPlan.cpp): the plans of one
// axis that take a prescribed time, used to synchronise several axes.
//
// The family: the time-optimal plan (duration minimum()), and every plan of the
// peak-velocity shape [transition (v0, a0) -> (vp, 0)] + [cruise at vp for tc >= 0]
// + [transition (vp, 0) -> (vEnd, 0)] with any |vp| <= vel (vp = 0 only when the
// two transitions alone cover the distance: stop, wait, go on).  Its duration as a
// function of vp, G(vp) = T1 + T2 + (delta - D(vp)) / vp, is continuous between the
// breakpoints of vp and the roots of D(vp) = delta, and grows without bound as the
// cruise velocity goes to 0: the feasible durations are a union of intervals, the
// last one unbounded; between two of them the axis cannot arrive ("blocked").
#pragma once

#include "stdlib-motion/core/Trajectory.h"

namespace stc::motion::detail {

// The limits as the planner uses them (Trajectory.cpp: makeCtx).
struct Ctx {
  double J;       // jerk (jerk mode only)
  double acc, dec, vel;
  bool jerkMode;
  // reciprocals (jerk mode): 1/J and 1/acc, 1/dec, 1/min(acc, dec)
  double iJ, iAcc, iDec, amin, iAmin;
};

// A plan's segments as Profile::pushSegments takes them, and its exact end.
struct PlanSegs {
  double dur[8], val[8];
  int n = 0, snapAt = -1;
  double snapV = 0;
  bool acc = false;
  Kinematic end;
  void build(const Kinematic& start, Profile& out) const {
    out.clear(start);
    out.pushSegments(dur, val, n, acc, snapAt, snapV);
    out.finish(end);
  }
};

class TimedFamily {
public:
  // Plans the time-optimal motion and prepares the family.  Same checks and
  // statuses as planPosition.
  PlanStatus init(const Kinematic& start, double target, double vEnd, const Limits& lim);
  double minimum() const { return tMin_; }
  const Profile& optimal() const;
  // Durations where a feasible interval may begin (includes minimum()).
  int starts(double* out, int cap) const;
  // Can the axis arrive (target, vEnd, a = 0) after exactly T seconds?
  bool feasible(double T) const;
  // A plan of duration T (T feasible); false (out unspecified) otherwise.
  bool plan(double T, Profile& out) const;

  static constexpr int kMaxPoints = 16;


private:
  // the problem
  Ctx c_;
  Kinematic start_;
  double target_ = 0, vEnd_ = 0, delta_ = 0, v0_ = 0, a0_ = 0;
  // the time-optimal plan: its duration, its segments, and the Profile, built
  // only when asked for (most families of a synchronised plan end at a later T)
  double tMin_ = 0;
  PlanSegs optSegs_;
  mutable bool optBuilt_ = false;
  mutable Profile opt_;
  int n_ = 0;
  double x_[kMaxPoints];   // vp points, sorted (0 twice: 0- then 0+)
  int zs_[kMaxPoints];
  double f_[kMaxPoints], tt_[kMaxPoints], g_[kMaxPoints];
  bool inS_[kMaxPoints];   // the piece [x_k, x_k+1] admits a cruise (tc >= 0)
  bool wait_ = false;      // D(0) = delta: stop, wait any time, go on
  int waitSide_ = 0;
  double waitT_ = 0;
};

}  // namespace stc::motion::detail
