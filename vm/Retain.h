// RETAIN/PERSISTENT storage (plan §7).  The file is replaced atomically:
// written to FILE.tmp, fsync'ed, renamed over FILE, and the directory fsync'ed,
// so a crash leaves either the old or the new file, never a torn one.
//
// Layout (little-endian): "STCRET01", u32 version = 1, u32 count, then per
// entry u32 length + path, u32 length + signature, u32 size + bytes; then the
// CRC-32 (IEEE 802.3) of everything before it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace stc::vm {

struct RetainEntry {
  std::string path;         // e.g. "GVL.counter"
  std::string signature;    // the Layout-based type signature
  std::vector<uint8_t> bytes;
};

bool saveRetainFile(const std::string& file, const std::vector<RetainEntry>& entries, std::string& error);

enum class RetainLoad { Ok, Missing, Corrupt };

// Also removes a FILE.tmp left by an interrupted save.  Corrupt covers a bad
// CRC, a malformed file and read errors; `error` says which.
RetainLoad loadRetainFile(const std::string& file, std::vector<RetainEntry>& out, std::string& error);

uint32_t crc32(const uint8_t* data, size_t size);

}  // namespace stc::vm
