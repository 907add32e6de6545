// Path planner: queue, blending, look-ahead, interpolation (see Planner.h and docs/path.md).
#include "stdlib-motion/path/Planner.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "stdlib-motion/core/InputBounds.h"

namespace stc::motion::path {

namespace {

constexpr double kTangentAngle = 1e-6;                          // rad: junctions below this need no transition
constexpr double kMaxBlendAngle = 175.0 * std::numbers::pi / 180;   // beyond: a reversal, exact stop

// Duration of a velocity change by dv >= 0 starting and ending with a = 0
// (rate bound A, jerk J; J == 0: constant rate).
double transTime(double dv, double A, double J) {
  if (dv <= 0) return 0;
  if (J <= 0) return dv / A;
  if (dv >= A * A / J) return dv / A + A / J;
  return 2 * std::sqrt(dv / J);
}

// Distance of the change v0 -> v1 (both >= 0): the profile is point-symmetric.
double transDist(double v0, double v1, double A, double J) {
  return 0.5 * (v0 + v1) * transTime(std::fabs(v1 - v0), A, J);
}

double jerkMin(double a, double b) {   // 0 = unlimited
  if (a <= 0) return b;
  if (b <= 0) return a;
  return std::min(a, b);
}
double jerkMax(double a, double b) {
  if (a <= 0 || b <= 0) return 0;
  return std::max(a, b);
}

bool validDyn(const Dynamics& d) {
  return bounds::velocity(d.vel) && bounds::rate(d.acc) && bounds::rate(d.dec) && bounds::jerk(d.jerk);
}

}  // namespace

const char* toString(PathStatus s) {
  switch (s) {
    case PathStatus::Ok: return "ok";
    case PathStatus::QueueFull: return "path queue full";
    case PathStatus::InvalidDynamics: return "invalid velocity/acceleration/deceleration/jerk";
    case PathStatus::InvalidGeometry: return "invalid geometry";
    case PathStatus::BlendingNeedsTransition: return "blending buffer mode needs a transition mode";
    case PathStatus::TransitionNotAllowed: return "transition mode not allowed with this buffer mode";
    case PathStatus::InvalidTransitionParameter: return "invalid transition parameter";
    case PathStatus::InvalidOverride: return "invalid override";
    case PathStatus::NotHeld: return "not interrupted";
    case PathStatus::Unreachable: return "a point out of the kinematics' reach";
  }
  return "?";
}

Planner::Planner(const PlannerConfig& cfg)
    : dims_(std::clamp(cfg.dims, 1, kMaxCoords)), cap_(std::max(cfg.capacity, 2)), axes_(cfg.axes) {
  axes_.count = std::clamp(axes_.count, 0, kMaxCoords);
  if (!axes_.map) axes_.count = std::min(axes_.count, dims_);
  axes_.curvatureShare = std::clamp(axes_.curvatureShare, 0.05, 0.95);
  ring_.resize(cap_);
  scratchSegs_.resize(cap_);
  savedVEnd_.resize(cap_);
  events_.resize(2 * cap_ + 16);
  splineScratch_.h.resize(cap_ + 1);
  splineScratch_.diag.resize(cap_ + 1);
  splineScratch_.cprime.resize(cap_ + 1);
  splineScratch_.rhs.resize((cap_ + 1) * kMaxCoords);
  sample_.pos = holdPos_;
}

bool Planner::setPosition(const Vec& p) {
  if (count_ > 0) return false;
  for (int i = 0; i < dims_; ++i)
    if (!std::isfinite(p[i])) return false;
  holdPos_ = {};
  for (int i = 0; i < dims_; ++i) holdPos_[i] = p[i];
  sample_ = Sample{};
  sample_.pos = holdPos_;
  return true;
}

void Planner::pushEvent(uint32_t id, EventKind k, double t) {
  if (nEvents_ < static_cast<int>(events_.size())) events_[nEvents_++] = {id, k, t};
}

// Slots a and b (consecutive) belong to one run: equal rate and jerk limits, a
// junction that does not stop, and velocity caps within 10 % of each other -- or
// the faster slot is too short to use its higher cap (shorter than the way up to
// it and back down).  A run is planned as one motion at its lowest cap
// (docs/path.md, "Runs").
bool Planner::sameLimits(const Slot& a, const Slot& b) const {
  constexpr double kRunSpread = 0.9;
  if (!(a.acc == b.acc && a.dec == b.dec && a.jerk == b.jerk && a.juncCap > 0)) return false;
  const double lo = std::min({a.vcap, b.vcap, a.juncCap});
  auto fits = [&](const Slot& x) {
    if (x.vcap * kRunSpread <= lo) return true;
    // Jerk-limited: a slot too short for the transition to its own cap and back joins the
    // run (its profile could not be planned alone from a state with acceleration).
    // Trapezoidal slots are never merged for that: a run's velocity is the lowest cap in
    // it, and a chain of short slots behind one tight curve then crept at that curve's cap.
    return x.jerk > 0 && x.geo.length() < 2 * transDist(lo, x.vcap, std::min(x.acc, x.dec), x.jerk);
  };
  return fits(a) && fits(b);
}

double Planner::remaining() const {
  if (count_ == 0) return 0;
  double s = planned_ ? prof_.at(tau_).p - at(0).planStart : sHead_;
  double r = -s;
  for (int i = 0; i < count_; ++i) r += at(i).geo.length();
  return std::max(0.0, r);
}

// ---------------------------------------------------------------- caps and look-ahead

bool Planner::computeCaps(Slot& s, bool* unreachable) const {
  const Dynamics& d = s.nominal;
  s.vcap = d.vel;
  s.acc = d.acc;
  s.dec = d.dec;
  s.jerk = d.jerk;
  const double kap = s.geo.maxCurvature();
  if (kap > 0) s.vcap = std::min(s.vcap, std::sqrt(d.acc / kap));
  if (axes_.count > 0) {
    int M = 16;
    if (s.geo.kind() == SegKind::Line && !axes_.map) M = 1;
    else if (s.geo.kind() == SegKind::Arc)
      M = std::min(256, 16 * static_cast<int>(std::ceil(s.geo.sweep() / (2 * std::numbers::pi) + 1e-9)));
    else if (s.geo.kind() != SegKind::Line) M = 32;
    double qv[kMaxCoords] = {}, qa[kMaxCoords] = {};
    PathPoint pp;
    Vec dq{}, ddq{};
    for (int k = 0; k <= M; ++k) {
      s.geo.eval(s.geo.length() * k / M, pp);
      if (axes_.map) {
        dq = {};
        ddq = {};
        if (!axes_.map(pp.pos, pp.d1, pp.d2, dq, ddq)) {
          if (unreachable) *unreachable = true;
          return false;
        }
      } else {
        dq = pp.d1;
        ddq = pp.d2;
      }
      for (int i = 0; i < axes_.count; ++i) {
        if (!std::isfinite(dq[i]) || !std::isfinite(ddq[i])) return false;
        qv[i] = std::max(qv[i], std::fabs(dq[i]));
        qa[i] = std::max(qa[i], std::fabs(ddq[i]));
      }
    }
    const double margin = (M == 1) ? 1.0 : 1.03;   // between samples
    const double share = axes_.curvatureShare;
    for (int i = 0; i < axes_.count; ++i) {
      if (qv[i] > 0) {
        if (axes_.vel[i] > 0) s.vcap = std::min(s.vcap, axes_.vel[i] / (qv[i] * margin));
        if (axes_.acc[i] > 0) {
          s.acc = std::min(s.acc, (1 - share) * axes_.acc[i] / (qv[i] * margin));
          s.dec = std::min(s.dec, (1 - share) * axes_.acc[i] / (qv[i] * margin));
        }
      }
      if (qa[i] > 0 && axes_.acc[i] > 0) s.vcap = std::min(s.vcap, std::sqrt(share * axes_.acc[i] / (qa[i] * margin)));
    }
  }
  return s.vcap > 0 && s.acc > 0 && s.dec > 0;
}

// (len is shortened by a relative 1e-7 so that a plan is never exactly at the
// limit: the 1-D planner's rounding must not turn it into a tiny reversal.)
double Planner::brakeReach(double vEnd, double len, double dec, double jerk, double vcap) const {
  len *= 1 - 1e-7;
  if (transDist(vcap, vEnd, dec, jerk) <= len) return vcap;
  if (jerk <= 0) return std::min(vcap, std::sqrt(vEnd * vEnd + 2 * dec * len));
  double lo = vEnd, hi = vcap;
  for (int i = 0; i < 60 && hi - lo > 1e-13 * hi; ++i) {
    const double m = 0.5 * (lo + hi);
    if (transDist(m, vEnd, dec, jerk) <= len) lo = m;
    else hi = m;
  }
  return lo;
}

double Planner::accelReach(double v0, double len, double acc, double jerk, double vcap) const {
  len *= 1 - 1e-7;
  if (transDist(v0, vcap, acc, jerk) <= len) return vcap;
  if (jerk <= 0) return std::min(vcap, std::sqrt(v0 * v0 + 2 * acc * len));
  double lo = v0, hi = vcap;
  for (int i = 0; i < 60 && hi - lo > 1e-13 * hi; ++i) {
    const double m = 0.5 * (lo + hi);
    if (transDist(v0, m, acc, jerk) <= len) lo = m;
    else hi = m;
  }
  return lo;
}

// Recomputes vEndMax from the end of the queue backwards.  `from` is the index
// of the first slot whose data changed; below it the pass stops as soon as a
// value no longer changes at a point that decouples the slots before it.
void Planner::backwardPass(int from) {
  if (count_ == 0) return;
  Slot& tail = at(count_ - 1);
  tail.vEndMax = 0;
  tail.juncCap = 0;
  double runEndV = 0, runLen = 0, runMin = 0;
  for (int k = count_ - 2; k >= 0; --k) {
    const Slot& nx = at(k + 1);
    const bool boundary = (k + 1 == count_ - 1) || !sameLimits(nx, at(k + 2));
    if (boundary) {
      runEndV = nx.vEndMax;
      runLen = nx.geo.length();
      runMin = nx.vcap;
    } else {
      runLen += nx.geo.length();
      runMin = std::min({runMin, nx.vcap, nx.juncCap});
    }
    Slot& s = at(k);
    const double reach = brakeReach(std::min(runEndV, runMin), runLen, nx.dec, nx.jerk, runMin);
    const double nv = std::min({s.juncCap, runMin, reach});
    const double old = s.vEndMax;
    s.vEndMax = nv;
    ++backSteps_;
    if (k < from && nv == old && (boundary || reach >= runMin)) break;
  }
}

// ---------------------------------------------------------------- planning

bool Planner::valid(const Profile& p) const {
  const double tol = 1e-7 * std::max(1.0, std::fabs(p.start().v) + std::fabs(p.end().v));
  for (int i = 0; i < p.segmentCount(); ++i) {
    const auto& g = p.segment(i);
    if (g.v < -tol) return false;
    if (g.j != 0) {
      const double t = -g.a / g.j;
      if (t > 0 && t < g.dur && g.v + g.a * t + 0.5 * g.j * t * t < -tol) return false;
    } else if (g.a < 0 && g.v + g.a * g.dur < -tol) {
      return false;
    }
  }
  return p.end().v >= -tol;
}

Kinematic Planner::planState() const {
  if (!planned_) return {0, 0, 0};
  return prof_.at(tau_);
}

// Plans from the head (path length s into it, velocity v, acceleration a) to the
// end of the head's run.  Writes planStart/planEnd of the covered slots and the
// plan only on success.
bool Planner::planRun(const Kinematic& st, int& runEnd, Profile& out) {
  const Slot& h = at(0);
  const double s = st.p;
  int e = 0;
  double vel = h.vcap;
  while (e + 1 < count_ && sameLimits(at(e), at(e + 1))) {
    vel = std::min({vel, at(e).juncCap, at(e + 1).vcap});
    ++e;
  }
  double target = h.geo.length() - s;
  for (int i = 1; i <= e; ++i) target += at(i).geo.length();
  if (!(target > 0)) target = 0;
  const Limits lim{vel, h.acc, h.dec, h.jerk};
  double vEnd = std::min(at(e).vEndMax, vel);
  const double v0 = std::max(0.0, st.v);
  if (st.a == 0 && v0 <= vel) vEnd = std::min(vEnd, accelReach(v0, target, h.acc, h.jerk, vel));
  Profile p;
  bool ok = planPosition({0, v0, st.a}, target, vEnd, lim, p) == PlanStatus::Ok && valid(p);
  if (!ok) {
    // the largest end velocity that gives a forward-only profile
    double lo = 0, hi = vEnd;
    Profile q;
    if (planPosition({0, v0, st.a}, target, 0, lim, q) == PlanStatus::Ok && valid(q)) {
      p = q;
      ok = true;
      for (int it = 0; it < 40 && hi - lo > 1e-12 * std::max(1.0, hi); ++it) {
        const double m = 0.5 * (lo + hi);
        if (planPosition({0, v0, st.a}, target, m, lim, q) == PlanStatus::Ok && valid(q)) {
          lo = m;
          p = q;
        } else {
          hi = m;
        }
      }
    }
  }
  if (!ok) return false;
  ++replans_;
  double ps = -s;
  for (int i = 0; i <= e; ++i) {
    Slot& x = at(i);
    x.planStart = ps;
    x.planEnd = i == e ? target : ps + x.geo.length();
    ps = x.planEnd;
  }
  runEnd = e;
  out = p;
  return true;
}

bool Planner::replan() {
  if (count_ == 0) {
    planned_ = false;
    return true;
  }
  Kinematic st;
  if (planned_) {
    const Kinematic k = prof_.at(tau_);
    st = {k.p - at(0).planStart, k.v, k.a};
  } else {
    st = {sHead_, 0, 0};
  }
  int e = 0;
  Profile p;
  if (!planRun(st, e, p)) return false;
  prof_ = p;
  tau_ = 0;
  planSlots_ = e + 1;
  planned_ = true;
  return true;
}

// ---------------------------------------------------------------- operations

GeoStatus Planner::buildGeometry(const MoveSpec& m, const Vec& start, const Vec* inTangent, int& n) {
  auto rel = [&](const Vec& v) {
    Vec r = v;
    if (m.relative)
      for (int i = 0; i < dims_; ++i) r[i] = start[i] + v[i];
    for (int i = dims_; i < kMaxCoords; ++i) r[i] = 0;
    return r;
  };
  n = 1;
  const Vec end = rel(m.end);
  switch (m.kind) {
    case MoveKind::Line: return Segment::line(start, end, dims_, scratchSegs_[0]);
    case MoveKind::ArcBorder: return Segment::arcBorder(start, rel(m.aux), end, m.normal, dims_, scratchSegs_[0]);
    case MoveKind::ArcCenter:
    {
      Vec centre = rel(m.aux);
      if (m.centerRelative && !m.relative)
        for (int i = 0; i < dims_; ++i) centre[i] = start[i] + m.aux[i];
      return Segment::arcCenter(start, centre, end, m.normal, m.ccw, m.turns, dims_, scratchSegs_[0]);
    }
    case MoveKind::ArcRadius:
      return Segment::arcRadius(start, end, m.radius, m.normal, m.ccw, m.longArc, m.turns, dims_, scratchSegs_[0]);
    case MoveKind::Ellipse:
      return Segment::ellipse(start, rel(m.aux), end, m.majorAngle, m.ratio, m.normal, m.ccw, m.turns, dims_,
                              scratchSegs_[0]);
    case MoveKind::Spline: {
      const int np = static_cast<int>(m.points.size());
      if (np < 1) return GeoStatus::BadParameter;
      if (np > cap_) return GeoStatus::TooManyPoints;
      // the points (relative ones converted) go through the ring's spare slots' scratch
      static thread_local std::vector<Vec> abs;   // (sized once per thread; see docs/path.md)
      if (abs.size() < static_cast<size_t>(np)) abs.resize(std::max<size_t>(np, 64));
      for (int i = 0; i < np; ++i) abs[i] = rel(m.points[i]);
      n = np;
      return splineThrough(start, {abs.data(), static_cast<size_t>(np)}, dims_, inTangent, nullptr,
                           {scratchSegs_.data(), static_cast<size_t>(np)}, splineScratch_);
    }
    case MoveKind::Prebuilt: {
      if (!m.segment || m.segment->dims() != dims_) return GeoStatus::BadDims;
      const Vec& a = m.segment->startPoint();
      for (int i = 0; i < dims_; ++i)
        if (!(std::fabs(a[i] - start[i]) <= 1e-9 * std::max(1.0, std::fabs(start[i])))) return GeoStatus::BadParameter;
      scratchSegs_[0] = *m.segment;
      return GeoStatus::Ok;
    }
  }
  return GeoStatus::BadParameter;
}

// Where a stop along the path from the current state ends: a velocity ramp to 0
// with (at least) dec / jerk, or -- when that would run past the first exact stop
// ahead (a stop corner or the end of the queue) -- that stop, which the running
// plan reaches by itself.
void Planner::computeStop(double dec, double jerk, StopInfo& st) const {
  st = StopInfo{};
  if (count_ == 0) {
    st.atRest = true;
    st.point = holdPos_;
    return;
  }
  const Slot& h = at(0);
  const Kinematic k = planState();
  const double s = planned_ ? k.p - h.planStart : sHead_;
  st.s0 = s;
  st.slot = 0;
  st.local = s;
  if (!planned_ || !(k.v > 0 || k.a > 0)) {
    st.atRest = true;
    st.point = h.geo.position(s);
    return;
  }
  const Limits lim{std::max(k.v, h.vcap), h.acc, std::max(dec, h.dec),
                   (jerk <= 0 || h.jerk <= 0) ? 0.0 : std::max(jerk, h.jerk)};
  Profile sp;
  planVelocity({0, k.v, k.a}, 0, lim, sp);
  const double dist = sp.end().p;
  double acc = -s;
  int j = 0;
  for (; j < count_; ++j) {
    acc += at(j).geo.length();
    if (at(j).juncCap <= 0) break;
  }
  if (j >= count_) j = count_ - 1;
  if (dist <= acc && valid(sp)) {
    st.ramp = true;
    st.prof = sp;
    double ps = -s;
    int i = 0;
    for (; i < count_ - 1; ++i) {
      const double pe = ps + at(i).geo.length();
      if (dist <= pe) break;
      ps = pe;
    }
    st.slot = i;
    st.local = std::clamp(dist - ps, 0.0, at(i).geo.length());
    // a stop within rounding of a segment start ends the segment before instead
    if (st.local <= 1e-12 * std::max(1.0, at(i).geo.length())) {
      if (i > 0) {
        st.slot = i - 1;
        st.local = at(i - 1).geo.length();
      } else {
        st.atRest = true;
        st.ramp = false;
        st.local = s;
      }
    }
  } else {
    st.slot = j;
    st.local = at(j).geo.length();
  }
  st.point = at(st.slot).geo.position(st.local);
}

AppendResult Planner::append(const MoveSpec& m) {
  AppendResult r;
  if (!validDyn(m.dyn)) return r.status = PathStatus::InvalidDynamics, r;
  const bool blending = m.buffer >= BufferMode::BlendingLow;
  if (blending && m.transition == TransitionMode::None) return r.status = PathStatus::BlendingNeedsTransition, r;
  if (m.buffer == BufferMode::Buffered && m.transition != TransitionMode::None)
    return r.status = PathStatus::TransitionNotAllowed, r;
  if (m.transition != TransitionMode::None && !(std::isfinite(m.transitionParam) && m.transitionParam >= 0))
    return r.status = PathStatus::InvalidTransitionParameter, r;
  if (static_cast<uint8_t>(m.buffer) > 5 || static_cast<uint8_t>(m.transition) > 4)
    return r.status = PathStatus::InvalidTransitionParameter, r;

  const bool aborting = m.buffer == BufferMode::Aborting && count_ > 0;

  // Where the move starts: the end of the queue, or the stop point of an abort.
  StopInfo stop;
  Vec start = count_ == 0 ? holdPos_ : at(count_ - 1).geo.endPoint();
  int keep = count_;   // slots kept in the queue
  if (aborting) {
    computeStop(m.dyn.dec, m.dyn.jerk, stop);
    start = stop.point;
    keep = stop.atRest ? 0 : stop.slot + 1;
  }

  // Geometry of the new move.
  Vec inTan{};
  const Vec* inTanPtr = nullptr;
  if (count_ > 0 && !aborting && blending) {
    PathPoint pp;
    const Slot& t = at(count_ - 1);
    t.geo.eval(t.geo.length(), pp);
    inTan = pp.d1;
    inTanPtr = &inTan;
  }
  int n = 0;
  const GeoStatus gs = buildGeometry(m, start, inTanPtr, n);
  if (gs != GeoStatus::Ok) return r.status = PathStatus::InvalidGeometry, r.geo = gs, r;
  if (keep + n + 1 > cap_) return r.status = PathStatus::QueueFull, r;

  // Caps of the new slots (checked before anything changes).
  const uint32_t id = nextId_;
  Slot proto;
  proto.nominal = m.dyn;
  proto.owner = id;
  for (int i = 0; i < n; ++i) {
    Slot t = proto;
    t.geo = scratchSegs_[i];
    bool unreachable = false;
    if (!computeCaps(t, &unreachable)) {
      r.status = unreachable ? PathStatus::Unreachable : PathStatus::InvalidGeometry;
      r.geo = unreachable ? GeoStatus::Ok : GeoStatus::BadParameter;
      return r;
    }
  }
  ++nextId_;
  r.id = id;

  // ---- commit
  bool startedNow = count_ == 0;
  if (aborting) {
    // every move in the queue is aborted now
    uint32_t lastOwner = 0;
    for (int i = 0; i < count_; ++i) {
      const Slot& x = at(i);
      if (!x.silent && x.owner != lastOwner) pushEvent(x.owner, EventKind::Aborted, 0);
      lastOwner = x.owner;
    }
    if (keep == 0) {
      count_ = 0;
      planned_ = false;
      held_ = false;
      holdPos_ = start;
    } else {
      count_ = keep;
      Slot& last = at(keep - 1);
      if (stop.local < last.geo.length() && stop.local > 0) last.geo.trim(0, stop.local);
      if (stop.ramp) {
        installStopRamp(stop, keep);
        last.planEnd = prof_.end().p;
      }
      for (int i = 0; i < keep; ++i) {
        Slot& x = at(i);
        x.owner = id;
        x.silent = true;
        x.first = x.last = false;
      }
      last.juncCap = 0;
      last.vEndMax = 0;
      held_ = false;
      holding_ = false;
    }
    startedNow = true;
  }
  const int tailIdx = count_ - 1;   // -1: empty
  Slot savedTail;
  if (tailIdx >= 0) savedTail = at(tailIdx);
  for (int i = 0; i < count_; ++i) savedVEnd_[i] = at(i).vEndMax;
  const int oldCount = count_;
  bool blendUsed = false;

  auto pushSlots = [&](int from) {
    for (int i = from; i < n; ++i) {
      Slot t = proto;
      t.geo = scratchSegs_[i];
      t.origLen = t.geo.length();
      computeCaps(t);
      t.first = (i == 0) && !startedNow;
      t.last = i == n - 1;
      t.juncCap = 0;
      if (i + 1 < n) {   // spline pieces: tangent, curvature-continuous
        Slot nx = proto;
        nx.geo = scratchSegs_[i + 1];
        computeCaps(nx);
        t.juncCap = std::min(t.vcap, nx.vcap);
      }
      at(count_++) = t;
    }
  };

  if (tailIdx >= 0 && !aborting && m.buffer == BufferMode::Buffered && m.junctionVel > 0 &&
      std::isfinite(m.junctionVel)) {
    Slot sFirst = proto;
    sFirst.geo = scratchSegs_[0];
    computeCaps(sFirst);
    Slot& T = at(tailIdx);
    T.juncCap = std::min({T.vcap, sFirst.vcap, m.junctionVel});
  } else if (tailIdx >= 0 && !aborting && m.buffer != BufferMode::Buffered) {
    Slot& T = at(tailIdx);
    Segment& S = scratchSegs_[0];
    Slot sFirst = proto;
    sFirst.geo = S;
    computeCaps(sFirst);
    const double ang = cornerAngle(T.geo, S);
    if (ang <= kTangentAngle) {
      T.juncCap = std::min(T.vcap, sFirst.vcap);
    } else if (blending && ang <= kMaxBlendAngle && T.geo.cartesianMetric() && S.cartesianMetric() &&
               !(holding_ && tailIdx < planSlots_)) {
      // transition distance from the corner
      double d = 0;
      const double half = 0.5 * std::min(T.origLen, S.length());
      switch (m.transition) {
        case TransitionMode::CornerDistance: d = m.transitionParam; break;
        case TransitionMode::CornerRadius: d = m.transitionParam * std::tan(0.5 * ang); break;
        case TransitionMode::StartVelocity: {
          const double v1 = T.nominal.vel, v2 = m.dyn.vel;
          d = m.transitionParam * std::min(v1 * v1 / (2 * T.nominal.dec), v2 * v2 / (2 * m.dyn.acc));
          break;
        }
        case TransitionMode::MaxCornerDeviation: d = half; break;
        case TransitionMode::None: break;
      }
      d = std::min(d, half);
      // not behind the current point
      if (planned_ && tailIdx < planSlots_) {
        const double s = prof_.at(tau_).p - T.planStart;
        d = std::min(d, T.geo.length() - s - 1e-9 * std::max(1.0, T.origLen));
      } else if (!planned_ && tailIdx == 0) {
        d = std::min(d, T.geo.length() - sHead_ - 1e-9 * std::max(1.0, T.origLen));
      }
      d = std::min(d, T.geo.length() * (1 - 1e-9));
      Segment blend;
      GeoStatus bs = GeoStatus::BadParameter;
      if (d > 1e-9 * std::max(1.0, half)) {
        bs = blendBetween(T.geo, T.geo.length() - d, S, d, blend);
        if (bs == GeoStatus::Ok && m.transition == TransitionMode::MaxCornerDeviation) {
          // the deviation of the blend's middle from the corner scales ~ linearly with d
          const Vec corner = T.geo.endPoint();
          for (int it = 0; it < 4 && bs == GeoStatus::Ok; ++it) {
            const Vec mid = blend.position(0.5 * blend.length());
            double dev = 0;
            for (int i = 0; i < std::min(dims_, 3); ++i) dev += (mid[i] - corner[i]) * (mid[i] - corner[i]);
            dev = std::sqrt(dev);
            if (dev <= m.transitionParam * (1 + 1e-9)) break;
            d *= 0.999 * m.transitionParam / dev;
            if (!(d > 1e-9 * std::max(1.0, half))) {
              bs = GeoStatus::BadParameter;
              break;
            }
            bs = blendBetween(T.geo, T.geo.length() - d, S, d, blend);
          }
        }
      }
      if (bs == GeoStatus::Ok) {
        Slot b = proto;
        b.geo = blend;
        b.origLen = blend.length();
        const Dynamics& a1 = T.nominal;
        const Dynamics& a2 = m.dyn;
        switch (m.buffer) {
          case BufferMode::BlendingLow:
            b.nominal = {std::min(a1.vel, a2.vel), std::min(a1.acc, a2.acc), std::min(a1.dec, a2.dec),
                         jerkMin(a1.jerk, a2.jerk)};
            break;
          case BufferMode::BlendingPrevious: b.nominal = a1; break;
          case BufferMode::BlendingHigh:
            b.nominal = {std::max(a1.vel, a2.vel), std::max(a1.acc, a2.acc), std::max(a1.dec, a2.dec),
                         jerkMax(a1.jerk, a2.jerk)};
            break;
          default: b.nominal = a2; break;
        }
        if (computeCaps(b)) {
          T.geo.trim(0, T.geo.length() - d);
          computeCaps(T);
          scratchSegs_[0].trim(d, S.length());
          sFirst.geo = scratchSegs_[0];
          computeCaps(sFirst);
          T.juncCap = std::min(T.vcap, b.vcap);
          b.juncCap = std::min(b.vcap, sFirst.vcap);
          b.first = !startedNow;
          b.last = false;
          at(count_++) = b;
          blendUsed = true;
          proto.first = false;
        }
      }
      if (!blendUsed) {
        T.juncCap = 0;
        r.blendDropped = true;
      }
    } else {
      T.juncCap = 0;
      if (blending) r.blendDropped = true;
    }
  }
  pushSlots(0);
  if (blendUsed) at(oldCount + 1).first = false;   // the blend started the move
  if (aborting && keep > 0) {
    // first real slot of the aborting move: already started (in this call)
    at(keep).first = false;
  }
  backwardPass(std::max(0, tailIdx));
  if (startedNow) pushEvent(id, EventKind::Started, 0);

  if (aborting && !stop.atRest) return r;   // the stop ramp / running plan ends at the stop point

  if (count_ == 0) return r;
  if (!planned_) {
    if (!held_) {
      sHead_ = (oldCount == 0) ? 0.0 : sHead_;
      replan();
    }
    return r;
  }
  if (holding_) return r;   // a feed-hold ramp runs; the plan resumes later
  // the running plan: replan when it covers the old tail or its end velocity changed
  const bool covers = tailIdx >= 0 && tailIdx < planSlots_;
  const bool endChanged = planSlots_ > 0 && planSlots_ - 1 < oldCount && at(planSlots_ - 1).vEndMax != savedVEnd_[planSlots_ - 1];
  if (covers || endChanged) {
    if (!replan()) {
      if (blendUsed) {
        // too late for this blend: restore the tail, stop exactly at the corner
        count_ = oldCount;
        at(tailIdx) = savedTail;
        for (int i = 0; i < count_; ++i) at(i).vEndMax = savedVEnd_[i];
        // rebuild the new move's slots untrimmed
        int n2 = 0;
        buildGeometry(m, start, inTanPtr, n2);
        at(tailIdx).juncCap = 0;
        pushSlots(0);
        backwardPass(tailIdx);
        r.blendDropped = true;
      }
      // else: the old plan stays valid (it ends where it did, within the limits)
    }
  }
  return r;
}

void Planner::installStopRamp(const StopInfo& st, int slots) {
  Slot& last = at(slots - 1);
  prof_ = st.prof;
  tau_ = 0;
  planned_ = true;
  planSlots_ = slots;
  double ps = -st.s0;   // plan coordinates: p = 0 at the current point
  for (int i = 0; i < slots; ++i) {
    Slot& x = at(i);
    x.planStart = ps;
    x.planEnd = x.planStart + x.geo.length();
    ps = x.planEnd;
  }
  (void)last;
}

uint32_t Planner::halt(double dec, double jerk) {
  const uint32_t id = nextId_++;
  if (!bounds::rate(dec)) dec = 0;
  if (!bounds::jerk(jerk)) jerk = 0;
  StopInfo st;
  computeStop(dec, jerk, st);
  uint32_t lastOwner = 0;
  for (int i = 0; i < count_; ++i) {
    const Slot& x = at(i);
    if (!x.silent && x.owner != lastOwner) pushEvent(x.owner, EventKind::Aborted, 0);
    lastOwner = x.owner;
  }
  pushEvent(id, EventKind::Started, 0);
  held_ = holding_ = false;
  if (st.atRest) {
    count_ = 0;
    planned_ = false;
    holdPos_ = st.point;
    pushEvent(id, EventKind::Done, 0);
    return id;
  }
  const int keep = st.slot + 1;
  count_ = keep;
  Slot& last = at(keep - 1);
  if (st.local < last.geo.length() && st.local > 0) last.geo.trim(0, st.local);
  if (st.ramp) {
    installStopRamp(st, keep);
    at(keep - 1).planEnd = prof_.end().p;
  }
  for (int i = 0; i < keep; ++i) {
    Slot& x = at(i);
    x.owner = id;
    x.silent = i != keep - 1;
    x.first = false;
    x.last = i == keep - 1;
  }
  last.juncCap = 0;
  last.vEndMax = 0;
  return id;
}

PathStatus Planner::interrupt(double dec, double jerk) {
  if (count_ == 0) return PathStatus::Ok;
  if (!bounds::rate(dec)) dec = 0;
  if (!bounds::jerk(jerk)) jerk = 0;
  StopInfo st;
  computeStop(dec, jerk, st);
  held_ = true;
  if (st.atRest) {
    if (planned_) {   // standing at the start of a plan: hold here
      const Kinematic k = prof_.at(tau_);
      sHead_ = k.p - at(0).planStart;
      planned_ = false;
    }
    holding_ = false;
    return PathStatus::Ok;
  }
  if (st.ramp) {
    // plan coordinates for the slots the ramp crosses (the rest keeps its geometry)
    installStopRamp(st, st.slot + 1);
    at(st.slot).planEnd = at(st.slot).planStart + at(st.slot).geo.length();
  }
  holding_ = true;
  return PathStatus::Ok;
}

PathStatus Planner::resume() {
  if (!held_) return PathStatus::NotHeld;
  held_ = false;
  if (holding_) {
    // still braking: continue the path from the current state
    holding_ = false;
    replan();
    return PathStatus::Ok;
  }
  if (count_ > 0 && !planned_) replan();
  return PathStatus::Ok;
}

void Planner::freeze() {
  if (count_ == 0) return;
  if (planned_) sHead_ = std::clamp(prof_.at(tau_).p - at(0).planStart, 0.0, at(0).geo.length());
  planned_ = false;
  held_ = true;
  holding_ = false;
  sample_.v = sample_.a = 0;
  sample_.vel = sample_.acc = Vec{};
  sample_.moving = false;
  sample_.held = true;
}

PathStatus Planner::setOverride(double f) {
  if (!std::isfinite(f) || f < 0 || f > 1e3) return PathStatus::InvalidOverride;
  override_ = f;
  return PathStatus::Ok;
}

void Planner::clear() {
  uint32_t lastOwner = 0;
  for (int i = 0; i < count_; ++i) {
    const Slot& x = at(i);
    if (!x.silent && x.owner != lastOwner) pushEvent(x.owner, EventKind::Aborted, 0);
    lastOwner = x.owner;
  }
  if (count_ > 0) holdPos_ = sample_.pos;
  count_ = 0;
  planned_ = false;
  held_ = holding_ = false;
  sample_.v = sample_.a = 0;
  sample_.vel = sample_.acc = Vec{};
  sample_.moving = false;
  sample_.active = 0;
}

// ---------------------------------------------------------------- the cycle

const Sample& Planner::advance(double dt) {
  double R = std::isfinite(dt) && dt > 0 ? dt : 0;   // real time left in this step
  double tReal = 0;                                  // real time consumed
  const double f = override_;
  for (int guard = 0; planned_ && f > 0 && guard < 4 * cap_ + 16; ++guard) {
    const double dur = prof_.duration();
    const double tEnd = std::min(dur, tau_ + R * f);
    const double pEnd = prof_.at(tEnd).p;
    // segment ends passed in this piece of the step
    while (count_ > 0 && planSlots_ > 0 && pEnd >= at(0).planEnd) {
      const double b = at(0).planEnd;
      double lo = tau_, hi = tEnd;
      if (tEnd >= dur && b >= prof_.end().p) {
        lo = hi = dur;
      } else {
        for (int it = 0; it < 60 && hi - lo > 1e-15 * std::max(1.0, hi); ++it) {
          const double mid = 0.5 * (lo + hi);
          if (prof_.at(mid).p >= b) hi = mid;
          else lo = mid;
        }
      }
      const double te = tReal + (hi - tau_) / f;
      const Slot& x = at(0);
      if (x.last && !x.silent) pushEvent(x.owner, EventKind::Done, te);
      if (count_ == 1) holdPos_ = x.geo.endPoint();
      head_ = (head_ + 1) % cap_;
      --count_;
      --planSlots_;
      if (count_ > 0 && at(0).first) pushEvent(at(0).owner, EventKind::Started, te);
    }
    tReal += (tEnd - tau_) / f;
    R = std::max(0.0, dt - tReal);
    tau_ = tEnd;
    if (count_ == 0) {   // every segment passed (the plan's end within rounding): idle
      planned_ = false;
      break;
    }
    if (tau_ < dur) break;
    // the plan is complete
    const Kinematic e = prof_.end();
    planned_ = false;
    if (count_ == 0) break;
    sHead_ = planSlots_ > 0 ? std::clamp(e.p - at(0).planStart, 0.0, at(0).geo.length()) : 0.0;
    if (held_ && e.v <= 0) {
      holding_ = false;
      break;
    }
    // next run from the exact end state (at a segment end: a = 0)
    Kinematic st{sHead_, e.v, 0};
    int runEnd = 0;
    Profile p;
    if (!planRun(st, runEnd, p)) {
      // cannot happen within the model (the look-ahead guarantees a stop); keep going safely
      ++planFailures_;
      planPosition({0, std::max(0.0, e.v), 0}, at(0).geo.length() - sHead_, 0,
                   {std::max(e.v, at(0).vcap), at(0).acc, at(0).dec, at(0).jerk}, p);
      at(0).planStart = -sHead_;
      at(0).planEnd = p.end().p;
      runEnd = 0;
    }
    prof_ = p;
    tau_ = 0;
    planSlots_ = runEnd + 1;
    planned_ = true;
    if (!(R > 0)) break;
  }
  // the sample
  Sample& o = sample_;
  o.held = held_ && !planned_;
  if (count_ == 0) {
    o.pos = holdPos_;
    o.vel = o.acc = Vec{};
    o.v = o.a = 0;
    o.active = 0;
    o.moving = false;
    return o;
  }
  double s, v = 0, a = 0;
  if (planned_) {
    const Kinematic k = prof_.at(tau_);
    s = k.p - at(0).planStart;
    v = k.v * f;
    a = k.a * f * f;
  } else {
    s = sHead_;
  }
  const Slot& h = at(0);
  PathPoint pp;
  h.geo.eval(s, pp);
  o.pos = pp.pos;
  for (int i = 0; i < kMaxCoords; ++i) {
    o.vel[i] = pp.d1[i] * v;
    o.acc[i] = pp.d1[i] * a + pp.d2[i] * v * v;
  }
  o.v = v;
  o.a = a;
  o.active = h.owner;
  o.moving = planned_;
  return o;
}

}  // namespace stc::motion::path
