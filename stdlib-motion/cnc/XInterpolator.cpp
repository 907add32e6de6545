// The position-based interpolator (XInterpolator.h; docs/cnc.md, "SMC_XInterpolator").
#include "stdlib-motion/cnc/XInterpolator.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/IpoCommon.h"
#include "stdlib-motion/cnc/PathSegment.h"

namespace stc::cnc {

namespace {

constexpr int kMonotonicSamples = 64;   // dX/ds checked at this many points per element

}  // namespace

struct XInterpolator::Item {
  Element e;
  bool hasSeg = false;       // a motion element of non-zero length
  double xs = 0, xe = 0;     // dir x X at the start / end
  double wayStart = 0, wayEnd = 0;
  SwitchTrack track;
};

XInterpolator::XInterpolator(int dir) : dir_(dir) {
  if (dir != 1 && dir != -1) {
    error_ = kXIpoInvalidDirection;
    return;
  }
  items_ = std::make_unique<Item[]>(kWindow);
  segs_ = std::make_unique<path::Segment[]>(kWindow);
  out_.status = IpoStatus::Init;
}

XInterpolator::~XInterpolator() = default;

XInterpolator::Item& XInterpolator::at(int i) { return items_[(head_ + i) % kWindow]; }
const XInterpolator::Item& XInterpolator::at(int i) const { return items_[(head_ + i) % kWindow]; }

bool XInterpolator::wantsMore() const { return error_ == kIpoOk && items_ && count_ < kWindow && !endOfList_; }

int16_t XInterpolator::feed(const Element& e) {
  if (!wantsMore()) return error_;
  if (!finitePos(e.start) || !finitePos(e.end)) return error_ = kIpoPathExceeded;
  const int slot = (head_ + count_) % kWindow;
  Item& it = items_[slot];
  it = Item{};
  it.e = e;
  it.xs = dir_ * e.start[AxX];
  it.xe = dir_ * e.end[AxX];
  it.wayStart = it.wayEnd = wayFed_;
  if (isMotion(e.type) && e.start != e.end) {
    path::Segment& seg = segs_[slot];
    if (!buildPathSegment(e, seg)) return error_ = kIpoPathExceeded;
    it.hasSeg = true;
    it.wayEnd = wayFed_ + seg.length();
    // unique in X: X never runs against the direction along the element
    const double scale = std::max(1.0, std::fabs(it.xe - it.xs));
    if (it.xe < it.xs - 1e-9 * scale) return error_ = kXIpoNoIntersection;
    path::PathPoint pp;
    for (int k = 0; k <= kMonotonicSamples; ++k) {
      seg.eval(seg.length() * k / kMonotonicSamples, pp);
      if (dir_ * pp.d1[AxX] < -1e-9) return error_ = kXIpoNoIntersection;
    }
    it.track.place(e, it.wayStart, it.wayEnd - it.wayStart);
  }
  wayFed_ = it.wayEnd;
  if (!everFed_) {
    everFed_ = true;
    out_.pos = e.start;
  }
  ++count_;
  return kIpoOk;
}

// The path length from the element's start at which dir x X equals nx (xs <= nx <= xe).
double XInterpolator::solve(const Item& it, int slot, double nx) const {
  const path::Segment& seg = segs_[slot];
  const double len = seg.length();
  if (it.xe - it.xs <= 0) return len;   // no X extent: passed as a whole
  if (it.e.type == MoveType::Lin || it.e.type == MoveType::LinPos) return std::clamp((nx - it.xs) / (it.xe - it.xs), 0.0, 1.0) * len;
  double lo = 0, hi = len;
  for (int k = 0; k < 200 && hi - lo > 1e-13 * len; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (dir_ * seg.position(mid)[AxX] < nx) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

void XInterpolator::fireSwitches(double from, double to) {
  moveSwitches(0, count_, [this](int i) -> Item& { return at(i); }, from, to, out_);
}

// The unit tangent of the path (X/Y/Z) at a point of a segment; kept when it has none.
void XInterpolator::setTangent(const path::PathPoint& pp) {
  const double n = std::sqrt(pp.d1[0] * pp.d1[0] + pp.d1[1] * pp.d1[1] + pp.d1[2] * pp.d1[2]);
  if (n > 0)
    for (int i = 0; i < 3; ++i) out_.tangent[i] = pp.d1[i] / n;
}

const IpoOutput& XInterpolator::step(double x) {
  warning_ = kIpoOk;
  if (!items_ || error_ != kIpoOk || out_.finished) return out_;
  if (!std::isfinite(x) || std::fabs(x) > 1e12) {
    error_ = kIpoInvalidParameter;
    out_.working = false;
    return out_;
  }
  const bool moved = !haveX_ || x != lastX_;
  lastX_ = x;
  haveX_ = true;
  if (count_ == 0) {
    if (endOfList_ && everFed_) out_.finished = true;
    out_.status = out_.finished ? IpoStatus::Finished : IpoStatus::Init;
    warning_ = everFed_ && !endOfList_ ? kIpoDataUnderrun : kIpoOk;
    return out_;
  }
  const double nx = dir_ * x;
  const double tol = 1e-12 * std::max(1.0, std::fabs(nx));
  // the element at nx: forwards over ends (and over elements without X extent), backwards over starts
  for (;;) {
    const Item& it = at(ctl_);
    const bool flat = !it.hasSeg || it.xe - it.xs <= 0;
    if (flat) {
      if (ctl_ + 1 < count_ && nx >= it.xs - tol) {
        ++ctl_;
        continue;
      }
      if (nx < it.xs - tol && ctl_ > 0) {
        --ctl_;
        continue;
      }
      break;
    }
    if (ctl_ + 1 < count_) {
      const Item& nxt = at(ctl_ + 1);
      const bool nextFlat = !nxt.hasSeg || nxt.xe - nxt.xs <= 0;
      if (nx > it.xe + tol || (nextFlat && nx >= it.xe - tol)) {   // a step at the end is taken there
        ++ctl_;
        continue;
      }
    }
    if (nx < it.xs - tol && ctl_ > 0) {
      --ctl_;
      continue;
    }
    break;
  }
  const int slot = (head_ + ctl_) % kWindow;
  const Item& it = items_[slot];
  const double before = way_;
  const bool flat = !it.hasSeg || it.xe - it.xs <= 0;
  if (nx < it.xs - tol && ctl_ == 0) {
    if (entered_) {   // back beyond what is kept
      error_ = kXIpoNoIntersection;
      out_.working = false;
      return out_;
    }
    out_.pos = it.e.start;   // the workpiece has not reached the path yet
    out_.status = IpoStatus::Init;
    return out_;
  }
  entered_ = true;
  bool atEnd = false;
  if (flat) {
    const bool passed = nx >= it.xs - tol;
    out_.pos = passed ? it.e.end : it.e.start;
    way_ = passed ? it.wayEnd : it.wayStart;
    atEnd = passed && ctl_ + 1 == count_;
  } else if (nx >= it.xe - tol) {   // at the element's end (within rounding), or beyond the last one
    out_.pos = it.e.end;
    way_ = it.wayEnd;
    atEnd = ctl_ + 1 == count_;
    if (!(atEnd && endOfList_) && nx <= it.xe + tol) out_.pos[AxX] = x;   // X exactly as given
    path::PathPoint pp;
    segs_[slot].eval(segs_[slot].length(), pp);
    setTangent(pp);
  } else {
    const double s = solve(it, slot, nx);
    path::PathPoint pp;
    segs_[slot].eval(s, pp);
    for (int i = 0; i < kPathDims; ++i) out_.pos[i] = pp.pos[i];
    out_.pos[AxX] = x;
    way_ = it.wayStart + s;
    setTangent(pp);
  }
  fireSwitches(before, way_);
  out_.wayPos = way_;
  out_.sourceLine = std::max(0, it.e.line - 1);
  out_.objNo = it.e.objNo;
  if (atEnd && endOfList_) {   // the end: every element leaves the queue
    out_.finished = true;
    finished_ += count_;
    head_ = (head_ + count_) % kWindow;
    count_ = ctl_ = 0;
  } else {
    warning_ = atEnd && nx > it.xe + tol ? kIpoDataUnderrun : kIpoOk;
    for (; ctl_ > kKeptBehind; --ctl_, --count_, ++finished_) head_ = (head_ + 1) % kWindow;
  }
  out_.working = !out_.finished;
  out_.status = out_.finished ? IpoStatus::Finished : moved ? IpoStatus::Constant : IpoStatus::Wait;
  return out_;
}

}  // namespace stc::cnc
