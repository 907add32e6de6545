// The Leadshine PMC_IpoLib interpolation blocks (ls_interpolation.st): lines of
// 2..6 axes, planar arcs (four modes), spatial three-point arcs, ellipses,
// helices and MoveSequence tables.  Each instance drives an internal axis group
// of its axes (AxisGroup::internal, stdlib-motion/group) with path moves on the
// group's planner: Halt is MC_GroupInterrupt / MC_GroupContinue, Stop is
// MC_GroupHalt.  This file only maps the blocks' inputs to path moves and the
// group's command outputs to the blocks' outputs; decisions where the manual is
// silent: docs/leadshine-interpolation.md.
#include <cmath>
#include <numbers>

#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/group/GroupMotion.h"
#include "stdlib-motion/leadshine/LsMoves.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;
using namespace stc::motion::leadshine;

namespace {

// The inputs every interpolation block has (latched at the Exec edge; Halt, Stop and
// VelRatio are read in every call).
struct Common {
  bool exec = false, halt = false, stop = false;
  uint32_t ipoCycleUs = 0;
  int velocityMode = 1;
  double vel = 0, acc = 0, dec = 0, jerk = 0;
  bool hasRatio = false;
  double ratio = 1;
};

// One path move of a block: the spec, the error a refused geometry gets, its line number.
struct Segment {
  path::MoveSpec spec;
  int32_t geoError = kIpoParaErr;
  double lineNum = 0;
};

constexpr size_t kSlotPool = 32;   // path-move slots of a MoveSequence (reused in turn)

// The state of one block instance, kept on its kernel slot.
class IpoRun : public FbBehaviour {
public:
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}

  uint32_t group = 0;                      // the internal group's index + 1 (0: none yet)
  uint64_t slots[kSlotPool] = {};          // path-move slots (handles)
  int64_t slotSeg[kSlotPool] = {};         // the segment each slot carries (-1: none)
  uint64_t interruptSlot = 0, continueSlot = 0, haltSlot = 0;
  uint32_t token = 0, movementId = 0;

  std::vector<Segment> segs;               // the moves of the running command
  size_t next = 0;                         // the first segment not yet handed to the group
  bool running = false, halted = false, stopping = false;
  int32_t pendingError = 0;                // a later segment was refused: ends with this error at rest
  double dec = 0, jerk = 0;                // for Stop
  double lineCurrent = 0;

  // outputs (the PLCopen hold rules: held while Exec, else one cycle)
  bool exec = false;
  bool done = false, aborted = false, error = false, fresh = false;
  int32_t errorId = 0;
  bool terminal() const { return done || aborted || error; }
};

void publishNothing(void*, const FbOutputs&) {}

AxisGroup* groupOf(Kernel& k, IpoRun& r) { return r.group ? k.group(r.group - 1) : nullptr; }

template <class T>
FbSlot& mainSlot(T* self) {
  return kernel().slot(self->__handle, self, FbKind::Leadshine, &publishNothing);
}

template <class T>
void publishSub(void* instance, const FbOutputs&);

template <class T>
FbSlot& sub(T* self, uint64_t& handle) {
  return kernel().slot(handle, self, FbKind::Group, &publishSub<T>);
}

void terminate(IpoRun& r, bool done, bool aborted, int32_t errorId, bool fromStep) {
  r.running = r.halted = r.stopping = false;
  r.pendingError = 0;
  r.done = done;
  r.aborted = aborted;
  r.error = errorId != 0;
  r.errorId = errorId;
  r.fresh = fromStep;
  for (int64_t& s : r.slotSeg) s = -1;
  r.segs.clear();
  r.next = 0;
}

// The error of the group behind a path command that ended with e (positive: SMC_ERROR).
int32_t runtimeError(const AxisGroup* g, Error e) {
  if (g && g->axisError() != Error::None) return static_cast<int32_t>(smcError(g->axisError()));
  return static_cast<int32_t>(smcError(e));
}

