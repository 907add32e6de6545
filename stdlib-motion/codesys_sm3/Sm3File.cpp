// FILE.* of the CAA File library (sm3_file.st): files in the run's data directory,
// opened through the sandbox (vm/FileSandbox.h).  Every block completes in the call of
// its rising edge.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "vm/FileSandbox.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

// FILE.ERROR
enum FileError : int16_t {
  kNoError = 0,
  kHandleInvalid = 5103,
  kNotExist = 5104,
  kReadOnly = 5108,
  kWrongParameter = 5109,
  kUnknown = 5110,
  kWriteIncomplete = 5111,
  kDenied = 5114,
};

constexpr size_t kMaxOpenFiles = 32;
constexpr uint64_t kMaxTransfer = 16ull << 20;   // bytes per Read / Write call
constexpr uint64_t kMaxFileBytes = 64ull << 20;  // a file the program writes

// The edge logic of every block: true in the call of the rising edge (outputs cleared
// for the new job); a falling edge clears the outputs.
template <class T>
bool rising(T* self) {
  const bool edge = self->xExecute && !self->__prev;
  self->__prev = self->xExecute;
  if (edge || !self->xExecute) {
    self->xDone = self->xBusy = self->xError = false;
    self->eError = kNoError;
  }
  return edge;
}
template <class T>
void finish(T* self, int16_t error) {
  self->xDone = error == kNoError;
  self->xError = error != kNoError;
  self->eError = error;
}

std::string nameOf(const char* s) { return std::string(s, strnlen(s, 255)); }

MotionSession::OpenFile* fileOf(uint64_t handle) {
  MotionSession& s = MotionSession::current();
  const uint64_t slot = (handle & 0xffffffffu);
  if (slot == 0 || slot > s.files.size()) return nullptr;
  MotionSession::OpenFile& f = s.files[slot - 1];
  return f.fd >= 0 && f.generation == (handle >> 32) ? &f : nullptr;
}

void FileOpen(sm3::Open* self) {
  if (!rising(self)) return;
  self->hFile = 0;
  struct Mode { stc::vm::FileAccess access; bool read, write; };
  static const Mode modes[] = {
      {stc::vm::FileAccess::Write, false, true},        {stc::vm::FileAccess::Read, true, false},
      {stc::vm::FileAccess::ReadWriteNew, true, true},  {stc::vm::FileAccess::Append, false, true},
      {stc::vm::FileAccess::ReadWrite, true, true},     {stc::vm::FileAccess::ReadWriteNew, true, true},
      {stc::vm::FileAccess::AppendRead, true, true},
  };
  if (self->eFileMode < 0 || self->eFileMode > 6) return finish(self, kWrongParameter);
  const Mode m = modes[self->eFileMode];
  MotionSession& s = MotionSession::current();
  const std::string name = nameOf(self->sFileName);
  std::string resolved, why;
  if (name.empty()) return finish(self, kWrongParameter);
  if (!stc::vm::resolveInside(s.filesDir(), name, resolved, why)) return finish(self, kDenied);
  // Exclusive either way: no second open of a file held exclusively, nor an exclusive one of an open file.
  for (const MotionSession::OpenFile& f : s.files)
    if (f.fd >= 0 && f.path == resolved && (f.exclusive || self->xExclusive)) return finish(self, kDenied);
  auto slot = std::find_if(s.files.begin(), s.files.end(), [](const MotionSession::OpenFile& f) { return f.fd < 0; });
  if (slot == s.files.end()) {
    if (s.files.size() >= kMaxOpenFiles) return finish(self, kUnknown);
    s.files.emplace_back();
    slot = s.files.end() - 1;
  }
  errno = 0;
  const int fd = stc::vm::openInside(s.filesDir(), name, m.access, why, &resolved);
  if (fd < 0) return finish(self, errno == ENOENT || why.find("does not exist") != std::string::npos ? kNotExist : kDenied);
  slot->fd = fd;
  slot->generation = (slot->generation + 1) & 0x7fffffffu;
  slot->read = m.read;
  slot->write = m.write;
  slot->exclusive = self->xExclusive;
  slot->path = resolved;
  self->hFile = (static_cast<uint64_t>(slot->generation) << 32) | static_cast<uint64_t>(slot - s.files.begin() + 1);
  finish(self, kNoError);
}

void FileClose(sm3::Close* self) {
  if (!rising(self)) return;
  MotionSession::OpenFile* f = fileOf(self->hFile);
  if (!f) return finish(self, kHandleInvalid);
  const int rc = ::close(f->fd);
  f->fd = -1;
  f->path.clear();
  finish(self, rc == 0 ? kNoError : kUnknown);
}

