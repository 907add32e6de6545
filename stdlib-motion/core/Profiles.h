// Profile tables (MC_PositionProfile / MC_VelocityProfile / MC_AccelerationProfile),
// direct set points (SMC_FollowPosition / PositionVelocity / SetValues / Velocity),
// torque (SMC_SetTorque) and the controller mode (SMC_SetControllerMode).
// Semantics, timing and decisions: docs/motion-profiles.md.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "stdlib-motion/core/Kernel.h"

namespace stc::motion {

// ---------------------------------------------------------------- generators

// One table point: the time since the previous point [s] and its value
// (position, velocity or acceleration), already scaled and offset.
struct TablePoint {
  double dt = 0;
  double value = 0;
};

enum class TableKind : uint8_t { Position, Velocity, Acceleration };

// A time table as a set-point generator starting at t = 0 from `start`:
// - Position: a C2 cubic spline through the points (clamped: velocity = start.v at
//   t = 0 and 0 at the last point); exact at every point.
// - Velocity: v = start.v + V(t), V going from 0 through the points, each segment an
//   S-curve (3s^2 - 2s^3, acceleration 0 at the points); the position gains
//   (V(i-1) + V(i)) / 2 * dt per segment.
// - Acceleration: a from 0 through the points, each segment an S-curve, so the velocity
//   gains (A + B) / 2 * dt per segment (the manual's rule); v starts at start.v.
// Values are absolute (the point's position / velocity / acceleration) or relative
// (increments over the previous point).  After the last point the axis continues at
// the end velocity (Movement::at).
class TableGenerator : public Generator {
public:
  TableGenerator(TableKind kind, const std::vector<TablePoint>& pts, bool absolute, const Kinematic& start, double positionBase);
  Kinematic at(double t) const override;
  double duration() const override { return t_.back(); }
  // The state at point i (0 = start).
  Kinematic knot(size_t i) const { return Kinematic{p_[i], v_[i], a_[i]}; }

private:
  TableKind kind_;
  std::vector<double> t_, p_, v_, a_, val_;   // knot times and states; val_: the table value per knot
};

// A set point written from outside every cycle (follow FBs, couplings): the
// state written at tSet; later times continue at its velocity (an abandoned
// follow keeps moving, like a slave after MC_CamOut).
class DirectGenerator : public Generator {
public:
  Kinematic state;
  double tSet = 0;
  Kinematic at(double t) const override;
  double duration() const override;
  // A generator holding the axis's present set state, made the axis's movement from nowNs.
  static std::shared_ptr<DirectGenerator> startOn(Axis& ax, int64_t nowNs);
};

// ---------------------------------------------------------------- instructions

// MC_*Profile.  `points` are the first ArraySize raw table entries
// (delta_time in ns, value), read only on the rising edge.
struct RawPoint {
  int64_t dtNs = 0;
  double value = 0;
};
void callProfile(Kernel& k, FbSlot& fb, Axis& ax, bool execute, TableKind kind, int arraySize, const std::vector<RawPoint>& points,
                 bool absolute, double scale, double offset, const CallCtx& c);

// SMC_Follow*: the set values of this call (dwValueMask bits: 0 position, 1 velocity,
// 2 acceleration, 3 jerk, 4 torque, 5 current).
struct FollowInputs {
  uint32_t mask = 0;
  double position = 0, velocity = 0, acceleration = 0, jerk = 0, torque = 0, current = 0;
};
enum : uint32_t { kFollowPosition = 1, kFollowVelocity = 2, kFollowAcceleration = 4, kFollowJerk = 8, kFollowTorque = 16, kFollowCurrent = 32 };
void callFollow(Kernel& k, FbSlot& fb, Axis& ax, bool execute, bool abort, const FollowInputs& in, const CallCtx& c);

// SMC_CONTROLLER_MODE values and the CiA402 modes of operation (6060h) they select.
enum class ControllerMode : int16_t { NoControl = 0, Torque = 1, Velocity = 2, Position = 3, Current = 4 };
constexpr int8_t kModeCsp = 8, kModeCsv = 9, kModeCst = 10;
ControllerMode controllerMode(const Axis& ax);

void callSetControllerMode(Kernel& k, FbSlot& fb, Axis& ax, bool execute, int16_t mode, const CallCtx& c);
// SMC_SetTorque (Enable-type).
void callSetTorque(Kernel& k, FbSlot& fb, Axis& ax, bool enable, double torque, const CallCtx& c);

}  // namespace stc::motion
