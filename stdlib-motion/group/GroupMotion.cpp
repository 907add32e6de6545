// Group commands and the group's kernel step (docs/motion-groups.md, "Motion").
#include "stdlib-motion/group/GroupMotion.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/core/Kernel.h"
#include "stdlib-motion/core/Profiles.h"
#include "stdlib-motion/core/SyncPlan.h"

namespace stc::motion {

namespace {
// SMC_GroupWait: the members stand where the dwell began.
class HoldMotion : public GroupMotion {
public:
  std::vector<Kinematic> at_;
  double total = 0;
  void at(double, Kinematic* q) const override {
    for (size_t i = 0; i < at_.size(); ++i) q[i] = Kinematic{at_[i].p, 0, 0};
  }
  double duration() const override { return total; }
};
}  // namespace

void PtpMotion::at(double t, Kinematic* q) const {
  for (size_t i = 0; i < profiles.size(); ++i) q[i] = profiles[i].at(t);
}

PlanStatus planPtp(const std::vector<Kinematic>& start, const std::vector<double>& target, const std::vector<Limits>& lim,
                   PtpMotion& out, bool pathInvariant) {
  const size_t n = start.size();
  out.profiles.assign(n, Profile{});
  out.total = 0;
  bool atRest = true;
  for (size_t i = 0; i < n; ++i) atRest = atRest && start[i].v == 0 && start[i].a == 0;
  if (!atRest || pathInvariant) {
    SyncAxis axes[kMaxSyncAxes];
    for (size_t i = 0; i < n; ++i) axes[i] = SyncAxis{start[i], target[i], 0, lim[i]};
    Profile profiles[kMaxSyncAxes];
    const SyncResult r = atRest ? planPhaseSynchronized(axes, static_cast<int>(n), profiles)
                                : planSynchronized(axes, static_cast<int>(n), profiles);
    if (r.status != SyncStatus::Ok) return PlanStatus::InvalidLimits;
    out.profiles.assign(profiles, profiles + n);
    out.total = r.duration;
    return PlanStatus::Ok;
  }
  for (size_t i = 0; i < n; ++i) {
    if (PlanStatus s = planPosition(start[i], target[i], 0, lim[i], out.profiles[i]); s != PlanStatus::Ok) return s;
    out.total = std::max(out.total, out.profiles[i].duration());
  }
  if (out.total <= 0) return PlanStatus::Ok;
  // Time scaling of the faster members: the same plan at k times the speed lasts T_i / k.
  for (size_t i = 0; i < n; ++i) {
    const double ti = out.profiles[i].duration();
    if (ti <= 0 || ti >= out.total) continue;
    const double f = ti / out.total;
    Limits l = lim[i];
    l.vel *= f;
    l.acc *= f * f;
    l.dec *= f * f;
    l.jerk *= f * f * f;
    if (PlanStatus s = planPosition(start[i], target[i], 0, l, out.profiles[i]); s != PlanStatus::Ok) return s;
  }
  return PlanStatus::Ok;
}

namespace {

// The data of one group command (the FB slot's behaviour).
struct GroupCommand : FbBehaviour {
  enum class Kind : uint8_t { Direct, Halt, Stop, Path, Wait, Jog } kind = Kind::Direct;
  double waitTime = 0;
  std::vector<double> targets;   // Direct: absolute targets, fixed at the first start (continue reuses them)
  Limits anc[kMaxGroupAxes] = {};   // the ancillary axis limits when it was accepted ...
  uint64_t ancSerial = 0;           // ... and their serial
  DirectInputs direct;
  GroupStopInputs stop;
  PathInputs path;
  std::vector<path::Vec> splinePoints;   // the spec's points refer to these
  CoordSystem space = CoordSystem::ACS;  // Path: the planner space it runs in
  // Jog: the reference axes of X..C (null: not used), the coordinate each one drives, the
  // coordinates at the start (the unused ones keep them), the members' limits.
  JogInputs jog;
  int jogCoord[6] = {};
  double jogStart[kMaxGroupAxes] = {};
  std::vector<Limits> jogLim;
  uint64_t jogStartCycle = 0;
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}   // groups start commands themselves
};

GroupCommand& commandOf(FbSlot& fb) { return behaviourOf<GroupCommand>(fb); }

// MC_GroupContinue of saved data: every member within this of the continue position (units).
constexpr double kContinueTolerance = 1e-6;

// The slot that stands for the group as the command in control of member i.
FbSlot& memberSlot(Kernel& k, AxisGroup& g, size_t i) {
  FbSlot& s = k.slot(g.memberHandles[i], &g, FbKind::Group, nullptr);
  s.functionStyle = true;   // the group FB, not this slot, must be called in every cycle
  return s;
}

// The running PTP motion's own time (override: time scaling from rateNs on).
double groupTime(const AxisGroup& g, int64_t nowNs) { return g.rateTau + g.motionRate * static_cast<double>(nowNs - g.rateNs) * 1e-9; }

// The members' states of motion m at its own time t, in real time: the override's time
// scaling (rate f) makes velocities x f and accelerations x f^2.
void sampleScaled(const AxisGroup& g, const GroupMotion& m, double t, Kinematic* q) {
  m.at(t, q);
  const double f = g.motionRate;
  for (size_t i = 0; i < g.axes().size(); ++i) {
    q[i].v *= f;
    q[i].a *= f * f;
  }
}

bool controlsMembers(Kernel& k, AxisGroup& g) {
  if (g.gens.size() != g.axes().size()) return false;
  for (size_t i = 0; i < g.axes().size(); ++i)
    if (g.axes()[i]->controller != &memberSlot(k, g, i)) return false;
  return true;
}

// The members' exact present state (for a planner start or a PTP after a path).
std::vector<Kinematic> presentStates(Kernel& k, AxisGroup& g, int64_t nowNs) {
  std::vector<Kinematic> s(g.axes().size());
  if (g.lastMotion && controlsMembers(k, g)) {
    Kinematic q[kMaxGroupAxes];
    sampleScaled(g, *g.lastMotion, groupTime(g, nowNs), q);
    std::copy(q, q + s.size(), s.begin());
  } else if (controlsMembers(k, g)) {
    for (size_t i = 0; i < s.size(); ++i) s[i] = g.gens[i]->state;
  } else {
    for (size_t i = 0; i < s.size(); ++i) s[i] = g.axes()[i]->set();
  }
  return s;
}

// The group takes control of its members (a DirectGenerator each, SynchronizedMotion).
void takeMembers(Kernel& k, AxisGroup& g, int64_t nowNs) {
  if (controlsMembers(k, g)) return;
  g.gens.assign(g.axes().size(), nullptr);
  for (size_t i = 0; i < g.axes().size(); ++i) {
    Axis& ax = *g.axes()[i];
    FbSlot& ms = memberSlot(k, g, i);
    ms.axis = &ax;
    ms.out.busy = true;
    ax.sample(nowNs);
    ax.controller = &ms;
    g.gens[i] = DirectGenerator::startOn(ax, nowNs);
    ax.setState(AxisState::SynchronizedMotion);
  }
}

// The members are let go where they stand (GroupStandby: Standstill).
void releaseMembers(Kernel& k, AxisGroup& g) {
  for (size_t i = 0; i < g.axes().size(); ++i) {
    Axis& ax = *g.axes()[i];
    FbSlot& ms = memberSlot(k, g, i);
    ms.out.busy = false;
    if (ax.controller != &ms) continue;
    ax.controller = nullptr;
    // Where the group put it last (this step's set state is written but not yet stepped).
    ax.holdAt(i < g.gens.size() && g.gens[i] ? g.gens[i]->state.p : ax.set().p);
    if (ax.state() == AxisState::SynchronizedMotion) ax.setState(AxisState::Standstill);
  }
  g.gens.clear();
  g.lastMotion.reset();
}

// The members' dynamic limits for group PTP moves: their configured maxima x the factors.
// min(A, x) with A = 0 meaning no ancillary limit.
double capped(double a, double x) { return a > 0 ? std::min(a, x) : x; }

// The members' limits for a group PTP move: L = min(A, M x G) per component (docs/motion-groups.md).
bool memberLimits(const AxisGroup& g, double vf, double af, double jf, std::vector<Limits>& out, const Limits* anc = nullptr) {
  out.clear();
  if (!anc) anc = g.anc;
  for (size_t i = 0; i < g.axes().size(); ++i) {
    const AxisConfig& c = g.axes()[i]->config();
    if (!(c.maxVelocity > 0) || !(c.maxAcceleration > 0)) return false;
    const double dec = c.maxDeceleration > 0 ? c.maxDeceleration : c.maxAcceleration;
    const Limits& a = anc[i];
    out.push_back(Limits{capped(a.vel, c.maxVelocity * vf), capped(a.acc, c.maxAcceleration * af), capped(a.dec, dec * af),
                         c.maxJerk > 0 ? capped(a.jerk, c.maxJerk * jf) : 0});
  }
  return true;
}

// Ends every command of the group: the active one and the buffered ones.
void endCommands(Kernel& k, AxisGroup& g, const CallCtx* c, uint64_t cycle, Error e) {
  auto end = [&](FbSlot* fb) {
    if (!fb) return;
    fb->out.active = false;
    k.finish(*fb, c, cycle, false, e == Error::None, e);
  };
  end(g.pending);
  end(g.active);
  for (FbSlot* q : g.queue) end(q);
  for (auto& [id, fb] : g.pathCommands) end(fb);
  if (g.interrupted != g.active) end(g.interrupted);
  end(g.interrupter);
  g.interrupted = g.interrupter = nullptr;
  g.pathInterrupted = false;
  g.pending = g.active = nullptr;
  g.queue.clear();
  g.pathCommands.clear();
  if (g.planner && !g.saved.path) {   // (a path saved for MC_GroupContinue stays held)
    g.planner->clear();
    g.planner->clearEvents();
  }
  g.motion.reset();
  g.jogPcs = 0;
}

// SMC_GroupSaveContinueData / SMC_GroupEnableResumeAfterError: the saved motion is at rest at
// `pos`; the saving FB is Done (its native writes the continue data).
void completeSave(Kernel& k, AxisGroup& g, const double* pos, uint64_t cycle) {
  std::copy(pos, pos + g.axes().size(), g.saved.pos);
  g.saved.complete = true;
  if (g.saver) k.finish(*g.saver, nullptr, cycle, true, false, Error::None);
  g.saver = nullptr;
}

// The group goes to GroupErrorStop: its commands end with the error, the members
// that are not in error brake with their own deceleration.
void brakeMembers(Kernel& k, AxisGroup& g, int64_t nowNs) {
  for (size_t i = 0; i < g.axes().size(); ++i) {
    Axis& ax = *g.axes()[i];
    FbSlot& ms = memberSlot(k, g, i);
    ms.out.busy = false;
    if (ax.controller != &ms) continue;   // in ErrorStop, or taken by a single-axis command
    ax.controller = nullptr;
    if (ax.state() == AxisState::ErrorStop) continue;
    if (ax.set().v == 0 && ax.set().a == 0) {
      ax.holdAt(ax.set().p);
      ax.setState(AxisState::Standstill);
      continue;
    }
    const AxisConfig& c = ax.config();
    const double dec = c.errorDeceleration > 0 ? c.errorDeceleration : c.maxDeceleration > 0 ? c.maxDeceleration : 1000.0;
    ax.sample(nowNs);
    ax.startStop(Limits{1, dec, dec, 0}, nowNs);
    ax.setState(AxisState::Stopping);
  }
  g.gens.clear();
  g.lastMotion.reset();
}

bool pathMode(const AxisGroup& g);

// SMC_GroupEnableResumeAfterError: the running MoveDirect or path (with the moves queued on
// it) is kept where its set point stands when a member's error stops the group.
void saveForResume(AxisGroup& g) {
  if (g.gens.size() != g.axes().size()) return;
  bool path = pathMode(g) && !g.pathCommands.empty() && !g.pathInterrupted;
  for (const auto& [id, fb] : g.pathCommands) path = path && commandOf(*fb).kind == GroupCommand::Kind::Path;
  const bool ptp = !path && g.active && commandOf(*g.active).kind == GroupCommand::Kind::Direct;
  if (!path && !ptp) return;
  g.dropSaved();
  g.saved.token = ++g.interruptToken;
  if (path) {
    g.planner->freeze();
    g.saved.path = true;
  } else {
    g.saved.ptp = std::make_shared<GroupCommand>(commandOf(*g.active));
  }
  for (size_t i = 0; i < g.axes().size(); ++i) g.saved.pos[i] = g.gens[i]->state.p;
  g.saved.complete = true;
}

void groupError(Kernel& k, AxisGroup& g, Error groupErr, Error axisErr, int64_t nowNs, uint64_t cycle) {
  if (g.resumeAfterError && groupErr == Error::AgAxisError) saveForResume(g);
  endCommands(k, g, nullptr, cycle, groupErr);
  brakeMembers(k, g, nowNs);
  g.ended = false;
  g.enterErrorStop(groupErr, axisErr);
}

// Makes m the group's running motion from originNs at the given rate (also the latest
// motion, which the next command starts from).
void runMotion(AxisGroup& g, std::shared_ptr<const GroupMotion> m, int64_t originNs, double rate) {
  g.motion = m;
  g.lastMotion = std::move(m);
  g.originNs = g.lastOriginNs = g.rateNs = originNs;
  g.rateTau = 0;
  g.motionRate = rate;
}

// Where each member comes to rest when it brakes from `start` under its limits (to velocity 0).
std::vector<double> brakeTargets(const std::vector<Kinematic>& start, const std::vector<Limits>& lim) {
  std::vector<double> target(start.size());
  for (size_t i = 0; i < start.size(); ++i) {
    Profile p;
    planVelocity(start[i], 0, lim[i], p);
    target[i] = p.end().p;
  }
  return target;
}

Error directTargets(const Kernel& k, const AxisGroup& g, const DirectInputs& d, const double* q, double* out);

// Starts fb (the group's next command) at nowNs from the members' present set states.
Error startCommand(Kernel& k, AxisGroup& g, FbSlot& fb, int64_t nowNs, int64_t originNs) {
  GroupCommand& cmd = commandOf(fb);
  // The members' exact state now: from the group's latest motion while it controls them
  // (the axes have not been stepped in this cycle yet), else their set states.
  const std::vector<Kinematic> start = presentStates(k, g, nowNs);
  takeMembers(k, g, nowNs);
  const double rate = cmd.kind == GroupCommand::Kind::Stop ? 1.0 : g.rate;   // MC_GroupStop ignores the override
  if (cmd.kind == GroupCommand::Kind::Jog) {
    // Tracking: stepJog moves the members from their states (no precomputed motion).
    g.motion.reset();
    g.lastMotion.reset();
  } else if (cmd.kind == GroupCommand::Kind::Wait) {
    auto hold = std::make_shared<HoldMotion>();
    hold->at_ = start;
    hold->total = cmd.waitTime;
    runMotion(g, std::move(hold), originNs, rate);
  } else {
    std::vector<Limits> lim;
    std::vector<double> target;
    if (cmd.kind == GroupCommand::Kind::Direct) {
      const Limits* anc = cmd.ancSerial < g.ancImmediate ? g.anc : cmd.anc;   // an immediate change since: the group's
      if (!memberLimits(g, cmd.direct.velFactor, cmd.direct.accFactor, cmd.direct.jerkFactor, lim, anc)) return Error::AgAxisLimitsMissing;
      if (cmd.targets.size() != start.size()) {   // the first start (a continue keeps the targets)
        double q[kMaxGroupAxes] = {}, t[kMaxGroupAxes] = {};
        for (size_t i = 0; i < start.size(); ++i) q[i] = start[i].p;
        if (Error e = directTargets(k, g, cmd.direct, q, t); e != Error::None) return e;
        cmd.targets.assign(t, t + start.size());
      }
      target = cmd.targets;
    } else {
      // Halt / stop: every member brakes to rest along its own profile (the PTP path is
      // not defined); Deceleration and Jerk are the group's, limited by the axes' maxima.
      if (!memberLimits(g, 1, 1, 1, lim)) return Error::AgAxisLimitsMissing;
      for (size_t i = 0; i < lim.size(); ++i) {
        Limits& l = lim[i];
        l.vel = std::max(l.vel, std::fabs(start[i].v));
        l.dec = cmd.stop.deceleration * cmd.stop.accFactor;
        l.acc = std::max(l.acc, l.dec);
        l.jerk = cmd.stop.jerk > 0 ? cmd.stop.jerk * cmd.stop.jerkFactor : 0;
      }
      target = brakeTargets(start, lim);
    }
    auto m = std::make_shared<PtpMotion>();
    const bool invariant = cmd.kind == GroupCommand::Kind::Direct && cmd.direct.pathInvariant;
    if (planPtp(start, target, lim, *m, invariant) != PlanStatus::Ok) return Error::AgAxisLimitsMissing;
    runMotion(g, std::move(m), originNs, rate);
  }
  g.active = &fb;
  g.ended = false;
  g.activeMovementId = fb.out.movementId;
  g.setState(cmd.kind == GroupCommand::Kind::Stop ? GroupState::Stopping : GroupState::Moving);
  fb.out.active = true;
  fb.sync();
  return Error::None;
}

// The accepting call: CommandAccepted, Busy and a movement id.
void accepted(AxisGroup& g, FbSlot& fb) {
  fb.out.busy = true;
  fb.out.commandAccepted = true;
  fb.out.movementId = static_cast<uint32_t>(g.nextMovementId++);
  fb.sync();
}

// SMC_GroupTargetPosition: the target of a move just accepted.  Relative moves add to the
// previous queued target, or (aborting, or nothing queued) to the present position.
// The target is kept in the move's space (ACS, MCS or a dynamic PCS: g.targetCs).
void noteTarget(Kernel& k, AxisGroup& g, const double* value, bool relative, bool fromPresent, int64_t nowNs,
                CoordSystem space = CoordSystem::ACS) {
  if (relative && (fromPresent || !g.targetValid || g.targetCs != space)) {
    const std::vector<Kinematic> s = presentStates(k, g, nowNs);
    double q[kMaxGroupAxes] = {};
    for (size_t i = 0; i < s.size(); ++i) q[i] = s[i].p;
    if (!coordsOf(k, g, space, q, g.target)) std::copy(q, q + kMaxGroupAxes, g.target);
  }
  const int n = coordCount(g, space);
  for (int i = 0; i < n; ++i) g.target[i] = relative ? g.target[i] + value[i] : value[i];
  g.targetCs = space;
  g.targetValid = true;
}

// TCS: the pose x (X..C in MCS) moved by `delta` given in the tool's own frame; false when
// the displacement is not finite or implausible.
bool toolRelative(double* x, const double* delta) {
  Frame tool, d;
  if (!Frame::fromCoords(x, tool) || !Frame::fromCoords(delta, d)) return false;
  double near[3] = {x[3], x[4], x[5]};
  (tool * d).toCoords(x, near);
  return true;
}

// A Direct move's target in its own system -> the members' targets, from the members at q.
Error directTargets(const Kernel& k, const AxisGroup& g, const DirectInputs& d, const double* q, double* out) {
  const size_t n = g.axes().size();
  CoordSystem cs = static_cast<CoordSystem>(d.coordSystem);
  const bool relative = d.relative || cs == CoordSystem::TCS;
  if (cs == CoordSystem::TCS) cs = CoordSystem::MCS;
  if (cs == CoordSystem::ACS || (!g.kin && cs == CoordSystem::MCS)) {
    for (size_t i = 0; i < n; ++i) out[i] = relative ? q[i] + d.position[i] : d.position[i];
    return Error::None;
  }
  double x[kMaxGroupAxes] = {};
  if (!coordsOf(k, g, cs, q, x)) return Error::AgInvalidCoordSystem;
  const int m = coordCount(g, cs);
  if (static_cast<CoordSystem>(d.coordSystem) == CoordSystem::TCS && g.kin) {
    // In the tool's frame: the pose becomes tool x displacement (position turned with the
    // tool, orientation composed); additional axes add.
    if (!toolRelative(x, d.position)) return Error::AgInvalidMoveInputs;
    for (int i = 6; i < m; ++i) x[i] += d.position[i];
  } else {
    for (int i = 0; i < m; ++i) x[i] = relative ? x[i] + d.position[i] : d.position[i];
  }
  if (!jointsOf(k, g, cs, x, g.kinConfig, q, out)) return Error::AgUnreachable;
  return Error::None;
}

// The state checks every group motion command makes in its call.
Error motionRefusal(Kernel& k, AxisGroup& g) {
  if (!g.enabled()) return Error::AgNotEnabled;
  if (g.state() == GroupState::ErrorStop) return Error::AgInErrorStop;
  if (g.state() == GroupState::Stopping) return Error::AgStopping;
  for (size_t i = 0; i < g.axes().size(); ++i) {
    const Axis& ax = *g.axes()[i];
    if (!ax.ready()) return Error::AgAxisNotReady;
    // A single-axis command on a member: the group goes to GroupErrorStop (CODESYS).
    if (ax.controller && ax.controller != &memberSlot(k, g, i)) return Error::AgSingleAxisActive;
  }
  return Error::None;
}

// Execute's falling edge clears CommandAccepted (it follows Execute).
void followExecute(FbSlot& fb, bool execute) {
  if (!execute && fb.out.commandAccepted) {
    fb.out.commandAccepted = false;
    fb.sync();
  }
}

// ---- path moves

bool pathMode(const AxisGroup& g) { return g.planner && (!g.pathCommands.empty() || g.planner->sample().moving); }
bool ptpBusy(const AxisGroup& g) {
  if (g.pending || g.active) return true;
  for (const FbSlot* q : g.queue)
    if (q->behaviour && static_cast<const GroupCommand&>(*q->behaviour).kind != GroupCommand::Kind::Path) return true;
  return false;
}

// Does the path's space need the kinematics (or a moving frame) to give the joints?
bool pathThroughKinematics(const AxisGroup& g) {
  return g.pathCs != CoordSystem::ACS && (g.kin || g.pathCs != CoordSystem::MCS);
}

// The joints for path coordinates x in the path's space, near qNear (the path keeps the
// configuration it started in).
bool pathJoints(const Kernel& k, const AxisGroup& g, const double* x, const double* qNear, double* q) {
  const KinConfigData cfg = g.kin ? g.kin->configOf(qNear) : KinConfigData{};
  return jointsOf(k, g, g.pathCs, x, cfg, qNear, q);
}

path::Planner& plannerOf(Kernel& k, AxisGroup& g) {
  if (!g.planner) {
    path::PlannerConfig pc;
    pc.dims = coordCount(g, g.pathCs);
    // The members' velocity and acceleration limits bound the path (when every member has them).
    bool all = true;
    for (const Axis* ax : g.axes()) all = all && ax->config().maxVelocity > 0 && ax->config().maxAcceleration > 0;
    if (all || pathThroughKinematics(g)) {
      pc.axes.count = static_cast<int>(g.axes().size());
      for (size_t i = 0; i < g.axes().size() && all; ++i) {
        const AxisConfig& ac = g.axes()[i]->config();
        pc.axes.vel[i] = capped(g.anc[i].vel, ac.maxVelocity);
        pc.axes.acc[i] = capped(g.anc[i].dec, capped(g.anc[i].acc, ac.maxAcceleration));
      }
      // Through the kinematics: the joints' path derivatives by central differences of the
      // inverse (h along s), from the joints at the point itself.  Also without axis limits:
      // the map refuses a path through a point out of reach.
      if (pathThroughKinematics(g)) {
        const Kernel* kp = &k;
        const AxisGroup* gp = &g;
        pc.axes.map = [kp, gp](const path::Vec& pos, const path::Vec& d1, const path::Vec& d2, path::Vec& dq, path::Vec& d2q) {
          constexpr double h = 1e-4;
          double near[kMaxGroupAxes], q0[kMaxGroupAxes], qp[kMaxGroupAxes], qm[kMaxGroupAxes];
          path::Vec xp = pos, xm = pos;
          for (size_t i = 0; i < gp->axes().size(); ++i) near[i] = gp->axes()[i]->set().p;
          for (int i = 0; i < path::kMaxCoords; ++i) {
            xp[i] += h * d1[i] + 0.5 * h * h * d2[i];
            xm[i] += -h * d1[i] + 0.5 * h * h * d2[i];
          }
          if (!jointsOf(*kp, *gp, gp->pathCs, pos.data(), gp->kin ? gp->kin->configOf(near) : KinConfigData{}, near, q0)) return false;
          if (!pathJoints(*kp, *gp, xp.data(), q0, qp) || !pathJoints(*kp, *gp, xm.data(), q0, qm)) return false;
          dq = path::Vec{};
          d2q = path::Vec{};
          for (size_t i = 0; i < gp->axes().size(); ++i) {
            dq[i] = (qp[i] - qm[i]) / (2 * h);
            d2q[i] = (qp[i] - 2 * q0[i] + qm[i]) / (h * h);
          }
          return true;
        };
      } else if (g.kin) {
        pc.axes.count = pc.dims;   // joint space: the members are the coordinates
      }
    }
    g.planner = std::make_unique<path::Planner>(pc);
    g.planner->setOverride(g.rate);   // an override set before the first path move
  }
  return *g.planner;
}

// The space a path move in cs runs in (GroupKinematics.h): dynamic PCS as given, ACS of a
// group with kinematics, else MCS (a group without kinematics: MCS = the members).
CoordSystem pathSpace(const AxisGroup& g, CoordSystem cs) {
  if ((cs == CoordSystem::PCS1 || cs == CoordSystem::PCS2) && g.pcs[cs == CoordSystem::PCS1 ? 0 : 1].master != UINT32_MAX) return cs;
  if (cs == CoordSystem::ACS && g.kin) return CoordSystem::ACS;
  return CoordSystem::MCS;
}

// Moves a path move given in the static Cartesian system cs into MCS: points through the
// frames, displacements and the plane normal rotated.  False when a frame is missing.
bool specToMcs(const Kernel& k, const AxisGroup& g, CoordSystem cs, path::MoveSpec& m, std::vector<path::Vec>& points) {
  if (cs == CoordSystem::MCS || cs == CoordSystem::TCS || cs == CoordSystem::ACS) return true;
  Frame f, mcs;
  if (!frameInWorld(k, g, cs, f) || !frameInWorld(k, g, CoordSystem::MCS, mcs)) return false;
  const Frame t = mcs.inverse() * f;
  auto point = [&](path::Vec& v) { return convertCoords(k, g, cs, CoordSystem::MCS, v.data(), v.data()); };
  auto vector = [&](path::Vec& v) {
    t.vector(v.data(), v.data());
    if (g.kin)
      for (int i = 0; i < 3; ++i)
        if (!(g.kin->controlled() & (1u << i))) v[i] = 0;
    return true;
  };
  bool ok = vector(m.normal);
  if (m.relative) {
    ok = ok && vector(m.end) && vector(m.aux);
    for (path::Vec& p : points) ok = ok && vector(p);
  } else {
    ok = ok && point(m.end) && (m.centerRelative ? vector(m.aux) : point(m.aux));
    for (path::Vec& p : points) ok = ok && point(p);
  }
  return ok;
}

// A relative path move given in the tool's frame at pose `base` (MCS) -> relative in MCS:
// end and spline points become (base x displacement) - base, the orientation composed with the
// tool's; circle points and the plane normal turn with the tool.
bool specFromTool(const double* base, path::MoveSpec& m, std::vector<path::Vec>& points) {
  Frame tool;
  if (!Frame::fromCoords(base, tool)) return false;
  auto displacement = [&](path::Vec& v) {
    double x[6];
    std::copy(base, base + 6, x);
    if (!toolRelative(x, v.data())) return false;
    for (int i = 0; i < 6; ++i) v[i] = x[i] - base[i];
    return true;
  };
  bool ok = displacement(m.end);
  for (path::Vec& p : points) ok = ok && displacement(p);
  tool.vector(m.aux.data(), m.aux.data());
  tool.vector(m.normal.data(), m.normal.data());
  return ok;
}

Error pathError(const path::AppendResult& r) {
  switch (r.status) {
    case path::PathStatus::Ok: return Error::None;
    case path::PathStatus::QueueFull: return Error::BufferFull;
    case path::PathStatus::InvalidGeometry: return Error::AgInvalidGeometry;
    case path::PathStatus::BlendingNeedsTransition: return Error::AgBlendingNotSupported;
    case path::PathStatus::TransitionNotAllowed: return Error::AgTransitionNotAllowed;
    case path::PathStatus::Unreachable: return Error::AgUnreachable;
    default: return Error::AgInvalidMoveInputs;
  }
}

// Hands fb's path move to the planner (from the members' present state when it is idle).
Error appendPath(Kernel& k, AxisGroup& g, FbSlot& fb, int64_t nowNs, uint64_t cycle) {
  if (g.plannerStale && !pathMode(g)) {
    g.planner.reset();
    g.dropSaved();
    g.plannerStale = false;
  }
  GroupCommand& cmd = commandOf(fb);
  if (!pathMode(g) && cmd.space != g.pathCs) {   // another space: another planner
    g.planner.reset();
    g.dropSaved();
    g.pathCs = cmd.space;
  }
  path::Planner& p = plannerOf(k, g);
  if (!pathMode(g)) {
    g.dropSaved();   // a new path: a held one is not continued
    g.pathStartCycle = cycle;
    const std::vector<Kinematic> s = presentStates(k, g, nowNs);
    double q[kMaxGroupAxes] = {};
    for (size_t i = 0; i < s.size(); ++i) q[i] = s[i].p;
    path::Vec pos{};
    if (!coordsOf(k, g, g.pathCs, q, pos.data())) return Error::AgUnreachable;
    p.clear();
    p.setPosition(pos);
  }
  path::MoveSpec spec = cmd.path.spec;
  spec.points = cmd.splinePoints;
  const path::AppendResult r = p.append(spec);
  if (Error e = pathError(r); e != Error::None) return e;
  g.pathCommands.push_back({r.id, &fb});
  takeMembers(k, g, nowNs);
  g.lastMotion.reset();
  g.ended = false;
  g.setState(GroupState::Moving);
  return Error::None;
}

// Brings a running planner to the time of this call (its last step was the previous cycle's).
void advanceToCall(AxisGroup& g, const CallCtx& c) {
  if (!g.planner || g.pathAdvancedCycle == c.cycle || g.pathStartCycle == c.cycle || !g.planner->sample().moving) return;
  g.planner->advance(static_cast<double>(c.intervalNs) * 1e-9);
  g.pathAdvancedCycle = c.cycle;
}

// The planner's events of this step or call: Active, Done, CommandAborted of the path FBs.
void drainPathEvents(Kernel& k, AxisGroup& g, const CallCtx* c, uint64_t cycle) {
  if (!g.planner) return;
  std::vector<path::Event> events(g.planner->events().begin(), g.planner->events().end());
  g.planner->clearEvents();
  if (!c) {   // a step: first the moves started by calls of this cycle
    for (uint32_t id : g.startedInCall) events.insert(events.begin(), path::Event{id, path::EventKind::Started, 0});
    g.startedInCall.clear();
  }
  for (const path::Event& e : events) {
    auto it = std::find_if(g.pathCommands.begin(), g.pathCommands.end(), [&](const auto& pc) { return pc.first == e.id; });
    if (it == g.pathCommands.end()) continue;
    FbSlot& fb = *it->second;
    if (e.kind == path::EventKind::Started && c) {   // in a call: Active from the step on
      g.startedInCall.push_back(e.id);
      continue;
    }
    if (e.kind == path::EventKind::Started) {
      fb.out.active = true;
      g.activeMovementId = fb.out.movementId;
      fb.sync();
      continue;
    }
    g.pathCommands.erase(it);
    fb.out.active = false;
    const bool stop = commandOf(fb).kind == GroupCommand::Kind::Stop;
    k.finish(fb, c, cycle, e.kind == path::EventKind::Done, e.kind == path::EventKind::Aborted, Error::None);
    // MC_GroupStop holds GroupStopping until its Execute falls (callGroupBrake).
    if (stop) g.setState(fb.execute ? GroupState::Stopping : GroupState::Moving);
  }
}

// A move behind running moves of the other kind (PTP / path): queued in the group until they
// end; Aborting them is refused (the path planner cannot start from motion).
void queueBehindOtherKind(Kernel& k, AxisGroup& g, FbSlot& fb, BufferMode mode, const CallCtx& c) {
  if (mode == BufferMode::Aborting) return k.fail(fb, Error::AgModeChangeWhileMoving, c);
  if (g.queue.size() >= k.profile.queueCapacity) return k.fail(fb, Error::BufferFull, c);
  g.queue.push_back(&fb);
  accepted(g, fb);
}

}  // namespace

