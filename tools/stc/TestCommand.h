// `stc test`: runs the scenarios of projects (scenarios/*.toml) on the
// simulated controller, evaluates their checks and compares their traces
// with the golden files (expected/<scenario>.csv).  See docs/projects.md.
#pragma once

#include <string>
#include <vector>

namespace stc::tools {

struct TestArgs {
  std::vector<std::string> paths;      // project directories (default ".")
  bool update = false;                 // write the golden files
  bool force = false;                  // --update also of scenarios that fail their checks or fault
  unsigned jobs = 0;                   // parallel projects (0: one per core)
  std::vector<std::string> scenarios;  // run only these (exact names, scenarios/<name>.toml)
  std::string actual;                  // write each scenario's actual trace into this directory
  std::string one;                     // internal: run this one project in this process
};

// Returns the exit status: 0 all passed, 1 something failed, 2 a bad
// command line (a path that is not a project directory, an unknown --scenario,
// an --actual directory that is a project's expected/ or cannot be created,
// --force without --update).
int runTest(const TestArgs& args);

}  // namespace stc::tools
