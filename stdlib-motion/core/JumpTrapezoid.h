// A trapezoid with velocity jumps: the start (jump) velocity and creep
// velocity of stepper and pulse-train drives as a core limit option.  The
// velocity jumps to vStart, ramps to vMax, and for a position target ramps
// down to vCreep, reaches the target at vCreep and stops there.  Vendor-free:
// the Leadshine LS_Move* blocks (leadshine/LsMoves.*) are built on it.
#pragma once

#include <memory>

#include "stdlib-motion/core/Axis.h"

namespace stc::motion {

// The velocity jumps to vStart, ramps with `acc` to vMax (acc = 0: jumps), and
// for a position target ramps with `dec` down to vCreep, reaches the target
// at vCreep and stops there (a jump to 0).  On distances too short for the
// ramps the acceleration limits are kept and the peak (or the arrival)
// velocity adapts.  Positions relative to the start position p0.
class JumpTrapezoid : public Generator {
public:
  static std::shared_ptr<JumpTrapezoid> position(double p0, double distance, double vStart, double vMax, double vCreep,
                                                 double acc, double dec);
  // Velocity target: ramps from vStart to |v| in the direction of v, then runs on.
  static std::shared_ptr<JumpTrapezoid> velocity(double p0, double v, double vStart, double acc);
  Kinematic at(double t) const override;
  double duration() const override { return t1_ + t2_ + t3_; }
  double peakVelocity() const { return vp_; }

private:
  double p0_ = 0, sign_ = 1;
  double v0_ = 0, vp_ = 0, ve_ = 0;    // start, peak, arrival speed
  double a_ = 0, d_ = 0;               // ramp rates (0: the ramp is a jump)
  double t1_ = 0, t2_ = 0, t3_ = 0;    // ramp up, cruise, ramp down
  bool stops_ = true;                  // position target: velocity 0 at the end
};

}  // namespace stc::motion