void callGroupMovePath(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const PathInputs& in, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return followExecute(fb, execute);
  fb.out.commandAccepted = false;
  auto factor = [](double f) { return std::isfinite(f) && f > 0 && f <= 1; };
  if (!factor(in.velFactor) || !factor(in.accFactor) || !factor(in.jerkFactor)) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (!validBufferMode(in.bufferMode)) return k.fail(fb, Error::InvalidBufferMode, c);
  if (in.transitionMode < 0 || in.transitionMode > 4) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (!validCoordSystem(in.coordSystem)) return k.fail(fb, Error::AgInvalidCoordSystem, c);
  if (Error e = motionRefusal(k, g); e != Error::None) {
    if (e == Error::AgSingleAxisActive) groupError(k, g, e, Error::None, c.nowNs, c.cycle);
    return k.fail(fb, e, c);
  }
  GroupCommand& cmd = commandOf(fb);
  cmd.kind = GroupCommand::Kind::Path;
  cmd.path = in;
  // L = min(A, C) for the path (SMC_GroupSetAncillaryPathLimits); jerk 0 = trapezoidal stays 0.
  path::Dynamics& dyn = cmd.path.spec.dyn;
  dyn.vel = capped(g.ancPath.vel, dyn.vel);
  dyn.acc = capped(g.ancPath.acc, dyn.acc);
  dyn.dec = capped(g.ancPath.dec, dyn.dec);
  if (dyn.jerk > 0) dyn.jerk = capped(g.ancPath.jerk, dyn.jerk);
  cmd.path.spec.buffer = static_cast<path::BufferMode>(in.bufferMode);
  cmd.path.spec.transition = static_cast<path::TransitionMode>(in.transitionMode);
  cmd.splinePoints.assign(in.spec.points.begin(), in.spec.points.end());
  const CoordSystem cs = static_cast<CoordSystem>(in.coordSystem);
  cmd.space = pathSpace(g, cs);
  if (cmd.space == CoordSystem::MCS && !specToMcs(k, g, cs, cmd.path.spec, cmd.splinePoints)) return k.fail(fb, Error::AgInvalidCoordSystem, c);
  if (in.orientationMode != 0 && in.orientationMode != 1) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  const unsigned turning = g.kin ? g.kin->controlled() & 0b111000u : 0;
  if (cmd.space == CoordSystem::MCS && turning) {
    // The tool's pose where the move starts: the predecessor's end when it is queued behind
    // one, else where the tool is now (an aborting move while the path moves takes the tool's
    // present orientation, not yet that of its stop point).
    double base[kMaxGroupAxes] = {};
    const bool behind = in.bufferMode != BufferMode::Aborting && (ptpBusy(g) || !g.queue.empty() || pathMode(g));
    if (behind && g.targetValid && g.targetCs == CoordSystem::MCS) {
      std::copy(g.target, g.target + kMaxGroupAxes, base);
    } else {
      const std::vector<Kinematic> s = presentStates(k, g, c.nowNs);
      double q[kMaxGroupAxes] = {};
      for (size_t i = 0; i < s.size(); ++i) q[i] = s[i].p;
      if (!coordsOf(k, g, CoordSystem::MCS, q, base)) return k.fail(fb, Error::AgUnreachable, c);
    }
    // TCS: in the tool's frame there.
    if (cs == CoordSystem::TCS && !specFromTool(base, cmd.path.spec, cmd.splinePoints)) return k.fail(fb, Error::AgInvalidMoveInputs, c);
    // GreatCircle and Axis differ only when more than one orientation axis turns.
    const path::MoveSpec& m = cmd.path.spec;
    bool turns = false;
    for (int i = 3; i < 6; ++i) {
      const double d = m.relative ? m.end[i] : m.end[i] - base[i];
      turns = turns || std::fabs(std::remainder(d, 360.0)) > 1e-9;
    }
    if (in.orientationMode == 0 && turns && (turning & (turning - 1))) return k.fail(fb, Error::AgOrientationMode, c);
  }
  fb.axis = nullptr;
  // Behind a PTP move (or a path in another space): buffered until it ends; aborting a moving
  // PTP move by a path move needs a stop first (docs/motion-groups.md).
  double end[kMaxGroupAxes];
  for (size_t i = 0; i < kMaxGroupAxes; ++i) end[i] = cmd.path.spec.end[i];
  if (ptpBusy(g) || !g.queue.empty() || (pathMode(g) && cmd.space != g.pathCs)) {
    queueBehindOtherKind(k, g, fb, in.bufferMode, c);
    if (!fb.out.error) noteTarget(k, g, end, in.spec.relative, false, c.nowNs, cmd.space);
    return;
  }
  const bool wasMoving = pathMode(g);
  if (in.bufferMode == BufferMode::Aborting) advanceToCall(g, c);   // the replaced path stops from now
  if (Error e = appendPath(k, g, fb, c.nowNs, c.cycle); e != Error::None) return k.fail(fb, e, c);
  noteTarget(k, g, end, in.spec.relative, !wasMoving, c.nowNs, cmd.space);
  // Aborting a moving path: the new move starts where the old one stops, which is not known
  // yet, so a relative target is unknown (SMC_GroupTargetPosition not Valid, manual case 1).
  if (wasMoving && in.bufferMode == BufferMode::Aborting && in.spec.relative) g.targetValid = false;
  accepted(g, fb);
  drainPathEvents(k, g, &c, c.cycle);   // Aborting: the replaced moves end in this call
}

