// The core side of one motion FB instance: its kind, latched inputs and the
// PLCopen outputs (Busy, Active, Done, Error, ErrorID, CommandAborted, In*).
// The ST instance keeps a handle to its slot; the kernel writes the outputs
// back through `publish` whenever they change (also between calls, in the
// cycle where the axis reaches the target).  Output rules: docs/motion.md.
#pragma once

#include <cstdint>

#include "stdlib-motion/core/Axis.h"
#include "stdlib-motion/core/Errors.h"

namespace stc::motion {

enum class FbKind : uint8_t {
  Power, Reset, MoveAbsolute, MoveRelative, MoveAdditive, MoveSuperImposed, MoveVelocity,
  MoveContinuousAbsolute, MoveContinuousRelative, Halt, Stop, Jog, Inch, SetPosition, Home, Other,
};

struct FbOutputs {
  bool busy = false;
  bool active = false;
  bool done = false;
  bool error = false;
  bool aborted = false;       // CommandAborted
  bool inState = false;       // InVelocity / InEndVelocity
  Error errorId = Error::None;
  // MC_Power only.
  bool status = false, regulatorRealState = false, driveStartRealState = false;
  bool terminal() const { return done || error || aborted; }
};

// The inputs of a move, latched at the rising edge.
struct MoveInputs {
  double position = 0;        // MoveAbsolute / ContinuousAbsolute
  double distance = 0;        // MoveRelative / Additive / SuperImposed / ContinuousRelative / Inch
  double velocity = 0;
  double acceleration = 0;
  double deceleration = 0;
  double jerk = 0;
  double endVelocity = 0;     // Continuous moves
  Direction direction = Direction::Positive;
  Direction endDirection = Direction::Current;
  BufferMode bufferMode = BufferMode::Aborting;
};

using PublishFn = void (*)(void* instance, const FbOutputs& out);

class FbSlot {
public:
  FbKind kind = FbKind::Other;
  void* instance = nullptr;         // the ST instance (outputs are written there)
  PublishFn publish = nullptr;
  Axis* axis = nullptr;             // the axis of the current/last command
  FbOutputs out;
  MoveInputs in;

  bool execute = false;             // Execute (or Enable) at the latest call
  uint64_t lastCallCycle = 0;       // task cycle of the latest call
  uint64_t callSeq = 0;             // global call order (detects successor-before-predecessor)
  uint64_t terminalCycle = 0;       // cycle in which Done/Error/CommandAborted rose with Execute low
  bool clearPending = false;

  // Planned command (set when the command is accepted).
  double target = 0;                // unwrapped target of a position command
  double endVelocity = 0;           // planned end velocity (continuous moves, blending hand-over)
  int8_t levelDir = 0;              // MC_Jog / SMC_Inch: direction of the step or jog in progress
  int64_t sinceNs = 0;              // MC_Power: when the enable request began

  void sync() { if (publish) publish(instance, out); }
};

}  // namespace stc::motion
