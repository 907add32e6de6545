// SMC_ReadNCFile and SMC_NCDecoder (sm3_cnc_decoder.st; docs/cnc.md, "The pipeline
// blocks"): a G-code file of the data directory read into a buffer of the program, and
// decoded by stdlib-motion/cnc's Decoder into the user's SMC_GEOINFO ring (SMC_OUTQUEUE).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/codesys_sm3/Sm3GeoInfo.h"
#include "stdlib-motion/codesys_sm3/Sm3NcProgram.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

// SMC_ERROR numbers of these blocks (sm3_types.st).
enum : int16_t {
  kNoError = 0,
  kQueueTooSmall = 1080,      // SMC_WAR_INT_OUTQUEUE_TOO_SMALL: fewer than 5 elements
  kNoCncRef = 1500,           // SMC_NO_CNC_REF_TYPE: ncprog not filled by SMC_ReadNCFile (or its text not in static memory)
  kBufferMisaligned = 1502,   // SMC_GEOINFO_BUFFER_MISALIGNED
  kNotInBuffer = 1800,        // SMC_SA_QUEUE_NOT_IN_BUFFER: buffer (or the instance) not in static memory
  kQueueChanged = 1801,       // SMC_SA_QUEUE_CHANGED_DURING_OP: the queue's buffer, capacity or positions broken
  kInvalidParameter = 1820,   // SMC_OS_INVALID_PARAMETER: start position not finite or beyond 1e10
  kFileDoesntExist = 2000,    // SMC_RNCF_FILE_DOESNT_EXIST
  kNoBuffer = 2001,           // SMC_RNCF_NO_BUFFER
  kNotVarList = 2005,         // SMC_RNCF_NOT_VARLIST
  kBufferTooSmall = 2002,     // SMC_RNCF_BUFFER_TOO_SMALL
};

constexpr uint16_t kOutQueueId = 0x9878;
constexpr uint8_t kGeneratorDecoder = 1;
constexpr uint32_t kMinElements = 5;
constexpr uint32_t kBlocksPerCall = 100;
constexpr size_t kStaging = 8;

template <size_t N>
void putString(char (&dst)[N], std::string_view s) {
  const size_t n = std::min(s.size(), N - 1);
  std::memcpy(dst, s.data(), n);
  dst[n] = 0;
}
template <size_t N>
std::string getString(const char (&src)[N]) {
  return std::string(src, strnlen(src, N));
}

// ---------------------------------------------------------------- SMC_ReadNCFile

void SMC_ReadNCFile(sm3::SMC_ReadNCFile* self) {
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  if (!edge) {
    if (!self->bExecute) {
      self->bDone = self->bBusy = self->bError = self->bExecuteDecoder = false;
      self->ErrorID = kNoError;
    }
    return;
  }
  self->bDone = self->bBusy = self->bError = self->bExecuteDecoder = false;
  self->ErrorID = kNoError;
  self->dwFileSize = self->dwPos = 0;
  auto fail = [&](int16_t id) {
    self->bError = true;
    self->ErrorID = id;
  };
  MotionSession& s = MotionSession::current();
  if (self->pvl && !usableVarList(s, self->pvl)) return fail(kNotVarList);
  if (!self->pBuffer || self->dwBufferSize == 0 || !s.inImage(self->pBuffer, self->dwBufferSize)) return fail(kNoBuffer);
  const std::string name = getString(self->sFileName);
  const uint64_t room = std::min<uint64_t>(self->dwBufferSize, kMaxNcProgramBytes);
  std::string text;
  uint64_t size = 0;
  const NcFileRead r = readNcFile(s, name, room, text, size);
  self->dwFileSize = static_cast<uint32_t>(std::min<uint64_t>(size, UINT32_MAX));
  if (r == NcFileRead::Missing) return fail(kFileDoesntExist);
  if (r == NcFileRead::TooBig) return fail(kBufferTooSmall);
  std::memcpy(self->pBuffer, text.data(), text.size());
  if (text.size() < self->dwBufferSize) static_cast<uint8_t*>(self->pBuffer)[text.size()] = 0;
  sm3::SMC_CNC_REF& p = self->ncprog;
  p.wCNCREFStructID = kCncRefStructId;
  p.pText = static_cast<uint8_t*>(self->pBuffer);
  p.dwTextSize = static_cast<uint32_t>(text.size());
  putString(p.strFileName, name);
  p.fDefaultVel = self->fDefaultVel;
  p.fDefaultAccel = self->fDefaultAccel;
  p.fDefaultDecel = self->fDefaultDecel;
  p.fDefaultVelFF = self->fDefaultVelFF;
  p.fDefaultAccelFF = self->fDefaultAccelFF;
  p.fDefaultDecelFF = self->fDefaultDecelFF;
  p.pvl = self->pvl;
  self->dwFileSize = static_cast<uint32_t>(text.size());
  self->dwPos = static_cast<uint32_t>(text.size());
  self->bDone = self->bExecuteDecoder = true;
}