void callGroupMoveDirect(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const DirectInputs& in, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return followExecute(fb, execute);
  fb.out.commandAccepted = false;
  const size_t n = g.axes().size();
  bool finite = bounds::rate(in.velFactor) && bounds::rate(in.accFactor) && bounds::rate(in.jerkFactor) && in.velFactor <= 1 &&
                in.accFactor <= 1 && in.jerkFactor <= 1;
  for (size_t i = 0; i < n; ++i) finite = finite && bounds::position(in.position[i]);
  if (!finite) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (!validBufferMode(in.bufferMode)) return k.fail(fb, Error::InvalidBufferMode, c);
  // Blending needs a transition element (TMNone is not allowed with it, manual 1.5); PTP
  // moves have no transition elements yet (docs/motion-groups.md).
  if (in.bufferMode != BufferMode::Aborting && in.bufferMode != BufferMode::Buffered) return k.fail(fb, Error::AgBlendingNotSupported, c);
  if (in.transitionMode < 0 || in.transitionMode > 4) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (in.transitionMode != 0) return k.fail(fb, Error::AgTransitionNotAllowed, c);   // Aborting / Buffered: TMNone only
  if (!validCoordSystem(in.coordSystem)) return k.fail(fb, Error::AgInvalidCoordSystem, c);
  if (Error e = motionRefusal(k, g); e != Error::None) {
    if (e == Error::AgSingleAxisActive) groupError(k, g, e, Error::None, c.nowNs, c.cycle);
    return k.fail(fb, e, c);
  }
  std::vector<Limits> lim;
  if (!memberLimits(g, in.velFactor, in.accFactor, in.jerkFactor, lim)) return k.fail(fb, Error::AgAxisLimitsMissing, c);
  // An absolute Cartesian target must be reachable (checked again when the move starts).
  const CoordSystem dcs = static_cast<CoordSystem>(in.coordSystem);
  const CoordSystem space = dcs == CoordSystem::ACS || !g.kin ? CoordSystem::ACS : dcs == CoordSystem::TCS ? CoordSystem::MCS : dcs;
  double noted[kMaxGroupAxes];
  std::copy(in.position, in.position + kMaxGroupAxes, noted);
  if (space != CoordSystem::ACS || (dcs != CoordSystem::ACS && dcs != CoordSystem::TCS)) {
    double q[kMaxGroupAxes] = {}, t[kMaxGroupAxes] = {};
    const std::vector<Kinematic> s = presentStates(k, g, c.nowNs);
    for (size_t i = 0; i < s.size(); ++i) q[i] = s[i].p;
    if (!in.relative && dcs != CoordSystem::TCS) {
      if (Error e = directTargets(k, g, in, q, t); e != Error::None) return k.fail(fb, e, c);
      if (!g.kin) std::copy(t, t + kMaxGroupAxes, noted);   // no kinematics: the members' targets
    }
  }
  GroupCommand& cmd = commandOf(fb);
  cmd.kind = GroupCommand::Kind::Direct;
  cmd.direct = in;
  std::copy(g.anc, g.anc + kMaxGroupAxes, cmd.anc);
  cmd.ancSerial = g.ancSerial;
  fb.axis = nullptr;
  // Behind path moves: buffered until the path ends; a moving path is not aborted by a PTP move.
  const bool rel = in.relative || dcs == CoordSystem::TCS;
  const CoordSystem noteSpace = g.kin ? space : CoordSystem::ACS;
  if (pathMode(g)) {
    queueBehindOtherKind(k, g, fb, in.bufferMode, c);
    if (!fb.out.error) noteTarget(k, g, noted, rel, false, c.nowNs, noteSpace);
    return;
  }
  const bool idle = !g.pending && !g.active && g.queue.empty();
  noteTarget(k, g, noted, rel, in.bufferMode == BufferMode::Aborting || idle, c.nowNs, noteSpace);
  if (in.bufferMode == BufferMode::Aborting || idle) {
    // The running and buffered commands end now; fb starts in this cycle's step.
    endCommands(k, g, &c, c.cycle, Error::None);
    g.pending = &fb;
  } else {
    if (g.queue.size() >= k.profile.queueCapacity) return k.fail(fb, Error::BufferFull, c);
    g.queue.push_back(&fb);
  }
  accepted(g, fb);
}

