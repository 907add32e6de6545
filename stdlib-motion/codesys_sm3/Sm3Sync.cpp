// The synchronized-motion blocks of sm3_sync.st: gear in/out, gear in
// position, phasing.  The slave is bound (and owned) like any axis; the
// master is only read (bindMaster).
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/Coupling.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

// The common body of a master/slave block: bind both, refuse (34) when either is missing.
template <class T, class F>
void coupledFb(T* self, F call) {
  CallCtx c = callContext();
  Axis* slave = bind(self->Slave, c);
  Axis* master = slave ? bindMaster(self->Master, c) : nullptr;
  if (refuse(self, master ? slave : nullptr) || rewired(self, *slave, c)) return;
  call(kernel(), *master, *slave, c);
  mirrorCall(*slave);
}

void MC_GearIn(sm3::MC_GearIn* self) {
  coupledFb(self, [&](Kernel& k, Axis& m, Axis& s, const CallCtx& c) {
    GearInputs in;
    in.numerator = self->RatioNumerator;
    in.denominator = self->RatioDenominator;
    in.acceleration = self->Acceleration;
    in.deceleration = self->Deceleration;
    in.jerk = self->Jerk;
    in.bufferMode = bufferModeOf(self->BufferMode);
    callGearIn(k, slotOf(self, FbKind::GearIn), m, s, self->Execute, in, c);
  });
}

void MC_GearInPos(sm3::MC_GearInPos* self) {
  coupledFb(self, [&](Kernel& k, Axis& m, Axis& s, const CallCtx& c) {
    GearInPosInputs in;
    in.numerator = self->RatioNumerator;
    in.denominator = self->RatioDenominator;
    in.masterSyncPosition = self->MasterSyncPosition;
    in.slaveSyncPosition = self->SlaveSyncPosition;
    in.masterStartDistance = self->MasterStartDistance;
    in.avoidReversal = self->AvoidReversal;
    in.bufferMode = bufferModeOf(self->BufferMode);
    callGearInPos(k, slotOf(self, FbKind::GearInPos), m, s, self->Execute, in, c);
  });
}

void MC_GearOut(sm3::MC_GearOut* self) {
  CallCtx c = callContext();
  Axis* slave = bind(self->Slave, c);
  if (refuse(self, slave) || rewired(self, *slave, c)) return;
  callCouplingOut(kernel(), slotOf(self, FbKind::Other), *slave, self->Execute, false, c);
  mirrorCall(*slave);
}

void MC_Phasing(sm3::MC_Phasing* self) {
  coupledFb(self, [&](Kernel& k, Axis& m, Axis& s, const CallCtx& c) {
    PhasingInputs in{self->PhaseShift, self->Velocity, self->Acceleration, self->Deceleration, self->Jerk};
    callPhasing(k, slotOf(self, FbKind::Phasing), m, s, self->Execute, in, c);
  });
}

void SMC_BacklashCompensation(sm3::SMC_BacklashCompensation* self) {
  coupledFb(self, [&](Kernel& k, Axis& m, Axis& s, const CallCtx& c) {
    BacklashInputs in;
    in.backlash = self->fBacklash;
    in.velocity = self->fCompensationVel;
    in.acceleration = self->fCompensationAcc;
    in.deceleration = self->fCompensationDec;
    in.jerk = self->fCompensationJerk;
    in.mode = enumOf<BacklashMode>(self->eBacklashMode, 3);
    in.start = enumOf<BacklashStart>(self->eBacklashStartState, 2);
    callBacklash(k, slotOf(self, FbKind::Backlash), m, s, self->bExecute, in, c);
  });
}

}  // namespace

namespace stc::motion {

void registerSm3SyncNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(MC_GearIn, MC_GearIn)
  STC_SM3_NATIVE(MC_GearInPos, MC_GearInPos)
  STC_SM3_NATIVE(MC_GearOut, MC_GearOut)
  STC_SM3_NATIVE(MC_Phasing, MC_Phasing)
  STC_SM3_NATIVE(SMC_BacklashCompensation, SMC_BacklashCompensation)
}

}  // namespace stc::motion
