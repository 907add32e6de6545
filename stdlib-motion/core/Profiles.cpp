// Profile tables, direct set points, torque and controller mode: see Profiles.h
// and docs/motion-profiles.md.
#include "stdlib-motion/core/Profiles.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stc::motion {

// ---------------------------------------------------------------- TableGenerator

namespace {
// The S-curve of a segment (0 -> 1, slope 0 at both ends) and its integrals.
double sCurve(double s) { return s * s * (3 - 2 * s); }
double sCurveInt(double s) { return s * s * s * (1 - 0.5 * s); }                   // int_0^s S
double sCurveInt2(double s) { return s * s * s * s * (0.25 - 0.1 * s); }           // int_0^s int S
}  // namespace

TableGenerator::TableGenerator(TableKind kind, const std::vector<TablePoint>& pts, bool absolute, const Kinematic& start, double positionBase)
    : kind_(kind) {
  const size_t n = pts.size();
  t_.assign(n + 1, 0);
  p_.assign(n + 1, 0);
  v_.assign(n + 1, 0);
  a_.assign(n + 1, 0);
  val_.assign(n + 1, 0);
  for (size_t i = 1; i <= n; ++i) t_[i] = t_[i - 1] + pts[i - 1].dt;
  p_[0] = start.p;
  v_[0] = start.v;
  switch (kind) {
    case TableKind::Position: {
      for (size_t i = 1; i <= n; ++i) p_[i] = absolute ? positionBase + pts[i - 1].value : p_[i - 1] + pts[i - 1].value;
      // Clamped C2 cubic spline: knot velocities m (m0 = start velocity, mn = 0) from the
      // tridiagonal system of continuous accelerations at the inner knots (Thomas algorithm).
      v_[n] = 0;
      if (n >= 2) {
        std::vector<double> lo(n + 1, 0), di(n + 1, 0), up(n + 1, 0), rhs(n + 1, 0);
        for (size_t i = 1; i < n; ++i) {
          const double h0 = t_[i] - t_[i - 1], h1 = t_[i + 1] - t_[i];
          lo[i] = 1 / h0;
          di[i] = 2 * (1 / h0 + 1 / h1);
          up[i] = 1 / h1;
          rhs[i] = 3 * ((p_[i] - p_[i - 1]) / (h0 * h0) + (p_[i + 1] - p_[i]) / (h1 * h1));
        }
        rhs[1] -= lo[1] * v_[0];
        rhs[n - 1] -= up[n - 1] * v_[n];
        for (size_t i = 2; i < n; ++i) {
          const double w = lo[i] / di[i - 1];
          di[i] -= w * up[i - 1];
          rhs[i] -= w * rhs[i - 1];
        }
        v_[n - 1] = rhs[n - 1] / di[n - 1];
        for (size_t i = n - 1; i-- > 1;) v_[i] = (rhs[i] - up[i] * v_[i + 1]) / di[i];
      }
      for (size_t i = 0; i <= n; ++i) a_[i] = at(t_[i]).a;
      break;
    }
    case TableKind::Velocity: {
      // v = start.v + V(t), V(0) = 0: a repeated run adds to the velocity it starts from.
      double V = 0;
      for (size_t i = 1; i <= n; ++i) {
        V = absolute ? pts[i - 1].value : V + pts[i - 1].value;
        val_[i] = V;
        v_[i] = start.v + V;
        p_[i] = p_[i - 1] + 0.5 * (v_[i - 1] + v_[i]) * (t_[i] - t_[i - 1]);
      }
      break;
    }
    case TableKind::Acceleration: {
      double A = 0;
      for (size_t i = 1; i <= n; ++i) {
        A = absolute ? pts[i - 1].value : A + pts[i - 1].value;
        a_[i] = val_[i] = A;
        const double h = t_[i] - t_[i - 1], a0 = a_[i - 1], dA = A - a0;
        v_[i] = v_[i - 1] + h * (a0 + 0.5 * dA);
        p_[i] = p_[i - 1] + v_[i - 1] * h + h * h * (0.5 * a0 + 0.15 * dA);
      }
      break;
    }
  }
}

