// The SoftMotion face of the diagnostic, FB-error, touch-probe and cam-switch
// blocks of sm3_diag.st.  Semantics: core/Diag.h; docs/motion-diag.md.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/Diag.h"
#include "vm/FileSandbox.h"

#include <unistd.h>

using namespace stc::motion;
using namespace stc::motion::sm3face;
namespace diag = stc::motion::diag;

namespace {

int16_t id(Error e) { return static_cast<int16_t>(smcError(e)); }

sm3::AXIS_REF_SM3* refOf(void* p) { return static_cast<sm3::AXIS_REF_SM3*>(p); }

// The type name of an ST FB instance (the first entry of its vtable), "" if unknown.
const char* typeNameOf(const void* instance) {
  if (!instance) return "";
  const void* vtable = *static_cast<const void* const*>(instance);
  if (!vtable) return "";
  const char* name = *static_cast<const char* const*>(vtable);
  return name ? name : "";
}

template <size_t N>
void copyString(char (&dst)[N], const std::string& s) {
  const size_t n = std::min(N - 1, s.size());
  std::memcpy(dst, s.data(), n);
  dst[n] = 0;
}

// Enable-type FBs: the axis, or the outputs of a refused call (error 34) and null.
template <class T>
Axis* enableAxis(T* self, bool enable, CallCtx& c) {
  c = callContext();
  if (!enable) return nullptr;
  return bind(refOf(self->Axis), c);
}

void SMC_CheckLimits(sm3::SMC_CheckLimits* self) {
  CallCtx c;
  Axis* ax = enableAxis(self, self->bEnable, c);
  diag::CheckLimitsOut o;
  if (self->bEnable && !ax) {
    o.error = true;
    o.errorId = Error::NotReadyForMotion;
  } else if (ax) {
    const sm3::AXIS_REF_SM3* r = refOf(self->Axis);
    o = diag::checkLimits(*ax, true, self->bCheckVel, self->bCheckAccDec,
                          diag::SwMax{r->fSWMaxVelocity, r->fSWMaxAcceleration, r->fSWMaxDeceleration});
    if (o.error && !(self->bError && self->iErrorID == id(o.errorId))) {
      FbSlot& s = slotOf(self, FbKind::Diagnostic);
      s.axis = ax;
      kernel().noteFbError(s, o.errorId, c.nowNs);
    }
  }
  self->bBusy = o.busy;
  self->bError = o.error;
  self->iErrorID = id(o.errorId);
  self->bLimitsExceeded = o.exceeded;
}

// Records an Enable FB's error on its axis (SMC_ReadFBError) when it appears (not again in every call).
template <class T>
void note(T* self, Axis* ax, const diag::EnableOut& o, const CallCtx& c) {
  if (!ax || !o.error || (self->bError && self->nErrorID == id(o.errorId))) return;
  FbSlot& s = slotOf(self, FbKind::Diagnostic);
  s.axis = ax;
  kernel().noteFbError(s, o.errorId, c.nowNs);
}

void SMC_InPosition(sm3::SMC_InPosition* self) {
  CallCtx c;
  Axis* ax = enableAxis(self, self->bEnable, c);
  diag::InPositionOut o;
  FbSlot& s = slotOf(self, FbKind::Diagnostic);
  if (self->bEnable && !ax) {
    o.error = true;
    o.errorId = Error::NotReadyForMotion;
  } else if (ax) {
    o = diag::callInPosition(s, ax, {true, self->fPosWindow, self->fPosTime, self->fTimeOut}, c);
    note(self, ax, o, c);
    self->fCurrentDistance = o.distance;
  } else {
    diag::callInPosition(s, nullptr, {}, c);
  }
  self->bBusy = o.busy;
  self->bInPosition = o.inPosition;
  self->bTimeOut = o.timeOut;
  self->bError = o.error;
  self->nErrorID = id(o.errorId);
}

template <class T>
void getMax(T* self, diag::MaxOf what) {
  CallCtx c;
  Axis* ax = enableAxis(self, self->bEnable, c);
  FbSlot& s = slotOf(self, FbKind::Diagnostic);
  diag::MaxOut o;
  if (self->bEnable && !ax) {
    o.error = true;
    o.errorId = Error::NotReadyForMotion;
  } else {
    o = diag::callGetMax(s, ax, what, self->bEnable, self->dwTimeStamp, self->bResetMax);
  }
  self->bValid = self->bBusy = o.busy;
  self->bError = o.error;
  self->nErrorID = id(o.errorId);
  if (o.busy) self->dwTimeAtMax = o.timeAtMax;
  if constexpr (requires { self->fMaxVelocity; }) {
    if (o.busy) self->fMaxVelocity = o.max;
  } else {
    if (o.busy) self->fMaxAcceleration = o.max;
  }
}

void SMC_GetMaxSetVelocity(sm3::SMC_GetMaxSetVelocity* self) { getMax(self, diag::MaxOf::Velocity); }
void SMC_GetMaxSetAccDec(sm3::SMC_GetMaxSetAccDec* self) { getMax(self, diag::MaxOf::AccDec); }

void SMC_GetTrackingError(sm3::SMC_GetTrackingError* self) {
  CallCtx c;
  Axis* ax = enableAxis(self, self->bEnable, c);
  FbSlot& s = slotOf(self, FbKind::Diagnostic);
  diag::TrackingOut o;
  if (self->bEnable && !ax) {
    o.error = true;
    o.errorId = Error::NotReadyForMotion;
  } else {
    o = diag::callTrackingError(s, ax, self->bEnable, self->byDeadTimeCycles, self->dwTimeStamp, self->bResetMax);
  }
  self->bValid = self->bBusy = o.busy;
  self->bError = o.error;
  self->nErrorID = id(o.errorId);
  if (o.busy) {
    self->fActTrackingError = o.actual;
    self->fMaxTrackingError = o.max;
    self->dwTimeAtMax = o.timeAtMax;
  }
}

void SMC_MeasureDistance(sm3::SMC_MeasureDistance* self) {
  CallCtx c = callContext();
  Axis* ax = bind(refOf(self->Axis), c);
  if (!ax) {
    self->bBusy = false;
    self->bError = true;
    self->nErrorID = id(Error::NotReadyForMotion);
    return;
  }
  diag::MeasureOut o = diag::callMeasureDistance(slotOf(self, FbKind::Diagnostic), *ax, self->bExecute);
  self->bBusy = o.busy;
  self->bError = false;
  self->nErrorID = 0;
  self->fDistance = o.distance;
  mirrorAll(*ax);
}

void SMC_CheckAxisCommunication(sm3::SMC_CheckAxisCommunication* self) {
  CallCtx c;
  Axis* ax = enableAxis(self, self->bEnable, c);
  diag::ComOut o;
  if (self->bEnable && !ax) {
    o.error = true;
    o.errorId = Error::NotReadyForMotion;
  } else if (ax) {
    o = diag::checkCommunication(*ax, true);
  }
  self->bValid = o.valid;
  self->bError = o.error;
  self->eErrorID = id(o.errorId);
  self->bOperational = o.operational;
  self->eComState = static_cast<decltype(self->eComState)>(o.state);
  self->wComState = o.valid ? refOf(self->Axis)->wCommunicationState : 0;
}

void SMC_ReadFBError(sm3::SMC_ReadFBError* self) {
  CallCtx c;
  Axis* ax = enableAxis(self, self->bEnable, c);
  diag::FbErrorOut o;
  if (self->bEnable && !ax) {
    o.error = true;
    o.errorId = Error::NotReadyForMotion;
  } else if (ax) {
    o = diag::readFbError(*ax, true);
  }
  self->bValid = self->bBusy = o.busy;
  self->bError = o.error;
  self->nErrorID = id(o.errorId);
  if (!o.busy) return;   // values keep the last ones
  self->bFBError = o.record.set;
  self->nFBErrorID = id(o.record.id);
  self->pbyErrorInstance = const_cast<void*>(o.record.instance);
  copyString(self->strErrorInstance, typeNameOf(o.record.instance));
  self->tTimeStamp = o.record.atNs;
}

bool SMC_ClearFBError(void* pDrive) {
  if (!pDrive) return false;
  CallCtx c = callContext();
  Axis* ax = bind(refOf(pDrive), c);
  if (!ax) return false;
  const bool ok = diag::clearFbError(*ax);
  mirrorAll(*ax);
  return ok;
}

void SMC_ErrorString(char* result, int16_t errorId) {
  const std::string s = errorString(static_cast<uint16_t>(errorId));
  const size_t n = std::min<size_t>(255, s.size());
  std::memcpy(result, s.data(), n);
  result[n] = 0;
}

// ---- the diagnostic log
void publishLog(void* instance, const FbOutputs& o) {
  auto* s = static_cast<sm3::SMC_AxisDiagnosticLog*>(instance);
  publish<sm3::SMC_AxisDiagnosticLog>(instance, o);
  FbSlot& slot = kernel().slot(s->__handle, s, FbKind::Diagnostic, &publishLog);
  auto* log = dynamic_cast<diag::DiagnosticLog*>(slot.behaviour.get());
  s->bRecording = o.busy && log && log->recording;
}

void SMC_AxisDiagnosticLog(sm3::SMC_AxisDiagnosticLog* self) {
  CallCtx c = callContext();
  Axis* ax = bind(refOf(self->Axis), c);
  if (!ax) {
    FbOutputs o;
    o.error = true;
    o.errorId = Error::NotReadyForMotion;
    publishLog(self, o);
    return;
  }
  FbSlot& s = kernel().slot(self->__handle, self, FbKind::Diagnostic, &publishLog);
  diag::LogConfig cfg;
  cfg.fileName = self->sFileName;
  // Inside the data directory only (vm/FileSandbox.h): an absolute name, a '..' escape or a
  // link out of it cannot be opened (2100 at the first WriteToFile, like any open failure).
  cfg.open = [dir = MotionSession::current().filesDir(), name = cfg.fileName]() -> std::FILE* {
    std::string why;
    const int fd = stc::vm::openInside(dir, name, stc::vm::FileAccess::Write, why);
    if (fd < 0) return nullptr;
    std::FILE* f = ::fdopen(fd, "wb");
    if (!f) ::close(fd);
    return f;
  };
  cfg.setPosition = self->bSetPosition;
  cfg.actPosition = self->bActPosition;
  cfg.setVelocity = self->bSetVelocity;
  cfg.actVelocity = self->bActVelocity;
  cfg.setAcceleration = self->bSetAcceleration;
  cfg.actAcceleration = self->bActAcceleration;
  cfg.separator = static_cast<char>(self->bySeparatorChar);
  cfg.recordEnd = self->sRecordSeparatorString[0] ? std::string(self->sRecordSeparatorString) : std::string("\n");
  cfg.mode = self->eMode == 1 ? diag::LogMode::AtClose : diag::LogMode::Continuous;
  diag::callDiagnosticLog(kernel(), s, *ax, self->bExecute, self->bCloseFile, cfg, c);
  publishLog(self, s.out);
  mirrorAll(*ax);
}

void SMC_AxisDiagnosticLog_WriteToFile(sm3::SMC_AxisDiagnosticLog* self) {
  if (!self->__handle) return;   // never executed
  diag::writeToFile(kernel().slot(self->__handle, self, FbKind::Diagnostic, &publishLog));
}

// ---- touch probe
diag::TriggerRef triggerOf(void* p) {
  diag::TriggerRef t;
  auto* r = static_cast<sm3::TRIGGER_REF*>(p);
  if (!r) return t;
  t.id = r;
  t.number = r->iTriggerNumber;
  t.fast = r->bFastLatching;
  t.input = &r->bInput;
  t.active = &r->bActive;
  return t;
}

void publishProbe(void* instance, const FbOutputs& o) {
  auto* s = static_cast<sm3::MC_TouchProbe*>(instance);
  publish<sm3::MC_TouchProbe>(instance, o);
  FbSlot& slot = kernel().slot(s->__handle, s, FbKind::Probe, &publishProbe);
  s->RecordedPosition = diag::recordedPosition(slot);
}

void MC_TouchProbe(sm3::MC_TouchProbe* self) {
  CallCtx c = callContext();
  Axis* ax = bind(refOf(self->Axis), c);
  if (refuse(self, ax)) return;
  if (!self->TriggerInput) {
    FbOutputs o;
    o.error = true;
    o.errorId = Error::TpCommError;
    publish<sm3::MC_TouchProbe>(self, o);
    return;
  }
  FbSlot& s = kernel().slot(self->__handle, self, FbKind::Probe, &publishProbe);
  diag::callTouchProbe(kernel(), s, *ax, self->Execute, triggerOf(self->TriggerInput),
                       {self->WindowOnly, self->FirstPosition, self->LastPosition}, c);
  publishProbe(self, s.out);
  mirrorAll(*ax);
}

void MC_AbortTrigger(sm3::MC_AbortTrigger* self) {
  CallCtx c = callContext();
  Axis* ax = bind(refOf(self->Axis), c);
  if (refuse(self, ax)) return;
  FbSlot& s = slotOf(self, FbKind::Probe);
  diag::callAbortTrigger(kernel(), s, *ax, self->Execute, triggerOf(self->TriggerInput), c);
  s.sync();
  mirrorAll(*ax);
}

// ---- cam switch
void MC_DigitalCamSwitch(sm3::MC_DigitalCamSwitch* self) {
  CallCtx c = callContext();
  Axis* ax = bind(refOf(self->Axis), c);
  if (!ax) {
    self->InOperation = self->Busy = false;
    self->Error = true;
    self->ErrorID = id(Error::NotReadyForMotion);
    return;
  }
  FbSlot& s = slotOf(self, FbKind::CamSwitch);
  const bool rising = self->Enable && !s.execute;
  std::vector<diag::CamSwitch> switches;
  diag::TrackOption options[diag::kTracks];
  auto* sw = static_cast<sm3::MC_CAMSWITCH_REF*>(self->Switches);
  auto* tracks = static_cast<sm3::MC_TRACK_REF*>(self->TrackOptions);
  auto* outs = static_cast<sm3::MC_OUTPUT_REF*>(self->Outputs);
  if (rising) {
    if (sw && sw->CamSwitchPtr) {
      const auto* tr = static_cast<const sm3::MC_CAMSWITCH_TR*>(sw->CamSwitchPtr);
      for (int i = 0; i < sw->NoOfSwitches; ++i)
        switches.push_back({tr[i].TrackNumber, tr[i].FirstOnPosition, tr[i].LastOnPosition, tr[i].AxisDirection,
                            tr[i].CamSwitchMode, tr[i].Duration});
    }
    if (tracks)
      for (int t = 0; t < diag::kTracks; ++t)
        options[t] = {tracks->Track[t].OnCompensation, tracks->Track[t].OffCompensation, tracks->Track[t].Hysteresis};
  }
  diag::CamSwitchOut o = diag::callDigitalCamSwitch(kernel(), s, *ax, self->Enable, rising ? &switches : nullptr, options,
                                                    outs ? outs->Track : nullptr, self->EnableMask,
                                                    enumOf<diag::TappetMode>(self->TappetMode, 2), c);
  if (o.error && rising) {
    s.axis = ax;
    kernel().noteFbError(s, o.errorId, c.nowNs);
  }
  self->InOperation = o.inOperation;
  self->Busy = o.busy;
  self->Error = o.error;
  self->ErrorID = id(o.errorId);
  self->SwitchCorrupted = o.corrupted;
  mirrorAll(*ax);
}

}  // namespace

