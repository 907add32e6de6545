// Semantics of Leadshine's single-axis blocks (PMC_SingleAxisLib,
// PMC_IpoLib, PMC_Controller) on the common kernel: moves with a start
// (jump) velocity and a creep velocity, on-the-fly target/velocity changes,
// the two-segment position-to-velocity move and handwheel following.
// Decisions where the manual is silent: docs/motion.md ("Leadshine blocks").
#pragma once

#include <memory>

#include "stdlib-motion/core/JumpTrapezoid.h"
#include "stdlib-motion/core/Kernel.h"

namespace stc::motion::leadshine {

using stc::motion::JumpTrapezoid;

struct StartVelInputs {
  double position = 0, distance = 0, velocity = 0, acceleration = 0, deceleration = 0;
  double startVel = 20, endSecondVel = 20;
  Direction direction = Direction::Shortest;
};

// LS_MoveAbs (kind MoveAbsolute), LS_MoveRel (MoveRelative), LS_MoveVel (MoveVelocity) on an Execute edge.
void callStartVelMove(Kernel& k, FbSlot& fb, Axis& ax, bool execute, FbKind kind, const StartVelInputs& in, const CallCtx& c);

// LS_MoveAbsChangePosVel (kind MoveAbsolute) and LS_MoveChangeVel (kind
// MoveVelocity, in.direction = +1 / -1): an Execute edge starts the move;
// while Execute stays TRUE and the command runs, changed inputs replan it
// from the current state at once.
void callChangeOnTheFly(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const MoveInputs& in, const CallCtx& c);

// LS_PositionToVelocity: segment 0 to endPos[0] at velocity[0], then segment
// 1 to endPos[1] at velocity[1] without stopping in between (when both go the
// same way).  Exec / Halt / Stop are edge inputs.
struct TwoSegmentInputs {
  bool exec = false, halt = false, stop = false;
  uint32_t ipoCycleUs = 2000;
  bool relative = false;
  int velocityMode = 1;   // 0 trapezoid, 1 sigmoid (jerk-limited), 3 quadratic (jerk-limited, jerk required)
  double endPos[2]{}, velocity[2]{}, acceleration[2]{}, deceleration[2]{}, jerk[2]{};
};
struct TwoSegmentOutputs { bool commandHalt = false; double vel = 0; };
void callPositionToVelocity(Kernel& k, FbSlot& fb, Axis& ax, const TwoSegmentInputs& in, TwoSegmentOutputs& out, const CallCtx& c);

// LS_Encoder_SetAxisMove: the axis follows the local encoder `channel`
// (an encoder axis with that encoderChannel): target = start position +
// (encoder increments since the start) * num / denom + additions, smoothed by
// a first-order filter of `filter` cycles.  Exec / Stop / additiveTrig are edges.
struct HandwheelInputs {
  bool exec = false, stop = false;
  int channel = 0, num = 1, denom = 1, filter = 2;
  bool additiveTrig = false;
  double additivePos = 0;
  uint32_t additiveCycles = 1;
};
struct HandwheelOutputs { bool done = false, error = false; int32_t errorId = 0; double deltaPulseUnit = 0; };
// PMC_BasicModule GVL_Err (manual appendix A-3), the ErrorID (DINT) of the PMC_IpoLib blocks.
// The manual prints IpoErrID_AxisNotStandStill with the code of IpoErrID_SpaceCircleParaErr;
// stc gives it the next free number, -17 (docs/leadshine-interpolation.md).
enum IpoErr : int32_t {
  kIpoParaErr = -2,            // IpoCycle, Jerk, limits 0 (or not the task cycle), inputs not finite
  kIpoCirDir = -4,             // ArcIpo_dir not 0 / 1
  kIpoCirMode = -5,            // Circle_Mode not supported
  kIpoDataType = -6,           // MoveSequence.DataType not 1 / 2
  kIpoVel = -7,
  kIpoAcc = -8,
  kIpoDec = -9,
  kIpoCirParaErr = -10,        // the parameters do not form a circle (ellipse)
  kIpoBufferOver = -11,        // more points than the table holds
  kIpoCirRadErr = -12,         // radius below 0.000001
  kIpoCirAngelOrg = -13,       // stop angle / centre wrong
  kIpoCirThreePoint = -14,     // three points do not form an arc
  kIpoConfigAxisErr = -15,     // an axis twice (or one that cannot be interpolated)
  kIpoSpaceCircleParaErr = -16,
  kIpoAxisNotStandStill = -17,
};
void callHandwheel(Kernel& k, FbSlot& fb, Axis& ax, const HandwheelInputs& in, HandwheelOutputs& out, const CallCtx& c);

}  // namespace stc::motion::leadshine