void callGroupWait(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, double waitTime, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return followExecute(fb, execute);
  fb.out.commandAccepted = false;
  if (!std::isfinite(waitTime) || waitTime < 0 || waitTime > 1e9) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (Error e = motionRefusal(k, g); e != Error::None) return k.fail(fb, e, c);
  GroupCommand& cmd = commandOf(fb);
  cmd.kind = GroupCommand::Kind::Wait;
  cmd.waitTime = waitTime;
  fb.axis = nullptr;
  // Always queued behind what the group does; on an idle group it starts in this cycle's step.
  const bool idle = !g.pending && !g.active && g.queue.empty() && !pathMode(g);
  if (idle) {
    g.pending = &fb;
  } else {
    if (g.queue.size() >= k.profile.queueCapacity) return k.fail(fb, Error::BufferFull, c);
    g.queue.push_back(&fb);
  }
  accepted(g, fb);
}

namespace {

void callGroupBrake(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const GroupStopInputs& in, const CallCtx& c,
                    GroupCommand::Kind kind) {
  const bool wasDone = fb.out.done;
  const bool rising = k.beginExecute(fb, execute, c);
  if (kind == GroupCommand::Kind::Stop && !execute && wasDone && g.state() == GroupState::Stopping && !g.active && !pathMode(g)) {
    // MC_GroupStop holds GroupStopping until its Execute falls (PLCopen Part 4).
    g.setState(GroupState::Standby);
    releaseMembers(k, g);
  }
  if (!rising) return followExecute(fb, execute);
  fb.out.commandAccepted = false;
  if (!bounds::rate(in.deceleration) || !bounds::jerk(in.jerk) || !bounds::rate(in.accFactor) || !bounds::rate(in.jerkFactor) ||
      in.accFactor > 1 || in.jerkFactor > 1)
    return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (!g.enabled()) return k.fail(fb, Error::AgNotEnabled, c);
  if (g.state() == GroupState::ErrorStop) return k.fail(fb, Error::AgInErrorStop, c);
  // A group stop in progress cannot be aborted (only by itself).
  if (g.state() == GroupState::Stopping && g.active && g.active != &fb) {
    if (kind == GroupCommand::Kind::Halt) return k.fail(fb, Error::AgStopping, c);
  }
  GroupCommand& cmd = commandOf(fb);
  cmd.kind = kind;
  cmd.stop = in;
  fb.axis = nullptr;
  g.targetValid = false;   // unknown until the group stands
  // SMC_GroupSaveContinueData called before in this cycle: the motion is kept for MC_GroupContinue.
  const bool save = g.saver && !g.saverTaken && g.saverCycle == c.cycle;
  if (pathMode(g)) {
    // On the path: the planner brakes along it; every queued move (and PTP behind it) ends.
    for (FbSlot* q : g.queue) k.finish(*q, &c, c.cycle, false, true, Error::None);
    g.queue.clear();
    // An interrupted path is not continued after a halt: the interrupt ends too.
    if (g.interrupter) k.finish(*g.interrupter, &c, c.cycle, false, true, Error::None);
    g.interrupter = nullptr;
    g.pathInterrupted = false;
    advanceToCall(g, c);
    bool moves = !g.pathCommands.empty();
    for (const auto& [id, p] : g.pathCommands) moves = moves && commandOf(*p).kind == GroupCommand::Kind::Path;
    if (save && moves) {
      // The moves end (CommandAborted) but the planner holds the rest of the path: a feed hold
      // with the halt's dynamics, this FB Done at rest (stepPath), then the save completes.
      for (auto& [id, p] : g.pathCommands) {
        p->out.active = false;
        k.finish(*p, &c, c.cycle, false, true, Error::None);
      }
      g.pathCommands.clear();
      g.dropSaved();
      g.saverTaken = true;
      g.saved.token = ++g.interruptToken;
      g.saved.path = true;
      g.planner->interrupt(in.deceleration * in.accFactor, in.jerk * in.jerkFactor);
      g.interrupter = &fb;
      g.pathInterrupted = true;
      g.setState(kind == GroupCommand::Kind::Stop ? GroupState::Stopping : GroupState::Moving);
      return accepted(g, fb);
    }
    const uint32_t id = g.planner->halt(in.deceleration * in.accFactor, in.jerk * in.jerkFactor);
    drainPathEvents(k, g, &c, c.cycle);
    g.pathCommands.push_back({id, &fb});
    g.setState(kind == GroupCommand::Kind::Stop ? GroupState::Stopping : GroupState::Moving);
    return accepted(g, fb);
  }
  if (save && g.active && commandOf(*g.active).kind == GroupCommand::Kind::Direct) {
    // PTP: the move's targets and dynamics are kept; the save completes when this halt is at rest.
    g.dropSaved();
    g.saverTaken = true;
    g.saved.token = ++g.interruptToken;
    g.saved.ptp = std::make_shared<GroupCommand>(commandOf(*g.active));
  }
  endCommands(k, g, &c, c.cycle, Error::None);
  g.pending = &fb;
  accepted(g, fb);
}

}  // namespace

