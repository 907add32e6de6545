// Axis groups (PLCopen Motion Control Part 4, CODESYS SM3_Robotics): a set of
// member axes that the group's commands move together.  This header holds the
// group object and its state machine; the administration instructions
// (add/remove axes, enable, disable, reset, power) are the call* functions
// below.  Group motion (lines, arcs, PTP) builds on it (docs/motion-groups.md).
//
// A group belongs to the task that first calls one of its FBs, like an axis;
// its members must belong to that task too.  Every admin instruction takes
// effect in its call (Done in the call of the rising edge).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "stdlib-motion/core/Axis.h"
#include "stdlib-motion/core/Errors.h"
#include "stdlib-motion/core/Fb.h"
#include "stdlib-motion/group/GroupKinematics.h"

namespace stc::motion {

class Kernel;
struct CallCtx;
class GroupMotion;
class DirectGenerator;
namespace path {
class Planner;
}

// SMC_AXIS_GROUP_STATE; the numbering is stc's (the manuals list the names only).
enum class GroupState : uint8_t { Disabled = 0, Standby = 1, Moving = 2, Homing = 3, Stopping = 4, ErrorStop = 5 };

// SMC_RCNST.MAX_AXES: six kinematic axes plus three additional axes.
inline constexpr size_t kMaxGroupAxes = 9;

class AxisGroup {
public:
  explicit AxisGroup(uint32_t index);
  ~AxisGroup();

  uint32_t index() const { return index_; }
  GroupState state() const { return state_; }
  bool enabled() const { return state_ != GroupState::Disabled; }
  // MC_GroupReadError: the group's own error (GroupErrorID) and the member axis
  // error that caused it (ErrorID), None when there is none.
  Error groupError() const { return groupError_; }
  Error axisError() const { return axisError_; }
  const std::vector<Axis*>& axes() const { return axes_; }
  // The member's index in the group (IdentInGroup), or -1.
  int identOf(const Axis& ax) const;

  uint32_t task = UINT32_MAX;          // the owning task (first FB call)
  // Owned by a block instead of an AXIS_GROUP_REF_SM3 (the Leadshine LS_ interpolation
  // FBs): enabled for that block's moves only; while it stands idle another internal group
  // may take its members over (enableGroupWith).
  bool internal = false;
  uint64_t activeMovementId = 0;       // MC_GroupReadStatus.ActiveMovementId
  uint64_t nextMovementId = 1;         // the id the next accepted movement gets

  // ---- motion (GroupMotion.cpp)
  FbSlot* pending = nullptr;           // accepted in a call (Aborting), started in that cycle's step
  FbSlot* active = nullptr;            // the command in control
  std::vector<FbSlot*> queue;          // buffered commands behind it
  std::shared_ptr<const GroupMotion> motion;   // the active command's set points
  int64_t originNs = 0;                // when it started
  // The latest motion (also after it ended or was aborted) and its start: the exact
  // state the next command starts from, whatever the members' last written step was.
  std::shared_ptr<const GroupMotion> lastMotion;
  int64_t lastOriginNs = 0;
  bool ended = false;                  // the last command ended: GroupStandby in the next step
  std::vector<std::shared_ptr<DirectGenerator>> gens;   // per member while the group moves
  uint64_t memberHandles[kMaxGroupAxes] = {};            // kernel slots standing for the group on its members
  // Path moves (MC_MoveLinear*, MC_MoveCircular*) run on the path planner (stdlib-motion/path),
  // created for the members at the first path move; each queued move is one planner id.
  std::unique_ptr<path::Planner> planner;
  std::vector<std::pair<uint32_t, FbSlot*>> pathCommands;
  // A path started from rest in a call of cycle N begins at that cycle's time: the step of
  // cycle N samples it at t = 0 and shows Active (as every group move: Active in N + 1).
  uint64_t pathStartCycle = 0;
  // A halt or an aborting move in a call of cycle N acts at that cycle's time: the planner
  // is advanced to it in the call, and the step of cycle N does not advance it again.
  uint64_t pathAdvancedCycle = 0;
  std::vector<uint32_t> startedInCall;   // Started events of a call, shown by the next step

  // MC_GroupSetOverride: time scaling of every group motion by `rate` (it persists, also
  // across re-enabling); PTP motions run on group time (groupTime()).
  double rate = 1;
  int64_t rateNs = 0;                  // when the rate last changed (or the motion started) ...
  double rateTau = 0;                  // ... and the motion's time then
  double motionRate = 1;               // the rate of the running motion (MC_GroupStop: 1)

  // MC_GroupInterrupt / MC_GroupContinue: the interrupted command (PTP: its slot, kept Busy),
  // the interrupting FB until it is Done, and a token the continue data carries.
  FbSlot* interrupted = nullptr;
  FbSlot* interrupter = nullptr;
  bool pathInterrupted = false;
  uint32_t interruptToken = 0;
  double continuePos[kMaxGroupAxes] = {};   // where the interrupted motion stands (SMC_GroupGetContinuePosition)

