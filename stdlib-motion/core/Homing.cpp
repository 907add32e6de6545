// Homing: CiA402 homing methods in the simulated drive, and the homing FBs.
// docs/motion-homing.md describes the behaviour and every decision taken
// where the manuals are silent.
#include "stdlib-motion/core/Homing.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/core/InputBounds.h"
#include <limits>

namespace stc::motion {

// ================================================================ CiA402 methods in the drive

namespace {

// The sensor whose edge is the reference of a method.
enum class Sensor : uint8_t { None, NegLimit, PosLimit, HomeLow, HomeHigh, Index, Current };

// One homing method, table-driven (CiA402-2 figures):
//  a     side of the edge on which the sensor is active (+1: above the edge)
//  d     direction of the final slow approach across the edge (and towards the index mark)
//  off   initial direction when the sensor is not active at the start
//  limit the limit switch the method needs to reverse its search (0: none)
struct Method {
  Sensor sensor;
  int8_t a, d, off, limit;
  bool index;
};

bool methodOf(int m, Method& out) {
  // 1-14 with index pulse; 17-30 the same without (m - 16).
  static const Method base[15] = {
      {Sensor::None, 0, 0, 0, 0, false},
      {Sensor::NegLimit, -1, +1, -1, 0, true},   // 1 negative limit switch
      {Sensor::PosLimit, +1, -1, +1, 0, true},   // 2 positive limit switch
      {Sensor::HomeLow, +1, -1, +1, 0, true},    // 3 positive home switch, index left of the edge
      {Sensor::HomeLow, +1, +1, +1, 0, true},    // 4 positive home switch, index right of the edge
      {Sensor::HomeHigh, -1, +1, -1, 0, true},   // 5 negative home switch, index right
      {Sensor::HomeHigh, -1, -1, -1, 0, true},   // 6 negative home switch, index left
      {Sensor::HomeLow, +1, -1, +1, +1, true},   // 7 home switch + positive limit: left of the lower edge
      {Sensor::HomeLow, +1, +1, +1, +1, true},   // 8 right of the lower edge
      {Sensor::HomeHigh, -1, -1, +1, +1, true},  // 9 left of the upper edge
      {Sensor::HomeHigh, -1, +1, +1, +1, true},  // 10 right of the upper edge
      {Sensor::HomeHigh, -1, +1, -1, -1, true},  // 11 home switch + negative limit: right of the upper edge
      {Sensor::HomeHigh, -1, -1, -1, -1, true},  // 12 left of the upper edge
      {Sensor::HomeLow, +1, +1, -1, -1, true},   // 13 right of the lower edge
      {Sensor::HomeLow, +1, -1, -1, -1, true},   // 14 left of the lower edge
  };
  if (m >= 1 && m <= 14) {
    out = base[m];
    return true;
  }
  if (m >= 17 && m <= 30) {
    out = base[m - 16];
    out.index = false;
    return true;
  }
  if (m == 33 || m == 34) {
    out = Method{Sensor::Index, 0, static_cast<int8_t>(m == 33 ? -1 : +1), 0, 0, true};
    return true;
  }
  if (m == 35 || m == 37) {
    out = Method{Sensor::Current, 0, 0, 0, 0, false};
    return true;
  }
  return false;   // 0, negative (manufacturer specific), 15, 16, 31, 32, 36: not supported
}

int64_t od(const Drive& d, uint16_t index, uint8_t sub) {
  int64_t v = 0;
  d.readObject(index, sub, v);
  return v;
}

// The first index mark strictly beyond x in direction dir.
double markBeyond(const Drive& d, double x, int dir) {
  const DriveConfig& c = d.config();
  const double p = c.indexPeriod, o = c.indexOffset + d.coordinateShift();
  return dir > 0 ? o + (std::floor((x - o) / p) + 1) * p : o + (std::ceil((x - o) / p) - 1) * p;
}

constexpr double kTol = 1e-10;

}  // namespace

bool DriveHoming::sensor(const Drive& d) const {
  Method m{};
  methodOf(method_, m);
  switch (m.sensor) {
    case Sensor::NegLimit: return d.limitNegativeActive();
    case Sensor::PosLimit: return d.limitPositiveActive();
    case Sensor::HomeLow:
    case Sensor::HomeHigh: return d.homeSwitchActive();
    default: return false;
  }
}

// The position of the method's edge (what a latch on the sensor would capture).
double DriveHoming::edge(const Drive& d) const {
  Method m{};
  methodOf(method_, m);
  const DriveConfig& c = d.config();
  const double s = d.shift_;
  switch (m.sensor) {
    case Sensor::NegLimit: return c.hasLimitNegative ? c.limitNegative + s : d.actPos_;
    case Sensor::PosLimit: return c.hasLimitPositive ? c.limitPositive + s : d.actPos_;
    case Sensor::HomeLow: return c.homeSwitchLow + s;
    case Sensor::HomeHigh: return c.homeSwitchHigh + s;
    default: return d.actPos_;
  }
}

void DriveHoming::velocity(double v) {
  // A start above |v| is braked to it with the same acceleration.
  const Limits lim{std::max(std::fabs(v), 1e-9), acc_, acc_, 0};
  planVelocity(sp_, v, lim, prof_);
  t_ = 0;
  fresh_ = false;
}

void DriveHoming::fail(Drive& d, bool moving) {
  (void)d;
  status_ = Status::Failed;
  if (!moving) {
    phase_ = Phase::Idle;
    return;
  }
  failing_ = true;
  phase_ = Phase::Halt;
  velocity(0);
}

void DriveHoming::start(Drive& d) {
  const double inc = d.config().incrementsPerUnit > 0 ? d.config().incrementsPerUnit : 1;
  method_ = static_cast<uint8_t>(std::clamp<int64_t>(od(d, 0x6098, 0), 0, 255));
  if (static_cast<int8_t>(od(d, 0x6098, 0)) < 0) method_ = 0;
  vFast_ = static_cast<double>(od(d, 0x6099, 1)) / inc;
  vSlow_ = static_cast<double>(od(d, 0x6099, 2)) / inc;
  acc_ = static_cast<double>(od(d, 0x609A, 0)) / inc;
  offset_ = static_cast<double>(static_cast<int32_t>(od(d, 0x607C, 0))) / inc;
  sp_ = Kinematic{d.actPos_, 0, 0};
  spValid_ = true;
  homed_ = false;
  failing_ = false;
  reversals_ = 0;
  fresh_ = true;
  t_ = 0;
  status_ = Status::Running;
  Method m{};
  const DriveConfig& c = d.config();
  if (!methodOf(method_, m)) return fail(d, false);
  if (m.sensor == Sensor::Current) {
    reference(d, d.actPos_);
    return;
  }
  // Everything a method needs must be there: sensors, speeds, acceleration.
  const bool needFast = m.sensor != Sensor::Index;
  if ((needFast && !(vFast_ > 0)) || !(vSlow_ > 0) || !(acc_ > 0)) return fail(d, false);
  if (m.index && !(c.indexPeriod > 0)) return fail(d, false);
  if ((m.sensor == Sensor::NegLimit || m.limit < 0) && !c.hasLimitNegative) return fail(d, false);
  if ((m.sensor == Sensor::PosLimit || m.limit > 0) && !c.hasLimitPositive) return fail(d, false);
  if ((m.sensor == Sensor::HomeLow || m.sensor == Sensor::HomeHigh) && !c.hasHomeSwitch) return fail(d, false);
  if (m.sensor == Sensor::Index) {
    mark_ = markBeyond(d, d.actPos_, m.d);
    phase_ = Phase::Index;
    velocity(m.d * vSlow_);
    fresh_ = true;
    return;
  }
  prevS_ = sensor(d);
  if (prevS_ && (m.sensor == Sensor::NegLimit || m.sensor == Sensor::PosLimit)) {
    // Standing on the limit switch: already on its active side.
    phase_ = Phase::Approach;
    velocity(m.d * vSlow_);
  } else {
    dir_ = prevS_ ? static_cast<int8_t>(-m.a) : m.off;
    phase_ = Phase::Search;
    velocity(dir_ * vFast_);
  }
  fresh_ = true;
}

// The reference point r (current coordinates) becomes the home offset; the
// drive then returns to it at the slow speed.
void DriveHoming::reference(Drive& d, double r) {
  const double delta = offset_ - r;
  d.shift(delta);
  sp_.p += delta;
  homed_ = true;
  if (sp_.v == 0 && sp_.a == 0 && std::fabs(sp_.p - offset_) < kTol) {
    sp_.p = offset_;
    phase_ = Phase::Idle;
    status_ = Status::Attained;
    return;
  }
  phase_ = Phase::Return;
  planPosition(sp_, offset_, 0, Limits{std::max(vSlow_, 1e-9), acc_, acc_, 0}, prof_);
  t_ = 0;
  fresh_ = false;
}

void DriveHoming::before(Drive& d, double dt, double& p, double& v, double& a) {
  const bool bit4 = (d.controlword() & 0x10) != 0;
  const bool rising = bit4 && !prevBit4_;
  const bool falling = !bit4 && prevBit4_;
  prevBit4_ = bit4;
  if (rising) {
    start(d);
  } else if (falling && phase_ != Phase::Idle && phase_ != Phase::Halt) {
    // Controlword bit 4 reset: homing interrupted, the drive stops with the homing acceleration.
    // The halt starts at this cycle's time from the state the method has reached by then.
    t_ += fresh_ ? 0 : dt;
    sp_ = prof_.at(t_);
    status_ = Status::Interrupted;
    phase_ = Phase::Halt;
    velocity(0);
    fresh_ = true;
  }
  if (phase_ == Phase::Idle) {
    if (!spValid_ || status_ != Status::Attained) sp_ = Kinematic{d.actPos_, 0, 0};
    spValid_ = true;
  } else {
    if (fresh_) fresh_ = false;
    else t_ += dt;
    sp_ = prof_.at(t_);
  }
  p = sp_.p;
  v = sp_.v;
  a = sp_.a;
}

void DriveHoming::after(Drive& d) {
  if (phase_ == Phase::Idle) return;
  Method m{};
  methodOf(method_, m);
  const double move = d.actPos_ - d.prevPos_;
  const int mv = move > 0 ? 1 : move < 0 ? -1 : 0;
  switch (phase_) {
    case Phase::Return:
      if (t_ >= prof_.duration() - kTol) {
        sp_ = Kinematic{offset_, 0, 0};
        phase_ = Phase::Idle;
        status_ = Status::Attained;
      }
      return;
    case Phase::Halt:
      if (t_ >= prof_.duration() - kTol) {
        sp_ = prof_.end();
        sp_.a = 0;
        phase_ = Phase::Idle;
        status_ = failing_ ? Status::Failed : Status::Interrupted;
      }
      return;
    case Phase::Index:
      if (mv == m.d && d.actPos_ * m.d >= mark_ * m.d - kTol) reference(d, mark_);
      return;
    default: break;
  }
  const bool s = sensor(d);
  // The method's edge: the sensor turns active moving towards its active side, or inactive moving away.
  const bool crossed = mv != 0 && ((mv == m.a && s && !prevS_) || (mv == -m.a && !s && prevS_));
  prevS_ = s;
  // A limit switch other than the method's own sensor, met in the direction of travel.
  const bool ownLimitPos = m.sensor == Sensor::PosLimit, ownLimitNeg = m.sensor == Sensor::NegLimit;
  const bool limitAhead = (mv > 0 && !ownLimitPos && d.limitPositiveActive()) || (mv < 0 && !ownLimitNeg && d.limitNegativeActive());
  switch (phase_) {
    case Phase::Search:
      if (crossed) {
        if (mv == -m.d) {
          phase_ = Phase::Approach;
          velocity(m.d * vSlow_);
        } else {
          phase_ = Phase::Backoff;
          velocity(-m.d * vSlow_);
        }
      } else if (limitAhead && mv == dir_) {
        // Reverse the search at a limit switch; the second one means the edge is not there.
        if (++reversals_ > 1) return fail(d, true);
        dir_ = static_cast<int8_t>(-dir_);
        velocity(dir_ * vFast_);
      }
      return;
    case Phase::Backoff:
      if (crossed && mv == -m.d) {
        phase_ = Phase::Approach;
        velocity(m.d * vSlow_);
      } else if (limitAhead) {
        fail(d, true);
      }
      return;
    case Phase::Approach:
      if (crossed && mv == m.d) {
        const double e = edge(d);
        if (!m.index) return reference(d, e);
        mark_ = markBeyond(d, e, m.d);
        if (d.actPos_ * m.d >= mark_ * m.d - kTol) return reference(d, mark_);
        phase_ = Phase::Index;
      } else if (limitAhead) {
        fail(d, true);
      }
      return;
    default: return;
  }
}

void DriveHoming::leaveMode(Drive& d) {
  (void)d;
  prevBit4_ = false;
  if (phase_ != Phase::Idle) {
    phase_ = Phase::Idle;
    status_ = Status::Interrupted;
  }
  spValid_ = false;
}

void DriveHoming::powerOff(Drive& d) {
  leaveMode(d);
}

void DriveHoming::setPoint(const Drive& d, double& p, double& v, double& a) const {
  if (!spValid_) {
    p = d.actPos_;
    v = a = 0;
    return;
  }
  p = sp_.p;
  v = sp_.v;
  a = sp_.a;
}

uint16_t DriveHoming::statusBits(const Drive& d) const {
  uint16_t bits = homed_ ? 0x8000 : 0;
  if (!d.homingMode()) return bits;
  const bool atRest = phase_ == Phase::Idle;
  switch (status_) {
    case Status::NotStarted:
    case Status::Interrupted: bits |= atRest ? 0x0400 : 0; break;
    case Status::Running: break;
    case Status::Attained: bits |= 0x1400; break;
    case Status::Failed: bits |= 0x2000 | (atRest ? 0x0400 : 0); break;
  }
  return bits;
}

// ================================================================ the FBs

namespace {

bool finitePositive(double x) { return bounds::rate(x); }   // velocities and rates: finite, > 0, not absurd

// ---------------------------------------------------------------- MC_Home, LS_EtherCATAxis_HomeMove

class DriveHomeFb final : public FbBehaviour {
public:
  bool idle = true;
  bool halting = false;      // LS: bExecute released, the drive is stopping
  uint64_t startCycle = 0;

