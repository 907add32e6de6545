// The Leadshine homing FBs (ls_homing.st): SMC_Home (controller side, local
// pulse axes) and LS_EtherCATAxis_HomeMove (drive side).  Semantics in core/Homing.cpp.
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/Homing.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {


void SMC_Home(sm3::SMC_Home* self) {
  CallCtx c = callContext();
  Axis* ax = bind(self->Axis, c);
  if (refuse(self, ax)) return;
  SmcHomeInputs in;
  in.stop = self->bStop;
  in.velocityFast = self->fVelocityFast;
  in.velocitySlow = self->fVelocitySlow;
  in.acceleration = self->fAcceleration;
  in.deceleration = self->fDeceleration;
  in.jerk = self->fJerk;
  in.direction = self->nDirection;
  in.homePosition = self->fHomePosition;
  in.completeMode = self->bHomeCompleteMode;
  in.mode = self->imode;
  in.limitsEnable = self->iHomeElEnable;
  in.limitDecelerate = self->bELStopMode;
  in.driverCounter = self->iDriverCounter;
  callSmcHome(kernel(), kernel().slot(self->__handle, self, FbKind::Home, &publish<sm3::SMC_Home>), *ax, self->bExecute, in, c);
  mirrorAll(*ax);
}

void LS_EtherCATAxis_HomeMove(sm3::LS_EtherCATAxis_HomeMove* self) {
  CallCtx c = callContext();
  Axis* ax = bind(self->Axis, c);
  if (refuse(self, ax)) return;
  DriveHomeParams p;
  p.method = self->Home_Method;
  p.fastVel = self->Home_FastVel;
  p.slowVel = self->Home_SlowVel;
  p.acc = self->Home_Acc;
  p.homePos = self->Home_Pos;
  p.axisNo = self->HomeAxisNo;
  callDriveHomeMove(kernel(), kernel().slot(self->__handle, self, FbKind::Home, &publish<sm3::LS_EtherCATAxis_HomeMove>), *ax,
                    self->bExecute, p, c);
  mirrorAll(*ax);
}

}  // namespace

namespace stc::motion {

void registerLsHomingNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(SMC_Home, SMC_Home)
  STC_SM3_NATIVE(LS_EtherCATAxis_HomeMove, LS_EtherCATAxis_HomeMove)
}

}  // namespace stc::motion
