// The bidirectional CNC interpolator behind SMC_Interpolator2Dir (docs/cnc.md,
// "SMC_Interpolator2Dir"): the same checked elements as Interpolator, but a
// negative override runs the path backwards (a hand wheel on the path).
//
// Why not the path planner: stdlib-motion/path plans forwards only.  Here the
// state is one coordinate along the path (w, the path length from its start)
// with a velocity and acceleration, moved each cycle by the one-axis trajectory
// generator (core/Trajectory.h) under the constraints that lie ahead in the
// direction of travel:
//  - inside an element: |v| <= F x |override|, and on curves <= sqrt(E / curvature) as the
//    path planner caps them (not scaled by the override: the acceleration is not);
//  - at a junction: |v| <= min(dVelEnd, next F) x |override| and both curve caps (0 with
//    bSingleStep);
//  - stop points: v = 0 at an M function or dwell not served yet, at the end of
//    what is known, at the oldest element kept (going backwards), at a G92.
// Each cycle follows the time-optimal velocity plan towards the element's F unless
// the state it would reach could no longer meet a constraint ahead; then it follows
// the time-optimal position plan to that constraint.  Set points come from the
// exact element geometry (PathSegment.h) at w.
//
// History: elements behind the one in control are kept (for going back) up to
// `history` queue entries; older ones are released to the caller (which removes them
// from its queue).  M functions and dwells are served once, in the forward direction;
// H switches follow the path position both ways (going back over "H+n" clears n).
//
// Memory: fixed after construction (a ring of history + 1 + kLookAhead items, or the
// whole path for startAtEnd); no allocation per cycle or per element.
#pragma once

#include <cstdint>
#include <memory>

#include "stdlib-motion/cnc/Interpolator.h"

namespace stc::cnc {

struct Ipo2DirSettings {
  IpoSettings ipo;
  int history = 0;          // queue entries kept behind the element in control (n of "n + 3")
  bool startAtEnd = false;  // take the whole path, start at its end (bStartAtEnd)
  int pathCapacity = 0;     // startAtEnd: the most elements the path may have (the queue's capacity)
};

class Interpolator2Dir {
public:
  static constexpr int kLookAhead = 64;        // elements ahead of the one in control
  static constexpr int kMaxHistory = 4096;     // queue entries kept behind it
  static constexpr int kMaxPath = 8192;        // startAtEnd: elements of the whole path
  // Elements taken per cycle: building a segment (arc-length tables of splines and ellipses)
  // costs a few us, so a path start spreads them instead of making one long cycle.
  static constexpr int kFeedsPerCycle = 8;

  // `error` is set (and nothing else done) when the settings are not usable:
  // the IpoSettings errors, or SMC_INT2DIR_BUFFER_TOO_SMALL (1050) for a history or
  // path capacity beyond the limits above.
  Interpolator2Dir(const Ipo2DirSettings& settings, int16_t& error);
  ~Interpolator2Dir();
  Interpolator2Dir(const Interpolator2Dir&) = delete;
  Interpolator2Dir& operator=(const Interpolator2Dir&) = delete;

  bool wantsMore() const;
  // Hands over the next element (queue order); kIpoOk or the error that stops the path.
  int16_t feed(const Element& e);
  void endOfList() { endOfList_ = true; }

  // One cycle.  c.override in -2 .. 2: its sign is the direction.
  const IpoOutput& step(const IpoControls& c);
  const IpoOutput& output() const { return out_; }
  // -1 backwards, 0 standing, +1 forwards (SMC_DIRECTION).
  int direction() const { return direction_; }
  // Elements released since the last call, oldest first (the caller removes them).
  int takeReleased() {
    const int n = released_;
    released_ = 0;
    return n;
  }
  int kept() const { return count_; }
  bool started() const { return started_; }
  int16_t error() const { return error_; }
  int16_t warning() const { return warning_; }

private:
  struct Item;
  struct Constraint {
    double dist;   // ahead of the set point, in the direction of travel (>= 0)
    double vel;    // the most |v| there
  };

  Item& at(int i);
  const Item& at(int i) const;
  void fail(int16_t error);
  void startAtEndIfReady();
  int governing(int dir) const;
  int collectConstraints(int dir, double horizon, double ov, bool singleStep);
  void move(const IpoControls& c);
  void serveStopItem(const IpoControls& c);
  void updateControl();
  void fireSwitches(double from, double to);
  void release();
  void publish(double prevAcc);
  bool atStopPoint(bool singleStep) const;
  double junctionAfter(int i, bool singleStep, double ov, bool* last) const;
  int motionBefore(int i) const;

  Ipo2DirSettings cfg_;
  int capacity_ = 0;
  std::unique_ptr<Item[]> items_;
  std::unique_ptr<path::Segment[]> segs_;
  std::unique_ptr<Constraint[]> cons_;
  int head_ = 0, count_ = 0;
  int ctl_ = 0;              // the item in control (index from the oldest kept)
  double w_ = 0, v_ = 0, a_ = 0;   // path coordinate, signed velocity and acceleration
  double wayFed_ = 0;        // path length of everything fed
  bool endOfList_ = false;
  bool everFed_ = false;
  bool started_ = false;     // startAtEnd: the whole path is in and the set point at its end
  bool leftStart_ = false;   // moved once (bWaitAtNextStop holds only after that)
  bool dwellStarted_ = false;
  double dwellElapsed_ = 0;
  int direction_ = 0;
  int released_ = 0;
  int fedThisCycle_ = 0;
  int servedG92_ = -1;       // index of a G92 served this cycle (release() drops up to it)
  int16_t error_ = kIpoOk, warning_ = kIpoOk;
  IpoOutput out_;
};

}  // namespace stc::cnc