  void start(Kernel&, FbSlot&, Axis& ax, int64_t) override {
    ax.drive().writeObject(0x6060, 0, 6);
    ax.setControlwordBits(0x10);
    ax.setState(AxisState::Homing);
    idle = false;
    halting = false;
  }
  void reached(Kernel&, FbSlot&, Axis&, int64_t, uint64_t, double) override {}
  void afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override {
    if (idle) return;
    if (ax.controller != &fb) {   // aborted (MC_Stop) or ended by an axis error: the axis took the drive back
      idle = true;
      return;
    }
    const uint16_t sw = ax.drive().statusword();
    const bool targetReached = sw & 0x0400, attained = sw & 0x1000, failed = sw & 0x2000;
    auto leave = [&] {
      ax.setControlwordBits(0);
      ax.drive().writeObject(0x6060, 0, 8);
      idle = true;
    };
    if (attained && targetReached) {
      leave();
      ax.holdAt(ax.set().p);
      k.completeCommand(ax, nowNs, cycle, 0);   // Done, Standstill
    } else if (failed && cycle == startCycle) {
      // The drive refused to start the method (unsupported method, missing sensor, zero speeds).
      leave();
      ax.setState(AxisState::Standstill);
      k.finish(fb, nullptr, cycle, false, false, Error::HomeAxisDidntStartHoming);
    } else if (failed) {
      if (!targetReached) return;   // the drive is still stopping
      leave();
      k.errorStop(ax, Error::DiHomingError, nowNs, cycle);
    } else if (halting && targetReached) {
      leave();
      ax.setState(AxisState::Standstill);
      k.finish(fb, nullptr, cycle, false, true, Error::None);
    }
  }
};

DriveHomeFb& driveHomeOf(FbSlot& fb) {
  if (!dynamic_cast<DriveHomeFb*>(fb.behaviour.get())) fb.behaviour = std::make_unique<DriveHomeFb>();
  return static_cast<DriveHomeFb&>(*fb.behaviour);
}

void observe(Axis& ax, FbSlot& fb) {
  if (std::find(ax.observers.begin(), ax.observers.end(), &fb) == ax.observers.end()) ax.observers.push_back(&fb);
}

// Checks common to both drive-side FBs; false: refused (fb failed).
bool driveHomeAllowed(Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
  if (ax.state() == AxisState::ErrorStop) return k.fail(fb, Error::HomeAxisInErrorStop, c), false;
  if (ax.state() != AxisState::Standstill || ax.controller) return k.fail(fb, Error::HomeAxisWasntStandstill, c), false;
  if (!ax.drive().communication()) return k.fail(fb, Error::HomeAxisDidntAnswer, c), false;
  if (ax.config().drive.kind == AxisKind::Encoder) return k.fail(fb, Error::HomeAxisDidntStartHoming, c), false;
  return true;
}

void startDriveHome(Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
  // A method that moves needs a homing acceleration to stop with (173).
  int64_t method = 0, acc = 0;
  ax.drive().readObject(0x6098, 0, method);
  ax.drive().readObject(0x609A, 0, acc);
  if (method != 35 && method != 37 && acc <= 0) return k.fail(fb, Error::HomeErrorWhenStopping, c);
  DriveHomeFb& b = driveHomeOf(fb);
  b.startCycle = c.cycle;
  observe(ax, fb);
  fb.in = MoveInputs{};
  k.accept(fb, ax, c);
}

// Drops finished drive-homing FBs from the observers (outside the kernel's iteration).
void unobserveIdle(Axis& ax, FbSlot& fb) {
  auto* b = dynamic_cast<DriveHomeFb*>(fb.behaviour.get());
  if (b && b->idle) ax.observers.erase(std::remove(ax.observers.begin(), ax.observers.end(), &fb), ax.observers.end());
}

bool toIncrements(double units, double inc, int64_t& out) {
  const double x = std::nearbyint(units * inc);
  if (!std::isfinite(x) || x < -2147483648.0 || x > 2147483647.0) return false;
  out = static_cast<int64_t>(x);
  return true;
}

}  // namespace

void callHome(Kernel& k, FbSlot& fb, Axis& ax, bool execute, double position, const CallCtx& c) {
  unobserveIdle(ax, fb);
  if (!k.beginExecute(fb, execute, c)) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  if (!driveHomeAllowed(k, fb, ax, c)) return;
  int64_t offset = 0;
  const double inc = ax.config().drive.incrementsPerUnit > 0 ? ax.config().drive.incrementsPerUnit : 1;
  if (!toIncrements(position, inc, offset)) return k.fail(fb, Error::HomeAxisDidntStartHoming, c);
  ax.drive().writeObject(0x607C, 0, offset);
  startDriveHome(k, fb, ax, c);
}

void callDriveHomeMove(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const DriveHomeParams& p, const CallCtx& c) {
  unobserveIdle(ax, fb);
  const bool wasExecute = fb.execute;
  const bool rising = k.beginExecute(fb, execute, c);
  if (!execute && wasExecute && ax.controller == &fb && fb.out.busy) {
    // Level-held bExecute released during homing: interrupt (controlword bit 4 off), CommandAborted at rest.
    auto& b = driveHomeOf(fb);
    if (!b.halting) {
      b.halting = true;
      ax.setControlwordBits(0);
    }
  }
  if (!rising) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  if (!driveHomeAllowed(k, fb, ax, c)) return;
  if (p.axisNo != 0) return k.fail(fb, Error::HomeAxisDidntAnswer, c);   // a single-axis drive: no second axis answers
  // The SDO writes (DWORD inputs: 6098h is INT8, 607Ch INT32).
  Drive& d = ax.drive();
  d.writeObject(0x6098, 0, static_cast<int8_t>(p.method & 0xFF));
  d.writeObject(0x6099, 1, p.fastVel);
  d.writeObject(0x6099, 2, p.slowVel);
  d.writeObject(0x609A, 0, p.acc);
  d.writeObject(0x607C, 0, static_cast<int32_t>(static_cast<uint32_t>(p.homePos)));
  startDriveHome(k, fb, ax, c);
}

// ---------------------------------------------------------------- SMC_Homing

namespace {

class SmcHomingFb final : public FbBehaviour {
public:
  enum class Phase : uint8_t { Fast, Slow, WaitIndex, Stopping, Return };
  SmcHomingInputs in;
  Phase phase = Phase::Fast;
  bool latching = false, shiftPending = false;
  int8_t slowDir = 0;
  double refPos = 0;

