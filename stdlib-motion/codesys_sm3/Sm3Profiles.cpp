// SM3 face of the profile tables, direct set points, torque and controller mode
// (sm3_profiles.st); the semantics are in core/Profiles.* (docs/motion-profiles.md).
#include <algorithm>
#include <cmath>
#include <vector>

#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/Profiles.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

// The first ArraySize points of a table, read on the rising edge only.
template <class T, class Table, class Get>
void profileBody(T* self, const Table* table, bool execute, TableKind kind, double scale, Get get) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    FbSlot& fb = slotOf(self, FbKind::Profile);
    std::vector<RawPoint> pts;
    bool absolute = true;
    if (execute && !fb.execute && table) {
      absolute = table->IsAbsolute;
      const int n = std::clamp<int>(self->ArraySize, 0, 100);
      for (int i = 0; i < n; ++i) pts.push_back(get(*table, i));
    }
    callProfile(k, fb, ax, execute, kind, self->ArraySize, pts, absolute, scale, self->Offset, c);
  });
}

void MC_PositionProfile(sm3::MC_PositionProfile* self) {
  profileBody(self, self->TimePosition, self->Execute, TableKind::Position, self->PositionScale,
              [](const sm3::MC_TP_REF& t, int i) { return RawPoint{t.MC_TP_Array[i].delta_time, t.MC_TP_Array[i].position}; });
}
void MC_VelocityProfile(sm3::MC_VelocityProfile* self) {
  profileBody(self, self->TimeVelocity, self->Execute, TableKind::Velocity, self->VelocityScale,
              [](const sm3::MC_TV_REF& t, int i) { return RawPoint{t.MC_TV_Array[i].delta_time, t.MC_TV_Array[i].velocity}; });
}
void MC_AccelerationProfile(sm3::MC_AccelerationProfile* self) {
  profileBody(self, self->TimeAcceleration, self->Execute, TableKind::Acceleration, self->AccelerationScale,
              [](const sm3::MC_TA_REF& t, int i) { return RawPoint{t.MC_TA_Array[i].delta_time, t.MC_TA_Array[i].acceleration}; });
}

void SMC_FollowPosition(sm3::SMC_FollowPosition* self) {
  axisFbSlot(self, FbKind::Follow, [&](Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
    FollowInputs in;
    in.mask = kFollowPosition;
    in.position = self->fSetPosition;
    callFollow(k, fb, ax, self->bExecute, false, in, c);
  });
}
void SMC_FollowPositionVelocity(sm3::SMC_FollowPositionVelocity* self) {
  axisFbSlot(self, FbKind::Follow, [&](Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
    FollowInputs in;
    in.mask = kFollowPosition | kFollowVelocity;
    in.position = self->fSetPosition;
    in.velocity = self->fSetVelocity;
    callFollow(k, fb, ax, self->bExecute, false, in, c);
  });
}
void SMC_FollowSetValues(sm3::SMC_FollowSetValues* self) {
  axisFbSlot(self, FbKind::Follow, [&](Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
    FollowInputs in;
    in.mask = self->dwValueMask;
    in.position = self->fSetPosition;
    in.velocity = self->fSetVelocity;
    in.acceleration = self->fSetAcceleration;
    in.jerk = self->fSetJerk;
    in.torque = self->fSetTorque;
    in.current = self->fSetCurrent;
    callFollow(k, fb, ax, self->bExecute, self->bAbort, in, c);
  });
}
void SMC_FollowVelocity(sm3::SMC_FollowVelocity* self) {
  axisFbSlot(self, FbKind::Follow, [&](Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
    FollowInputs in;
    in.mask = kFollowVelocity;
    in.velocity = self->fSetVelocity;
    callFollow(k, fb, ax, self->bExecute, false, in, c);
  });
}
void SMC_SetTorque(sm3::SMC_SetTorque* self) {
  axisFbSlot(self, FbKind::Torque, [&](Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
    callSetTorque(k, fb, ax, self->bEnable, self->fTorque, c);
  });
}
void SMC_SetControllerMode(sm3::SMC_SetControllerMode* self) {
  axisFbSlot(self, FbKind::Config, [&](Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
    callSetControllerMode(k, fb, ax, self->bExecute, static_cast<int16_t>(self->nControllerMode), c);
  });
}

}  // namespace

namespace stc::motion {

void registerSm3ProfilesNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(MC_PositionProfile, MC_PositionProfile)
  STC_SM3_NATIVE(MC_VelocityProfile, MC_VelocityProfile)
  STC_SM3_NATIVE(MC_AccelerationProfile, MC_AccelerationProfile)
  STC_SM3_NATIVE(SMC_FollowPosition, SMC_FollowPosition)
  STC_SM3_NATIVE(SMC_FollowPositionVelocity, SMC_FollowPositionVelocity)
  STC_SM3_NATIVE(SMC_FollowSetValues, SMC_FollowSetValues)
  STC_SM3_NATIVE(SMC_FollowVelocity, SMC_FollowVelocity)
  STC_SM3_NATIVE(SMC_SetTorque, SMC_SetTorque)
  STC_SM3_NATIVE(SMC_SetControllerMode, SMC_SetControllerMode)
}

}  // namespace stc::motion
