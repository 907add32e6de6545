// Gearing and phasing (docs/motion-sync.md).  A coupling runs as the
// slave's command in control: its behaviour writes the slave's set state in
// beforeStep(), once per cycle, from the master's set state of the same cycle
// (the master is stepped first: Axis::master).
#include "stdlib-motion/core/Coupling.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/core/Profiles.h"

namespace stc::motion {

Kinematic masterState(const Axis& master) {
  // An encoder axis has no set point: its counts are the master.
  return master.config().drive.kind == AxisKind::Encoder ? Kinematic{master.actPosition(), master.actVelocity(), 0} : master.set();
}

Kinematic masterSeenBy(const Axis& slave, const Axis& master, int64_t nowNs) {
  Kinematic m = masterState(master);
  const Kinematic s = slave.phase.at(nowNs);
  m.p -= s.p;
  m.v -= s.v;
  m.a -= s.a;
  return m;
}

bool couplingLoop(const Axis& master, const Axis& slave) {
  int hops = 0;
  for (const Axis* a = &master; a && hops < 1024; a = a->master, ++hops)
    if (a == &slave) return true;
  return false;
}

namespace {

bool isGear(FbKind k) { return k == FbKind::GearIn || k == FbKind::GearInPos; }
bool isCouplingKind(FbKind k) { return isGear(k) || k == FbKind::CamIn || k == FbKind::Backlash; }

// The common part: a DirectGenerator as the slave's movement, written each cycle.
class CouplingBehaviour : public FbBehaviour {
public:
  Axis* master = nullptr;
  std::shared_ptr<DirectGenerator> gen;
  int64_t lastNs = 0;

  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    gen = DirectGenerator::startOn(ax, nowNs);
    ax.setState(AxisState::SynchronizedMotion);
    ax.master = master;
    lastNs = nowNs;
    restart();
  }
  void beforeStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override {
    if (!gen || ax.movement().gen != gen || !master) return;
    const double dt = static_cast<double>(nowNs - lastNs) * 1e-9;
    lastNs = nowNs;
    const Kinematic prev = gen->state;
    Kinematic next = prev;
    const bool wasIn = fb.out.inState, wasStart = fb.out.startSync, wasEnd = fb.out.endOfProfile;
    Error e = advance(masterSeenBy(ax, *master, nowNs), prev, dt, fb, ax, next);
    if (e != Error::None) return k.errorStop(ax, e, nowNs, cycle);
    gen->state = next;
    gen->tSet = ax.movement().t(nowNs);
    if (fb.out.inState != wasIn || fb.out.startSync != wasStart || fb.out.endOfProfile != wasEnd) fb.sync();
    // A buffered successor takes over once the coupling is established (as after a
    // continuous move); after a cam, at its end of profile.
    if (handover(fb, wasIn, wasEnd) && !ax.queue.empty()) {
      FbSlot* succ = ax.queue.front();
      ax.queue.erase(ax.queue.begin());
      ax.controller = nullptr;
      const bool endOfProfile = fb.out.endOfProfile;
      k.finish(fb, nullptr, cycle, false, true, Error::None);
      if (endOfProfile) {   // the boundary's pulse is still shown for one cycle, with CommandAborted
        fb.out.endOfProfile = true;
        fb.endOfProfileCycle = cycle;
        fb.sync();
        if (std::find(ax.pendingClear.begin(), ax.pendingClear.end(), &fb) == ax.pendingClear.end()) ax.pendingClear.push_back(&fb);
      }
      k.startCommand(*succ, ax, nowNs, 0);
      succ->out.active = true;
      succ->sync();
    }
  }

protected:
  virtual void restart() {}
  virtual bool handover(const FbSlot& fb, bool wasIn, bool /*wasEnd*/) const { return fb.out.inState && !wasIn; }
  // The slave's set state of this cycle from the master's (m) and its own previous one.
  virtual Error advance(const Kinematic& m, const Kinematic& prev, double dt, FbSlot& fb, Axis& ax, Kinematic& next) = 0;
};

// MC_GearIn: the slave velocity ramps (Acceleration while |v| grows, else
// Deceleration) to ratio x master velocity; from the first cycle it matches,
// the slave distance is locked to the master distance x ratio (InGear).
class GearBehaviour : public CouplingBehaviour {
public:
  double ratio = 1, acc = 0, dec = 0;
  bool locked = false;
  double lockSlave = 0, lockMaster = 0;

protected:
  void restart() override { locked = false; }
  Error advance(const Kinematic& m, const Kinematic& prev, double dt, FbSlot& fb, Axis&, Kinematic& next) override {
    if (locked) {
      next = Kinematic{lockSlave + ratio * (m.p - lockMaster), ratio * m.v, ratio * m.a};
      return Error::None;
    }
    const double target = ratio * m.v;
    const double dv = target - prev.v;
    const bool growing = std::fabs(target) > std::fabs(prev.v) && target * prev.v >= 0;
    const double maxStep = (growing ? acc : dec) * dt;
    if (std::fabs(dv) <= maxStep) {
      next.v = target;
      locked = true;
    } else {
      next.v = prev.v + std::copysign(maxStep, dv);
    }
    next.p = prev.p + 0.5 * (prev.v + next.v) * dt;
    next.a = dt > 0 ? (next.v - prev.v) / dt : prev.a;
    if (locked) {
      lockSlave = next.p;
      lockMaster = m.p;
      next.a = ratio * m.a;
      fb.out.inState = true;   // InGear
    }
    return Error::None;
  }
};

// A quintic over u in [0, 1] with given value, slope and curvature 0 at both ends.
struct Quintic {
  double c[6] = {};
  static Quintic hermite(double y0, double d0, double y1, double d1) {
    Quintic q;
    const double h = y1 - y0;
    q.c[0] = y0;
    q.c[1] = d0;
    q.c[2] = 0;
    q.c[3] = 10 * h - 6 * d0 - 4 * d1;
    q.c[4] = -15 * h + 8 * d0 + 7 * d1;
    q.c[5] = 6 * h - 3 * d0 - 3 * d1;
    return q;
  }
  double y(double u) const { return c[0] + u * (c[1] + u * (c[2] + u * (c[3] + u * (c[4] + u * c[5])))); }
  double dy(double u) const { return c[1] + u * (2 * c[2] + u * (3 * c[3] + u * (4 * c[4] + u * 5 * c[5]))); }
  double ddy(double u) const { return 2 * c[2] + u * (6 * c[3] + u * (12 * c[4] + u * 20 * c[5])); }
  // The slope changes sign somewhere in [0, 1] (sampled densely; the slope is a quartic).
  bool reverses(double dir) const {
    for (int i = 0; i <= 256; ++i)
      if (dir * dy(i / 256.0) < -1e-12) return true;
    return false;
  }
};

// MC_GearInPos: waits until the master enters [MasterSyncPosition - MasterStartDistance,
// MasterSyncPosition] (StartSync), then follows a quintic in the master position from
// its state there to (SlaveSyncPosition, slope = ratio) at MasterSyncPosition (InSync),
// then the locked gear.
class GearInPosBehaviour : public CouplingBehaviour {
public:
  double ratio = 1;
  GearInPosInputs in;
  enum class Phase : uint8_t { Waiting, Syncing, Locked } phase = Phase::Waiting;
  double m0 = 0, m1 = 0, s1 = 0;
  int dir = 1;           // master direction of travel (+1 / -1)
  Quintic q;

protected:
  void restart() override { phase = Phase::Waiting; }
  Error advance(const Kinematic& m, const Kinematic& prev, double dt, FbSlot& fb, Axis& ax, Kinematic& next) override {
    if (phase == Phase::Waiting) {
      next = Kinematic{prev.p + prev.v * dt, prev.v, 0};
      if (dir * (m.p - (m1 - dir * in.masterStartDistance)) < 0) return Error::None;
      if (Error e = beginSync(m, next, ax); e != Error::None) return e;
      fb.out.startSync = true;
    }
    if (phase == Phase::Syncing) {
      if (m.v * dir < 0) return Error::GipMasterDirectionChange;
      const double span = m1 - m0;
      const double u = span != 0 ? (m.p - m0) / span : 1;
      if (u < 1) {
        const double slope = q.dy(u) / span, curve = q.ddy(u) / (span * span);
        next = Kinematic{q.y(u), slope * m.v, curve * m.v * m.v + slope * m.a};
        return Error::None;
      }
      phase = Phase::Locked;
      fb.out.inState = true;   // InSync: from this cycle on the gear is exact
    }
    next = Kinematic{s1 + ratio * (m.p - m1), ratio * m.v, ratio * m.a};
    return Error::None;
  }

private:
  Error beginSync(const Kinematic& m, const Kinematic& slave, const Axis& ax) {
    m0 = m.p;
    const double span = m1 - m0;
    const double slope0 = m.v != 0 ? slave.v / m.v : 0;
    // SlaveSyncPosition on a modulo slave: the period where the gear would put it, or
    // (AvoidReversal) the first one ahead that the slave reaches without reversing.
    s1 = in.slaveSyncPosition;
    const double period = ax.config().period;
    if (ax.isModulo()) {
      const double expect = slave.p + ratio * span;
      s1 = expect + std::remainder(in.slaveSyncPosition - expect, period);
    }
    phase = Phase::Syncing;
    q = Quintic::hermite(slave.p, slope0 * span, s1, ratio * span);
    if (!in.avoidReversal || span == 0) return Error::None;
    const double sdir = ratio * dir >= 0 ? 1 : -1;
    for (int k = 0; k < 4 && q.reverses(sdir * (span > 0 ? 1 : -1)); ++k) {
      s1 += sdir * period;
      q = Quintic::hermite(slave.p, slope0 * span, s1, ratio * span);
    }
    return q.reverses(sdir * (span > 0 ? 1 : -1)) ? Error::GipSlaveReversalCannotBeAvoided : Error::None;
  }
};

// MC_CamIn.  The cam coordinate X = X0 + MasterScaling·(master - master at start), with
// X0 = MasterScaling·master + MasterOffset (master absolute; a modulo master by its
// position within the period) or xStart + MasterOffset (master relative).  A periodic
// cam wraps X into [xStart, xEnd) and adds its lift per period; a non-periodic one
// ends at xEnd (EndOfProfile held, the slave stays).  The slave's target is
// SlaveScaling·(y + periods·lift) + SlaveOffset, moved by a base that makes the
// relative modes start where the slave is; the ramp_in modes add a compensation that
// runs from the slave's start offset to 0 within VelocityDiff / Acceleration / Deceleration.
class CamBehaviour : public CouplingBehaviour {
public:
  CamInInputs in;
  uint32_t resets = 0;
  void configure(const CamInInputs& i) {
    in = i;
    first = true;
    ++resets;
  }

protected:
  void restart() override { first = true; }
  bool handover(const FbSlot& fb, bool, bool wasEnd) const override { return fb.out.endOfProfile && !wasEnd; }
  Error advance(const Kinematic& m, const Kinematic& prev, double dt, FbSlot& fb, Axis& ax, Kinematic& next) override {
    const Cam& cam = *in.sel.cam;
    const double L = cam.length(), Ms = in.masterScaling;
    if (first) {
      first = false;
      m0 = m.p;
      double mStart = m.p;
      if (master->isModulo()) mStart = m.p - master->config().period * std::floor(m.p / master->config().period);
      X0 = in.sel.masterAbsolute ? Ms * mStart + in.masterOffset : cam.xStart() + in.masterOffset;
      if (!in.sel.periodic && (X0 < cam.xStart() - 1e-9 * L || X0 > cam.xEnd() + 1e-9 * L)) return Error::CiMasterOutOfScale;
      k0 = in.sel.periodic ? std::floor((X0 - cam.xStart()) / L) : 0;
      kLast = k0;
      const Sample t0 = target(cam, m, 0);
      // Where the cam's slave coordinates sit on the (unwrapped) slave axis.
      base = 0;
      const bool relative = !in.sel.slaveAbsolute || in.startMode == CamStartMode::Relative;
      const double P = ax.isModulo() ? ax.config().period : 0;
      double comp0 = 0;
      if (relative) {
        base = prev.p - t0.k.p;
      } else {
        if (P > 0) base = P * std::round((prev.p - t0.k.p) / P);
        comp0 = prev.p - (t0.k.p + base);
        if (P > 0 && in.startMode == CamStartMode::RampInPos) comp0 -= P * std::ceil(comp0 / P);     // (-P, 0]: catch up forwards
        if (P > 0 && in.startMode == CamStartMode::RampInNeg) comp0 -= P * std::floor(comp0 / P);    // [0, P): backwards
        base = prev.p - comp0 - t0.k.p;
      }
      ramping = false;
      if (in.startMode >= CamStartMode::RampIn && comp0 != 0) {
        const Limits lim{in.velocityDiff, in.acceleration, in.deceleration, in.jerk};
        // From the slave's own velocity difference, so its velocity never jumps: a difference
        // beyond VelocityDiff is first brought within it at Deceleration.
        const double dv = prev.v - t0.k.v;
        if (planPosition(Kinematic{comp0, dv, 0}, 0, 0, lim, comp) != PlanStatus::Ok) return Error::CiRampInNeedsVelAcc;
        ramping = comp.duration() > 0;
        tComp = 0;
      }
      if (!cam.tappets().empty()) {
        tappets.reset(cam.tappets(), t0.x, in.tappetHysteresis);
        publish(fb);
      }
      fb.out.endOfProfile = false;
    }
    const Sample t = target(cam, m, 1);
    if (!cam.tappets().empty() && tappets.move(t.x)) publish(fb);
    // A one-cycle pulse per period boundary passed (periodic), held from the end on (non-periodic).
    fb.out.endOfProfile = in.sel.periodic ? fbEnd : (fbEnd || fb.out.endOfProfile);
    next = Kinematic{t.k.p + base, t.k.v, t.k.a};
    if (ramping) {
      tComp += dt;
      if (tComp >= comp.duration() - Axis::kEndTolerance - 1e-12 * tComp) ramping = false;
      else {
        const Kinematic c = comp.at(tComp);
        next.p += c.p, next.v += c.v, next.a += c.a;
      }
    }
    fb.out.inState = !ramping;
    return Error::None;
  }

private:
  struct Sample {
    Kinematic k;
    double x = 0;   // the cam coordinate within [xStart, xEnd]
  };
  // The cam target (without base) for master state m; phase 1 also advances the
  // period count, EndOfProfile and the tappets.
  Sample target(const Cam& cam, const Kinematic& m, int phase) {
    const double L = cam.length();
    const double Ms = in.masterScaling, Ss = in.slaveScaling;
    const double X = X0 + Ms * (m.p - m0);
    Sample r;
    double periods = 0, dydx, d2;
    bool stopped = false;
    if (in.sel.periodic) {
      const double kAbs = std::floor((X - cam.xStart()) / L);
      r.x = X - kAbs * L;
      periods = kAbs - k0;
      if (phase == 1) {
        fbEnd = kAbs != kLast;
        if (fbEnd && !cam.tappets().empty()) {
          // Pass the boundary (each one if the master crossed several in one cycle).
          const bool fwd = kAbs > kLast;
          for (int n = 0; n < std::min(2.0, std::fabs(kAbs - kLast)); ++n) {
            tappets.move(fwd ? cam.xEnd() : cam.xStart());
            tappets.wrap(fwd ? cam.xStart() : cam.xEnd());
          }
        }
        kLast = kAbs;
      }
    } else {
      r.x = std::clamp(X, cam.xStart(), cam.xEnd());
      stopped = X >= cam.xEnd() || X <= cam.xStart() - 1e-9 * L;
      if (phase == 1) fbEnd = X >= cam.xEnd();
    }
    const CamSample s = cam.at(r.x);
    dydx = stopped ? 0 : s.dy;
    d2 = stopped ? 0 : s.ddy;
    const double mv = Ms * m.v, ma = Ms * m.a;
    r.k = Kinematic{Ss * (s.y + periods * cam.lift()) + in.slaveOffset, Ss * dydx * mv, Ss * (d2 * mv * mv + dydx * ma)};
    return r;
  }
  void publish(FbSlot& fb) {
    if (in.publishTappets && fb.instance) in.publishTappets(fb.instance, tappets.groups(), resets);
  }

