// Semantics of the Leadshine single-axis blocks (LsMoves.h) on the common kernel.
#include "stdlib-motion/leadshine/LsMoves.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"
#include "stdlib-motion/core/InputBounds.h"

namespace stc::motion::leadshine {

namespace {

bool finite(double x) { return std::isfinite(x); }
bool finitePositive(double x) { return bounds::rate(x); }   // velocities and rates: finite, > 0, not absurd
bool finiteNonNegative(double x) { return std::isfinite(x) && x >= 0; }

// The set speed of the axis along `sign` (0 when it moves the other way).
double speedAlong(const Axis& ax, double sign) { return std::max(0.0, ax.set().v * sign); }

}  // namespace

// ---------------------------------------------------------------- LS_MoveAbs / LS_MoveRel / LS_MoveVel

namespace {

class StartVelMove : public FbBehaviour {
public:
  StartVelInputs in;
  void start(Kernel&, FbSlot& fb, Axis& ax, int64_t nowNs) override {
    const Kinematic s = ax.set();
    if (fb.kind == FbKind::MoveVelocity) {
      double sign = in.direction == Direction::Negative ? -1 : 1;
      if (in.direction == Direction::Current && s.v < 0) sign = -1;
      const double v = sign * in.velocity;   // a negative velocity in the negative direction is positive
      const double vs = std::max(in.startVel, speedAlong(ax, v < 0 ? -1 : 1));
      ax.startExternal(JumpTrapezoid::velocity(s.p, v, vs, in.acceleration), nowNs);
      ax.setState(AxisState::ContinuousMotion);
      return;
    }
    double target = s.p + in.distance;
    if (fb.kind == FbKind::MoveAbsolute) ax.absoluteTarget(in.position, in.direction, target);
    fb.target = target;
    const double vs = std::max(in.startVel, speedAlong(ax, target < s.p ? -1 : 1));
    ax.startExternal(JumpTrapezoid::position(s.p, target - s.p, vs, in.velocity, in.endSecondVel, in.acceleration,
                                             in.deceleration),
                     nowNs);
    ax.lastCommandedTarget = target;
    ax.setState(AxisState::DiscreteMotion);
  }
  void reached(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot) override {
    if (fb.kind != FbKind::MoveVelocity) return k.completeCommand(ax, nowNs, cycle, overshoot);
    fb.out.inState = true;   // InVelocity; Busy until another command takes over
    fb.sync();
  }
};

Error velAccError(FbKind kind) {
  return kind == FbKind::MoveAbsolute ? Error::MaInvalidVelAcc
         : kind == FbKind::MoveRelative ? Error::MrInvalidVelAcc : Error::MvInvalidAccDec;
}

}  // namespace

void callStartVelMove(Kernel& k, FbSlot& fb, Axis& ax, bool execute, FbKind kind, const StartVelInputs& in, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = &ax;
  fb.kind = kind;
  // StartVel / EndSecondVel: at least 0.001 (manual); Acc / Dec = 0: the velocity jumps.
  const bool creepOk = kind == FbKind::MoveVelocity || (finite(in.endSecondVel) && in.endSecondVel >= 0.001);
  if (!finitePositive(in.velocity) || !finiteNonNegative(in.acceleration) || !finiteNonNegative(in.deceleration) ||
      !finite(in.startVel) || in.startVel < 0.001 || !creepOk || !finite(in.position) || !finite(in.distance))
    return k.fail(fb, velAccError(kind), c);
  const int d = static_cast<int>(in.direction);
  if (d < -1 || d > 3) return k.fail(fb, kind == FbKind::MoveVelocity ? Error::MvDirectionNotApplicable : Error::MaInvalidDirection, c);
  if (kind == FbKind::MoveVelocity && (in.direction == Direction::Shortest || in.direction == Direction::Fastest))
    return k.fail(fb, Error::MvDirectionNotApplicable, c);
  if (Error e = k.motionStateError(ax); e != Error::None) return k.fail(fb, e, c);
  if (ax.config().drive.kind == AxisKind::Encoder) return k.fail(fb, Error::NotReadyForMotion, c);
  StartVelMove* b = &behaviourOf<StartVelMove>(fb);
  b->in = in;
  fb.in = MoveInputs{};
  fb.in.velocity = in.velocity;
  fb.in.bufferMode = BufferMode::Aborting;
  k.accept(fb, ax, c);
}

// ---------------------------------------------------------------- on-the-fly changes

void callChangeOnTheFly(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const MoveInputs& in, const CallCtx& c) {
  const bool running = fb.execute && execute && ax.controller == &fb && fb.out.busy;
  if (running) {
    fb.lastCallCycle = c.cycle;
    fb.callSeq = ++k.callCounter;
    const MoveInputs& o = fb.in;
    const bool changed = in.position != o.position || in.velocity != o.velocity || in.acceleration != o.acceleration ||
                         in.deceleration != o.deceleration || in.jerk != o.jerk || in.direction != o.direction;
    if (!changed) return fb.sync();
    // A change with bad values is refused; the move goes on with the old ones.
    const bool ok = finitePositive(in.velocity) && finitePositive(in.acceleration) && finitePositive(in.deceleration) &&
                    finiteNonNegative(in.jerk) && finite(in.position) &&
                    (fb.kind != FbKind::MoveVelocity || in.direction == Direction::Positive || in.direction == Direction::Negative);
    if (!ok) return fb.sync();
    fb.in = in;
    if (fb.kind == FbKind::MoveVelocity) fb.endVelocity = (in.direction == Direction::Negative ? -1 : 1) * in.velocity;
    k.startCommand(fb, ax, c.nowNs, 0);
    return;
  }
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = &ax;
  const Error velAcc = fb.kind == FbKind::MoveVelocity ? Error::MvInvalidAccDec : Error::MaInvalidVelAcc;
  if (!finitePositive(in.velocity) || !finitePositive(in.acceleration) || !finitePositive(in.deceleration) ||
      !finiteNonNegative(in.jerk) || !finite(in.position) || ((ax.config().ramp == RampType::Quadratic || ax.config().ramp == RampType::QuadraticSmooth) && in.jerk == 0))
    return k.fail(fb, velAcc, c);
  if (fb.kind == FbKind::MoveVelocity && in.direction != Direction::Positive && in.direction != Direction::Negative)
    return k.fail(fb, Error::MvDirectionNotApplicable, c);
  if (Error e = k.motionStateError(ax); e != Error::None) return k.fail(fb, e, c);
  if (ax.config().drive.kind == AxisKind::Encoder) return k.fail(fb, Error::NotReadyForMotion, c);
  fb.in = in;
  fb.in.bufferMode = BufferMode::Aborting;
  if (fb.kind == FbKind::MoveVelocity) fb.endVelocity = (in.direction == Direction::Negative ? -1 : 1) * in.velocity;
  k.accept(fb, ax, c);
}

// ---------------------------------------------------------------- LS_PositionToVelocity

namespace {

class TwoSegmentMove : public FbBehaviour {
public:
  TwoSegmentInputs in;
  double target[2]{};
  int phase = 0;                   // segment in progress
  bool halted = false, stopping = false;