  Limits lim(double v, const Axis& ax) const { return ax.limitsFor(v, in.acceleration, in.deceleration, in.jerk); }

  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    phase = Phase::Fast;
    latching = shiftPending = false;
    slowDir = static_cast<int8_t>(in.mode < 4 ? -in.direction : in.direction);
    ax.setState(AxisState::Homing);
    ax.startVelocity(in.direction * in.velocityFast, lim(in.velocityFast, ax), nowNs);
  }
  void setOrStop(Axis& ax, int64_t nowNs) {
    ax.sample(nowNs);
    const bool stopFirst = in.mode == 1 || in.mode == 5;
    if (!stopFirst) ax.shiftPosition(in.homePosition - refPos);
    shiftPending = stopFirst;
    ax.startStop(lim(std::fabs(ax.set().v), ax), nowNs);
    phase = Phase::Stopping;
  }
  void beforeStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override {
    if (!in.ignoreHwLimit && ((ax.drive().limitPositiveActive() && ax.set().v > 0) || (ax.drive().limitNegativeActive() && ax.set().v < 0))) {
      latching = false;
      return k.errorStop(ax, Error::HwLimitsExceeded, nowNs, cycle);
    }
    switch (phase) {
      case Phase::Fast:
        if (!in.referenceSwitch) {   // on the switch: slow phase (reverse for the BSLOW modes)
          ax.sample(nowNs);
          ax.startVelocity(slowDir * in.velocitySlow, lim(in.velocitySlow, ax), nowNs);
          phase = Phase::Slow;
        }
        break;
      case Phase::Slow:
        if (in.referenceSwitch && ax.set().v * slowDir > 0) {   // the switch is left in the slow direction
          refPos = ax.actPosition() - ax.actVelocity() * in.signalDelay;
          if (in.mode == 2 || in.mode == 6) {
            latching = true;
            phase = Phase::WaitIndex;
            fb.sync();
          } else {
            setOrStop(ax, nowNs);
          }
        }
        break;
      case Phase::WaitIndex:
        if (in.indexOccured) {
          latching = false;
          refPos = in.indexPosition;
          setOrStop(ax, nowNs);
          fb.sync();
        }
        break;
      default: break;
    }
  }
  void reached(Kernel& k, FbSlot&, Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot) override {
    if (phase == Phase::Stopping) {
      if (shiftPending) ax.shiftPosition(in.homePosition - refPos);
      shiftPending = false;
      if (in.returnToZero) {
        double target = 0;
        ax.absoluteTarget(0, Direction::Shortest, target);
        ax.startPosition(target, 0, lim(in.velocityFast, ax), nowNs);
        phase = Phase::Return;
        return;
      }
      k.completeCommand(ax, nowNs, cycle, overshoot);
    } else if (phase == Phase::Return) {
      k.completeCommand(ax, nowNs, cycle, overshoot);
    }
  }
};

}  // namespace

