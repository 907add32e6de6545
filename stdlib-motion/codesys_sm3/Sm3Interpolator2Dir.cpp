// SMC_Interpolator2Dir and SMC_Interpolator2Dir_SlowTask (sm3_cnc_interpolator.st;
// docs/cnc.md, "SMC_Interpolator2Dir"): the checked queue of a program run forwards or
// backwards by stdlib-motion/cnc's Interpolator2Dir.  The fast block only reads the
// queue; the slow-task block removes what the interpolator no longer keeps.
#include <algorithm>
#include <cmath>
#include <memory>

#include "stdlib-motion/cnc/Interpolator2Dir.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/codesys_sm3/Sm3IpoCommon.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

constexpr int16_t kBufferTooSmall = 1050;   // SMC_INT2DIR_BUFFER_TOO_SMALL
constexpr uint32_t kMinReserved = 3;        // SMC_MIN_RESERVED_QUEUE_ELEMS

struct Ipo2State : MotionSession::InstanceState {
  std::unique_ptr<stc::cnc::Interpolator2Dir> ipo;
  sm3::SMC_OUTQUEUE* queue = nullptr;
  uint32_t fed = 0;        // queue elements (from nReadPos) handed to the interpolator
  uint32_t released = 0;   // of those, released by it: the slow task removes them
  double wayBase = 0;
  bool stopping = false;
};

// Reserved entries in force for q, and whether the queue has room for them and a look-ahead.
uint32_t reservedOf(const sm3::SMC_OUTQUEUE& q) { return std::max(q.nNumReservedEntries, kMinReserved); }
bool roomForReserved(const sm3::SMC_OUTQUEUE& q) { return uint64_t(q.nCapacity) >= uint64_t(reservedOf(q)) + 2; }

void startRun(sm3::SMC_Interpolator2Dir* self, MotionSession& s) {
  auto fail = [&](int16_t e) {
    self->bError = true;
    self->wErrorID = e;
  };
  QueueView v;
  if (const int16_t e = checkRunStart(s, self, v)) return fail(e);
  const sm3::SMC_OUTQUEUE& q = *v.queue();
  if (!roomForReserved(q)) return fail(kBufferTooSmall);
  stc::cnc::Ipo2DirSettings cfg;
  cfg.ipo.cycle = self->dwIpoTime * 1e-6;
  cfg.ipo.mode = static_cast<stc::cnc::VelMode>(self->iVelMode);
  cfg.ipo.jerk = self->dJerkMax;
  cfg.history = static_cast<int>(std::min<uint32_t>(reservedOf(q) - kMinReserved, stc::cnc::Interpolator2Dir::kMaxHistory + 1));
  cfg.startAtEnd = self->bStartAtEnd;
  cfg.pathCapacity = static_cast<int>(std::min<uint32_t>(q.nCapacity, stc::cnc::Interpolator2Dir::kMaxPath + 1));
  int16_t err = 0;
  auto ipo = std::make_unique<stc::cnc::Interpolator2Dir>(cfg, err);
  if (err != 0) return fail(err);
  auto owned = std::make_unique<Ipo2State>();
  owned->ipo = std::move(ipo);
  owned->queue = v.queue();
  owned->wayBase = self->dLastWayPos;
  installRunState(s, self, std::move(owned));
}

void SMC_Interpolator2Dir(sm3::SMC_Interpolator2Dir* self) {
  MotionSession& s = MotionSession::current();
  Ipo2State* st = beginTimedRunCall<Ipo2State>(s, self, startRun);
  if (!st) return;
  stc::cnc::Interpolator2Dir& ipo = *st->ipo;
  QueueView v;
  const int16_t queueError = takeCheckedElements(s, self->poqDataIn, *st, ipo, v);

  const stc::cnc::IpoControls c = ipoControls(self, st->stopping || queueError != 0);
  const stc::cnc::IpoOutput& o = ipo.step(c);
  st->released += static_cast<uint32_t>(ipo.takeReleased());
  publishIpoOutputs(self, st->wayBase, o);
  self->eDirection = static_cast<int32_t>(ipo.direction());

  endTimedRunCall(s, self, *st, ipo, o, queueError);
}

void SMC_Interpolator2Dir_SlowTask(sm3::SMC_Interpolator2Dir_SlowTask* self) {
  MotionSession& s = MotionSession::current();
  self->bError = false;
  self->wErrorID = 0;
  sm3::SMC_Interpolator2Dir* ipo = self->Interpolator2Dir;
  Ipo2State* st = ipo ? s.instanceState<Ipo2State>(ipo->__handle, ipo) : nullptr;
  if (!st) return;   // no run: nothing to remove
  QueueView v;
  if (openRunQueue(s, ipo->poqDataIn, st->queue, st->fed, v) != 0) return;   // the interpolator reports it
  if (!roomForReserved(*v.queue())) {
    self->bError = true;
    self->wErrorID = kBufferTooSmall;
  }
  const uint32_t n = std::min({st->released, st->fed, v.size()});
  for (uint32_t i = 0; i < n; ++i) v.pop();
  st->fed -= n;
  st->released -= n;
}

}  // namespace

namespace stc::motion::sm3face {
void registerSm3Interpolator2DirNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(SMC_Interpolator2Dir, SMC_Interpolator2Dir)
  STC_SM3_NATIVE(SMC_Interpolator2Dir_SlowTask, SMC_Interpolator2Dir_SlowTask)
}
}  // namespace stc::motion::sm3face
