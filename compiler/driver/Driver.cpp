#include "driver/Driver.h"
#include "driver/DeclaredNames.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "config/ConfigSchema.h"
#include "sema/Model.h"

#include <pthread.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <atomic>
#include <cctype>
#include <chrono>
#include <thread>
#include <filesystem>
#include <sstream>
#include <string_view>

#include "basic/Text.h"
#include "import/Import.h"
#include "parse/Parser.h"

namespace fs = std::filesystem;

namespace stc {

// Generated from stdlib-motion/iec/*.st at configure time (StdlibSources.cpp).
struct EmbeddedSource { const char* name; const char* text; };
extern const EmbeddedSource kStdlibSources[];
extern const size_t kStdlibSourceCount;
struct EmbeddedLibrarySource { const char* library; const char* name; const char* text; };
extern const EmbeddedLibrarySource kLibrarySources[];
extern const size_t kLibrarySourceCount;

std::vector<std::string> availableLibraries() {
  std::vector<std::string> names;
  for (size_t i = 0; i < kLibrarySourceCount; ++i)
    if (names.empty() || names.back() != kLibrarySources[i].library) names.push_back(kLibrarySources[i].library);
  return names;
}

// Named global lists and TwinCAT tasks of imported files, applied after parsing.
struct Compilation::Imports {
  std::vector<std::pair<uint32_t, import::NamedGlobals>> globals;   // (generated file, list)
  std::vector<import::TwinCatTask> tasks;
  bool configurationAdded = false;
};

Compilation::Compilation() : diags_(sm_), ast_(std::make_unique<ast::ASTContext>()), imports_(std::make_unique<Imports>()) {}
Compilation::~Compilation() = default;

bool Compilation::addImported(const std::string& path) {
  if (import::kindOf(path) == import::FileKind::TwinCatProject) {
    std::vector<std::string> files;
    bool ok = import::loadPlcProject(sm_, diags_, path, files);
    for (const std::string& f : files) ok = addPath(f) && ok;
    return ok;
  }
  import::ImportResult r;
  bool ok = import::importFile(sm_, diags_, path, r);
  if (r.file) {
    files_.push_back(r.file);
    for (const import::NamedGlobals& g : r.globals) imports_->globals.push_back({r.file, g});
  }
  imports_->tasks.insert(imports_->tasks.end(), r.tasks.begin(), r.tasks.end());
  // A file that imported with errors (an LD POU, an unknown element) still yields
  // its ST: checking goes on, so one run reports those errors and the others.
  return ok || r.file != 0;
}

// A project.toml error "file:line:col: error: message" as a diagnostic at that
// place (with the source line and a caret); "file: error: message" without one.
void Compilation::projectError(const std::string& error) {
  const size_t e = error.find(": error: ");
  if (e == std::string::npos) {
    diags_.error(SourceLoc{}, error, "project");
    return;
  }
  const std::string prefix = error.substr(0, e), message = error.substr(e + 9);
  auto digits = [](const std::string& x) { return !x.empty() && x.size() < 9 && std::all_of(x.begin(), x.end(), ::isdigit); };
  const size_t c2 = prefix.rfind(':'), c1 = c2 == std::string::npos || c2 == 0 ? std::string::npos : prefix.rfind(':', c2 - 1);
  std::string text, why;
  if (c1 != std::string::npos && digits(prefix.substr(c1 + 1, c2 - c1 - 1)) && digits(prefix.substr(c2 + 1)) &&
      config::readRegularFile(prefix.substr(0, c1), text, why)) {
    const uint32_t id = sm_.addBuffer(prefix.substr(0, c1), std::move(text));
    const unsigned line = std::clamp<unsigned>(static_cast<unsigned>(std::stoul(prefix.substr(c1 + 1, c2 - c1 - 1))), 1, std::max(1u, sm_.lineCount(id)));
    const unsigned col = static_cast<unsigned>(std::stoul(prefix.substr(c2 + 1)));
    const uint32_t begin = sm_.lineStart(id, line);
    const std::string_view lineText = sm_.lineText(SourceLoc{id, begin});
    // toml++ counts columns in characters: step over UTF-8 continuation bytes.
    uint32_t off = 0;
    for (unsigned c = 1; c < col && off < lineText.size(); ++c)
      for (++off; off < lineText.size() && (static_cast<unsigned char>(lineText[off]) & 0xC0) == 0x80;) ++off;
    diags_.error(SourceLoc{id, begin + off}, message, "project");
    return;
  }
  diags_.error(SourceLoc{}, prefix + ": " + message, "project");
}

void Compilation::addBuffer(const std::string& name, std::string text) {
  files_.push_back(sm_.addBuffer(name, std::move(text)));
}

namespace {
// G-code programs by their extension (docs/cnc.md): .cnc (CODESYS / Moons), .ngc, .nc.
bool isGCodeFile(const fs::path& p) {
  const std::string ext = asciiLower(p.extension().string());
  return ext == ".cnc" || ext == ".ngc" || ext == ".nc";
}
}  // namespace

bool Compilation::addPath(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    ProjectConfig pc;
    std::string error;
    // Any kind of entry named project.toml makes a project (loadProject says what is wrong with it).
    if (!fs::exists(fs::symlink_status(fs::path(path) / "project.toml", ec))) {
      // A TwinCAT PLC project directory: the one .plcproj in it.
      std::vector<std::string> plcproj;
      for (const fs::directory_entry& e : fs::directory_iterator(path, ec))
        if (e.is_regular_file(ec) && import::kindOf(e.path().string()) == import::FileKind::TwinCatProject) plcproj.push_back(e.path().string());
      if (plcproj.size() == 1) return addImported(plcproj.front());
      diags_.error(SourceLoc{}, "'" + path + "' is a directory without project.toml" +
                                    (plcproj.empty() ? std::string(" or .plcproj") : " and with several .plcproj files") +
                                    "; pass source files or a project directory", "input");
      return false;
    }
    if (!loadProject(path, pc, error)) {
      projectError(error);
      return false;
    }
    projectDirs_.push_back(path);
    if (pc.dialect) projectDialect_ = pc.dialect;
    if (pc.addressBits) projectAddressBits_ = pc.addressBits;
    projectDefines_.insert(projectDefines_.end(), pc.defines.begin(), pc.defines.end());
    projectLibraries_.insert(projectLibraries_.end(), pc.libraries.begin(), pc.libraries.end());
    bool ok = true;
    for (const std::string& s : pc.sources) ok = addPath(s) && ok;
    // The project's G-code programs: nc/*.cnc, *.ngc, *.nc (docs/cnc.md).
    // Only files inside the project are read: a symbolic link out of it is an error, never
    // followed (docs/security.md), as the run refuses it.
    const fs::path root = fs::weakly_canonical(fs::path(path), ec);
    auto inside = [&](const std::string& file) {
      const fs::path real = fs::weakly_canonical(fs::path(file), ec);
      const auto [r, f] = std::mismatch(root.begin(), root.end(), real.begin(), real.end());
      if (!ec && r == root.end()) return true;
      diags_.error(SourceLoc{}, file + ": leads outside the project directory '" + path + "'; not read", "input");
      return false;
    };
    std::vector<std::string> nc;
    for (const fs::directory_entry& e : fs::directory_iterator(fs::path(path) / "nc", ec))
      if (e.is_regular_file(ec) && isGCodeFile(e.path())) nc.push_back(e.path().string());
    std::sort(nc.begin(), nc.end());
    const size_t before = gcodeFiles_.size();
    for (const std::string& s : nc) ok = (inside(s) && addPath(s)) && ok;
    // [[cnc_program]] files: G-code whatever their extension, decoded with their defaults.
    for (const ProjectConfig::CncProgram& p : pc.cncPrograms) {
      if (!inside(p.path)) {
        ok = false;
        continue;
      }
      uint32_t id = 0;
      for (size_t i = before; i < gcodeFiles_.size() && !id; ++i)
        if (fs::equivalent(fs::path(p.path), fs::path(sm_.file(gcodeFiles_[i]).path), ec)) id = gcodeFiles_[i];
      std::string error;
      if (!id && (id = sm_.loadFile(p.path, error)) != 0) gcodeFiles_.push_back(id);
      if (!id) {
        diags_.error(SourceLoc{}, p.path + ": " + error, "input");
        ok = false;
        continue;
      }
      gcodeDefaults_.emplace_back(id, p);
    }
    if (!pc.tasksSource.empty()) {
      // The generated CONFIGURATION reports its errors at the [[task]] tables it comes from.
      std::string why;
      const uint32_t manifest = sm_.loadFile(pc.manifest, why);
      if (manifest) {
        std::vector<SourceSegment> segs = pc.tasksSegments;
        for (SourceSegment& g : segs) g.file = manifest;
        files_.push_back(sm_.addGenerated((fs::path(path) / "project.toml [[task]]").string(), pc.tasksSource, std::move(segs)));
      } else {
        addBuffer((fs::path(path) / "project.toml [[task]]").string(), pc.tasksSource);
      }
      tasksFile_ = files_.back();
      tasksWhere_ = pc.tasksWhere;
    }
    return ok;
  }
  if (import::kindOf(path) != import::FileKind::None) return addImported(path);
  std::string error;
  uint32_t id = sm_.loadFile(path, error);
  if (!id) {
    diags_.error(SourceLoc{}, path + ": " + error, "input");
    return false;
  }
  (isGCodeFile(path) ? gcodeFiles_ : files_).push_back(id);
  return true;
}