bool smcHomingLatching(const FbSlot& fb) {
  auto* b = dynamic_cast<const SmcHomingFb*>(fb.behaviour.get());
  return b && b->latching && fb.out.busy;
}

void callSmcHoming(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const SmcHomingInputs& in, const CallCtx& c) {
  if (!dynamic_cast<SmcHomingFb*>(fb.behaviour.get())) fb.behaviour = std::make_unique<SmcHomingFb>();
  auto& b = static_cast<SmcHomingFb&>(*fb.behaviour);
  if (ax.controller == &fb) {
    // Inputs read in every call.
    b.in.referenceSwitch = in.referenceSwitch;
    b.in.indexOccured = in.indexOccured;
    b.in.indexPosition = in.indexPosition;
  }
  if (!k.beginExecute(fb, execute, c)) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  b.latching = false;
  const bool jerkOk = ax.acceptsJerk(in.jerk);
  const bool modeOk = in.mode == 0 || in.mode == 1 || in.mode == 2 || in.mode == 4 || in.mode == 5 || in.mode == 6;
  if (!finitePositive(in.velocityFast) || !finitePositive(in.velocitySlow) || !finitePositive(in.acceleration) ||
      !finitePositive(in.deceleration) || !jerkOk || !std::isfinite(in.homePosition) || !std::isfinite(in.signalDelay) ||
      in.signalDelay < 0 || (in.direction != 1 && in.direction != -1) || !modeOk)
    return k.fail(fb, Error::HomingInvalidVelAcc, c);
  // The modes that go on in the search direction after the switch need the limit switch there.
  const DriveConfig& dc = ax.config().drive;
  const bool limitThere = in.direction > 0 ? dc.hasLimitPositive : dc.hasLimitNegative;
  if (in.mode >= 4 && (in.ignoreHwLimit || !limitThere)) return k.fail(fb, Error::HomingModeNeedsHwLimit, c);
  if (Error e = k.motionStateError(ax); e != Error::None) return k.fail(fb, e, c);
  if (ax.state() != AxisState::Standstill || ax.controller) return k.fail(fb, Error::NotReadyForMotion, c);
  if (dc.kind == AxisKind::Encoder) return k.fail(fb, Error::NotReadyForMotion, c);
  b.in = in;
  fb.in = MoveInputs{};
  k.accept(fb, ax, c);
}

