// The simulated drive behind an axis: a CiA402 device (controlword /
// statusword state machine, object dictionary), a motor model that turns set
// points into actual values, the sensors on the mechanics (limit switches,
// home switch, index pulse) and injected faults.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace stc::motion {

enum class AxisKind : uint8_t {
  Servo,      // CiA402 bus drive: enabling takes the controlword handshake (3 cycles)
  Virtual,    // no hardware: actual = set, enabled at once
  Encoder,    // feedback only (e.g. a conveyor master): moves at encoderVelocity, takes no commands
  Pulse,      // stepper on pulse outputs: actual = set rounded to whole pulses, enabled at once
};

enum class DriveModel : uint8_t {
  Ideal,      // actual follows the set point exactly
  Lag,        // position loop (gain kv) + first-order velocity loop (lagTime): a following error
};

enum class FaultKind : uint8_t {
  DriveError,          // the drive faults (CiA402 Fault, error code 0x603F), axis -> ErrorStop (2)
  CommunicationLost,   // bCommunication FALSE, axis -> ErrorStop (1); MC_Reset refused until restored
  CommunicationRestored,
  LimitPositive,       // the positive limit switch closes (whatever the position)
  LimitNegative,
  LimitsReleased,      // forced limit switches open again
};

struct FaultEvent {
  int64_t atNs = 0;
  FaultKind kind = FaultKind::DriveError;
  uint16_t code = 0x5530;    // drive error code reported in 0x603F
};

struct DriveConfig {
  AxisKind kind = AxisKind::Virtual;
  DriveModel model = DriveModel::Ideal;
  double lagTime = 0.002;            // velocity-loop time constant [s] (Lag)
  double kv = 100;                   // position-loop gain [1/s] (Lag)
  double followingErrorLimit = 0;    // [u]; 0 = not checked (error 16)
  double incrementsPerUnit = 1;      // encoder increments (pulses) per technical unit
  double inertia = 0;                // torque = inertia * acceleration (reported torque)
  double encoderVelocity = 0;        // Encoder axes: constant velocity of the measured shaft [u/s]
  // Sensors at fixed actual positions [u] (unwrapped).
  bool hasLimitPositive = false, hasLimitNegative = false;
  double limitPositive = 0, limitNegative = 0;    // closed at/above, at/below
  bool hasHomeSwitch = false;
  double homeSwitchLow = 0, homeSwitchHigh = 0;   // closed while low <= pos <= high
  double indexPeriod = 0, indexOffset = 0;        // index pulse at offset + k * period; 0 = none
  std::vector<FaultEvent> faults;                 // sorted by time
};

// CiA402 power state machine states.
enum class Cia402 : uint8_t {
  SwitchOnDisabled, ReadyToSwitchOn, SwitchedOn, OperationEnabled, QuickStopActive, FaultReactionActive, Fault,
};

class DriveHoming;   // core/Homing.h: the CiA402 homing methods (mode 6)

class Drive {
public:
  explicit Drive(const DriveConfig& cfg);

  const DriveConfig& config() const { return cfg_; }
  // Scaling changes (SMC_ChangeGearingRatio); sensors and faults are fixed at construction.
  DriveConfig& mutableConfig() { return cfg_; }
  // ---- CiA402
  void setControlword(uint16_t cw) { controlword_ = cw; }
  // Devices without a bus (virtual, pulse, encoder) act on a controlword at once.
  void settle() { if (cfg_.kind != AxisKind::Servo) stepStateMachine(); }
  uint16_t controlword() const { return controlword_; }
  uint16_t statusword() const;
  Cia402 cia402() const { return state_; }
  bool operationEnabled() const { return state_ == Cia402::OperationEnabled; }
  bool faulted() const { return state_ == Cia402::Fault || state_ == Cia402::FaultReactionActive; }
  bool communication() const { return communication_; }
  uint16_t errorCode() const { return errorCode_; }