namespace {
// `stc check` knows a $name$ of a G-code program when it starts with a global variable
// (x, GVL.x, x[2], x.member, any case) or a PROGRAM (MAIN.x), as the run-time lookup
// (codesys_sm3/Sm3NcProgram.h, NcVariables) takes them; its value comes at run time, so it
// reads as 0 here and the geometry of a block with variables is left to the decoder then.
class CheckedVariables : public cnc::VariableAccess {
public:
  explicit CheckedVariables(ast::ASTContext& ast) : names_(ast) {}
  bool read(std::string_view name, double& v) override {
    v = 0;
    return names_.known(name);
  }
  bool write(std::string_view name, double) override { return names_.known(name); }
  std::string suggest(std::string_view name) override { return names_.closest(name); }

private:
  DeclaredNames names_;
};
}  // namespace

void Compilation::checkGCode() {
  CheckedVariables vars(*ast_);
  for (uint32_t file : gcodeFiles_) {
    DiagnosticsEngine d(sm_);
    d.opts.errorLimit = 0;
    cnc::DecoderOptions o;
    for (const auto& [id, p] : gcodeDefaults_)
      if (id == file) {
        o.defaultVel = p.vel;
        o.defaultAcc = p.acc;
        o.defaultDec = p.dec;
        o.defaultRapidVel = p.velFF;
        o.defaultRapidAcc = p.accFF;
        o.defaultRapidDec = p.decFF;
      }
    cnc::decodeAll(sm_, file, d, o, &vars);
    const std::string_view text = sm_.file(file).text;
    for (const Diagnostic& g : d.diagnostics()) {
      // In a block with $variables$ only the syntax and the names can be checked now.
      const size_t begin = text.rfind('\n', g.loc.offset ? g.loc.offset - 1 : 0);
      const size_t end = text.find('\n', g.loc.offset);
      const std::string_view line = text.substr(begin == std::string_view::npos ? 0 : begin + 1,
                                                (end == std::string_view::npos ? text.size() : end) - (begin == std::string_view::npos ? 0 : begin + 1));
      const bool variable = line.find('$') != std::string_view::npos;
      if (variable && g.code != "gcode-syntax" && g.code != "gcode-variable" && g.code != "gcode-unknown-word" &&
          g.code != "gcode-unknown-code" && g.code != "gcode-duplicate-n" && g.code != "gcode-duplicate-word")
        continue;
      diags_.commit(g);
    }
  }
}


