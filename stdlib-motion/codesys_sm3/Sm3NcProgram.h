// What every block that takes a G-code program shares (SMC_ReadNCFile, SMC_NCDecoder,
// the Leadshine LS_nAxisGCode* blocks): the check of an SMC_CNC_REF that ST hands over,
// reading a program file from the controller's data directory, and how G-code errors
// reach the user (stderr, at file:line:col).  One place for the
// rules, so a program is accepted or refused the same way by every block.
#pragma once

#include <cstdint>
#include <string>

#include "basic/Diagnostics.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"

namespace stc::motion::sm3face {

inline constexpr uint16_t kCncRefStructId = 0xBA56;        // SMC_CNC_REF.wCNCREFStructID
inline constexpr uint64_t kMaxNcProgramBytes = 64ull << 20;   // the largest program text

// TRUE when `p` is an SMC_CNC_REF in static memory with the struct ID, a text of at most
// kMaxNcProgramBytes, and that text in static memory too (never a stack frame).
bool usableCncRef(const MotionSession& s, const sm3::SMC_CNC_REF* p);

enum class NcFileRead { Ok, Missing, TooBig };
// Reads `name` from the data directory (vm/FileSandbox.h: no absolute names, no `..` above the
// directory, no links out).  Missing: an empty name, a name outside, no such file, not a
// regular file, a read error; TooBig: larger than maxBytes.  `size` gets the file's size when
// it could be opened (also when it is too big).
NcFileRead readNcFile(const MotionSession& s, const std::string& name, uint64_t maxBytes, std::string& text, uint64_t& size);

// Writes the G-code diagnostics from index `printed` on to stderr as `stc check` renders them
// (file:line:col, the line, a caret), warnings too, and advances `printed`.
void printNewDiagnostics(const DiagnosticsEngine& diags, size_t& printed);

}  // namespace stc::motion::sm3face
