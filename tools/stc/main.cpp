// stc: the command-line entry point.  Subcommands map onto the driver; the
// command contract is ../shared/DESIGN.md ("The stc command").
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <iostream>

#include "basic/Text.h"
#include "driver/Driver.h"

using namespace stc;

namespace {

struct CheckArgs {
  std::vector<std::string> paths;
  std::string dialect;
  std::vector<std::string> defines;
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
  o.parseThreads = a.jobs;
  for (const std::string& d : a.defines) o.defines.insert(asciiLower(d));
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

int runCheck(const CheckArgs& a) {
  if (a.verify) return runVerify(a);
  Compilation c;
  applyDiagOptions(a, c.diags());
  bool inputsOk = true;
  for (const std::string& p : a.paths) inputsOk = c.addPath(p) && inputsOk;
  bool ok = false;
  if (inputsOk) runWithLargeStack([&] { ok = c.check(compileOptions(a)); });
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
  return (ok && inputsOk && !c.diags().hasErrors()) ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stc - IEC 61131-3 Structured Text compiler and virtual controller"};
  app.set_version_flag("--version", std::string("stc ") + STC_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Commands not listed here (build, run, test) are not implemented yet; see docs/status.md.\n"
      "Exit status: 0 success, 1 errors in the input, 2 bad command line.");

  CheckArgs ca;
  CLI::App* check = app.add_subcommand("check", "Parse and analyse ST sources or project directories");
  check->add_option("paths", ca.paths, "Files (.st, .exp) or project directories")->required();
  check->add_option("--dialect", ca.dialect, "Language dialect (default: the project's, else iec)")->check(CLI::IsMember({"iec", "codesys"}));
  check->add_option("-D,--define", ca.defines, "Define NAME for {IF defined(NAME)} pragmas");
  check->add_option("--format", ca.format, "Diagnostic format")->check(CLI::IsMember({"text", "json"}));
  check->add_option("--color", ca.color, "Colour diagnostics")->check(CLI::IsMember({"auto", "always", "never"}));
  check->add_flag("--verify", ca.verify, "Check diagnostics against expected-error/warning/note comments in each file");
  check->add_flag("--Werror", ca.werror, "Treat warnings as errors");
  check->add_flag("-w,--no-warnings", ca.noWarnings, "Suppress all warnings");
  check->add_option("--Wno", ca.noWarn, "Disable one warning by name (e.g. --Wno unused-variable)");
  check->add_option("--error-limit", ca.errorLimit, "Stop after N errors (0: no limit)");
  check->add_flag("--stats", ca.stats, "Print sizes and front-end timing");
  check->add_option("-j,--jobs", ca.jobs, "Parse with N threads (default: one per core)");

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
  return 2;
}