  Limits limits(const Axis&, int i) const {
    Limits l{in.velocity[i], in.acceleration[i], in.deceleration[i], in.velocityMode == 0 ? 0.0 : in.jerk[i]};
    return l;
  }
  // The hand-over speed at the end of segment 0: its velocity when segment 1 goes on the same way, else 0.
  double handOver(double from) const {
    const double d0 = target[0] - from, d1 = target[1] - target[0];
    if (d0 == 0 || d1 == 0 || (d0 > 0) != (d1 > 0)) return 0;
    return d0 > 0 ? in.velocity[0] : -in.velocity[0];
  }
  void planPhase(Axis& ax, int64_t nowNs, double frac) {
    const double from = ax.set().p;
    const double vEnd = phase == 0 ? handOver(from) : 0;
    ax.startPosition(target[phase], vEnd, limits(ax, phase), nowNs, frac);
    ax.setState(AxisState::DiscreteMotion);
  }
  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    halted = stopping = false;
    planPhase(ax, nowNs, 0);
  }
  void reached(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot) override {
    if (stopping) {
      stopping = false;
      ax.controller = nullptr;
      k.finish(fb, nullptr, cycle, false, true, Error::None);
      ax.setState(AxisState::Standstill);
      return;
    }
    if (halted) return;   // paused at standstill, still in control (CommandHalt)
    if (phase == 0) {
      phase = 1;
      const bool moving = ax.movement().end().v != 0;
      planPhase(ax, nowNs, moving ? overshoot : 0);
      if (moving && overshoot == 0) ax.sample(nowNs);
      return;
    }
    k.completeCommand(ax, nowNs, cycle, overshoot);
  }
};

}  // namespace

