// Group motion: the commands that move an axis group's members together and
// the group's part of the kernel step (docs/motion-groups.md, "Motion").
//
// A group command in control owns every member axis: the member runs a
// DirectGenerator whose state the group writes in groupBeforeStep() from the
// command's GroupMotion (joint space), before the axes are stepped.  Members
// are in SynchronizedMotion while the group is GroupMoving.
#pragma once

#include <memory>
#include <vector>

#include "stdlib-motion/core/Trajectory.h"
#include "stdlib-motion/group/AxisGroup.h"
#include "stdlib-motion/path/Planner.h"

namespace stc::motion {

// The joint set states of a group command over time (t: seconds since its start).
class GroupMotion {
public:
  virtual ~GroupMotion() = default;
  virtual void at(double t, Kinematic* q) const = 0;   // one state per member
  virtual double duration() const = 0;
};

// Point to point: one profile per member, all ending at the same time.
class PtpMotion : public GroupMotion {
public:
  std::vector<Profile> profiles;
  double total = 0;
  void at(double t, Kinematic* q) const override;
  double duration() const override { return total; }
};

// Plans every member from `start` to `target` (at rest) under its limits, all arriving
// together at the earliest common time.  From rest (Fast): the members whose own
// time-optimal plan is shorter are slowed down by time scaling (velocity x k, acceleration
// x k^2, jerk x k^3 with k = their time / the longest time) and keep their profile shape;
// from a moving start: the synchronised planner (core/SyncPlan.h).  pathInvariant (from
// rest): every member moves proportionally, on the straight line in joint space.
PlanStatus planPtp(const std::vector<Kinematic>& start, const std::vector<double>& target, const std::vector<Limits>& lim,
                   PtpMotion& out, bool pathInvariant = false);

// MC_MoveDirectAbsolute / MC_MoveDirectRelative inputs (joint space), latched at the edge.
struct DirectInputs {
  double position[kMaxGroupAxes] = {};   // absolute targets, or distances when `relative`
  bool relative = false;
  bool pathInvariant = false;            // SMC_PTP_MOVEMENT_TYPE.Path_Invariant
  double velFactor = 1, accFactor = 1, jerkFactor = 1;
  BufferMode bufferMode = BufferMode::Aborting;
  int transitionMode = 0;                // MC_TRANSITION_MODE (0 TMNone)
  // The system of `position` (TCS: relative in MCS).  Cartesian targets become joint
  // targets by the inverse kinematics with the group's configuration (SMC_SetKinConfiguration).
  int coordSystem = 0;
};
void callGroupMoveDirect(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const DirectInputs& in, const CallCtx& c);

// MC_MoveLinear* / MC_MoveCircular*: a path move in coordSystem (coordinates as
// GroupKinematics.h lays them out), latched at the edge.  Static Cartesian systems are
// converted into MCS, where the planner runs; ACS paths of a group with kinematics run in
// joint space; a dynamic PCS keeps its own coordinates (the path follows the master).
struct PathInputs {
  path::MoveSpec spec;
  int coordSystem = 0;                            // SMC_COORD_SYSTEM (TCS: relative in MCS)
  BufferMode bufferMode = BufferMode::Aborting;   // checked, then mapped to spec.buffer
  int transitionMode = 0;                         // MC_TRANSITION_MODE, mapped to spec.transition
  double velFactor = 1, accFactor = 1, jerkFactor = 1;
  // SMC_ORIENTATION_MODE: 0 GreatCircle, 1 Axis (A, B, C each linear with the path, which
  // is what the planner does).  GreatCircle is refused (SMC_AG_ORIENTATION_MODE) when the move
  // turns a tool whose orientation has more than one axis (it would differ from Axis).
  int orientationMode = 1;
};
void callGroupMovePath(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const PathInputs& in, const CallCtx& c);

// SMC_GroupJog: the group tracks the set positions of reference axes (X, Y, Z, A, B, C; null:
// not used, that coordinate keeps its value) in coordSystem.  From the rising edge it moves
// there (InitialPositionReached: FbOutputs::inState), then follows them one cycle behind,
// each member under its limits x the factors, until another command takes the group.
struct JogInputs {
  int coordSystem = 1;         // SMC_COORD_SYSTEM (not TCS)
  int pcs = 3;                 // CoordSystemPCS: PCS_1 or PCS_2 (reserved while the jog tracks)
  double velFactor = 1, accFactor = 1, jerkFactor = 1;
  const Axis* ref[6] = {};
  bool abcAsAcs = false;       // needs Kin_Coupled kinematics: refused
};
void callGroupJog(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const JogInputs& in, const CallCtx& c);

// SMC_GroupSaveContinueData: armed in its call; a MC_GroupHalt / MC_GroupStop later in the same
// cycle keeps the running motion for MC_GroupContinue; Done when that halt is at rest.
void callGroupSaveContinueData(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c);
// SMC_GroupEnableResumeAfterError (called cyclically): while enable is TRUE, a motion that a
// member's error stops is kept where its set point stood.  Returns Busy.
bool setGroupResumeAfterError(AxisGroup& g, bool enable);
// The token of saved continue data that can be written out now (0: none).
uint32_t savedContinueToken(const AxisGroup& g);

// SMC_GroupWait: a dwell of waitTime seconds queued like a buffered move; the next
// buffered command starts exactly when it expires (also between cycles).
void callGroupWait(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, double waitTime, const CallCtx& c);

// MC_GroupSetPosition: in GroupStandby, the members' positions (absolute or relative).
void callGroupSetPosition(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const double* position, bool relative,
                          const CallCtx& c);

// MC_GroupSetOverride (Enable FB): the factors in [0, 1]; the group's motions are time-scaled
// by the largest factor f that keeps velocities within VelFactor / PathVelFactor, accelerations
// within Acc / PathAcc (f^2) and jerks within Jerk / PathJerk (f^3).  Returns the applied f.
struct OverrideInputs {
  double vel = 1, acc = 1, jerk = 1, pathVel = 1, pathAcc = 1, pathJerk = 1;
};
void callGroupSetOverride(Kernel& k, FbSlot& fb, AxisGroup& g, bool enable, const OverrideInputs& in, const CallCtx& c);
// The time scaling f of the group's motions from this call on (MC_GroupSetOverride's f, or a
// vendor's speed ratio such as Leadshine's VelRatio up to 2): f finite, 0 <= f <= 1000.
// Returns false (nothing changed) otherwise.
bool setGroupRate(Kernel& k, AxisGroup& g, double f, const CallCtx& c);

// MC_GroupInterrupt: the running MoveDirect/MoveLinear/MoveCircular brakes to rest (on its
// path) and stays Busy; Done at rest writes `token` (the continue data).  MC_GroupContinue
// with that token resumes it.
void callGroupInterrupt(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, uint32_t& token, uint32_t& movementId, const CallCtx& c);
void callGroupContinue(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, uint32_t token, const CallCtx& c);

// SMC_SetDynamicLimitFactors: factors in (0, 1] per member, for the moves planned afterwards;
// not in GroupDisabled or GroupErrorStop.
void callSetDynamicLimitFactors(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const AxisGroup::LimitFactors* f,
                                const CallCtx& c);

// SMC_GroupSetAncillaryAxisLimits (per member) / SMC_GroupSetAncillaryPathLimits (lim[0]):
// every component > 0.  Immediately: for every move that starts afterwards; Queued: for the
// moves commanded afterwards.  Path moves take them when they are handed to the planner.
void callSetAncillaryLimits(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, bool pathLimits, bool immediately, const Limits* lim,
                           const CallCtx& c);

// MC_SetKinTransform / SMC_SetKinConfiguration / MC_SetCoordinateTransform /
// MC_SetDynCoordTransform: only while the group stands (GroupDisabled or GroupStandby, nothing
// interrupted); Done in the call of the edge.  kin null: an invalid kinematics (error).
void callSetKinTransform(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, std::shared_ptr<const GroupKinematics> kin, const CallCtx& c);
void callSetKinConfiguration(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const KinConfigData& cfg, const CallCtx& c);
// coords: X, Y, Z, A, B, C of the frame; master: the master group (dynamic PCS) or null.
void callSetCoordinateTransform(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const double* coords, int coordSystem,
                                const AxisGroup* master, const CallCtx& c);

// SMC_GroupGetContinuePosition: where the motion interrupted under `token` stands (members'
// coordinates); false when no such interruption can be continued.
bool continuePosition(const AxisGroup& g, uint32_t token, double* position);

// MC_GroupHalt (group to Standby at rest) and MC_GroupStop (GroupStopping while Execute).
struct GroupStopInputs {
  double deceleration = 0, jerk = 0, accFactor = 1, jerkFactor = 1;
};
void callGroupHalt(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const GroupStopInputs& in, const CallCtx& c);
void callGroupStop(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const GroupStopInputs& in, const CallCtx& c);

// The group's parts of the kernel step: before the axes (start commands, write the
// members' set states, completion and hand-over to the next command) and after them
// (member errors, members taken by single-axis commands).
void groupBeforeStep(Kernel& k, AxisGroup& g, int64_t nowNs, int64_t intervalNs, uint64_t cycle);
void groupAfterStep(Kernel& k, AxisGroup& g, int64_t nowNs, uint64_t cycle);

// MC_GroupDisable: every group command ends (CommandAborted); moving members brake
// with their own deceleration and are let go.
void abortGroupMotion(Kernel& k, AxisGroup& g, const CallCtx& c);

}  // namespace stc::motion
