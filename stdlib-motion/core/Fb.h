// The core side of one motion FB instance: its kind, latched inputs and the
// PLCopen outputs (Busy, Active, Done, Error, ErrorID, CommandAborted, In*).
// The ST instance keeps a handle to its slot; the kernel writes the outputs
// back through `publish` whenever they change (also between calls, in the
// cycle where the axis reaches the target).  Output rules: docs/motion.md.
#pragma once

#include <cstdint>
#include <memory>

#include "stdlib-motion/core/Axis.h"
#include "stdlib-motion/core/Errors.h"

namespace stc::motion {

enum class FbKind : uint8_t {
  Power, Reset, MoveAbsolute, MoveRelative, MoveAdditive, MoveSuperImposed, MoveVelocity,
  MoveContinuousAbsolute, MoveContinuousRelative, Halt, Stop, Jog, Inch, SetPosition, Home,
  // Kinds whose semantics live in an FbBehaviour (see below), one per family.
  Profile, Follow, Torque, Probe, CamSwitch, Parameter, Config, Diagnostic, Leadshine, Other,
  // Couplings (Coupling.h): the slave follows a master.
  GearIn, GearInPos, CamIn, Phasing, Backlash,
  // Axis-group instructions (stdlib-motion/group).
  Group,
};

struct FbOutputs {
  bool busy = false;
  bool active = false;
  bool done = false;
  bool error = false;
  bool aborted = false;       // CommandAborted
  bool inState = false;       // InVelocity / InEndVelocity / InGear / InSync
  bool startSync = false;     // MC_GearInPos.StartSync
  bool endOfProfile = false;  // MC_CamIn.EndOfProfile (a one-cycle pulse in periodic mode)
  Error errorId = Error::None;
  // Group moves: CommandAccepted (follows Execute once accepted) and MovementId.
  bool commandAccepted = false;
  uint32_t movementId = 0;
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

class Kernel;
class FbSlot;

// What an FB does beyond the built-in commands (homing, profile tables,
// follow set values, probes, cam switches ...).  Modules outside Kernel.cpp
// attach one to their slot; the kernel calls it at fixed points of the cycle.
class FbBehaviour {
public:
  virtual ~FbBehaviour() = default;
  // The command becomes the one in control (directly or from the buffer):
  // start the axis movement (Axis::startPosition/Velocity/External ...) and set the axis state.
  virtual void start(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs) = 0;
  // Before the axis step, while the FB is in control of the axis.
  virtual void beforeStep(Kernel&, FbSlot&, Axis&, int64_t /*nowNs*/, uint64_t /*cycle*/) {}
  // The axis movement reached its end in this cycle (instead of the built-in Done).
  virtual void reached(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot);
  // After the axis step, for FBs registered in Axis::observers.
  virtual void afterStep(Kernel&, FbSlot&, Axis&, int64_t /*nowNs*/, uint64_t /*cycle*/) {}
};

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
  uint64_t endOfProfileCycle = 0;   // the cycle an EndOfProfile pulse was raised at a handover
  bool clearPending = false;
  // A command of a function-style face (Commands.h): the kernel owns it; it need not be
  // called in every cycle and its outputs are kept until the slot is reused.
  bool functionStyle = false;

  // Planned command (set when the command is accepted).
  double target = 0;                // unwrapped target of a position command
  double endVelocity = 0;           // planned end velocity (continuous moves, blending hand-over)
  int8_t levelDir = 0;              // MC_Jog / SMC_Inch: direction of the step or jog in progress
  int64_t sinceNs = 0;              // MC_Power: when the enable request began
  std::unique_ptr<FbBehaviour> behaviour;   // FBs the kernel does not implement itself

  void sync() { if (publish) publish(instance, out); }
};

// The behaviour of type T attached to fb, created on first use.
template <class T>
T& behaviourOf(FbSlot& fb) {
  if (auto* b = dynamic_cast<T*>(fb.behaviour.get())) return *b;
  fb.behaviour = std::make_unique<T>();
  return static_cast<T&>(*fb.behaviour);
}

}  // namespace stc::motion