// ---------------------------------------------------------------- SMC_NCDecoder

// The decoder of one SMC_NCDecoder instance, made at the rising edge of bExecute.
struct NcState : MotionSession::InstanceState {
  stc::SourceManager sm;
  stc::DiagnosticsEngine diags{sm};
  uint32_t file = 0;
  std::unique_ptr<NcVariables> vars;   // the program's $name$ (before dec: it outlives it)
  std::unique_ptr<stc::cnc::Decoder> dec;
  stc::cnc::ElementQueue staging{kStaging};
  size_t printed = 0;        // diagnostics already written to stderr
  bool running = false;
  bool waitSync = false;     // a G75 element is queued: wait until the queue is empty
};

bool finite(const sm3::SMC_POSINFO& p) {
  for (double v : {p.dX, p.dY, p.dZ, p.dA, p.dB, p.dC, p.dA1, p.dA2, p.dA3, p.dA4, p.dA5})
    if (!std::isfinite(v) || std::fabs(v) > 1e10) return false;
  return true;
}

void stop(sm3::SMC_NCDecoder* self, NcState* st, int16_t error) {
  if (st) st->running = false;
  self->bBusy = false;
  if (error != kNoError) {
    self->bError = true;
    self->wErrorID = error;
  }
}

// Moves staged elements into the user's ring while it has room.
void flush(NcState& st, sm3::SMC_OUTQUEUE& q) {
  auto* buf = reinterpret_cast<sm3::SMC_GEOINFO*>(q.pbyBuffer);
  while (!st.staging.empty() && !q.bFull) {
    toGeoInfo(st.staging.front(), buf[q.nWritePos]);
    st.staging.pop();
    q.nWritePos = (q.nWritePos + 1) % q.nCapacity;
    if (q.nWritePos == q.nReadPos) q.bFull = true;
  }
}

void lineOutputs(sm3::SMC_NCDecoder* self, const NcState& st) {
  const uint32_t line = st.dec->lastLine();
  self->iLineNumberDecoded = static_cast<int16_t>(std::min<uint32_t>(line, INT16_MAX));
  if (line == 0 || line > st.sm.lineCount(st.file)) return putString(self->GCodeText, "");
  std::string_view text = st.sm.lineText(stc::SourceLoc{st.file, st.sm.lineStart(st.file, line)});
  while (!text.empty() && (text.back() == '\r' || text.back() == '\n')) text.remove_suffix(1);
  putString(self->GCodeText, text);
}

void startDecoder(sm3::SMC_NCDecoder* self, MotionSession& s) {
  // The queue lives in this instance, so the instance must be static too.
  if (!s.inImage(self, sizeof *self)) return stop(self, nullptr, kNotInBuffer);
  const sm3::SMC_CNC_REF* p = self->ncprog;
  if (!usableCncRef(s, p)) return stop(self, nullptr, kNoCncRef);
  if (p->pvl && !usableVarList(s, p->pvl)) return stop(self, nullptr, kNotVarList);
  auto* buffer = reinterpret_cast<uint8_t*>(self->pbyBufferOutQueue);
  if (!buffer || !s.inImage(buffer, self->nSizeOutQueue)) return stop(self, nullptr, kNotInBuffer);
  if (reinterpret_cast<uintptr_t>(buffer) % alignof(sm3::SMC_GEOINFO) != 0) return stop(self, nullptr, kBufferMisaligned);
  const uint64_t capacity = self->nSizeOutQueue / sizeof(sm3::SMC_GEOINFO);
  if (capacity < kMinElements) return stop(self, nullptr, kQueueTooSmall);
  if (!finite(self->piStartPosition)) return stop(self, nullptr, kInvalidParameter);

  // A new decoder (the previous one, if any, is dropped).
  if (s.instanceState<NcState>(self->__handle, self)) s.instanceStates.erase(self->__handle);   // never another instance's (a copy)
  auto owned = std::make_unique<NcState>();
  NcState& st = *owned;
  st.owner = self;
  const uint64_t id = s.nextInstanceState++;
  s.instanceStates[id] = std::move(owned);
  self->__handle = id;

  std::string name = getString(p->strFileName);
  if (name.empty()) name = "ncprog";
  st.file = st.sm.addBuffer(name, std::string(reinterpret_cast<const char*>(p->pText), p->dwTextSize));
  stc::cnc::DecoderOptions o;
  o.skipSlashBlocks = self->bStepSuppress;
  const sm3::SMC_POSINFO& sp = self->piStartPosition;
  o.startPosition = {sp.dX, sp.dY, sp.dZ, sp.dA, sp.dB, sp.dC, sp.dA1, sp.dA2, sp.dA3, sp.dA4, sp.dA5};
  auto dflt = [](double v) { return std::isfinite(v) && v > 0 ? v : 0.0; };
  o.defaultVel = dflt(p->fDefaultVel);
  o.defaultAcc = dflt(p->fDefaultAccel);
  o.defaultDec = dflt(p->fDefaultDecel);
  o.defaultRapidVel = dflt(p->fDefaultVelFF);
  o.defaultRapidAcc = dflt(p->fDefaultAccelFF);
  o.defaultRapidDec = dflt(p->fDefaultDecelFF);
  o.stopAtFirstError = true;
  st.vars = std::make_unique<NcVariables>(s, p->pvl);
  st.dec = std::make_unique<stc::cnc::Decoder>(st.sm, st.file, st.diags, o, st.vars.get());
  st.running = true;

  sm3::SMC_OUTQUEUE& q = self->__oq;
  const bool append = self->bAppend && q.wOUTQUEUEStructID == kOutQueueId && q.pbyBuffer == self->pbyBufferOutQueue &&
                      q.nCapacity == capacity && q.nReadPos < capacity && q.nWritePos < capacity;
  q.wOUTQUEUEStructID = kOutQueueId;
  q.pbyBuffer = self->pbyBufferOutQueue;
  q.nCapacity = static_cast<uint32_t>(capacity);
  if (!append) {
    q.nReadPos = q.nWritePos = 0;
    q.bFull = false;
  }
  q.bEndOfList = false;
  q.byGenerator = kGeneratorDecoder;
  q.bReCheckVelocities = false;
  q.nNumReservedEntries = 0;
  putString(q.strProgramName, name);
  self->poqDataOut = &q;
  self->bBusy = true;
}

