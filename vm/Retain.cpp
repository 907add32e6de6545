#include "vm/Retain.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstddef>
#include <cstring>

namespace stc::vm {
namespace {

constexpr char kMagic[8] = {'S', 'T', 'C', 'R', 'E', 'T', '0', '1'};

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

// A leftover temporary file of ours: a regular file, empty or starting with (a prefix of) the magic.
bool isOurTemp(const std::string& tmp) {
  struct stat st {};
  if (::lstat(tmp.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  if (st.st_size == 0) return true;
  int fd = ::open(tmp.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return false;
  char head[sizeof kMagic] = {};
  ssize_t n = ::read(fd, head, sizeof head);
  ::close(fd);
  return n > 0 && std::memcmp(head, kMagic, static_cast<size_t>(n)) == 0;
}

std::string directoryOf(const std::string& file) {
  size_t slash = file.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : file.substr(0, slash);
}

// Reads the entries from `data` (CRC already checked); false if malformed.
bool parse(const std::vector<uint8_t>& data, std::vector<RetainEntry>& out, std::string& error) {
  // (the version was checked by the caller)
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

bool retainTarget(const std::string& file, std::string& target, std::string& error) {
  std::string cur = file;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(cur.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) {
      target = cur;
      return true;
    }
    char buf[PATH_MAX];
    ssize_t n = ::readlink(cur.c_str(), buf, sizeof buf - 1);
    if (n < 0) {
      error = sysError("read the link", cur);
      return false;
    }
    std::string link(buf, static_cast<size_t>(n));
    if (link.empty()) {
      error = "'" + cur + "' is an empty symbolic link";
      return false;
    }
    // A relative link target is relative to the link's directory.
    cur = link[0] == '/' ? link : (cur.find('/') == std::string::npos ? link : directoryOf(cur) + "/" + link);
  }
  error = "'" + file + "': too many levels of symbolic links";
  return false;
}

bool retainWritable(const std::string& file, std::string& error) {
  std::string target;
  if (!retainTarget(file, target, error)) return false;
  const std::string dir = directoryOf(target);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) return error = sysError("use the directory", dir), false;
  if (!S_ISDIR(st.st_mode)) return error = "'" + dir + "' is not a directory", false;
  if (::access(dir.c_str(), W_OK | X_OK) != 0) return error = sysError("write into", dir), false;
  if (::stat(target.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) return error = "'" + target + "' is a directory", false;
  return true;
}

bool saveRetainFile(const std::string& file, const std::vector<RetainEntry>& entries, std::string& error) {
  std::vector<uint8_t> data(kMagic, kMagic + sizeof kMagic);
  putU32(data, kRetainVersion);
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

  // Through symbolic links: the temporary file goes next to the file replaced, so the
  // rename stays within one directory (and one file system) and the link stays a link.
  std::string target;
  if (!retainTarget(file, target, error)) return false;
  const std::string tmp = target + ".tmp";
  struct stat st {};
  if (::lstat(tmp.c_str(), &st) == 0) {
    if (!isOurTemp(tmp)) {
      error = "'" + tmp + "' is in the way and is not a temporary retain file of stc (it is left as it is)";
      return false;
    }
    ::unlink(tmp.c_str());
  }
  // Only a retain file is ever replaced, also when something else took its place during
  // the run (the check at start is not enough on its own).
  if (::lstat(target.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) return error = "'" + target + "' is not a regular file; it is not replaced", false;
    int fd = ::open(target.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    char head[6] = {};
    const ssize_t n = fd < 0 ? -1 : ::read(fd, head, sizeof head);
    if (fd >= 0) ::close(fd);
    if (n < 0 && st.st_size > 0) return error = sysError("read", target) + "; it is not replaced", false;
    if (n > 0 && std::memcmp(head, kMagic, static_cast<size_t>(n)) != 0)
      return error = "'" + target + "' is no longer a retain file (it was replaced during the run); it is not overwritten", false;
  }
  mode_t mode = 0644;
  const bool replacing = ::stat(target.c_str(), &st) == 0;
  if (replacing) mode = st.st_mode & 07777;
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) {
    error = sysError("create", tmp);
    return false;
  }
  if (replacing) (void)::fchmod(fd, mode);   // keep the replaced file's permissions
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
  if (::rename(tmp.c_str(), target.c_str()) != 0) {
    error = sysError("replace", target);
    ::unlink(tmp.c_str());
    return false;
  }
  // Make the rename itself durable.
  const std::string dir = directoryOf(target);
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

RetainLoad loadRetainFile(const std::string& file, std::vector<RetainEntry>& out, uint32_t& version, std::string& error) {
  std::string target;
  if (!retainTarget(file, target, error)) return RetainLoad::Unreadable;
  // A leftover .tmp is an interrupted save: the file is still the last good one.
  if (isOurTemp(target + ".tmp")) ::unlink((target + ".tmp").c_str());

  int fd = ::open(target.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return RetainLoad::Missing;
    error = sysError("open", file);
    return RetainLoad::Unreadable;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    error = "'" + file + "' is not a regular file";
    return RetainLoad::Unreadable;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::vector<uint8_t> data;
  uint8_t buf[1 << 16];
  for (;;) {
    ssize_t r = ::read(fd, buf, sizeof buf);
    if (r < 0) {
      if (errno == EINTR) continue;
      error = sysError("read", file);
      ::close(fd);
      return RetainLoad::Unreadable;
    }
    if (r == 0) break;
    data.insert(data.end(), buf, buf + r);
    // Not one of ours: stop reading at once (a large foreign file is not read whole).
    if (data.size() >= 6 && std::memcmp(data.data(), kMagic, 6) != 0) break;
  }
  ::close(fd);

  if (data.empty()) return RetainLoad::Missing;   // an empty file holds nothing to keep
  if (data.size() < 6 || std::memcmp(data.data(), kMagic, 6) != 0) {
    error = "'" + file + "' is not a retain file (it does not start with STCRET)";
    return RetainLoad::Foreign;
  }
  if (data.size() < sizeof kMagic || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0) {
    const std::string magic(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(std::min<size_t>(data.size(), sizeof kMagic)));
    if (magic.size() == sizeof kMagic && std::isdigit(static_cast<unsigned char>(magic[6])) && std::isdigit(static_cast<unsigned char>(magic[7])) &&
        magic.substr(6) > "01") {
      error = "'" + file + "' has the format " + magic + ", newer than this stc reads (STCRET01)";
      return RetainLoad::Newer;
    }
    error = "'" + file + "' is damaged (its header is not STCRET01)";
    return RetainLoad::Damaged;
  }
  if (data.size() < sizeof kMagic + 8) {
    error = "'" + file + "' is damaged (truncated header)";
    return RetainLoad::Damaged;
  }
  version = getU32(&data[sizeof kMagic]);
  if (version > kRetainVersion) {
    error = "'" + file + "' has the format version " + std::to_string(version) + ", newer than this stc reads (1 to " +
            std::to_string(kRetainVersion) + ")";
    return RetainLoad::Newer;
  }
  if (crc32(data.data(), data.size() - 4) != getU32(&data[data.size() - 4])) {
    error = "'" + file + "' is damaged (bad checksum)";
    return RetainLoad::Damaged;
  }
  if (version == 0) {
    error = "'" + file + "' is damaged (format version 0)";
    return RetainLoad::Damaged;
  }
  std::string why;
  if (!parse(data, out, why)) {
    error = "'" + file + "' is damaged (" + why + ")";
    return RetainLoad::Damaged;
  }
  return RetainLoad::Ok;
}

}  // namespace stc::vm
