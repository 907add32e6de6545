// `stc init NAME [--lib L] [--axes N]`: a new project that `stc test` passes at once
// (docs/projects.md, "Starting a project").
#pragma once

#include <string>

namespace stc::tools {

struct InitArgs {
  std::string path;          // the new project's directory (created; must not exist or be empty)
  std::string lib = "codesys_sm3";
  unsigned axes = 1;         // 0 .. kMaxInitAxes
};

inline constexpr unsigned kMaxInitAxes = 16;

// Returns the exit status: 0 done, 1 the files or the first test run failed, 2 bad arguments.
int runInit(const InitArgs& args);

}  // namespace stc::tools
