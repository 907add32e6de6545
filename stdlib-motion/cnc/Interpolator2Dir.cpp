// The bidirectional CNC interpolator (Interpolator2Dir.h; docs/cnc.md, "SMC_Interpolator2Dir").
#include "stdlib-motion/cnc/Interpolator2Dir.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/IpoCommon.h"
#include "stdlib-motion/cnc/PathSegment.h"
#include "stdlib-motion/core/Trajectory.h"

namespace stc::cnc {

namespace {

constexpr double kMaxOverride = 2.0;
constexpr int16_t kBufferTooSmall = 1050;      // SMC_INT2DIR_BUFFER_TOO_SMALL
constexpr int16_t kPathFitsNotInQueue = 1051;  // SMC_INT2DIR_PATH_FITS_NOT_IN_QUEUE

}  // namespace

struct Interpolator2Dir::Item {
  Element e;
  double wayStart = 0, wayEnd = 0;
  bool motion = false;     // a motion element (its segment is in segs_ when length > 0)
  bool hasSeg = false;
  bool stop = false;       // M (not pre-acknowledged), dwell, G92, G75: v = 0 there, served once forwards
  bool served = false;
  double curveCap = 1e300;   // sqrt(E / max curvature): the path planner's cap on curves (not scaled by the override)
  SwitchTrack track;
};

Interpolator2Dir::Interpolator2Dir(const Ipo2DirSettings& settings, int16_t& error) : cfg_(settings) {
  error = checkIpoSettings(cfg_.ipo);
  if (error == kIpoOk && (cfg_.history < 0 || cfg_.history > kMaxHistory ||
                          (cfg_.startAtEnd && (cfg_.pathCapacity < 1 || cfg_.pathCapacity > kMaxPath))))
    error = kBufferTooSmall;
  if (error != kIpoOk) {
    error_ = error;
    return;
  }
  capacity_ = cfg_.startAtEnd ? cfg_.pathCapacity : cfg_.history + 1 + kLookAhead;
  items_ = std::make_unique<Item[]>(capacity_);
  segs_ = std::make_unique<path::Segment[]>(capacity_);
  cons_ = std::make_unique<Constraint[]>(capacity_ + 2);
  started_ = !cfg_.startAtEnd;
  out_.status = IpoStatus::Init;
}

Interpolator2Dir::~Interpolator2Dir() = default;

Interpolator2Dir::Item& Interpolator2Dir::at(int i) { return items_[(head_ + i) % capacity_]; }
const Interpolator2Dir::Item& Interpolator2Dir::at(int i) const { return items_[(head_ + i) % capacity_]; }

bool Interpolator2Dir::wantsMore() const {
  if (error_ != kIpoOk || !items_ || endOfList_ || count_ >= capacity_) return false;
  if (fedThisCycle_ >= kFeedsPerCycle) return false;   // spread segment building over cycles
  return cfg_.startAtEnd || count_ - ctl_ - 1 < kLookAhead;
}

int16_t Interpolator2Dir::feed(const Element& e) {
  if (!wantsMore()) return error_;
  if (const int16_t bad = checkIpoElement(e); bad != kIpoOk) return fail(bad), error_;
  const int slot = (head_ + count_) % capacity_;
  Item& it = items_[slot];
  it = Item{};
  it.e = e;
  it.motion = isMotion(e.type);
  it.stop = isIpoStop(e);
  it.wayStart = it.wayEnd = wayFed_;
  if (it.motion) {
    const bool zero = e.start == e.end;
    if (!zero) {
      if (!buildPathSegment(e, segs_[slot])) return fail(kIpoPathExceeded), error_;
      it.hasSeg = true;
      it.wayEnd = wayFed_ + segs_[slot].length();
      const double kappa = segs_[slot].maxCurvature();
      if (kappa > 0) it.curveCap = std::sqrt(e.acc / kappa);
    }
    it.track.place(e, it.wayStart, it.wayEnd - it.wayStart);
  }
  wayFed_ = it.wayEnd;
  ++fedThisCycle_;
  if (!everFed_) {   // the set point starts at the first element's start
    everFed_ = true;
    out_.pos = e.start;
  }
  ++count_;
  return error_;
}

void Interpolator2Dir::fail(int16_t error) {
  if (error_ == kIpoOk) error_ = error;   // the path then stops along itself (move() brakes)
}

// The motion item whose F / E / E- govern travel in direction `dir` from w, or -1.
int Interpolator2Dir::governing(int dir) const {
  const double tol = 1e-12 * std::max(1.0, std::fabs(w_));
  if (dir > 0) {
    for (int i = ctl_; i < count_; ++i) {
      const Item& it = at(i);
      if (it.stop && !it.served && i > ctl_) return -1;
      if (it.motion && it.wayEnd > w_ + tol) return i;
    }
  } else {
    for (int i = ctl_; i >= 0; --i) {
      const Item& it = at(i);
      if (it.motion && it.wayStart < w_ - tol) return i;
    }
  }
  return -1;
}

// The velocity allowed at the end of motion item i with override ov: 0 where the path stops
// (a stop item follows, nothing follows yet, single steps), else the smaller of dVelEnd and
// the next element's F (x ov) and the curvature caps of both.  *last: nothing but
// pre-acknowledged M functions follows.
double Interpolator2Dir::junctionAfter(int i, bool singleStep, double ov, bool* last) const {
  if (last) *last = false;
  for (int j = i + 1; j < count_; ++j) {
    if (at(j).motion) {
      if (singleStep) return 0;
      return std::min({std::min(at(i).e.velEnd, at(j).e.vel) * ov, at(i).curveCap, at(j).curveCap});
    }
    if (at(j).stop) return 0;
  }
  if (last) *last = true;
  return 0;
}

// The motion item before item i, or -1.
int Interpolator2Dir::motionBefore(int i) const {
  for (int j = i - 1; j >= 0; --j)
    if (at(j).motion) return j;
  return -1;
}

// Fills cons_ with the points ahead (direction dir, up to `horizon`) where |v| is capped,
// nearest first; ends at the first point where v must be 0.  Returns the count, or -1 when
// the set point stands at a wall (an unserved stop item, the end of what is known, the
// oldest element kept) and cannot move in that direction.
int Interpolator2Dir::collectConstraints(int dir, double horizon, double ov, bool singleStep) {
  const double tol = 1e-12 * std::max(1.0, std::fabs(w_));
  int n = 0;
  auto push = [&](double dist, double vel, bool wall) -> bool {   // FALSE: stop collecting
    if (dist <= tol) {
      if (wall) n = -1;
      return !wall && dist <= horizon;
    }
    cons_[n++] = {dist, vel};
    return vel > 0 && dist <= horizon;
  };
  if (dir > 0) {
    for (int i = ctl_; i < count_; ++i) {
      const Item& it = at(i);
      if (it.stop) {
        if (!it.served && !push(it.wayStart - w_, 0, true)) return n;
        continue;
      }
      if (!it.motion) continue;
      bool wall = false;   // the last element known
      const double cap = junctionAfter(i, singleStep, ov, &wall);
      if (it.wayEnd < w_ - tol) continue;
      if (!push(it.wayEnd - w_, cap, wall)) return n;
    }
    return n;
  }
  for (int i = ctl_; i >= 0; --i) {
    const Item& it = at(i);
    if (!it.motion) {
      if (it.stop && it.wayStart < w_ - tol && !push(w_ - it.wayStart, 0, false)) return n;
      continue;
    }
    const int p = motionBefore(i);
    const double cap = p >= 0 ? junctionAfter(p, singleStep, ov, nullptr) : 0;
    const bool wall = i == 0;
    if (it.wayStart > w_ + tol) continue;
    if (!push(w_ - it.wayStart, cap, wall)) return n;
  }
  return n;
}

// TRUE while the set point stands where the path stops anyway (bWaitAtNextStop holds there):
// a stop item, or a junction of the element in control (its start or its end) with velocity 0.
bool Interpolator2Dir::atStopPoint(bool singleStep) const {
  if (v_ != 0 || count_ == 0) return false;
  const Item& it = at(ctl_);
  if (it.stop) return true;
  if (!it.motion) return false;
  const double tol = 1e-12 * std::max(1.0, std::fabs(w_));
  if (std::fabs(w_ - it.wayEnd) <= tol && junctionAfter(ctl_, singleStep, 1, nullptr) == 0) return true;
  if (std::fabs(w_ - it.wayStart) <= tol) {
    const int p = motionBefore(ctl_);
    return p < 0 || junctionAfter(p, singleStep, 1, nullptr) == 0;
  }
  return false;
}

void Interpolator2Dir::move(const IpoControls& c) {
  using motion::Kinematic;
  using motion::Limits;
  using motion::Profile;
  const double dt = cfg_.ipo.cycle;
  const double ovMag = std::fabs(c.override);
  const int dirCmd = c.override > 0 ? 1 : c.override < 0 ? -1 : 0;
  if (c.emergencyStop || (error_ != kIpoOk && v_ == 0)) {   // freeze at once (continue from rest when
    v_ = a_ = 0;                                            // released); after an error stop: stay
    return;
  }
  const int travel = v_ > 0 ? 1 : v_ < 0 ? -1 : dirCmd;
  if (travel == 0) {
    a_ = 0;
    return;
  }
  const bool holding = v_ == 0 && c.waitAtNextStop && leftStart_ && atStopPoint(c.singleStep);
  const int g = governing(travel);
  if (g < 0 || holding) {   // nothing to run in that direction
    v_ = a_ = 0;
    return;
  }
  const Element& ge = at(g).e;
  const bool trapezoid = cfg_.ipo.mode == VelMode::Trapezoid;
  Limits lim;
  lim.acc = ge.acc;
  lim.dec = ge.dec;
  lim.jerk = trapezoid ? 0 : cfg_.ipo.jerk;
  const bool quick = c.quickStop && std::isfinite(c.quickDecel) && c.quickDecel > 0 && c.quickDecel <= 1e12;
  if (quick) lim.dec = c.quickDecel;
  const bool wantStop = dirCmd != travel || c.slowStop || quick || error_ != kIpoOk;
  const double cap = std::min(ge.vel * ovMag, at(g).curveCap);
  lim.vel = std::max(cap, 1e-12);
  const double target = wantStop ? 0.0 : cap;

  Kinematic k{0, std::fabs(v_), trapezoid ? 0.0 : travel * a_};
  // how far ahead a constraint can matter: the stop distance from the highest speed this cycle
  const double vh = std::max(k.v + lim.acc * dt, cap);
  Profile p;
  double horizon = 0;
  if (motion::planVelocity(Kinematic{0, vh, 0}, 0, lim, p) == motion::PlanStatus::Ok) horizon = p.end().p;
  horizon += 2 * vh * dt + 1e-9;
  const int n = collectConstraints(travel, horizon, ovMag, c.singleStep);
  if (n < 0) {   // at a wall
    v_ = a_ = 0;
    return;
  }

  Kinematic next;
  if (motion::planVelocity(k, target, lim, p) != motion::PlanStatus::Ok) {
    fail(kIpoPathExceeded);
    v_ = a_ = 0;
    return;
  }
  next = p.at(dt);
  auto feasible = [&](const Kinematic& s, const Constraint& con) {
    const double tol = 1e-9 * std::max(1.0, con.vel);
    const double rest = con.dist - s.p;
    if (rest < 0) return s.v <= con.vel + tol;   // passed during the cycle
    if (s.v <= con.vel + tol && (trapezoid || s.a <= 1e-9)) return true;
    Profile b;
    if (motion::planVelocity(Kinematic{0, s.v, trapezoid ? 0.0 : s.a}, std::min(con.vel, lim.vel), lim, b) != motion::PlanStatus::Ok)
      return false;
    return b.end().p <= rest + 1e-12 * std::max(1.0, con.dist);
  };
  bool ok = true;
  for (int i = 0; i < n && ok; ++i) ok = feasible(next, cons_[i]);
  if (!ok) {
    bool have = false;
    Kinematic best;
    for (int i = 0; i < n; ++i) {
      if (feasible(next, cons_[i])) continue;
      Profile q;
      Kinematic cand;
      const double vEnd = std::min(cons_[i].vel, lim.vel);
      bool reverses = motion::planPosition(k, cons_[i].dist, vEnd, lim, q) != motion::PlanStatus::Ok;
      for (int s = 0; s < q.segmentCount() && !reverses; ++s) reverses = q.segment(s).v < -1e-9;
      if (reverses) {   // already too fast for it (a cap that dropped): brake as hard as allowed
        if (motion::planVelocity(k, vEnd, lim, q) != motion::PlanStatus::Ok) continue;
      }
      cand = q.at(dt);
      if (cons_[i].vel == 0 && cand.p > cons_[i].dist) cand = Kinematic{cons_[i].dist, 0, 0};
      if (!have || cand.v < best.v) best = cand, have = true;
    }
    if (have) next = best;
  }
  // never past a point where v must be 0
  for (int i = 0; i < n; ++i)
    if (cons_[i].vel == 0 && next.p >= cons_[i].dist) {
      next = Kinematic{cons_[i].dist, 0, 0};
      break;
    }
  // the last cycle of a stop (rounding leaves ~1e-14 of speed): at rest
  if (next.v <= 1e-9 * std::max(1.0, lim.vel) && (trapezoid || std::fabs(next.a) <= 1e-6 * std::max(lim.acc, lim.dec)))
    next.v = next.a = 0;
  const double from = w_;
  w_ += travel * next.p;
  v_ = travel * next.v;
  a_ = travel * next.a;
  if (next.p > 0) leftStart_ = true;
  fireSwitches(from, w_);
}

// Moves ctl_ to the item the set point is in: forwards onto the next item at a boundary,
// onto an unserved stop item when it is reached; backwards onto the previous item.
void Interpolator2Dir::updateControl() {
  const double tol = 1e-12 * std::max(1.0, std::fabs(w_));
  const bool backwards = v_ < 0 || (v_ == 0 && direction_ < 0);
  if (!backwards) {
    while (ctl_ + 1 < count_) {
      const Item& cur = at(ctl_);
      if (cur.stop && !cur.served) break;
      if (cur.motion && w_ < cur.wayEnd - tol) break;
      const Item& nx = at(ctl_ + 1);
      if (nx.wayStart > w_ + tol) break;
      ++ctl_;
    }
  } else {
    while (ctl_ > 0) {
      const Item& cur = at(ctl_);
      if (cur.motion && w_ > cur.wayStart + tol) break;
      --ctl_;
    }
  }
}

void Interpolator2Dir::serveStopItem(const IpoControls& c) {
  out_.m = 0;
  out_.mK = out_.mL = 0;
  if (count_ == 0 || v_ != 0) return;
  Item& it = at(ctl_);
  const double tol = 1e-12 * std::max(1.0, std::fabs(w_));
  if (!it.stop || it.served || std::fabs(w_ - it.wayStart) > tol) {
    dwellStarted_ = false;
    return;
  }
  switch (it.e.type) {
    case MoveType::MCommand:
      if (!waitOnM(out_, it.e, c.acknM)) return;
      break;
    case MoveType::Dwell:
      if (!dwellStarted_) {
        dwellStarted_ = true;
        dwellElapsed_ = 0;
      } else {
        dwellElapsed_ += cfg_.ipo.cycle;
      }
      if (dwellElapsed_ < it.e.dwell - 1e-9 * cfg_.ipo.cycle) return;
      dwellStarted_ = false;
      break;
    case MoveType::InitPos:   // the next element starts at the new position: nothing before it is kept
      servedG92_ = std::max(servedG92_, ctl_);
      break;
    default: break;   // G75: reached
  }
  it.served = true;
  if (ctl_ + 1 < count_) ++ctl_;
}

void Interpolator2Dir::fireSwitches(double from, double to) {
  // items before the one in control lie behind `from` with every switch fired (backwards the
  // scan starts one item ahead: a point within the switch tolerance of the next element)
  moveSwitches(to > from ? ctl_ : ctl_ + 1, count_, [this](int i) -> Item& { return at(i); }, from, to, out_);
}

// Drops items that are no longer needed for going back: more than `history` behind the
// one in control, or before a G92 that has been served (the coordinates changed there).
void Interpolator2Dir::release() {
  if (cfg_.startAtEnd) return;
  const int barrier = servedG92_;
  servedG92_ = -1;
  int drop = std::max(ctl_ - cfg_.history, barrier + 1);
  drop = std::min(drop, ctl_);   // never the item in control
  if (barrier >= 0 && barrier == ctl_) drop = ctl_;
  for (int i = 0; i < drop; ++i) {
    head_ = (head_ + 1) % capacity_;
    --count_;
    --ctl_;
    ++released_;
  }
}

void Interpolator2Dir::startAtEndIfReady() {
  if (started_ || !endOfList_ || error_ != kIpoOk || count_ == 0) return;
  started_ = true;
  ctl_ = count_ - 1;
  w_ = wayFed_;
  for (int i = 0; i < count_; ++i) {
    Item& it = at(i);
    it.served = true;   // the set point starts behind every stop item
    it.track.forwardTo(it.wayEnd, 0, out_);
  }
  leftStart_ = true;
}

void Interpolator2Dir::publish(double prevAcc) {
  const double tol = 1e-12 * std::max(1.0, std::fabs(w_));
  if (count_ > 0) {
    const int slot = (head_ + ctl_) % capacity_;
    const Item& it = items_[slot];
    if (it.motion) {
      if (it.hasSeg) {
        path::PathPoint pp;
        segs_[slot].eval(std::clamp(w_ - it.wayStart, 0.0, it.wayEnd - it.wayStart), pp);
        for (int i = 0; i < kPathDims; ++i) out_.pos[i] = pp.pos[i];
        if (std::fabs(w_ - it.wayEnd) <= tol) out_.pos = it.e.end;   // exact end points
        if (v_ != 0) {
          const double s = v_ > 0 ? 1 : -1;
          const double nrm = std::sqrt(pp.d1[0] * pp.d1[0] + pp.d1[1] * pp.d1[1] + pp.d1[2] * pp.d1[2]);
          if (nrm > 0)
            for (int i = 0; i < 3; ++i) out_.tangent[i] = s * pp.d1[i] / nrm;
        }
      } else {
        out_.pos = it.e.end;
      }
    } else {
      out_.pos = it.served ? it.e.end : it.e.start;
    }
    out_.sourceLine = std::max(0, it.e.line - 1);
    out_.objNo = it.e.objNo;
  }
  out_.vel = std::fabs(v_);
  out_.acc = v_ != 0 ? (v_ > 0 ? a_ : -a_) : 0;
  out_.wayPos = w_;
  direction_ = v_ > 0 ? 1 : v_ < 0 ? -1 : 0;

  bool atEnd = false;
  if (count_ > 0 && ctl_ == count_ - 1) {
    const Item& last = at(ctl_);
    atEnd = last.stop ? last.served : w_ >= last.wayEnd - tol;
  }
  out_.finished = started_ && endOfList_ && atEnd && v_ == 0 && error_ == kIpoOk;
  out_.working = started_ && everFed_ && !out_.finished && error_ == kIpoOk;
  if (!everFed_ || !started_) {
    out_.status = IpoStatus::Init;
    return;
  }
  if (out_.finished) {
    out_.status = IpoStatus::Finished;
    return;
  }
  if (v_ == 0) {
    out_.status = IpoStatus::Wait;
    return;
  }
  const double acc = out_.acc;   // along the direction of travel: > 0 speeds up
  const double tolA = 1e-9 * std::max(1.0, std::fabs(acc));
  if (std::fabs(acc) <= 1e-9) {
    out_.status = IpoStatus::Constant;
    return;
  }
  const bool jerkMode = cfg_.ipo.mode != VelMode::Trapezoid;
  const double growth = std::fabs(acc) - std::fabs(prevAcc);
  if (acc > 0) {
    if (!jerkMode || prevAcc < 0) out_.status = IpoStatus::Accel;
    else out_.status = growth > tolA ? IpoStatus::IncreasingAccel : growth < -tolA ? IpoStatus::DecreasingAccel : IpoStatus::Accel;
  } else {
    if (!jerkMode || prevAcc > 0) out_.status = IpoStatus::Decel;
    else out_.status = growth > tolA ? IpoStatus::IncreasingDecel : growth < -tolA ? IpoStatus::DecreasingDecel : IpoStatus::Decel;
  }
}

const IpoOutput& Interpolator2Dir::step(const IpoControls& c) {
  if (!items_) return out_;
  const double prevAcc = out_.acc;
  IpoControls cc = c;
  if (!(std::isfinite(c.override) && std::fabs(c.override) <= kMaxOverride)) {
    fail(kIpoInvalidParameter);
    cc.override = v_ >= 0 ? 1e-300 : -1e-300;   // keep the direction: the error stop brakes along the path
  }
  if (c.quickStop && !(std::isfinite(c.quickDecel) && c.quickDecel > 0 && c.quickDecel <= 1e12)) fail(kIpoInvalidParameter);
  if (!started_) {
    if (count_ == capacity_ && !endOfList_) fail(kPathFitsNotInQueue);   // the path does not fit
    startAtEndIfReady();
  }
  if (started_ && count_ > 0) {
    serveStopItem(cc);
    move(cc);
    updateControl();
    serveStopItem(cc);   // reached during this cycle: an M shows at once (the dwell counts from the next cycle)
    release();
  }
  publish(prevAcc);
  fedThisCycle_ = 0;
  // the queue running dry forwards, or the oldest element kept reached backwards
  const bool standing = started_ && everFed_ && v_ == 0 && error_ == kIpoOk && !out_.finished;
  bool starved = false;
  if (standing && count_ > 0) {
    const double tol = 1e-12 * std::max(1.0, std::fabs(w_));
    if (cc.override > 0 && !endOfList_ && ctl_ == count_ - 1) starved = at(ctl_).motion ? w_ >= at(ctl_).wayEnd - tol : at(ctl_).served;
    if (cc.override < 0 && ctl_ == 0) starved = !at(0).motion || w_ <= at(0).wayStart + tol;
  }
  warning_ = starved ? kIpoDataUnderrun : kIpoOk;
  return out_;
}

}  // namespace stc::cnc
