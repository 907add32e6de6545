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

// The master position, velocity and acceleration a coupling of `slave` sees this
// cycle: the master's set state minus the phase shift of MC_Phasing.
Kinematic masterSeenBy(const Axis& slave, const Axis& master, int64_t nowNs);

// True when making `slave` follow `master` would close a loop of couplings.
bool couplingLoop(const Axis& master, const Axis& slave);

}  // namespace stc::motion
