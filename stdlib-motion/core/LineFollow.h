// A leader axis positioning move with a follower axis that starts and stops
// with it, its position proportional to the leader's (Leadshine
// LS_LineFollowAbs / LS_LineFollowRel).  The leader runs an ordinary profile
// (Halt pauses it, Exec resumes, Stop aborts it); the follower is coupled to
// it (Axis::master): follower = f0 + (leader - l0) x ratio, so both stop
// together on the line whatever the leader does.  docs/motion-sync.md.
#pragma once

#include <cstdint>

#include "stdlib-motion/core/Kernel.h"

namespace stc::motion {

struct LineFollowInputs {
  bool exec = false, halt = false, stop = false;
  bool relative = false;
  uint32_t ipoCycleUs = 2000;       // must equal the task interval
  double endPos[2] = {0, 0};        // master, slave (targets, or distances when relative)
  int velocityMode = 1;             // SMC_INT_VELOCITY_MODE: 0 trapezoid, 1 sigmoid, 3 quadratic (jerk-limited)
  double velocity = 0, acceleration = 0, deceleration = 0, jerk = 0;   // of the master (of the slave when the master does not move)
};
struct LineFollowOutputs {
  bool commandHalt = false;
  double vel = 0;                   // the leader's set velocity
};

// `fb` is the FB's slot (it commands the leader), `follow` its second slot (the follower).
void callLineFollow(Kernel& k, FbSlot& fb, FbSlot& follow, Axis& master, Axis& slave, const LineFollowInputs& in,
                    LineFollowOutputs& out, const CallCtx& c);

}  // namespace stc::motion