Kinematic TableGenerator::at(double t) const {
  const size_t n = t_.size() - 1;
  size_t i = static_cast<size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin());
  i = std::clamp<size_t>(i, 1, n);
  const double h = t_[i] - t_[i - 1];
  const double s = std::clamp((t - t_[i - 1]) / h, 0.0, 1.0);
  Kinematic k;
  switch (kind_) {
    case TableKind::Position: {
      const double s2 = s * s, s3 = s2 * s;
      const double P0 = p_[i - 1], P1 = p_[i], M0 = v_[i - 1] * h, M1 = v_[i] * h;
      k.p = (2 * s3 - 3 * s2 + 1) * P0 + (s3 - 2 * s2 + s) * M0 + (-2 * s3 + 3 * s2) * P1 + (s3 - s2) * M1;
      k.v = ((6 * s2 - 6 * s) * P0 + (3 * s2 - 4 * s + 1) * M0 + (-6 * s2 + 6 * s) * P1 + (3 * s2 - 2 * s) * M1) / h;
      k.a = ((12 * s - 6) * P0 + (6 * s - 4) * M0 + (-12 * s + 6) * P1 + (6 * s - 2) * M1) / (h * h);
      break;
    }
    case TableKind::Velocity: {
      const double v0 = v_[i - 1], dV = v_[i] - v0;
      k.v = v0 + dV * sCurve(s);
      k.p = p_[i - 1] + h * (v0 * s + dV * sCurveInt(s));
      k.a = dV * 6 * s * (1 - s) / h;
      break;
    }
    case TableKind::Acceleration: {
      const double a0 = a_[i - 1], dA = a_[i] - a0;
      k.a = a0 + dA * sCurve(s);
      k.v = v_[i - 1] + h * (a0 * s + dA * sCurveInt(s));
      k.p = p_[i - 1] + v_[i - 1] * h * s + h * h * (0.5 * a0 * s * s + dA * sCurveInt2(s));
      break;
    }
  }
  // Exact at the table points.
  if (s == 1.0) k.p = p_[i], k.v = kind_ == TableKind::Position ? k.v : v_[i];
  if (s == 0.0) k.p = p_[i - 1], k.v = kind_ == TableKind::Position ? k.v : v_[i - 1];
  return k;
}

// ---------------------------------------------------------------- DirectGenerator

Kinematic DirectGenerator::at(double t) const {
  if (t <= tSet) return state;
  Kinematic k = state;
  k.p += state.v * (t - tSet);
  k.a = 0;
  return k;
}

double DirectGenerator::duration() const { return std::numeric_limits<double>::infinity(); }

std::shared_ptr<DirectGenerator> DirectGenerator::startOn(Axis& ax, int64_t nowNs) {
  auto gen = std::make_shared<DirectGenerator>();
  gen->state = ax.set();
  ax.startExternal(gen, nowNs);
  return gen;
}

// ---------------------------------------------------------------- behaviours

namespace {

class ProfileBehaviour : public FbBehaviour {
public:
  TableKind kind = TableKind::Position;
  bool absolute = true;
  std::vector<TablePoint> points;
  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    const Kinematic s = ax.set();
    const double base = ax.isModulo() ? std::floor(s.p / ax.config().period) * ax.config().period : 0.0;
    ax.startExternal(std::make_shared<TableGenerator>(kind, points, absolute, s, base), nowNs);
    ax.setState(kind == TableKind::Velocity ? AxisState::ContinuousMotion : AxisState::DiscreteMotion);
  }
};

class FollowBehaviour : public FbBehaviour {
public:
  FollowInputs in;
  int64_t intervalNs = 1000000;
  std::shared_ptr<DirectGenerator> gen;
  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    gen = DirectGenerator::startOn(ax, nowNs);
    ax.setState(AxisState::SynchronizedMotion);
  }
  // The set values of this cycle's call become the set point of this cycle's step.
  void beforeStep(Kernel&, FbSlot&, Axis& ax, int64_t nowNs, uint64_t) override {
    if (!gen || ax.movement().gen != gen) return;
    const double dt = static_cast<double>(intervalNs) * 1e-9;
    const Kinematic prev = gen->state;
    const bool hasP = in.mask & kFollowPosition, hasV = in.mask & kFollowVelocity, hasA = in.mask & kFollowAcceleration;
    double p = in.position;
    // Modulo axes: the unwrapped position nearest to the previous set position.
    if (hasP && ax.isModulo()) p = prev.p + std::remainder(in.position - prev.p, ax.config().period);
    Kinematic n;
    n.v = hasV ? in.velocity : hasP ? (p - prev.p) / dt : hasA ? prev.v + 0.5 * (prev.a + in.acceleration) * dt : prev.v;
    n.p = hasP ? p : prev.p + 0.5 * (prev.v + n.v) * dt;
    n.a = hasA ? in.acceleration : (n.v - prev.v) / dt;
    if (in.mask & kFollowTorque) ax.drive().setTargetTorque(in.torque);
    gen->state = n;
    gen->tSet = ax.movement().t(nowNs);
  }
};