  bool first = true, ramping = false, fbEnd = false;
  double m0 = 0, X0 = 0, k0 = 0, kLast = 0, base = 0, tComp = 0;
  Profile comp;
  TappetTracker tappets;
};

// MC_Phasing: plans the shift as a profile of its own; Done when it has run out.
class PhasingBehaviour : public FbBehaviour {
public:
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}
  void afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override {
    Axis::PhaseShift& ph = ax.phase;
    if (!fb.out.busy || fb.axis != &ax) return;
    if (!ph.moving) return k.finish(fb, nullptr, cycle, false, true, Error::None);   // an errorstop ended it
    if (static_cast<double>(nowNs - ph.originNs) * 1e-9 < ph.profile.duration() - Axis::kEndTolerance) return;
    ph.done += ph.profile.end().p;
    ph.moving = false;
    k.finish(fb, nullptr, cycle, true, false, Error::None);
  }
};

// SMC_BacklashCompensation: the offset's target follows the master's direction of travel
// (or the forced mode); each change of target is a profile from the offset's current state.
class BacklashBehaviour : public CouplingBehaviour {
public:
  BacklashInputs in;
  double target = 0;
  Profile profile;
  double originT = 0, t = 0;
  bool moving = false;

  void retarget(double to, const Kinematic& from) {
    target = to;
    const Limits lim{in.velocity, in.acceleration, in.deceleration, in.jerk};
    moving = planPosition(Kinematic{from.p, from.v, from.a}, to, 0, lim, profile) == PlanStatus::Ok && profile.duration() > 0;
    originT = t;
  }
  Kinematic offset() const { return moving ? profile.at(t - originT) : Kinematic{target, 0, 0}; }

protected:
  void restart() override { t = 0; }
  Error advance(const Kinematic& m, const Kinematic& prev, double dt, FbSlot& fb, Axis&, Kinematic& next) override {
    if (t == 0 && !moving) {
      // Start: the slave's distance to the master is the first offset, moved to the start value.
      const double b = in.backlash;
      const double start = in.start == BacklashStart::Negative ? -b : in.start == BacklashStart::Positive ? b : 0.0;
      target = prev.p - m.p;
      retarget(in.mode == BacklashMode::Positive ? b : in.mode == BacklashMode::Negative ? -b : in.mode == BacklashMode::Off ? 0 : start,
               Kinematic{target, 0, 0});
    }
    t += dt;
    if (moving && t - originT >= profile.duration() - Axis::kEndTolerance - 1e-12 * t) moving = false;   // t sums dt: allow its rounding
    if (in.mode == BacklashMode::Auto && m.v != 0) {
      const double want = m.v > 0 ? in.backlash : -in.backlash;
      if (want != target) retarget(want, offset());
    }
    const Kinematic o = offset();
    next = Kinematic{m.p + o.p, m.v + o.v, m.a + o.a};
    fb.out.inState = moving;   // bCompensating
    return Error::None;
  }
};

