// Time-synchronised plans of several axes (up to kMaxSyncAxes): every axis
// leaves its own start state (p, v, a) and arrives at its own target position
// and end velocity (a = 0) at one common time T, under its own Limits.
//
// planSynchronized: T is the earliest time at which every axis can arrive.
// An axis cannot always arrive at every time after its own minimum: from a
// moving start it may reach the target directly up to some time, and later
// only by overshooting and coming back (its feasible times are intervals with
// gaps).  T is the smallest time not in any axis' gap.  Each axis' profile is a
// valid Profile of the one-axis model (docs/motion.md, "Trajectories"): its
// time-optimal plan when T is its minimum, otherwise a plan of the peak-velocity
// shape with a cruise at a lower speed (or a stop and wait).
//
// planPhaseSynchronized: rest-to-rest straight-line motion (PTP): all axes move
// proportionally along one normalised path s(t) in [0, 1] planned with the
// tightest of the scaled limits, so the set point moves on the straight line
// between start and target (start velocities and accelerations must be 0 and
// end velocities are 0).
#pragma once

#include <cstdint>

#include "stdlib-motion/core/Trajectory.h"

namespace stc::motion {

constexpr int kMaxSyncAxes = 16;

struct SyncAxis {
  Kinematic start;
  double target = 0;
  double vEnd = 0;
  Limits lim;
};

enum class SyncStatus : uint8_t {
  Ok,
  InvalidLimits,   // an axis' limits (see PlanStatus::InvalidLimits)
  InvalidTarget,   // an axis' target or end velocity
  InvalidState,    // an axis' start state
  BadAxisCount,    // n < 1 or n > kMaxSyncAxes
  NotAtRest,       // planPhaseSynchronized: a start with v or a != 0, or vEnd != 0
};

struct SyncResult {
  SyncStatus status = SyncStatus::Ok;
  int axis = -1;          // the first axis with invalid input, else -1
  double duration = 0;    // the common duration T
};

// On Ok, out[i] holds axis i's profile, each of duration T (to rounding) and
// ending exactly at (target, vEnd, 0).  On an error every out[i] holds its start.
SyncResult planSynchronized(const SyncAxis* axes, int n, Profile* out);
SyncResult planPhaseSynchronized(const SyncAxis* axes, int n, Profile* out);

}  // namespace stc::motion