namespace {

// Upper-case names a declaration introduces (POUs, types, globals, namespaces).
void declaredNames(const ast::Decl* d, std::set<std::string>& out) {
  if (auto* p = ast::dyn_cast<ast::PouDecl>(d)) {
    if (!p->name.parts.empty()) out.insert(asciiUpper(p->name.parts.front().name));
  } else if (auto* t = ast::dyn_cast<ast::TypeDecl>(d)) {
    out.insert(asciiUpper(t->name.name));
  } else if (auto* g = ast::dyn_cast<ast::GlobalVarDecl>(d)) {
    for (const ast::VarDecl* v : g->block.vars) out.insert(asciiUpper(v->name.name));
    if (!g->listName.name.empty()) out.insert(asciiUpper(g->listName.name));
  } else if (auto* n = ast::dyn_cast<ast::NamespaceDecl>(d)) {
    if (!n->name.parts.empty()) out.insert(asciiUpper(n->name.parts.front().name));
    for (const ast::Decl* c : n->decls) declaredNames(c, out);
  }
}

bool covers(const SourceRange& r, SourceLoc l) {
  return r.begin.file == l.file && l.offset >= r.begin.offset && l.offset <= r.end.offset;
}

}  // namespace

// Removes the top-level declarations that contain a syntax error; returns the
// names they declared.
std::set<std::string> dropBrokenDeclarations(ast::ASTContext& ast, const DiagnosticsEngine& diags) {
  std::vector<SourceLoc> errors;
  for (const Diagnostic& d : diags.diagnostics())
    if (d.severity == Severity::Error && d.loc.valid()) errors.push_back(d.loc);
  std::set<std::string> dropped;
  for (ast::SourceUnit& u : ast.units()) {
    std::vector<ast::Decl*> kept;
    for (ast::Decl* d : u.decls) {
      bool broken = !d->range.valid();
      for (SourceLoc l : errors) broken = broken || covers(d->range, l);
      if (broken) declaredNames(d, dropped);
      else kept.push_back(d);
    }
    // A syntax error outside every declaration (between them) leaves no trace
    // in the tree; the declarations around it are fine.
    u.decls = std::move(kept);
  }
  return dropped;
}