bool validRatio(int64_t num, int64_t den) { return den != 0 && std::llabs(num) <= 1'000'000'000 && std::llabs(den) <= 1'000'000'000; }

// Checks shared by the couplings; Error::None when the slave may follow the master.
Error couplingError(Kernel& k, const Axis& master, const Axis& slave) {
  if (&master == &slave || couplingLoop(master, slave)) return Error::NotReadyForMotion;
  if (slave.config().drive.kind == AxisKind::Encoder) return Error::NotReadyForMotion;
  return k.motionStateError(slave);
}

}  // namespace

void callGearIn(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const GearInputs& in, const CallCtx& c) {
  const bool retrigger = execute && !fb.execute && fb.out.busy && slave.controller == &fb;
  if (retrigger) {
    fb.execute = true;
    fb.lastCallCycle = c.cycle;
    // While the slave is still ramping, a new edge has no effect; once in gear it
    // ramps to the new ratio (InGear falls meanwhile), Busy stays TRUE.
    auto& b = behaviourOf<GearBehaviour>(fb);
    if (b.locked && validRatio(in.numerator, in.denominator)) {
      b.ratio = static_cast<double>(in.numerator) / static_cast<double>(in.denominator);
      b.locked = false;
      fb.out.inState = false;
    }
    return fb.sync();
  }
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = &slave;
  if (in.denominator == 0 || !validRatio(in.numerator, in.denominator)) return k.fail(fb, Error::GiRatioDenom, c);
  if (!bounds::rate(in.acceleration)) return k.fail(fb, Error::GiInvalidAcc, c);
  if (!bounds::rate(in.deceleration)) return k.fail(fb, Error::GiInvalidDec, c);
  if (!bounds::jerk(in.jerk)) return k.fail(fb, Error::GiInvalidJerk, c);
  if (Error e = couplingError(k, master, slave); e != Error::None) return k.fail(fb, e, c);
  auto& b = behaviourOf<GearBehaviour>(fb);
  b.master = &master;
  b.ratio = static_cast<double>(in.numerator) / static_cast<double>(in.denominator);
  b.acc = in.acceleration;
  b.dec = in.deceleration;
  fb.in = MoveInputs{};
  fb.in.bufferMode = in.bufferMode;
  k.accept(fb, slave, c);
}