class TorqueBehaviour : public FbBehaviour {
public:
  double torque = 0;
  void start(Kernel&, FbSlot&, Axis& ax, int64_t) override { ax.setState(AxisState::ContinuousMotion); }
  void beforeStep(Kernel&, FbSlot&, Axis& ax, int64_t, uint64_t) override { ax.drive().setTargetTorque(torque); }
};

class ControllerModeBehaviour : public FbBehaviour {
public:
  int8_t want = kModeCsp, before = kModeCsp;
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}
  // Done once the drive reports the new mode (6061h), in the kernel step of the edge cycle;
  // an errorstop or MC_Stop in that step interrupts it (72) and the previous mode is restored.
  void afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t, uint64_t cycle) override {
    if (!fb.out.busy || fb.axis != &ax) return;
    int64_t display = 0;
    ax.drive().readObject(0x6061, 0, display);
    if (ax.state() == AxisState::ErrorStop || (ax.state() == AxisState::Stopping && ax.blockingStop)) {
      ax.drive().writeObject(0x6060, 0, before);
      k.finish(fb, nullptr, cycle, false, false, Error::ScmInterrupted);
    } else if (display == want) {
      k.finish(fb, nullptr, cycle, true, false, Error::None);
    }
  }
};

Error sizeError(TableKind k) {
  return k == TableKind::Position ? Error::PpArraySize : k == TableKind::Velocity ? Error::VpArraySize : Error::ApArraySize;
}

Error stepError(TableKind k) {
  return k == TableKind::Position ? Error::PpStep0ms : k == TableKind::Velocity ? Error::VpStep0ms : Error::ApStep0ms;
}

}  // namespace

// ---------------------------------------------------------------- instructions

void callProfile(Kernel& k, FbSlot& fb, Axis& ax, bool execute, TableKind kind, int arraySize, const std::vector<RawPoint>& points,
                 bool absolute, double scale, double offset, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  if (arraySize < 1 || arraySize > 100 || points.size() < static_cast<size_t>(arraySize)) return k.fail(fb, sizeError(kind), c);
  for (int i = 0; i < arraySize; ++i)
    if (points[i].dtNs <= 0) return k.fail(fb, stepError(kind), c);
  // Values that are not numbers make the table invalid (no code of their own in the manuals).
  if (!std::isfinite(scale) || !std::isfinite(offset)) return k.fail(fb, sizeError(kind), c);
  for (int i = 0; i < arraySize; ++i)
    if (!std::isfinite(points[i].value)) return k.fail(fb, sizeError(kind), c);
  if (Error e = k.motionStateError(ax); e != Error::None) return k.fail(fb, e, c);
  if (ax.config().drive.kind == AxisKind::Encoder) return k.fail(fb, Error::NotReadyForMotion, c);
  // Position and acceleration tables start from standstill (or re-trigger in discrete motion).
  if (kind != TableKind::Velocity && ax.state() != AxisState::Standstill && ax.state() != AxisState::DiscreteMotion)
    return k.fail(fb, Error::NotReadyForMotion, c);
  ProfileBehaviour& b = behaviourOf<ProfileBehaviour>(fb);
  b.kind = kind;
  b.absolute = absolute;
  b.points.resize(arraySize);
  for (int i = 0; i < arraySize; ++i) b.points[i] = TablePoint{static_cast<double>(points[i].dtNs) * 1e-9, scale * points[i].value + offset};
  fb.in = MoveInputs{};
  k.accept(fb, ax, c);
}

void callFollow(Kernel& k, FbSlot& fb, Axis& ax, bool execute, bool abort, const FollowInputs& in, const CallCtx& c) {
  FollowBehaviour& b = behaviourOf<FollowBehaviour>(fb);
  b.in = in;
  b.intervalNs = c.intervalNs > 0 ? c.intervalNs : 1000000;
  const bool rising = k.beginExecute(fb, execute, c);
  if (rising) {
    fb.axis = &ax;
    // The simulated drives have no current controller.
    if (in.mask & kFollowCurrent) return k.fail(fb, Error::WrongControllerMode, c);
    if (Error e = k.motionStateError(ax); e != Error::None) return k.fail(fb, e, c);
    if (ax.config().drive.kind == AxisKind::Encoder) return k.fail(fb, Error::NotReadyForMotion, c);
    fb.in = MoveInputs{};
    k.accept(fb, ax, c);
  }
  // bAbort (SMC_FollowSetValues) ends the command: CommandAborted; the axis keeps its last velocity.
  if (abort && fb.out.busy && ax.controller == &fb) return k.finish(fb, &c, c.cycle, false, true, Error::None);
  fb.sync();
}

