// RETAIN/PERSISTENT storage (plan §7, docs/vm.md "Retain").  The file is replaced
// atomically: written to TARGET.tmp next to the file it stands for (symbolic links
// are followed, so a linked retain file stays linked), fsync'ed, renamed over
// TARGET, and the directory fsync'ed, so a crash leaves either the old or the new
// file, never a torn one.
//
// Layout (little-endian): "STCRET01", u32 version, u32 count, then per entry u32
// length + path, u32 length + signature, u32 size + bytes; then the CRC-32 (IEEE
// 802.3) of everything before it.  Version 1 (before issue 14) holds one entry per
// retained variable; version 2 one per leaf (an elementary value, a string, an array
// of them, a union; struct members and FB variables are separate leaves), so a
// changed FB restores the members that still match.
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

inline constexpr uint32_t kRetainVersion = 2;   // written; 1 and 2 are read

// The file `file` stands for: symbolic links followed (also a dangling one: its
// target is where the file will be created).  False with `error` for a link loop.
bool retainTarget(const std::string& file, std::string& target, std::string& error);

// Writes `entries` (version kRetainVersion) through `file`'s links, atomically; the
// replaced file's permissions are kept.
bool saveRetainFile(const std::string& file, const std::vector<RetainEntry>& entries, std::string& error);

// Missing: no file (a cold start; it is created at the first save).  The others are
// never overwritten without --retain-reset (Damaged, Newer) or at all (Unreadable,
// Foreign): Unreadable cannot be opened or read, or is not a regular file; Foreign does
// not start with the retain file magic; Newer is a later format; Damaged has the magic
// but a bad checksum or is malformed.  `error` says which.
enum class RetainLoad { Ok, Missing, Unreadable, Foreign, Newer, Damaged };

// Also removes a TARGET.tmp left by an interrupted save (only one of ours: empty or
// starting with the magic).  `version` gets the file's format version.
RetainLoad loadRetainFile(const std::string& file, std::vector<RetainEntry>& out, uint32_t& version, std::string& error);

// Whether `file` can be saved: its (link-resolved) directory exists and is writable.
bool retainWritable(const std::string& file, std::string& error);

uint32_t crc32(const uint8_t* data, size_t size);

}  // namespace stc::vm
