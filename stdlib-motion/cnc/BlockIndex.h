// Where each block number (or jump label) of a program starts: an open-
// addressing hash table in one vector, so indexing a block allocates nothing
// but the table's occasional doubling (16 bytes per slot, at most half full).
#pragma once

#include <cstdint>
#include <vector>

namespace stc::cnc {

class BlockIndex {
public:
  struct Entry {
    int64_t key = -1;          // -1: empty
    uint32_t offset = 0;       // the block's first byte
    uint32_t line = 0;
  };

  // Inserts key; returns nullptr, or the existing entry if the key is taken.
  const Entry* insert(int32_t key, uint32_t offset, uint32_t line) {
    if ((count_ + 1) * 2 > slots_.size()) grow();
    Entry* e = probe(key);
    if (e->key == key) return e;
    *e = Entry{key, offset, line};
    ++count_;
    return nullptr;
  }
  const Entry* find(int32_t key) const {
    if (slots_.empty()) return nullptr;
    const Entry* e = const_cast<BlockIndex*>(this)->probe(key);
    return e->key == key ? e : nullptr;
  }
  size_t bytes() const { return slots_.capacity() * sizeof(Entry); }
  size_t size() const { return count_; }
  void clear() {
    slots_.clear();
    count_ = 0;
  }

private:
  Entry* probe(int64_t key) {
    size_t mask = slots_.size() - 1;
    size_t i = static_cast<size_t>((static_cast<uint64_t>(key) * 0x9E3779B97F4A7C15ull) >> 17) & mask;
    while (slots_[i].key != -1 && slots_[i].key != key) i = (i + 1) & mask;
    return &slots_[i];
  }
  void grow() {
    std::vector<Entry> old = std::move(slots_);
    slots_.assign(old.empty() ? 64 : old.size() * 2, Entry{});
    for (const Entry& e : old)
      if (e.key != -1) *probe(e.key) = e;
  }
  std::vector<Entry> slots_;
  size_t count_ = 0;
};

}  // namespace stc::cnc
