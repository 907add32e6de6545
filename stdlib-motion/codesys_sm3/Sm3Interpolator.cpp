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
  IpoState* st = beginTimedRunCall<IpoState>(s, self, startRun);
  if (!st) return;
  stc::cnc::Interpolator& ipo = *st->ipo;
  QueueView v;
  const int16_t queueError = takeCheckedElements(s, self->poqDataIn, *st, ipo, v);

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

  endTimedRunCall(s, self, *st, ipo, o, queueError);
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
