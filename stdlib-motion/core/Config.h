// Parameter access and axis configuration: MC_ReadParameter,
// MC_ReadBoolParameter, MC_WriteParameter, MC_WriteBoolParameter,
// SMC_ChangeDynamicLimits, SMC_ChangeGearingRatio, SMC_SetRampType,
// SMC_SetCustomRampType, SMC_SetMovementType, SMC_SetSoftwareLimits.
//
// Positive parameter numbers are axis parameters (PLCopen 1..16 and the
// SoftMotion 1000+ numbers), read from and written to the live axis in the
// call.  Negative numbers address an object of the simulated drive by SDO:
// -(length << 24 | index << 8 | subindex); the transfer happens in the bus
// exchange of the cycle (the kernel step), so Valid/Done rise there.
// Timing, error numbers and decisions: docs/motion-config.md.
#pragma once

#include <cstdint>

#include "stdlib-motion/core/Kernel.h"

namespace stc::motion {

// ---- parameter numbers
enum class ParamType : uint8_t { Bool, Int, Real };

struct AxisParamInfo {
  int32_t number;
  ParamType type;
  bool writable;
  const char* name;          // the AXIS_REF_SM3 member (or the PLCopen name)
};
// The axis parameter with that number; null if there is none.
const AxisParamInfo* axisParameter(int32_t number);

struct SdoAddress {
  uint8_t length = 0;        // 1, 2 or 4 bytes
  uint16_t index = 0;
  uint8_t sub = 0;
};
// -(length << 24 | index << 8 | sub).
int32_t sdoParameterNumber(uint8_t length, uint16_t index, uint8_t sub);
// False if `number` is not negative or its length is not 1, 2 or 4.
bool decodeSdo(int32_t number, SdoAddress& a);

// Axis parameters, at once.  Read: 130 unknown.  Write: 140 unknown, read-only
// or refused (value out of range, wrong axis state), 143 value not representable.
// `intervalNs` is the task cycle (parameter 1025).
Error readAxisParameter(const Axis& ax, int32_t number, double& value, int64_t intervalNs);
Error writeAxisParameter(Axis& ax, int32_t number, double value);
// One SDO transfer with the axis' drive.  Read: 131 (no communication, no such
// object, length mismatch).  Write: 141 (the same, or read-only), 143 (value
// not an integer in the object's range).
Error sdoRead(const Axis& ax, const SdoAddress& a, double& value);
Error sdoWrite(Axis& ax, const SdoAddress& a, double value);

// Axis parameters a vendor face keeps in its axis variable rather than in the
// core (SM3: fSWMaxVelocity 1113, fSWMaxAcceleration 1123, fSWMaxDeceleration
// 1133, fSWMaxJerk 1143; LREAL, >= 0).
class FaceParameters {
public:
  virtual ~FaceParameters() = default;
  virtual bool read(int32_t number, double& value) const = 0;   // false: not one of them
  virtual void write(int32_t number, double value) = 0;
};

// ---- FB calls (the faces copy the ST inputs into these)
// The reading FBs' outputs beyond FbOutputs: Valid and Value (BOOL variants: value 0/1).
struct ParameterState {
  bool valid = false;
  double value = 0;
};
const ParameterState& parameterState(const FbSlot& fb);

// Enable-type: Busy while Enable; an axis parameter is Valid in the call, an SDO
// answer in the kernel step of the cycle (one request per call).
void callReadParameter(Kernel& k, FbSlot& fb, Axis& ax, bool enable, int32_t number, bool asBool, const CallCtx& c,
                       const FaceParameters* face = nullptr);
// Execute-type: an axis parameter is written and Done in the call; an SDO write
// is Busy in the call and Done (or Error 141) in the kernel step of that cycle.
void callWriteParameter(Kernel& k, FbSlot& fb, Axis& ax, bool execute, int32_t number, double value, bool asBool,
                        const CallCtx& c, FaceParameters* face = nullptr);

// Synchronous on the rising edge (Done or Error in the call).
void callChangeDynamicLimits(Kernel& k, FbSlot& fb, Axis& ax, bool execute, double vel, double acc, double dec,
                             double jerk, const CallCtx& c);
void callSetRampType(Kernel& k, FbSlot& fb, Axis& ax, bool execute, int rampType, const CallCtx& c);
// User ramp objects cannot be run by the kernel: 850 in a wrong state, else 851.
void callSetCustomRampType(Kernel& k, FbSlot& fb, Axis& ax, bool execute, bool ramp1Set, bool ramp2Set,
                           const CallCtx& c);
void callSetMovementType(Kernel& k, FbSlot& fb, Axis& ax, bool execute, int movementType, double period,
                         const CallCtx& c);
struct SoftwareLimits {
  bool activated = false;
  double positive = 0, negative = 0;
  bool decelerate = true;
  double deceleration = 0, maxDistance = 0;
};
void callSetSoftwareLimits(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const SoftwareLimits& l, const CallCtx& c);
// Busy in the call; applied (Done) in the kernel step of that cycle if the axis is still not powered.
void callChangeGearingRatio(Kernel& k, FbSlot& fb, Axis& ax, bool execute, uint32_t denom, int32_t num,
                            double period, int movementType, const CallCtx& c);

// ---- configuration changes (also used by the parameter writes)
// New modulo period (0 = linear); the reported position stays where it is.
void setPositionPeriod(Axis& ax, double period);
// New scaling; the drive's position counter (increments) stays where it is.
void setIncrementsPerUnit(Axis& ax, double incrementsPerUnit);

}  // namespace stc::motion
