// Sm3NcProgram.h: the SMC_CNC_REF check and the program file reader.
#include "stdlib-motion/codesys_sm3/Sm3NcProgram.h"

#include <sys/stat.h>
#include <unistd.h>

#include <iostream>

#include "vm/FileSandbox.h"

namespace stc::motion::sm3face {

bool usableCncRef(const MotionSession& s, const sm3::SMC_CNC_REF* p) {
  return p && s.inImage(p, sizeof *p) && p->wCNCREFStructID == kCncRefStructId && p->dwTextSize <= kMaxNcProgramBytes &&
         (p->dwTextSize == 0 || s.inImage(p->pText, p->dwTextSize));
}

NcFileRead readNcFile(const MotionSession& s, const std::string& name, uint64_t maxBytes, std::string& text, uint64_t& size) {
  size = 0;
  std::string why;
  const int fd = name.empty() ? -1 : stc::vm::openInside(s.filesDir(), name, stc::vm::FileAccess::Read, why);
  if (fd < 0) return NcFileRead::Missing;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return NcFileRead::Missing;
  }
  size = static_cast<uint64_t>(st.st_size);
  switch (stc::vm::readAndClose(fd, maxBytes, text)) {
  case stc::vm::ReadResult::Ok: return NcFileRead::Ok;
  case stc::vm::ReadResult::TooBig: return NcFileRead::TooBig;
  case stc::vm::ReadResult::Failed: break;
  }
  return NcFileRead::Missing;
}

void printNewDiagnostics(const DiagnosticsEngine& diags, size_t& printed) {
  const auto& ds = diags.diagnostics();
  if (printed >= ds.size()) return;
  for (; printed < ds.size(); ++printed) std::cerr << stc::renderText(diags.sourceManager(), ds[printed]);
  std::cerr.flush();
}

}  // namespace stc::motion::sm3face
