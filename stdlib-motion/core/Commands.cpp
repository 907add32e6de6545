#include "stdlib-motion/core/Commands.h"

namespace stc::motion {

uint32_t CommandTable::move(Kernel& k, Axis& ax, FbKind kind, const MoveInputs& in, const CallCtx& c) {
  const uint32_t id = next_++;
  Entry& e = ring_[id % kRing];
  // The entry's previous command, if any, is kRing ids old: it ends now if it is still queued.
  if (e.slot && (e.slot->out.busy)) k.finish(*e.slot, &c, c.cycle, false, true, Error::None);
  FbSlot& fb = k.slot(e.handle, &e, kind, nullptr);
  fb.kind = kind;
  fb.functionStyle = true;
  e.id = id;
  e.slot = &fb;
  k.callMove(fb, ax, false, in, c);   // a falling edge first, so that the slot starts afresh
  k.callMove(fb, ax, true, in, c);
  return id;
}

const FbSlot* CommandTable::slotOf(uint32_t id) const {
  if (id == 0 || id >= next_) return nullptr;
  const Entry& e = ring_[id % kRing];
  return e.id == id ? e.slot : nullptr;
}

CommandStatus CommandTable::status(uint32_t id) const {
  const FbSlot* fb = slotOf(id);
  if (!fb) return CommandStatus::Unknown;
  if (fb->out.error) return CommandStatus::Error;
  if (fb->out.aborted) return CommandStatus::Aborted;
  if (fb->out.done) return CommandStatus::Done;
  if (fb->out.active) return CommandStatus::Active;
  return fb->out.busy ? CommandStatus::Queued : CommandStatus::Unknown;
}

Error CommandTable::error(uint32_t id) const {
  const FbSlot* fb = slotOf(id);
  return fb ? fb->out.errorId : Error::None;
}

}  // namespace stc::motion