void callPositionToVelocity(Kernel& k, FbSlot& fb, Axis& ax, const TwoSegmentInputs& in, TwoSegmentOutputs& out, const CallCtx& c) {
  TwoSegmentMove* b = &behaviourOf<TwoSegmentMove>(fb);
  // Halt and Stop are edges of their own inputs; their previous levels live in the behaviour.
  const bool haltEdge = in.halt && !b->in.halt, stopEdge = in.stop && !b->in.stop;
  const bool inControl = ax.controller == &fb && fb.out.busy;
  b->in.halt = in.halt;
  b->in.stop = in.stop;
  fb.axis = &ax;
  if (inControl && stopEdge) {
    // Stop: brake with the deceleration of the segment in progress; CommandAborted at standstill.
    fb.lastCallCycle = c.cycle;
    b->stopping = true;
    b->halted = false;
    ax.sample(c.nowNs);
    ax.startStop(Limits{1, b->in.deceleration[b->phase], b->in.deceleration[b->phase], b->limits(ax, b->phase).jerk}, c.nowNs);
  } else if (inControl && haltEdge && !b->halted && !b->stopping) {
    // Halt: brake and pause; Exec resumes the segment in progress.
    fb.lastCallCycle = c.cycle;
    b->halted = true;
    ax.sample(c.nowNs);
    ax.startStop(Limits{1, b->in.deceleration[b->phase], b->in.deceleration[b->phase], b->limits(ax, b->phase).jerk}, c.nowNs);
  }
  const bool rising = in.exec && !fb.execute;
  if (inControl && rising && b->halted) {
    fb.execute = true;
    fb.lastCallCycle = c.cycle;
    b->halted = false;
    ax.sample(c.nowNs);
    b->planPhase(ax, c.nowNs, 0);
  } else if (k.beginExecute(fb, in.exec, c) && !inControl) {
    const Error velAcc = in.relative ? Error::MrInvalidVelAcc : Error::MaInvalidVelAcc;
    for (int i = 0; i < 2; ++i)
      if (!finitePositive(in.velocity[i]) || !finitePositive(in.acceleration[i]) || !finitePositive(in.deceleration[i]) ||
          !finite(in.endPos[i]) || !finiteNonNegative(in.jerk[i]) || (in.velocityMode == 3 && in.jerk[i] == 0) ||
          (in.velocityMode != 0 && in.velocityMode != 1 && in.velocityMode != 3) ||
          (in.velocityMode == 1 && in.jerk[i] == 0))
        return k.fail(fb, velAcc, c), void(out = TwoSegmentOutputs{false, ax.set().v});
    if (static_cast<int64_t>(in.ipoCycleUs) * 1000 != c.intervalNs)
      return k.fail(fb, Error::UnknownTaskInterval, c), void(out = TwoSegmentOutputs{false, ax.set().v});
    if (Error e = k.motionStateError(ax); e != Error::None) return k.fail(fb, e, c), void(out = TwoSegmentOutputs{false, ax.set().v});
    b->in = in;
    b->phase = 0;
    ax.sample(c.nowNs);
    const double p = ax.set().p;
    b->target[0] = in.relative ? p + in.endPos[0] : in.endPos[0];
    b->target[1] = in.relative ? b->target[0] + in.endPos[1] : in.endPos[1];
    fb.in = MoveInputs{};
    fb.in.bufferMode = BufferMode::Aborting;
    k.accept(fb, ax, c);
  } else {
    fb.sync();
  }
  out.commandHalt = b->halted && ax.controller == &fb;
  out.vel = ax.set().v;
}

// ---------------------------------------------------------------- LS_Encoder_SetAxisMove

namespace {

class Handwheel : public FbBehaviour {
public:
  HandwheelInputs in;
  Axis* encoder = nullptr;
  double encStart = 0;        // encoder increments at the start
  double base = 0;            // axis set position at the start
  double added = 0;           // additions completed or in progress
  double addStep = 0;         // per-cycle share of the addition in progress
  uint32_t addLeft = 0;
  double filtered = 0;        // the smoothed set position
  double lastDelta = 0;       // set-position change of the latest cycle [u]
  int64_t prevNs = 0;         // time of the previous step (set velocity = change / cycle time)
  int32_t errorId = 0;        // dErrorID (Leadshine DINT; SMC_ERROR codes when the kernel ended it)