void callGroupHalt(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const GroupStopInputs& in, const CallCtx& c) {
  callGroupBrake(k, fb, g, execute, in, c, GroupCommand::Kind::Halt);
}

void callGroupStop(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const GroupStopInputs& in, const CallCtx& c) {
  callGroupBrake(k, fb, g, execute, in, c, GroupCommand::Kind::Stop);
}

namespace {

// After a command ended: the next buffered one starts from this instant; consecutive
// path moves go to the planner together.  Nothing left: GroupStandby in the next step.
void startQueued(Kernel& k, AxisGroup& g, int64_t nowNs, uint64_t cycle, int64_t originNs) {
  if (g.queue.empty()) {
    g.ended = true;
    return;
  }
  FbSlot* next = g.queue.front();
  if (commandOf(*next).kind != GroupCommand::Kind::Path) {
    g.queue.erase(g.queue.begin());
    if (Error e = startCommand(k, g, *next, nowNs, originNs); e != Error::None) {
      k.finish(*next, nullptr, cycle, false, false, e);
      groupError(k, g, e, Error::None, nowNs, cycle);
    }
    return;
  }
  const CoordSystem space = commandOf(*next).space;
  while (!g.queue.empty() && commandOf(*g.queue.front()).kind == GroupCommand::Kind::Path && commandOf(*g.queue.front()).space == space) {
    FbSlot* p = g.queue.front();
    g.queue.erase(g.queue.begin());
    if (Error e = appendPath(k, g, *p, nowNs, cycle); e != Error::None) k.finish(*p, nullptr, cycle, false, false, e);
  }
  if (!pathMode(g)) g.ended = true;
}

void stepPath(Kernel& k, AxisGroup& g, int64_t nowNs, int64_t intervalNs, uint64_t cycle) {
  // The move in control must be called in every cycle until it ends (error 30).
  for (const auto& [id, fb] : g.pathCommands)
    if (fb->out.active && fb->lastCallCycle != cycle && commandOf(*fb).kind != GroupCommand::Kind::Stop)
      return groupError(k, g, Error::FbWasntCalledDuringMotion, Error::None, nowNs, cycle);
  const double dt = cycle == g.pathStartCycle || cycle == g.pathAdvancedCycle ? 0.0 : static_cast<double>(intervalNs) * 1e-9;
  const path::Sample& s = g.planner->advance(dt);
  if (pathThroughKinematics(g)) {
    // The joints at the sample and at +-h seconds along it: velocities and accelerations by
    // central differences (exact for the quadratic the sample describes).
    constexpr double h = 1e-4;
    double near[kMaxGroupAxes], q0[kMaxGroupAxes], qp[kMaxGroupAxes], qm[kMaxGroupAxes];
    path::Vec xp = s.pos, xm = s.pos;
    for (int i = 0; i < path::kMaxCoords; ++i) {
      xp[i] += h * s.vel[i] + 0.5 * h * h * s.acc[i];
      xm[i] += -h * s.vel[i] + 0.5 * h * h * s.acc[i];
    }
    for (size_t i = 0; i < g.gens.size(); ++i) near[i] = g.gens[i]->state.p;
    if (!pathJoints(k, g, s.pos.data(), near, q0) || !pathJoints(k, g, xp.data(), q0, qp) || !pathJoints(k, g, xm.data(), q0, qm))
      return groupError(k, g, Error::AgUnreachable, Error::None, nowNs, cycle);
    for (size_t i = 0; i < g.axes().size() && i < g.gens.size(); ++i) {
      g.gens[i]->state = Kinematic{q0[i], (qp[i] - qm[i]) / (2 * h), (qp[i] - 2 * q0[i] + qm[i]) / (h * h)};
      g.gens[i]->tSet = g.axes()[i]->movement().t(nowNs);
    }
  } else {
    for (size_t i = 0; i < g.axes().size() && i < g.gens.size(); ++i) {
      g.gens[i]->state = Kinematic{s.pos[i], s.vel[i], s.acc[i]};
      g.gens[i]->tSet = g.axes()[i]->movement().t(nowNs);
    }
  }
  drainPathEvents(k, g, nullptr, cycle);
  if (g.pathInterrupted && g.interrupter && s.held && !s.moving) {
    FbSlot* it = g.interrupter;
    g.interrupter = nullptr;
    for (size_t i = 0; i < g.axes().size() && i < g.gens.size(); ++i) g.continuePos[i] = g.gens[i]->state.p;
    k.finish(*it, nullptr, cycle, true, false, Error::None);
    const GroupCommand::Kind kind = commandOf(*it).kind;
    if (kind == GroupCommand::Kind::Halt || kind == GroupCommand::Kind::Stop) {
      // A halt / stop that saved the path: it stands like after any halt (GroupStandby in
      // the next step; a stop holds GroupStopping while its Execute is TRUE).
      g.pathInterrupted = false;
      completeSave(k, g, g.continuePos, cycle);
      g.ended = true;
      if (kind == GroupCommand::Kind::Stop && !it->execute) g.setState(GroupState::Moving);
      return;
    }
    for (auto& [id, fb] : g.pathCommands)
      if (fb->out.active) {
        fb->out.active = false;
        fb->sync();
      }
    g.setState(GroupState::Standby);
    return;
  }
  if (!pathMode(g) && g.state() != GroupState::Stopping) startQueued(k, g, nowNs, cycle, nowNs);
}

}  // namespace

