// SMC_XInterpolator (sm3_cnc_interpolator.st; docs/cnc.md, "SMC_XInterpolator"): the path
// of a queue as a cam over an external X axis, run by stdlib-motion/cnc's XInterpolator.
#include <cmath>
#include <memory>

#include "stdlib-motion/cnc/XInterpolator.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/codesys_sm3/Sm3IpoCommon.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

constexpr int32_t kDirPositive = 1, kDirNegative = -1;   // MC_Direction

struct XIpoState : MotionSession::InstanceState {
  std::unique_ptr<stc::cnc::XInterpolator> ipo;
  sm3::SMC_OUTQUEUE* queue = nullptr;
  uint32_t fed = 0;
  double wayBase = 0;
};

void startRun(sm3::SMC_XInterpolator* self, MotionSession& s) {
  auto fail = [&](int16_t e) {
    self->bError = true;
    self->wErrorID = e;
  };
  QueueView v;
  if (const int16_t e = checkRunStart(s, self, v)) return fail(e);
  if (self->eDirection != kDirPositive && self->eDirection != kDirNegative) return fail(stc::cnc::kXIpoInvalidDirection);
  auto owned = std::make_unique<XIpoState>();
  owned->ipo = std::make_unique<stc::cnc::XInterpolator>(self->eDirection);
  owned->queue = v.queue();
  owned->wayBase = self->dLastWayPos;
  installRunState(s, self, std::move(owned));
}

void SMC_XInterpolator(sm3::SMC_XInterpolator* self) {
  MotionSession& s = MotionSession::current();
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  XIpoState* st = s.instanceState<XIpoState>(self->__handle, self);
  if (self->bAbort || !self->bExecute) {   // a cam: nothing to brake, the run ends at once
    if (st) dropRunState<XIpoState>(s, self);
    clearRunFlags(self);
    self->bWorking = false;
    if (self->bAbort) self->iStatus = static_cast<int16_t>(stc::cnc::IpoStatus::Unknown);
    return;
  }
  if (edge) {
    if (st) dropRunState<XIpoState>(s, self);
    clearRunFlags(self);
    startRun(self, s);
    st = s.instanceState<XIpoState>(self->__handle, self);
  }
  if (!st) return;
  stc::cnc::XInterpolator& ipo = *st->ipo;
  QueueView v;
  int16_t err = openRunQueue(s, self->poqDataIn, st->queue, st->fed, v);
  if (err == 0 && ipo.error() == 0) err = feedFromQueue(v, st->fed, ipo, false);
  if (err == 0) {
    // the path X: a non-finite offset or axis position is the core's SMC_OS_INVALID_PARAMETER
    const stc::cnc::IpoOutput& o = ipo.step(self->X_Axis->fSetPosition - self->dXOffset);
    const int done = ipo.takeFinished();
    for (int i = 0; i < done && st->fed > 0 && !v.empty(); ++i) {
      v.pop();
      --st->fed;
    }
    publishIpoOutputs(self, st->wayBase, o);
    err = ipo.error();
  }
  if (err != 0) {
    self->bError = true;
    self->wErrorID = err;
    self->bBusy = false;
    self->bWorking = false;
    dropRunState<XIpoState>(s, self);   // stays in error until the next rising edge
    return;
  }
  self->wErrorID = ipo.warning();   // SMC_INT_DATA_UNDERRUN: X beyond what the queue holds yet
  self->bDone = ipo.output().finished;
  self->bBusy = !self->bDone;
}

}  // namespace

namespace stc::motion::sm3face {
void registerSm3XInterpolatorNatives(MotionLibrary& lib) { STC_SM3_NATIVE(SMC_XInterpolator, SMC_XInterpolator) }
}  // namespace stc::motion::sm3face