// Reads the group commands' outputs into the block's state.
template <class T>
void observe(T* self, IpoRun& r, bool fromStep) {
  if (!r.running) return;
  Kernel& k = kernel();
  AxisGroup* g = groupOf(k, r);
  if (r.stopping) {
    FbSlot& h = sub(self, r.haltSlot);
    if (h.out.error) return terminate(r, false, false, runtimeError(g, h.out.errorId), fromStep);
    if (h.out.done || h.out.aborted) {
      const int32_t pe = r.pendingError;
      return pe ? terminate(r, false, false, pe, fromStep) : terminate(r, false, true, 0, fromStep);
    }
    return;
  }
  for (size_t j = 0; j < kSlotPool; ++j) {
    if (r.slotSeg[j] < 0) continue;
    FbSlot& s = sub(self, r.slots[j]);
    if (s.out.error) return terminate(r, false, false, runtimeError(g, s.out.errorId), fromStep);
    if (s.out.aborted) return terminate(r, false, true, 0, fromStep);
    if (s.out.active) r.lineCurrent = r.segs[static_cast<size_t>(r.slotSeg[j])].lineNum;
    if (s.out.done) {
      const bool last = static_cast<size_t>(r.slotSeg[j]) + 1 == r.segs.size() && r.next == r.segs.size();
      r.slotSeg[j] = -1;
      if (last) return terminate(r, true, false, 0, fromStep);
    }
  }
}

template <class T>
void writeOutputs(T* self, IpoRun& r) {
  Kernel& k = kernel();
  AxisGroup* g = groupOf(k, r);
  self->Done = r.done;
  self->CommandAborted = r.aborted;
  self->Error = r.error;
  self->ErrorID = r.errorId;
  self->Busy = r.running;
  self->CommandHalt = r.running && r.halted;
  self->Vel = r.running && g && g->planner ? std::fabs(g->planner->sample().v) : 0.0;
  if constexpr (requires { self->LineCurrent; }) {
    const double l = std::isfinite(r.lineCurrent) ? std::clamp(r.lineCurrent, 0.0, 65535.0) : 0.0;
    self->LineCurrent = self->LineCurent = static_cast<uint16_t>(l);
  }
}

// A group command's outputs changed (in a call or in the kernel step).
template <class T>
void publishSub(void* instance, const FbOutputs&) {
  T* self = static_cast<T*>(instance);
  IpoRun& r = behaviourOf<IpoRun>(mainSlot(self));
  const bool wasRunning = r.running;
  observe(self, r, true);
  if (wasRunning) writeOutputs(self, r);
}

// Hands segment i to the group (on a free slot); 0 or the block's error.
template <class T>
int32_t issue(T* self, IpoRun& r, AxisGroup& g, size_t i, const CallCtx& c) {
  const size_t j = i % kSlotPool;
  if (r.slotSeg[j] >= 0) return 1;   // still busy: later
  FbSlot& s = sub(self, r.slots[j]);
  PathInputs in;
  in.spec = r.segs[i].spec;
  in.bufferMode = static_cast<BufferMode>(in.spec.buffer);
  in.transitionMode = static_cast<int>(in.spec.transition);
  s.execute = false;   // a new command on this slot
  callGroupMovePath(kernel(), s, g, true, in, c);
  if (s.out.error) {
    switch (s.out.errorId) {
      case Error::AgInvalidGeometry: return r.segs[i].geoError;
      case Error::BufferFull: return kIpoBufferOver;
      case Error::AgInvalidMoveInputs: return kIpoParaErr;
      default: return runtimeError(&g, s.out.errorId);
    }
  }
  r.slotSeg[j] = static_cast<int64_t>(i);
  r.next = i + 1;
  return 0;
}

// Hands over the segments that fit into the planner's queue.
template <class T>
int32_t feed(T* self, IpoRun& r, AxisGroup& g, const CallCtx& c) {
  while (r.next < r.segs.size()) {
    if (r.next > 0 && g.planner && g.planner->queued() + 8 > g.planner->capacity()) return 0;
    const int32_t e = issue(self, r, g, r.next, c);
    if (e == 1) return 0;
    if (e != 0) return e;
  }
  return 0;
}

int32_t checkCommon(const Common& in, const CallCtx& c) {
  if (in.ipoCycleUs == 0 || static_cast<int64_t>(in.ipoCycleUs) * 1000 != c.intervalNs) return kIpoParaErr;
  if (in.velocityMode != 0 && in.velocityMode != 1 && in.velocityMode != 3) return kIpoParaErr;
  if (!bounds::jerk(in.jerk) || in.jerk == 0) return kIpoParaErr;
  if (!bounds::velocity(in.vel)) return kIpoVel;
  if (!bounds::rate(in.acc)) return kIpoAcc;
  if (!bounds::rate(in.dec)) return kIpoDec;
  if (in.hasRatio && !(in.ratio >= 0.01 && in.ratio <= 2)) return kIpoParaErr;
  return 0;
}