namespace {
bool stepPtp(Kernel& k, AxisGroup& g, int64_t nowNs, uint64_t cycle);
void stepJog(Kernel& k, AxisGroup& g, int64_t nowNs, int64_t intervalNs, uint64_t cycle);
}  // namespace

void groupBeforeStep(Kernel& k, AxisGroup& g, int64_t nowNs, int64_t intervalNs, uint64_t cycle) {
  // SMC_GroupSaveContinueData whose cycle passed without a halt or stop taking it.
  if (g.saver && !g.saverTaken && g.saverCycle <= cycle) {
    k.finish(*g.saver, nullptr, cycle, false, false, Error::AgNothingToSave);
    g.saver = nullptr;
  }
  if (!g.enabled() || g.state() == GroupState::ErrorStop) return;
  // The last command ended in the previous step: the group stands (one cycle after the
  // last position change, as CODESYS).
  if (g.ended && !g.pending && !g.active) {
    g.ended = false;
    if (g.state() == GroupState::Moving) g.setState(GroupState::Standby);
    if (g.state() == GroupState::Standby) releaseMembers(k, g);
  }
  if (g.pending) {
    FbSlot* fb = g.pending;
    g.pending = nullptr;
    if (Error e = startCommand(k, g, *fb, nowNs, nowNs); e != Error::None) {
      k.finish(*fb, nullptr, cycle, false, false, e);
      return groupError(k, g, e, Error::None, nowNs, cycle);
    }
  }
  if (g.active && commandOf(*g.active).kind == GroupCommand::Kind::Jog) return stepJog(k, g, nowNs, intervalNs, cycle);
  if (pathMode(g)) return stepPath(k, g, nowNs, intervalNs, cycle);
  // A successor of a dwell starts at the dwell's exact end, maybe between cycles: it is
  // sampled in this step too (at most a few hand-overs per step).
  for (int handovers = 0; handovers < 8 && g.active && g.motion; ++handovers)
    if (!stepPtp(k, g, nowNs, cycle)) return;
}

namespace {

// One command of the PTP kind (PTP, halt, stop, wait) in this step; true when it ended and
// its successor started before nowNs (sample again).
bool stepPtp(Kernel& k, AxisGroup& g, int64_t nowNs, uint64_t cycle) {
  // The command in control must be called in every cycle until it ends (error 30).
  if (g.active->lastCallCycle != cycle) {
    groupError(k, g, Error::FbWasntCalledDuringMotion, Error::None, nowNs, cycle);
    return false;
  }
  Kinematic q[kMaxGroupAxes];
  const double t = groupTime(g, nowNs);
  sampleScaled(g, *g.motion, t, q);
  for (size_t i = 0; i < g.axes().size() && i < g.gens.size(); ++i) {
    g.gens[i]->state = q[i];
    g.gens[i]->tSet = g.axes()[i]->movement().t(nowNs);
  }
  if (t < g.motion->duration()) return false;
  // The end is reached in this step: Done; a buffered successor becomes active here and
  // starts from this instant (its first motion in the next step), after a dwell from the
  // dwell's exact end.
  const bool wait = commandOf(*g.active).kind == GroupCommand::Kind::Wait;
  const int64_t endNs = g.motionRate > 0 ? g.rateNs + static_cast<int64_t>(std::llround((g.motion->duration() - g.rateTau) / g.motionRate * 1e9)) : nowNs;
  if (g.interrupter && g.active == g.interrupted) {
    // MC_GroupInterrupt: at rest; the interrupted move stays Busy, the group stands.
    FbSlot* it = g.interrupter;
    g.interrupter = nullptr;
    g.active = nullptr;
    g.motion.reset();
    for (size_t i = 0; i < g.axes().size(); ++i) g.continuePos[i] = q[i].p;
    k.finish(*it, nullptr, cycle, true, false, Error::None);
    g.setState(GroupState::Standby);
    releaseMembers(k, g);
    return false;
  }
  FbSlot* done = g.active;
  const bool stop = commandOf(*done).kind == GroupCommand::Kind::Stop;
  if ((stop || commandOf(*done).kind == GroupCommand::Kind::Halt) && g.saved.token && !g.saved.complete && g.saved.ptp) {
    double pos[kMaxGroupAxes];
    for (size_t i = 0; i < g.axes().size(); ++i) pos[i] = q[i].p;
    completeSave(k, g, pos, cycle);
  }
  g.active = nullptr;
  g.motion.reset();
  done->out.active = false;
  if (stop) {   // MC_GroupStop: Done at rest, Busy ends, GroupStopping while Execute (callGroupBrake)
    k.finish(*done, nullptr, cycle, true, false, Error::None);
    if (!done->execute) {
      g.setState(GroupState::Standby);
      releaseMembers(k, g);
    }
    return false;
  }
  k.finish(*done, nullptr, cycle, true, false, Error::None);
  const int64_t originNs = wait ? std::min(endNs, nowNs) : nowNs;
  startQueued(k, g, nowNs, cycle, originNs);
  return g.active && g.motion && g.originNs < nowNs;
}

}  // namespace

namespace {

// SMC_GroupJog in one step: the reference axes' set positions (of their last step) are the
// coordinates in the jog's system; each member is replanned from its state towards the joint
// target at the joint velocity the references give (time-optimal under its limits) and
// advanced by one cycle.  Exact tracking (one cycle behind) once caught up.
void stepJog(Kernel& k, AxisGroup& g, int64_t nowNs, int64_t intervalNs, uint64_t cycle) {
  FbSlot& fb = *g.active;
  GroupCommand& cmd = commandOf(fb);
  if (fb.lastCallCycle != cycle) return groupError(k, g, Error::FbWasntCalledDuringMotion, Error::None, nowNs, cycle);
  const CoordSystem cs = static_cast<CoordSystem>(cmd.jog.coordSystem);
  double x[kMaxGroupAxes], xp[kMaxGroupAxes], xm[kMaxGroupAxes];
  std::copy(cmd.jogStart, cmd.jogStart + kMaxGroupAxes, x);
  constexpr double h = 1e-4;   // seconds: joint velocities by central differences
  std::copy(x, x + kMaxGroupAxes, xp);
  std::copy(x, x + kMaxGroupAxes, xm);
  for (int r = 0; r < 6; ++r) {
    const Axis* ref = cmd.jog.ref[r];
    if (!ref) continue;
    const int i = cmd.jogCoord[r];
    x[i] = ref->set().p;
    xp[i] = x[i] + h * ref->set().v;
    xm[i] = x[i] - h * ref->set().v;
  }
  const size_t n = g.axes().size();
  double near[kMaxGroupAxes] = {}, q[kMaxGroupAxes] = {}, qp[kMaxGroupAxes] = {}, qm[kMaxGroupAxes] = {};
  for (size_t i = 0; i < n; ++i) near[i] = g.gens[i]->state.p;
  const KinConfigData cfg = g.kin ? g.kin->configOf(near) : KinConfigData{};
  if (!jointsOf(k, g, cs, x, cfg, near, q) || !jointsOf(k, g, cs, xp, cfg, q, qp) || !jointsOf(k, g, cs, xm, cfg, q, qm))
    return groupError(k, g, Error::AgUnreachable, Error::None, nowNs, cycle);
  const double dt = cycle == cmd.jogStartCycle ? 0.0 : static_cast<double>(intervalNs) * 1e-9;
  bool reached = true;
  for (size_t i = 0; i < n; ++i) {
    // In the frame that moves with the target (at its joint velocity vf, capped by the member's
    // limit): the error comes to rest time-optimally, with the velocity the limit leaves.
    const Limits& lim = cmd.jogLim[i];
    const Kinematic s = g.gens[i]->state;
    const double vf = std::clamp((qp[i] - qm[i]) / (2 * h), -lim.vel, lim.vel);
    const Limits rel{std::max(lim.vel - std::fabs(vf), 1e-9 * lim.vel), lim.acc, lim.dec, lim.jerk};
    Profile p;
    if (planPosition(Kinematic{s.p - q[i], s.v - vf, s.a}, 0, 0, rel, p) != PlanStatus::Ok) {
      reached = false;
      continue;   // (not within the model: the member keeps its state)
    }
    const Kinematic e = p.at(dt);
    // At the reference pose after this step (to rounding): the error has come to rest.
    reached = reached && std::fabs(e.p) <= 1e-9 * std::max(1.0, std::fabs(q[i])) && std::fabs(e.v) <= 1e-9 * std::max(1.0, lim.vel);
    g.gens[i]->state = Kinematic{q[i] + vf * dt + e.p, vf + e.v, e.a};
    g.gens[i]->tSet = g.axes()[i]->movement().t(nowNs);
  }
  if (reached && !fb.out.inState) {   // InitialPositionReached (stays while the jog tracks)
    fb.out.inState = true;
    fb.sync();
  }
}

}  // namespace

