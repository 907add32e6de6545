// SMC_ToolCorr and SMC_AvoidLoop (sm3_cnc_preprocess_tc.st; docs/cnc.md, "Tool radius
// correction", "Loop avoidance"): the streaming cores of stdlib-motion/cnc between the
// program's input queue and the block's own output queue.
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>

#include "stdlib-motion/cnc/AvoidLoop.h"
#include "stdlib-motion/cnc/ToolCorr.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/codesys_sm3/Sm3GeoInfo.h"
#include "stdlib-motion/codesys_sm3/Sm3Queue.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

// SMC_ERROR numbers of these blocks (sm3_types.st; docs/cnc.md).
enum : int16_t {
  kNoError = 0,
  kQueueTooSmall = 1080,      // SMC_WAR_INT_OUTQUEUE_TOO_SMALL: own buffer below 5 elements
  kNoOutQueue = 1501,         // SMC_NO_OUTQUEUE_TYPE: poqDataIn 0, not in static memory, wrong ID, broken, bad element
  kBufferMisaligned = 1502,   // SMC_GEOINFO_BUFFER_MISALIGNED
  kNotPlanar = 1600,          // SMC_3D_MODE_NOT_SUPPORTED: an element the correction cannot offset
  kNotInBuffer = 1800,        // SMC_SA_QUEUE_NOT_IN_BUFFER
  kQueueChanged = 1801,       // SMC_SA_QUEUE_CHANGED_DURING_OP: the own queue broken by a consumer
  kInvalidParameter = 1820,   // SMC_OS_INVALID_PARAMETER: radius, mode, an arc smaller than the tool
};

constexpr uint32_t kElementsPerCall = 200;   // input elements taken per call at most
constexpr size_t kBacklog = 8;               // corrected elements waiting for room at most

// What the two blocks share: the output ring, the input handshake, the flags.
struct StageState : MotionSession::InstanceState {
  bool running = false;
  bool finishing = false;   // the input reached its end: the core has been told
  virtual bool push(const stc::cnc::Element& e) = 0;   // false on an error
  virtual void finish() = 0;
  virtual bool hasOutput() const = 0;
  virtual size_t outputSize() const = 0;
  virtual const stc::cnc::Element& front() const = 0;
  virtual void pop() = 0;
};

struct ToolCorrState : StageState {
  stc::cnc::ToolCorrector tc;
  explicit ToolCorrState(stc::cnc::ToolCorrMode m, double r) : tc(m, r) {}
  bool push(const stc::cnc::Element& e) override { return tc.push(e); }
  void finish() override { tc.finish(); }
  bool hasOutput() const override { return tc.hasOutput(); }
  size_t outputSize() const override { return tc.outputSize(); }
  const stc::cnc::Element& front() const override { return tc.front(); }
  void pop() override { tc.pop(); }
};

struct AvoidLoopState : StageState {
  stc::cnc::LoopAvoider la;
  bool push(const stc::cnc::Element& e) override {
    la.push(e);
    return true;
  }
  void finish() override { la.finish(); }
  bool hasOutput() const override { return la.hasOutput(); }
  size_t outputSize() const override { return la.outputSize(); }
  const stc::cnc::Element& front() const override { return la.front(); }
  void pop() override { la.pop(); }
};

template <class FB>
sm3::SMC_OUTQUEUE* inputQueue(FB* self) {
  return static_cast<sm3::SMC_OUTQUEUE*>(self->poqDataIn);
}

// The block's fields the shared code needs (both FBs have them under the same names).
template <class FB>
void clearFlags(FB* self) {
  self->bDone = self->bBusy = self->bError = false;
  self->wErrorID = kNoError;
}
template <class FB>
void stopWith(FB* self, StageState* st, int16_t error) {
  if (st) st->running = false;
  self->bBusy = false;
  if (error != kNoError) {
    self->bError = true;
    self->wErrorID = error;
  }
}

// The rising edge: checks, the own queue, a new state.  Returns the state or null (error set).
template <class FB>
StageState* startStage(FB* self, MotionSession& s, std::unique_ptr<StageState> owned, uint8_t generator) {
  if (!s.inImage(self, sizeof *self)) return stopWith(self, nullptr, kNotInBuffer), nullptr;
  QueueView in;
  if (openQueue(s, inputQueue(self), in) != QueueCheck::Ok) return stopWith(self, nullptr, kNoOutQueue), nullptr;
  const int16_t err = setupOwnQueue(s, self->__oq, self->pbyBufferOutQueue, self->nSizeOutQueue, generator);
  if (err != 0) return stopWith(self, nullptr, err), nullptr;
  std::memcpy(self->__oq.strProgramName, in.queue()->strProgramName, sizeof self->__oq.strProgramName);
  if (s.instanceState<StageState>(self->__handle, self)) s.instanceStates.erase(self->__handle);   // never a copy's
  owned->owner = self;
  owned->running = true;
  StageState* st = owned.get();
  const uint64_t id = s.nextInstanceState++;
  s.instanceStates[id] = std::move(owned);
  self->__handle = id;
  self->poqDataOut = &self->__oq;
  self->bBusy = true;
  return st;
}

