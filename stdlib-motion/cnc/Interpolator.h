// The CNC path interpolator behind SMC_Interpolator (docs/cnc.md, "SMC_Interpolator"):
// checked path elements in, one set point per cycle out.
//
//  - Elements are handed over in queue order (feed) once SMC_CheckVelocities has
//    fixed their end velocity.  Motion elements become segments of the axis-group
//    path planner (stdlib-motion/path: exact lines, arcs and helices, ellipses,
//    splines and parabolas as polynomial pieces) with the element's F / E / E- and
//    the end velocity as the junction cap, so the feed is planned with look-ahead
//    over everything handed over up to the next point where the path must stop.
//  - Points where the velocity is 0 anyway (a sharp corner, an M function, a
//    dwell, G92, G75, the end) split the path into runs; the next run is handed to
//    the planner when the previous one has stopped.  That is where the interpolator
//    waits: for an M acknowledgement, a dwell, bWaitAtNextStop, single steps.
//  - H switch points fire at their exact path position (in the cycle the set point
//    passes it); the path position is measured along the planner's queue.
//
// Memory: fixed after construction (a ring of kMaxInFlight elements and the
// planner's segments); no allocation per cycle or per element.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "stdlib-motion/cnc/Element.h"

namespace stc::motion::path {
class Planner;
class Segment;
}  // namespace stc::motion::path

namespace stc::cnc {

namespace path = stc::motion::path;

// SMC_INT_STATUS.
enum class IpoStatus : int16_t {
  Unknown = 0, Init = 1, Accel = 2, Constant = 3, Decel = 4, Finished = 5, Wait = 6,
  IncreasingAccel = 7, DecreasingAccel = 8, IncreasingDecel = 9, DecreasingDecel = 10,
};
// SMC_INT_VELMODE: TRAPEZOID is acceleration-limited; SIGMOID and QUADRATIC are
// jerk-limited with the interpolator's jerk (the same profile here, docs/cnc.md).
enum class VelMode : int16_t { Trapezoid = 0, Sigmoid = 1, Quadratic = 2 };

// SMC_ERROR numbers the interpolator reports.
enum IpoError : int16_t {
  kIpoOk = 0,
  kIpoVelZero = 1001,           // SMC_INT_VEL_ZERO: an element with velocity 0
  kIpoDataUnderrun = 1003,      // SMC_INT_DATA_UNDERRUN (a warning): queue empty before bEndOfList
  kIpoNoCheckVelocities = 1006, // SMC_INT_NO_CHECKVELOCITIES
  kIpoPathExceeded = 1007,      // SMC_INT_PATH_EXCEEDED: an element the planner cannot run
  kIpoVelAccDecZero = 1008,     // SMC_INT_VEL_ACC_DEC_ZERO
  kIpoIpoTimeZero = 1009,       // SMC_INT_DWIPOTIME_ZERO (also beyond 1 s)
  kIpoJerkNonPositive = 1010,   // SMC_INT_JERK_NONPOSITIVE
  kIpoInvalidVelMode = 1012,    // SMC_INT_INVLALID_VELOCITY_MODE
  kIpoInvalidParameter = 1820,  // SMC_OS_INVALID_PARAMETER: override or quick deceleration not usable
};

struct IpoSettings {
  double cycle = 0.001;              // s per step (dwIpoTime)
  VelMode mode = VelMode::Trapezoid;
  double jerk = 0;                   // SIGMOID / QUADRATIC: > 0
};

// Inputs read every cycle.
struct IpoControls {
  bool slowStop = false;        // stop along the path with the element's deceleration; continue when FALSE
  bool quickStop = false;       // the same with quickDecel
  bool emergencyStop = false;   // stop at once (no ramp); continue from rest when FALSE
  bool waitAtNextStop = false;  // hold at the next point where the path stops anyway
  bool singleStep = false;      // every element ends at rest
  bool acknM = false;           // acknowledges the M function the interpolator waits on
  double override = 1;          // 0 .. 10, ramped within the element's acceleration
  double quickDecel = 0;        // > 0 when quickStop is used
};

struct IpoOutput {
  Pos pos{};                    // set position (all 11 axes)
  double vel = 0;               // path velocity (override applied)
  double acc = 0;               // path acceleration
  std::array<double, 3> tangent{};   // unit tangent in X/Y/Z at the set point (0 at rest without motion)
  IpoStatus status = IpoStatus::Unknown;
  int32_t sourceLine = 0;       // iSourceLine_No (0-based line) of the element in control
  int32_t objNo = 0;            // its object number
  int16_t lastSwitch = 0;       // the last H switch passed (+n on, -n off)
  uint32_t switches = 0;        // state of switches 1..32 (bit n-1)
  double wayPos = 0;            // path length covered since the start
  uint16_t m = 0;               // the M function waited on (0: none)
  double mK = 0, mL = 0;        // its K and L
  bool finished = false;        // the end of the list was reached
  bool working = false;         // a path is being interpolated (started, not finished, no error)
};

class Interpolator {
public:
  static constexpr int kMaxInFlight = 64;   // elements handed over and not finished

  // `error` is set (and nothing else done) when the settings are not usable.
  Interpolator(const IpoSettings& settings, int16_t& error);
  ~Interpolator();
  Interpolator(const Interpolator&) = delete;
  Interpolator& operator=(const Interpolator&) = delete;

  // TRUE when the interpolator can take another element now.
  bool wantsMore() const;
  // Hands over the next element (queue order).  Returns kIpoOk or the error that stops
  // the path (then the path stops along the planner with the element's deceleration).
  int16_t feed(const Element& e);
  // No more elements will come (SMC_OUTQUEUE.bEndOfList).
  void endOfList() { endOfList_ = true; }

  // One interpolation cycle.
  const IpoOutput& step(const IpoControls& c);
  const IpoOutput& output() const { return out_; }
  // Elements finished since the last call (the caller removes them from its queue).
  int takeFinished() {
    const int n = finishedCount_;
    finishedCount_ = 0;
    return n;
  }
  int inFlight() const { return count_; }
  int16_t error() const { return error_; }
  int16_t warning() const { return warning_; }

private:
  struct Item;
  enum class Hold : uint8_t { None, Slow, Quick, Emergency };

  Item& at(int i);
  const Item& at(int i) const;
  void fail(int16_t error);
  void applyHolds(const IpoControls& c);
  void processFront(const IpoControls& c, bool newCycle);
  void appendRuns(const IpoControls& c);
  void collectEvents();
  void fireSwitches(double way);
  void updateStatus(double prevAcc);

  IpoSettings cfg_;
  std::unique_ptr<path::Planner> planner_;
  std::unique_ptr<Item[]> items_;
  std::unique_ptr<path::Segment> scratch_;
  int head_ = 0, count_ = 0;
  int appended_ = 0;            // items (from the head) handed to the planner or processed as stops
  int finishedCount_ = 0;
  bool positioned_ = false;     // the planner has its start position
  bool endOfList_ = false;
  bool everFed_ = false;
  double wayAppended_ = 0;      // path length of everything handed to the planner
  double dwellElapsed_ = 0;
  bool dwellStarted_ = false;
  double prevVelEnd_ = 0;       // end velocity of the last element handed over (0: the run ends there)
  bool startedOnce_ = false;    // a run has been handed over (bWaitAtNextStop holds only after that)
  uint32_t lastDone_ = 0;       // highest planner move id reported done
  double override_ = 1;         // ramped override in use
  Hold hold_ = Hold::None;
  int16_t error_ = kIpoOk, warning_ = kIpoOk;
  IpoOutput out_;
};

}  // namespace stc::cnc
