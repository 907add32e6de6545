// The file sandbox (docs/security.md, "Files"): every file a program or a
// library block opens on the program's behalf (SMC_ReadCAM, SMC_WriteCAM,
// SMC_AxisDiagnosticLog.WriteToFile, project.toml cam files) and every file
// `stc test --update` writes goes through here, so the rules live in one place:
//
//  - the name is relative: absolute names are refused;
//  - it stays inside the root: a `..` that climbs above the root is refused,
//    and so is a symbolic link (anywhere on the path) that resolves outside it;
//  - the file opened is the one checked: the resolved path is opened one
//    component at a time with O_NOFOLLOW, so a link swapped in after the check
//    is not followed either;
//  - only regular files: a FIFO, a directory or a device is refused without
//    blocking (O_NONBLOCK); a write to a file with other hard links is refused.
#pragma once

#include <string>

namespace stc::vm {

enum class FileAccess {
  Read,          // an existing regular file
  Write,         // created or truncated; the root is created if missing (its parent must exist)
  WriteMakeDirs, // as Write, and missing directories between the root and the file are created
  ReadWrite,     // an existing regular file, read and written, kept as it is
  ReadWriteNew,  // created or truncated, read and written
  Append,        // created if missing, kept, every write at the end (write only)
  AppendRead,    // as Append, and read
};

// Opens `name` inside `root` (an empty root is the working directory).  Returns a file
// descriptor (O_CLOEXEC, blocking) or -1 with `why` (a short sentence for messages).
// `resolved`, when given, gets the absolute path opened.
int openInside(const std::string& root, const std::string& name, FileAccess access, std::string& why,
               std::string* resolved = nullptr);

// Whether `name` would be accepted (the same checks as openInside, nothing opened or
// created); `resolved` gets the absolute path.
bool resolveInside(const std::string& root, const std::string& name, std::string& resolved, std::string& why);

// Reads an open file (closing it) up to `maxBytes`; false when it is larger or a read fails.
enum class ReadResult { Ok, TooBig, Failed };
ReadResult readAndClose(int fd, unsigned long long maxBytes, std::string& text);

}  // namespace stc::vm
