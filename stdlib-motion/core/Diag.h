// Diagnostics, FB errors, touch probe and cam switch (docs/motion-diag.md):
// the semantics of SMC_CheckLimits, SMC_InPosition, SMC_GetMaxSet*,
// SMC_GetTrackingError, SMC_MeasureDistance, SMC_AxisDiagnosticLog,
// SMC_CheckAxisCommunication, SMC_ReadFBError / SMC_ClearFBError /
// SMC_ErrorString, MC_TouchProbe, MC_AbortTrigger and MC_DigitalCamSwitch.
// The faces copy the ST inputs in and the results out; state that must
// survive between calls lives in the FB slot's behaviour.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "stdlib-motion/core/Kernel.h"

namespace stc::motion::diag {

// The result of an Enable-type FB call (outputs refreshed in every call).
struct EnableOut {
  bool busy = false;    // Busy and Valid: Enable TRUE and no error
  bool error = false;
  Error errorId = Error::None;
};

// Bad numeric inputs of the diagnostic FBs (no value in the manuals): SMC_WP_PARAM_INVALID.
constexpr Error kBadInput = Error::WriteParamInvalid;

// ---- SMC_CheckLimits: the set values of the latest kernel step against Axis.fSWMax*.
struct SwMax { double velocity = 0, acceleration = 0, deceleration = 0; };
struct CheckLimitsOut : EnableOut { bool exceeded = false; };
CheckLimitsOut checkLimits(const Axis& ax, bool enable, bool checkVel, bool checkAccDec, const SwMax& lim);

// Signed set acceleration: + while |v| grows (or from rest), - while it falls.
double signedAcceleration(const Kinematic& k);

// ---- SMC_InPosition (the monitors take a null axis while disabled)
struct InPositionIn { bool enable = false; double window = 0, posTime = 0, timeOut = 0; };
struct InPositionOut : EnableOut { bool inPosition = false, timeOut = false; double distance = 0; };
InPositionOut callInPosition(FbSlot& fb, const Axis* ax, const InPositionIn& in, const CallCtx& c);

// ---- SMC_GetMaxSetVelocity / SMC_GetMaxSetAccDec / SMC_GetTrackingError
enum class MaxOf : uint8_t { Velocity, AccDec };
struct MaxOut : EnableOut { double max = 0; uint32_t timeAtMax = 0; };
MaxOut callGetMax(FbSlot& fb, const Axis* ax, MaxOf what, bool enable, uint32_t timeStamp, bool resetMax);
struct TrackingOut : MaxOut { double actual = 0; };
TrackingOut callTrackingError(FbSlot& fb, const Axis* ax, bool enable, uint8_t deadTimeCycles, uint32_t timeStamp, bool resetMax);

// ---- SMC_MeasureDistance: actual distance (unwrapped) since the rising edge of bExecute.
struct MeasureOut { bool busy = false, error = false; Error errorId = Error::None; double distance = 0; };
MeasureOut callMeasureDistance(FbSlot& fb, Axis& ax, bool execute);

// ---- SMC_CheckAxisCommunication
enum class ComState : uint16_t { NotStarted = 0, Operational = 100, Error = 200 };
struct ComOut { bool valid = false, error = false, operational = false; Error errorId = Error::None; ComState state = ComState::NotStarted; };
ComOut checkCommunication(const Axis& ax, bool enable);

// ---- SMC_ReadFBError / SMC_ClearFBError / SMC_ErrorString
struct FbErrorOut : EnableOut { FbErrorRecord record; };
FbErrorOut readFbError(const Axis& ax, bool enable);
bool clearFbError(Axis& ax);              // false while the axis is in errorstop (the record stays)
// (SMC_ErrorString's texts are the SM3 face's: codesys_sm3/Sm3ErrorText.h.)

// ---- SMC_AxisDiagnosticLog
enum class LogMode : uint8_t { Continuous = 0, AtClose = 1 };
struct LogConfig {
  std::string fileName;
  // Opens the log file (truncated) at the first WriteToFile; null when it cannot.  The faces
  // open inside the data directory (vm/FileSandbox.h); without it fileName is opened as is
  // (the core's own tests).
  std::function<std::FILE*()> open;
  bool setPosition = false, actPosition = false, setVelocity = false, actVelocity = false,
       setAcceleration = false, actAcceleration = false;
  char separator = '\t';
  std::string recordEnd = "\r\n";
  LogMode mode = LogMode::Continuous;
};
struct LogOut { bool done = false, busy = false, error = false, recording = false; Error errorId = Error::None; };
class DiagnosticLog : public FbBehaviour {
public:
  static constexpr size_t kBufferSize = 10 * 1024;
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}   // never in control of the axis
  void afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override;
  LogConfig cfg;
  std::string buffer;           // records not yet written
  bool recording = false, closeRequested = false, fileOpen = false, closed = false;
  Error ioError = Error::None;   // set by writeToFile, published by the next kernel step
  double prevActVelocity = 0;
  bool havePrev = false;
  std::FILE* file = nullptr;
  ~DiagnosticLog() override;
};
// The FB call (owning task): rising edge starts recording, bCloseFile ends it.
void callDiagnosticLog(Kernel& k, FbSlot& fb, Axis& ax, bool execute, bool closeFile, const LogConfig& cfg, const CallCtx& c);
// The action WriteToFile (any task): writes the buffer; closes the file once closing was requested.
void writeToFile(FbSlot& fb);

