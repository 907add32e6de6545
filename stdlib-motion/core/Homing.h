// Homing: the CiA402 homing methods a simulated drive runs in homing mode
// (6060h = 6), and the homing FBs of the vendor faces:
//   MC_Home, LS_EtherCATAxis_HomeMove  drive-side: switch the drive to mode 6, start the method
//                                      (controlword bit 4), Done when the drive reports homing attained;
//   SMC_Homing                          controller-side on the application's reference switch input;
//   SMC_Home                            controller-side on the axis's own switches (Leadshine pulse axes).
// Behaviour, timing and decisions: docs/motion-homing.md.
#pragma once

#include <cstdint>

#include "stdlib-motion/core/Kernel.h"
#include "stdlib-motion/core/Trajectory.h"

namespace stc::motion {

// ---------------------------------------------------------------- drive side (CiA402)

// The homing state machine inside a Drive (created on the first cycle in mode 6).
class DriveHoming {
public:
  // The set point of this cycle (called by Drive::cycle before the motor model) ...
  void before(Drive& d, double dt, double& p, double& v, double& a);
  // ... and the sensor events after it.
  void after(Drive& d);
  void leaveMode(Drive& d);     // the drive left mode 6: a running method is interrupted
  void powerOff(Drive& d);      // the power stage went off: likewise
  void setPoint(const Drive& d, double& p, double& v, double& a) const;
  // Statusword bits: 10/12/13 in mode 6 (CiA402 homing table), 15 once homed (vendor bit).
  uint16_t statusBits(const Drive& d) const;

  enum class Status : uint8_t { NotStarted, Running, Attained, Interrupted, Failed };
  Status status() const { return status_; }

private:
  enum class Phase : uint8_t { Idle, Search, Backoff, Approach, Index, Return, Halt };
  void start(Drive& d);
  void fail(Drive& d, bool moving);
  void velocity(double v);
  void reference(Drive& d, double r);
  bool sensor(const Drive& d) const;
  double edge(const Drive& d) const;

  Phase phase_ = Phase::Idle;
  Status status_ = Status::NotStarted;
  bool homed_ = false, prevBit4_ = false, fresh_ = false, failing_ = false, prevS_ = false;
  uint8_t method_ = 0;
  Kinematic sp_;
  bool spValid_ = false;
  Profile prof_;
  double t_ = 0;
  double vFast_ = 0, vSlow_ = 0, acc_ = 0, offset_ = 0;
  int8_t dir_ = 0;       // search direction
  int reversals_ = 0;
  double mark_ = 0;      // the index mark that is the reference (Phase::Index)
};

// ---------------------------------------------------------------- the FBs

// MC_Home: Position becomes 607Ch (whole increments); the method and speeds are the drive's (6098h, 6099h, 609Ah).
void callHome(Kernel& k, FbSlot& fb, Axis& ax, bool execute, double position, const CallCtx& c);

// LS_EtherCATAxis_HomeMove: writes 6098h, 6099h:01/02, 609Ah, 607Ch (drive units) at the rising
// edge, then homes like MC_Home.  bExecute is level-held: released before Done it interrupts the
// homing (CommandAborted once the drive is at rest).
struct DriveHomeParams {
  int64_t method = 21, fastVel = 500, slowVel = 100, acc = 1000, homePos = 0, axisNo = 0;
};
void callDriveHomeMove(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const DriveHomeParams& p, const CallCtx& c);

// SMC_Homing (controller side, SMC_HOMING_MODE).
struct SmcHomingInputs {
  double homePosition = 0, velocitySlow = 0, velocityFast = 0, acceleration = 0, deceleration = 0, jerk = 0;
  int direction = -1;          // MC_Direction: negative / positive
  double signalDelay = 0;      // [s]
  int mode = 0;                // SMC_HOMING_MODE: 0, 1, 2, 4, 5, 6
  bool returnToZero = false, ignoreHwLimit = false;
  // Read in every call:
  bool referenceSwitch = true; // TRUE = open (not on the switch)
  bool indexOccured = false;
  double indexPosition = 0;
};
void callSmcHoming(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const SmcHomingInputs& in, const CallCtx& c);
// bStartLatchingIndex of an SMC_Homing slot.
bool smcHomingLatching(const FbSlot& fb);

// SMC_Home (Leadshine, controller side on the axis's home switch, index pulse and limits).
struct SmcHomeInputs {
  bool stop = false;
  double velocityFast = 1000, velocitySlow = 100, acceleration = 1000, deceleration = 1000, jerk = 9e7;
  int direction = 1;
  double homePosition = 0;
  int completeMode = 0;        // bHomeCompleteMode 0, 1, 2
  int mode = 0;                // imode 0, 1, 2, 6, 7, 8, 9, 10
  bool limitsEnable = true;    // iHomeElEnable
  bool limitDecelerate = false;// bELStopMode: FALSE emergency stop, TRUE decelerate
  int64_t driverCounter = 200; // cycles to wait for the drive to settle
};
void callSmcHome(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const SmcHomeInputs& in, const CallCtx& c);

}  // namespace stc::motion
