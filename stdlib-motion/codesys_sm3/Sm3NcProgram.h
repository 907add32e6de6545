// What every block that takes a G-code program shares (SMC_ReadNCFile, SMC_NCDecoder,
// the Leadshine LS_nAxisGCode* blocks): the check of an SMC_CNC_REF that ST hands over,
// reading a program file from the controller's data directory, and how G-code errors
// reach the user (stderr, at file:line:col).  One place for the
// rules, so a program is accepted or refused the same way by every block.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "basic/Diagnostics.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"

namespace stc::motion::sm3face {

inline constexpr uint16_t kCncRefStructId = 0xBA56;        // SMC_CNC_REF.wCNCREFStructID
inline constexpr uint64_t kMaxNcProgramBytes = 64ull << 20;   // the largest program text

// TRUE when `p` is an SMC_CNC_REF in static memory with the struct ID, a text of at most
// kMaxNcProgramBytes, and that text in static memory too (never a stack frame) or in a
// program the controller holds ([[cnc_program]] of project.toml).
bool usableCncRef(const MotionSession& s, const sm3::SMC_CNC_REF* p);

enum class NcFileRead { Ok, Missing, TooBig };
// Reads `name` from the data directory (vm/FileSandbox.h: no absolute names, no `..` above the
// directory, no links out).  Missing: an empty name, a name outside, no such file, not a
// regular file, a read error; TooBig: larger than maxBytes.  `size` gets the file's size when
// it could be opened (also when it is too big).
NcFileRead readNcFile(const MotionSession& s, const std::string& name, uint64_t maxBytes, std::string& text, uint64_t& size);

inline constexpr uint16_t kVarListId = 0x87FD;            // SMC_VARLIST.wVarListID
inline constexpr int kMaxVarListEntries = 10000;

// TRUE when `p` is an SMC_VARLIST in static memory with its ID and at most kMaxVarListEntries
// entries, all of them in static memory too (SMC_RNCF_NOT_VARLIST otherwise).
// (ST hands the list over as an untyped POINTER TO.)
bool usableVarList(const MotionSession& s, const void* p);

// The variables behind a program's $name$ (docs/cnc.md, "$var$"): the entries of an
// SMC_VARLIST (copied when the decoder starts) first, then the project's variables by the
// name written between the dollars (`x`, `GVL.x`, `arr[2]`, `MAIN.fb.q`, any case).  BOOL,
// the integers and REAL/LREAL can stand in a program; G36/G37 O$name$ stores only a value
// the variable's type holds exactly (an INT takes -32768..32767 integers), never into a
// CONSTANT or a process input.  A name is resolved once per decoder and kept: what it points
// to is static memory, which stays where it is for the whole run.
class NcVariables : public stc::cnc::VariableAccess {
public:
  // `list` must be null or have passed usableVarList.
  NcVariables(const MotionSession& s, const void* list);
  bool read(std::string_view name, double& v) override;
  bool write(std::string_view name, double v) override;
  std::string suggest(std::string_view name) override;
  std::string problem() const override { return problem_; }

  enum class Kind : uint8_t { None, Bool, S8, S16, S32, S64, U8, U16, U32, U64, F32, F64 };
  struct Var {
    uint8_t* address = nullptr;
    int bit = -1;
    Kind kind = Kind::None;
    bool constant = false;
    std::string problem;   // why it cannot stand in a program (Kind::None); empty: unknown name
    std::string hint;      // a close name, when unknown
  };

private:
  const Var& find(std::string_view name);

  const MotionSession& session_;
  std::vector<std::pair<std::string, Var>> list_;   // lower-case name -> the entry
  std::unordered_map<std::string, Var> cache_;       // lower-case name -> what it resolved to
  std::string problem_;
};

// Writes the G-code diagnostics from index `printed` on to stderr as `stc check` renders them
// (file:line:col, the line, a caret), warnings too, and advances `printed`.
void printNewDiagnostics(const DiagnosticsEngine& diags, size_t& printed);

}  // namespace stc::motion::sm3face