void callGroupJog(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const JogInputs& in, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();   // Execute falling: the jog goes on tracking
  fb.out.commandAccepted = false;
  auto factor = [](double f) { return std::isfinite(f) && f > 0 && f <= 1; };
  if (!factor(in.velFactor) || !factor(in.accFactor) || !factor(in.jerkFactor)) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (!validCoordSystem(in.coordSystem) || in.coordSystem == static_cast<int>(CoordSystem::TCS) ||
      (in.pcs != static_cast<int>(CoordSystem::PCS1) && in.pcs != static_cast<int>(CoordSystem::PCS2)))
    return k.fail(fb, Error::AgInvalidCoordSystem, c);
  if (in.abcAsAcs) return k.fail(fb, Error::AgInvalidKinematics, c);   // needs Kin_Coupled, not offered
  if (Error e = motionRefusal(k, g); e != Error::None) {
    if (e == Error::AgSingleAxisActive) groupError(k, g, e, Error::None, c.nowNs, c.cycle);
    return k.fail(fb, e, c);
  }
  const CoordSystem cs = static_cast<CoordSystem>(in.coordSystem);
  // The coordinate each reference axis drives: X, Y, Z; A, B, C the orientation when the
  // kinematics controls it, else the additional axes (coordinates 6..8 in a Cartesian system).
  GroupCommand tmp;
  bool any = false;
  const int count = coordCount(g, cs);
  for (int r = 0; r < 6; ++r) {
    const Axis* ref = in.ref[r];
    if (!ref) continue;
    any = true;
    if (g.identOf(*ref) >= 0) return k.fail(fb, Error::AgInvalidMoveInputs, c);   // a member cannot lead the group
    int i = r;
    if (cartesian(g, cs) && r >= 3 && !(g.kin->controlled() & (1u << r))) i = 6 + (r - 3);
    if (cartesian(g, cs) && r < 3 && !(g.kin->controlled() & (1u << r))) return k.fail(fb, Error::AgInvalidMoveInputs, c);
    if (i >= count) return k.fail(fb, Error::AgInvalidMoveInputs, c);
    tmp.jogCoord[r] = i;
  }
  if (!any) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  // Restarting with the PCS of the jog that still tracks needs another move first (manual).
  if (g.jogPcs == in.pcs && g.active && commandOf(*g.active).kind == GroupCommand::Kind::Jog)
    return k.fail(fb, Error::AgPcsStillInUse, c);
  if (pathMode(g)) return k.fail(fb, Error::AgModeChangeWhileMoving, c);
  std::vector<Limits> lim;
  if (!memberLimits(g, in.velFactor, in.accFactor, in.jerkFactor, lim, g.anc)) return k.fail(fb, Error::AgAxisLimitsMissing, c);
  const std::vector<Kinematic> s = presentStates(k, g, c.nowNs);
  double q[kMaxGroupAxes] = {};
  for (size_t i = 0; i < s.size(); ++i) q[i] = s[i].p;
  if (!coordsOf(k, g, cs, q, tmp.jogStart)) return k.fail(fb, Error::AgInvalidCoordSystem, c);
  GroupCommand& cmd = commandOf(fb);
  cmd.kind = GroupCommand::Kind::Jog;
  cmd.jog = in;
  std::copy(tmp.jogCoord, tmp.jogCoord + 6, cmd.jogCoord);
  std::copy(tmp.jogStart, tmp.jogStart + kMaxGroupAxes, cmd.jogStart);
  cmd.jogLim = std::move(lim);
  cmd.jogStartCycle = c.cycle;
  fb.axis = nullptr;
  fb.out.inState = false;
  // Like an aborting move: what runs or waits ends now, the jog takes over in this cycle's step.
  endCommands(k, g, &c, c.cycle, Error::None);
  g.pending = &fb;
  g.jogPcs = in.pcs;
  g.targetValid = false;   // it follows the references: no fixed target
  accepted(g, fb);
}

void callGroupSaveContinueData(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  if (!g.enabled()) return k.fail(fb, Error::AgNotEnabled, c);
  if (g.state() == GroupState::ErrorStop) return k.fail(fb, Error::AgInErrorStop, c);
  // One save at a time per group: an armed one that another instance replaces ends aborted.
  if (g.saver && g.saver != &fb) k.finish(*g.saver, &c, c.cycle, false, true, Error::None);
  g.saver = &fb;
  g.saverCycle = c.cycle;
  g.saverTaken = false;
  fb.out.busy = true;
  fb.sync();
}

bool setGroupResumeAfterError(AxisGroup& g, bool enable) {
  g.resumeAfterError = enable && g.enabled();
  return g.resumeAfterError;
}

uint32_t savedContinueToken(const AxisGroup& g) { return g.saved.complete ? g.saved.token : 0; }

void abortGroupMotion(Kernel& k, AxisGroup& g, const CallCtx& c) {
  endCommands(k, g, &c, c.cycle, Error::None);
  brakeMembers(k, g, c.nowNs);
  g.ended = false;
}

void groupAfterStep(Kernel& k, AxisGroup& g, int64_t nowNs, uint64_t cycle) {
  if (!g.enabled() || g.state() == GroupState::ErrorStop) return;
  for (size_t i = 0; i < g.axes().size(); ++i) {
    const Axis& ax = *g.axes()[i];
    if (ax.state() == AxisState::ErrorStop) return groupError(k, g, Error::AgAxisError, ax.error(), nowNs, cycle);
    // A single-axis command took a member from the moving group (CODESYS: group error).
    if ((g.active || g.pending) && g.gens.size() == g.axes().size() && ax.controller != &memberSlot(k, g, i))
      return groupError(k, g, Error::AgInterruptedBySingleAxis, Error::None, nowNs, cycle);
  }
}