  // SMC_GroupSaveContinueData / SMC_GroupEnableResumeAfterError: a motion that a halt, a stop
  // or an axis error ended, kept for MC_GroupContinue (docs/motion-groups.md).
  FbSlot* saver = nullptr;             // SMC_GroupSaveContinueData armed in saverCycle, then its halt's
  uint64_t saverCycle = 0;
  bool saverTaken = false;             // a halt / stop of saverCycle took it
  bool resumeAfterError = false;       // SMC_GroupEnableResumeAfterError's Enable in its last call
  struct SavedMotion {
    uint32_t token = 0;                    // 0: nothing saved (tokens count with interruptToken)
    bool complete = false;                 // at rest: continue data can be written
    bool path = false;                     // the planner holds the rest of the path ...
    std::shared_ptr<FbBehaviour> ptp;      // ... or the PTP move (its targets and dynamics)
    double pos[kMaxGroupAxes] = {};        // where it resumes (members' coordinates)
  } saved;
  // Forgets saved continue data (the members' coordinates, the kinematics or the path changed);
  // a held path is cleared from the planner.
  void dropSaved();

  // SMC_GroupJog: the PCS (1 or 2) the tracking jog uses; 0 when none runs.
  int jogPcs = 0;

  // Ancillary limits A (SMC_GroupSetAncillaryAxisLimits, or factor x the axis limit G from
  // SMC_SetDynamicLimitFactors): a member's limit for a move is min(A, M x G), M the move's
  // factors; a component of 0 is no ancillary limit.  Cleared at MC_GroupEnable.
  struct LimitFactors { double vel = 1, acc = 1, dec = 1, jerk = 1; };
  Limits anc[kMaxGroupAxes] = {};
  Limits ancPath = {};                 // SMC_GroupSetAncillaryPathLimits: A of the path
  // Queued limits apply to the moves commanded after them, immediate ones to every move that
  // starts after them: a move keeps the limits of its acceptance unless an immediate change
  // came later (its serial is below ancImmediate).
  uint64_t ancSerial = 0, ancImmediate = 0;
  bool plannerStale = false;           // the factors changed: a new planner at the next path start
  // SMC_GroupTargetPosition: the target of the last queued move (members' coordinates).
  double target[kMaxGroupAxes] = {};
  bool targetValid = false;
  CoordSystem targetCs = CoordSystem::ACS;   // the system of `target` (ACS, MCS or a dynamic PCS)

  // ---- kinematics and coordinate systems (GroupKinematics.h)
  std::shared_ptr<const GroupKinematics> kin;   // MC_SetKinTransform; null: the members are the coordinates
  KinConfigData kinConfig;                      // SMC_SetKinConfiguration: for Cartesian PTP targets
  Frame mcs;                                    // MCS in WCS (MC_SetCoordinateTransform)
  // PCS_1 / PCS_2 in WCS; dynamic (MC_SetDynCoordTransform) when `master` names a group:
  // then `frame` is the PCS relative to that group's tool.
  struct Pcs {
    Frame frame;
    uint32_t master = UINT32_MAX;
  };
  Pcs pcs[2];
  // The system of the path planner's coordinates: ACS, MCS (every static Cartesian move is
  // converted into it) or a dynamic PCS (the path follows its master).
  CoordSystem pathCs = CoordSystem::ACS;

  // ---- state machine (used by the group instructions and the kernel step)
  void addAxis(Axis& ax) { axes_.push_back(&ax); }
  void removeAxis(Axis& ax);
  void clearAxes() { axes_.clear(); }
  void setState(GroupState s) { state_ = s; }
  // GroupErrorStop with the group error and the axis error behind it.
  void enterErrorStop(Error group, Error axis);
  void clearErrors() { groupError_ = axisError_ = Error::None; }

private:
  uint32_t index_;
  GroupState state_ = GroupState::Disabled;
  Error groupError_ = Error::None;
  Error axisError_ = Error::None;
  std::vector<Axis*> axes_;
};

// ---- the administration instructions (Execute FBs: Done or Error in the call of the edge)
void callAddAxisToGroup(Kernel& k, FbSlot& fb, AxisGroup& g, Axis& ax, bool execute, const CallCtx& c);
void callRemoveAxisFromGroup(Kernel& k, FbSlot& fb, AxisGroup& g, Axis& ax, bool execute, const CallCtx& c);
void callUngroupAllAxes(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c);
void callGroupEnable(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c);

// For internal groups (AxisGroup::internal): disables the group if it is enabled (its
// members let go where they stand), makes `axes` the members and enables it with
// MC_GroupEnable's checks.  An idle internal group that holds one of the axes (all its
// commands ended) is disabled first, so one block's move can follow another's at once.
// allowPulse admits pulse (stepper) axes, which MC_GroupEnable refuses.  None when enabled.
Error enableGroupWith(Kernel& k, AxisGroup& g, const std::vector<Axis*>& axes, bool allowPulse, const CallCtx& c);
// MC_GroupDisable without an FB: the commands end, moving members brake and are let go.
void disableGroup(Kernel& k, AxisGroup& g, const CallCtx& c);
void callGroupDisable(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c);
void callGroupReset(Kernel& k, FbSlot& fb, AxisGroup& g, bool execute, const CallCtx& c);
// SMC_GroupPower: MC_Power on every member (Enable FB; Status when every member is ready).
// Each member is powered through a kernel slot of its own, whose handle the ST instance keeps
// in `handles` (by member index; 0 = none yet) with `instance` as the slots' owner.
void callGroupPower(Kernel& k, FbSlot& fb, AxisGroup& g, uint64_t (&handles)[kMaxGroupAxes], void* instance, bool enable,
                    bool regulatorOn, bool driveStart, const CallCtx& c);

}  // namespace stc::motion