void callGearInPos(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const GearInPosInputs& in, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = &slave;
  fb.out.startSync = false;
  if (in.denominator == 0 || !validRatio(in.numerator, in.denominator)) return k.fail(fb, Error::GiRatioDenom, c);
  if (!bounds::position(in.masterSyncPosition) || !bounds::position(in.slaveSyncPosition) || !bounds::position(in.masterStartDistance) ||
      in.masterStartDistance < 0)
    return k.fail(fb, Error::NotReadyForMotion, c);
  if (in.avoidReversal && !slave.isModulo()) return k.fail(fb, Error::GipAvoidReversalForFiniteAxis, c);
  if (Error e = couplingError(k, master, slave); e != Error::None) return k.fail(fb, e, c);
  auto& b = behaviourOf<GearInPosBehaviour>(fb);
  b.master = &master;
  b.in = in;
  b.ratio = static_cast<double>(in.numerator) / static_cast<double>(in.denominator);
  // The master's direction of travel (positive when it stands) and the sync point ahead of it:
  // on a modulo master the next occurrence whose start distance is not yet entered.
  const Kinematic m = masterSeenBy(slave, master, c.nowNs);
  b.dir = m.v < 0 ? -1 : 1;
  b.m1 = in.masterSyncPosition;
  if (master.isModulo()) {
    const double P = master.config().period;
    b.m1 = m.p + std::remainder(in.masterSyncPosition - m.p, P);
    while (b.dir * (b.m1 - m.p) < 0) b.m1 += b.dir * P;
    while (b.dir * (b.m1 - b.dir * in.masterStartDistance - m.p) > P) b.m1 -= b.dir * P;
  } else if (b.dir * (m.p - b.m1) > 0) {
    return k.fail(fb, Error::NotReadyForMotion, c);   // a linear master already past the sync point
  }
  fb.in = MoveInputs{};
  fb.in.bufferMode = in.bufferMode;
  k.accept(fb, slave, c);
}

