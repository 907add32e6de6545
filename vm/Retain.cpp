#include "vm/Retain.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstddef>
#include <cstring>

namespace stc::vm {
namespace {

constexpr char kMagic[8] = {'S', 'T', 'C', 'R', 'E', 'T', '0', '1'};
constexpr uint32_t kVersion = 1;

constexpr std::array<uint32_t, 256> makeCrcTable() {
  std::array<uint32_t, 256> table{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}
constexpr std::array<uint32_t, 256> kCrcTable = makeCrcTable();

void putU32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

uint32_t getU32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

std::string sysError(const char* what, const std::string& file) {
  return std::string("cannot ") + what + " '" + file + "': " + std::strerror(errno);
}

bool writeAll(int fd, const uint8_t* p, size_t n) {
  while (n > 0) {
    ssize_t w = ::write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += w;
    n -= static_cast<size_t>(w);
  }
  return true;
}

std::string directoryOf(const std::string& file) {
  size_t slash = file.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : file.substr(0, slash);
}

// Reads the entries from `data` (CRC already checked); false if malformed.
bool parse(const std::vector<uint8_t>& data, std::vector<RetainEntry>& out, std::string& error) {
  size_t pos = sizeof kMagic;
  const size_t end = data.size() - 4;
  auto u32 = [&](uint32_t& v) {
    if (end - pos < 4) return false;
    v = getU32(&data[pos]);
    pos += 4;
    return true;
  };
  auto blob = [&](auto& dst) {
    uint32_t n;
    if (!u32(n) || end - pos < n) return false;
    dst.assign(data.begin() + static_cast<std::ptrdiff_t>(pos), data.begin() + static_cast<std::ptrdiff_t>(pos + n));
    pos += n;
    return true;
  };
  uint32_t version, count;
  if (!u32(version) || !u32(count)) {
    error = "truncated header";
    return false;
  }
  if (version != kVersion) {
    error = "unsupported version " + std::to_string(version);
    return false;
  }
  std::vector<RetainEntry> entries;
  for (uint32_t i = 0; i < count; ++i) {
    RetainEntry e;
    if (!blob(e.path) || !blob(e.signature) || !blob(e.bytes)) {
      error = "truncated entry " + std::to_string(i);
      return false;
    }
    entries.push_back(std::move(e));
  }
  if (pos != end) {
    error = "trailing bytes after the entries";
    return false;
  }
  out = std::move(entries);
  return true;
}

}  // namespace

uint32_t crc32(const uint8_t* data, size_t size) {
  uint32_t c = 0xFFFFFFFFu;
  for (size_t i = 0; i < size; ++i) c = kCrcTable[(c ^ data[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

bool saveRetainFile(const std::string& file, const std::vector<RetainEntry>& entries, std::string& error) {
  std::vector<uint8_t> data(kMagic, kMagic + sizeof kMagic);
  putU32(data, kVersion);
  putU32(data, static_cast<uint32_t>(entries.size()));
  for (const RetainEntry& e : entries) {
    putU32(data, static_cast<uint32_t>(e.path.size()));
    data.insert(data.end(), e.path.begin(), e.path.end());
    putU32(data, static_cast<uint32_t>(e.signature.size()));
    data.insert(data.end(), e.signature.begin(), e.signature.end());
    putU32(data, static_cast<uint32_t>(e.bytes.size()));
    data.insert(data.end(), e.bytes.begin(), e.bytes.end());
  }
  putU32(data, crc32(data.data(), data.size()));

  const std::string tmp = file + ".tmp";
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    error = sysError("create", tmp);
    return false;
  }
  if (!writeAll(fd, data.data(), data.size()) || ::fsync(fd) != 0) {
    error = sysError("write", tmp);
    ::close(fd);
    ::unlink(tmp.c_str());
    return false;
  }
  if (::close(fd) != 0) {
    error = sysError("write", tmp);
    ::unlink(tmp.c_str());
    return false;
  }
  if (::rename(tmp.c_str(), file.c_str()) != 0) {
    error = sysError("replace", file);
    ::unlink(tmp.c_str());
    return false;
  }
  // Make the rename itself durable.
  const std::string dir = directoryOf(file);
  int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) {
    error = sysError("open directory", dir);
    return false;
  }
  bool ok = ::fsync(dfd) == 0;
  if (!ok) error = sysError("sync directory", dir);
  ::close(dfd);
  return ok;
}

RetainLoad loadRetainFile(const std::string& file, std::vector<RetainEntry>& out, std::string& error) {
  // A leftover .tmp is an interrupted save: FILE is still the last good one.
  ::unlink((file + ".tmp").c_str());

  int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return RetainLoad::Missing;
    error = sysError("open", file);
    return RetainLoad::Corrupt;
  }
  std::vector<uint8_t> data;
  uint8_t buf[1 << 16];
  for (;;) {
    ssize_t r = ::read(fd, buf, sizeof buf);
    if (r < 0) {
      if (errno == EINTR) continue;
      error = sysError("read", file);
      ::close(fd);
      return RetainLoad::Corrupt;
    }
    if (r == 0) break;
    data.insert(data.end(), buf, buf + r);
  }
  ::close(fd);

  if (data.size() < sizeof kMagic + 4 || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0) {
    error = "'" + file + "' is not a retain file";
    return RetainLoad::Corrupt;
  }
  if (crc32(data.data(), data.size() - 4) != getU32(&data[data.size() - 4])) {
    error = "'" + file + "' has a bad checksum";
    return RetainLoad::Corrupt;
  }
  std::string why;
  if (!parse(data, out, why)) {
    error = "'" + file + "' is malformed: " + why;
    return RetainLoad::Corrupt;
  }
  return RetainLoad::Ok;
}

}  // namespace stc::vm