path::Dynamics dynamicsOf(const Common& in) {
  // TRAPEZOID: acceleration-limited; SIGMOID and QUADRATIC: jerk-limited with Jerk.
  return path::Dynamics{in.vel, in.acc, in.dec, in.velocityMode == 0 ? 0.0 : in.jerk};
}

// Stop (or a refused later segment): the path brakes along itself (MC_GroupHalt with at
// least the running segment's deceleration); CommandAborted, or the error, at standstill.
template <class T>
void stopRun(T* self, IpoRun& r, AxisGroup& g, int32_t pendingError, const CallCtx& c) {
  r.stopping = true;   // first: the path moves the halt aborts report in this call
  r.halted = false;
  r.pendingError = pendingError;
  r.next = r.segs.size();   // MoveSequence: the rest is dropped
  FbSlot& h = sub(self, r.haltSlot);
  h.execute = false;
  callGroupHalt(kernel(), h, g, true, GroupStopInputs{r.dec, r.jerk, 1, 1}, c);
  observe(self, r, false);
}

// The common body: bind the axes, run the state machine, build the segments at the Exec
// edge with `build(start, segs)` (start: the axes' set positions; 0 or the block's error).
template <class T, size_t N, class Build>
void ipoBody(T* self, sm3::AXIS_REF_SM3* const (&refs)[N], const Common& in, Build build) {
  CallCtx c = callContext();
  Kernel& k = kernel();
  std::vector<Axis*> axes;
  for (sm3::AXIS_REF_SM3* ref : refs) {
    Axis* ax = bind(ref, c);
    if (!ax) {
      self->Error = true;
      self->Busy = false;
      self->ErrorID = static_cast<int32_t>(smcError(Error::NotReadyForMotion));
      return;
    }
    axes.push_back(ax);
  }
  FbSlot& main = mainSlot(self);
  main.lastCallCycle = c.cycle;
  IpoRun& r = behaviourOf<IpoRun>(main);
  if (!r.group) {
    AxisGroup& ng = k.addGroup();
    ng.internal = true;
    ng.task = c.task;
    r.group = ng.index() + 1;
    for (int64_t& s : r.slotSeg) s = -1;
  }
  AxisGroup& g = *groupOf(k, r);
  const bool rising = in.exec && !r.exec;
  r.exec = in.exec;
  // Output hold: a terminal output shown with Exec FALSE is cleared in the next call.
  if (!in.exec && r.terminal() && !r.fresh) {
    r.done = r.aborted = r.error = false;
    r.errorId = 0;
  }
  if (r.running) {
    // The group's commands must be called in every cycle (else error 30).
    static const PathInputs idle;
    for (size_t j = 0; j < kSlotPool; ++j)
      if (r.slotSeg[j] >= 0) callGroupMovePath(k, sub(self, r.slots[j]), g, true, idle, c);
    observe(self, r, false);
  }
  if (r.running && !r.stopping && in.stop) {
    stopRun(self, r, g, 0, c);
  } else if (r.running && !r.stopping) {
    if (in.halt && !r.halted) {
      FbSlot& is = sub(self, r.interruptSlot);
      is.execute = false;
      callGroupInterrupt(k, is, g, true, r.token, r.movementId, c);
      r.halted = !is.out.error;
    } else if (!in.halt && r.halted && sub(self, r.interruptSlot).out.done) {
      FbSlot& cs = sub(self, r.continueSlot);
      cs.execute = false;
      callGroupContinue(k, cs, g, true, r.token, c);
      r.halted = !cs.out.done;
    }
    if (in.hasRatio && in.ratio >= 0.01 && in.ratio <= 2) setGroupRate(k, g, in.ratio, c);
    if (!r.halted) {
      // A later segment refused: the path stops, then the block reports the error.
      if (int32_t e = feed(self, r, g, c); e != 0) stopRun(self, r, g, e, c);
    }
  }
  if (rising && !r.running) {   // an Exec edge while the block runs is ignored
    r.done = r.aborted = r.error = false;
    r.errorId = 0;
    r.lineCurrent = 0;
    auto fail = [&](int32_t e) { terminate(r, false, false, e, false); };
    std::vector<Segment> segs;
    std::vector<double> start;
    for (Axis* ax : axes) start.push_back(ax->set().p);
    int32_t e = checkCommon(in, c);
    if (e == 0) e = build(start, segs);
    for (size_t i = 0; e == 0 && i < axes.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (axes[i] == axes[j]) e = kIpoConfigAxisErr;
    for (size_t i = 0; e == 0 && i < axes.size(); ++i)
      if (axes[i]->config().drive.kind == AxisKind::Encoder) e = kIpoConfigAxisErr;
    if (e == 0 && in.stop) {
      terminate(r, false, true, 0, false);   // Stop already TRUE: nothing moves
    } else if (e != 0) {
      fail(e);
    } else if (segs.empty()) {
      terminate(r, true, false, 0, false);   // already at the end point: Done at once
    } else if (Error ge = enableGroupWith(k, g, axes, true, c); ge != Error::None) {
      fail(ge == Error::AgAxisNotServo ? kIpoConfigAxisErr
           : ge == Error::AgAxisNotReady || ge == Error::AgAxisInOtherGroup ? kIpoAxisNotStandStill
                                                                            : static_cast<int32_t>(smcError(ge)));
    } else {
      setGroupRate(k, g, in.hasRatio ? in.ratio : 1.0, c);
      r.lineCurrent = segs.front().lineNum;   // the first segment starts in this cycle
      r.segs = std::move(segs);
      r.next = 0;
      r.dec = in.dec;
      r.jerk = in.velocityMode == 0 ? 0.0 : in.jerk;
      r.running = true;
      r.halted = r.stopping = false;
      r.pendingError = 0;
      for (int64_t& s : r.slotSeg) s = -1;
      if (int32_t fe = feed(self, r, g, c); fe != 0) {
        if (r.next == 0) {
          fail(fe);
        } else {   // a later segment: stop what runs, then report
          stopRun(self, r, g, fe, c);
        }
      }
    }
  }
  writeOutputs(self, r);
  r.fresh = false;
  for (Axis* ax : axes) mirrorCall(*ax);
}

bool finiteAll(const float* v, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!bounds::position(v[i])) return false;
  return true;
}

