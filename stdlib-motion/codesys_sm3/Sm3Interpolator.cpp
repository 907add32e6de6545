// SMC_Interpolator and SMC_GetMParameters (sm3_cnc_interpolator.st; docs/cnc.md,
// "SMC_Interpolator"): the checked queue of a program run by stdlib-motion/cnc's
// Interpolator, one set point per call.
#include <algorithm>
#include <cmath>
#include <memory>

#include "stdlib-motion/cnc/Interpolator.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/codesys_sm3/Sm3IpoCommon.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {


struct IpoState : MotionSession::InstanceState {
  std::unique_ptr<stc::cnc::Interpolator> ipo;
  sm3::SMC_OUTQUEUE* queue = nullptr;
  uint32_t fed = 0;          // queue elements (from nReadPos) handed to the interpolator
  double wayBase = 0;        // dLastWayPos at the rising edge
  bool stopping = false;     // bExecute fell: stop along the path, then drop the run
};

void startRun(sm3::SMC_Interpolator* self, MotionSession& s) {
  auto fail = [&](int16_t e) {
    self->bError = true;
    self->wErrorID = e;
  };
  QueueView v;
  if (const int16_t e = checkRunStart(s, self, v)) return fail(e);
  stc::cnc::IpoSettings cfg;
  cfg.cycle = self->dwIpoTime * 1e-6;
  cfg.mode = static_cast<stc::cnc::VelMode>(self->iVelMode);
  cfg.jerk = self->dJerkMax;
  int16_t err = 0;
  auto ipo = std::make_unique<stc::cnc::Interpolator>(cfg, err);
  if (err != 0) return fail(err);
  auto owned = std::make_unique<IpoState>();
  owned->ipo = std::move(ipo);
  owned->queue = v.queue();
  owned->wayBase = self->dLastWayPos;
  installRunState(s, self, std::move(owned));
}

void SMC_Interpolator(sm3::SMC_Interpolator* self) {
  MotionSession& s = MotionSession::current();
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  IpoState* st = s.instanceState<IpoState>(self->__handle, self);
  if (self->bAbort) {   // abandon the path where it stands (no ramp: after an emergency stop)
    if (st) dropRunState<IpoState>(s, self);
    clearRunFlags(self);
    self->bWorking = false;
    self->dVel = 0;
    self->iStatus = static_cast<int16_t>(stc::cnc::IpoStatus::Unknown);
    return;
  }
  if (edge) {
    if (st) dropRunState<IpoState>(s, self);
    clearRunFlags(self);
    startRun(self, s);
    st = s.instanceState<IpoState>(self->__handle, self);
  }
  if (!st) {
    if (!self->bExecute) clearRunFlags(self);
    return;
  }
  if (!self->bExecute) st->stopping = true;

  stc::cnc::Interpolator& ipo = *st->ipo;
  QueueView v;
  int16_t queueError = openRunQueue(s, self->poqDataIn, st->queue, st->fed, v);
  const sm3::SMC_OUTQUEUE* q = st->queue;

  if (queueError == 0 && ipo.error() == 0 && !st->stopping) {
    if (st->fed < v.size() && q->byGenerator != kGenCheckVelocities) queueError = stc::cnc::kIpoNoCheckVelocities;
    if (queueError == 0) queueError = feedFromQueue(v, st->fed, ipo, true);
  }

  const stc::cnc::IpoControls c = ipoControls(self, st->stopping || queueError != 0);
  const stc::cnc::IpoOutput& o = ipo.step(c);
  if (queueError == 0) {
    const int done = ipo.takeFinished();
    for (int i = 0; i < done && st->fed > 0 && !v.empty(); ++i) {
      v.pop();
      --st->fed;
    }
  }
  publishIpoOutputs(self, st->wayBase, o);
  self->__mK = o.mK;
  self->__mL = o.mL;

  const int16_t err = queueError != 0 ? queueError : ipo.error();
  if (err != 0) {
    self->bError = true;
    self->wErrorID = err;
    self->bBusy = false;
  } else {
    self->wErrorID = ipo.warning();   // SMC_INT_DATA_UNDERRUN while the queue runs dry
    self->bDone = o.finished;
    self->bBusy = !o.finished;
  }
  if (st->stopping && o.vel == 0) {   // bExecute FALSE: dropped once at rest
    dropRunState<IpoState>(s, self);
    clearRunFlags(self);
    self->bWorking = false;
  }
}

void SMC_GetMParameters(sm3::SMC_GetMParameters* self) {
  const sm3::SMC_Interpolator* ipo = self->Interpolator;
  const bool active = self->bEnable && ipo && ipo->wM != 0;
  self->bMActive = active;
  self->dK = active ? ipo->__mK : 0;
  self->dL = active ? ipo->__mL : 0;
  self->MParameters.dK = self->dK;
  self->MParameters.dL = self->dL;
}

}  // namespace

namespace stc::motion::sm3face {
void registerSm3InterpolatorNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(SMC_Interpolator, SMC_Interpolator)
  STC_SM3_NATIVE(SMC_GetMParameters, SMC_GetMParameters)
}
}  // namespace stc::motion::sm3face
