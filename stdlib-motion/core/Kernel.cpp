// Instruction semantics and the per-cycle step of the motion kernel.
// The timing rules implemented here are listed in docs/motion.md
// ("Timing rules"); each rule has a cycle-by-cycle test in
// tests/unit/motion/ and tests/run/motion_*.st.
#include "stdlib-motion/core/Kernel.h"

#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/group/GroupMotion.h"

#include <algorithm>
#include <cmath>

namespace stc::motion {

bool VendorProfile::named(std::string_view name, VendorProfile& out) {
  out = VendorProfile{};
  if (name == "amc1600c") return true;   // its manual: jog Busy falls at release
  if (name == "leadshine_pmc600") {
    out.jogBusyEndsAtRelease = false;    // the manual is silent: CODESYS SoftMotion's rule
    return true;
  }
  return false;
}

void Kernel::reset() {
  groups_.clear();   // first: groups point to axes
  encoders_.clear();
  axes_.clear();
  slots_.clear();
  stepNowNs_ = 0;
  callCounter = 0;
  profile = VendorProfile{};
}

AxisGroup& Kernel::addGroup() {
  groups_.push_back(std::make_unique<AxisGroup>(static_cast<uint32_t>(groups_.size())));
  return *groups_.back();
}

Axis& Kernel::addAxis(const AxisConfig& cfg) {
  axes_.push_back(std::make_unique<Axis>(cfg, static_cast<uint32_t>(axes_.size())));
  if (cfg.drive.kind == AxisKind::Encoder) encoders_.push_back(axes_.back().get());
  return *axes_.back();
}

FbSlot& Kernel::newSlot(uint64_t& handle, void* instance, FbKind kind, PublishFn publish) {
  slots_.push_back(std::make_unique<FbSlot>());
  FbSlot& s = *slots_.back();
  s.kind = kind;
  s.instance = instance;
  s.publish = publish;
  handle = slots_.size();
  return s;
}

bool Kernel::axisChangedSlow(FbSlot& fb, Axis& ax, const CallCtx& c) {
  Axis& old = *fb.axis;
  if (!fb.out.busy) {
    fb.axis = &ax;   // idle: the next command runs on the new axis
    return false;
  }
  const bool commands = old.controller == &fb || old.superimposer == &fb ||
                        std::find(old.queue.begin(), old.queue.end(), &fb) != old.queue.end();
  if (commands) {
    errorStop(old, Error::AxisRefChanged, c.nowNs, c.cycle);   // ends fb's command with error 32
    if (fb.out.busy) finish(fb, &c, c.cycle, false, false, Error::AxisRefChanged);
  } else {
    if (old.power == &fb) old.power = nullptr;
    finish(fb, &c, c.cycle, false, false, Error::AxisRefChanged);
  }
  return true;
}

// ---------------------------------------------------------------- output rules

namespace {

bool finitePositive(double x) { return bounds::rate(x); }   // accelerations, decelerations (and the Jog/Inch velocity)

bool isPositionMove(FbKind k) {
  return k == FbKind::MoveAbsolute || k == FbKind::MoveRelative || k == FbKind::MoveAdditive ||
         k == FbKind::MoveContinuousAbsolute || k == FbKind::MoveContinuousRelative || k == FbKind::Inch;
}
bool isContinuous(FbKind k) {
  return k == FbKind::MoveVelocity || k == FbKind::Jog || k == FbKind::MoveContinuousAbsolute || k == FbKind::MoveContinuousRelative;
}
bool isCoupling(FbKind k) { return k == FbKind::GearIn || k == FbKind::GearInPos || k == FbKind::CamIn || k == FbKind::Backlash; }
bool isBlending(BufferMode m) { return m >= BufferMode::BlendingLow && m <= BufferMode::BlendingHigh; }

// The error codes each move reports for bad dynamics / a bad direction.
struct MoveCodes { Error velAcc, direction, directionNotApplicable; };
MoveCodes codesOf(FbKind k) {
  switch (k) {
    case FbKind::MoveAbsolute: return {Error::MaInvalidVelAcc, Error::MaInvalidDirection, Error::MaInvalidDirection};
    case FbKind::MoveRelative: return {Error::MrInvalidVelAcc, Error::MrInvalidDirection, Error::MrInvalidDirection};
    case FbKind::MoveAdditive: return {Error::MadInvalidVelAcc, Error::MadInvalidDirection, Error::MadInvalidDirection};
    case FbKind::MoveSuperImposed: return {Error::MsiInvalidVelAcc, Error::MsiInvalidDirection, Error::MsiInvalidDirection};
    case FbKind::MoveVelocity: return {Error::MvInvalidAccDec, Error::MvDirectionNotApplicable, Error::MvDirectionNotApplicable};
    case FbKind::MoveContinuousAbsolute: return {Error::McaInvalidVelAcc, Error::McaInvalidDirection, Error::McaDirectionNotApplicable};
    case FbKind::MoveContinuousRelative: return {Error::McrInvalidVelAcc, Error::McrInvalidDirection, Error::McrInvalidDirection};
    case FbKind::Halt: case FbKind::Stop: return {Error::StopInvalidAccDec, Error::StopDirectionNotApplicable, Error::StopDirectionNotApplicable};
    default: return {Error::NotReadyForMotion, Error::NotReadyForMotion, Error::NotReadyForMotion};
  }
}

bool validDirection(Direction d) { int v = static_cast<int>(d); return v >= -1 && v <= 3; }

// Bad inputs of a move, in the order the checks are made.
Error validateMove(FbKind k, const MoveInputs& in, const Axis& ax) {
  const MoveCodes codes = codesOf(k);
  const bool jerkOk = ax.acceptsJerk(in.jerk);
  const bool velOk = k == FbKind::MoveVelocity ? bounds::signedVelocity(in.velocity) : bounds::velocity(in.velocity);
  if (!velOk || !finitePositive(in.acceleration) || !finitePositive(in.deceleration) || !jerkOk) return codes.velAcc;
  if (!bounds::position(in.position) || !bounds::position(in.distance)) return codes.velAcc;
  if (!validBufferMode(in.bufferMode)) return Error::InvalidBufferMode;
  switch (k) {
    case FbKind::MoveAbsolute:
      if (!validDirection(in.direction)) return codes.direction;
      break;
    case FbKind::MoveVelocity:
      if (!validDirection(in.direction)) return codes.direction;
      if (in.direction == Direction::Shortest || in.direction == Direction::Fastest) return codes.directionNotApplicable;
      break;
    case FbKind::MoveContinuousAbsolute:
    case FbKind::MoveContinuousRelative:
      if (!bounds::signedVelocity(in.endVelocity) || in.endVelocity < 0) return codes.velAcc;
      if (!validDirection(in.direction) || !validDirection(in.endDirection)) return codes.direction;
      if (in.endDirection == Direction::Shortest || in.endDirection == Direction::Fastest) return codes.directionNotApplicable;
      if (k == FbKind::MoveContinuousAbsolute && in.direction == Direction::Fastest) return codes.directionNotApplicable;
      if (!ax.isModulo() && k == FbKind::MoveContinuousAbsolute && in.direction != Direction::Positive &&
          in.direction != Direction::Negative && in.direction != Direction::Shortest)
        return codes.direction;
      break;
    default: break;
  }
  return Error::None;
}

}  // namespace

bool Kernel::beginExecute(FbSlot& fb, bool execute, const CallCtx& c) {
  const bool rising = execute && !fb.execute;
  fb.execute = execute;
  fb.lastCallCycle = c.cycle;
  fb.callSeq = ++callCounter;
  if (!execute && fb.out.terminal() && !fb.out.busy) {
    // A terminal output shown while Execute was TRUE resets with Execute; one
    // that rose with Execute already FALSE is visible for exactly one cycle.
    if (!fb.clearPending || c.cycle > fb.terminalCycle + 1) {
      fb.out.done = fb.out.error = fb.out.aborted = false;
      fb.out.errorId = Error::None;
      fb.clearPending = false;
    }
  }
  if (rising) {
    fb.out.done = fb.out.error = fb.out.aborted = false;
    fb.out.errorId = Error::None;
    fb.clearPending = false;
  }
  return rising;
}

void Kernel::finish(FbSlot& fb, const CallCtx* c, uint64_t cycle, bool done, bool aborted, Error e) {
  (void)c;
  fb.out.busy = fb.out.active = fb.out.inState = fb.out.startSync = fb.out.endOfProfile = false;
  fb.out.done = done;
  fb.out.aborted = aborted;
  fb.out.error = e != Error::None;
  fb.out.errorId = e;
  if (e != Error::None) noteFbError(fb, e, c ? c->nowNs : stepNowNs_);
  if (fb.axis) {
    Axis& ax = *fb.axis;
    if (ax.controller == &fb) ax.controller = nullptr;
    if (ax.superimposer == &fb) ax.superimposer = nullptr;
    if (ax.resetter == &fb) ax.resetter = nullptr;
    ax.queue.erase(std::remove(ax.queue.begin(), ax.queue.end(), &fb), ax.queue.end());
    if (!fb.execute) {
      fb.clearPending = true;
      fb.terminalCycle = cycle;
      ax.pendingClear.push_back(&fb);
    }
  }
  fb.sync();
}

void Kernel::fail(FbSlot& fb, Error e, const CallCtx& c) {
  fb.out.busy = fb.out.active = fb.out.inState = false;
  fb.out.done = fb.out.aborted = false;
  fb.out.error = true;
  fb.out.errorId = e;
  noteFbError(fb, e, c.nowNs);
  fb.sync();
}

void Kernel::noteFbError(FbSlot& fb, Error e, int64_t nowNs) {
  if (!fb.axis || e == Error::None) return;
  fb.axis->fbError = FbErrorRecord{true, e, fb.instance, nowNs};
}

// The axis refuses motion commands in these states (error per state).
Error Kernel::motionStateError(const Axis& ax) const {
  const VendorProfile& vp = profile;
  switch (ax.state()) {
    case AxisState::PowerOff: return Error::RegulatorOrStartNotSet;
    case AxisState::ErrorStop: return Error::NotReadyForMotion;
    case AxisState::Homing: return Error::NotReadyForMotion;
    case AxisState::Stopping:
      // Still braking: not ready; braked but held by an MC_Stop whose Execute is TRUE: 184.
      return ax.blockingStop && ax.blockingStop->out.done ? Error::BlockingStopWasntCalled : Error::NotReadyForMotion;
    case AxisState::SynchronizedMotion: return vp.movesAbortSynchronized ? Error::None : Error::NotReadyForMotion;
    default: break;
  }
  if (ax.drive().modeOfOperation() == 10) return Error::WrongControllerMode;   // torque control: no set-point motion
  if (!ax.ready()) return Error::RegulatorOrStartNotSet;
  return Error::None;
}

// Ends the command in control and every buffered one with CommandAborted
// (Error e instead when given: ErrorStop aborts with Error).
void Kernel::abortController(Axis& ax, uint64_t cycle, Error e) {
  std::vector<FbSlot*> victims;
  if (ax.controller) victims.push_back(ax.controller);
  victims.insert(victims.end(), ax.queue.begin(), ax.queue.end());
  ax.controller = nullptr;
  ax.queue.clear();
  for (FbSlot* v : victims) finish(*v, nullptr, cycle, false, e == Error::None, e);
}

// ---------------------------------------------------------------- starting commands

// Starts fb's command on ax at time nowNs (+frac seconds for a blended hand-over).
void Kernel::startCommand(FbSlot& fb, Axis& ax, int64_t nowNs, double frac) {
  if (frac == 0) ax.sample(nowNs);
  ax.controller = &fb;
  ax.master = nullptr;   // a new command in control ends any coupling (couplings set it again)
  fb.axis = &ax;
  fb.out.busy = fb.out.active = true;
  fb.out.inState = false;
  if (fb.behaviour) {
    fb.behaviour->start(*this, fb, ax, nowNs);
    fb.sync();
    return;
  }
  const MoveInputs& in = fb.in;
  Limits lim = ax.limitsFor(std::fabs(in.velocity), in.acceleration, in.deceleration, in.jerk);
  const double startPos = frac != 0 && ax.movement().kind != Movement::Kind::None ? fb.target : ax.set().p;
  // Hand-over velocity to a blending successor (PLCopen Part 1, buffer modes).
  double vEnd = 0;
  auto plannedEnd = [&](double target) {
    if (isContinuous(fb.kind)) return fb.endVelocity;
    if (ax.queue.empty() || !isBlending(ax.queue.front()->in.bufferMode)) return 0.0;
    FbSlot& next = *ax.queue.front();
    const double dir1 = target - startPos;
    double dir2 = 0, v2 = std::fabs(next.in.velocity);
    if (next.kind == FbKind::MoveVelocity) dir2 = next.in.velocity * (next.in.direction == Direction::Negative ? -1 : 1);
    else if (next.kind == FbKind::MoveAbsolute) dir2 = next.in.position - target;
    else dir2 = next.in.distance;
    if (dir1 == 0 || dir2 == 0 || (dir1 > 0) != (dir2 > 0)) return 0.0;   // reversal: no blending velocity
    const double v1 = std::fabs(in.velocity);
    double vb = 0;
    switch (next.in.bufferMode) {
      case BufferMode::BlendingLow: vb = std::min(v1, v2); break;
      case BufferMode::BlendingPrevious: vb = v1; break;
      case BufferMode::BlendingNext: vb = v2; break;
      default: vb = std::max(v1, v2); break;
    }
    return dir1 > 0 ? vb : -vb;
  };
  switch (fb.kind) {
    case FbKind::MoveAbsolute:
    case FbKind::MoveContinuousAbsolute: {
      double target = 0;
      ax.absoluteTarget(in.position, in.direction, target);
      if (fb.kind == FbKind::MoveContinuousAbsolute) {
        const double sign = in.endDirection == Direction::Negative ? -1 : in.endDirection == Direction::Positive ? 1
                            : (target >= startPos ? 1 : -1);
        fb.endVelocity = sign * std::fabs(in.endVelocity);
      }
      fb.target = target;
      vEnd = plannedEnd(target);
      break;
    }
    case FbKind::MoveRelative:
    case FbKind::MoveContinuousRelative:
    case FbKind::Inch: {
      fb.target = startPos + in.distance;
      if (fb.kind == FbKind::MoveContinuousRelative) {
        const double sign = in.endDirection == Direction::Negative ? -1 : in.endDirection == Direction::Positive ? 1
                            : (in.distance >= 0 ? 1 : -1);
        fb.endVelocity = sign * std::fabs(in.endVelocity);
      }
      vEnd = plannedEnd(fb.target);
      break;
    }
    case FbKind::MoveAdditive:
      // In discrete motion: adds to the previously commanded target; otherwise relative to the set position.
      fb.target = (ax.state() == AxisState::DiscreteMotion ? ax.lastCommandedTarget : startPos) + in.distance;
      vEnd = plannedEnd(fb.target);
      break;
    default: break;
  }
  if (std::fabs(vEnd) > lim.vel) lim.vel = std::fabs(vEnd);
  if (fb.kind == FbKind::MoveVelocity || fb.kind == FbKind::Jog) lim.vel = std::max(std::fabs(fb.endVelocity), 1e-9);
  switch (fb.kind) {
    case FbKind::MoveVelocity:
    case FbKind::Jog: {
      double v = fb.endVelocity;
      ax.startVelocity(v, lim, nowNs, frac);
      ax.setState(AxisState::ContinuousMotion);
      break;
    }
    case FbKind::Halt:
      ax.startStop(lim, nowNs);
      ax.setState(AxisState::DiscreteMotion);
      break;
    case FbKind::Stop:
      ax.startStop(lim, nowNs);
      ax.setState(AxisState::Stopping);
      break;
    default:
      ax.startPosition(fb.target, vEnd, lim, nowNs, frac);
      ax.lastCommandedTarget = fb.target;
      ax.setState(AxisState::DiscreteMotion);
      break;
  }
  fb.sync();
}

// The command of fb was accepted in this call: Aborting starts it now (the
// running command ends with CommandAborted in this cycle); the other buffer
// modes queue it behind the running one.
void Kernel::accept(FbSlot& fb, Axis& ax, const CallCtx& c) {
  fb.axis = &ax;
  if (!validBufferMode(fb.in.bufferMode)) {   // a number outside MC_BUFFER_MODE: refused, never run as another mode
    fail(fb, Error::InvalidBufferMode, c);
    return;
  }
  const bool idle = !ax.controller && ax.queue.empty();
  if (fb.in.bufferMode == BufferMode::Aborting || idle || ax.controller == &fb) {
    if (ax.controller && ax.controller != &fb) {
      FbSlot* old = ax.controller;
      ax.controller = nullptr;
      finish(*old, &c, c.cycle, false, true, Error::None);
    }
    while (!ax.queue.empty()) finish(*ax.queue.front(), &c, c.cycle, false, true, Error::None);
    startCommand(fb, ax, c.nowNs, 0);
    return;
  }
  FbSlot* prev = ax.queue.empty() ? ax.controller : ax.queue.back();
  if (isBlending(fb.in.bufferMode) && prev && (isContinuous(prev->kind) || isCoupling(prev->kind) || prev->kind == FbKind::Halt)) {
    fail(fb, Error::BlendingNotSupportedByPrevious, c);
    return;
  }
  if (ax.queue.size() >= profile.queueCapacity) {
    fail(fb, Error::BufferFull, c);
    return;
  }
  ax.queue.push_back(&fb);
  fb.out.busy = true;
  fb.out.active = false;
  // A blending successor of the running move changes its end velocity: replan it now.
  if (isBlending(fb.in.bufferMode) && ax.queue.size() == 1 && ax.controller && isPositionMove(ax.controller->kind) &&
      !isContinuous(ax.controller->kind)) {
    FbSlot& cur = *ax.controller;
    ax.sample(c.nowNs);
    const double keepTarget = cur.target;
    startCommand(cur, ax, c.nowNs, 0);
    (void)keepTarget;
  }
  fb.sync();
}

// ---------------------------------------------------------------- instructions

void Kernel::callPower(FbSlot& fb, Axis& ax, bool enable, bool regulatorOn, bool driveStart, const CallCtx& c) {
  const bool rising = enable && !fb.execute;
  fb.execute = enable;
  fb.lastCallCycle = c.cycle;
  fb.axis = &ax;
  if (!enable) {
    // The FB stops processing its inputs; the axis keeps its power state.
    fb.out = FbOutputs{};
    fb.sync();
    return;
  }
  if (rising || (regulatorOn && !ax.powerRequested())) fb.sinceNs = c.nowNs;
  ax.power = &fb;
  if (c.intervalNs <= 0) {
    fail(fb, Error::PowerTaskCycleEmpty, c);
    return;
  }
  ax.requestPower(regulatorOn, driveStart, c.nowNs);
  updatePower(ax, c.nowNs, c.cycle);
}

// Power follow-up, in the call of MC_Power and in every step of the axis.
void Kernel::updatePower(Axis& ax, int64_t nowNs, uint64_t cycle) {
  if (ax.state() != AxisState::ErrorStop) {
    if (!ax.powerRequested() && ax.state() != AxisState::PowerOff) {
      // Regulator switched off: the axis is disabled where it stands; a command in control ends with error 33.
      if (ax.controller || !ax.queue.empty()) abortController(ax, cycle, Error::FbActiveAxisDisabled);
      ax.holdAt(ax.actPosition());
      ax.setState(AxisState::PowerOff);
    } else if (ax.operational() && ax.powerRequested() && ax.state() == AxisState::PowerOff) {
      ax.holdAt(ax.actPosition());
      ax.setState(AxisState::Standstill);
    }
    if (ax.operational() && !ax.driveStart() && (ax.controller || !ax.queue.empty())) {
      // Quick stop (bDriveStart FALSE): the command in control ends with error 20, the axis brakes.
      abortController(ax, cycle, Error::RegulatorOrStartNotSet);
      const double dec = ax.config().errorDeceleration > 0 ? ax.config().errorDeceleration
                         : ax.config().maxDeceleration > 0 ? ax.config().maxDeceleration : 1000.0;
      ax.sample(nowNs);
      ax.startStop(Limits{1, dec, dec, 0}, nowNs);
      ax.setState(AxisState::Stopping);
    }
  }
  if (FbSlot* p = ax.power; p && p->execute) {
    p->out.busy = true;
    p->out.regulatorRealState = ax.operational();
    p->out.driveStartRealState = ax.operational() && ax.driveStart();
    p->out.status = ax.ready() && ax.state() != AxisState::PowerOff;
    // The axis error is shown by MC_Power while the axis is in ErrorStop.
    const bool timeout = ax.powerRequested() && ax.driveStart() && !ax.operational() && nowNs - p->sinceNs > kPowerTimeoutNs;
    p->out.error = ax.state() == AxisState::ErrorStop || timeout;
    p->out.errorId = ax.state() == AxisState::ErrorStop ? ax.error() : timeout ? Error::VoltageDisabled : Error::None;
    p->sync();
  }
}

void Kernel::callReset(FbSlot& fb, Axis& ax, bool execute, const CallCtx& c) {
  if (!beginExecute(fb, execute, c)) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  if (ax.state() != AxisState::ErrorStop && !ax.drive().faulted()) return fail(fb, Error::ResetNoErrorToReset, c);
  if (!ax.drive().communication()) return fail(fb, Error::ResetDriveDoesntAnswer, c);
  ax.clearError();
  ax.resetter = &fb;
  fb.out.busy = true;
  completeReset(ax, c.cycle);
  fb.sync();
}

// MC_Reset completes once the drive has left its fault state and the set point is at rest.
void Kernel::completeReset(Axis& ax, uint64_t cycle) {
  FbSlot* r = ax.resetter;
  if (!r || ax.drive().faulted() || !ax.atRest()) return;
  if (ax.powerRequested() && !ax.operational() && ax.config().drive.kind == AxisKind::Servo) return;  // re-enabling
  ax.setState(ax.operational() && ax.powerRequested() ? AxisState::Standstill : AxisState::PowerOff);
  finish(*r, nullptr, cycle, true, false, Error::None);
}

void Kernel::callMove(FbSlot& fb, Axis& ax, bool execute, const MoveInputs& in, const CallCtx& c) {
  if (!beginExecute(fb, execute, c)) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  if (Error e = validateMove(fb.kind, in, ax); e != Error::None) return fail(fb, e, c);
  if (Error e = motionStateError(ax); e != Error::None) return fail(fb, e, c);
  if (ax.config().drive.kind == AxisKind::Encoder) return fail(fb, Error::NotReadyForMotion, c);
  fb.in = in;
  if (fb.kind == FbKind::MoveVelocity) {
    // Velocity and Direction give the sign (a negative velocity in the negative direction is positive).
    double sign = 1;
    if (in.direction == Direction::Negative) sign = -1;
    else if (in.direction == Direction::Current) sign = ax.set().v < 0 ? -1 : 1;
    fb.endVelocity = sign * in.velocity;
  }
  if (fb.kind == FbKind::MoveSuperImposed) {
    if (ax.state() == AxisState::Standstill && !ax.controller) {
      // In standstill it is a relative move.
      fb.kind = FbKind::MoveRelative;
      accept(fb, ax, c);
      fb.kind = FbKind::MoveSuperImposed;
      return;
    }
    // Not supported on profile tables (the manual gives no code: 34, the axis is not ready for it).
    if (ax.controller && ax.controller->kind == FbKind::Profile) return fail(fb, Error::NotReadyForMotion, c);
    if (ax.superimposer && ax.superimposer != &fb) finish(*ax.superimposer, &c, c.cycle, false, true, Error::None);
    ax.sample(c.nowNs);
    ax.startSuperimposed(in.distance, ax.limitsFor(std::fabs(in.velocity), in.acceleration, in.deceleration, in.jerk), c.nowNs);
    ax.superimposer = &fb;
    fb.out.busy = fb.out.active = true;
    fb.sync();
    return;
  }
  accept(fb, ax, c);
}

void Kernel::callHalt(FbSlot& fb, Axis& ax, bool execute, const MoveInputs& in, const CallCtx& c) {
  if (!beginExecute(fb, execute, c)) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  if (!finitePositive(in.deceleration) || !ax.acceptsJerk(in.jerk)) return fail(fb, Error::StopInvalidAccDec, c);
  if (Error e = motionStateError(ax); e != Error::None) return fail(fb, e, c);
  fb.in = in;
  fb.in.velocity = std::max(std::fabs(ax.set().v), 1e-9);
  fb.in.acceleration = in.deceleration;
  accept(fb, ax, c);
}

void Kernel::callStop(FbSlot& fb, Axis& ax, bool execute, const MoveInputs& in, const CallCtx& c) {
  const bool wasExecute = fb.execute, wasDone = fb.out.done;
  const bool rising = beginExecute(fb, execute, c);
  if (!execute && wasExecute && ax.blockingStop == &fb && wasDone && ax.state() == AxisState::Stopping) {
    // Stopping -> Standstill: Done and Execute FALSE (state diagram *6).
    ax.blockingStop = nullptr;
    ax.setState(AxisState::Standstill);
  }
  if (!rising) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  if (ax.state() == AxisState::ErrorStop) return fail(fb, Error::StopAxisInErrorStop, c);
  if (ax.blockingStop && ax.blockingStop != &fb) return fail(fb, Error::BlockingStopWasntCalled, c);
  if (!finitePositive(in.deceleration) || !ax.acceptsJerk(in.jerk)) return fail(fb, Error::StopInvalidAccDec, c);
  if (ax.state() == AxisState::PowerOff) return fail(fb, Error::RegulatorOrStartNotSet, c);
  if (ax.drive().modeOfOperation() == 10) return fail(fb, Error::WrongControllerMode, c);   // torque control
  fb.in = in;
  fb.in.velocity = std::max(std::fabs(ax.set().v), 1e-9);
  fb.in.acceleration = in.deceleration;
  // MC_Stop aborts everything, including a superimposed move, and blocks the axis.
  if (ax.superimposer) finish(*ax.superimposer, &c, c.cycle, false, true, Error::None);
  if (ax.controller != &fb) {
    FbSlot* old = ax.controller;
    ax.controller = nullptr;
    if (old) finish(*old, &c, c.cycle, false, true, Error::None);
  }
  while (!ax.queue.empty()) finish(*ax.queue.front(), &c, c.cycle, false, true, Error::None);
  ax.blockingStop = &fb;
  startCommand(fb, ax, c.nowNs, 0);
}

void Kernel::callJog(FbSlot& fb, Axis& ax, bool forward, bool backward, const MoveInputs& in, const CallCtx& c) {
  fb.lastCallCycle = c.cycle;
  fb.callSeq = ++callCounter;
  fb.axis = &ax;
  const int8_t want = forward == backward ? 0 : forward ? 1 : -1;
  if (want == 0 && fb.out.error) {
    // Errors of a level-controlled FB last while its inputs do.
    fb.out.error = false;
    fb.out.errorId = Error::None;
  }
  if (want == 0 && !fb.out.busy) fb.out.aborted = false;
  if (want != 0 && fb.levelDir != want && !fb.out.error) {
    fb.out.aborted = false;
    MoveInputs i = in;
    if (!bounds::velocity(in.velocity) || !finitePositive(in.acceleration) || !finitePositive(in.deceleration) || !ax.acceptsJerk(in.jerk)) {
      fb.levelDir = want;
      return fail(fb, Error::MvInvalidAccDec, c);
    }
    if (Error e = motionStateError(ax); e != Error::None) {
      fb.levelDir = want;
      return fail(fb, e, c);
    }
    fb.in = i;
    fb.in.bufferMode = BufferMode::Aborting;
    fb.endVelocity = want * in.velocity;
    fb.levelDir = want;
    accept(fb, ax, c);
    return;
  }
  if (want == 0 && fb.levelDir != 0) {
    fb.levelDir = 0;
    if (ax.controller == &fb) {
      // Release: decelerate to a stop.
      Limits lim = ax.limitsFor(std::max(std::fabs(ax.set().v), 1e-9), fb.in.deceleration, fb.in.deceleration, fb.in.jerk);
      ax.sample(c.nowNs);
      ax.startStop(lim, c.nowNs);
      ax.setState(AxisState::DiscreteMotion);
      if (profile.jogBusyEndsAtRelease) {
        ax.controller = nullptr;   // the ramp runs on without an FB in control
        fb.out.busy = fb.out.active = false;
      }
    }
  }
  fb.sync();
}

void Kernel::callInch(FbSlot& fb, Axis& ax, bool forward, bool backward, const MoveInputs& in, const CallCtx& c) {
  fb.lastCallCycle = c.cycle;
  fb.callSeq = ++callCounter;
  fb.axis = &ax;
  const int8_t want = forward == backward ? 0 : forward ? 1 : -1;
  const bool rising = want != 0 && fb.levelDir == 0;
  if (want == 0 && fb.levelDir != 0) {
    fb.levelDir = 0;
    if (fb.out.error) {
      fb.out.error = false;
      fb.out.errorId = Error::None;
    }
    if (ax.controller == &fb && ax.movement().kind != Movement::Kind::None) {
      // Released before the step is done: brake at once; Busy falls at standstill.
      ax.sample(c.nowNs);
      ax.startStop(ax.limitsFor(std::max(std::fabs(ax.set().v), 1e-9), fb.in.deceleration, fb.in.deceleration, fb.in.jerk), c.nowNs);
    } else if (fb.out.done) {
      fb.out.done = false;
    }
  }
  if (rising) {
    fb.levelDir = want;
    fb.out.done = fb.out.error = fb.out.aborted = false;
    fb.out.errorId = Error::None;
    if (!bounds::velocity(in.velocity) || !finitePositive(in.acceleration) || !finitePositive(in.deceleration) ||
        !ax.acceptsJerk(in.jerk) || !bounds::position(in.distance))
      return fail(fb, Error::MrInvalidVelAcc, c);
    if (Error e = motionStateError(ax); e != Error::None) return fail(fb, e, c);
    fb.in = in;
    fb.in.distance = want * std::fabs(in.distance);
    fb.in.bufferMode = BufferMode::Aborting;
    accept(fb, ax, c);
    return;
  }
  fb.sync();
}

void Kernel::callSetPosition(FbSlot& fb, Axis& ax, bool execute, double position, bool relative, const CallCtx& c) {
  if (!beginExecute(fb, execute, c)) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  // Beyond the position bound (or a shift that would leave it) it is refused: never an Inf/NaN position.
  if (!bounds::position(position)) return fail(fb, Error::NotReadyForMotion, c);
  ax.sample(c.nowNs);
  const double delta = relative ? position : position - ax.reportPosition(ax.set().p);
  if (!bounds::position(ax.set().p + delta) || !bounds::position(ax.actPosition() + delta)) return fail(fb, Error::NotReadyForMotion, c);
  ax.shiftPosition(delta);
  finish(fb, &c, c.cycle, true, false, Error::None);
}

// ---------------------------------------------------------------- the cycle

void Kernel::cycle(uint32_t task, int64_t nowNs, int64_t intervalNs, uint64_t cycle) {
  const double dt = static_cast<double>(intervalNs) * 1e-9;
  stepNowNs_ = nowNs;
  // Encoder-only axes are inputs: they are stepped first, so every axis that
  // follows one sees its value of this cycle, whatever the order of the axes.
  // Groups first write their members' set states of this cycle.
  for (auto& g : groups_)
    if (g->task == task) groupBeforeStep(*this, *g, nowNs, intervalNs, cycle);
  stepped_.assign(axes_.size(), 0);
  for (Axis* a : encoders_)
    if (a->task == task) {
      stepped_[a->index()] = 1;
      stepAxis(*a, nowNs, dt, cycle);
      a->trackActual();
    }
  // Then masters before their slaves (Axis::master), whatever order the axes were added in;
  // a master of another task is stepped by that task.
  for (auto& a : axes_) {
    chain_.clear();
    for (Axis* x = a.get(); x && x->task == task && !stepped_[x->index()]; x = x->master) {
      stepped_[x->index()] = 1;
      chain_.push_back(x);
    }
    for (size_t i = chain_.size(); i-- > 0;) stepAxis(*chain_[i], nowNs, dt, cycle);
  }
  for (auto& g : groups_)
    if (g->task == task) groupAfterStep(*this, *g, nowNs, cycle);
}

void Kernel::errorStop(Axis& ax, Error e, int64_t nowNs, uint64_t cycle) {
  if (ax.state() == AxisState::ErrorStop) return;
  abortController(ax, cycle, e);
  if (ax.superimposer) finish(*ax.superimposer, nullptr, cycle, false, false, e);
  if (ax.blockingStop) {
    FbSlot* s = ax.blockingStop;
    ax.blockingStop = nullptr;
    if (s->out.busy) finish(*s, nullptr, cycle, false, false, e);
  }
  ax.master = nullptr;
  ax.phase.moving = false;
  ax.enterErrorStop(e, nowNs);
}

void Kernel::stepAxis(Axis& ax, int64_t nowNs, double dt, uint64_t cycle) {
  // A command in control must be called in every cycle until its motion ends.
  if (FbSlot* fb = ax.controller; fb && fb->out.busy && fb->lastCallCycle != cycle && fb->kind != FbKind::Stop && !fb->functionStyle)
    errorStop(ax, Error::FbWasntCalledDuringMotion, nowNs, cycle);
  if (FbSlot* fb = ax.controller; fb && fb->behaviour) fb->behaviour->beforeStep(*this, *fb, ax, nowNs, cycle);
  StepResult r = ax.step(nowNs, dt);
  if (r.error != Error::None) errorStop(ax, r.error, nowNs, cycle);
  if (r.superimposedReached && ax.superimposer) finish(*ax.superimposer, nullptr, cycle, true, false, Error::None);
  if (r.reached) onReached(ax, nowNs, cycle, r.overshoot);
  // Without a command in control, a motion state ends when the set point is at rest.
  if (!ax.controller && ax.atRest() &&
      (ax.state() == AxisState::DiscreteMotion || ax.state() == AxisState::ContinuousMotion ||
       (ax.state() == AxisState::Stopping && !ax.blockingStop)))
    ax.setState(AxisState::Standstill);
  for (size_t i = 0; i < ax.observers.size(); ++i) {
    FbSlot* o = ax.observers[i];
    if (o->behaviour) o->behaviour->afterStep(*this, *o, ax, nowNs, cycle);
  }
  updatePower(ax, nowNs, cycle);
  completeReset(ax, cycle);
  // Terminal outputs that rose with Execute FALSE were visible for one cycle.
  if (!ax.pendingClear.empty()) {
    size_t keep = 0;
    for (FbSlot* fb : ax.pendingClear) {
      bool again = false;
      // An EndOfProfile pulse raised at a buffered handover (the coupling no longer steps it).
      if (fb->out.endOfProfile && !fb->out.busy) {
        if (cycle > fb->endOfProfileCycle) {
          fb->out.endOfProfile = false;
          fb->sync();
        } else {
          again = true;
        }
      }
      if (fb->clearPending) {
        if (cycle > fb->terminalCycle && !fb->execute && !fb->out.busy) {
          fb->out.done = fb->out.error = fb->out.aborted = false;
          fb->out.errorId = Error::None;
          fb->clearPending = false;
          fb->sync();
        } else {
          again = true;
        }
      }
      if (again) ax.pendingClear[keep++] = fb;
    }
    ax.pendingClear.resize(keep);
  }
}

void FbBehaviour::reached(Kernel& k, FbSlot&, Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot) {
  k.completeCommand(ax, nowNs, cycle, overshoot);
}

void Kernel::onReached(Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot) {
  FbSlot* fb = ax.controller;
  if (!fb) return;
  if (fb->behaviour) return fb->behaviour->reached(*this, *fb, ax, nowNs, cycle, overshoot);
  if (fb->kind == FbKind::Jog && fb->levelDir == 0) {
    // A released jog whose Busy lasts until standstill (vendor profile): it ends here.
    ax.controller = nullptr;
    fb->out.busy = fb->out.active = fb->out.inState = false;
    fb->sync();
    return;
  }
  switch (fb->kind) {
    case FbKind::MoveVelocity:
    case FbKind::Jog:
    case FbKind::MoveContinuousAbsolute:
    case FbKind::MoveContinuousRelative:
      // InVelocity / InEndVelocity: a level output; the FB stays Busy until aborted.
      fb->out.inState = true;
      if (fb->kind != FbKind::Jog) ax.setState(AxisState::ContinuousMotion);
      fb->sync();
      if (!ax.queue.empty() && fb->kind != FbKind::Jog) {
        // A buffered successor of a continuous move starts when it is in velocity.
        FbSlot* next = ax.queue.front();
        ax.queue.erase(ax.queue.begin());
        ax.controller = nullptr;
        finish(*fb, nullptr, cycle, false, true, Error::None);
        startCommand(*next, ax, nowNs, 0);
        next->out.active = true;
        next->sync();
      }
      return;
    case FbKind::Stop:
      ax.controller = nullptr;
      finish(*fb, nullptr, cycle, true, false, Error::None);
      if (!fb->execute) {
        ax.blockingStop = nullptr;
        ax.setState(AxisState::Standstill);
      }
      return;
    default: break;
  }
  completeCommand(ax, nowNs, cycle, overshoot);
}

// Position moves and MC_Halt: Done at the target (velocity 0) or at the hand-over velocity.
void Kernel::completeCommand(Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot) {
  FbSlot* fb = ax.controller;
  if (!fb) return;
  ax.controller = nullptr;
  const bool blended = ax.movement().kind != Movement::Kind::None && ax.movement().end().v != 0;
  finish(*fb, nullptr, cycle, true, false, Error::None);
  if (!ax.queue.empty()) {
    FbSlot* next = ax.queue.front();
    ax.queue.erase(ax.queue.begin());
    // Buffered: Active now, interpolation from the next cycle; blending: continues from the exact hand-over instant.
    if (blended) next->target = ax.movement().end().p;
    startCommand(*next, ax, nowNs, blended ? overshoot : 0);
    if (blended && overshoot == 0) ax.sample(nowNs);
    return;
  }
  ax.setState(blended ? AxisState::ContinuousMotion : AxisState::Standstill);
}

}  // namespace stc::motion
