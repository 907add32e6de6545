// A simulated axis: PLCopen state machine, set-point generation from the
// active movement, the drive (ideal, velocity-loop lag, stepper, encoder
// only) with a CiA402 state machine and object dictionary, limit switches,
// home switch, index pulse and injected faults.  See docs/motion.md.
//
// Positions inside the core are unwrapped; a modulo axis reports them in
// [0, period).  All times are simulated: nanoseconds of the controller clock.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "stdlib-motion/core/Drive.h"
#include "stdlib-motion/core/Errors.h"
#include "stdlib-motion/core/Trajectory.h"

namespace stc::motion {

// SMC_AXIS_STATE values.
enum class AxisState : uint8_t {
  PowerOff = 0, ErrorStop = 1, Stopping = 2, Standstill = 3,
  DiscreteMotion = 4, ContinuousMotion = 5, SynchronizedMotion = 6, Homing = 7,
};

// MC_DIRECTION values; Invalid stands for any other number a program passed.
enum class Direction : int8_t { Negative = -1, Shortest = 0, Positive = 1, Current = 2, Fastest = 3, Invalid = 127 };

// MC_BUFFER_MODE values; Invalid stands for any other number (SMC_INVALID_BUFFER_MODE).
enum class BufferMode : uint8_t { Aborting = 0, Buffered = 1, BlendingLow = 2, BlendingPrevious = 3, BlendingNext = 4, BlendingHigh = 5, Invalid = 255 };

// From the ST enum values (16- or 32-bit) to the core's: a plain cast to the
// 8-bit enums would wrap 257 to 1, so everything out of range becomes Invalid.
constexpr Direction directionOf(int64_t v) { return v >= -1 && v <= 3 ? static_cast<Direction>(v) : Direction::Invalid; }
constexpr BufferMode bufferModeOf(int64_t v) { return v >= 0 && v <= 5 ? static_cast<BufferMode>(v) : BufferMode::Invalid; }
// The same for the other 8-bit enums numbered 0..last: out of range becomes 255,
// which every validation refuses.
template <class E>
constexpr E enumOf(int64_t v, int64_t last) { return v >= 0 && v <= last ? static_cast<E>(v) : static_cast<E>(255); }
constexpr bool validBufferMode(BufferMode m) { return static_cast<int>(m) <= 5; }

// SMC_RAMPTYPE values: trapez ignores Jerk; the quadratic ramps use it.
enum class RampType : uint8_t { Trapez = 0, SinSquare = 1, Quadratic = 2, QuadraticSmooth = 3 };

// The fields read in every cycle come first (they share two cache lines).
struct AxisConfig {
  double period = 0;             // modulo period [u]; 0 = linear axis
  // Dynamic limits (fMaxVelocity ...): set values beyond them are errors 40-42.  0 = not checked.
  double maxVelocity = 0, maxAcceleration = 0, maxDeceleration = 0, maxJerk = 0;
  // Software limits (errors 10).
  bool swLimitEnable = false;
  double swLimitPositive = 0, swLimitNegative = 0;
  double errorDeceleration = 0;  // stop ramp in ErrorStop; 0 = maxDeceleration, else 1e3 u/s^2 if that is 0 too
  RampType ramp = RampType::Trapez;
  // Reaction to a software limit (error 10; SMC_SetSoftwareLimits, parameters 1203/1250):
  // brake with swLimitDeceleration (0 = the error deceleration), at least hard enough to
  // stand within swErrorMaxDistance (0 = no bound); swLimitDecelerate FALSE: stop at once.
  bool swLimitDecelerate = true;
  double swLimitDeceleration = 0, swErrorMaxDistance = 0;
  DriveConfig drive;             // kind, model, scaling, switches, faults
  int encoderChannel = -1;       // Encoder axes: the controller's local encoder input 0..2 (LS_Encoder_SetAxisMove)
  std::string name;              // the AXIS_REF global it is bound to ("" = bound from ST)
  std::string task;              // owning task; "" = the task of the first FB call on it
};

class FbSlot;
class HomingCoast;   // Axis.cpp: the drive's homing set point as a movement

// The last error an FB reported on an axis (SMC_ReadFBError; SMC_ClearFBError clears it).
struct FbErrorRecord {
  bool set = false;
  Error id = Error::None;
  const void* instance = nullptr;   // the ST instance of the FB
  int64_t atNs = 0;                 // controller time of the error
};

// What one step of an axis found.
struct StepResult {
  bool reached = false;              // the base movement reached the end of its profile
  double overshoot = 0;              // seconds between that end and this cycle's time
  bool superimposedReached = false;  // the superimposed move finished
  Error error = Error::None;         // a supervision error (limits, drive, communication)
};

// A set-point source other than a planned profile (PVT tables, follow
// set values, homing phases...): the base state at t seconds after its start.
// After duration() the axis continues at the end velocity, like a profile.
class Generator {
public:
  virtual ~Generator() = default;
  virtual Kinematic at(double t) const = 0;
  virtual double duration() const = 0;   // +infinity: never ends by itself
};

// The movement that currently generates the set point.
struct Movement {
  enum class Kind : uint8_t { None, Position, Velocity, Stop, External };
  Kind kind = Kind::None;
  std::shared_ptr<const Generator> gen;  // Kind::External
  int64_t originNs = 0;          // the profile's t = 0 ...
  double originFrac = 0;         // ... plus this many seconds (blended hand-overs start between cycles)
  bool reached = false;          // the end of the profile has been reached
  // Override: from rateNs on, profile time runs at `rate` times the clock (time scaling:
  // velocities x rate, accelerations x rate^2, the path unchanged).
  double rate = 1;
  int64_t rateNs = 0;            // when `rate` took effect ...
  double rateTau = 0;            // ... and the profile time then (rate == 1 from the origin: unused)
  Profile profile;               // last: the fields above share a cache line
  double t(int64_t nowNs) const {
    if (rate == 1 && rateNs == 0) return static_cast<double>(nowNs - originNs) * 1e-9 + originFrac;
    return rateTau + rate * static_cast<double>(nowNs - rateNs) * 1e-9;
  }
  double duration() const { return gen ? gen->duration() : profile.duration(); }
  // The state at t; past the end, the end state continued at its velocity.
  Kinematic at(double t) const;
  Kinematic end() const { return gen ? gen->at(gen->duration()) : profile.end(); }
};

class Axis {
public:
  explicit Axis(AxisConfig cfg, uint32_t index);

