#include "stdlib-motion/core/Axis.h"
#include "stdlib-motion/core/InputBounds.h"

#include <algorithm>
#include <cmath>

namespace stc::motion {

// The drive's homing set point continued at its velocity: what a command
// that takes over between two cycles (MC_Stop) starts from.
class HomingCoast final : public Generator {
public:
  double p = 0, v = 0;
  Kinematic at(double t) const override { return Kinematic{p + v * t, v, 0}; }
  double duration() const override { return 0; }
};

Axis::Axis(AxisConfig cfg, uint32_t index) : index_(index), cfg_(std::move(cfg)), drive_(cfg_.drive) {}

double Axis::reportPosition(double unwrapped) const {
  if (cfg_.period <= 0) return unwrapped;
  double r = std::fmod(unwrapped, cfg_.period);
  if (r < 0) r += cfg_.period;
  if (r >= cfg_.period) r = 0;   // fmod rounding at -0 / period
  return r;
}

// The controlword the controller sends: the CiA402 enable handshake one
// step per cycle (the drive answers in the next), quick stop while
// bDriveStart is FALSE, shutdown when the regulator is switched off.
void Axis::requestPower(bool regulatorOn, bool driveStart, int64_t nowNs) {
  wantPower_ = regulatorOn;
  driveStart_ = driveStart;
  updateControlword();
  // Devices without a bus answer within the call (MC_Power.Status in c0).
  if (cfg_.drive.kind != AxisKind::Servo) drive_.settle();
  (void)nowNs;
}

void Axis::updateControlword() {
  uint16_t cw = 0x06;                         // shutdown: power stage off
  if (wantPower_) {
    if (!driveStart_) cw = 0x02;              // quick stop
    else if (cfg_.drive.kind != AxisKind::Servo) cw = 0x0F;
    else switch (drive_.cia402()) {
      case Cia402::SwitchOnDisabled: cw = 0x06; break;
      case Cia402::ReadyToSwitchOn: cw = 0x07; break;
      default: cw = 0x0F; break;
    }
  }
  if (resetPulse_) cw |= 0x80;
  if (wantPower_ && driveStart_) cw |= cwBits_;
  drive_.setControlword(cw);
}

void Axis::clearError() {
  error_ = Error::None;
  resetPulse_ = true;       // fault reset (controlword bit 7) to the drive
  updateControlword();
}

Limits Axis::limitsFor(double vel, double acc, double dec, double jerk) const {
  Limits l;
  l.vel = vel;
  l.acc = acc;
  l.dec = dec;
  switch (cfg_.ramp) {
    case RampType::Trapez: l.jerk = 0; break;
    case RampType::SinSquare: {
      // A sin² ramp from 0 to vel with peak acceleration A lasts 2 vel / A: the
      // triangular jerk-limited ramp with jerk A^2 / vel has the same time and peak.
      const double a = std::max(acc, dec);
      l.jerk = vel > 0 && a > 0 && std::isfinite(a * a / vel) ? a * a / vel : 0.0;
      break;
    }
    default: l.jerk = jerk; break;
  }
  return l;
}

bool Axis::acceptsJerk(double jerk) const {
  return bounds::jerk(jerk) && (cfg_.ramp == RampType::Trapez || cfg_.ramp == RampType::SinSquare || jerk > 0);
}

bool Axis::absoluteTarget(double position, Direction dir, double& target) const {
  const int d = static_cast<int>(dir);
  if (d < -1 || d > 3) return false;
  if (cfg_.period <= 0) {
    target = position;
    return true;
  }
  const double P = cfg_.period;
  const double cur = set_.p;
  const double base = std::floor(cur / P) * P;
  double cand = base + reportPosition(position);
  const double up = cand < cur ? cand + P : cand;      // reached moving in +
  const double down = cand > cur ? cand - P : cand;    // reached moving in -
  switch (dir) {
    case Direction::Positive: target = up; break;
    case Direction::Negative: target = down; break;
    case Direction::Shortest: target = (up - cur) <= (cur - down) ? up : down; break;
    case Direction::Current: target = set_.v < 0 ? down : up; break;
    case Direction::Fastest: {
      // The direction whose plan takes less time from the current state.
      Limits l = lastLimits_;
      if (!(l.vel > 0 && l.acc > 0 && l.dec > 0)) l = Limits{1, 1, 1, 0};
      Profile a, b;
      planPosition(set_, up, 0, l, a);
      planPosition(set_, down, 0, l, b);
      target = a.duration() <= b.duration() ? up : down;
      break;
    }
    case Direction::Invalid: return false;   // refused above; kept for -Wswitch
  }
  return true;
}

// The state a new base movement starts from: the set state without the
// contribution of a superimposed move in progress.
Kinematic Axis::baseState() const {
  return Kinematic{set_.p - supState_.p, set_.v - supState_.v, set_.a - supState_.a};
}

// Starts a base movement of `kind` whose profile the caller plans from the
// returned state.  A blended hand-over (frac != 0) starts from the
// predecessor's exact end state at the instant it was reached.
Kinematic Axis::beginBase(Movement::Kind kind, int64_t nowNs, double frac) {
  Kinematic s = baseState();
  if (frac != 0 && mv_.kind != Movement::Kind::None) {
    s = mv_.end();
    s.p += offset_;
  }
  offset_ = 0;
  mv_.kind = kind;
  mv_.gen.reset();
  mv_.originNs = nowNs;
  mv_.originFrac = frac;
  mv_.rate = override_;
  mv_.rateNs = override_ == 1 ? 0 : nowNs;
  mv_.rateTau = frac;
  mv_.reached = false;
  return s;
}

void Axis::startPosition(double target, double vEnd, const Limits& lim, int64_t nowNs, double frac) {
  Kinematic s = beginBase(Movement::Kind::Position, nowNs, frac);
  lastLimits_ = lim;
  planPosition(s, target, vEnd, lim, mv_.profile);
}

void Axis::startVelocity(double v, const Limits& lim, int64_t nowNs, double frac) {
  Kinematic s = beginBase(Movement::Kind::Velocity, nowNs, frac);
  lastLimits_ = lim;
  planVelocity(s, v, lim, mv_.profile);
}

void Axis::startStop(const Limits& lim, int64_t nowNs) {
  Kinematic s = beginBase(Movement::Kind::Stop, nowNs, 0);
  Limits l = lim;
  // A stop never speeds up: its velocity bound is the current speed.
  l.vel = std::max(std::fabs(s.v), 1e-9);
  planVelocity(s, 0, l, mv_.profile);
}

void Axis::startSuperimposed(double distance, const Limits& lim, int64_t nowNs) {
  // A new superimposed move takes over from the one in progress: what that
  // one has moved so far stays, its remaining distance is dropped.
  Kinematic rel{0, supState_.v, supState_.a};
  offset_ += supState_.p;
  planPosition(rel, distance, 0, lim, sup_.profile);
  sup_.kind = Movement::Kind::Position;
  sup_.originNs = nowNs;
  sup_.originFrac = 0;
  sup_.reached = false;
  supState_ = rel;
}

void Axis::setOverride(double factor, int64_t nowNs) {
  if (mv_.kind != Movement::Kind::None) {
    mv_.rateTau = mv_.t(nowNs);
    mv_.rateNs = nowNs;
    mv_.rate = factor;
  }
  override_ = factor;
}

void Axis::startExternal(std::shared_ptr<const Generator> gen, int64_t nowNs) {
  beginBase(Movement::Kind::External, nowNs, 0);
  mv_.gen = std::move(gen);
}

Kinematic Movement::at(double t) const {
  const double T = duration();
  if (t >= T - Axis::kEndTolerance) {
    Kinematic e = end();
    e.p += e.v * (t - T);
    e.a = 0;
    return e;
  }
  return gen ? gen->at(t) : profile.at(t);
}

void Axis::shiftPosition(double delta) {
  offset_ += delta;
  set_.p += delta;
  drive_.shift(delta);
  lastCommandedTarget += delta;
}

void Axis::holdAt(double pos) {
  set_ = heldBase_ = Kinematic{pos, 0, 0};
  offset_ = 0;
  mv_.kind = sup_.kind = Movement::Kind::None;
  mv_.gen.reset();
  supState_ = Kinematic{};
}

void Axis::sample(int64_t nowNs) {
  Kinematic base = heldBase_;
  base.v = base.a = 0;
  if (mv_.kind != Movement::Kind::None) {
    base = mv_.at(mv_.t(nowNs));
    if (mv_.rate != 1) {
      base.v *= mv_.rate;
      base.a *= mv_.rate * mv_.rate;
    }
  }
  if (sup_.kind != Movement::Kind::None) {
    const double t = sup_.t(nowNs);
    supState_ = t >= sup_.profile.duration() - kEndTolerance ? sup_.profile.end() : sup_.profile.at(t);
  }
  baseNow_ = base;
  set_.p = base.p + offset_ + supState_.p;
  set_.v = base.v + supState_.v;
  set_.a = base.a + supState_.a;
}

StepResult Axis::step(int64_t nowNs, double dt) {
  StepResult r;
  // ---- set point = base movement + offset + superimposed part
  sample(nowNs);
  if (mv_.kind != Movement::Kind::None) {
    const double over = mv_.t(nowNs) - mv_.duration();
    if (!mv_.reached && over >= -kEndTolerance) {
      mv_.reached = true;
      r.reached = true;
      r.overshoot = std::max(over, 0.0);
    }
    if (mv_.reached && baseNow_.v == 0) {   // at rest: nothing left to generate
      mv_.kind = Movement::Kind::None;
      mv_.gen.reset();
    }
  }
  heldBase_ = baseNow_;
  if (sup_.kind != Movement::Kind::None && sup_.t(nowNs) >= sup_.profile.duration() - kEndTolerance) {
    offset_ += supState_.p;       // the finished superimposed distance becomes part of the offset
    supState_ = Kinematic{};
    sup_.kind = Movement::Kind::None;
    r.superimposedReached = true;
  }

  // ---- drive
  // Drive-side homing (6060h = 6) lasts while the axis is in Homing; any other state takes the drive back to CSP.
  if (state_ != AxisState::Homing && drive_.homingMode()) {
    drive_.writeObject(0x6060, 0, 8);
    cwBits_ = 0;
  }
  if (cfg_.drive.kind != AxisKind::Servo) updateControlword();
  drive_.cycle(set_.p, set_.v, set_.a, dt, nowNs);
  if (cfg_.drive.kind == AxisKind::Servo) updateControlword();   // answered in the next cycle
  resetPulse_ = false;
  if (drive_.modeOfOperation() == 10) {
    // Cyclic synchronous torque: the motor follows the set torque and the set point follows the motor.
    const double a = cfg_.drive.inertia > 0 && drive_.operationEnabled() ? drive_.actTorque() / cfg_.drive.inertia : 0.0;
    holdAt(drive_.actPosition());
    set_.v = drive_.actVelocity();
    set_.a = a;
  } else if (state_ == AxisState::Homing && drive_.homingMode()) {
    // The drive generates the set point: the axis reports (and supervises) the drive's.
    Kinematic h;
    drive_.homingSetPoint(h.p, h.v, h.a);
    holdAt(h.p);
    set_.v = h.v;
    set_.a = h.a;
    lastCommandedTarget = h.p;
    if (h.v != 0) {
      mv_.kind = Movement::Kind::External;
      if (!homingCoast_) homingCoast_ = std::make_shared<HomingCoast>();   // reused: no allocation per cycle
      homingCoast_->p = h.p;
      homingCoast_->v = h.v;
      mv_.gen = homingCoast_;
      mv_.originNs = nowNs;
      mv_.originFrac = 0;
      mv_.rate = 1;
      mv_.rateNs = 0;
      mv_.reached = true;
    }
  }

  // ---- supervision (the first error wins; ErrorStop reports no further ones)
  if (state_ == AxisState::ErrorStop) return r;
  if (!drive_.communication()) r.error = Error::Communication;
  else if (drive_.faulted()) r.error = Error::DriveError;
  else if (state_ != AxisState::PowerOff && state_ != AxisState::Homing &&
           ((drive_.limitPositiveActive() && set_.v > 0) || (drive_.limitNegativeActive() && set_.v < 0)))
    r.error = Error::HwLimitsExceeded;
  else if (cfg_.swLimitEnable && state_ != AxisState::Homing &&
           ((set_.p > cfg_.swLimitPositive && set_.v > 0) || (set_.p < cfg_.swLimitNegative && set_.v < 0)))
    // Only motion further out trips: an axis reset outside a limit may move back in.
    r.error = Error::SwLimitsExceeded;
  else if (cfg_.drive.followingErrorLimit > 0 && std::fabs(set_.p - drive_.actPosition()) > cfg_.drive.followingErrorLimit)
    r.error = Error::FollowingError;
  else if (cfg_.maxVelocity > 0 && std::fabs(set_.v) > cfg_.maxVelocity * (1 + 1e-9))
    r.error = Error::VdMaxVelocityExceeded;
  else if (cfg_.maxAcceleration > 0 && set_.a * set_.v > 0 && std::fabs(set_.a) > cfg_.maxAcceleration * (1 + 1e-9))
    r.error = Error::VdMaxAccelerationExceeded;
  else if (cfg_.maxDeceleration > 0 && set_.a * set_.v < 0 && std::fabs(set_.a) > cfg_.maxDeceleration * (1 + 1e-9))
    r.error = Error::VdMaxDecelerationExceeded;
  return r;
}

void Axis::enterErrorStop(Error e, int64_t nowNs) {
  state_ = AxisState::ErrorStop;
  error_ = e;
  drive_.setTargetTorque(0);     // torque control: the set torque drops, the load coasts
  sup_.kind = Movement::Kind::None;
  if (!drive_.operationEnabled()) {
    // The power stage is off (drive fault, lost enable): the motor stands where it is.
    holdAt(drive_.actPosition());
    return;
  }
  double dec = cfg_.errorDeceleration > 0 ? cfg_.errorDeceleration : cfg_.maxDeceleration > 0 ? cfg_.maxDeceleration : 1000.0;
  if (e == Error::SwLimitsExceeded) {
    if (!cfg_.swLimitDecelerate) {
      holdAt(set_.p);     // no ramp: the set point stops where it tripped
      return;
    }
    if (cfg_.swLimitDeceleration > 0) dec = cfg_.swLimitDeceleration;
    if (cfg_.swErrorMaxDistance > 0) dec = std::max(dec, set_.v * set_.v / (2 * cfg_.swErrorMaxDistance));
  }
  if (set_.v != 0 || set_.a != 0) {
    startStop(Limits{std::fabs(set_.v), dec, dec, 0}, nowNs);
  } else {
    holdAt(set_.p);
  }
}

}  // namespace stc::motion