void SMC_NCDecoder(sm3::SMC_NCDecoder* self) {
  MotionSession& s = MotionSession::current();
  const bool edge = self->bExecute && !self->__prev;
  self->__prev = self->bExecute;
  NcState* st = s.instanceState<NcState>(self->__handle, self);
  if (!self->bExecute || edge) {
    self->bDone = self->bBusy = self->bError = false;
    self->wErrorID = kNoError;
    if (st) st->running = false;
    if (!self->bExecute) return;
    startDecoder(self, s);
    if (!self->bBusy) return;
    st = s.instanceState<NcState>(self->__handle, self);
  }
  if (!st || !st->running) return;
  if (self->bAbort) return stop(self, st, kNoError);

  sm3::SMC_OUTQUEUE& q = self->__oq;
  if (q.wOUTQUEUEStructID != kOutQueueId || q.pbyBuffer != self->pbyBufferOutQueue || q.nCapacity == 0 ||
      q.nCapacity != self->nSizeOutQueue / sizeof(sm3::SMC_GEOINFO) || q.nReadPos >= q.nCapacity || q.nWritePos >= q.nCapacity ||
      (q.bFull && q.nReadPos != q.nWritePos))
    return stop(self, st, kQueueChanged);
  self->poqDataOut = &q;

  uint32_t budget = kBlocksPerCall;
  for (;;) {
    flush(*st, q);
    if (!st->staging.empty() || q.bFull) break;   // wait for the consumer
    if (st->dec->finished()) {
      q.bEndOfList = true;
      self->bDone = true;
      stop(self, st, kNoError);
      break;
    }
    if (st->waitSync) {
      if (q.nReadPos != q.nWritePos) break;   // G75: until the consumer has taken everything
      st->waitSync = false;
    }
    if (budget == 0) break;
    const stc::cnc::StepResult r = st->dec->step(st->staging, budget);
    budget -= std::min(budget, r.blocks);
    printNewDiagnostics(st->diags, st->printed);
    lineOutputs(self, *st);
    if (st->dec->errorCount() > 0) {
      flush(*st, q);   // the elements before the error stay in the queue; bEndOfList stays FALSE
      return stop(self, st, static_cast<int16_t>(st->dec->firstError()));
    }
    if (r.status == stc::cnc::StepStatus::Sync) st->waitSync = true;
    if (r.blocks == 0 && r.elements == 0 && r.status == stc::cnc::StepStatus::Progress) break;
  }
}

// A [[cnc_program]] of project.toml into its SMC_CNC_REF: the text stays with the controller.
void bindHeldProgram(void* var, const CncProgramConfig& c) {
  auto& p = *static_cast<sm3::SMC_CNC_REF*>(var);
  p.wCNCREFStructID = kCncRefStructId;
  p.pText = const_cast<char*>(c.text->data());
  p.dwTextSize = static_cast<uint32_t>(c.text->size());
  putString(p.strFileName, c.name);
  p.fDefaultVel = c.defaultVel;
  p.fDefaultAccel = c.defaultAccel;
  p.fDefaultDecel = c.defaultDecel;
  p.fDefaultVelFF = c.defaultVelFF;
  p.fDefaultAccelFF = c.defaultAccelFF;
  p.fDefaultDecelFF = c.defaultDecelFF;
  p.pvl = nullptr;
}

}  // namespace

namespace stc::motion::sm3face {
void registerSm3NcNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(SMC_ReadNCFile, SMC_ReadNCFile)
  STC_SM3_NATIVE(SMC_NCDecoder, SMC_NCDecoder)
  lib.addCncProgramFace({"SMC_CNC_REF", &bindHeldProgram});
}
}  // namespace stc::motion::sm3face
