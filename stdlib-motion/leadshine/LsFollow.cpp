// LS_LineFollowAbs / LS_LineFollowRel (ls_follow.st) over core/LineFollow.h.
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/LineFollow.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

void publishNothing(void*, const FbOutputs&) {}   // the follower's slot has no outputs of its own

template <class T>
void lineFollow(T* self, bool relative) {
  CallCtx c = callContext();
  Axis* master = bind(static_cast<sm3::AXIS_REF_SM3*>(self->AxisMaster), c);
  Axis* slave = master ? bind(static_cast<sm3::AXIS_REF_SM3*>(self->AxisSlave), c) : nullptr;
  if (refuse(self, master ? slave : nullptr) || rewired(self, *master, c)) return;
  LineFollowInputs in;
  in.exec = self->Exec;
  in.halt = self->Halt;
  in.stop = self->Stop;
  in.relative = relative;
  in.ipoCycleUs = self->IpoCycle;
  in.endPos[0] = self->EndPos[0];
  in.endPos[1] = self->EndPos[1];
  in.velocityMode = self->VelocityMode;
  in.velocity = self->Velocity;
  in.acceleration = self->Acceleration;
  in.deceleration = self->Deceleration;
  in.jerk = self->Jerk;
  LineFollowOutputs out;
  Kernel& k = kernel();
  FbSlot& follow = k.slot(self->__handle2, &self->__handle2, FbKind::Leadshine, &publishNothing);
  callLineFollow(k, slotOf(self, FbKind::Leadshine), follow, *master, *slave, in, out, c);
  self->CommandHalt = out.commandHalt;
  self->Vel = out.vel;
  mirrorCall(*master);
  mirrorCall(*slave);
}

void LS_LineFollowAbs(sm3::LS_LineFollowAbs* self) { lineFollow(self, false); }
void LS_LineFollowRel(sm3::LS_LineFollowRel* self) { lineFollow(self, true); }

}  // namespace

namespace stc::motion {

void registerLsFollowNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(LS_LineFollowAbs, LS_LineFollowAbs)
  STC_SM3_NATIVE(LS_LineFollowRel, LS_LineFollowRel)
}

}  // namespace stc::motion