namespace stc::motion::sm3face {

void registerSm3DiagNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(SMC_CheckLimits, SMC_CheckLimits)
  STC_SM3_NATIVE(SMC_InPosition, SMC_InPosition)
  STC_SM3_NATIVE(SMC_GetMaxSetVelocity, SMC_GetMaxSetVelocity)
  STC_SM3_NATIVE(SMC_GetMaxSetAccDec, SMC_GetMaxSetAccDec)
  STC_SM3_NATIVE(SMC_GetTrackingError, SMC_GetTrackingError)
  STC_SM3_NATIVE(SMC_MeasureDistance, SMC_MeasureDistance)
  STC_SM3_NATIVE(SMC_CheckAxisCommunication, SMC_CheckAxisCommunication)
  STC_SM3_NATIVE(SMC_ReadFBError, SMC_ReadFBError)
  STC_SM3_NATIVE(SMC_ClearFBError, SMC_ClearFBError)
  STC_SM3_NATIVE(SMC_ErrorString, SMC_ErrorString)
  STC_SM3_NATIVE(SMC_AxisDiagnosticLog, SMC_AxisDiagnosticLog)
  STC_SM3_NATIVE(SMC_AxisDiagnosticLog_WriteToFile, SMC_AxisDiagnosticLog_WriteToFile)
  STC_SM3_NATIVE(MC_TouchProbe, MC_TouchProbe)
  STC_SM3_NATIVE(MC_AbortTrigger, MC_AbortTrigger)
  STC_SM3_NATIVE(MC_DigitalCamSwitch, MC_DigitalCamSwitch)
}

}  // namespace stc::motion::sm3face