ControllerMode controllerMode(const Axis& ax) {
  switch (ax.drive().modeOfOperation()) {
    case kModeCst: return ControllerMode::Torque;
    case kModeCsv: return ControllerMode::Velocity;
    default: return ControllerMode::Position;
  }
}

void callSetControllerMode(Kernel& k, FbSlot& fb, Axis& ax, bool execute, int16_t mode, const CallCtx& c) {
  ControllerModeBehaviour& b = behaviourOf<ControllerModeBehaviour>(fb);
  if (!k.beginExecute(fb, execute, c)) {
    fb.sync();
    return;
  }
  fb.axis = &ax;
  int8_t want = 0;
  switch (static_cast<ControllerMode>(mode)) {
    case ControllerMode::Torque: want = kModeCst; break;
    case ControllerMode::Velocity: want = kModeCsv; break;
    case ControllerMode::Position: want = kModeCsp; break;
    default: break;   // no control, current control, unknown values: not supported by the simulated drive
  }
  if (ax.config().drive.kind != AxisKind::Servo || want == 0) return k.fail(fb, Error::ScmNotSupported, c);
  if (ax.state() == AxisState::ErrorStop || ax.state() == AxisState::Stopping || ax.state() == AxisState::Homing)
    return k.fail(fb, Error::ScmAxisInWrongState, c);
  b.before = ax.drive().modeOfOperation();
  b.want = want;
  // Into or out of torque control: the command in control (its set values no longer
  // apply) ends with CommandAborted; the set torque restarts from 0.
  if ((b.before == kModeCst) != (want == kModeCst)) {
    k.abortController(ax, c.cycle);
    ax.drive().setTargetTorque(0);
  }
  ax.drive().writeObject(0x6060, 0, want);
  if (std::find(ax.observers.begin(), ax.observers.end(), &fb) == ax.observers.end()) ax.observers.push_back(&fb);
  fb.out.busy = true;
  fb.sync();
}

void callSetTorque(Kernel& k, FbSlot& fb, Axis& ax, bool enable, double torque, const CallCtx& c) {
  TorqueBehaviour& b = behaviourOf<TorqueBehaviour>(fb);
  b.torque = std::isfinite(torque) ? torque : 0.0;
  fb.lastCallCycle = c.cycle;
  fb.callSeq = ++k.callCounter;
  const bool rising = enable && !fb.execute;
  fb.execute = enable;
  if (!enable) {
    // Enable FALSE: the FB releases the axis; the set torque falls to 0.
    if (ax.controller == &fb) {
      ax.controller = nullptr;
      ax.drive().setTargetTorque(0);
    }
    fb.out = FbOutputs{};
    fb.sync();
    return;
  }
  if (!rising) {
    if (ax.controller == &fb && !std::isfinite(torque)) {
      // A set torque that is not a number ends the command (the torque falls to 0).
      ax.drive().setTargetTorque(0);
      return k.finish(fb, &c, c.cycle, false, false, Error::NotReadyForMotion);
    }
    if (ax.controller == &fb) ax.drive().setTargetTorque(b.torque);
    fb.sync();
    return;
  }
  fb.out = FbOutputs{};
  fb.axis = &ax;
  Error e = Error::None;
  if (ax.state() == AxisState::PowerOff) e = Error::RegulatorOrStartNotSet;
  else if (ax.state() == AxisState::ErrorStop || ax.state() == AxisState::Homing || ax.state() == AxisState::Stopping) e = Error::NotReadyForMotion;
  else if (controllerMode(ax) != ControllerMode::Torque) e = Error::StWrongControllerMode;
  else if (!std::isfinite(torque)) e = Error::NotReadyForMotion;
  if (e != Error::None) return k.fail(fb, e, c);
  fb.in = MoveInputs{};
  k.accept(fb, ax, c);
  ax.drive().setTargetTorque(b.torque);
}

}  // namespace stc::motion