  // Object dictionary (index, subindex).  False: no such object / read-only.
  bool readObject(uint16_t index, uint8_t sub, int64_t& value) const;
  bool writeObject(uint16_t index, uint8_t sub, int64_t value);

  // ---- one cycle: faults due by nowNs, the state machine, the motor.
  // `setPos`/`setVel` are the set values the controller sends this cycle.
  void cycle(double setPos, double setVel, double setAcc, double dt, int64_t nowNs);

  // ---- actual values [u, u/s]
  double actPosition() const { return actPos_; }
  double actVelocity() const { return actVel_; }
  double actTorque() const { return actTorque_; }
  // A new coordinate system (MC_SetPosition, homing): the sensors stay where they are on the mechanics.
  void shift(double delta) { actPos_ += delta; prevPos_ += delta; lagSetPos_ += delta; shift_ += delta; }
  // Coordinates minus this = the mechanical position the sensor positions of DriveConfig refer to.
  double coordinateShift() const { return shift_; }
  void place(double pos) { actPos_ = prevPos_ = lagSetPos_ = pos; actVel_ = lagSetVel_ = 0; }
  // Cyclic modes (6060h): 8 CSP (position loop), 9 CSV (the motor follows the set velocity),
  // 10 CST (the motor follows the target torque 6071h: acceleration = torque / inertia;
  // without an inertia the load cannot be simulated and stands).
  int8_t modeOfOperation() const { return modesOfOperation_; }
  void setTargetTorque(double t) { targetTorque_ = t; }
  double targetTorque() const { return targetTorque_; }

  // ---- sensors (levels at the current actual position)
  bool limitPositiveActive() const;
  bool limitNegativeActive() const;
  bool homeSwitchActive() const;
  // CiA402 digital inputs (60FDh): bit 0 negative limit, bit 1 positive limit, bit 2 home switch.
  uint32_t digitalInputs() const {
    return (limitNegativeActive() ? 1u : 0u) | (limitPositiveActive() ? 2u : 0u) | (homeSwitchActive() ? 4u : 0u);
  }
  // An index pulse passed during the last cycle: its position.
  bool indexPassed(double& at) const;
  double prevPosition() const { return prevPos_; }

  // ---- homing mode (6060h = 6): the drive generates its own set point (core/Homing.cpp)
  bool homingMode() const { return modesOfOperation_ == 6 && cfg_.kind != AxisKind::Encoder; }
  // The drive's internal set point in homing mode [u, u/s, u/s^2].
  void homingSetPoint(double& p, double& v, double& a) const;

private:
  friend class DriveHoming;
  void applyFaults(int64_t nowNs);
  void stepStateMachine();
  void motor(double setPos, double setVel, double setAcc, double dt);
  size_t nextFault_ = 0;
  Cia402 state_ = Cia402::SwitchOnDisabled;
  uint16_t controlword_ = 0, prevControlword_ = 0;
  uint16_t errorCode_ = 0;
  bool communication_ = true;
  bool forcedLimitPos_ = false, forcedLimitNeg_ = false;
  double actPos_ = 0, actVel_ = 0, actTorque_ = 0, prevPos_ = 0, targetTorque_ = 0;
  double encCount_ = 0, encFrac_ = 0, encLastPos_ = 0;   // encoder axes: whole increments, carry
  double lagSetPos_ = 0, lagSetVel_ = 0;   // the set point of the previous cycle (Lag model)
  double shift_ = 0;                 // sum of the coordinate shifts
  int8_t modesOfOperation_ = 8;      // 0x6060: cyclic synchronous position
  DriveConfig cfg_;                  // after the state: the state fields share two cache lines
  struct Object { uint16_t index; uint8_t sub; bool writable; int64_t value; };
  std::vector<Object> od_;
  std::shared_ptr<DriveHoming> homing_;   // created on the first cycle in homing mode
};

}  // namespace stc::motion