// Whether a message quotes one of `names` ('X', case-insensitive).
bool namesAny(const std::string& message, const std::set<std::string>& names) {
  for (size_t a = message.find('\''); a != std::string::npos; a = message.find('\'', a + 1)) {
    size_t b = message.find('\'', a + 1);
    if (b == std::string::npos) break;
    std::string quoted = asciiUpper(std::string_view(message).substr(a + 1, b - a - 1));
    size_t dot = quoted.find('.');
    if (names.count(quoted) || (dot != std::string::npos && names.count(quoted.substr(0, dot)))) return true;
    a = b;
  }
  return false;
}

namespace {
// The names an ST text declares as a TYPE, FUNCTION_BLOCK, FUNCTION, INTERFACE or PROGRAM
// (upper case): the keyword, blanks, then the name.
void declaredNames(std::string_view text, const std::string& library, std::map<std::string, std::string>& out) {
  const std::string t = asciiUpper(std::string(text));
  auto nameChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (const char* kw : {"TYPE ", "FUNCTION_BLOCK ", "FUNCTION ", "INTERFACE ", "PROGRAM "}) {
    for (size_t at = t.find(kw); at != std::string::npos; at = t.find(kw, at + 1)) {
      if (at > 0 && nameChar(t[at - 1])) continue;
      size_t b = at + std::strlen(kw);
      while (b < t.size() && (t[b] == ' ' || t[b] == '\t')) ++b;
      size_t e = b;
      while (e < t.size() && nameChar(t[e])) ++e;
      if (e > b) out.emplace(t.substr(b, e - b), library);
    }
  }
}
}  // namespace

