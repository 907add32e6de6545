// SMC_OUTQUEUE access for the CNC pipeline natives (Sm3Queue.h).
#include "stdlib-motion/codesys_sm3/Sm3Queue.h"

#include <algorithm>

#include "stdlib-motion/codesys_sm3/Sm3GeoInfo.h"

namespace stc::motion::sm3face {

namespace {
constexpr uint64_t kMaxElements = 1u << 24;   // a 11 GB buffer: beyond any static memory
}

QueueCheck openQueue(const MotionSession& s, sm3::SMC_OUTQUEUE* q, QueueView& out) {
  out = QueueView{};
  if (!q) return QueueCheck::Null;
  if (!s.inImage(q, sizeof *q)) return QueueCheck::NotInImage;
  if (q->wOUTQUEUEStructID != kOutQueueStructId) return QueueCheck::BadId;
  auto* buf = reinterpret_cast<sm3::SMC_GEOINFO*>(q->pbyBuffer);
  if (q->nCapacity == 0 || q->nCapacity > kMaxElements || q->nReadPos >= q->nCapacity ||
      q->nWritePos >= q->nCapacity || (q->bFull && q->nReadPos != q->nWritePos) ||
      reinterpret_cast<uintptr_t>(buf) % alignof(sm3::SMC_GEOINFO) != 0)
    return QueueCheck::Broken;
  if (!buf || !s.inImage(buf, uint64_t{q->nCapacity} * sizeof(sm3::SMC_GEOINFO))) return QueueCheck::NotInImage;
  out.q_ = q;
  out.buf_ = buf;
  return QueueCheck::Ok;
}

void QueueView::push(const sm3::SMC_GEOINFO& g) const {
  buf_[q_->nWritePos] = g;
  q_->nWritePos = (q_->nWritePos + 1) % q_->nCapacity;
  if (q_->nWritePos == q_->nReadPos) q_->bFull = true;
}

void QueueView::push(const cnc::Element& e) const {
  toGeoInfo(e, buf_[q_->nWritePos]);
  q_->nWritePos = (q_->nWritePos + 1) % q_->nCapacity;
  if (q_->nWritePos == q_->nReadPos) q_->bFull = true;
}

int16_t setupOwnQueue(const MotionSession& s, sm3::SMC_OUTQUEUE& q, void* buffer, uint64_t bytes, uint8_t generator,
                      uint32_t minElements) {
  if (!buffer || !s.inImage(buffer, bytes)) return 1800;   // SMC_SA_QUEUE_NOT_IN_BUFFER
  if (reinterpret_cast<uintptr_t>(buffer) % alignof(sm3::SMC_GEOINFO) != 0) return 1502;   // SMC_GEOINFO_BUFFER_MISALIGNED
  const uint64_t capacity = bytes / sizeof(sm3::SMC_GEOINFO);
  if (capacity < minElements) return 1080;   // SMC_WAR_INT_OUTQUEUE_TOO_SMALL
  q.wOUTQUEUEStructID = kOutQueueStructId;
  q.pbyBuffer = buffer;
  q.nCapacity = static_cast<uint32_t>(std::min<uint64_t>(capacity, kMaxElements));
  q.nReadPos = q.nWritePos = 0;
  q.bFull = false;
  q.bEndOfList = false;
  q.byGenerator = generator;
  q.bReCheckVelocities = false;
  q.nNumReservedEntries = 0;
  return 0;
}

}  // namespace stc::motion::sm3face