void callCouplingOut(Kernel& k, FbSlot& fb, Axis& slave, bool execute, bool cam, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = &slave;
  FbSlot* coupling = slave.controller;
  const bool ours = coupling && (cam ? coupling->kind == FbKind::CamIn || coupling->kind == FbKind::Follow : isGear(coupling->kind));
  if (!ours) return k.fail(fb, Error::NotReadyForMotion, c);
  // The slave keeps the velocity of its last set state (the coupling's generator runs on).
  slave.controller = nullptr;
  slave.master = nullptr;
  // MC_CamIn ends quietly (the manual's chart: Busy and InSync fall, CommandAborted stays
  // FALSE); a gear shows CommandAborted.
  k.finish(*coupling, &c, c.cycle, false, !cam, Error::None);
  slave.setState(AxisState::ContinuousMotion);
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

void callPhasing(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const PhasingInputs& in, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = &slave;
  if (!bounds::velocity(in.velocity) || !bounds::rate(in.acceleration) || !bounds::rate(in.deceleration) || !bounds::jerk(in.jerk) ||
      !bounds::position(in.phaseShift))
    return k.fail(fb, Error::PhInvalidVelAccDec, c);
  FbSlot* coupling = slave.controller;
  if (!coupling || slave.master != &master || !isCouplingKind(coupling->kind))
    return k.fail(fb, Error::NotReadyForMotion, c);
  Axis::PhaseShift& ph = slave.phase;
  // A shift in progress continues from its current state (its distance so far is kept).
  Kinematic from{0, 0, 0};
  if (ph.moving) {
    const Kinematic now = ph.at(c.nowNs);
    ph.done = now.p;
    from = Kinematic{0, now.v, now.a};
  }
  Profile p;
  const Limits lim{in.velocity, in.acceleration, in.deceleration, in.jerk};
  if (planPosition(from, in.phaseShift, 0, lim, p) != PlanStatus::Ok) return k.fail(fb, Error::PhInvalidVelAccDec, c);
  ph.profile = p;
  ph.originNs = c.nowNs;
  ph.moving = true;
  for (FbSlot* o : slave.observers)
    if (o != &fb && o->kind == FbKind::Phasing && o->out.busy) k.finish(*o, &c, c.cycle, false, true, Error::None);
  behaviourOf<PhasingBehaviour>(fb);
  if (std::find(slave.observers.begin(), slave.observers.end(), &fb) == slave.observers.end()) slave.observers.push_back(&fb);
  fb.out.busy = fb.out.active = true;
  fb.sync();
}

void callBacklash(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const BacklashInputs& in, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = &slave;
  if (!bounds::position(in.backlash) || in.backlash < 0 || (master.isModulo() && in.backlash > master.config().period / 2))
    return k.fail(fb, Error::BcBacklashTooBig, c);
  if (!bounds::velocity(in.velocity) || !bounds::rate(in.acceleration) || !bounds::rate(in.deceleration) || !bounds::jerk(in.jerk))
    return k.fail(fb, Error::PhInvalidVelAccDec, c);
  if (static_cast<int>(in.mode) > 3 || static_cast<int>(in.start) > 2) return k.fail(fb, Error::NotReadyForMotion, c);
  if (Error e = couplingError(k, master, slave); e != Error::None) return k.fail(fb, e, c);
  auto& b = behaviourOf<BacklashBehaviour>(fb);
  b.master = &master;
  b.in = in;
  b.moving = false;
  fb.in = MoveInputs{};
  k.accept(fb, slave, c);
}

void callCamIn(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const CamInInputs& in, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = &slave;
  fb.out.endOfProfile = false;
  if (!in.sel.cam) return k.fail(fb, Error::CiNoCamSelected, c);
  const Cam& cam = *in.sel.cam;
  if (!validCamScaling(in.masterScaling) || !validCamScaling(in.slaveScaling) || !bounds::position(in.masterOffset) ||
      !bounds::position(in.slaveOffset) || static_cast<int>(in.startMode) > 4 || !std::isfinite(in.tappetHysteresis) ||
      in.tappetHysteresis < 0 || in.tappetHysteresis > cam.length())
    return k.fail(fb, Error::CiScalingIncorrect, c);
  if (in.startMode >= CamStartMode::RampIn &&
      (!bounds::velocity(in.velocityDiff) || !bounds::rate(in.acceleration) || !bounds::rate(in.deceleration) || !bounds::jerk(in.jerk)))
    return k.fail(fb, Error::CiRampInNeedsVelAcc, c);
  if (Error e = couplingError(k, master, slave); e != Error::None) return k.fail(fb, e, c);
  // A non-periodic cam with an absolute master must start inside its master range.
  if (!in.sel.periodic && in.sel.masterAbsolute) {
    double mp = masterSeenBy(slave, master, c.nowNs).p;
    if (master.isModulo()) mp -= master.config().period * std::floor(mp / master.config().period);
    const double X = in.masterScaling * mp + in.masterOffset;
    if (X < cam.xStart() - 1e-9 * cam.length() || X > cam.xEnd() + 1e-9 * cam.length()) return k.fail(fb, Error::CiMasterOutOfScale, c);
  }
  auto& b = behaviourOf<CamBehaviour>(fb);
  b.master = &master;
  b.configure(in);
  fb.in = MoveInputs{};
  fb.in.bufferMode = in.bufferMode;
  k.accept(fb, slave, c);
}

bool camSlaveState(const CamSelection& sel, double masterOffset, double slaveOffset, double masterScaling, double slaveScaling,
                   const Kinematic& m, Kinematic& out) {
  const Cam& cam = *sel.cam;
  const double X = masterScaling * m.p + masterOffset;
  double x = X;
  if (sel.periodic) x = X - cam.length() * std::floor((X - cam.xStart()) / cam.length());
  else if (X < cam.xStart() || X > cam.xEnd()) return false;
  const CamSample s = cam.at(x);
  const double mv = masterScaling * m.v, ma = masterScaling * m.a;
  out = Kinematic{slaveScaling * s.y + slaveOffset, slaveScaling * s.dy * mv, slaveScaling * (s.ddy * mv * mv + s.dy * ma)};
  return true;
}

}  // namespace stc::motion
