// Importers of the XML files other tools write: PLCopen TC6 XML (CODESYS and
// Beremiz flavours) and TwinCAT 3 (.TcPOU, .TcGVL, .TcDUT, .TcIO, .TcTTO and
// .plcproj).  Each file becomes one generated ST buffer whose segments map
// every offset back into the XML file (SourceManager::addGenerated), so the
// parser, sema and the diagnostics work on it like on any .st file.
//
// This header is light on purpose: pugixml stays inside compiler/import/.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "basic/Diagnostics.h"

namespace stc::import {

enum class FileKind {
  None,          // not an importable file (.st and friends are read directly)
  PlcOpen,       // *.xml
  TwinCat,       // *.TcPOU, *.TcGVL, *.TcDUT, *.TcIO, *.TcTTO
  TwinCatProject // *.plcproj
};

// By extension, case-insensitive.
FileKind kindOf(const std::string& path);

// A global variable list of a generated buffer: the VAR_GLOBAL blocks in
// [begin, end) form the list `name` (GVL.x), as a .st file named after it.
struct NamedGlobals {
  uint32_t begin = 0, end = 0;
  std::string name;
};

// A TwinCAT task (.TcTTO); the project's tasks become one CONFIGURATION.
struct TwinCatTask {
  std::string name;
  uint64_t cycleMicros = 0;
  int priority = 0;
  std::vector<std::string> programs;
  SourceLoc loc;   // the <Task> element
};

struct ImportResult {
  uint32_t file = 0;                    // the generated buffer; 0 if nothing to compile
  std::vector<NamedGlobals> globals;
  std::vector<TwinCatTask> tasks;       // .TcTTO
};

// Reads `path` (a PLCopen XML or TwinCAT object file), reports problems
// through `diags` (locations in the XML file) and adds the generated buffer.
// Returns false on errors; the buffer is still added when it is usable, so
// one run reports the XML problems and the ST errors together.
bool importFile(SourceManager& sm, DiagnosticsEngine& diags, const std::string& path, ImportResult& out);

// A TwinCAT PLC project: the files of its <Compile Include=...> items, in
// project order.  Paths that leave the project directory are refused.
bool loadPlcProject(SourceManager& sm, DiagnosticsEngine& diags, const std::string& path, std::vector<std::string>& files);

// The CONFIGURATION for TwinCAT tasks (ST), in a generated buffer whose
// pieces point at the <Task> elements; 0 when there are no tasks.
uint32_t twinCatConfiguration(SourceManager& sm, const std::vector<TwinCatTask>& tasks);

}  // namespace stc::import

namespace stc::ast { class ASTContext; }

namespace stc::import {

struct ExportOptions {
  std::string projectName = "stc";
  std::string productVersion;   // stc's version, for <fileHeader>
};

// Writes the user's declarations (units of `files`) as PLCopen TC6 XML
// v2.01 in the CODESYS form.  Declarations that PLCopen XML cannot hold are
// reported through `diags`; returns false then.
bool exportPlcOpen(const SourceManager& sm, const ast::ASTContext& ast, const std::vector<uint32_t>& files,
                   DiagnosticsEngine& diags, const ExportOptions& opts, std::string& xml);

}  // namespace stc::import