template <class T>
Common commonOf(const T* s) {
  Common in;
  in.exec = s->Exec;
  in.halt = s->Halt;
  in.stop = s->Stop;
  in.ipoCycleUs = s->IpoCycle;
  in.velocityMode = s->VelocityMode;
  if constexpr (requires { s->Velocity; }) {
    in.vel = s->Velocity;
    in.acc = s->Acceleration;
    in.dec = s->Deceleration;
  }
  in.jerk = s->Jerk;
  if constexpr (requires { s->VelRatio; }) {
    in.hasRatio = true;
    in.ratio = s->VelRatio;
  }
  return in;
}

bool samePoint(const path::Vec& a, const std::vector<double>& start, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (std::fabs(a[i] - start[i]) > 1e-12 * std::max(1.0, std::fabs(start[i]))) return false;
  return true;
}

// ---- lines: axes 0..2 interpolate in space, the others follow in proportion (the path layer's rule).
template <class T, size_t N>
void line(T* self, sm3::AXIS_REF_SM3* const (&refs)[N], bool relative) {
  const Common in = commonOf(self);
  ipoBody(self, refs, in, [&](const std::vector<double>& start, std::vector<Segment>& segs) -> int32_t {
    if (!finiteAll(self->EndPos, N)) return kIpoParaErr;
    Segment s;
    s.spec.kind = path::MoveKind::Line;
    for (size_t i = 0; i < N; ++i) s.spec.end[i] = relative ? start[i] + self->EndPos[i] : self->EndPos[i];
    s.spec.dyn = dynamicsOf(in);
    if (!samePoint(s.spec.end, start, N)) segs.push_back(s);
    return 0;
  });
}

// ---- planar arcs (LS_2AxisCircle*, the arc of LS_2AxisCircle*_Helical): every mode becomes
// an arc about a centre in the X/Y plane of axes 0 and 1 (the helix: axis 2 linear in the angle).
struct ArcIn {
  int dir = 0, mode = 1;
  double stopAngle = 0, radius = 0;
  double aux[2] = {}, end[2] = {};
  unsigned turns = 0;
};

