// stc: the command-line entry point.  Subcommands map onto the driver; the
// command contract is ../shared/DESIGN.md ("The stc command").
#include <filesystem>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <set>
#include <iostream>

#include "basic/Text.h"
#include "codegen/CodeGen.h"
#include "config/ConfigSchema.h"
#include "config/Duration.h"
#include "driver/Driver.h"
#include "import/Import.h"
#include "sema/Model.h"
#include "vm/Controller.h"
#include "vm/Time.h"
#include "vm/testlib/TestLib.h"
#include "tools/stc/Libraries.h"
#include "tools/stc/Init.h"
#include "tools/stc/TestCommand.h"
#include "tools/stc/Plot.h"

using namespace stc;

namespace {

struct CheckArgs {
  std::vector<std::string> paths;
  std::string dialect;
  unsigned addressModel = 0;   // 0: the project's (default 32)
  std::vector<std::string> defines;
  std::vector<std::string> libs;
  std::string format = "text";
  std::string color = "auto";
  bool verify = false;
  bool werror = false;
  bool noWarnings = false;
  std::vector<std::string> noWarn;
  unsigned errorLimit = 100;
  bool stats = false;
  unsigned jobs = 0;
};

CompileOptions compileOptions(const CheckArgs& a) {
  CompileOptions o;
  if (a.dialect == "codesys") o.dialect = sema::Dialect::Codesys;
  else if (a.dialect == "iec") o.dialect = sema::Dialect::IEC;
  if (a.addressModel) o.addressBits = a.addressModel;
  o.parseThreads = a.jobs;
  for (const std::string& d : a.defines) o.defines.insert(asciiLower(d));
  o.libraryNames = a.libs;
  return o;
}

void applyDiagOptions(const CheckArgs& a, DiagnosticsEngine& d) {
  d.opts.warningsAsErrors = a.werror;
  d.opts.noWarnings = a.noWarnings;
  d.opts.errorLimit = a.errorLimit;
  for (const std::string& w : a.noWarn) d.opts.disabledWarnings.insert(w);
}

int runVerify(const CheckArgs& a) {
  // Each file is checked on its own, with options from its header.
  int failures = 0;
  for (const std::string& path : a.paths) {
    Compilation c;
    applyDiagOptions(a, c.diags());
    c.diags().opts.errorLimit = 0;
    if (!c.addPath(path)) {
      for (const Diagnostic& d : c.diags().diagnostics()) std::cerr << renderText(c.sources(), d);
      ++failures;
      continue;
    }
    CompileOptions o = compileOptions(a);
    for (uint32_t f = 1; f <= c.sources().fileCount(); ++f) o = optionsFromFileHeader(c.sources().file(f).text, o);
    runWithLargeStack([&] { c.check(o); });
    std::string report;
    if (!verifyDiagnostics(c, report)) {
      std::cerr << path << ": verification failed\n" << report;
      ++failures;
    }
  }
  return failures ? 1 : 0;
}

// Adds the inputs and checks them with the command's options; false on any error.
bool checkInputs(Compilation& c, const CheckArgs& a) {
  applyDiagOptions(a, c.diags());
  bool inputsOk = true;
  for (const std::string& p : a.paths) inputsOk = c.addPath(p) && inputsOk;
  bool ok = false;
  CompileOptions o = compileOptions(a);
  o.checkProjectFiles = true;
  if (inputsOk) runWithLargeStack([&] { ok = c.check(o); });
  return ok;
}

int runCheck(const CheckArgs& a) {
  if (a.verify) return runVerify(a);
  Compilation c;
  bool ok = checkInputs(c, a);
  const auto& diags = c.diags().diagnostics();
  if (a.format == "json") {
    std::cout << renderJson(c.sources(), diags);
  } else {
    bool color = a.color == "always" || (a.color == "auto" && isatty(STDERR_FILENO));
    for (const Diagnostic& d : diags) std::cerr << renderText(c.sources(), d, color);
    unsigned e = c.diags().errorCount(), w = c.diags().warningCount();
    // clang's summary line.
    std::string ws = fmt::format("{} warning{}", w, w == 1 ? "" : "s");
    std::string es = fmt::format("{} error{}", e, e == 1 ? "" : "s");
    if (w && e) std::cerr << ws << " and " << es << " generated.\n";
    else if (e) std::cerr << es << " generated.\n";
    else if (w) std::cerr << ws << " generated.\n";
  }
  if (a.stats) {
    const CompileStats& s = c.stats();
    double total = s.parseSeconds + s.semaSeconds;
    std::cerr << fmt::format("stc: {} files, {} lines, {} tokens; parse {:.3f} s (lex {:.3f}, parser {:.3f}, AST {:.3f}), sema {:.3f} s; {:.0f} lines/s{}\n",
                             s.files, s.lines, s.tokens, s.parseSeconds, s.lexSeconds, s.antlrSeconds, s.buildSeconds, s.semaSeconds,
                             total > 0 ? s.lines / total : 0.0, s.llFallback ? " (LL fallback used)" : "");
  }
  return (ok && !c.diags().hasErrors()) ? 0 : 1;
}

struct ExportArgs : CheckArgs {
  std::string plcopen;
};

// stc export --plcopen OUT.xml PATH...: the checked program as PLCopen XML.
int runExport(const ExportArgs& a) {
  Compilation c;
  bool ok = checkInputs(c, a);
  std::string xml;
  if (ok) {
    import::ExportOptions eo;
    std::filesystem::path first(a.paths.front());
    eo.projectName = (first.filename().empty() ? first.parent_path() : first).stem().string();
    eo.productVersion = STC_VERSION;
    ok = import::exportPlcOpen(c.sources(), c.ast(), c.inputFiles(), c.diags(), eo, xml);
  }
  bool color = a.color == "always" || (a.color == "auto" && isatty(STDERR_FILENO));
  for (const Diagnostic& d : c.diags().diagnostics()) std::cerr << renderText(c.sources(), d, color);
  if (!ok || c.diags().hasErrors()) return 1;
  FILE* f = a.plcopen == "-" ? stdout : std::fopen(a.plcopen.c_str(), "wb");
  if (!f || std::fwrite(xml.data(), 1, xml.size(), f) != xml.size() || (f != stdout && std::fclose(f) != 0)) {
    std::cerr << "stc: error: cannot write '" << a.plcopen << "'\n";
    return 1;
  }
  return 0;
}

// Durations on the command line: T#1s500ms, 1s500ms, 10s, 250ms, 2m, 1h, 5us, 100ns.
// The grammar is config::parseDuration's, as in project.toml and scenarios.
bool parseDuration(const char* option, const std::string& text, config::DurationSign sign, int64_t& out) {
  std::string why;
  if (config::parseDuration(text, sign, out, &why)) return true;
  std::cerr << "stc: error: " << option << ": " << why << " (e.g. 10s, 250ms, 1h30m, T#1s500ms)\n";
  return false;
}

struct BuildArgs : CheckArgs {
  std::string output;
  std::string emit = "obj";
  std::string opt;
  bool noChecks = false;
  bool checkPointers = false;
  bool debug = false;
  std::vector<std::string> programs;
  std::string interval;
  // run
  uint64_t cycles = 0;
  bool cyclesGiven = false;
  std::string forDuration;
  std::vector<std::string> watches;
  std::vector<std::string> traces;
  std::string traceOut;
  std::string plotOut;   // --plot: an SVG of the trace (tools/stc/Plot.h)
  std::vector<std::string> plotXy;   // --xy X,Y: a path plot instead of the time plot
  bool realtime = false;
  std::string watchdog;
  int64_t slice = 0;
  std::string retain;
  std::string retainEvery;
  std::string watchEvery;
  bool cold = false;
  bool retainReset = false;
  std::string dataDir;
  bool testlib = false;
  std::set<std::string> given;   // duration options given on the command line (also as "")
};

void printDiagnostics(Compilation& c, const CheckArgs& a) {
  bool color = a.color == "always" || (a.color == "auto" && isatty(STDERR_FILENO));
  for (const Diagnostic& d : c.diags().diagnostics()) std::cerr << renderText(c.sources(), d, color);
}

// Parses, checks and generates code.  Returns null (diagnostics printed) on errors.
std::unique_ptr<codegen::CompiledModule> compile(Compilation& c, const BuildArgs& a, bool needTasks, int& status) {
  applyDiagOptions(a, c.diags());
  bool inputsOk = true;
  for (const std::string& p : a.paths) inputsOk = c.addPath(p) && inputsOk;
  bool ok = false;
  CompileOptions co = compileOptions(a);
  // The test natives are always registered (a declaration that does not
  // match them is a load error); their ST declarations only with --testlib.
  if (a.testlib) co.libraries.push_back({"<testlib>", vm::TestLibrary::source()});
  if (inputsOk) runWithLargeStack([&] { ok = c.check(co); });
  status = 1;
  if (!ok || !inputsOk || !c.model()) {
    printDiagnostics(c, a);
    return nullptr;
  }
  codegen::CodegenOptions o;
  o.optLevel = a.opt.empty() ? (needTasks ? 1 : 2) : static_cast<unsigned>(a.opt[0] - '0');
  o.checks = !a.noChecks;
  o.checkPointers = a.checkPointers && !a.noChecks;
  o.debugInfo = a.debug;
  o.programs = a.programs;
  if (!a.interval.empty() || a.given.count("--interval")) {
    int64_t ns = 0;
    if (!parseDuration("--interval", a.interval, config::DurationSign::Positive, ns)) {
      status = 2;
      return nullptr;
    }
    o.defaultIntervalNs = ns;
  }
  std::unique_ptr<codegen::CompiledModule> m;
  runWithLargeStack([&] { m = codegen::generate(*c.model(), c.sources(), c.diags(), o, needTasks); });
  printDiagnostics(c, a);
  if (!m) return nullptr;
  status = 0;
  return m;
}

std::string outputStem(const BuildArgs& a) {
  std::string p = a.paths.empty() ? "out" : a.paths[0];
  while (!p.empty() && p.back() == '/') p.pop_back();
  ProjectConfig cfg;
  std::string err;
  if (loadProject(p, cfg, err) && !cfg.name.empty()) return cfg.name;
  size_t slash = p.find_last_of('/');
  std::string base = slash == std::string::npos ? p : p.substr(slash + 1);
  size_t dot = base.find_last_of('.');
  return dot == std::string::npos ? base : base.substr(0, dot);
}

int runBuild(const BuildArgs& a) {
  Compilation c;
  int status = 0;
  auto m = compile(c, a, false, status);
  if (!m) return status;
  bool ir = a.emit == "llvm";
  std::string out = a.output.empty() ? outputStem(a) + (ir ? ".ll" : ".o") : a.output;
  if (!ir && out == "-") {
    std::cerr << "stc: error: an object file cannot be written to stdout\n";
    return 2;
  }
  std::string err;
  if (!codegen::emit(*m, ir ? codegen::EmitKind::LLVM : codegen::EmitKind::Object, out, err)) {
    std::cerr << "stc: error: " << err << "\n";
    return 1;
  }
  return 0;
}

int runRun(const BuildArgs& a) {
  if (!a.retain.empty()) {
    // The retain file is read at start and written at the end: a directory, FIFO (which would
    // block), device or link loop in its place is refused before anything runs.
    std::string why;
    if (!config::checkRegularFile(a.retain, why, true)) {
      std::cerr << "stc: error: --retain: '" << a.retain << "' " << why << "\n";
      return 2;
    }
  }
  Compilation c;
  int status = 0;
  auto m = compile(c, a, true, status);
  if (!m) return status;
  vm::RunOptions ro;
  if (a.cyclesGiven) ro.cycles = a.cycles;
  // Duration options: absent, or a valid duration (else exit 2).
  auto duration = [&](const char* option, const std::string& text, bool positive, std::optional<int64_t>& out) {
    if (text.empty() && !a.given.count(option)) return true;
    int64_t ns = 0;
    if (!parseDuration(option, text, positive ? config::DurationSign::Positive : config::DurationSign::NonNegative, ns)) return false;
    out = ns;
    return true;
  };
  if (!duration("--for", a.forDuration, false, ro.duration) || !duration("--watchdog", a.watchdog, false, ro.watchdog) ||
      !duration("--retain-every", a.retainEvery, true, ro.retainEvery) || !duration("--watch-every", a.watchEvery, true, ro.watchEvery))
    return 2;
  if (a.slice > 0) ro.slice = a.slice;
  ro.retainFile = a.retain;
  ro.cold = a.cold;
  ro.retainReset = a.retainReset;
  if (a.retainReset && a.retain.empty()) {
    std::cerr << "stc: error: --retain-reset needs --retain FILE\n";
    return 2;
  }
  ro.realtime = a.realtime;
  ro.stats = a.stats;
  ro.watches = a.watches;
  if (ro.watchEvery && ro.watches.empty()) {
    std::cerr << "stc: error: --watch-every needs --watch VAR (the values to print)\n";
    return 2;
  }
  for (const std::string& t : a.traces) {
    size_t pos = 0;
    while (pos <= t.size()) {
      size_t comma = t.find(',', pos);
      std::string one = t.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
      if (!one.empty()) ro.traces.push_back(one);
      if (comma == std::string::npos) break;
      pos = comma + 1;
    }
  }
  ro.traceOut = a.traceOut;
  // --plot: the trace goes to --trace-out (a CSV) or a temporary CSV, plotted after the run.
  std::string plotCsv;
  struct RemoveAtExit {
    std::string path;
    ~RemoveAtExit() {
      if (!path.empty()) std::remove(path.c_str());
    }
  } plotTemp;
  if (!a.plotOut.empty()) {
    plot::PlotOptions xyCheck;
    std::string xyError;
    if (!plot::parseXyPairs(a.plotXy, xyCheck, xyError)) {
      std::cerr << "stc: error: " << xyError << "\n";
      return 2;
    }
    if (ro.traces.empty()) {
      std::cerr << "stc: error: --plot needs --trace VAR,... (the variables to plot)\n";
      return 2;
    }
    if (ro.traceOut.empty()) {
      std::string tmpl = (std::filesystem::temp_directory_path() / "stc-plot-XXXXXX.csv").string();
      int fd = mkstemps(tmpl.data(), 4);
      if (fd < 0) {
        std::cerr << "stc: error: --plot: cannot create a temporary trace file\n";
        return 1;
      }
      close(fd);
      ro.traceOut = plotCsv = plotTemp.path = tmpl;
    } else if (ro.traceOut.size() >= 4 && asciiLower(ro.traceOut.substr(ro.traceOut.size() - 4)) == ".csv") {
      plotCsv = ro.traceOut;
    } else {
      std::cerr << "stc: error: --plot reads the trace as CSV: use --trace-out FILE.csv or leave --trace-out out\n";
      return 2;
    }
  }
  if (!ro.traces.empty() && ro.traceOut.empty()) {
    std::cerr << "stc: error: --trace needs --trace-out FILE.csv|FILE.vcd (or --plot FILE.svg)\n";
    return 2;
  }
  if (ro.traces.empty() && !a.traceOut.empty()) {   // else the file would silently not be written
    std::cerr << "stc: error: --trace-out needs --trace VAR,... (the variables to record)\n";
    return 2;
  }
  // The axes, devices and vendor profile that project directories configure (project.toml).
  tool::RunLibraries libs;
  libs.motion.config().profile = motion::defaultVendorProfile(a.libs);
  for (const std::string& p : a.paths) {
    std::error_code ec;
    if (!std::filesystem::is_directory(p, ec)) continue;
    std::string err;
    if (!libs.motion.readProject(p, a.libs, err)) {
      std::cerr << "stc: error: " << err << "\n";
      return 1;
    }
  }
  // The data directory: --data-dir, else the project's (readProject), else for loose
  // files the directory of the first one (docs/security.md).
  if (!a.dataDir.empty()) libs.motion.config().filesDir = a.dataDir;
  if (libs.motion.config().filesDir.empty() && !a.paths.empty()) {
    std::string d = std::filesystem::path(a.paths[0]).parent_path().string();
    libs.motion.config().filesDir = d.empty() ? "." : d;
  }
  vm::Controller ctl(*c.model(), c.diags());
  libs.attachTo(ctl);
  std::string err;
  size_t before = c.diags().diagnostics().size();
  if (!ctl.load(std::move(m), err)) {
    std::cerr << "stc: error: " << err << "\n";
    return 1;
  }
  int rc = ctl.run(ro, std::cout, std::cerr);
  bool color = a.color == "always" || (a.color == "auto" && isatty(STDERR_FILENO));
  const auto& diags = c.diags().diagnostics();
  for (size_t i = before; i < diags.size(); ++i) std::cerr << renderText(c.sources(), diags[i], color);
  if (!plotCsv.empty() && rc != 2) {
    plot::PlotOptions po;
    po.title = outputStem(a);
    std::string e;
    plot::parseXyPairs(a.plotXy, po, e);   // checked before the run
    if (plot::plotTraceFile(plotCsv, a.plotOut, po, e) != 0) {
      std::cerr << "stc: error: --plot: " << e << "\n";
      if (rc == 0) rc = 1;
    }
  }
  return rc;
}

void addCompileOptions(CLI::App* cmd, BuildArgs& a) {
  cmd->add_option("paths", a.paths, "Files (.st, .exp, PLCopen .xml, TwinCAT .TcPOU/.plcproj ...) or project directories")->required();
  cmd->add_option("--dialect", a.dialect, "Language dialect (default: the project's, else codesys)")->check(CLI::IsMember({"iec", "codesys"}));
  cmd->add_option("--address-model", a.addressModel, "Pointer size in bits, 32 or 64 (default: the project's, else 32)")->check(CLI::IsMember({32u, 64u}));
  cmd->add_option("-D,--define", a.defines, "Define NAME for {IF defined(NAME)} pragmas")->allow_extra_args(false);
  cmd->add_option("--lib", a.libs, "Compile in an optional library (e.g. codesys_sm3)")->check(CLI::IsMember(availableLibraries()))->allow_extra_args(false);
  cmd->add_option("-O", a.opt, "Optimisation level 0-3 (-O0 .. -O3)")->check(CLI::IsMember({"0", "1", "2", "3"}));
  cmd->add_flag("--no-checks", a.noChecks, "Drop the runtime checks (division by zero, bounds, NULL, subranges)");
  cmd->add_flag("--check-pointers", a.checkPointers, "Fault on dereferences outside the program's image and the task's stack");
  cmd->add_flag("-g", a.debug, "Emit debug information");
  cmd->add_option("--color", a.color, "Colour diagnostics")->check(CLI::IsMember({"auto", "always", "never"}));
  cmd->add_flag("-w,--no-warnings", a.noWarnings, "Suppress all warnings");
  cmd->add_flag("--testlib", a.testlib, "Compile in the controller's test natives (TEST_Sleep, TEST_Counter, ...)")->group("");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stc - IEC 61131-3 Structured Text compiler and virtual controller"};
  app.set_version_flag("--version", std::string("stc ") + STC_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success, 1 errors in the input (test: a failed scenario), 2 bad command line (run: also a retain file\n"
      "that is not one stc can use), 3 a runtime fault (run), 4 the retain file could not be saved (run).");

  CheckArgs ca;
  CLI::App* check = app.add_subcommand("check", "Parse and analyse ST sources or project directories");
  check->add_option("paths", ca.paths, "Files (.st, .exp, PLCopen .xml, TwinCAT .TcPOU/.plcproj ...) or project directories")->required();
  check->add_option("--dialect", ca.dialect, "Language dialect (default: the project's, else codesys)")->check(CLI::IsMember({"iec", "codesys"}));
  check->add_option("--address-model", ca.addressModel, "Pointer size in bits, 32 or 64 (default: the project's, else 32)")->check(CLI::IsMember({32u, 64u}));
  check->add_option("-D,--define", ca.defines, "Define NAME for {IF defined(NAME)} pragmas")->allow_extra_args(false);
  check->add_option("--lib", ca.libs, "Compile in an optional library (e.g. codesys_sm3)")->check(CLI::IsMember(availableLibraries()))->allow_extra_args(false);
  check->add_option("--format", ca.format, "Diagnostic format")->check(CLI::IsMember({"text", "json"}));
  check->add_option("--color", ca.color, "Colour diagnostics")->check(CLI::IsMember({"auto", "always", "never"}));
  check->add_flag("--verify", ca.verify, "Check diagnostics against expected-error/warning/note comments in each file");
  check->add_flag("--Werror", ca.werror, "Treat warnings as errors");
  check->add_flag("-w,--no-warnings", ca.noWarnings, "Suppress all warnings");
  check->add_option("--Wno", ca.noWarn, "Disable one warning by name (e.g. --Wno unused-variable)");
  check->add_option("--error-limit", ca.errorLimit, "Stop after N errors (0: no limit)");
  check->add_flag("--stats", ca.stats, "Print sizes and front-end timing");
  check->add_option("-j,--jobs", ca.jobs, "Parse with N threads (default: one per core)");

  BuildArgs ba;
  CLI::App* build = app.add_subcommand("build", "Compile to LLVM IR or an object file");
  addCompileOptions(build, ba);
  build->add_option("-o,--output", ba.output, "Output file (default: <project or file name>.o|.ll; '-' = stdout for IR)");
  build->add_option("--emit", ba.emit, "What to write")->check(CLI::IsMember({"llvm", "obj"}));

  BuildArgs ra;
  CLI::App* run = app.add_subcommand("run", "Run on the simulated controller and print watched variables");
  addCompileOptions(run, ra);
  // A count is digits only, at most 10^12 (CLI11 would wrap "-5" into a huge unsigned number).
  auto* cyc = run->add_option("--cycles", ra.cycles, "Run N cycles of the fastest task (0 .. 10^12); without --cycles and --for: one cycle")
                  ->check([](const std::string& t) -> std::string {
                    if (t.empty() || t.size() > 13 || t.find_first_not_of("0123456789") != std::string::npos || std::stoull(t) > 1'000'000'000'000ull)
                      return "'" + t.substr(0, 40) + "' is not a number of cycles from 0 to 10^12";
                    return "";
                  });
  run->add_option("--for", ra.forDuration, "Run for a simulated duration (10s, 250ms, T#1s500ms); without --for and --cycles: one cycle")->excludes(cyc);
  run->add_option("--interval", ra.interval, "Cycle time of the implicit task (default 1ms)");
  run->add_option("--program", ra.programs, "PROGRAM(s) the implicit task runs (without a CONFIGURATION)")->allow_extra_args(false);
  run->add_option("--watch", ra.watches, "Print VAR after the run (MAIN.fb.Q, GVL.x, arr[3])")->allow_extra_args(false);
  run->add_option("--trace", ra.traces, "Record VAR,... at every tick")->allow_extra_args(false);
  run->add_option("--trace-out", ra.traceOut, "Trace file: .csv or .vcd");
  auto* plotOpt = run->add_option("--plot", ra.plotOut, "Also draw the --trace variables into an SVG file (see stc plot)");
  run->add_option("--xy", ra.plotXy, "With --plot: draw the path of Y over X instead (see stc plot --xy); repeat for more paths")
      ->type_name("X,Y")
      ->allow_extra_args(false)
      ->needs(plotOpt);
  run->add_flag("--realtime", ra.realtime, "Pace the simulated clock to the wall clock");
  run->add_flag("--stats", ra.stats, "Print per-task statistics");
  run->add_option("--watchdog", ra.watchdog, "Per-task watchdog (simulated time; 0 = off; default 1s)");
  run->add_option("--slice", ra.slice, "Loop back-edges a task may run per slot before it yields")
      ->check(CLI::Range(int64_t(1), int64_t(1'000'000'000'000'000)));
  run->add_option("--retain", ra.retain, "Keep RETAIN/PERSISTENT variables in FILE across runs");
  run->add_option("--retain-every", ra.retainEvery, "Also save the retain file every DUR of simulated time");
  run->add_option("--watch-every", ra.watchEvery, "Also print the watches every DUR of simulated time (with --realtime: live)");
  run->add_flag("--cold", ra.cold, "Cold start: restore only PERSISTENT variables");
  run->add_flag("--retain-reset", ra.retainReset,
                "Start from the initial values and replace the --retain FILE even if it is damaged or of a newer format "
                "(a file that is not a retain file is never replaced)");
  run->add_option("--data-dir", ra.dataDir,
                  "Directory the program's files live in (SMC_ReadCAM, SMC_WriteCAM, diagnostic logs; default: the "
                  "project's data_dir, else the first file's directory)");

  ExportArgs ea;
  CLI::App* exp = app.add_subcommand("export", "Write the checked program as PLCopen XML (CODESYS, Beremiz, TwinCAT import it)");
  exp->add_option("paths", ea.paths, "Files (.st, .exp, .xml, .TcPOU ...) or project directories")->required();
  exp->add_option("--plcopen", ea.plcopen, "Output file: PLCopen TC6 XML v2.01 ('-' = stdout)")->required();
  exp->add_option("--dialect", ea.dialect, "Language dialect (default: the project's, else codesys)")->check(CLI::IsMember({"iec", "codesys"}));
  exp->add_option("-D,--define", ea.defines, "Define NAME for {IF defined(NAME)} pragmas")->allow_extra_args(false);
  exp->add_option("--lib", ea.libs, "Compile in an optional library (e.g. codesys_sm3)")->check(CLI::IsMember(availableLibraries()))->allow_extra_args(false);
  exp->add_option("--color", ea.color, "Colour diagnostics")->check(CLI::IsMember({"auto", "always", "never"}));
  exp->add_flag("-w,--no-warnings", ea.noWarnings, "Suppress all warnings");

  tools::TestArgs ta;
  CLI::App* test = app.add_subcommand("test", "Run the scenarios of projects and compare them with their golden traces");
  test->add_option("paths", ta.paths, "Project directories (default: .)");
  test->add_flag("--update", ta.update, "Write the golden files expected/<scenario>.csv from this run (not of a failing scenario)");
  test->add_flag("--force", ta.force, "With --update: also write the golden files of scenarios whose checks fail or that fault");
  test->add_option("--scenario", ta.scenarios, "Run only the scenario NAME (scenarios/NAME.toml; repeatable)")->allow_extra_args(false);
  test->add_option("--actual", ta.actual, "Write each scenario's actual trace to DIR/<scenario>.csv (created; never a golden file)");
  test->add_option("-j,--jobs", ta.jobs, "Run N projects in parallel (default: one per core)");
  test->add_option("--one", ta.one, "Run one project in this process (used by the parallel runner)")->group("");
  plot::PlotCommand pc;
  pc.add(app);
  tools::InitArgs ia;
  CLI::App* init = app.add_subcommand("init", "Make a new project that stc test passes at once (project.toml, GVL, PROGRAM, task, scenario)");
  init->add_option("name", ia.path, "The new project's directory (must not exist, or be empty)")->required();
  init->add_option("--lib", ia.lib, "The instruction set (default codesys_sm3)")->check(CLI::IsMember(availableLibraries()));
  init->add_option("--axes", ia.axes, "Simulated servo axes Axis1..AxisN (0 .. 16, default 1)")->check(CLI::Range(0u, tools::kMaxInitAxes));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  if (check->parsed()) return runCheck(ca);
  if (build->parsed()) return runBuild(ba);
  if (exp->parsed()) return runExport(ea);
  if (pc.cmd->parsed()) return pc.run();
  ra.cyclesGiven = cyc->count() > 0;
  for (const char* o : {"--for", "--interval", "--watchdog", "--retain-every", "--watch-every"})
    if (run->get_option(o)->count() > 0) ra.given.insert(o);
  if (run->parsed()) return runRun(ra);
  if (test->parsed()) return tools::runTest(ta);
  if (init->parsed()) return tools::runInit(ia);
  return 2;
}