void FileWrite(sm3::Write* self) {
  if (!rising(self)) return;
  MotionSession::OpenFile* f = fileOf(self->hFile);
  if (!f) return finish(self, kHandleInvalid);
  if (!f->write) return finish(self, kReadOnly);
  if (self->szSize > kMaxTransfer || !MotionSession::current().inImage(self->pBuffer, self->szSize)) return finish(self, kWrongParameter);
  const off_t at = ::lseek(f->fd, 0, SEEK_CUR);
  struct stat st {};
  if (at < 0 || ::fstat(f->fd, &st) != 0) return finish(self, kUnknown);
  if (static_cast<uint64_t>(std::max<off_t>(at, st.st_size)) + self->szSize > kMaxFileBytes) return finish(self, kWrongParameter);
  const auto* p = static_cast<const uint8_t*>(self->pBuffer);
  uint64_t done = 0;
  while (done < self->szSize) {
    const ssize_t n = ::write(f->fd, p + done, self->szSize - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<uint64_t>(n);
  }
  finish(self, done == self->szSize ? kNoError : kWriteIncomplete);
}

void FileRead(sm3::Read* self) {
  if (!rising(self)) return;
  self->szSize = 0;
  MotionSession::OpenFile* f = fileOf(self->hFile);
  if (!f) return finish(self, kHandleInvalid);
  if (!f->read) return finish(self, kReadOnly);
  if (self->szBuffer > kMaxTransfer || !MotionSession::current().inImage(self->pBuffer, self->szBuffer)) return finish(self, kWrongParameter);
  auto* p = static_cast<uint8_t*>(self->pBuffer);
  uint64_t done = 0;
  while (done < self->szBuffer) {
    const ssize_t n = ::read(f->fd, p + done, self->szBuffer - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return finish(self, kUnknown);
    if (n == 0) break;   // the end of the file
    done += static_cast<uint64_t>(n);
  }
  self->szSize = done;
  finish(self, kNoError);
}

void FileSetPos(sm3::SetPos* self) {
  if (!rising(self)) return;
  MotionSession::OpenFile* f = fileOf(self->hFile);
  if (!f) return finish(self, kHandleInvalid);
  struct stat st {};
  if (::fstat(f->fd, &st) != 0) return finish(self, kUnknown);
  if (self->udiPos > static_cast<uint64_t>(st.st_size)) return finish(self, kWrongParameter);
  finish(self, ::lseek(f->fd, static_cast<off_t>(self->udiPos), SEEK_SET) >= 0 ? kNoError : kUnknown);
}

void FileGetPos(sm3::GetPos* self) {
  if (!rising(self)) return;
  self->udiPos = 0;
  MotionSession::OpenFile* f = fileOf(self->hFile);
  if (!f) return finish(self, kHandleInvalid);
  const off_t at = ::lseek(f->fd, 0, SEEK_CUR);
  if (at < 0 || at > static_cast<off_t>(UINT32_MAX)) return finish(self, kUnknown);
  self->udiPos = static_cast<uint32_t>(at);
  finish(self, kNoError);
}

void FileGetSize(sm3::GetSize* self) {
  if (!rising(self)) return;
  self->szSize = 0;
  const std::string name = nameOf(self->sFileName);
  std::string resolved, why;
  if (name.empty()) return finish(self, kWrongParameter);
  if (!stc::vm::resolveInside(MotionSession::current().filesDir(), name, resolved, why)) return finish(self, kDenied);
  struct stat st {};
  if (::stat(resolved.c_str(), &st) != 0) return finish(self, errno == ENOENT ? kNotExist : kUnknown);
  if (!S_ISREG(st.st_mode)) return finish(self, kDenied);
  self->szSize = static_cast<uint64_t>(st.st_size);
  finish(self, kNoError);
}

}  // namespace

namespace stc::motion::sm3face {
void registerSm3FileNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(Open, FileOpen)
  STC_SM3_NATIVE(Close, FileClose)
  STC_SM3_NATIVE(Write, FileWrite)
  STC_SM3_NATIVE(Read, FileRead)
  STC_SM3_NATIVE(SetPos, FileSetPos)
  STC_SM3_NATIVE(GetPos, FileGetPos)
  STC_SM3_NATIVE(GetSize, FileGetSize)
}
}  // namespace stc::motion::sm3face
