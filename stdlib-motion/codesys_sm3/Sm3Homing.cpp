// The SoftMotion homing FBs (sm3_homing.st): MC_Home (drive side) and
// SMC_Homing (controller side).  Semantics in core/Homing.cpp.
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/Homing.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

void smcHomingPublish(void* instance, const FbOutputs& o) {
  auto* s = static_cast<sm3::SMC_Homing*>(instance);
  publish<sm3::SMC_Homing>(instance, o);
  FbSlot& slot = kernel().slot(s->__handle, s, FbKind::Home, &smcHomingPublish);
  s->bStartLatchingIndex = smcHomingLatching(slot);
}

void MC_Home(sm3::MC_Home* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) { callHome(k, slotOf(self, FbKind::Home), ax, self->Execute, self->Position, c); });
}

void SMC_Homing(sm3::SMC_Homing* self) {
  CallCtx c = callContext();
  Axis* ax = bind(self->Axis, c);
  if (!ax) {
    FbOutputs o;
    o.error = true;
    o.errorId = Error::NotReadyForMotion;
    smcHomingPublish(self, o);
    return;
  }
  SmcHomingInputs in;
  in.homePosition = self->fHomePosition;
  in.velocitySlow = self->fVelocitySlow;
  in.velocityFast = self->fVelocityFast;
  in.acceleration = self->fAcceleration;
  in.deceleration = self->fDeceleration;
  in.jerk = self->fJerk;
  in.direction = self->nDirection;
  in.referenceSwitch = self->bReferenceSwitch;
  in.signalDelay = self->fSignalDelay;
  in.mode = self->nHomingMode;
  in.returnToZero = self->bReturnToZero;
  in.indexOccured = self->bIndexOccured;
  in.indexPosition = self->fIndexPosition;
  in.ignoreHwLimit = self->bIgnoreHWLimit;
  callSmcHoming(kernel(), kernel().slot(self->__handle, self, FbKind::Home, &smcHomingPublish), *ax, self->bExecute, in, c);
  mirrorAll(*ax);
}

}  // namespace

namespace stc::motion {
void registerLsHomingNatives(MotionLibrary& lib);   // leadshine/LsHoming.cpp
}

namespace stc::motion::sm3face {

void registerSm3HomingNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(MC_Home, MC_Home)
  STC_SM3_NATIVE(SMC_Homing, SMC_Homing)
  registerLsHomingNatives(lib);
}

}  // namespace stc::motion::sm3face