  const AxisConfig& config() const { return cfg_; }
  // For the configuration FBs (limits, ramp type, gearing ...): changes apply from the next command.
  AxisConfig& mutableConfig() { return cfg_; }
  uint32_t index() const { return index_; }
  AxisState state() const { return state_; }
  Error error() const { return error_; }
  bool isModulo() const { return cfg_.period > 0; }

  // ---- set point and feedback (unwrapped, technical units)
  const Kinematic& set() const { return set_; }
  double actPosition() const { return drive_.actPosition(); }
  double actVelocity() const { return drive_.actVelocity(); }
  double actTorque() const { return drive_.actTorque(); }
  // Reported values: modulo axes in [0, period).
  double reportPosition(double unwrapped) const;
  Drive& drive() { return drive_; }
  const Drive& drive() const { return drive_; }

  // ---- power (MC_Power): the controlword follows the request (CiA402 handshake)
  bool powerRequested() const { return wantPower_; }
  bool driveStart() const { return driveStart_; }
  bool operational() const { return drive_.operationEnabled(); }
  bool ready() const { return operational() && driveStart_ && state_ != AxisState::ErrorStop; }
  void requestPower(bool regulatorOn, bool driveStart, int64_t nowNs);
  // Mode-specific controlword bits 4-6, 8 (homing: bit 4 starts the method); sent at once.
  void setControlwordBits(uint16_t bits) { cwBits_ = bits & 0x0170; updateControlword(); }

  // ---- errors
  // ErrorStop: the set point ramps down with the error deceleration (or
  // stands still when the power stage is off).
  void enterErrorStop(Error e, int64_t nowNs);
  // MC_Reset: clears the error and pulses the drive's fault reset.
  void clearError();
  void setState(AxisState s) { state_ = s; }
  // An encoder axis has no set point of its own: its set state is its measurement.
  void trackActual() { set_ = Kinematic{actPosition(), actVelocity(), 0}; }
  bool atRest() const { return set_.v == 0 && set_.a == 0 && mv_.kind == Movement::Kind::None; }

  // ---- movements (positions unwrapped), started at nowNs (+frac seconds)
  void startPosition(double target, double vEnd, const Limits& lim, int64_t nowNs, double frac = 0);
  void startVelocity(double v, const Limits& lim, int64_t nowNs, double frac = 0);
  void startStop(const Limits& lim, int64_t nowNs);
  void startSuperimposed(double distance, const Limits& lim, int64_t nowNs);
  // A base movement from a generator whose at(0) continues the current set state.
  void startExternal(std::shared_ptr<const Generator> gen, int64_t nowNs);
  void holdAt(double pos);                       // ends every movement, set point at rest at pos
  const Movement& movement() const { return mv_; }
  bool superimposedActive() const { return sup_.kind != Movement::Kind::None; }
  // Velocity override of the base movement (0 <= factor, 1 = none): from nowNs the
  // movement in progress, and every later one, runs at factor x its planned speed along
  // the same path (factor 0 holds the axis on its path).  A superimposed move is not scaled.
  void setOverride(double factor, int64_t nowNs);
  double override() const { return override_; }
  // MC_SetPosition: shifts set and actual position by `delta` (no motion).
  void shiftPosition(double delta);