int32_t planarArc(const ArcIn& a, const std::vector<double>& start, bool relative, path::MoveSpec& spec) {
  const double ax = start[0], ay = start[1];
  if (!bounds::position(a.aux[0]) || !bounds::position(a.aux[1]) || !bounds::position(a.end[0]) || !bounds::position(a.end[1]) ||
      !std::isfinite(a.stopAngle) || !std::isfinite(a.radius))
    return kIpoParaErr;
  if (a.mode < 0 || a.mode > 3) return kIpoCirMode;
  if (a.mode != 0 && a.dir != 0 && a.dir != 1) return kIpoCirDir;
  const double bx = relative ? ax + a.aux[0] : a.aux[0], by = relative ? ay + a.aux[1] : a.aux[1];
  double ex = relative ? ax + a.end[0] : a.end[0], ey = relative ? ay + a.end[1] : a.end[1];
  bool ccw = a.dir == 0;
  double cx = 0, cy = 0;
  switch (a.mode) {
    case 0: {   // three points: start, via AuxPos, end
      const double d = 2 * ((bx - ax) * (ey - by) - (by - ay) * (ex - bx));
      const double scale = std::max({std::hypot(bx - ax, by - ay), std::hypot(ex - bx, ey - by), 1e-300});
      if (std::hypot(ex - ax, ey - ay) <= 1e-9 * scale) {   // back to the start: the circle with diameter A-B
        if (std::hypot(bx - ax, by - ay) < 1e-6) return kIpoCirThreePoint;
        cx = (ax + bx) / 2;
        cy = (ay + by) / 2;
        ex = ax;
        ey = ay;
        break;
      }
      if (std::fabs(d) <= 1e-12 * scale * scale) return kIpoCirThreePoint;
      const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, e2 = ex * ex + ey * ey;
      cx = (a2 * (by - ey) + b2 * (ey - ay) + e2 * (ay - by)) / d;
      cy = (a2 * (ex - bx) + b2 * (ax - ex) + e2 * (bx - ax)) / d;
      ccw = d > 0;   // the turn from A over B to C
      break;
    }
    case 1:   // centre AuxPos, end EndPos
      cx = bx;
      cy = by;
      break;
    case 2: {   // end and radius: positive the arc below half a turn, negative the one above
      const double r = std::fabs(a.radius);
      if (r < 1e-6) return kIpoCirRadErr;
      const double chord = std::hypot(ex - ax, ey - ay);
      if (chord < 1e-9 || chord > 2 * r * (1 + 1e-12)) return kIpoCirParaErr;
      const double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4));
      // The centre on the left of the chord (seen along A -> C) for a short ccw arc.
      const double side = (ccw ? 1.0 : -1.0) * (a.radius > 0 ? 1.0 : -1.0);
      cx = (ax + ex) / 2 - side * h * (ey - ay) / chord;
      cy = (ay + ey) / 2 + side * h * (ex - ax) / chord;
      break;
    }
    case 3: {   // centre AuxPos and stop angle in degrees (0, 360] from the start
      cx = bx;
      cy = by;
      if (!(a.stopAngle > 0 && a.stopAngle <= 360)) return kIpoCirAngelOrg;
      if (std::hypot(ax - cx, ay - cy) < 1e-6) return kIpoCirAngelOrg;
      const double th = (ccw ? 1.0 : -1.0) * a.stopAngle * std::numbers::pi / 180.0;
      ex = cx + (ax - cx) * std::cos(th) - (ay - cy) * std::sin(th);
      ey = cy + (ax - cx) * std::sin(th) + (ay - cy) * std::cos(th);
      if (a.stopAngle == 360) {
        ex = ax;
        ey = ay;
      }
      break;
    }
  }
  if (std::hypot(ax - cx, ay - cy) < 1e-6) return a.mode == 1 ? kIpoCirRadErr : kIpoCirParaErr;
  spec.kind = path::MoveKind::ArcCenter;
  spec.aux = path::Vec{};
  spec.aux[0] = cx;
  spec.aux[1] = cy;
  for (size_t i = 2; i < start.size(); ++i) spec.aux[i] = start[i];
  spec.end[0] = ex;
  spec.end[1] = ey;
  spec.ccw = ccw;
  spec.turns = static_cast<int>(a.turns);
  spec.normal = path::Vec{0, 0, 1};
  return 0;
}