  double target() const {
    const double incs = encoder->actPosition() * encoder->config().drive.incrementsPerUnit - encStart;
    return base + incs * in.num / in.denom + added;
  }
  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    base = filtered = ax.set().p;
    added = addStep = lastDelta = 0;
    addLeft = 0;
    prevNs = nowNs;
    encStart = encoder->actPosition() * encoder->config().drive.incrementsPerUnit;
    hold(filtered, 0, ax, nowNs);
    ax.setState(AxisState::SynchronizedMotion);
  }
  void beforeStep(Kernel&, FbSlot&, Axis& ax, int64_t nowNs, uint64_t) override {
    if (addLeft > 0) {
      added += addStep;
      --addLeft;
    }
    const double prev = filtered;
    filtered += (target() - filtered) / in.filter;
    lastDelta = filtered - prev;
    const double dt = prevNs > 0 && nowNs > prevNs ? static_cast<double>(nowNs - prevNs) * 1e-9 : 0;
    prevNs = nowNs;
    hold(filtered, dt > 0 ? lastDelta / dt : 0, ax, nowNs);
  }
  void reached(Kernel&, FbSlot&, Axis&, int64_t, uint64_t, double) override {}

  // The set point of this cycle: stays at p until the next cycle replaces it.  One
  // generator per FB, updated in place (no allocation in the cycle).
  void hold(double p, double v, Axis& ax, int64_t nowNs) {
    if (!holdGen) holdGen = std::make_shared<Hold>(p, v);
    holdGen->p = p;
    holdGen->v = v;
    ax.startExternal(holdGen, nowNs);
  }
  struct Hold : Generator {
    double p, v;
    Hold(double pos, double vel) : p(pos), v(vel) {}
    Kinematic at(double) const override { return Kinematic{p, v, 0}; }
    double duration() const override { return INFINITY; }
  };
  std::shared_ptr<Hold> holdGen;
};

}  // namespace

void callHandwheel(Kernel& k, FbSlot& fb, Axis& ax, const HandwheelInputs& in, HandwheelOutputs& out, const CallCtx& c) {
  Handwheel* b = &behaviourOf<Handwheel>(fb);
  const bool stopEdge = in.stop && !b->in.stop, trigEdge = in.additiveTrig && !b->in.additiveTrig;
  const bool rising = in.exec && !fb.execute;
  b->in.stop = in.stop;
  b->in.additiveTrig = in.additiveTrig;
  fb.execute = in.exec;
  fb.lastCallCycle = c.cycle;
  fb.axis = &ax;
  bool following = ax.controller == &fb && fb.out.busy;
  if (following && stopEdge) {
    // Stop: the axis stays where the smoothed set point is; bDone until the next Exec edge.
    ax.controller = nullptr;
    ax.sample(c.nowNs);
    ax.holdAt(ax.set().p);
    ax.setState(AxisState::Standstill);
    fb.out.busy = fb.out.active = false;
    fb.out.done = true;
    following = false;
  }
  if (rising && !following) {
    fb.out = FbOutputs{};
    b->errorId = 0;
    Axis* enc = nullptr;
    for (size_t i = 0; i < k.axisCount(); ++i)
      if (Axis* a = k.axis(static_cast<uint32_t>(i)); a->config().drive.kind == AxisKind::Encoder && a->config().encoderChannel == in.channel)
        enc = a;
    Error e = Error::None;
    if (in.channel < 0 || in.channel > 2 || in.num < 1 || in.num > 10000 || in.denom < 1 || in.denom > 10000 ||
        in.filter < 1 || in.filter > 100 || !finite(in.additivePos) || !enc || !k.claim(*enc, c))
      b->errorId = kIpoParaErr;
    else if ((e = k.motionStateError(ax)) != Error::None)
      b->errorId = sm3face::smcError(e);
    if (b->errorId == 0) {
      b->in = in;
      b->encoder = enc;
      fb.in = MoveInputs{};
      fb.in.bufferMode = BufferMode::Aborting;
      k.accept(fb, ax, c);
      following = true;
    }
  }
  if (following && trigEdge) {
    // The addition is spread evenly over PosAdditive_Cycle cycles (not multiplied by the ratio).
    const uint32_t n = std::max<uint32_t>(in.additiveCycles, 1);
    b->addStep = in.additivePos / n;
    b->addLeft = n;
  }
  // Ended by the kernel (another command, ErrorStop): bError with the SMC_ERROR code.
  if (fb.out.error && fb.out.errorId != Error::None) b->errorId = sm3face::smcError(fb.out.errorId);
  if (fb.out.aborted && b->errorId == 0) b->errorId = sm3face::smcError(Error::NotReadyForMotion);
  if (!in.exec && !fb.out.busy && b->errorId != 0 && !rising) {
    // Errors last while Exec stays TRUE.
    b->errorId = 0;
    fb.out.aborted = fb.out.error = false;
  }
  out.done = fb.out.done;
  out.error = b->errorId != 0;
  out.errorId = b->errorId;
  out.deltaPulseUnit = ax.controller == &fb ? b->lastDelta * ax.config().drive.incrementsPerUnit : 0;
  fb.sync();
}

}  // namespace stc::motion::leadshine
