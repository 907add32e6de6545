// `stc test`: runs the scenarios of projects (scenarios/*.toml) on the
// simulated controller, evaluates their checks and compares their traces
// with the golden files (expected/<scenario>.csv).  See docs/projects.md.
#pragma once

#include <string>
#include <vector>

namespace stc::tools {

struct TestArgs {
  std::vector<std::string> paths;   // project directories (default ".")
  bool update = false;              // write the golden files
  unsigned jobs = 0;                // parallel projects (0: one per core)
  std::string one;                  // internal: run this one project in this process
};

// Returns the exit status: 0 all passed, 1 something failed, 2 a bad
// command line (a path that is not a project directory).
int runTest(const TestArgs& args);

}  // namespace stc::tools