template <class T>
ArcIn arcIn(const T* s) {
  ArcIn a;
  a.dir = s->ArcIpo_dir;
  a.mode = s->Circle_Mode;
  a.stopAngle = s->StopAngle;
  a.radius = s->CircleRadiual;
  a.aux[0] = s->AuxPos[0];
  a.aux[1] = s->AuxPos[1];
  a.end[0] = s->EndPos[0];
  a.end[1] = s->EndPos[1];
  a.turns = s->RunCycle;
  return a;
}

template <class T, size_t N>
void circle2(T* self, sm3::AXIS_REF_SM3* const (&refs)[N], bool relative) {
  const Common in = commonOf(self);
  ipoBody(self, refs, in, [&](const std::vector<double>& start, std::vector<Segment>& segs) -> int32_t {
    Segment s;
    if (int32_t e = planarArc(arcIn(self), start, relative, s.spec); e != 0) return e;
    if constexpr (requires { self->HelicalPos; }) {
      if (!bounds::position(self->HelicalPos)) return kIpoParaErr;
      s.spec.end[2] = relative ? start[2] + self->HelicalPos : self->HelicalPos;
    }
    s.spec.dyn = dynamicsOf(in);
    s.geoError = kIpoCirParaErr;
    segs.push_back(s);
    return 0;
  });
}

template <class T, size_t N>
void circle3(T* self, sm3::AXIS_REF_SM3* const (&refs)[N], bool relative) {
  const Common in = commonOf(self);
  ipoBody(self, refs, in, [&](const std::vector<double>& start, std::vector<Segment>& segs) -> int32_t {
    if (!finiteAll(self->AuxPos, 3) || !finiteAll(self->EndPos, 3)) return kIpoParaErr;
    if (self->Circle_Mode != 0) return kIpoCirMode;
    Segment s;
    s.spec.kind = path::MoveKind::ArcBorder;
    for (size_t i = 0; i < 3; ++i) {
      s.spec.aux[i] = relative ? start[i] + self->AuxPos[i] : self->AuxPos[i];
      s.spec.end[i] = relative ? start[i] + self->EndPos[i] : self->EndPos[i];
    }
    // Coincident or collinear points: no arc (the path layer's check would give the same).
    path::Vec a{start[0], start[1], start[2]};
    auto dist = [](const path::Vec& p, const path::Vec& q) { return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]); };
    if (dist(a, s.spec.aux) < 1e-9 || dist(s.spec.aux, s.spec.end) < 1e-9) return kIpoSpaceCircleParaErr;
    const double u[3] = {s.spec.aux[0] - a[0], s.spec.aux[1] - a[1], s.spec.aux[2] - a[2]};
    const double w[3] = {s.spec.end[0] - s.spec.aux[0], s.spec.end[1] - s.spec.aux[1], s.spec.end[2] - s.spec.aux[2]};
    const double cross = std::hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]);
    if (cross <= 1e-12 * dist(a, s.spec.aux) * dist(s.spec.aux, s.spec.end)) return kIpoSpaceCircleParaErr;
    s.spec.dyn = dynamicsOf(in);
    s.geoError = kIpoSpaceCircleParaErr;
    segs.push_back(s);
    return 0;
  });
}

template <class T, size_t N>
void ellipse(T* self, sm3::AXIS_REF_SM3* const (&refs)[N], bool relative) {
  const Common in = commonOf(self);
  ipoBody(self, refs, in, [&](const std::vector<double>& start, std::vector<Segment>& segs) -> int32_t {
    if (!finiteAll(self->CenPos, 2) || !finiteAll(self->EndPos, 2) || !std::isfinite(self->K) || !std::isfinite(self->Rcorp))
      return kIpoParaErr;
    if (self->ArcIpo_dir != 0 && self->ArcIpo_dir != 1) return kIpoCirDir;
    if (self->K < 0 || self->K > 360) return kIpoCirAngelOrg;
    if (!(self->Rcorp > 0 && self->Rcorp <= 1)) return kIpoCirParaErr;
    Segment s;
    s.spec.kind = path::MoveKind::Ellipse;
    for (size_t i = 0; i < 2; ++i) {
      s.spec.aux[i] = relative ? start[i] + self->CenPos[i] : self->CenPos[i];
      s.spec.end[i] = relative ? start[i] + self->EndPos[i] : self->EndPos[i];
    }
    s.spec.majorAngle = self->K * std::numbers::pi / 180.0;
    s.spec.ratio = self->Rcorp;
    s.spec.ccw = self->ArcIpo_dir == 0;
    s.spec.turns = static_cast<int>(self->RunCycle);
    s.spec.normal = path::Vec{0, 0, 1};
    s.spec.dyn = dynamicsOf(in);
    s.geoError = kIpoCirParaErr;
    segs.push_back(s);
    return 0;
  });
}

