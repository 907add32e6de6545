// One-axis trajectory generation: time-optimal trapezoidal and jerk-limited
// (7-segment, "double S") profiles from any current state.
//
// Everything in the motion core that moves a set point goes through here:
// MoveAbsolute/Relative plan to a position, MoveVelocity/Jog/Halt/Stop plan
// to a velocity, and a change of target, limits or override mid-motion is a
// new plan from the state sampled out of the old one.  Units are the axis'
// technical units (u, u/s, u/s^2, u/s^3) and seconds.
//
// The kinematic model (docs/motion.md, "Trajectories"):
//  - |v| <= vel at all times, except that a plan starting above vel first
//    brings |v| down to vel (it never speeds up beyond it).
//  - |a| <= acc while the speed |v| grows (v*a > 0), |a| <= dec while it
//    falls (v*a < 0).
//  - |j| <= jerk.  jerk == 0 (or +inf) means unlimited: the trapezoidal
//    profile, whose acceleration may jump (the start acceleration is then
//    irrelevant).
//  - A position plan ends exactly at (target, vEnd, a = 0); a velocity plan
//    ends at (vTarget, a = 0).  After the end, the profile continues at the
//    end velocity (constant), so a position plan with vEnd != 0 keeps moving.
//  - Within that model the plan is time-optimal.
#pragma once

#include <cstdint>

namespace stc::motion {

struct Kinematic {
  double p = 0;   // position
  double v = 0;   // velocity
  double a = 0;   // acceleration
};

struct Limits {
  double vel = 0;    // > 0
  double acc = 0;    // > 0, bound while |v| grows
  double dec = 0;    // > 0, bound while |v| falls
  double jerk = 0;   // >= 0; 0 = unlimited (trapezoidal profile)
};

enum class PlanStatus : uint8_t {
  Ok,
  InvalidLimits,     // vel/acc/dec not > 0, jerk < 0, or any of them NaN/inf (jerk may be +inf)
  InvalidTarget,     // target/vEnd/vTarget NaN or infinite, |vEnd| > vel, |vTarget| > vel
  InvalidState,      // the start state is NaN or infinite
};

// A piecewise constant-jerk motion: at most kMaxSegments segments, each
// starting at a known state.  Sampling is cheap (no allocation, no search
// beyond a few segments); the end state is stored exactly.
class Profile {
public:
  static constexpr int kMaxSegments = 16;

  struct Segment {
    double t0;       // start time, seconds since the profile's start
    double p, v, a;  // state at t0
    double j;        // constant jerk during the segment
    double dur;      // duration (the next segment starts at t0 + dur up to rounding)
  };

  // Seconds from the start state to the end state (0 if already there).
  double duration() const { return duration_; }
  // The state at time t (seconds since the start).  t <= 0: the start state;
  // t >= duration(): the end state exactly, then extrapolated at the end
  // velocity (p = end.p + end.v * (t - duration)).
  Kinematic at(double t) const;
  const Kinematic& start() const { return start_; }
  const Kinematic& end() const { return end_; }
  int segmentCount() const { return count_; }
  const Segment& segment(int i) const { return segs_[i]; }

  // Used by the planner.
  void clear(const Kinematic& start);
  void push(double duration, double jerk);   // appends a segment of that duration and jerk (duration > 0)
  void finish(const Kinematic& exactEnd);    // stores the exact end state
  // Appends a segment of that duration (> 0) with constant acceleration `acc`
  // and jerk 0; the acceleration may jump at its start (trapezoidal profiles).
  void pushAcc(double duration, double acc);
  // Replaces the integrated velocity and acceleration at the current end by the
  // exactly known values (removes rounding drift before a long cruise).
  void snap(double v, double a) { cur_.v = v; cur_.a = a; }
  // The same as, for i < n, push(dur[i], val[i]) (acc: pushAcc) where dur[i] > 0,
  // with snap(snapV, 0) before segment snapAt (n: after the last; -1: none), in
  // one pass: the integrated state stays in registers (push after push reloads it
  // from memory right after storing it, a store-forwarding stall per segment).
  void pushSegments(const double* dur, const double* val, int n, bool acc, int snapAt = -1, double snapV = 0);

private:
  Segment segs_[kMaxSegments] = {};
  int count_ = 0;
  double duration_ = 0;
  Kinematic start_, end_;
  Kinematic cur_;   // state at duration_ while planning (integrated)
};

// Time-optimal motion from `start` to position `target`, arriving with
// velocity vEnd (|vEnd| <= lim.vel) and acceleration 0.  Moves that must
// overshoot and come back (e.g. too little distance to stop) are planned
// as such.
PlanStatus planPosition(const Kinematic& start, double target, double vEnd, const Limits& lim, Profile& out);

// Time-optimal change from `start` to velocity vTarget (|vTarget| <= lim.vel)
// with acceleration 0; position is free.  vTarget = 0 is a stop.
PlanStatus planVelocity(const Kinematic& start, double vTarget, const Limits& lim, Profile& out);

}  // namespace stc::motion