bool Compilation::check(const CompileOptions& opts) {
  using clock = std::chrono::steady_clock;
  dialect_ = opts.dialect ? *opts.dialect : projectDialect_ ? *projectDialect_ : sema::Dialect::Codesys;
  addressBits_ = opts.addressBits ? *opts.addressBits : projectAddressBits_ ? *projectAddressBits_ : 32;
  // Built-in libraries are marked: their structures keep 8-byte pointer slots.
  auto library = [&](uint32_t id) { sm_.file(id).library = true; return id; };
  ParseOptions popts;
  popts.defines = opts.defines;
  for (const std::string& d : projectDefines_) popts.defines.insert(asciiLower(d));
  std::vector<uint32_t> all;
  if (opts.includeStdlib)
    for (size_t i = 0; i < kStdlibSourceCount; ++i) all.push_back(library(sm_.addBuffer(kStdlibSources[i].name, kStdlibSources[i].text)));
  for (const auto& [name, text] : opts.libraries) all.push_back(library(sm_.addBuffer(name, text)));
  std::vector<std::string> libs = opts.libraryNames;
  libs.insert(libs.end(), projectLibraries_.begin(), projectLibraries_.end());
  // A library names the libraries it builds on in a comment line
  // "stc-requires: NAME ..." (leadshine requires codesys_sm3 for AXIS_REF_SM3).
  for (size_t k = 0; k < libs.size(); ++k)
    for (size_t i = 0; i < kLibrarySourceCount; ++i) {
      if (libs[k] != kLibrarySources[i].library) continue;
      std::string_view text = kLibrarySources[i].text;
      size_t at = text.find("stc-requires:");
      if (at == std::string_view::npos) continue;
      std::string_view rest = text.substr(at + 13, text.find('\n', at) - at - 13);
      for (size_t b = 0; b < rest.size();) {
        while (b < rest.size() && (rest[b] == ' ' || rest[b] == ',')) ++b;
        size_t e = b;
        while (e < rest.size() && (std::isalnum(static_cast<unsigned char>(rest[e])) || rest[e] == '_')) ++e;
        if (e > b && std::find(libs.begin(), libs.end(), rest.substr(b, e - b)) == libs.end()) libs.emplace_back(rest.substr(b, e - b));
        b = e == b ? rest.size() : e;
      }
    }
  std::sort(libs.begin(), libs.end());
  libs.erase(std::unique(libs.begin(), libs.end()), libs.end());
  for (const std::string& lib : libs)
    for (size_t i = 0; i < kLibrarySourceCount; ++i)
      if (lib == kLibrarySources[i].library) all.push_back(library(sm_.addBuffer(kLibrarySources[i].name, kLibrarySources[i].text)));
  // TwinCAT tasks (.TcTTO) of all imported files form one CONFIGURATION.
  if (!imports_->configurationAdded && !imports_->tasks.empty()) {
    imports_->configurationAdded = true;
    files_.push_back(import::twinCatConfiguration(sm_, imports_->tasks));
  }
  all.insert(all.end(), files_.begin(), files_.end());

  auto t0 = clock::now();
  // Files are parsed in parallel, each into its own AST arena and
  // diagnostics list; results are merged in input order, so the output does
  // not depend on scheduling.
  struct FileResult {
    std::unique_ptr<ast::ASTContext> ast;
    std::unique_ptr<DiagnosticsEngine> diags;
    ParseStats stats;
    bool ok = true;
  };
  std::vector<FileResult> results(all.size());
  // Largest files first, so the workers finish at about the same time.
  std::vector<size_t> order(all.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return sm_.file(all[a]).text.size() > sm_.file(all[b]).text.size(); });
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t k = next++; k < all.size(); k = next++) {
      size_t i = order[k];
      FileResult& r = results[i];
      r.ast = std::make_unique<ast::ASTContext>();
      r.diags = std::make_unique<DiagnosticsEngine>(sm_);
      r.diags->opts.errorLimit = 0;
      r.ok = parseFile(sm_, all[i], *r.diags, *r.ast, popts, &r.stats);
    }
  };
  unsigned threads = std::max(1u, std::min<unsigned>(std::thread::hardware_concurrency(), static_cast<unsigned>(all.size())));
  if (opts.parseThreads) threads = std::min(threads, opts.parseThreads);
  runParallelWithLargeStacks(threads, worker);
  bool parsed = true;
  for (size_t i = 0; i < all.size(); ++i) {
    FileResult& r = results[i];
    parsed = parsed && r.ok;
    for (const Diagnostic& d : r.diags->diagnostics()) diags_.commit(d);
    ast_->adopt(std::move(*r.ast));
    const ParseStats& ps = r.stats;
    stats_.tokens += ps.tokens;
    stats_.lexSeconds += ps.lexSeconds;
    stats_.antlrSeconds += ps.parseSeconds;
    stats_.buildSeconds += ps.buildSeconds;
    stats_.llFallback = stats_.llFallback || ps.usedLLFallback;
    stats_.bytes += sm_.file(all[i]).text.size();
    stats_.lines += sm_.lineCount(all[i]);
    ++stats_.files;
  }
  // Imported global variable lists carry their names (<GVL Name=...>, <globalVars name=...>).
  for (ast::SourceUnit& u : ast_->units())
    for (ast::Decl* d : u.decls)
      if (auto* g = ast::dyn_cast<ast::GlobalVarDecl>(d))
        for (const auto& [file, named] : imports_->globals)
          if (file == u.file && d->range.begin.offset >= named.begin && d->range.begin.offset < named.end && !named.name.empty()) {
            g->listName.name = named.name;
            g->listName.range = SourceRange(d->range.begin);
          }
  // A file holding only VAR_GLOBAL blocks is a GVL named after the file.
  for (ast::SourceUnit& u : ast_->units()) {
    bool onlyGlobals = !u.decls.empty();
    for (ast::Decl* d : u.decls) onlyGlobals = onlyGlobals && ast::isa<ast::GlobalVarDecl>(d);
    if (!onlyGlobals) continue;
    std::string stem = fs::path(sm_.file(u.file).path).stem().string();
    bool ident = !stem.empty() && (std::isalpha(static_cast<unsigned char>(stem[0])) || stem[0] == '_');
    for (char c : stem) ident = ident && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
    if (!ident) continue;
    for (ast::Decl* d : u.decls) {
      auto* g = ast::cast<ast::GlobalVarDecl>(d);
      if (!g->listName.name.empty()) continue;
      g->listName.name = stem;
      g->listName.range = SourceRange(SourceLoc{u.file, 0});
    }
  }
  // [[task]] tables and an ST CONFIGURATION (or TwinCAT tasks) both define the tasks: one of them.
  if (tasksFile_)
    for (ast::SourceUnit& u : ast_->units())
      for (ast::Decl* d : u.decls)
        if (ast::isa<ast::ConfigurationDecl>(d) && u.file != tasksFile_ && !sm_.file(u.file).library) {
          diags_.error(d->range.begin, "this CONFIGURATION and the [[task]] tables of " + tasksWhere_ +
                                           " both define the tasks; keep one of them (docs/projects.md)", "project");
          parsed = false;
        }
  auto t1 = clock::now();
  stats_.parseSeconds = std::chrono::duration<double>(t1 - t0).count();
  sema::SemaOptions so;
  so.dialect = dialect_;
  so.addressBits = addressBits_;
  // "unknown type 'AXIS_REF_SM3'": which optional library, not compiled in, declares it.
  // The index of those libraries' names is built once, at the first unknown type.
  so.libraryOf = [libs, index = std::shared_ptr<std::map<std::string, std::string>>()](const std::string& name) mutable -> std::string {
    if (!index) {
      index = std::make_shared<std::map<std::string, std::string>>();
      for (size_t i = 0; i < kLibrarySourceCount; ++i)
        if (std::find(libs.begin(), libs.end(), kLibrarySources[i].library) == libs.end())
          declaredNames(kLibrarySources[i].text, kLibrarySources[i].library, *index);
    }
    const auto it = index->find(asciiUpper(name));
    return it == index->end() ? std::string() : it->second;
  };
  if (!parsed) {
    // Like clang, go on after syntax errors: the declarations that parsed
    // cleanly are checked, so one run reports the missing ';' and the
    // misspelt name elsewhere.  Declarations holding a syntax error are left
    // out, and "undeclared" errors about the names they declared are dropped.
    std::set<std::string> dropped = dropBrokenDeclarations(*ast_, diags_);
    DiagnosticsEngine semaDiags(sm_);
    semaDiags.opts = diags_.opts;
    sema_ = std::make_unique<sema::Sema>(*ast_, semaDiags, so);
    sema_->run();
    for (const Diagnostic& d : semaDiags.diagnostics())
      if (!((d.code == "undeclared-name" || d.code == "unknown-type") && namesAny(d.message, dropped))) diags_.commit(d);
    stats_.semaSeconds = std::chrono::duration<double>(clock::now() - t1).count();
    checkGCode();
    if (opts.checkProjectFiles) checkProjectFiles();
    return false;
  }
  sema_ = std::make_unique<sema::Sema>(*ast_, diags_, so);
  bool ok = sema_->run();
  stats_.semaSeconds = std::chrono::duration<double>(clock::now() - t1).count();
  checkGCode();
  if (opts.checkProjectFiles) checkProjectFiles();
  return ok && !diags_.hasErrors();
}

