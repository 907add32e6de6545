// The path preprocessing blocks (sm3_cnc_preprocess.st; docs/cnc.md, "Preprocessing
// blocks"): SMC_SmoothPath (own output queue, stdlib-motion/cnc/SmoothPath.h),
// SMC_CheckForLimits and SMC_CheckVelocities (in place, LimitsCheck.h /
// VelocityCheck.h), SMC_PreAcknowledgeM and SMC_QueueSetReservedEntries.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "stdlib-motion/cnc/Geometry.h"
#include "stdlib-motion/cnc/LimitsCheck.h"
#include "stdlib-motion/cnc/SmoothPath.h"
#include "stdlib-motion/cnc/VelocityCheck.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/codesys_sm3/Sm3GeoInfo.h"
#include "stdlib-motion/codesys_sm3/Sm3Queue.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;
namespace cnc = stc::cnc;

namespace {

// SMC_ERROR numbers of these blocks (sm3_types.st).
enum : int16_t {
  kNoError = 0,
  kCvNonPositive = 1100,      // SMC_CV_ACC_DEC_VEL_NONPOSITIVE
  kNoOutQueue = 1501,         // SMC_NO_OUTQUEUE_TYPE: poqDataIn null, not a queue, broken, or an element that is no SMC_GEOINFO
  kSpInvalidInput = 1701,     // SMC_SAA_SP_INVALID_INPUT
  kNotInBuffer = 1800,        // SMC_SA_QUEUE_NOT_IN_BUFFER
  kQueueChanged = 1801,       // SMC_SA_QUEUE_CHANGED_DURING_OP
  kInvalidParameter = 1820,   // SMC_OS_INVALID_PARAMETER
};

constexpr uint32_t kMinReservedEntries = 3;   // SMC_MIN_RESERVED_QUEUE_ELEMS (sm3_cnc_preprocess.st)
constexpr uint32_t kSmoothPerCall = 100;      // input elements SMC_SmoothPath takes per call at most
constexpr uint16_t kWIntMarkVelChecked = cnc::MarkVelChecked;
constexpr uint16_t kWIntMarkPreAck = cnc::MarkMPreAcknowledged;

sm3::SMC_OUTQUEUE* asQueue(void* p) { return static_cast<sm3::SMC_OUTQUEUE*>(p); }

// How many elements at the front of the queue a block has already handled, after its
// consumers popped some.  `done` counted from nReadPos == `readPos`; the last handled
// element had diObjNo `lastObj`.  Pops are nReadPos' advance; a whole lap (the queue
// emptied and refilled between two calls) is caught by the object number check.
uint32_t handledAfterPops(const QueueView& v, uint32_t done, uint32_t readPos, int32_t lastObj) {
  const uint32_t cap = v.capacity(), size = v.size();
  uint32_t popped = (v.queue()->nReadPos + cap - readPos % cap) % cap;
  if (popped == 0 && size < done) popped = done;
  done = done > popped ? done - popped : 0;
  done = std::min(done, size);
  if (done > 0 && v.at(done - 1).diObjNo != lastObj) {
    // Lost track: find the last handled element by its number, else start again (idempotent).
    done = 0;
    for (uint32_t i = size; i-- > 0;)
      if (v.at(i).diObjNo == lastObj) {
        done = i + 1;
        break;
      }
  }
  return done;
}

template <class T>
void rememberHandled(T* self, const QueueView& v, uint32_t done) {
  self->__done = done;
  self->__readPos = v.queue()->nReadPos;
  self->__lastObj = done > 0 ? v.at(done - 1).diObjNo : 0;
}

bool finite(const sm3::SMC_POSINFO& p) {
  for (double v : {p.dX, p.dY, p.dZ, p.dA, p.dB, p.dC, p.dA1, p.dA2, p.dA3, p.dA4, p.dA5})
    if (!std::isfinite(v)) return false;
  return true;
}
cnc::Pos toPos(const sm3::SMC_POSINFO& p) { return {p.dX, p.dY, p.dZ, p.dA, p.dB, p.dC, p.dA1, p.dA2, p.dA3, p.dA4, p.dA5}; }

// ---------------------------------------------------------------- SMC_CheckVelocities

void failCv(sm3::SMC_CheckVelocities* self, int16_t id) {
  self->bBusy = false;
  self->bError = true;
  self->wErrorID = id;
}

void SMC_CheckVelocities(sm3::SMC_CheckVelocities* self) {
  MotionSession& s = MotionSession::current();
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  if (!self->bExecute || edge) {
    self->bBusy = self->bError = false;
    self->wErrorID = kNoError;
    self->poqDataOut = nullptr;
    self->__queue = nullptr;
    if (!self->bExecute) return;
    cnc::VelocityCheckOptions o{self->dAngleTol, self->bCheckAddAxVelJump, self->dMaxAddAxVelDifference,
                                self->dDryRunVelocity};
    if (!cnc::validOptions(o)) return failCv(self, kInvalidParameter);
    QueueView v;
    if (openQueue(s, asQueue(self->poqDataIn), v) != QueueCheck::Ok) return failCv(self, kNoOutQueue);
    v.queue()->byGenerator = kGenCheckVelocities;   // the interpolator refuses an unchecked queue
    self->__queue = self->poqDataIn;
    self->poqDataOut = self->poqDataIn;
    rememberHandled(self, v, 0);
    self->bBusy = true;
  }
  if (!self->bBusy) return;
  if (self->bAbort) {
    self->bBusy = false;
    return;
  }
  QueueView v;
  if (self->poqDataIn != self->__queue) return failCv(self, kQueueChanged);
  if (openQueue(s, asQueue(self->poqDataIn), v) != QueueCheck::Ok) return failCv(self, kNoOutQueue);
  const cnc::VelocityCheckOptions o{self->dAngleTol, self->bCheckAddAxVelJump, self->dMaxAddAxVelDifference,
                                    self->dDryRunVelocity};
  if (!cnc::validOptions(o)) return failCv(self, kInvalidParameter);   // inputs may change while running

  uint32_t done = handledAfterPops(v, self->__done, self->__readPos, self->__lastObj);
  const uint32_t size = v.size();
  thread_local std::vector<cnc::Element> pending;
  pending.resize(size - done);
  for (uint32_t i = done; i < size; ++i)
    if (!fromGeoInfo(v.at(i), pending[i - done])) return failCv(self, kNoOutQueue);
  const bool cannotGrow = v.full() && done == 0;
  const cnc::VelocityCheckResult r = cnc::checkVelocities(pending, v.endOfList(), cannotGrow, o);
  // Only the members the check decides are written: the rest of each element stays as its producer wrote it.
  for (size_t i = 0; i < r.finalized; ++i) {
    sm3::SMC_GEOINFO& g = v.at(done + static_cast<uint32_t>(i));
    g.dVel = pending[i].vel;
    g.dVelEnd = pending[i].velEnd;
    g.wIntMark = static_cast<uint16_t>(g.wIntMark | kWIntMarkVelChecked);
  }
  done += static_cast<uint32_t>(r.finalized);
  rememberHandled(self, v, done);
  if (r.error) return failCv(self, kCvNonPositive);
  if (v.endOfList() && done == size) self->bBusy = false;   // the whole path is checked
}

// ---------------------------------------------------------------- SMC_PreAcknowledgeM

void SMC_PreAcknowledgeM(sm3::SMC_PreAcknowledgeM* self) {
  self->bDone = self->bBusy = self->bError = false;
  self->wErrorID = kNoError;
  if (!self->bEnable) return;
  // iM as the WORD M number: -2 is 65534, the G75 element; 0 and the reserved 65533 / 65535 match nothing.
  const uint16_t m = static_cast<uint16_t>(self->iM);
  if (m == 0 || m == 65533 || m == 65535) {
    self->bError = true;
    self->wErrorID = kInvalidParameter;
    return;
  }
  QueueView v;
  if (openQueue(MotionSession::current(), asQueue(self->poqDataIn), v) != QueueCheck::Ok) {
    self->bError = true;
    self->wErrorID = kNoOutQueue;
    return;
  }
  const int16_t wanted = m == 65534 ? int16_t(cnc::MoveType::Sync) : int16_t(cnc::MoveType::MCommand);
  for (uint32_t i = 0, n = v.size(); i < n; ++i) {
    sm3::SMC_GEOINFO& g = v.at(i);
    if (g.iMoveType == wanted && g.dP15 == m) g.wIntMark = static_cast<uint16_t>(g.wIntMark | kWIntMarkPreAck);
  }
  // Everything the producer will write is in the queue (and marked) once it has bEndOfList.
  self->bDone = v.endOfList();
  self->bBusy = !self->bDone;
}

// ---------------------------------------------------------------- SMC_CheckForLimits

void failCl(sm3::SMC_CheckForLimits* self, int16_t id) {
  self->bBusy = false;
  self->bError = true;
  self->wErrorID = id;
}

// X, Y, Z always, plus the additional axes of wAddAxis (bits 3..10).
uint16_t checkedAxes(uint16_t wAddAxis) { return static_cast<uint16_t>(0b111 | (wAddAxis & 0x7F8)); }

void SMC_CheckForLimits(sm3::SMC_CheckForLimits* self) {
  MotionSession& s = MotionSession::current();
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  if (!self->bExecute || edge) {
    self->bBusy = self->bError = false;
    self->wErrorID = kNoError;
    self->wAxisOutOfLimits = 0;
    self->iSourceLine_No = 0;
    self->__queue = nullptr;
    if (!self->bExecute) return;
    const cnc::Pos lo = toPos(self->piMin), hi = toPos(self->piMax);
    const uint16_t axes = checkedAxes(self->wAddAxis);
    bool ok = finite(self->piMin) && finite(self->piMax) && std::isfinite(self->d3dCheckDistance) &&
              self->d3dCheckDistance >= 0 && self->diMinNoPoints >= 0 && self->diMinNoPoints <= self->diMaxNoPoints &&
              self->diMaxNoPoints <= 100000;
    for (int k = 0; k < cnc::kAxisCount; ++k)
      if ((axes & (1u << k)) && lo[k] > hi[k]) ok = false;
    if (!ok) return failCl(self, kInvalidParameter);
    QueueView v;
    if (openQueue(s, asQueue(self->poqDataIn), v) != QueueCheck::Ok) return failCl(self, kNoOutQueue);
    self->__queue = self->poqDataIn;
    rememberHandled(self, v, 0);
    self->bBusy = true;
  }
  if (!self->bBusy) return;
  if (self->bAbort) {
    self->bBusy = false;
    return;
  }
  QueueView v;
  if (self->poqDataIn != self->__queue) return failCl(self, kQueueChanged);
  if (openQueue(s, asQueue(self->poqDataIn), v) != QueueCheck::Ok) return failCl(self, kNoOutQueue);
  const cnc::Pos lo = toPos(self->piMin), hi = toPos(self->piMax);
  const uint16_t axes = checkedAxes(self->wAddAxis);
  uint32_t done = handledAfterPops(v, self->__done, self->__readPos, self->__lastObj);
  const uint32_t size = v.size();
  cnc::Element e;
  for (; done < size; ++done) {
    const sm3::SMC_GEOINFO& g = v.at(done);
    if (!fromGeoInfo(g, e)) {
      rememberHandled(self, v, done);
      return failCl(self, kNoOutQueue);
    }
    if (const uint16_t out = cnc::axesOutOfLimits(e, lo, hi, axes)) {
      // A path outside the box is a finding about the program, not a fault of the block: wErrorID stays 0.
      self->wAxisOutOfLimits = out;
      self->iSourceLine_No = g.iSourceLine_No;
      self->bError = true;
      self->bBusy = false;
      rememberHandled(self, v, done + 1);
      return;
    }
  }
  rememberHandled(self, v, done);
  if (v.endOfList()) self->bBusy = false;
}

// ---------------------------------------------------------------- SMC_QueueSetReservedEntries

void SMC_QueueSetReservedEntries(sm3::SMC_QueueSetReservedEntries* self) {
  QueueView v;
  if (openQueue(MotionSession::current(), asQueue(self->poqDataIn), v) != QueueCheck::Ok) {
    self->poqDataOut = nullptr;
    return;
  }
  self->poqDataOut = self->poqDataIn;
  if (!self->bExecute) return;
  uint32_t n = std::max(self->nNumReservedEntries, kMinReservedEntries);
  n = std::min(n, v.capacity() - 1);   // a producer always keeps room for one element
  v.queue()->nNumReservedEntries = n;
}

// ---------------------------------------------------------------- SMC_SmoothPath

// The smoother of one SMC_SmoothPath instance, made at the rising edge of bExecute.
struct SmoothState : MotionSession::InstanceState {
  explicit SmoothState(const cnc::SmoothOptions& o) : smoother(o) {}
  cnc::PathSmoother smoother;
  std::vector<cnc::Element> staging;   // finished elements waiting for room in the output queue
  sm3::SMC_OUTQUEUE* input = nullptr;
  bool inputFinished = false;
  bool running = false;
};

void stopSp(sm3::SMC_SmoothPath* self, SmoothState* st, int16_t error) {
  if (st) st->running = false;
  self->bBusy = false;
  if (error != kNoError) {
    self->bError = true;
    self->wErrorID = error;
  }
}

void startSmoothing(sm3::SMC_SmoothPath* self, MotionSession& s) {
  // The output queue lives in this instance, so the instance must be static.
  if (!s.inImage(self, sizeof *self)) return stopSp(self, nullptr, kNotInBuffer);
  const cnc::SmoothOptions o{self->dEdgeDistance, self->dAngleTol, self->bSymmetricalDistances};
  if (!cnc::validOptions(o)) return stopSp(self, nullptr, kSpInvalidInput);
  QueueView in;
  if (openQueue(s, asQueue(self->poqDataIn), in) != QueueCheck::Ok) return stopSp(self, nullptr, kNoOutQueue);
  sm3::SMC_OUTQUEUE& q = self->__oq;
  const uint64_t capacity = self->nSizeOutQueue / sizeof(sm3::SMC_GEOINFO);
  // bAppend keeps what is still in the output queue when it is the same buffer.
  const bool append = self->bAppend && q.wOUTQUEUEStructID == kOutQueueStructId && q.pbyBuffer == self->pbyBufferOutQueue &&
                      q.nCapacity == capacity && q.nReadPos < capacity && q.nWritePos < capacity;
  const sm3::SMC_OUTQUEUE kept = q;
  if (const int16_t err = setupOwnQueue(s, q, self->pbyBufferOutQueue, self->nSizeOutQueue, kGenSmoothPath))
    return stopSp(self, nullptr, err);
  if (append) {
    q.nReadPos = kept.nReadPos;
    q.nWritePos = kept.nWritePos;
    q.bFull = kept.bFull;
  }
  std::copy(std::begin(in.queue()->strProgramName), std::end(in.queue()->strProgramName), std::begin(q.strProgramName));

  if (s.instanceState<SmoothState>(self->__handle, self)) s.instanceStates.erase(self->__handle);
  auto owned = std::make_unique<SmoothState>(o);
  owned->owner = self;
  owned->input = in.queue();
  owned->running = true;
  const uint64_t id = s.nextInstanceState++;
  s.instanceStates[id] = std::move(owned);
  self->__handle = id;
  self->poqDataOut = &q;
  self->bBusy = true;
}

void SMC_SmoothPath(sm3::SMC_SmoothPath* self) {
  MotionSession& s = MotionSession::current();
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  SmoothState* st = s.instanceState<SmoothState>(self->__handle, self);
  if (!self->bExecute || edge) {
    self->bDone = self->bBusy = self->bError = false;
    self->wErrorID = kNoError;
    if (st) st->running = false;
    if (!self->bExecute) return;
    startSmoothing(self, s);
    if (!self->bBusy) return;
    st = s.instanceState<SmoothState>(self->__handle, self);
  }
  if (!st || !st->running) return;
  if (self->bAbort) return stopSp(self, st, kNoError);

  sm3::SMC_OUTQUEUE& q = self->__oq;
  if (q.wOUTQUEUEStructID != kOutQueueStructId || q.pbyBuffer != self->pbyBufferOutQueue || q.nCapacity == 0 ||
      q.nCapacity != self->nSizeOutQueue / sizeof(sm3::SMC_GEOINFO) || q.nReadPos >= q.nCapacity || q.nWritePos >= q.nCapacity ||
      (q.bFull && q.nReadPos != q.nWritePos))
    return stopSp(self, st, kQueueChanged);
  QueueView out, in;
  if (openQueue(s, &q, out) != QueueCheck::Ok) return stopSp(self, st, kQueueChanged);
  if (asQueue(self->poqDataIn) != st->input) return stopSp(self, st, kQueueChanged);
  if (openQueue(s, st->input, in) != QueueCheck::Ok) return stopSp(self, st, kNoOutQueue);
  self->poqDataOut = &q;

  size_t next = 0;   // staged elements already written
  auto flush = [&] {
    while (next < st->staging.size() && out.room() > 0) out.push(st->staging[next++]);
    if (next == st->staging.size()) {
      st->staging.clear();
      next = 0;
    }
  };
  cnc::Element e;
  for (uint32_t taken = 0;;) {
    flush();
    if (!st->staging.empty()) {
      st->staging.erase(st->staging.begin(), st->staging.begin() + static_cast<std::ptrdiff_t>(next));
      break;   // wait for the consumer
    }
    if (!in.empty()) {
      if (taken == kSmoothPerCall) break;
      if (!fromGeoInfo(in.at(0), e)) return stopSp(self, st, kNoOutQueue);
      in.pop();
      ++taken;
      st->smoother.push(e, st->staging);
      continue;
    }
    if (!in.endOfList()) break;   // wait for the producer
    if (!st->inputFinished) {
      st->smoother.finish(st->staging);
      st->inputFinished = true;
      continue;
    }
    q.bEndOfList = true;
    self->bDone = true;
    stopSp(self, st, kNoError);
    break;
  }
}

}  // namespace

namespace stc::motion::sm3face {
void registerSm3PreprocessNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(SMC_SmoothPath, SMC_SmoothPath)
  STC_SM3_NATIVE(SMC_CheckForLimits, SMC_CheckForLimits)
  STC_SM3_NATIVE(SMC_PreAcknowledgeM, SMC_PreAcknowledgeM)
  STC_SM3_NATIVE(SMC_CheckVelocities, SMC_CheckVelocities)
  STC_SM3_NATIVE(SMC_QueueSetReservedEntries, SMC_QueueSetReservedEntries)
}
}  // namespace stc::motion::sm3face
