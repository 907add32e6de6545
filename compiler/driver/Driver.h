// The compilation driver: turns command-line inputs (files or project
// directories) into a checked AST, and renders diagnostics.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "ast/AST.h"
#include "basic/Diagnostics.h"
#include "sema/Sema.h"

namespace stc::sema { struct Model; }

namespace stc {

// project.toml, as far as compilation is concerned (docs/projects.md).
struct ProjectConfig {
  std::string root;                      // directory holding project.toml
  std::string name;
  std::optional<sema::Dialect> dialect;
  std::optional<unsigned> addressBits;   // [build] address_model = 32 | 64
  std::vector<std::string> defines;
  std::vector<std::string> sources;      // absolute or root-relative paths, sorted
  std::vector<std::string> libraries;    // [project] libraries: optional libraries of stdlib-motion/ (e.g. codesys_sm3)
  // [[task]] tables: the CONFIGURATION they stand for, as ST ("" = none; tasks come from the sources).
  std::string tasksSource;
  std::string tasksWhere;                // "dir/project.toml:L:C" of the first [[task]]
  // Where each piece of tasksSource comes from in project.toml (SourceSegment::file is 0:
  // the loader fills in project.toml's id), so diagnostics point at what the user wrote.
  std::vector<SourceSegment> tasksSegments;
  std::string manifest;                  // dir/project.toml
  // [[cnc_program]] files (inside the project): stc check decodes them too, with the defaults
  // the controller gives them (F/E/E- and FF/EF/EF- until the program sets them).
  struct CncProgram {
    std::string path;
    double vel = 0, acc = 0, dec = 0, velFF = 0, accFF = 0, decFF = 0;
  };
  std::vector<CncProgram> cncPrograms;
};

// The names of the optional libraries built into the compiler.
std::vector<std::string> availableLibraries();

// Reads `dir/project.toml` and lists its sources (src/**/*.st, *.exp, *.txt, *.xml, *.TcPOU ...).
bool loadProject(const std::string& dir, ProjectConfig& out, std::string& error);

struct CompileOptions {
  std::optional<sema::Dialect> dialect;  // overrides the project's
  std::optional<unsigned> addressBits;   // 32 or 64; overrides the project's (default 32)
  std::set<std::string> defines;         // lower-case
  bool includeStdlib = true;             // the IEC standard FB declarations
  // stc check: also the names project.toml tables and scenarios give (ProjectCheck.cpp).
  bool checkProjectFiles = false;
  // Declarations of native libraries (name, ST text) compiled in before the inputs.
  std::vector<std::pair<std::string, std::string>> libraries;
  // Optional libraries of stdlib-motion/ by name (--lib), besides the project's.
  std::vector<std::string> libraryNames;
  unsigned parseThreads = 0;             // 0 = one per core
};

struct CompileStats {
  size_t files = 0, lines = 0, tokens = 0, bytes = 0;
  double parseSeconds = 0, semaSeconds = 0;
  double lexSeconds = 0, antlrSeconds = 0, buildSeconds = 0;   // parts of parseSeconds
  bool llFallback = false;
};

class Compilation {
public:
  Compilation();
  ~Compilation();

  SourceManager& sources() { return sm_; }
  DiagnosticsEngine& diags() { return diags_; }
  ast::ASTContext& ast() { return *ast_; }

  // Adds inputs: .st/.exp/.txt files, PLCopen XML and TwinCAT files
  // (compiler/import), project directories (project.toml or one .plcproj).
  bool addPath(const std::string& path);
  // The files added by addPath/addBuffer (not the libraries), in order.
  const std::vector<uint32_t>& inputFiles() const { return files_; }
  // G-code programs (.cnc, .ngc, .nc files, a project's nc/ directory): check() decodes them
  // (docs/cnc.md) and reports their errors with the ST ones.
  const std::vector<uint32_t>& gcodeFiles() const { return gcodeFiles_; }
  // Adds an in-memory file (tests, benchmarks, fuzzing).
  void addBuffer(const std::string& name, std::string text);

  // Parses everything and, if parsing succeeded, runs semantic analysis.
  bool check(const CompileOptions& opts);
  const CompileStats& stats() const { return stats_; }
  // The checked program; null unless check() succeeded.
  const sema::Model* model() const;
  sema::Dialect dialect() const { return dialect_; }
  unsigned addressBits() const { return addressBits_; }

private:
  SourceManager sm_;
  DiagnosticsEngine diags_;
  std::unique_ptr<ast::ASTContext> ast_;
  // Owns the symbols and types the AST is annotated with: lives as long as the AST.
  std::unique_ptr<sema::Sema> sema_;
  std::vector<uint32_t> files_;
  std::vector<uint32_t> gcodeFiles_;
  std::vector<std::pair<uint32_t, ProjectConfig::CncProgram>> gcodeDefaults_;   // [[cnc_program]] files
  void checkGCode();
  void checkProjectFiles();             // ProjectCheck.cpp
  std::vector<std::string> projectDirs_;
  struct Imports;                       // what the XML importers found (Driver.cpp)
  std::unique_ptr<Imports> imports_;
  bool addImported(const std::string& path);
  void projectError(const std::string& error);
  uint32_t tasksFile_ = 0;              // the [[task]] tables' CONFIGURATION (0: none)
  std::string tasksWhere_;              // where the first [[task]] is
  std::optional<sema::Dialect> projectDialect_;
  std::optional<unsigned> projectAddressBits_;
  unsigned addressBits_ = 32;
  std::vector<std::string> projectDefines_;
  std::vector<std::string> projectLibraries_;
  sema::Dialect dialect_ = sema::Dialect::Codesys;
  CompileStats stats_;
};

// Error recovery (Driver.cpp): drops the top-level declarations holding a
// syntax error and returns the names they declared; namesAny() tells whether
// a message quotes one of them.
std::set<std::string> dropBrokenDeclarations(ast::ASTContext& ast, const DiagnosticsEngine& diags);
bool namesAny(const std::string& message, const std::set<std::string>& names);

// Runs `fn` on a thread with a large stack, so that deeply nested input
// cannot overflow it.
void runWithLargeStack(const std::function<void()>& fn);
// Runs `fn` on `n` such threads at once and waits for all of them.
void runParallelWithLargeStacks(unsigned n, const std::function<void()>& fn);

// -verify: checks the diagnostics against `expected-error {{...}}` comments
// in the sources.  Prints mismatches to `out`; returns true if all match.
bool verifyDiagnostics(Compilation& c, std::string& out);

// Options written in a source file as `stc-options: --dialect=codesys -D X`.
CompileOptions optionsFromFileHeader(const std::string& text, CompileOptions base);

}  // namespace stc