// ---- MoveSequence: lines and three-point arcs from a table, corners rounded (RoundDiameter).
template <class T, size_t N>
void moveSequence(T* self, sm3::AXIS_REF_SM3* const (&refs)[N]) {
  Common in = commonOf(self);
  // No Velocity/Acceleration/Deceleration inputs: each point has its own (checked below).
  in.vel = in.acc = in.dec = 1;
  ipoBody(self, refs, in, [&](const std::vector<double>& start, std::vector<Segment>& segs) -> int32_t {
    const double lim = self->LimitMaxAcc, limJ = self->LimitMaxAccJerk, round = self->RoundDiameter;
    if (!bounds::rate(lim) || !bounds::jerk(limJ) || limJ == 0 || !bounds::position(round) || !(round > 0)) return kIpoParaErr;
    constexpr size_t cap = sizeof(self->MoveSequencePoint) / sizeof(self->MoveSequencePoint[0]);
    if (self->PointsNum > cap) return kIpoBufferOver;
    if (self->PointsNum == 0) return kIpoParaErr;
    std::vector<double> prev = start;
    for (size_t i = 0; i < self->PointsNum; ++i) {
      const auto& p = self->MoveSequencePoint[i];
      const double endv[4] = {p.X_EndPos, p.Y_EndPos, p.Z_EndPos, p.U_EndPos};
      if (p.DataType != 1 && p.DataType != 2) return kIpoDataType;
      for (size_t a = 0; a < N; ++a)
        if (!bounds::position(endv[a])) return kIpoParaErr;
      if (!bounds::position(p.Aux_Pos[0]) || !bounds::position(p.Aux_Pos[1]) || !std::isfinite(p.LineNum)) return kIpoParaErr;
      if (!bounds::velocity(p.Vel)) return kIpoVel;
      if (!bounds::rate(p.Acc)) return kIpoAcc;
      Segment s;
      s.lineNum = p.LineNum;
      for (size_t a = 0; a < N; ++a) s.spec.end[a] = endv[a];
      if (p.DataType == 1) {
        s.spec.kind = path::MoveKind::Line;
        if (samePoint(s.spec.end, prev, N)) continue;   // no length: nothing to move
      } else {
        // The via point's Z is half way between the arc's ends (the table gives X and Y only).
        s.spec.kind = path::MoveKind::ArcBorder;
        s.spec.aux[0] = p.Aux_Pos[0];
        s.spec.aux[1] = p.Aux_Pos[1];
        s.spec.aux[2] = (prev[2] + endv[2]) / 2;
        if (N > 3) s.spec.aux[3] = (prev[3] + endv[3]) / 2;
        s.geoError = kIpoSpaceCircleParaErr;
      }
      const double acc = std::min(p.Acc, lim);
      s.spec.dyn = path::Dynamics{p.Vel, acc, acc, in.velocityMode == 0 ? 0.0 : std::min<double>(self->Jerk, limJ)};
      if (!segs.empty()) {
        s.spec.buffer = path::BufferMode::BlendingLow;
        s.spec.transition = path::TransitionMode::CornerRadius;
        s.spec.transitionParam = round / 2;
      }
      segs.push_back(s);
      for (size_t a = 0; a < N; ++a) prev[a] = endv[a];
    }
    return 0;
  });
}

#define LS_AXES2 {self->Axis0, self->Axis1}
#define LS_AXES3 {self->Axis0, self->Axis1, self->Axis2}
#define LS_AXES4 {self->Axis0, self->Axis1, self->Axis2, self->Axis3}
#define LS_AXES5 {self->Axis0, self->Axis1, self->Axis2, self->Axis3, self->Axis4}
#define LS_AXES6 {self->Axis0, self->Axis1, self->Axis2, self->Axis3, self->Axis4, self->Axis5}
#define LS_BODY(fn, n, call)                        \
  void fn(sm3::fn* self) {                          \
    sm3::AXIS_REF_SM3* const refs[n] = LS_AXES##n;  \
    call;                                           \
  }

