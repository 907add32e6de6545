// Access to an SMC_OUTQUEUE of the program from the natives of the CNC pipeline
// blocks (docs/cnc.md, "SMC_OUTQUEUE").  Every block that reads a queue it was
// given (poqDataIn) opens it with openQueue first: the pointer comes from the
// program, so the queue and its whole buffer must lie in the program's static
// memory and its positions must be consistent; a broken queue is an error, never
// a stray read.  Blocks that produce a queue of their own (tool correction,
// smoothing, loop avoidance) set it up over the user's buffer with setupOwnQueue.
#pragma once

#include <cstdint>

#include "sm3_native.h"
#include "stdlib-motion/MotionNatives.h"
#include "stdlib-motion/cnc/Element.h"

namespace stc::motion::sm3face {

namespace sm3 = stc::native::sm3;

constexpr uint16_t kOutQueueStructId = 0x9878;
// SMC_OUTQUEUE.byGenerator codes of our blocks (the CODESYS values are not documented;
// these are ours, docs/cnc.md).
enum : uint8_t {
  kGenDecoder = 1,
  kGenToolCorr = 2,
  kGenAvoidLoop = 3,
  kGenSmoothPath = 4,
  kGenCheckVelocities = 5,
};

enum class QueueCheck : uint8_t {
  Ok,
  Null,          // no queue (pointer 0)
  NotInImage,    // the queue or its buffer outside the program's static memory
  BadId,         // wOUTQUEUEStructID is not 16#9878
  Broken,        // capacity 0, a position beyond the capacity, bFull with different positions, misaligned buffer
};

// A checked view of a queue: positions are counted from nReadPos (0 = the oldest).
class QueueView {
public:
  QueueView() = default;
  sm3::SMC_OUTQUEUE* queue() const { return q_; }
  uint32_t capacity() const { return q_->nCapacity; }
  uint32_t size() const {
    if (q_->bFull) return q_->nCapacity;
    return (q_->nWritePos + q_->nCapacity - q_->nReadPos) % q_->nCapacity;
  }
  uint32_t room() const { return capacity() - size(); }
  bool empty() const { return size() == 0; }
  bool full() const { return q_->bFull; }
  bool endOfList() const { return q_->bEndOfList; }
  // The i-th element from the read position (i < size()).
  sm3::SMC_GEOINFO& at(uint32_t i) const { return buf_[(q_->nReadPos + i) % q_->nCapacity]; }
  // Index in the buffer of the i-th element from the read position.
  uint32_t slot(uint32_t i) const { return (q_->nReadPos + i) % q_->nCapacity; }
  // Removes the oldest element.
  void pop() const {
    q_->nReadPos = (q_->nReadPos + 1) % q_->nCapacity;
    q_->bFull = false;
  }
  // Appends `g` (room() > 0).
  void push(const sm3::SMC_GEOINFO& g) const;
  void push(const cnc::Element& e) const;

private:
  friend QueueCheck openQueue(const MotionSession&, sm3::SMC_OUTQUEUE*, QueueView&);
  sm3::SMC_OUTQUEUE* q_ = nullptr;
  sm3::SMC_GEOINFO* buf_ = nullptr;
};

// Checks the queue `q` (from the program) and makes `out` a view of it.
QueueCheck openQueue(const MotionSession& s, sm3::SMC_OUTQUEUE* q, QueueView& out);

// Sets up `q` (a member of a block instance) as an empty queue over the program's buffer
// (`bytes` bytes at `buffer`).  Returns 0 or the SMC_ERROR number: 1800 (no buffer, or not
// in static memory), 1502 (misaligned), 1080 (fewer than minElements elements).
int16_t setupOwnQueue(const MotionSession& s, sm3::SMC_OUTQUEUE& q, void* buffer, uint64_t bytes,
                      uint8_t generator, uint32_t minElements = 5);

}  // namespace stc::motion::sm3face
