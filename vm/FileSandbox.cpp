#include "vm/FileSandbox.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

namespace stc::vm {
namespace fs = std::filesystem;
namespace {

// The checks shared by openInside and resolveInside: `root` canonical, `parts` the
// components of the resolved file below it.
bool resolve(const std::string& rootName, const std::string& name, FileAccess access, bool create, fs::path& root,
             std::vector<std::string>& parts, std::string& why) {
  if (name.empty()) return why = "no file name", false;
  if (name.find('\0') != std::string::npos) return why = "not a valid file name", false;
  const fs::path rel(name);
  const std::string shown = rootName.empty() ? "." : rootName;
  if (rel.is_absolute() || rel.has_root_name())
    return why = "an absolute path (file names are relative to '" + shown + "')", false;
  const fs::path norm = rel.lexically_normal();
  if (!norm.empty() && *norm.begin() == "..") return why = "'..' leads outside '" + shown + "'", false;
  std::error_code ec;
  fs::path rootAbs = fs::absolute(shown, ec);
  if (ec) return why = "not a valid file name", false;
  if (!fs::exists(rootAbs, ec)) {
    if (access == FileAccess::Read || access == FileAccess::ReadWrite || !create) return why = "'" + shown + "' does not exist", false;
    if (::mkdir(rootAbs.c_str(), 0755) != 0 && errno != EEXIST)
      return why = "cannot create '" + shown + "': " + std::strerror(errno), false;
  }
  root = fs::canonical(rootAbs, ec);
  if (ec || !fs::is_directory(root, ec)) return why = "'" + shown + "' is not a directory", false;
  const fs::path full = fs::weakly_canonical(root / norm, ec);
  if (ec) return why = "not a valid file name", false;
  // Inside the root: the root's components are a prefix of the resolved path (links resolved).
  auto r = root.begin(), f = full.begin();
  for (; r != root.end(); ++r, ++f)
    if (f == full.end() || *r != *f) return why = "outside '" + shown + "' (through a symbolic link)", false;
  if (f == full.end()) return why = "not a file", false;
  parts.clear();
  for (; f != full.end(); ++f)
    if (!f->empty()) parts.push_back(f->string());
  if (parts.empty()) return why = "not a file", false;
  return true;
}

std::string openError(int e) {
  switch (e) {
    case ELOOP: case EMLINK: return "a symbolic link (changed while opening, or dangling)";
    case ENOENT: return "no such file";
    case ENOTDIR: return "a path component is not a directory";
    case EACCES: case EPERM: return "permission denied";
    case ENXIO: return "not a regular file";
    default: return std::strerror(e);
  }
}

}  // namespace

bool resolveInside(const std::string& root, const std::string& name, std::string& resolved, std::string& why) {
  fs::path r;
  std::vector<std::string> parts;
  if (!resolve(root, name, FileAccess::Read, false, r, parts, why)) return false;
  for (const std::string& p : parts) r /= p;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(r, ec);
  if (fs::exists(st) && !fs::is_regular_file(st)) return why = "not a regular file", false;
  resolved = r.string();
  return true;
}

int openInside(const std::string& root, const std::string& name, FileAccess access, std::string& why, std::string* resolved) {
  fs::path r;
  std::vector<std::string> parts;
  if (!resolve(root, name, access, true, r, parts, why)) return -1;
  int dfd = ::open(r.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW);
  if (dfd < 0) return why = openError(errno), -1;
  // Walk down without following links: the path was canonical when checked, so a link
  // met now was put there since.
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    int next = ::openat(dfd, parts[i].c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW);
    if (next < 0 && errno == ENOENT && access == FileAccess::WriteMakeDirs) {
      if (::mkdirat(dfd, parts[i].c_str(), 0755) != 0 && errno != EEXIST) {
        why = "cannot create the directory '" + parts[i] + "': " + std::strerror(errno);
        ::close(dfd);
        return -1;
      }
      next = ::openat(dfd, parts[i].c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW);
    }
    const int e = errno;
    ::close(dfd);
    if (next < 0) return why = openError(e), -1;
    dfd = next;
  }
  const bool write = access != FileAccess::Read;
  const bool read = access == FileAccess::Read || access == FileAccess::ReadWrite || access == FileAccess::ReadWriteNew ||
                    access == FileAccess::AppendRead;
  const bool create = write && access != FileAccess::ReadWrite;
  const bool truncate = access == FileAccess::Write || access == FileAccess::WriteMakeDirs || access == FileAccess::ReadWriteNew;
  const bool append = access == FileAccess::Append || access == FileAccess::AppendRead;
  // No O_TRUNC here: the file is checked first (a FIFO, a device or a hard link is left as it was).
  const int flags = (read && write ? O_RDWR : write ? O_WRONLY : O_RDONLY) | (create ? O_CREAT : 0) | (append ? O_APPEND : 0) |
                    O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY;
  int fd = ::openat(dfd, parts.back().c_str(), flags, 0644);
  const int e = errno;
  ::close(dfd);
  if (fd < 0) return why = openError(e), -1;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return why = "not a regular file", -1;
  }
  if (write && st.st_nlink > 1) {
    ::close(fd);
    return why = "the file has other hard links (it may be a file outside the directory)", -1;
  }
  if (truncate && ::ftruncate(fd, 0) != 0) {
    why = std::string("cannot truncate: ") + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  if (resolved) {
    for (const std::string& p : parts) r /= p;
    *resolved = r.string();
  }
  return fd;
}

ReadResult readAndClose(int fd, unsigned long long maxBytes, std::string& text) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    return ReadResult::Failed;
  }
  if (static_cast<unsigned long long>(st.st_size) > maxBytes) {
    ::close(fd);
    return ReadResult::TooBig;
  }
  text.clear();
  char buf[1 << 16];
  for (;;) {
    ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      return ReadResult::Failed;
    }
    if (n == 0) break;
    text.append(buf, static_cast<size_t>(n));
    if (text.size() > maxBytes) {   // grew while reading
      ::close(fd);
      return ReadResult::TooBig;
    }
  }
  ::close(fd);
  return ReadResult::Ok;
}

}  // namespace stc::vm
