// What the interpolator blocks of the SoftMotion face share (Sm3Interpolator.cpp,
// Sm3Interpolator2Dir.cpp, Sm3XInterpolator.cpp): their outputs from a core's
// IpoOutput, and handing checked queue elements to a core.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

#include "stdlib-motion/cnc/Interpolator.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/codesys_sm3/Sm3GeoInfo.h"
#include "stdlib-motion/codesys_sm3/Sm3Queue.h"

namespace stc::motion::sm3face {

// piSetPosition (all 11 axes), iStatus, bWorking, iActObjectSourceNo, vecActTangent,
// iLastSwitch, dwSwitches, dWayPos and, where the block has them, dVel and wM.
template <class T>
void publishIpoOutputs(T* self, double wayBase, const cnc::IpoOutput& o) {
  sm3::SMC_POSINFO& p = self->piSetPosition;
  p.dX = o.pos[cnc::AxX];
  p.dY = o.pos[cnc::AxY];
  p.dZ = o.pos[cnc::AxZ];
  p.dA = o.pos[cnc::AxA];
  p.dB = o.pos[cnc::AxB];
  p.dC = o.pos[cnc::AxC];
  p.dA1 = o.pos[cnc::AxP];
  p.dA2 = o.pos[cnc::AxQ];
  p.dA3 = o.pos[cnc::AxU];
  p.dA4 = o.pos[cnc::AxV];
  p.dA5 = o.pos[cnc::AxW];
  p.dA6 = 0;
  self->iStatus = static_cast<int16_t>(o.status);
  self->bWorking = o.working;
  self->iActObjectSourceNo = static_cast<int16_t>(std::min<int32_t>(o.sourceLine, INT16_MAX));
  self->vecActTangent.dX = o.tangent[0];
  self->vecActTangent.dY = o.tangent[1];
  self->vecActTangent.dZ = o.tangent[2];
  self->iLastSwitch = o.lastSwitch;
  self->dwSwitches = o.switches;
  self->dWayPos = wayBase + o.wayPos;
  if constexpr (requires { self->dVel; }) self->dVel = o.vel;
  if constexpr (requires { self->wM; }) self->wM = o.m;
}

constexpr int16_t kNoOutQueue = 1501;     // SMC_NO_OUTQUEUE_TYPE: no queue, or not one
constexpr int16_t kQueueChanged = 1801;   // SMC_SA_QUEUE_CHANGED_DURING_OP

// Opens the queue of a running interpolator: 0, or SMC_SA_QUEUE_CHANGED_DURING_OP (1801) when
// poqDataIn is not the queue of the rising edge any more, is broken, or holds fewer elements
// than the block has taken from it; SMC_NO_OUTQUEUE_TYPE (1501) when it is no queue now.
inline int16_t openRunQueue(const MotionSession& s, void* poqDataIn, const sm3::SMC_OUTQUEUE* atEdge, uint32_t fed,
                            QueueView& v) {
  auto* q = static_cast<sm3::SMC_OUTQUEUE*>(poqDataIn);
  const QueueCheck qc = openQueue(s, q, v);
  if (q != atEdge) return kQueueChanged;
  if (qc != QueueCheck::Ok) return qc == QueueCheck::Broken ? kQueueChanged : kNoOutQueue;
  if (fed > v.size()) return kQueueChanged;   // a consumer took elements it does not own
  return 0;
}

constexpr uint32_t kMaxIpoTimeUs = 1000000;

template <class T>
void clearRunFlags(T* self) {
  self->bDone = self->bBusy = self->bError = false;
  self->wErrorID = 0;
}

// Ends the run of an interpolator block: its state leaves the session.
template <class State, class T>
void dropRunState(MotionSession& s, T* self) {
  if (s.instanceState<State>(self->__handle, self)) s.instanceStates.erase(self->__handle);
  self->__handle = 0;
}

// The rising-edge checks every interpolator block makes: 0 and `v` the queue, or the error:
// the instance not in static memory or no queue (1501), dwIpoTime 0 or above 1 s (1009,
// where the block has it), dLastWayPos not finite or beyond 1e15 (1820).
template <class T>
int16_t checkRunStart(const MotionSession& s, T* self, QueueView& v) {
  if (!s.inImage(self, sizeof *self)) return kNoOutQueue;
  if (openQueue(s, static_cast<sm3::SMC_OUTQUEUE*>(self->poqDataIn), v) != QueueCheck::Ok) return kNoOutQueue;
  if constexpr (requires { self->dwIpoTime; })
    if (self->dwIpoTime == 0 || self->dwIpoTime > kMaxIpoTimeUs) return cnc::kIpoIpoTimeZero;
  if (!std::isfinite(self->dLastWayPos) || std::fabs(self->dLastWayPos) > 1e15) return cnc::kIpoInvalidParameter;
  return 0;
}

// Puts a run's state into the session under a new handle kept by the instance; bBusy rises.
template <class State, class T>
State& installRunState(MotionSession& s, T* self, std::unique_ptr<State> owned) {
  owned->owner = self;
  State& st = *owned;
  const uint64_t id = s.nextInstanceState++;
  s.instanceStates[id] = std::move(owned);
  self->__handle = id;
  self->bBusy = true;
  self->iLastSwitch = 0;
  self->dwSwitches = 0;
  if constexpr (requires { self->wM; }) self->wM = 0;
  return st;
}

// The per-cycle controls of a time-based interpolator block; `slowStop` adds a stop along
// the path (bExecute fell, a queue error).
template <class T>
cnc::IpoControls ipoControls(const T* self, bool slowStop) {
  cnc::IpoControls c;
  c.slowStop = self->bSlow_Stop || slowStop;
  c.quickStop = self->bQuick_Stop;
  c.emergencyStop = self->bEmergency_Stop;
  c.waitAtNextStop = self->bWaitAtNextStop;
  c.singleStep = self->bSingleStep;
  c.acknM = self->bAcknM;
  c.override = self->dOverride;
  c.quickDecel = self->dQuickDeceleration;
  return c;
}

// Hands the queue's elements from position `fed` on to `ipo` while it wants more; with
// `checkedOnly` only those SMC_CheckVelocities has finished (wIntMark bit 8).  Returns 0 or
// SMC_INT_PATH_EXCEEDED (1007) for an element that does not convert.
template <class Ipo>
int16_t feedFromQueue(const QueueView& v, uint32_t& fed, Ipo& ipo, bool checkedOnly) {
  while (fed < v.size() && ipo.wantsMore()) {
    const sm3::SMC_GEOINFO& g = v.at(fed);
    if (checkedOnly && !(g.wIntMark & cnc::MarkVelChecked)) break;   // not final yet
    cnc::Element e;
    if (!fromGeoInfo(g, e)) return cnc::kIpoPathExceeded;
    if (ipo.feed(e) != 0) break;
    ++fed;
  }
  if (v.endOfList() && fed == v.size()) ipo.endOfList();
  return 0;
}

// The start of every call of a time-based interpolator block (SMC_Interpolator,
// SMC_Interpolator2Dir): the rising edge of bExecute starts a run (startRun), bAbort drops it
// where it stands, bExecute FALSE marks it stopping.  Returns the run's state, or null when
// no run goes on.
template <class State, class T, class Start>
State* beginTimedRunCall(MotionSession& s, T* self, Start startRun) {
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  State* st = s.instanceState<State>(self->__handle, self);
  if (self->bAbort) {   // abandon the path where it stands (no ramp: after an emergency stop)
    if (st) dropRunState<State>(s, self);
    clearRunFlags(self);
    self->bWorking = false;
    self->dVel = 0;
    if constexpr (requires { self->eDirection; }) self->eDirection = 0;
    self->iStatus = static_cast<int16_t>(cnc::IpoStatus::Unknown);
    return nullptr;
  }
  if (edge) {
    if (st) dropRunState<State>(s, self);
    clearRunFlags(self);
    startRun(self, s);
    st = s.instanceState<State>(self->__handle, self);
  }
  if (!st) {
    if (!self->bExecute) clearRunFlags(self);
    return nullptr;
  }
  if (!self->bExecute) st->stopping = true;
  return st;
}

// Opens the run's queue and hands the elements SMC_CheckVelocities has finished to `ipo`
// (not while stopping).  Returns 0 or the queue error (1501, 1801, 1006 for a queue that
// does not come from SMC_CheckVelocities, 1007).
template <class State, class Ipo>
int16_t takeCheckedElements(const MotionSession& s, void* poqDataIn, State& st, Ipo& ipo, QueueView& v) {
  int16_t err = openRunQueue(s, poqDataIn, st.queue, st.fed, v);
  if (err != 0 || ipo.error() != 0 || st.stopping) return err;
  if (st.fed < v.size() && st.queue->byGenerator != kGenCheckVelocities) return cnc::kIpoNoCheckVelocities;
  return feedFromQueue(v, st.fed, ipo, true);
}

// The end of every call of a time-based interpolator block: bError / wErrorID from the queue
// or the core (the warning SMC_INT_DATA_UNDERRUN otherwise), bDone / bBusy, and the run
// dropped once it stands after bExecute fell.
template <class State, class T, class Ipo>
void endTimedRunCall(MotionSession& s, T* self, const State& st, const Ipo& ipo, const cnc::IpoOutput& o,
                     int16_t queueError) {
  const int16_t err = queueError != 0 ? queueError : ipo.error();
  if (err != 0) {
    self->bError = true;
    self->wErrorID = err;
    self->bBusy = false;
  } else {
    self->wErrorID = ipo.warning();
    self->bDone = o.finished;
    self->bBusy = !o.finished;
  }
  if (st.stopping && o.vel == 0) {   // bExecute FALSE: dropped once at rest
    dropRunState<State>(s, self);
    clearRunFlags(self);
    self->bWorking = false;
    if constexpr (requires { self->eDirection; }) self->eDirection = 0;
  }
}

}  // namespace stc::motion::sm3face