// ---- MC_TouchProbe / MC_AbortTrigger
struct TriggerRef {
  const void* id = nullptr;       // the TRIGGER_REF variable
  int16_t number = -1;            // drive channel (fast latching): 0/1 probe 1 rise/fall, 2/3 probe 2 rise/fall
  bool fast = true;               // latched by the drive (exact) / by the controller from *input
  const bool* input = nullptr;    // bInput (controller mode), read in every kernel step
  bool* active = nullptr;         // bActive: TRUE while armed
};
struct ProbeIn { bool windowOnly = false; double first = 0, last = 0; };
class TouchProbe : public FbBehaviour {
public:
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}   // never in control of the axis
  void afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override;
  TriggerRef trig;
  ProbeIn in;
  bool armed = false, prevInput = false;
  double prevAct = 0;
  double recorded = 0;            // RecordedPosition (reported: modulo axes in [0, period))
  bool sameTrigger(const TriggerRef& t) const;
};
void callTouchProbe(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const TriggerRef& trig, const ProbeIn& in, const CallCtx& c);
void callAbortTrigger(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const TriggerRef& trig, const CallCtx& c);
// RecordedPosition of a probe slot (0 before the first latch).
double recordedPosition(const FbSlot& fb);

// ---- MC_DigitalCamSwitch
struct CamSwitch {
  int16_t track = 0;              // 1..32
  double first = 0, last = 0;
  int16_t direction = 0;          // 0 both, 1 positive, -1 or 2 negative
  int16_t mode = 0;               // 0 position, 1 time (OFF after duration)
  int64_t durationNs = 0;
};
struct TrackOption { double onCompensation = 0, offCompensation = 0, hysteresis = 0; };
enum class TappetMode : uint8_t { Auto = 0, Demand = 1, Actual = 2 };
constexpr int kTracks = 32;
class DigitalCamSwitch : public FbBehaviour {
public:
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}   // never in control of the axis
  void afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) override;
  std::vector<CamSwitch> switches;   // copied at the rising edge of Enable
  TrackOption options[kTracks];
  bool* outputs = nullptr;           // MC_OUTPUT_REF.Track[1..32]
  uint32_t mask = 0xFFFFFFFF;
  TappetMode tappet = TappetMode::Auto;
  bool enabled = false;
  Error error = Error::None;         // of the latest Enable edge
  double prevPos = 0;                // position of the latest evaluation (unwrapped)
  int64_t lastNs = 0;                // its time
  double turnPos[kTracks] = {};      // per track: extreme since the last direction change
  int dir[kTracks] = {};             // per track: +1 / -1 (with hysteresis), 0 before the first movement
  std::vector<int64_t> timedOffNs;   // per switch: time-based OFF instant (0 = off)
  int16_t corrupted = -1;            // SwitchCorrupted
  void evaluate(Axis& ax, int64_t nowNs, bool first);
};
struct CamSwitchOut { bool inOperation = false, busy = false, error = false; Error errorId = Error::None; int16_t corrupted = -1; };
CamSwitchOut callDigitalCamSwitch(Kernel& k, FbSlot& fb, Axis& ax, bool enable, const std::vector<CamSwitch>* switches,
                                  const TrackOption* options, bool* outputs, uint32_t mask, TappetMode tappet, const CallCtx& c);

}  // namespace stc::motion::diag