const sema::Model* Compilation::model() const {
  if (!sema_ || diags_.hasErrors()) return nullptr;
  return &sema_->model();
}

void runParallelWithLargeStacks(unsigned n, const std::function<void()>& fn) {
  // 512 MiB of address space per thread; pages are only touched when used.
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, 512u << 20);
  auto tramp = [](void* p) -> void* {
    (*static_cast<const std::function<void()>*>(p))();
    return nullptr;
  };
  std::vector<pthread_t> started;
  for (unsigned i = 0; i < n; ++i) {
    pthread_t th;
    if (pthread_create(&th, &attr, tramp, const_cast<std::function<void()>*>(&fn)) == 0) started.push_back(th);
  }
  if (started.empty()) fn();   // could not start a thread: run here
  for (pthread_t th : started) pthread_join(th, nullptr);
  pthread_attr_destroy(&attr);
}

void runWithLargeStack(const std::function<void()>& fn) { runParallelWithLargeStacks(1, fn); }

CompileOptions optionsFromFileHeader(const std::string& text, CompileOptions base) {
  size_t p = text.find("stc-options:");
  if (p == std::string::npos) return base;
  size_t e = text.find_first_of("\r\n", p);
  std::istringstream in(text.substr(p + 12, e == std::string::npos ? std::string::npos : e - p - 12));
  std::string tok;
  while (in >> tok) {
    if (tok == "--dialect=codesys") base.dialect = sema::Dialect::Codesys;
    else if (tok == "--dialect=iec") base.dialect = sema::Dialect::IEC;
    else if (tok == "--address-model=32") base.addressBits = 32;
    else if (tok == "--address-model=64") base.addressBits = 64;
    else if (tok == "-D" && in >> tok) base.defines.insert(asciiLower(tok));
    else if (tok.rfind("-D", 0) == 0) base.defines.insert(asciiLower(tok.substr(2)));
  }
  return base;
}

}  // namespace stc