// ---------------------------------------------------------------- SMC_Home (Leadshine)

namespace {

class SmcHomeFb final : public FbBehaviour {
public:
  enum class Step : uint8_t {
    SearchFast,    // in dir at fast speed until the home switch closes
    LeaveSlow,     // in -dir at slow speed until it opens
    SearchSlow,    // in dir at slow speed until it closes
    IndexSame,     // in dir at slow speed until an index pulse
    IndexReverse,  // in -dir at slow speed until an index pulse
    Stop, Return, Settle, MoveHome, Abort,
  };
  SmcHomeInputs in;
  std::vector<Step> program;
  size_t pc = 0;
  int8_t dir = 1;
  int reversals = 0;
  bool latchEdges = false;
  bool prevSwitch = false, fresh = false;
  double ref = 0;
  int64_t settle = 0;

  Limits lim(double v, const Axis& ax) const { return ax.limitsFor(v, in.acceleration, in.deceleration, in.jerk); }
  Step step() const { return program[pc]; }

  void begin(Axis& ax, int64_t nowNs) {
    ax.sample(nowNs);
    fresh = true;
    switch (step()) {
      case Step::SearchFast: ax.startVelocity(dir * in.velocityFast, lim(in.velocityFast, ax), nowNs); break;
      case Step::LeaveSlow:
      case Step::IndexReverse: ax.startVelocity(-dir * in.velocitySlow, lim(in.velocitySlow, ax), nowNs); break;
      case Step::SearchSlow:
      case Step::IndexSame: ax.startVelocity(dir * in.velocitySlow, lim(in.velocitySlow, ax), nowNs); break;
      case Step::Stop:
      case Step::Abort: ax.startStop(lim(std::max(std::fabs(ax.set().v), 1e-9), ax), nowNs); break;
      case Step::Return: ax.startPosition(ref, 0, lim(in.velocitySlow, ax), nowNs); break;
      case Step::MoveHome: ax.startPosition(ref + in.homePosition, 0, lim(in.velocitySlow, ax), nowNs); break;
      case Step::Settle: settle = 0; break;
    }
  }
  void next(Axis& ax, int64_t nowNs) {
    ++pc;
    begin(ax, nowNs);
  }
  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    pc = 0;
    reversals = 0;
    dir = static_cast<int8_t>(in.direction);
    prevSwitch = ax.drive().homeSwitchActive();
    ax.setState(AxisState::Homing);
    begin(ax, nowNs);
  }
  void finishHome(Kernel& k, Axis& ax, int64_t nowNs, uint64_t cycle) {
    if (in.completeMode != 0) ax.shiftPosition(-ax.set().p);   // the current position becomes 0
    k.completeCommand(ax, nowNs, cycle, 0);
  }
  void beforeStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override {
    (void)fb;
    const Drive& d = ax.drive();
    const bool sw = d.homeSwitchActive();
    const bool closed = sw && !prevSwitch, opened = !sw && prevSwitch;
    prevSwitch = sw;
    const Step s = step();
    // The latched edge: the switch boundary the actual position crossed in the last cycle.
    const double move = d.actPosition() - d.prevPosition();
    const DriveConfig& c = d.config();
    auto latched = [&](bool entering) {
      if (!latchEdges) return d.actPosition();
      return ((entering == (move > 0)) ? c.homeSwitchLow : c.homeSwitchHigh) + d.coordinateShift();
    };
    // The direction the step moves in (0: not a search step).
    const int intended = s == Step::SearchFast || s == Step::SearchSlow || s == Step::IndexSame ? dir
                         : s == Step::LeaveSlow || s == Step::IndexReverse ? -dir : 0;
    const bool wasFresh = fresh;
    fresh = false;
    if (intended != 0 && in.limitsEnable && ax.set().v * intended > 0 &&
        (intended > 0 ? d.limitPositiveActive() : d.limitNegativeActive())) {
      if (s != Step::SearchFast || ++reversals > 1) return k.errorStop(ax, Error::HwLimitsExceeded, nowNs, cycle);
      // Limit in the search direction: stop (at once, or with the deceleration) and search the other way.
      ax.sample(nowNs);
      if (!in.limitDecelerate) ax.holdAt(ax.set().p);
      dir = static_cast<int8_t>(-dir);
      return begin(ax, nowNs);
    }
    double at = 0;
    switch (s) {
      case Step::SearchFast:
      case Step::SearchSlow:
        if (closed && move * dir > 0) {
          ref = latched(true);
          next(ax, nowNs);
        } else if (sw && wasFresh && pc == 0) {
          ref = d.actPosition();   // already on the switch at the start
          next(ax, nowNs);
        }
        break;
      case Step::LeaveSlow:
        if (opened && ax.set().v * dir < 0) {
          ref = latched(false);
          next(ax, nowNs);
        }
        break;
      case Step::IndexSame:
      case Step::IndexReverse:
        if (d.indexPassed(at) && move * (s == Step::IndexSame ? dir : -dir) > 0) {
          ref = at;
          next(ax, nowNs);
        }
        break;
      case Step::Settle:
        if (++settle >= in.driverCounter) settled(k, ax, nowNs, cycle);
        break;
      default: break;
    }
  }
  // At rest at the home point for iDriverCounter cycles.
  void settled(Kernel& k, Axis& ax, int64_t nowNs, uint64_t cycle) {
    if (in.completeMode == 2) return next(ax, nowNs);
    finishHome(k, ax, nowNs, cycle);
  }
  void reached(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle, double) override {
    switch (step()) {
      case Step::Stop: next(ax, nowNs); break;
      case Step::Return:
        next(ax, nowNs);
        if (in.driverCounter == 0) settled(k, ax, nowNs, cycle);
        break;
      case Step::MoveHome: finishHome(k, ax, nowNs, cycle); break;
      case Step::Abort:
        ax.setState(AxisState::Standstill);
        k.finish(fb, nullptr, cycle, false, true, Error::None);
        break;
      default: break;
    }
  }
  void abort(Axis& ax, int64_t nowNs) {
    program.assign({Step::Abort});
    pc = 0;
    begin(ax, nowNs);
  }
};

