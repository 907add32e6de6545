// Path planner of an axis group: a fixed-capacity queue of path segments
// (moves, corner blends), look-ahead velocity planning along the path length s,
// and the per-cycle interpolator (docs/path.md).
//
//  - append(move) builds the move's geometry from the end of the queue (or from
//    the stop point when it aborts a running path), inserts the corner
//    transition its BufferMode/TransitionMode ask for, and updates the
//    look-ahead incrementally (a backward pass from the new end that stops as
//    soon as nothing changes).
//  - The feed along s is planned with the one-axis planner of core/Trajectory.h
//    (jerk-limited when Jerk > 0) over "runs" of consecutive segments with equal
//    limits; the planner can always stop at the end of the known queue.
//  - advance(dt) moves along the plan by dt (scaled by the override) and returns
//    the coordinates, the path velocity, the active move and the events of the
//    step (moves started / done / aborted, each with its exact time in the step).
//
// Memory: everything is allocated in the constructor (capacity segments); no
// call allocates afterwards, except splineThrough's scratch the first time a
// spline longer than any before is appended (sized to the capacity up front).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "stdlib-motion/core/Trajectory.h"
#include "stdlib-motion/path/Geometry.h"

namespace stc::motion::path {

enum class BufferMode : uint8_t { Aborting, Buffered, BlendingLow, BlendingPrevious, BlendingNext, BlendingHigh };
enum class TransitionMode : uint8_t { None, StartVelocity, CornerDistance, MaxCornerDeviation, CornerRadius };

// Path dynamics of a move: Velocity, Acceleration, Deceleration (> 0), Jerk
// (>= 0, 0 = acceleration-limited profile).
struct Dynamics {
  double vel = 0, acc = 0, dec = 0, jerk = 0;
};

enum class MoveKind : uint8_t {
  Line, ArcBorder, ArcCenter, ArcRadius, Ellipse, Spline,
  Prebuilt,   // `segment`, built by the caller from the end of the queue (the CNC interpolator)
};

struct MoveSpec {
  MoveKind kind = MoveKind::Line;
  bool relative = false;     // end, aux and points relative to the move's start point
  Vec end{};                 // end point, all coordinates (not used by Spline)
  Vec aux{};                 // ArcBorder: the border point; ArcCenter / Ellipse: the centre
  bool centerRelative = false;   // ArcCenter: aux is the centre's offset from the start even when
                                 // the end is absolute (MC_MoveCircularAbsolute, CircMode CENTER)
  double radius = 0;         // ArcRadius
  bool longArc = false;      // ArcRadius: the arc of more than half a turn
  Vec normal{0, 0, 1};       // arcs, ellipses: plane normal (right-hand rule for ccw)
  bool ccw = true;           // ArcCenter, ArcRadius, Ellipse
  int turns = 0;             // extra full turns (ArcCenter, ArcRadius, Ellipse)
  double majorAngle = 0;     // Ellipse: angle of the major axis [rad]
  double ratio = 1;          // Ellipse: minor / major
  std::span<const Vec> points;   // Spline: the points after the start (C2 cubic spline)
  const Segment* segment = nullptr;   // Prebuilt: must start at the end of the queue (1e-9)
  // Buffered only: > 0 lets the path pass the junction with the previous move at up to this
  // velocity instead of stopping (the caller has judged the corner: the CNC interpolator
  // passes SMC_CheckVelocities' end velocity); the planner still applies its caps.
  double junctionVel = 0;
  Dynamics dyn;
  BufferMode buffer = BufferMode::Aborting;
  TransitionMode transition = TransitionMode::None;
  double transitionParam = 0;    // TransitionParameter[0]
};

enum class PathStatus : uint8_t {
  Ok,
  QueueFull,                  // the move does not fit into the remaining capacity
  InvalidDynamics,            // Velocity/Acceleration/Deceleration not > 0, Jerk < 0, NaN/Inf, beyond bounds
  InvalidGeometry,            // see AppendResult::geo
  BlendingNeedsTransition,    // a Blending buffer mode with TMNone
  TransitionNotAllowed,       // Buffered (or Aborting) with a transition mode other than TMNone
  InvalidTransitionParameter, // negative, NaN or infinite TransitionParameter
  InvalidOverride,            // override factor < 0 or not finite
  Unreachable,                // AxisLimits::map refused a point of the move (out of the kinematics' reach)
  NotHeld,                    // resume without a hold
};
const char* toString(PathStatus s);

struct AppendResult {
  PathStatus status = PathStatus::Ok;
  GeoStatus geo = GeoStatus::Ok;
  uint32_t id = 0;            // move id (> 0) when Ok
  bool blendDropped = false;  // a requested blend could not be used (too late or reversal): exact stop at the corner
};

enum class EventKind : uint8_t { Started, Done, Aborted };
struct Event {
  uint32_t id;
  EventKind kind;
  double t;   // seconds since the start of the advance() step; 0 for events of an operation call
};

// Axis (joint) limits applied along the path.  Without `map` the axes are the
// coordinates themselves (count <= dims).  With `map`, it returns the joint
// derivatives dq/ds and d2q/ds2 for the path derivatives at a point (through
// the Jacobian of the kinematics: dq/ds = J dp/ds, d2q/ds2 = J d2p/ds2 + (dJ/ds) dp/ds);
// returning false marks the point unreachable (the move is refused).
struct AxisLimits {
  int count = 0;
  double vel[kMaxCoords] = {};
  double acc[kMaxCoords] = {};
  std::function<bool(const Vec& pos, const Vec& dpds, const Vec& d2pds2, Vec& dqds, Vec& d2qds2)> map;
  double curvatureShare = 0.5;   // part of each axis' acceleration reserved for v^2 q''
};

struct PlannerConfig {
  int dims = 3;             // coordinates 1..11
  int capacity = 128;       // segments in the queue (moves, blends, spline pieces)
  AxisLimits axes;
};

struct Sample {
  Vec pos{};                // all coordinates
  Vec vel{};                // coordinate velocities (dp/ds * v)
  Vec acc{};                // coordinate accelerations (dp/ds * a + d2p/ds2 * v^2)
  double v = 0, a = 0;      // path velocity and acceleration (override applied)
  uint32_t active = 0;      // id of the move in control (0: none)
  bool moving = false;      // a plan is running (also while braking)
  bool held = false;        // stopped by interrupt() (resume() continues)
};

class Planner {
public:
  explicit Planner(const PlannerConfig& cfg);