// One call's work: corrected elements into the own ring while it has room, input elements
// into the core while its backlog is small; bEndOfList and bDone once everything is out.
// Returns the error (0 none); coreError maps the core's error.
template <class FB, class CoreError>
void runStage(FB* self, MotionSession& s, StageState& st, CoreError coreError) {
  if (self->bAbort) return stopWith(self, &st, kNoError);
  QueueView out;
  sm3::SMC_OUTQUEUE& oq = self->__oq;
  if (openQueue(s, &oq, out) != QueueCheck::Ok || oq.pbyBuffer != self->pbyBufferOutQueue ||
      oq.nCapacity != self->nSizeOutQueue / sizeof(sm3::SMC_GEOINFO))
    return stopWith(self, &st, kQueueChanged);
  self->poqDataOut = &oq;
  QueueView in;
  if (openQueue(s, inputQueue(self), in) != QueueCheck::Ok) return stopWith(self, &st, kNoOutQueue);
  auto drain = [&] {
    while (st.hasOutput() && out.room() > 0) {
      out.push(st.front());
      st.pop();
    }
  };
  uint32_t budget = kElementsPerCall;
  for (;;) {
    drain();
    if (st.outputSize() >= kBacklog || budget == 0) break;
    if (in.empty()) {
      if (!in.endOfList() || st.finishing) break;
      st.finishing = true;
      st.finish();
      continue;
    }
    stc::cnc::Element e;
    if (!fromGeoInfo(in.at(0), e)) return stopWith(self, &st, kNoOutQueue);
    in.pop();
    --budget;
    if (!st.push(e)) {
      drain();
      return stopWith(self, &st, coreError());
    }
  }
  if (st.finishing && !st.hasOutput()) {
    oq.bEndOfList = true;
    self->bDone = true;
    stopWith(self, &st, kNoError);
  }
}

// The common frame of both blocks: bExecute FALSE passes the input through.
template <class FB, class Make, class CoreError>
void stageCall(FB* self, uint8_t generator, Make make, CoreError coreError) {
  MotionSession& s = MotionSession::current();
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  StageState* st = s.instanceState<StageState>(self->__handle, self);
  if (!self->bExecute) {
    clearFlags(self);
    if (st) st->running = false;
    self->poqDataOut = self->poqDataIn;   // disabled: the output is the input
    return;
  }
  if (edge) {
    clearFlags(self);
    if (st) st->running = false;
    auto owned = make(self);
    if (!owned) return;
    st = startStage(self, s, std::move(owned), generator);
  }
  if (!st || !st->running) return;
  runStage(self, s, *st, [&] { return coreError(*st); });
}

bool validRadius(double r) { return std::isfinite(r) && r >= 0 && r <= 1e9; }

void SMC_ToolCorr(sm3::SMC_ToolCorr* self) {
  stageCall(
      self, kGenToolCorr,
      [](sm3::SMC_ToolCorr* fb) -> std::unique_ptr<StageState> {
        const int mode = static_cast<int>(fb->eMode);
        if (mode < 0 || mode > 2 || !validRadius(fb->dToolRadius)) {
          stopWith(fb, nullptr, kInvalidParameter);
          return nullptr;
        }
        return std::make_unique<ToolCorrState>(static_cast<stc::cnc::ToolCorrMode>(mode), fb->dToolRadius);
      },
      [self](StageState& base) -> int16_t {
        auto& st = static_cast<ToolCorrState&>(base);
        std::cerr << "SMC_ToolCorr: " << self->__oq.strProgramName << ": " << st.tc.errorMessage() << "\n";
        std::cerr.flush();
        return st.tc.error() == stc::cnc::ToolCorrError::NotInPlane ? kNotPlanar : kInvalidParameter;
      });
  // dToolRadius may change while running (for the sections that start later).
  if (self->bBusy) {
    MotionSession& s = MotionSession::current();
    if (auto* st = s.instanceState<StageState>(self->__handle, self)) {
      auto& tcs = static_cast<ToolCorrState&>(*st);
      if (!tcs.tc.setDefaultRadius(self->dToolRadius)) stopWith(self, st, kInvalidParameter);
    }
  }
}

void SMC_AvoidLoop(sm3::SMC_AvoidLoop* self) {
  stageCall(
      self, kGenAvoidLoop, [](sm3::SMC_AvoidLoop*) -> std::unique_ptr<StageState> { return std::make_unique<AvoidLoopState>(); },
      [](StageState&) -> int16_t { return kInvalidParameter; });   // LoopAvoider never fails
}

}  // namespace

namespace stc::motion::sm3face {
void registerSm3ToolCorrNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(SMC_ToolCorr, SMC_ToolCorr)
  STC_SM3_NATIVE(SMC_AvoidLoop, SMC_AvoidLoop)
}
}  // namespace stc::motion::sm3face