void callGroupSetPosition(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const double* position, bool relative,
                          const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  if (!g.enabled()) return k.fail(fb, Error::AgNotEnabled, c);
  if (g.state() != GroupState::Standby || g.interrupted || g.pathInterrupted) return k.fail(fb, Error::AgNotStandby, c);
  for (size_t i = 0; i < g.axes().size(); ++i) {
    const Axis& ax = *g.axes()[i];
    const double delta = relative ? position[i] : position[i] - ax.reportPosition(ax.set().p);
    if (!bounds::position(position[i]) || !bounds::position(ax.set().p + delta) || !bounds::position(ax.actPosition() + delta))
      return k.fail(fb, Error::AgInvalidMoveInputs, c);
    if (ax.controller || !ax.atRest()) return k.fail(fb, Error::AgSingleAxisActive, c);
  }
  for (size_t i = 0; i < g.axes().size(); ++i) {
    Axis& ax = *g.axes()[i];
    ax.sample(c.nowNs);
    ax.shiftPosition(relative ? position[i] : position[i] - ax.reportPosition(ax.set().p));
  }
  g.dropSaved();                        // the coordinates changed under it
  if (g.planner) g.planner->clear();   // it starts again from the members' positions
  g.lastMotion.reset();
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

void callGroupSetOverride(Kernel& k, FbSlot& fb, AxisGroup& g, bool enable, const OverrideInputs& in, const CallCtx& c) {
  fb.execute = enable;
  fb.lastCallCycle = c.cycle;
  fb.axis = nullptr;
  fb.out = FbOutputs{};
  if (!enable) return fb.sync();   // the last factors stay
  auto factor = [](double f) { return std::isfinite(f) && f >= 0 && f <= 1; };
  if (!factor(in.vel) || !factor(in.acc) || !factor(in.jerk) || !factor(in.pathVel) || !factor(in.pathAcc) || !factor(in.pathJerk)) {
    fb.out.error = true;
    fb.out.errorId = Error::AgInvalidMoveInputs;
    return fb.sync();
  }
  const double f = std::min({in.vel, in.pathVel, std::sqrt(in.acc), std::sqrt(in.pathAcc), std::cbrt(in.jerk), std::cbrt(in.pathJerk)});
  setGroupRate(k, g, f, c);
  fb.out.busy = true;
  fb.out.inState = true;   // Enabled
  fb.sync();
}

bool setGroupRate(Kernel& k, AxisGroup& g, double f, const CallCtx& c) {
  (void)k;
  if (!std::isfinite(f) || f < 0 || f > 1000) return false;
  if (f == g.rate) return true;
  // From now on: the running PTP motion's time runs at f (the same path, velocities x f).
  const bool stopRunning = g.active && commandOf(*g.active).kind == GroupCommand::Kind::Stop;
  if (!stopRunning) {
    g.rateTau = groupTime(g, c.nowNs);
    g.rateNs = c.nowNs;
    g.motionRate = f;
  }
  g.rate = f;
  if (g.planner) {
    advanceToCall(g, c);
    g.planner->setOverride(f);
  }
  return true;
}

void callGroupInterrupt(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, uint32_t& token, uint32_t& movementId, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  if (!g.enabled()) return k.fail(fb, Error::AgNotEnabled, c);
  if (g.state() == GroupState::ErrorStop) return k.fail(fb, Error::AgInErrorStop, c);
  // Another interrupt or a group stop in progress: CommandAborted at once (CODESYS).
  if (g.interrupter || g.state() == GroupState::Stopping) return k.finish(fb, &c, c.cycle, false, true, Error::None);
  if (pathMode(g)) {
    advanceToCall(g, c);
    g.planner->interrupt(0, 0);   // the running segment's deceleration
    g.pathInterrupted = true;
  } else if (g.active && commandOf(*g.active).kind == GroupCommand::Kind::Direct) {
    // PTP: the members brake along their own profiles; the move stays Busy (not Active).
    FbSlot& mv = *g.active;
    const std::vector<Kinematic> start = presentStates(k, g, c.nowNs);
    std::vector<Limits> lim;
    if (!memberLimits(g, 1, 1, 1, lim)) return k.fail(fb, Error::AgAxisLimitsMissing, c);
    auto m = std::make_shared<PtpMotion>();
    if (planPtp(start, brakeTargets(start, lim), lim, *m) != PlanStatus::Ok) return k.fail(fb, Error::AgAxisLimitsMissing, c);
    runMotion(g, std::move(m), c.nowNs, 1);
    g.interrupted = &mv;
    mv.out.active = false;
    mv.sync();
  } else {
    return k.fail(fb, Error::AgNotInterruptible, c);
  }
  g.interrupter = &fb;
  token = g.interruptToken = g.interruptToken + 1;
  movementId = static_cast<uint32_t>(g.activeMovementId);
  fb.out.busy = true;
  fb.sync();
}

namespace {
// MC_GroupContinue of a motion saved at a halt, a stop or an error: the group must stand at the
// continue position; this FB stands for the ended moves (Busy, Done at the end of the rest).
void continueSaved(Kernel& k, FbSlot& fb, AxisGroup& g, const CallCtx& c) {
  if (Error e = motionRefusal(k, g); e != Error::None) return k.fail(fb, e, c);
  if (g.active || g.pending || !g.queue.empty() || pathMode(g)) return k.fail(fb, Error::AgNotStandby, c);
  for (size_t i = 0; i < g.axes().size(); ++i)
    if (!(std::fabs(g.axes()[i]->set().p - g.saved.pos[i]) <= kContinueTolerance)) return k.fail(fb, Error::AgNotAtContinuePosition, c);
  if (g.saved.path) {
    auto cmd = std::make_unique<GroupCommand>();
    cmd->kind = GroupCommand::Kind::Path;
    cmd->space = g.pathCs;
    fb.behaviour = std::move(cmd);
    takeMembers(k, g, c.nowNs);
    g.planner->resume();
    g.pathStartCycle = c.cycle;   // resumes at this cycle's time (the step samples t = 0)
    g.pathCommands.push_back({g.planner->lastOwner(), &fb});
    g.lastMotion.reset();
    g.ended = false;
    g.setState(GroupState::Moving);
    fb.out.active = true;
  } else {
    fb.behaviour = std::make_unique<GroupCommand>(static_cast<const GroupCommand&>(*g.saved.ptp));
    g.pending = &fb;
  }
  g.saved = AxisGroup::SavedMotion{};   // taken (the planner keeps the path it runs now)
  accepted(g, fb);
}
}  // namespace

void callGroupContinue(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, uint32_t token, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  if (g.state() == GroupState::Stopping) return k.finish(fb, &c, c.cycle, false, true, Error::None);
  if (!g.enabled() || g.state() != GroupState::Standby) return k.fail(fb, Error::AgNotStandby, c);
  if (token != 0 && token == g.saved.token && g.saved.complete) return continueSaved(k, fb, g, c);
  const bool held = g.pathInterrupted || g.interrupted;
  if (!held || g.interrupter || token != g.interruptToken) return k.fail(fb, Error::AgNotInterrupted, c);
  if (g.pathInterrupted) {
    takeMembers(k, g, c.nowNs);
    g.planner->resume();
    g.pathStartCycle = c.cycle;   // resumes at this cycle's time (the step samples t = 0)
    g.pathInterrupted = false;
    for (auto& [id, p] : g.pathCommands)
      if (p->out.busy) {
        p->out.active = true;
        p->sync();
        break;
      }
    g.setState(GroupState::Moving);
  } else {
    g.pending = g.interrupted;   // from rest to its targets again, in this cycle's step
    g.interrupted = nullptr;
  }
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

void callSetDynamicLimitFactors(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const AxisGroup::LimitFactors* f,
                                const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  auto ok = [](double x) { return std::isfinite(x) && x > 0 && x <= 1; };
  for (size_t i = 0; i < kMaxGroupAxes; ++i)
    if (!ok(f[i].vel) || !ok(f[i].acc) || !ok(f[i].dec) || !ok(f[i].jerk)) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (!g.enabled()) return k.fail(fb, Error::AgNotEnabled, c);
  if (g.state() == GroupState::ErrorStop) return k.fail(fb, Error::AgInErrorStop, c);
  for (size_t i = 0; i < g.axes().size(); ++i) {
    const AxisConfig& ac = g.axes()[i]->config();
    const double dec = ac.maxDeceleration > 0 ? ac.maxDeceleration : ac.maxAcceleration;
    g.anc[i] = Limits{f[i].vel * ac.maxVelocity, f[i].acc * ac.maxAcceleration, f[i].dec * dec, f[i].jerk * ac.maxJerk};
  }
  g.ancImmediate = ++g.ancSerial;   // for every move that starts from now on
  g.plannerStale = true;            // the next path started from rest plans with the new axis limits
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

void callSetAncillaryLimits(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, bool pathLimits, bool immediately, const Limits* lim,
                           const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  // Limits must be > 0 (manual); a component of 0 would stop nothing but block every move.
  auto ok = [](double x) { return std::isfinite(x) && x > 0 && x <= 1e15; };
  const size_t n = pathLimits ? 1 : g.axes().size();
  for (size_t i = 0; i < n; ++i)
    if (!ok(lim[i].vel) || !ok(lim[i].acc) || !ok(lim[i].dec) || !ok(lim[i].jerk)) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (pathLimits) {
    g.ancPath = lim[0];
  } else {
    std::copy(lim, lim + n, g.anc);
    g.plannerStale = true;
  }
  ++g.ancSerial;
  if (immediately) g.ancImmediate = g.ancSerial;
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

bool continuePosition(const AxisGroup& g, uint32_t token, double* position) {
  if (g.enabled() && token != 0 && token == g.saved.token && g.saved.complete) {
    std::copy(g.saved.pos, g.saved.pos + kMaxGroupAxes, position);
    return true;
  }
  if (!g.enabled() || g.interrupter || !(g.interrupted || g.pathInterrupted) || token != g.interruptToken) return false;
  std::copy(g.continuePos, g.continuePos + kMaxGroupAxes, position);
  return true;
}

}  // namespace stc::motion

namespace stc::motion {

namespace {
// Kinematics and frames change only while the group stands still with nothing to continue.
Error configRefusal(const AxisGroup& g) {
  if (g.state() != GroupState::Disabled && g.state() != GroupState::Standby) return Error::AgNotStandby;
  if (g.active || g.pending || !g.queue.empty() || pathMode(g) || g.interrupted || g.pathInterrupted) return Error::AgNotStandby;
  return Error::None;
}
}  // namespace

void callSetKinTransform(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, std::shared_ptr<const GroupKinematics> kin, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  if (!kin) return k.fail(fb, Error::AgInvalidKinematics, c);
  if (Error e = configRefusal(g); e != Error::None) return k.fail(fb, e, c);
  g.kin = std::move(kin);
  g.planner.reset();   // its space and coordinates change
  g.dropSaved();
  g.pathCs = CoordSystem::ACS;
  g.targetValid = false;
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

void callSetKinConfiguration(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const KinConfigData& cfg, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  auto branch = [](int b) { return b >= -1 && b <= 1; };
  if (!branch(cfg.elbow) || !branch(cfg.shoulder) || !branch(cfg.wrist)) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  g.kinConfig = cfg;   // for the Cartesian PTP targets commanded from now on
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

void callSetCoordinateTransform(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const double* coords, int coordSystem,
                                const AxisGroup* master, const CallCtx& c) {
  if (!k.beginExecute(fb, execute, c)) return fb.sync();
  fb.axis = nullptr;
  const CoordSystem cs = static_cast<CoordSystem>(coordSystem);
  const bool pcs = cs == CoordSystem::PCS1 || cs == CoordSystem::PCS2;
  if (!validCoordSystem(coordSystem) || !(pcs || (cs == CoordSystem::MCS && !master))) return k.fail(fb, Error::AgInvalidCoordSystem, c);
  Frame f;
  if (!Frame::fromCoords(coords, f)) return k.fail(fb, Error::AgInvalidMoveInputs, c);
  if (master == &g) return k.fail(fb, Error::AgInvalidCoordSystem, c);   // a group cannot follow itself
  if (Error e = configRefusal(g); e != Error::None) return k.fail(fb, e, c);
  if (cs == CoordSystem::MCS) {
    g.mcs = f;
  } else {
    AxisGroup::Pcs& p = g.pcs[cs == CoordSystem::PCS1 ? 0 : 1];
    p.frame = f;
    p.master = master ? master->index() : UINT32_MAX;
  }
  g.planner.reset();
  g.dropSaved();
  g.pathCs = CoordSystem::ACS;
  g.targetValid = false;
  k.finish(fb, &c, c.cycle, true, false, Error::None);
}

}  // namespace stc::motion

namespace stc::motion {

void AxisGroup::dropSaved() {
  if (saved.path && planner && pathCommands.empty() && !planner->sample().moving) {
    planner->clear();
    planner->clearEvents();
  }
  saved = SavedMotion{};
}

}  // namespace stc::motion