  // Sets the position of an idle planner (no effect while moving; returns false then).
  bool setPosition(const Vec& p);

  AppendResult append(const MoveSpec& m);
  // Stop along the path with (at least) this deceleration / jerk; the queue is
  // aborted (Aborted events now), the halt gets an id whose Done event comes at
  // standstill.  An idle planner reports the halt Done at once.
  uint32_t halt(double dec, double jerk);
  // Feed hold: stop along the path (deceleration / jerk as halt), keep the queue.
  PathStatus interrupt(double dec, double jerk);
  PathStatus resume();
  // Holds the path where the last sample stands, at once (the caller stops the axes some
  // other way, e.g. an error stop): the queue stays, resume() starts there from rest.
  void freeze();
  // The move id of the last queued segment (0 when the queue is empty).
  uint32_t lastOwner() const { return count_ > 0 ? at(count_ - 1).owner : 0; }
  // Time scaling of the plan: path velocity x f, acceleration x f^2; 0 holds.
  PathStatus setOverride(double f);
  // Drops everything at once (error stop by the caller: the path stops dead).
  void clear();

  const Sample& advance(double dt);
  const Sample& sample() const { return sample_; }

  std::span<const Event> events() const { return {events_.data(), static_cast<size_t>(nEvents_)}; }
  void clearEvents() { nEvents_ = 0; }

  int queued() const { return count_; }
  int capacity() const { return cap_; }
  bool idle() const { return count_ == 0; }
  // Path length still to go to the end of the queue (from the current point).
  double remaining() const;
  // Counters for tests and benchmarks.
  uint64_t replans() const { return replans_; }
  uint64_t backwardSteps() const { return backSteps_; }
  uint64_t planFailures() const { return planFailures_; }

private:
  struct Slot {
    Segment geo;
    double origLen = 0;            // length before blends trimmed it
    double vcap = 0, acc = 0, dec = 0, jerk = 0;   // effective limits on the segment
    Dynamics nominal;              // the move's dynamics (blends: the mode's choice)
    double juncCap = 0;            // velocity allowed at the end junction (0: stop)
    double vEndMax = 0;            // look-ahead: highest velocity at the end that can still stop in time
    double planStart = 0, planEnd = 0;   // plan coordinates of the ends (slots in the plan)
    uint32_t owner = 0;            // move id Active on this segment
    bool first = false, last = false;    // first / last segment of its owner
    bool silent = false;           // segment of an aborted move kept for a stop ramp (no Done)
  };

  Slot& at(int i) { return ring_[(head_ + i) % cap_]; }
  const Slot& at(int i) const { return ring_[(head_ + i) % cap_]; }
  bool sameLimits(const Slot& a, const Slot& b) const;
  void pushEvent(uint32_t id, EventKind k, double t);
  GeoStatus buildGeometry(const MoveSpec& m, const Vec& start, const Vec* inTangent, int& n);
  // False when the segment admits no motion; *unreachable: because the axis map refused a point.
  bool computeCaps(Slot& s, bool* unreachable = nullptr) const;
  void backwardPass(int from);
  bool replan();
  bool planRun(const Kinematic& st, int& runEnd, Profile& out);
  bool valid(const Profile& p) const;
  Kinematic planState() const;
  struct StopInfo {
    bool atRest = false;   // already standing (or idle): stop where it is
    bool ramp = false;     // a velocity ramp (prof) ends at the stop point; else the running plan does
    Profile prof;
    int slot = 0;          // slot holding the stop point
    double local = 0;      // path length into that slot
    double s0 = 0;         // path length into the head now
    Vec point{};
  };
  void computeStop(double dec, double jerk, StopInfo& st) const;
  void installStopRamp(const StopInfo& st, int slots);
  double brakeReach(double vEnd, double len, double dec, double jerk, double vcap) const;
  double accelReach(double v0, double len, double acc, double jerk, double vcap) const;

  int dims_, cap_;
  AxisLimits axes_;
  std::vector<Slot> ring_;
  int head_ = 0, count_ = 0;
  std::vector<Segment> scratchSegs_;
  SplineScratch splineScratch_;
  std::vector<double> savedVEnd_;

  Vec holdPos_{};        // position when the queue is empty
  uint32_t nextId_ = 1;

  // the running plan (coordinates: p = 0 at the plan's start)
  Profile prof_;
  bool planned_ = false;
  int planSlots_ = 0;     // slots (from the head) the plan covers
  double tau_ = 0;        // plan time elapsed
  double sHead_ = 0;      // path length into the head slot (when no plan runs)
  bool held_ = false, holding_ = false;   // hold requested / hold plan running
  double override_ = 1;

  std::vector<Event> events_;
  int nEvents_ = 0;
  Sample sample_;
  uint64_t replans_ = 0, backSteps_ = 0, planFailures_ = 0;
};

}  // namespace stc::motion::path
