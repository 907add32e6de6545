// The Leadshine face: binds the native LS_ blocks of ls_single_axis.st to
// the Leadshine semantics (leadshine/LsMoves.h, over core/JumpTrapezoid.h).  They take AXIS_REF_SM3, so they
// share the SoftMotion face's binding and mirror (Sm3Face.h).
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/leadshine/LsMoves.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;
namespace ls = stc::motion::leadshine;

namespace {

void LS_ResetVirtualAxis(sm3::LS_ResetVirtualAxis* self) {
  // The same reset as MC_Reset: ErrorStop and FBErrorOccured cleared, StandStill.
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) { k.callReset(slotOf(self, FbKind::Reset), ax, self->Execute, c); });
}

template <class T>
ls::StartVelInputs startVelInputs(const T* s) {
  ls::StartVelInputs in;
  if constexpr (requires { s->Position; }) in.position = s->Position;
  if constexpr (requires { s->Distance; }) in.distance = s->Distance;
  if constexpr (requires { s->EndSecondVel; }) in.endSecondVel = s->EndSecondVel;
  if constexpr (requires { s->Deceleration; }) in.deceleration = s->Deceleration;
  if constexpr (requires { s->Direction; }) in.direction = directionOf(s->Direction);
  in.velocity = s->Velocity;
  in.acceleration = s->Acceleration;
  in.startVel = s->StartVel;
  return in;
}

template <class T, FbKind K>
void startVelMove(T* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    ls::callStartVelMove(k, slotOf(self, FbKind::Leadshine), ax, self->Execute, K, startVelInputs(self), c);
  });
}

void LS_MoveAbsChangePosVel(sm3::LS_MoveAbsChangePosVel* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    ls::callChangeOnTheFly(k, slotOf(self, FbKind::MoveAbsolute), ax, self->Execute, moveInputs(self), c);
  });
}

void LS_MoveChangeVel(sm3::LS_MoveChangeVel* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    MoveInputs in = moveInputs(self);
    // Direction is an INT here: 1 positive, -1 negative (anything else is refused).
    in.direction = self->Direction == 1 ? Direction::Positive : self->Direction == -1 ? Direction::Negative : Direction::Shortest;
    ls::callChangeOnTheFly(k, slotOf(self, FbKind::MoveVelocity), ax, self->Execute, in, c);
  });
}

void LS_PositionToVelocity(sm3::LS_PositionToVelocity* self) {
  axisFb(self, [&](Kernel& k, Axis& ax, const CallCtx& c) {
    ls::TwoSegmentInputs in;
    in.exec = self->Exec;
    in.halt = self->Halt;
    in.stop = self->Stop;
    in.ipoCycleUs = self->IpoCycle;
    in.relative = self->MoveMode;
    in.velocityMode = self->VelocityMode;
    for (int i = 0; i < 2; ++i) {
      in.endPos[i] = self->EndPos[i];
      in.velocity[i] = self->Velocity[i];
      in.acceleration[i] = self->Acceleration[i];
      in.deceleration[i] = self->Deceleration[i];
      in.jerk[i] = self->Jerk[i];
    }
    ls::TwoSegmentOutputs out;
    ls::callPositionToVelocity(k, slotOf(self, FbKind::Leadshine), ax, in, out, c);
    self->CommandHalt = out.commandHalt;
    self->Vel = out.vel;
  });
}

void publishHandwheel(void*, const FbOutputs&) {}   // outputs are written in the call (callHandwheel)

void LS_Encoder_SetAxisMove(sm3::LS_Encoder_SetAxisMove* self) {
  CallCtx c = callContext();
  Axis* ax = bind(self->SelAxis, c);
  if (!ax) {
    self->bError = true;
    self->dErrorID = smcError(Error::NotReadyForMotion);
    return;
  }
  ls::HandwheelInputs in;
  in.exec = self->Exec;
  in.stop = self->Stop;
  in.channel = self->EncodeNum;
  in.num = self->Ratio_Num;
  in.denom = self->Ratio_Denom;
  in.filter = self->FilterPara;
  in.additiveTrig = self->PosAdditive_Trig;
  in.additivePos = self->PosAdditive_Pos;
  in.additiveCycles = self->PosAdditive_Cycle;
  ls::HandwheelOutputs out;
  FbSlot& fb = kernel().slot(self->__handle, self, FbKind::Leadshine, &publishHandwheel);
  ls::callHandwheel(kernel(), fb, *ax, in, out, c);
  self->bDone = out.done;
  self->bError = out.error;
  self->dErrorID = out.errorId;
  self->deltaPulseUnit = out.deltaPulseUnit;
  mirrorAll(*ax);
}

}  // namespace

namespace stc::motion {

void registerLeadshineNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(LS_ResetVirtualAxis, LS_ResetVirtualAxis)
  STC_SM3_NATIVE(LS_MoveAbs, startVelMove<sm3::LS_MoveAbs, FbKind::MoveAbsolute>)
  STC_SM3_NATIVE(LS_MoveRel, startVelMove<sm3::LS_MoveRel, FbKind::MoveRelative>)
  STC_SM3_NATIVE(LS_MoveVel, startVelMove<sm3::LS_MoveVel, FbKind::MoveVelocity>)
  STC_SM3_NATIVE(LS_MoveAbsChangePosVel, LS_MoveAbsChangePosVel)
  STC_SM3_NATIVE(LS_MoveChangeVel, LS_MoveChangeVel)
  STC_SM3_NATIVE(LS_PositionToVelocity, LS_PositionToVelocity)
  STC_SM3_NATIVE(LS_Encoder_SetAxisMove, LS_Encoder_SetAxisMove)
}

}  // namespace stc::motion
