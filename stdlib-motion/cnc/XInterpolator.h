// The position-based interpolator behind SMC_XInterpolator (docs/cnc.md,
// "SMC_XInterpolator"): a cam whose master is an external X axis and whose
// profile is a G-code path.  Each call takes the current X; the set point is the
// point of the path at that X (the path must be unique in X: X monotonic along
// it, in the direction eDirection says the workpiece moves).
//
// The point is found on the exact element geometry (PathSegment.h): closed form
// on lines, bisection on the path length elsewhere (to 1e-12 of the element's
// length); its X is the given X exactly.  An element without X extent (a step in
// Y/Z) is passed when X reaches it: the set point jumps across it.  Elements that
// do not move (M functions, dwells, G92, G75) are skipped: nothing here can wait.
//
// Memory: a ring of kWindow elements (the ones ahead and two behind, so X may
// jitter back over a junction); no allocation per call.
#pragma once

#include <cstdint>
#include <memory>

#include "stdlib-motion/cnc/Interpolator.h"
#include "stdlib-motion/path/Geometry.h"

namespace stc::cnc {

enum XIpoError : int16_t {
  kXIpoInvalidDirection = 1070,   // SMC_XINT_INVALID_DIRECTION: eDirection neither positive nor negative
  kXIpoNoIntersection = 1071,     // SMC_XINT_NOINTERSECTION: no (unique) path point at this X
};

class XInterpolator {
public:
  static constexpr int kWindow = 64;
  static constexpr int kKeptBehind = 2;

  // dir: +1 the workpiece's X grows along the path, -1 it falls.
  explicit XInterpolator(int dir);
  ~XInterpolator();
  XInterpolator(const XInterpolator&) = delete;
  XInterpolator& operator=(const XInterpolator&) = delete;

  bool wantsMore() const;
  // The next element (queue order); kIpoOk or the error that stops it.
  int16_t feed(const Element& e);
  void endOfList() { endOfList_ = true; }

  // One call with the path X.  Not finite: SMC_OS_INVALID_PARAMETER (1820).
  const IpoOutput& step(double x);
  const IpoOutput& output() const { return out_; }
  // Elements left behind since the last call (the caller removes them from its queue).
  int takeFinished() {
    const int n = finished_;
    finished_ = 0;
    return n;
  }
  int16_t error() const { return error_; }
  int16_t warning() const { return warning_; }

private:
  struct Item;
  Item& at(int i);
  const Item& at(int i) const;
  double solve(const Item& it, int slot, double x) const;
  void fireSwitches(double from, double to);
  void setTangent(const path::PathPoint& pp);

  int dir_;
  std::unique_ptr<Item[]> items_;
  std::unique_ptr<path::Segment[]> segs_;
  int head_ = 0, count_ = 0;
  int ctl_ = 0;                // the element the set point is on
  double way_ = 0;             // path length from the first element's start to the set point
  double wayFed_ = 0;
  bool endOfList_ = false;
  bool everFed_ = false;
  bool entered_ = false;       // X has reached the path's start
  double lastX_ = 0;
  bool haveX_ = false;
  int finished_ = 0;
  int16_t error_ = kIpoOk, warning_ = kIpoOk;
  IpoOutput out_;
};

}  // namespace stc::cnc
