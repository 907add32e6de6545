// Reading tables of a project's project.toml for the simulation (axes, I/O).
// Internal to stdlib-motion (toml++ stays out of the public headers).
#pragma once

#include <filesystem>
#include <string>
#include <toml++/toml.h>

#include "config/ConfigSchema.h"

namespace stc::motion {

// The [[name]] tables of dir/project.toml, parsed and validated against the schema
// (compiler/config/ConfigSchema.h) into `holder`; null when there are none or the file
// is not valid (checkProjectToml and the compiler's project loader report that).
// `file` gets the path.
inline const toml::array* projectTables(const std::string& dir, const char* name, toml::table& holder, std::string& file) {
  file = dir + "/project.toml";
  std::string error;
  if (!config::loadProjectToml(dir, holder, error)) return nullptr;
  return holder[name].as_array();
}

// Validates dir/project.toml against the schema when there is one (a TwinCAT
// project directory has none): the error as config::loadProjectToml gives it.
inline bool checkProjectToml(const std::string& dir, std::string& error) {
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(dir + "/project.toml", ec))) return true;
  toml::table t;
  return config::loadProjectToml(dir, t, error);
}

// "file:line:col: " of a node, for messages.
inline std::string tomlWhere(const std::string& file, const toml::node& n) {
  return file + ":" + std::to_string(n.source().begin.line) + ":" + std::to_string(n.source().begin.column) + ": ";
}

}  // namespace stc::motion