  // Limits of a command: jerk only with the quadratic ramp types; sin² ramps are planned
  // jerk-limited with jerk = max(acc, dec)^2 / vel (docs/motion-config.md).
  Limits limitsFor(double vel, double acc, double dec, double jerk) const;
  // A command's Jerk input is valid for this axis: finite, within the bounds, and > 0 where the
  // ramp type plans with it (quadratic ramps; trapez and sin² ignore it, so 0 is allowed there).
  bool acceptsJerk(double jerk) const;
  // The unwrapped target of an absolute move (modulo direction rules).  False: invalid direction.
  bool absoluteTarget(double position, Direction dir, double& target) const;


  // ---- the cycle: advances the set point to nowNs, runs the drive, supervises.
  StepResult step(int64_t nowNs, double dt);
  // Evaluates the movements at nowNs into set() without side effects on the
  // drive (a command accepted in a call starts from the state at its cycle's time).
  void sample(int64_t nowNs);

  // Profile ends within this many seconds of a cycle's time count as reached
  // in that cycle (cycle times are whole nanoseconds).
  static constexpr double kEndTolerance = 1e-10;

private:
  Kinematic baseState() const;
  Kinematic beginBase(Movement::Kind kind, int64_t nowNs, double frac);
  void updateControlword();

  // ---- data, ordered for the cache: what every FB call and every step reads comes
  // first (the first lines of the object); profiles and rarely used state last.
public:
  // ---- FBs in control
  FbSlot* controller = nullptr;          // the FB whose command generates the set point
  // Coupling master (cam, gear ...): the kernel steps this axis after its master in every
  // cycle of their task, so the coupling reads the master's set state of the same cycle.
  Axis* master = nullptr;
  FbSlot* power = nullptr;               // the MC_Power instance that last operated the axis
  FbSlot* superimposer = nullptr;        // MC_MoveSuperImposed in progress
  FbSlot* blockingStop = nullptr;        // MC_Stop holding the axis in Stopping
  FbSlot* resetter = nullptr;            // MC_Reset waiting for the drive / standstill
  // Owning task (UINT32_MAX = not yet owned).
  uint32_t task = UINT32_MAX;
private:
  uint32_t index_;
  AxisState state_ = AxisState::PowerOff;
  Error error_ = Error::None;
  bool wantPower_ = false, driveStart_ = false, resetPulse_ = false;
  uint16_t cwBits_ = 0;
  Kinematic set_;                        // total set state
  double offset_ = 0;                    // MC_SetPosition shifts and finished superimposed moves
  double override_ = 1;                  // setOverride
public:
  std::vector<FbSlot*> pendingClear;     // terminal outputs to clear after one cycle
  std::vector<FbSlot*> observers;        // FBs with a behaviour that watch every step (probes, cam switches ...)
  std::vector<FbSlot*> queue;            // buffered commands, oldest first
private:
  Kinematic heldBase_, baseNow_;         // base movement state (without offset and superimposed part)
  Movement mv_;
  AxisConfig cfg_;
  Drive drive_;
public:
  double lastCommandedTarget = 0;        // for MC_MoveAdditive (unwrapped)
  FbErrorRecord fbError;                 // the latest FB error (Kernel::fail / finish with an error)
  // MC_Phasing: the master position this axis's coupling sees is shifted by
  // `done` plus the profile in progress (positive = this slave lags).
  struct PhaseShift {
    double done = 0;
    int64_t originNs = 0;
    bool moving = false;
    Profile profile;
    Kinematic at(int64_t nowNs) const {
      if (!moving) return Kinematic{done, 0, 0};
      Kinematic k = profile.at(static_cast<double>(nowNs - originNs) * 1e-9);
      k.p += done;
      return k;
    }
  } phase;
private:
  Movement sup_;
  std::shared_ptr<HomingCoast> homingCoast_;   // the drive's homing set point as a movement (Axis.cpp)
  Kinematic supState_;                   // contribution of the superimposed move in progress
  Limits lastLimits_{1, 1, 1, 0};
};

}  // namespace stc::motion
