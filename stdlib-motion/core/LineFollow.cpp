#include "stdlib-motion/core/LineFollow.h"

#include <cmath>
#include <memory>

#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/core/Profiles.h"

namespace stc::motion {

namespace {

// The leader's command: a profile to its target; Halt / Stop brake it.
class Leader : public FbBehaviour {
public:
  LineFollowInputs in;
  double target = 0;
  bool halted = false, stopping = false;
  Limits limits() const { return Limits{in.velocity, in.acceleration, in.deceleration, in.velocityMode == 0 ? 0.0 : in.jerk}; }
  void plan(Axis& ax, int64_t nowNs) {
    ax.startPosition(target, 0, limits(), nowNs);
    ax.setState(AxisState::DiscreteMotion);
  }
  void brake(Axis& ax, int64_t nowNs) {
    ax.sample(nowNs);
    Limits l = limits();
    l.vel = std::max(std::fabs(ax.set().v), 1e-9);
    l.acc = in.deceleration;
    ax.startStop(l, nowNs);
  }
  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    halted = stopping = false;
    plan(ax, nowNs);
  }
  void reached(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle, double overshoot) override {
    if (stopping) {
      ax.controller = nullptr;
      k.finish(fb, nullptr, cycle, false, true, Error::None);
      ax.setState(AxisState::Standstill);
      return;
    }
    if (halted) return;   // paused, still in control (CommandHalt)
    k.completeCommand(ax, nowNs, cycle, overshoot);
  }
};

// The follower: coupled to the leader; ends with it (Done or CommandAborted as the leader).
class Follower : public FbBehaviour {
public:
  Axis* leader = nullptr;
  FbSlot* leaderFb = nullptr;
  double l0 = 0, f0 = 0, ratio = 0;
  std::shared_ptr<DirectGenerator> gen;
  void start(Kernel&, FbSlot&, Axis& ax, int64_t nowNs) override {
    gen = DirectGenerator::startOn(ax, nowNs);
    ax.setState(AxisState::DiscreteMotion);
    ax.master = leader;
  }
  void beforeStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override {
    if (!gen || ax.movement().gen != gen) return;
    const Kinematic& m = leader->set();
    gen->state = Kinematic{f0 + (m.p - l0) * ratio, m.v * ratio, m.a * ratio};
    gen->tSet = ax.movement().t(nowNs);
    if (leaderFb->out.busy && leaderFb->axis == leader) return;
    // The leader's command has ended in this cycle: the follower ends the same way, at rest.
    gen->state.v = gen->state.a = 0;
    ax.controller = nullptr;
    ax.master = nullptr;
    k.finish(fb, nullptr, cycle, leaderFb->out.done, !leaderFb->out.done, leaderFb->out.error ? leaderFb->out.errorId : Error::None);
    ax.setState(AxisState::Standstill);
  }
};

bool validInputs(const LineFollowInputs& in) {
  const bool modeOk = in.velocityMode == 0 || in.velocityMode == 1 || in.velocityMode == 3;
  return bounds::velocity(in.velocity) && bounds::rate(in.acceleration) && bounds::rate(in.deceleration) && bounds::jerk(in.jerk) &&
         (in.velocityMode == 0 || in.jerk > 0) && modeOk && bounds::position(in.endPos[0]) && bounds::position(in.endPos[1]);
}

}  // namespace

void callLineFollow(Kernel& k, FbSlot& fb, FbSlot& follow, Axis& master, Axis& slave, const LineFollowInputs& in,
                    LineFollowOutputs& out, const CallCtx& c) {
  Leader& b = behaviourOf<Leader>(fb);
  const bool haltEdge = in.halt && !b.in.halt, stopEdge = in.stop && !b.in.stop;
  b.in.halt = in.halt;
  b.in.stop = in.stop;
  Axis* lead = fb.axis && fb.axis->controller == &fb && fb.out.busy ? fb.axis : nullptr;
  if (lead && stopEdge) {
    fb.lastCallCycle = c.cycle;
    b.stopping = true;
    b.halted = false;
    b.brake(*lead, c.nowNs);
  } else if (lead && haltEdge && !b.halted && !b.stopping) {
    fb.lastCallCycle = c.cycle;
    b.halted = true;
    b.brake(*lead, c.nowNs);
  }
  // Both axes are shown at the call's instant (the leader was just sampled there).
  if (lead && (stopEdge || haltEdge) && follow.axis && follow.axis->controller == &follow) follow.axis->sample(c.nowNs);
  const bool rising = in.exec && !fb.execute;
  if (lead && rising && b.halted) {
    fb.execute = true;
    fb.lastCallCycle = c.cycle;
    b.halted = false;
    lead->sample(c.nowNs);
    b.plan(*lead, c.nowNs);
    if (follow.axis && follow.axis->controller == &follow) follow.axis->sample(c.nowNs);
  } else if (k.beginExecute(fb, in.exec, c) && !lead) {
    fb.axis = &master;
    follow.lastCallCycle = c.cycle;
    if (!validInputs(in)) return k.fail(fb, Error::MaInvalidVelAcc, c), void(out = LineFollowOutputs{});
    if (static_cast<int64_t>(in.ipoCycleUs) * 1000 != c.intervalNs) return k.fail(fb, Error::UnknownTaskInterval, c), void(out = {});
    if (&master == &slave) return k.fail(fb, Error::NotReadyForMotion, c), void(out = {});
    for (Axis* ax : {&master, &slave})
      if (Error e = k.motionStateError(*ax); e != Error::None) return k.fail(fb, e, c), void(out = {});
    master.sample(c.nowNs);
    slave.sample(c.nowNs);
    const double m0 = master.set().p, s0 = slave.set().p;
    const double m1 = in.relative ? m0 + in.endPos[0] : in.endPos[0];
    const double s1 = in.relative ? s0 + in.endPos[1] : in.endPos[1];
    // The master leads; when it does not move, the slave does (and the master follows with ratio 0).
    const bool masterLeads = m1 != m0 || s1 == s0;
    Axis& leader = masterLeads ? master : slave;
    Axis& follower = masterLeads ? slave : master;
    const double l0 = masterLeads ? m0 : s0, l1 = masterLeads ? m1 : s1;
    const double f0 = masterLeads ? s0 : m0, f1 = masterLeads ? s1 : m1;
    b.in = in;
    b.target = l1;
    fb.in = MoveInputs{};
    k.accept(fb, leader, c);
    Follower& f = behaviourOf<Follower>(follow);
    f.leader = &leader;
    f.leaderFb = &fb;
    f.l0 = l0;
    f.f0 = f0;
    f.ratio = l1 != l0 ? (f1 - f0) / (l1 - l0) : 0;
    follow.in = MoveInputs{};
    follow.execute = true;
    follow.functionStyle = true;   // called through the FB's own slot; the follower need not be "called"
    follow.out = FbOutputs{};
    k.accept(follow, follower, c);
  } else {
    fb.sync();
  }
  out.commandHalt = b.halted && fb.axis && fb.axis->controller == &fb;
  out.vel = fb.axis ? fb.axis->set().v : 0;
}

}  // namespace stc::motion
