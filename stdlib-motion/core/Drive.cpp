#include "stdlib-motion/core/Drive.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/core/Homing.h"

namespace stc::motion {

namespace {
// Controlword commands (CiA402 table "device control commands").
bool isDisableVoltage(uint16_t cw) { return (cw & 0x02) == 0; }
bool isQuickStop(uint16_t cw) { return (cw & 0x06) == 0x02; }
bool isShutdown(uint16_t cw) { return (cw & 0x87) == 0x06; }
bool isSwitchOn(uint16_t cw) { return (cw & 0x8F) == 0x07; }
bool isEnableOperation(uint16_t cw) { return (cw & 0x8F) == 0x0F; }
}  // namespace

Drive::Drive(const DriveConfig& cfg) : cfg_(cfg) {
  std::sort(cfg_.faults.begin(), cfg_.faults.end(), [](const FaultEvent& a, const FaultEvent& b) { return a.atNs < b.atNs; });
  // The objects the simulation serves (values in drive units: increments, 0.1 % torque).
  od_ = {
      {0x603F, 0, false, 0},        // error code
      {0x6040, 0, true, 0},         // controlword
      {0x6041, 0, false, 0},        // statusword
      {0x6060, 0, true, 8},         // modes of operation (8 = CSP)
      {0x6061, 0, false, 8},        // modes of operation display
      {0x6064, 0, false, 0},        // position actual value
      {0x6065, 0, true, 0},         // following error window
      {0x606C, 0, false, 0},        // velocity actual value
      {0x6071, 0, true, 0},         // target torque
      {0x6077, 0, false, 0},        // torque actual value
      {0x607A, 0, true, 0},         // target position
      {0x607C, 0, true, 0},         // home offset
      {0x607D, 1, true, INT32_MIN}, // software position limit min
      {0x607D, 2, true, INT32_MAX}, // software position limit max
      {0x607F, 0, true, 0},         // max profile velocity
      {0x6091, 1, true, 1},         // gear ratio: motor revolutions
      {0x6091, 2, true, 1},         // gear ratio: shaft revolutions
      {0x6098, 0, true, 35},        // homing method
      {0x6099, 1, true, 1747626},   // homing speed: search for switch
      {0x6099, 2, true, 174762},    // homing speed: search for zero
      {0x609A, 0, true, 0},         // homing acceleration
      {0x60FD, 0, false, 0},        // digital inputs
      {0x60FF, 0, true, 0},         // target velocity
  };
  // Further objects of the CiA402 quick reference (spec/amc1600c.md, appendix 2): stored
  // values that MC_Read/WriteParameter reach by SDO (the motor model does not use them).
  od_.insert(od_.end(), {
      {0x6067, 0, true, 7},            // position window
      {0x6068, 0, true, 0},            // position window time [ms]
      {0x606D, 0, true, 100},          // velocity window
      {0x606E, 0, true, 0},            // velocity window time [ms]
      {0x6072, 0, true, 3000},         // max torque [0.1 %]
      {0x607E, 0, true, 0},            // polarity
      {0x6081, 0, true, 0},            // profile velocity
      {0x6083, 0, true, 1747626667},   // profile acceleration
      {0x6084, 0, true, 1747626667},   // profile deceleration
      {0x6085, 0, true, 1747626667},   // quick-stop deceleration
      {0x6086, 0, true, 0},            // motion profile type (linear)
      {0x6087, 0, true, 0},            // torque slope
      {0x60B0, 0, true, 0},            // position offset
      {0x60B1, 0, true, 0},            // velocity offset
      {0x60B2, 0, true, 0},            // torque offset
      {0x60E0, 0, true, 2000},         // positive torque limit [0.1 %]
      {0x60E1, 0, true, 2000},         // negative torque limit [0.1 %]
      {0x60E6, 0, true, 0},            // position calculation method
      {0x60FE, 1, true, 0},            // digital outputs
      {0x6502, 0, false, 0x3AD},       // supported drive modes
  });
  if (cfg_.followingErrorLimit > 0) writeObject(0x6065, 0, std::llround(cfg_.followingErrorLimit * cfg_.incrementsPerUnit));
}

uint16_t Drive::statusword() const {
  uint16_t sw = 0;
  switch (state_) {
    case Cia402::SwitchOnDisabled: sw = 0x0040; break;
    case Cia402::ReadyToSwitchOn: sw = 0x0031; break;
    case Cia402::SwitchedOn: sw = 0x0033; break;
    case Cia402::OperationEnabled: sw = 0x0037; break;
    case Cia402::QuickStopActive: sw = 0x0017; break;
    case Cia402::FaultReactionActive: sw = 0x001F; break;
    case Cia402::Fault: sw = 0x0018; break;
  }
  if (communication_) sw |= 0x0200;   // remote
  if (homing_) sw |= homing_->statusBits(*this);   // bits 10, 12, 13 in homing mode; 15 once homed
  return sw;
}

bool Drive::readObject(uint16_t index, uint8_t sub, int64_t& value) const {
  const double inc = cfg_.incrementsPerUnit;
  switch (index) {
    case 0x603F: value = errorCode_; return sub == 0;
    case 0x6040: value = controlword_; return sub == 0;
    case 0x6041: value = statusword(); return sub == 0;
    case 0x6061: value = modesOfOperation_; return sub == 0;
    case 0x6064: value = std::llround(actPos_ * inc); return sub == 0;
    case 0x606C: value = std::llround(actVel_ * inc); return sub == 0;
    case 0x6077: value = std::llround(actTorque_ * 10.0); return sub == 0;
    case 0x6071: value = std::llround(targetTorque_ * 10.0); return sub == 0;
    case 0x60FD: value = digitalInputs(); return sub == 0;
    default: break;
  }
  for (const Object& o : od_)
    if (o.index == index && o.sub == sub) {
      value = o.value;
      return true;
    }
  return false;
}

bool Drive::writeObject(uint16_t index, uint8_t sub, int64_t value) {
  for (Object& o : od_)
    if (o.index == index && o.sub == sub) {
      if (!o.writable) return false;
      o.value = value;
      if (index == 0x6040) controlword_ = static_cast<uint16_t>(value);
      if (index == 0x6060) modesOfOperation_ = static_cast<int8_t>(value);
      if (index == 0x6071) targetTorque_ = static_cast<double>(value) / 10.0;
      return true;
    }
  return false;
}

void Drive::applyFaults(int64_t nowNs) {
  while (nextFault_ < cfg_.faults.size() && cfg_.faults[nextFault_].atNs <= nowNs) {
    const FaultEvent& f = cfg_.faults[nextFault_++];
    switch (f.kind) {
      case FaultKind::DriveError:
        if (cfg_.kind != AxisKind::Encoder) {
          state_ = Cia402::Fault;
          errorCode_ = f.code;
        }
        break;
      case FaultKind::CommunicationLost: communication_ = false; break;
      case FaultKind::CommunicationRestored: communication_ = true; break;
      case FaultKind::LimitPositive: forcedLimitPos_ = true; break;
      case FaultKind::LimitNegative: forcedLimitNeg_ = true; break;
      case FaultKind::LimitsReleased: forcedLimitPos_ = forcedLimitNeg_ = false; break;
    }
  }
}

// One state transition per cycle on a bus drive (the controlword written in
// this cycle is answered by the statusword of the next); devices without a
// bus settle at once.
void Drive::stepStateMachine() {
  const bool instant = cfg_.kind != AxisKind::Servo;
  for (int guard = 0; guard < 4; ++guard) {
    const uint16_t cw = controlword_;
    Cia402 next = state_;
    switch (state_) {
      case Cia402::SwitchOnDisabled:
        if (isShutdown(cw) || (instant && (isSwitchOn(cw) || isEnableOperation(cw)))) next = Cia402::ReadyToSwitchOn;
        break;
      case Cia402::ReadyToSwitchOn:
        if (isDisableVoltage(cw) || isQuickStop(cw)) next = Cia402::SwitchOnDisabled;
        else if (isSwitchOn(cw) || (instant && isEnableOperation(cw))) next = Cia402::SwitchedOn;
        break;
      case Cia402::SwitchedOn:
        if (isDisableVoltage(cw) || isQuickStop(cw)) next = Cia402::SwitchOnDisabled;
        else if (isShutdown(cw)) next = Cia402::ReadyToSwitchOn;
        else if (isEnableOperation(cw)) next = Cia402::OperationEnabled;
        break;
      case Cia402::OperationEnabled:
        if (isDisableVoltage(cw)) next = Cia402::SwitchOnDisabled;
        else if (isQuickStop(cw)) next = Cia402::QuickStopActive;
        else if (isShutdown(cw)) next = Cia402::ReadyToSwitchOn;
        else if (isSwitchOn(cw)) next = Cia402::SwitchedOn;
        break;
      case Cia402::QuickStopActive:
        if (isDisableVoltage(cw)) next = Cia402::SwitchOnDisabled;
        else if (isEnableOperation(cw) && (cw & 0x04)) next = Cia402::OperationEnabled;
        break;
      case Cia402::FaultReactionActive: next = Cia402::Fault; break;
      case Cia402::Fault:
        if ((cw & 0x80) && !(prevControlword_ & 0x80) && communication_) {
          next = Cia402::SwitchOnDisabled;
          errorCode_ = 0;
        }
        break;
    }
    prevControlword_ = cw;
    if (next == state_) break;
    state_ = next;
    if (!instant) break;
  }
}

void Drive::cycle(double setPos, double setVel, double setAcc, double dt, int64_t nowNs) {
  applyFaults(nowNs);
  if (communication_) stepStateMachine();
  prevPos_ = actPos_;
  if (cfg_.kind == AxisKind::Encoder) {
    // Whole increments, as a real encoder counts: the position is count / increments per
    // unit, so it does not drift by rounding (100 mm/s at 1000 inc/mm is 300.0 at 3 s).
    const double ipu = cfg_.incrementsPerUnit > 0 ? cfg_.incrementsPerUnit : 1;
    if (actPos_ != encLastPos_) encCount_ = std::round(actPos_ * ipu);   // set from outside (MC_SetPosition ...)
    actVel_ = cfg_.encoderVelocity;
    encFrac_ += actVel_ * dt * ipu;
    const double whole = std::trunc(encFrac_ + std::copysign(1e-9, encFrac_));   // 99.99999999999999 is 100
    encFrac_ -= whole;
    encCount_ += whole;
    actPos_ = encLastPos_ = encCount_ / ipu;
    actTorque_ = 0;
    return;
  }
  if (state_ != Cia402::OperationEnabled && state_ != Cia402::QuickStopActive) {
    actVel_ = 0;          // power stage off: the (braked) motor holds its position
    actTorque_ = 0;
    lagSetPos_ = actPos_;
    lagSetVel_ = 0;
    if (homing_) homing_->powerOff(*this);
    return;
  }
  if (homingMode() && state_ == Cia402::OperationEnabled) {
    // Homing mode: the drive ignores the controller's set values and runs the method of 6098h.
    if (!homing_) homing_ = std::make_shared<DriveHoming>();
    double p = 0, v = 0, a = 0;
    homing_->before(*this, dt, p, v, a);
    motor(p, v, a, dt);
    homing_->after(*this);
    return;
  }
  if (homing_) homing_->leaveMode(*this);
  if (modesOfOperation_ == 10) {   // CST: the load accelerates with torque / inertia
    actTorque_ = targetTorque_;
    const double v0 = cfg_.inertia > 0 ? actVel_ : 0.0;
    actVel_ = cfg_.inertia > 0 ? v0 + actTorque_ / cfg_.inertia * dt : 0.0;
    actPos_ += 0.5 * (v0 + actVel_) * dt;
    return;
  }
  motor(setPos, setVel, setAcc, dt);
}

void Drive::homingSetPoint(double& p, double& v, double& a) const {
  if (homing_) return homing_->setPoint(*this, p, v, a);
  p = actPos_;
  v = a = 0;
}

void Drive::motor(double setPos, double setVel, double setAcc, double dt) {
  const bool csv = modesOfOperation_ == 9;   // CSV: no position loop, the motor follows the set velocity
  switch (cfg_.model) {
    case DriveModel::Ideal:
      if (csv) {
        const double v0 = actVel_;
        actVel_ = setVel;
        actPos_ += 0.5 * (v0 + actVel_) * dt;
      } else if (cfg_.kind == AxisKind::Pulse && cfg_.incrementsPerUnit > 0) {
        actPos_ = std::nearbyint(setPos * cfg_.incrementsPerUnit) / cfg_.incrementsPerUnit;
        actVel_ = dt > 0 ? (actPos_ - prevPos_) / dt : setVel;
      } else {
        actPos_ = setPos;
        actVel_ = setVel;
      }
      break;
    case DriveModel::Lag: {
      // The exact response of the first-order velocity loop over the cycle to
      // a command that goes linearly from its value at the previous cycle to
      // this one (feed-forward velocity + kv x the position error at the start
      // of the cycle).  Holding this cycle's command for the whole cycle would
      // make the motor lead the set point by about one cycle.
      const double e0 = lagSetPos_ - actPos_;
      // CSV (velocity mode): no position loop.
      const double loop = csv ? 0.0 : cfg_.kv * e0;
      const double u0 = lagSetVel_ + loop, u1 = setVel + loop;
      const double tau = cfg_.lagTime;
      if (tau <= 0 || dt <= 0) {
        actPos_ += 0.5 * (u0 + u1) * dt;
        actVel_ = u1;
      } else {
        const double slope = (u1 - u0) / dt, E = std::exp(-dt / tau), c = actVel_ - u0 + slope * tau;
        actPos_ += u0 * dt + slope * dt * dt / 2 - slope * tau * dt + c * tau * (1 - E);
        actVel_ = u1 - slope * tau + c * E;
      }
      break;
    }
  }
  actTorque_ = cfg_.inertia * setAcc;
  lagSetPos_ = setPos;
  lagSetVel_ = setVel;
}

bool Drive::limitPositiveActive() const { return forcedLimitPos_ || (cfg_.hasLimitPositive && actPos_ - shift_ >= cfg_.limitPositive); }
bool Drive::limitNegativeActive() const { return forcedLimitNeg_ || (cfg_.hasLimitNegative && actPos_ - shift_ <= cfg_.limitNegative); }
bool Drive::homeSwitchActive() const {
  const double x = actPos_ - shift_;
  return cfg_.hasHomeSwitch && x >= cfg_.homeSwitchLow && x <= cfg_.homeSwitchHigh;
}

bool Drive::indexPassed(double& at) const {
  if (cfg_.indexPeriod <= 0 || actPos_ == prevPos_) return false;
  const double p = cfg_.indexPeriod, o = cfg_.indexOffset + shift_;
  // The first index mark met in the direction of travel, in (prev, act] or [act, prev).
  const double mark = actPos_ > prevPos_ ? o + (std::floor((prevPos_ - o) / p) + 1) * p
                                         : o + (std::ceil((prevPos_ - o) / p) - 1) * p;
  if ((actPos_ > prevPos_ && mark <= actPos_) || (actPos_ < prevPos_ && mark >= actPos_)) {
    at = mark;
    return true;
  }
  return false;
}

}  // namespace stc::motion
