// Couplings: a slave axis whose set point follows a master axis (PLCopen
// Part 1 synchronized motion).  Each coupling is an FbBehaviour whose set-point
// source is advanced once per cycle, after the master has been stepped
// (Axis::master orders the step; docs/motion-sync.md):
//   MC_GearIn     velocity gearing: ramp to ratio x master velocity, then distance-locked;
//   MC_GearInPos  position gearing: an internal quintic cam over the master's start
//                 distance brings the slave to SlaveSyncPosition at MasterSyncPosition;
//   MC_CamIn      a cam table (Cam.h) with offsets, scalings and start modes;
//   MC_Phasing    shifts the master position a coupling sees (a profile of its own);
//   SMC_BacklashCompensation  slave = master + a direction-dependent offset;
//   MC_GearOut / MC_CamOut  end the coupling, the slave keeps its velocity.
#pragma once

#include <cstdint>
#include <memory>

#include "stdlib-motion/core/Cam.h"
#include "stdlib-motion/core/Kernel.h"

namespace stc::motion {

struct GearInputs {
  int64_t numerator = 1;
  int64_t denominator = 1;
  double acceleration = 0, deceleration = 0, jerk = 0;
  BufferMode bufferMode = BufferMode::Aborting;
};
void callGearIn(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const GearInputs& in, const CallCtx& c);

struct GearInPosInputs {
  int64_t numerator = 1;
  int64_t denominator = 1;
  double masterSyncPosition = 0, slaveSyncPosition = 0, masterStartDistance = 0;
  bool avoidReversal = false;
  BufferMode bufferMode = BufferMode::Aborting;
};
void callGearInPos(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const GearInPosInputs& in, const CallCtx& c);

// A cam chosen for a master/slave pair (MC_CamTableSelect): a snapshot of the
// table, shared by the couplings that use it, and how the pair follows it.
struct CamSelection {
  std::shared_ptr<const Cam> cam;
  bool periodic = false, masterAbsolute = false, slaveAbsolute = false;
};

enum class CamStartMode : uint8_t { Absolute = 0, Relative = 1, RampIn = 2, RampInPos = 3, RampInNeg = 4 };
struct CamInInputs {
  CamSelection sel;
  double masterOffset = 0, slaveOffset = 0, masterScaling = 1, slaveScaling = 1;
  CamStartMode startMode = CamStartMode::Absolute;
  double velocityDiff = 0, acceleration = 0, deceleration = 0, jerk = 0;   // ramp_in modes
  double tappetHysteresis = 0;
  BufferMode bufferMode = BufferMode::Aborting;
  // Writes the tappet groups into the FB instance, in the kernel cycle they change
  // (`resets` counts the couplings started, for SMC_GetTappetValue).
  void (*publishTappets)(void* instance, const TappetTracker::Groups& groups, uint32_t resets) = nullptr;
};
// A master or slave scaling of a cam: finite, > 0 and at most 1e9 (else 628 / 640).
inline bool validCamScaling(double s) { return s > 0 && s <= 1e9; }   // NaN fails both

// MC_CamIn: slave = SlaveScaling * CAM(MasterScaling * master + MasterOffset) + SlaveOffset
// (docs/motion-cam.md for the relative modes, start modes and periods).
void callCamIn(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const CamInInputs& in, const CallCtx& c);

// The slave state the cam gives for the master state m in absolute coordinates
// (SMC_GetCamSlaveSetPosition); false when a non-periodic cam does not reach m.
bool camSlaveState(const CamSelection& sel, double masterOffset, double slaveOffset, double masterScaling, double slaveScaling,
                   const Kinematic& m, Kinematic& out);

// MC_GearOut (kinds: GearIn, GearInPos) and MC_CamOut (CamIn, Follow): Done in the edge's call.
void callCouplingOut(Kernel& k, FbSlot& fb, Axis& slave, bool execute, bool cam, const CallCtx& c);

struct PhasingInputs {
  double phaseShift = 0, velocity = 0, acceleration = 0, deceleration = 0, jerk = 0;
};
void callPhasing(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const PhasingInputs& in, const CallCtx& c);

// SMC_BacklashCompensation: slave = master + an offset of +-backlash chosen by the
// master's direction (or forced), moved with the compensation dynamics.
enum class BacklashMode : uint8_t { Auto = 0, Positive = 1, Negative = 2, Off = 3 };
enum class BacklashStart : uint8_t { None = 0, Negative = 1, Positive = 2 };
struct BacklashInputs {
  double backlash = 0, velocity = 0, acceleration = 0, deceleration = 0, jerk = 0;
  BacklashMode mode = BacklashMode::Auto;
  BacklashStart start = BacklashStart::None;
};
void callBacklash(Kernel& k, FbSlot& fb, Axis& master, Axis& slave, bool execute, const BacklashInputs& in, const CallCtx& c);

// What a master gives its followers: the set state, or the actual one of an encoder axis.
Kinematic masterState(const Axis& master);
// The master position, velocity and acceleration a coupling of `slave` sees this
// cycle: the master's set state minus the phase shift of MC_Phasing.
Kinematic masterSeenBy(const Axis& slave, const Axis& master, int64_t nowNs);

// True when making `slave` follow `master` would close a loop of couplings.
bool couplingLoop(const Axis& master, const Axis& slave);

}  // namespace stc::motion
