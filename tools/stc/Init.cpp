// `stc init`: writes project.toml (the common keys, the optional ones commented), src/GVL.st
// with the axes, a PROGRAM that powers them and moves the first on a start signal, one task,
// one scenario with checks; then runs `stc test --update` once so the golden trace exists.
#include "tools/stc/Init.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "tools/stc/TestCommand.h"

namespace fs = std::filesystem;

namespace stc::tools {

namespace {

bool writeFile(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) std::cerr << "stc: error: cannot write " << p.string() << "\n";
  return static_cast<bool>(out);
}

std::string projectToml(const std::string& name, const InitArgs& a) {
  std::string t = fmt::format(R"(# {0}: made by `stc init` (docs/projects.md).  Keys after a '#' are optional:
# remove the '#' to use them.  stc check validates this file; stc test runs scenarios/*.toml.
[project]
name = "{0}"
description = "a new stc project"
libraries = ["{1}"]                 # instruction sets: codesys_sm3, leadshine (also brings codesys_sm3)
# data_dir = "data"                 # files the program opens (SMC_ReadNCFile, FILE.*, SMC_ReadCAM)

# [build]
# dialect = "codesys"               # or "iec" (strict IEC 61131-3)

[[task]]
name = "Main"
interval = "1ms"                    # the cycle; also: event = "GVL.bTrigger" (instead of interval)
programs = ["Main"]
# priority = 1                      # 0 .. 31, lower runs first
)",
                              name, a.lib);
  for (unsigned i = 1; i <= a.axes; ++i)
    t += fmt::format(R"(
[[axis]]
name = "Axis{0}"                     # the AXIS_REF_SM3 variable of src/GVL.st
type = "servo"                      # servo | virtual | encoder | pulse
task = "Main"                       # the task whose programs command it
# unit = "mm"                      # the positions' unit, shown by stc plot (default "u")
max_velocity = 1000.0               # u/s (u: the unit of the positions, e.g. mm)
max_acceleration = 10000.0          # u/s^2
max_deceleration = 10000.0
# increments_per_unit = 1000        # drive increments per u
# sw_limit_negative = -10.0         # software limits (u)
# sw_limit_positive = 1010.0
# drive = "lag"                     # ideal (default) | lag: a position loop with kv and lag_time
# Drive inputs (docs/projects.md, "Drive inputs and homing"): sensors on the mechanics, in u.
# home_switch = [-0.5, 0.5]         # TRUE between these positions (MC_Home CiA402 methods 3-14, 17-30)
# limit_switch_negative = -20.0     # TRUE at or below (methods 1, 2, 17, 18 and the reversals)
# limit_switch_positive = 1020.0
# index_period = 10.0               # an index (zero) mark every 10 u (methods 1-14, 33, 34)
)",
                     i);
  return t;
}

std::string gvl(const InitArgs& a) {
  std::string t = "VAR_GLOBAL\n";
  for (unsigned i = 1; i <= a.axes; ++i) t += fmt::format("  Axis{0} : AXIS_REF_SM3;   (* [[axis]] Axis{0} of project.toml *)\n", i);
  t += "  bStart : BOOL;            (* the start signal: set by scenarios/smoke.toml *)\n";
  return t + "END_VAR\n";
}

std::string mainProgram(const InitArgs& a) {
  if (a.axes == 0)
    return R"(PROGRAM Main
VAR
  count : DINT;   (* counts the cycles after the start signal *)
END_VAR
IF GVL.bStart THEN
  count := count + 1;
END_IF
END_PROGRAM
)";
  std::string vars, body;
  for (unsigned i = 1; i <= a.axes; ++i) {
    vars += fmt::format("  power{0} : MC_Power;\n", i);
    body += fmt::format("power{0}(Axis := GVL.Axis{0}, Enable := TRUE, bRegulatorOn := TRUE, bDriveStart := TRUE);\n", i);
  }
  return "PROGRAM Main\nVAR\n" + vars +
         "  move : MC_MoveAbsolute;   (* Axis1 to 100 u at 100 u/s once started *)\nEND_VAR\n" + body +
         "move(Axis := GVL.Axis1, Execute := GVL.bStart AND power1.Status, Position := 100, Velocity := 100,\n"
         "     Acceleration := 1000, Deceleration := 1000);\nEND_PROGRAM\n";
}

std::string scenario(const InitArgs& a) {
  if (a.axes == 0)
    return R"(description = "the start signal at 100 ms: Main counts from the next cycle"
duration = "200ms"
trace = ["GVL.bStart", "Main.count"]

[[set]]
at = "100ms"
var = "GVL.bStart"
value = "TRUE"

[[check]]
at = "99ms"
var = "Main.count"
equals = "0"

[[check]]
at = "199ms"
var = "Main.count"
equals = "100"
)";
  return R"(description = "start at 100 ms: Axis1 moves 100 u at 100 u/s (0.1 s ramps) and reports Done"
duration = "1.5s"
sample = "10ms"                     # golden rows every 10 ms (the checks see every cycle)
trace = ["GVL.bStart", "GVL.Axis1.fSetPosition", "GVL.Axis1.fSetVelocity", "Main.move.Done"]

[[set]]
at = "100ms"
var = "GVL.bStart"
value = "TRUE"

# The move takes 0.1 + 0.9 + 0.1 = 1.1 s from its start: Done by about 1.2 s.
[[check]]
at = "700ms"
var = "GVL.Axis1.fSetVelocity"
equals = "100.0"

[[check]]
var = "Main.move.Done"
rises_between = ["1.1s", "1.3s"]

[[check]]
at = "1.4s"
var = "GVL.Axis1.fSetPosition"
equals = "100.0"
)";
}

}  // namespace

int runInit(const InitArgs& a) {
  if (a.axes > kMaxInitAxes) {
    std::cerr << "stc: error: --axes " << a.axes << ": at most " << kMaxInitAxes << "\n";
    return 2;
  }
  const fs::path dir(a.path);
  std::string name = (dir.filename().empty() ? dir.parent_path() : dir).filename().string();
  const bool nameOk = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (!nameOk) {
    std::cerr << "stc: error: '" << a.path << "': a project name is letters, digits, '_' and '-'\n";
    return 2;
  }
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir, ec)) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec))) {
    std::cerr << "stc: error: '" << a.path << "' exists and is not an empty directory: stc init never overwrites\n";
    return 2;
  }
  for (const char* sub : {"src", "scenarios", "expected"}) fs::create_directories(dir / sub, ec);
  if (ec) {
    std::cerr << "stc: error: cannot create '" << a.path << "': " << ec.message() << "\n";
    return 1;
  }
  if (!writeFile(dir / "project.toml", projectToml(name, a)) || !writeFile(dir / "src" / "GVL.st", gvl(a)) ||
      !writeFile(dir / "src" / "Main.st", mainProgram(a)) || !writeFile(dir / "scenarios" / "smoke.toml", scenario(a)))
    return 1;
  std::cout << "stc: created " << dir.string() << " (project.toml, src/GVL.st, src/Main.st, scenarios/smoke.toml)\n";
  // The golden trace of the scenario: written only if its checks pass.
  TestArgs t;
  t.paths = {dir.string()};
  t.update = true;
  t.jobs = 1;
  const int rc = runTest(t);
  if (rc == 0)
    std::cout << "next: cd " << dir.string() << " && stc test   (docs/projects.md)\n";
  return rc == 0 ? 0 : 1;
}

}  // namespace stc::tools