bool programOf(int mode, std::vector<SmcHomeFb::Step>& p, bool& latch) {
  using S = SmcHomeFb::Step;
  latch = mode >= 6 && mode != 8;
  switch (mode) {
    case 0: case 6: p = {S::SearchFast}; break;
    case 1: p = {S::SearchFast, S::LeaveSlow}; break;
    case 2: case 10: p = {S::SearchFast, S::LeaveSlow, S::SearchSlow}; break;
    case 7: p = {S::SearchFast, S::IndexSame}; break;
    case 8: p = {S::IndexSame}; break;
    case 9: p = {S::SearchFast, S::IndexReverse}; break;
    default: return false;
  }
  p.insert(p.end(), {S::Stop, S::Return, S::Settle, S::MoveHome});
  return true;
}

}  // namespace

void callSmcHome(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const SmcHomeInputs& in, const CallCtx& c) {
  if (!dynamic_cast<SmcHomeFb*>(fb.behaviour.get())) fb.behaviour = std::make_unique<SmcHomeFb>();
  auto& b = static_cast<SmcHomeFb&>(*fb.behaviour);
  const bool wasExecute = fb.execute;
  const bool rising = k.beginExecute(fb, execute, c) && !in.stop;
  if (ax.controller == &fb && fb.out.busy && (in.stop || (!execute && wasExecute)) && b.step() != SmcHomeFb::Step::Abort) {
    // bStop, or the level-held bExecute released: stop; CommandAborted once the axis is at rest.
    b.abort(ax, c.nowNs);
  }
  if (!rising) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  const bool jerkOk = ax.acceptsJerk(in.jerk);
  std::vector<SmcHomeFb::Step> program;
  bool latch = false;
  if (!finitePositive(in.velocityFast) || !finitePositive(in.velocitySlow) || !finitePositive(in.acceleration) ||
      !finitePositive(in.deceleration) || !jerkOk || !std::isfinite(in.homePosition) || (in.direction != 1 && in.direction != -1) ||
      in.completeMode < 0 || in.completeMode > 2 || in.driverCounter < 0 || !programOf(in.mode, program, latch))
    return k.fail(fb, Error::HomingInvalidVelAcc, c);
  if (ax.state() == AxisState::ErrorStop) return k.fail(fb, Error::HomeAxisInErrorStop, c);
  if (ax.state() != AxisState::Standstill || ax.controller || !ax.ready()) return k.fail(fb, Error::HomeAxisWasntStandstill, c);
  const DriveConfig& dc = ax.config().drive;
  const bool needsSwitch = in.mode != 8, needsIndex = in.mode == 7 || in.mode == 8 || in.mode == 9;
  if (dc.kind == AxisKind::Encoder || (needsSwitch && !dc.hasHomeSwitch) || (needsIndex && !(dc.indexPeriod > 0)))
    return k.fail(fb, Error::DiHomingError, c);
  b.in = in;
  b.program = std::move(program);
  b.latchEdges = latch;
  if (in.completeMode != 2) b.program.pop_back();   // no move to fHomePosition
  fb.in = MoveInputs{};
  k.accept(fb, ax, c);
}

}  // namespace stc::motion
