// The CNC path interpolator (Interpolator.h; docs/cnc.md, "SMC_Interpolator").
#include "stdlib-motion/cnc/Interpolator.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/IpoCommon.h"
#include "stdlib-motion/cnc/PathSegment.h"
#include "stdlib-motion/path/Planner.h"

namespace stc::cnc {

namespace {

constexpr int kDims = kAxisCount;   // the planner runs all 11 axes: X Y Z A B C P Q U V W
static_assert(kDims <= path::kMaxCoords);
constexpr int kPlannerCapacity = 2 * Interpolator::kMaxInFlight + 4;
constexpr double kMaxOverride = 2.0;
// Elements handed to the planner per cycle: building a segment (arc-length tables of splines
// and ellipses) and the look-ahead pass cost up to ~50 us each, so the start of a path spreads
// them over cycles instead of one long cycle; 4 per cycle is far above any feed's consumption.
constexpr int kAppendsPerCycle = 4;
// Set by SMC_PreAcknowledgeM on an M element: the path passes it without stopping.
constexpr uint16_t kMarkPreAcknowledged = MarkMPreAcknowledged;

}  // namespace

struct Interpolator::Item {
  Element e;
  uint32_t moveId = 0;     // planner move (motion items handed over)
  double wayStart = 0, wayEnd = 0;
  bool done = false;
  SwitchTrack track;                     // H switch points at their way positions
};

Interpolator::Interpolator(const IpoSettings& settings, int16_t& error) : cfg_(settings) {
  error = checkIpoSettings(cfg_);
  if (error != kIpoOk) {
    error_ = error;
    return;
  }
  path::PlannerConfig pc;
  pc.dims = kDims;
  pc.capacity = kPlannerCapacity;
  planner_ = std::make_unique<path::Planner>(pc);
  items_ = std::make_unique<Item[]>(kMaxInFlight);
  scratch_ = std::make_unique<path::Segment>();
  out_.status = IpoStatus::Init;
}

Interpolator::~Interpolator() = default;

Interpolator::Item& Interpolator::at(int i) { return items_[(head_ + i) % kMaxInFlight]; }
const Interpolator::Item& Interpolator::at(int i) const { return items_[(head_ + i) % kMaxInFlight]; }

bool Interpolator::wantsMore() const { return error_ == kIpoOk && planner_ && count_ < kMaxInFlight && !endOfList_; }

int16_t Interpolator::feed(const Element& e) {
  if (!wantsMore()) return error_;
  everFed_ = true;
  if (const int16_t bad = checkIpoElement(e); bad != kIpoOk) return fail(bad), error_;
  Item& it = at(count_++);
  it = Item{};
  it.e = e;
  return kIpoOk;
}

void Interpolator::fail(int16_t error) {
  if (error_ != kIpoOk) return;
  error_ = error;
  // Stop along the path (never a jump): the deceleration of the element in control.
  double dec = 0, jerk = cfg_.mode == VelMode::Trapezoid ? 0 : cfg_.jerk;
  for (int i = 0; i < appended_ && i < count_; ++i)
    if (!at(i).done && isMotion(at(i).e.type)) {
      dec = at(i).e.dec;
      break;
    }
  if (planner_ && !planner_->idle() && hold_ != Hold::Emergency) planner_->interrupt(dec, jerk);
}

void Interpolator::applyHolds(const IpoControls& c) {
  Hold want = c.emergencyStop ? Hold::Emergency : c.quickStop ? Hold::Quick : c.slowStop ? Hold::Slow : Hold::None;
  if (want == Hold::Quick && !(std::isfinite(c.quickDecel) && c.quickDecel > 0 && c.quickDecel <= 1e12)) {
    fail(kIpoInvalidParameter);
    want = Hold::Slow;
  }
  if (want == hold_) return;
  const double jerk = cfg_.mode == VelMode::Trapezoid ? 0 : cfg_.jerk;
  switch (want) {
    case Hold::Emergency: planner_->freeze(); break;
    case Hold::Quick:
      if (hold_ != Hold::Emergency) planner_->interrupt(c.quickDecel, jerk);
      break;
    case Hold::Slow:
      if (hold_ == Hold::None) {
        double dec = 0;
        for (int i = 0; i < count_; ++i)
          if (!at(i).done && isMotion(at(i).e.type)) {
            dec = at(i).e.dec;
            break;
          }
        planner_->interrupt(dec, jerk);
      }
      break;
    case Hold::None:
      if (error_ == kIpoOk) planner_->resume();
      break;
  }
  if (error_ == kIpoOk || want != Hold::None) hold_ = want;
}

// Removes finished items at the head and runs the stop item that has come to the head
// (M function, dwell, G92, G75) once the planner has stopped.
void Interpolator::processFront(const IpoControls& c, bool newCycle) {
  while (count_ > 0) {
    Item& it = at(0);
    if (isMotion(it.e.type)) {
      if (!it.done) return;
    } else if (isIpoStop(it.e)) {
      if (appended_ > 0 || !planner_->idle() || error_ != kIpoOk) return;
      switch (it.e.type) {
        case MoveType::MCommand:
          if (!waitOnM(out_, it.e, c.acknM)) return;
          break;
        case MoveType::Dwell:
          // the cycle the previous element ended in does not count (the dwell is never shorter)
          if (!dwellStarted_) {
            dwellStarted_ = true;
            // reached during this cycle's motion: the rest of the cycle does not count
            dwellElapsed_ = newCycle ? 0 : -cfg_.cycle;
          } else if (newCycle) {
            dwellElapsed_ += cfg_.cycle;
          }
          if (dwellElapsed_ < it.e.dwell - 1e-9 * cfg_.cycle) return;
          dwellStarted_ = false;
          break;
        case MoveType::InitPos:
          planner_->setPosition(toPathVec(it.e.end));
          positioned_ = true;
          break;
        default: break;   // G75 sync: reached
      }
      prevVelEnd_ = 0;
      ++head_;
      head_ %= kMaxInFlight;
      --count_;
      ++finishedCount_;
      continue;
    }
    // a finished motion item or a pre-acknowledged M function
    if (!isMotion(it.e.type) && appended_ == 0) return;   // not handed over yet
    ++head_;
    head_ %= kMaxInFlight;
    --count_;
    --appended_;
    ++finishedCount_;
  }
}

// Hands motion elements to the planner up to the next point where the path stops.
void Interpolator::appendRuns(const IpoControls& c) {
  if (error_ != kIpoOk || hold_ != Hold::None) return;
  for (int budget = kAppendsPerCycle; appended_ < count_;) {
    Item& it = at(appended_);
    if (!isMotion(it.e.type)) {
      if (isIpoStop(it.e)) return;   // processFront runs it when the path has stopped there
      ++appended_;                    // pre-acknowledged M: passed on the fly
      continue;
    }
    const bool idle = planner_->idle();
    const bool continues = !idle && prevVelEnd_ > 0 && !c.singleStep;
    if (!continues) {
      if (!idle) return;                                   // wait until the run has stopped
      if (c.waitAtNextStop && startedOnce_) return;        // hold at a stop point
    }
    if (planner_->queued() + 1 >= planner_->capacity() || budget-- == 0) return;
    if (!positioned_) {
      planner_->setPosition(toPathVec(it.e.start));
      positioned_ = true;
    }
    const int16_t geo = buildPathSegment(it.e, *scratch_) ? kIpoOk : kIpoPathExceeded;
    if (geo != kIpoOk) return fail(geo);
    path::MoveSpec m;
    m.kind = path::MoveKind::Prebuilt;
    m.segment = scratch_.get();
    m.buffer = path::BufferMode::Buffered;
    m.junctionVel = continues ? prevVelEnd_ : 0;
    m.dyn = {it.e.vel, it.e.acc, it.e.dec, cfg_.mode == VelMode::Trapezoid ? 0.0 : cfg_.jerk};
    const path::AppendResult r = planner_->append(m);
    if (r.status != path::PathStatus::Ok)
      return fail(r.status == path::PathStatus::InvalidDynamics ? kIpoVelAccDecZero : kIpoPathExceeded);
    startedOnce_ = true;
    it.moveId = r.id;
    it.wayStart = wayAppended_;
    wayAppended_ += scratch_->length();
    it.wayEnd = wayAppended_;
    it.track.place(it.e, it.wayStart, it.wayEnd - it.wayStart);   // H switch points
    prevVelEnd_ = it.e.velEnd;
    ++appended_;
  }
}

void Interpolator::collectEvents() {
  for (const path::Event& ev : planner_->events())
    if (ev.kind == path::EventKind::Done) lastDone_ = std::max(lastDone_, ev.id);
  planner_->clearEvents();
  for (int i = 0; i < appended_ && i < count_; ++i) {
    Item& it = at(i);
    if (isMotion(it.e.type) && !it.done && it.moveId != 0 && it.moveId <= lastDone_) it.done = true;
  }
}

void Interpolator::fireSwitches(double way) {
  for (int i = 0; i < appended_ && i < count_; ++i) {
    Item& it = at(i);
    if (!isMotion(it.e.type)) continue;
    if (it.wayStart > way + 1e-12 * std::max(1.0, way)) break;
    it.track.forwardTo(way, 1e-9 * std::max(1.0, std::fabs(way)), out_);
  }
}

void Interpolator::updateStatus(double prevAcc) {
  const path::Sample& s = planner_->sample();
  if (!everFed_) {
    out_.status = IpoStatus::Init;
    return;
  }
  if (out_.finished) {
    out_.status = IpoStatus::Finished;
    return;
  }
  if (!s.moving || hold_ == Hold::Emergency) {
    out_.status = IpoStatus::Wait;
    return;
  }
  double accRef = 1;
  for (int i = 0; i < count_; ++i)
    if (!at(i).done && isMotion(at(i).e.type)) {
      accRef = std::max({1.0, at(i).e.acc, at(i).e.dec});
      break;
    }
  const double tol = 1e-9 * accRef;
  const double a = s.a;
  if (std::fabs(a) <= tol) {
    out_.status = s.v > 0 ? IpoStatus::Constant : IpoStatus::Wait;
    return;
  }
  const bool jerkMode = cfg_.mode != VelMode::Trapezoid;
  const double growth = std::fabs(a) - std::fabs(prevAcc);
  if (a > 0) {
    if (!jerkMode || (prevAcc < 0)) out_.status = IpoStatus::Accel;
    else out_.status = growth > tol ? IpoStatus::IncreasingAccel : growth < -tol ? IpoStatus::DecreasingAccel : IpoStatus::Accel;
  } else {
    if (!jerkMode || (prevAcc > 0)) out_.status = IpoStatus::Decel;
    else out_.status = growth > tol ? IpoStatus::IncreasingDecel : growth < -tol ? IpoStatus::DecreasingDecel : IpoStatus::Decel;
  }
}

const IpoOutput& Interpolator::step(const IpoControls& c) {
  if (!planner_) return out_;
  const double prevAcc = out_.acc;

  // override: finite, 0..kMaxOverride; ramped so the velocity changes within the element's acceleration
  if (!(std::isfinite(c.override) && c.override >= 0 && c.override <= kMaxOverride)) fail(kIpoInvalidParameter);
  else if (c.override != override_) {
    const path::Sample& s = planner_->sample();
    double acc = 0;
    for (int i = 0; i < count_; ++i)
      if (!at(i).done && isMotion(at(i).e.type)) {
        acc = std::min(at(i).e.acc, at(i).e.dec);
        break;
      }
    const double vPlan = override_ > 0 ? s.v / override_ : 0;
    const double maxStep = (vPlan > 0 && acc > 0) ? acc * cfg_.cycle / vPlan : 1e300;
    override_ += std::clamp(c.override - override_, -maxStep, maxStep);
    planner_->setOverride(override_);
  }

  applyHolds(c);
  processFront(c, true);
  appendRuns(c);
  const path::Sample& s = planner_->advance(cfg_.cycle);
  collectEvents();
  const double way = wayAppended_ - planner_->remaining();
  fireSwitches(way);
  processFront(c, false);   // finished motion leaves at once (the stop items wait for the next cycle)
  if (positioned_) {
    for (int i = 0; i < kDims; ++i) out_.pos[i] = s.pos[i];
  }
  out_.vel = s.v;
  out_.acc = s.a;
  if (s.v > 0) {
    const double n = std::sqrt(s.vel[0] * s.vel[0] + s.vel[1] * s.vel[1] + s.vel[2] * s.vel[2]);
    if (n > 0)
      for (int i = 0; i < 3; ++i) out_.tangent[i] = s.vel[i] / n;
  }
  out_.wayPos = way;
  for (int i = 0; i < count_; ++i)
    if (!at(i).done) {
      out_.sourceLine = std::max(0, at(i).e.line - 1);
      out_.objNo = at(i).e.objNo;
      break;
    }
  out_.finished = endOfList_ && count_ == 0 && planner_->idle() && error_ == kIpoOk;
  const bool underrun = everFed_ && !endOfList_ && count_ == 0 && planner_->idle() && error_ == kIpoOk;
  warning_ = underrun ? kIpoDataUnderrun : kIpoOk;
  out_.working = everFed_ && !out_.finished && error_ == kIpoOk;
  updateStatus(prevAcc);
  return out_;
}

}  // namespace stc::cnc
