// Function-style motion commands (the Hollysys HMC_ style): a function call
// queues a command and returns its id at once; the program may poll it or
// wait for it on its fiber (vm::waitUntil).  The PLCopen FB rules (edges,
// "must be called in every cycle", held / one-cycle outputs) do not apply:
// the command's slot belongs to this table, not to an ST instance.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include "stdlib-motion/core/Kernel.h"

namespace stc::motion {

enum class CommandStatus : uint8_t { Unknown = 0, Queued = 1, Active = 2, Done = 3, Aborted = 4, Error = 5 };

class CommandTable {
public:
  // Ids are 1, 2, 3 ...; a finished command's slot is reused after kRing newer ids.
  static constexpr uint32_t kRing = 1024;

  // Queues a MoveAbsolute/MoveRelative (in.bufferMode, usually Buffered) on ax.
  // Returns the id; a command refused at once still gets an id (status Error, error()).
  uint32_t move(Kernel& k, Axis& ax, FbKind kind, const MoveInputs& in, const CallCtx& c);
  CommandStatus status(uint32_t id) const;
  Error error(uint32_t id) const;
  bool finished(uint32_t id) const {
    CommandStatus s = status(id);
    return s != CommandStatus::Queued && s != CommandStatus::Active;
  }

private:
  const FbSlot* slotOf(uint32_t id) const;
  struct Entry {
    uint64_t handle = 0;       // the kernel slot (Kernel::slot's handle)
    uint32_t id = 0;
    FbSlot* slot = nullptr;
  };
  std::deque<Entry> ring_ = std::deque<Entry>(kRing);   // stable addresses: entries are the slots' instances
  uint32_t next_ = 1;
};

}  // namespace stc::motion
