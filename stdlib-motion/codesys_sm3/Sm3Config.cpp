// The CODESYS SoftMotion face of the parameter and configuration FBs
// (sm3_config.st): inputs into stdlib-motion/core/Config.h, outputs back.
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/Config.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

// FbOutputs plus the Valid/Value of the parameter readers.
template <class T>
void publishConfig(void* instance, const FbOutputs& o) {
  publish<T>(instance, o);
  T* s = static_cast<T*>(instance);
  if constexpr (requires { s->Valid; }) {
    const ParameterState& st = parameterState(kernel().slot(s->__handle, s, FbKind::Parameter, &publishConfig<T>));
    s->Valid = st.valid;
    s->Value = static_cast<decltype(s->Value)>(st.value);
  }
}

template <class T>
FbSlot& configSlot(T* self, FbKind kind) {
  return kernel().slot(self->__handle, self, kind, &publishConfig<T>);
}

// fSWMax* live in AXIS_REF_SM3 only (the kernel does not use them); 1031 is the
// axis error as its SMC_ERROR number.
class Sm3Parameters : public FaceParameters {
public:
  Sm3Parameters(sm3::AXIS_REF_SM3* r, const Axis& a) : ref(r), ax(a) {}
  bool read(int32_t n, double& v) const override {
    if (n == 1031) {
      v = smcError(ax.error());
      return true;
    }
    double* p = field(n);
    if (!p) return false;
    v = *p;
    return true;
  }
  void write(int32_t n, double v) override {
    if (double* p = field(n)) *p = v;
  }

private:
  double* field(int32_t n) const {
    switch (n) {
      case 1113: return &ref->fSWMaxVelocity;
      case 1123: return &ref->fSWMaxAcceleration;
      case 1133: return &ref->fSWMaxDeceleration;
      case 1143: return &ref->fSWMaxJerk;
      default: return nullptr;
    }
  }
  sm3::AXIS_REF_SM3* ref;
  const Axis& ax;
};

template <class T>
void readParameter(T* self, bool asBool) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    Sm3Parameters face(self->Axis, ax);
    callReadParameter(k, configSlot(self, FbKind::Parameter), ax, self->Enable, self->ParameterNumber, asBool, c, &face);
  });
}

template <class T>
void writeParameter(T* self, bool asBool) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    Sm3Parameters face(self->Axis, ax);
    callWriteParameter(k, configSlot(self, FbKind::Parameter), ax, self->Execute, self->ParameterNumber,
                       static_cast<double>(self->Value), asBool, c, &face);
  });
}

void MC_ReadParameter(sm3::MC_ReadParameter* self) { readParameter(self, false); }
void MC_ReadBoolParameter(sm3::MC_ReadBoolParameter* self) { readParameter(self, true); }
void MC_WriteParameter(sm3::MC_WriteParameter* self) { writeParameter(self, false); }
void MC_WriteBoolParameter(sm3::MC_WriteBoolParameter* self) { writeParameter(self, true); }

void SMC_ChangeDynamicLimits(sm3::SMC_ChangeDynamicLimits* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    callChangeDynamicLimits(k, configSlot(self, FbKind::Config), ax, self->bExecute, self->fMaxVelocity,
                            self->fMaxAcceleration, self->fMaxDeceleration, self->fMaxJerk, c);
  });
}

void SMC_ChangeGearingRatio(sm3::SMC_ChangeGearingRatio* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    callChangeGearingRatio(k, configSlot(self, FbKind::Config), ax, self->bExecute, self->dwRatioTechUnitsDenom,
                           self->iRatioTechUnitsNum, self->fPositionPeriod, static_cast<int>(self->iMovementType), c);
  });
}

void SMC_SetRampType(sm3::SMC_SetRampType* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    callSetRampType(k, configSlot(self, FbKind::Config), ax, self->bExecute, static_cast<int>(self->eRampType), c);
  });
}

void SMC_SetCustomRampType(sm3::SMC_SetCustomRampType* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    callSetCustomRampType(k, configSlot(self, FbKind::Config), ax, self->bExecute, self->iRampType1.self != nullptr,
                          self->iRampType2.self != nullptr, c);
  });
}

void SMC_SetMovementType(sm3::SMC_SetMovementType* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    callSetMovementType(k, configSlot(self, FbKind::Config), ax, self->bExecute, self->iMovementType,
                        self->fPositionPeriod, c);
  });
}

void SMC_SetSoftwareLimits(sm3::SMC_SetSoftwareLimits* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    SoftwareLimits l;
    l.activated = self->SWL_Activated;
    l.positive = self->SWL_Positive;
    l.negative = self->SWL_Negative;
    l.decelerate = self->SWL_Error_Decelerate;
    l.deceleration = self->SWL_Error_Deceleration;
    l.maxDistance = self->SWL_Error_MaxDistance;
    callSetSoftwareLimits(k, configSlot(self, FbKind::Config), ax, self->bExecute, l, c);
  });
}

}  // namespace

namespace stc::motion {

void registerSm3ConfigNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(MC_ReadParameter, MC_ReadParameter)
  STC_SM3_NATIVE(MC_ReadBoolParameter, MC_ReadBoolParameter)
  STC_SM3_NATIVE(MC_WriteParameter, MC_WriteParameter)
  STC_SM3_NATIVE(MC_WriteBoolParameter, MC_WriteBoolParameter)
  STC_SM3_NATIVE(SMC_ChangeDynamicLimits, SMC_ChangeDynamicLimits)
  STC_SM3_NATIVE(SMC_ChangeGearingRatio, SMC_ChangeGearingRatio)
  STC_SM3_NATIVE(SMC_SetRampType, SMC_SetRampType)
  STC_SM3_NATIVE(SMC_SetCustomRampType, SMC_SetCustomRampType)
  STC_SM3_NATIVE(SMC_SetMovementType, SMC_SetMovementType)
  STC_SM3_NATIVE(SMC_SetSoftwareLimits, SMC_SetSoftwareLimits)
}

}  // namespace stc::motion