LS_BODY(LS_2AxisLineAbs, 2, line(self, refs, false))
LS_BODY(LS_2AxisLineRel, 2, line(self, refs, true))
LS_BODY(LS_3AxisLineAbs, 3, line(self, refs, false))
LS_BODY(LS_3AxisLineRel, 3, line(self, refs, true))
LS_BODY(LS_4AxisLineAbs, 4, line(self, refs, false))
LS_BODY(LS_4AxisLineRel, 4, line(self, refs, true))
LS_BODY(LS_5AxisLineAbs, 5, line(self, refs, false))
LS_BODY(LS_5AxisLineRel, 5, line(self, refs, true))
LS_BODY(LS_6AxisLineAbs, 6, line(self, refs, false))
LS_BODY(LS_6AxisLineRel, 6, line(self, refs, true))
LS_BODY(LS_2AxisLineAbs_Ratio, 2, line(self, refs, false))
LS_BODY(LS_2AxisLineRel_Ratio, 2, line(self, refs, true))
LS_BODY(LS_2AxisCircleAbs, 2, circle2(self, refs, false))
LS_BODY(LS_2AxisCircleRel, 2, circle2(self, refs, true))
LS_BODY(LS_3AxisCircleAbs, 3, circle3(self, refs, false))
LS_BODY(LS_3AxisCircleRel, 3, circle3(self, refs, true))
LS_BODY(LS_2AxisEllipsesAbs, 2, ellipse(self, refs, false))
LS_BODY(LS_2AxisEllipsesRel, 2, ellipse(self, refs, true))
LS_BODY(LS_2AxisCircleAbs_Helical, 3, circle2(self, refs, false))
LS_BODY(LS_2AxisCircleRel_Helical, 3, circle2(self, refs, true))
LS_BODY(LS_3AxisMoveSequence, 3, moveSequence(self, refs))
LS_BODY(LS_4AxisMoveSequence, 4, moveSequence(self, refs))

}  // namespace

namespace stc::motion {

void registerLsInterpolationNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(LS_2AxisLineAbs, LS_2AxisLineAbs)
  STC_SM3_NATIVE(LS_2AxisLineRel, LS_2AxisLineRel)
  STC_SM3_NATIVE(LS_3AxisLineAbs, LS_3AxisLineAbs)
  STC_SM3_NATIVE(LS_3AxisLineRel, LS_3AxisLineRel)
  STC_SM3_NATIVE(LS_4AxisLineAbs, LS_4AxisLineAbs)
  STC_SM3_NATIVE(LS_4AxisLineRel, LS_4AxisLineRel)
  STC_SM3_NATIVE(LS_5AxisLineAbs, LS_5AxisLineAbs)
  STC_SM3_NATIVE(LS_5AxisLineRel, LS_5AxisLineRel)
  STC_SM3_NATIVE(LS_6AxisLineAbs, LS_6AxisLineAbs)
  STC_SM3_NATIVE(LS_6AxisLineRel, LS_6AxisLineRel)
  STC_SM3_NATIVE(LS_2AxisLineAbs_Ratio, LS_2AxisLineAbs_Ratio)
  STC_SM3_NATIVE(LS_2AxisLineRel_Ratio, LS_2AxisLineRel_Ratio)
  STC_SM3_NATIVE(LS_2AxisCircleAbs, LS_2AxisCircleAbs)
  STC_SM3_NATIVE(LS_2AxisCircleRel, LS_2AxisCircleRel)
  STC_SM3_NATIVE(LS_3AxisCircleAbs, LS_3AxisCircleAbs)
  STC_SM3_NATIVE(LS_3AxisCircleRel, LS_3AxisCircleRel)
  STC_SM3_NATIVE(LS_2AxisEllipsesAbs, LS_2AxisEllipsesAbs)
  STC_SM3_NATIVE(LS_2AxisEllipsesRel, LS_2AxisEllipsesRel)
  STC_SM3_NATIVE(LS_2AxisCircleAbs_Helical, LS_2AxisCircleAbs_Helical)
  STC_SM3_NATIVE(LS_2AxisCircleRel_Helical, LS_2AxisCircleRel_Helical)
  STC_SM3_NATIVE(LS_3AxisMoveSequence, LS_3AxisMoveSequence)
  STC_SM3_NATIVE(LS_4AxisMoveSequence, LS_4AxisMoveSequence)
}

}  // namespace stc::motion
