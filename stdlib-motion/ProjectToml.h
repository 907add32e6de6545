// Reading tables of a project's project.toml for the simulation (axes, I/O).
// Internal to stdlib-motion (toml++ stays out of the public headers).
#pragma once

#include <string>
#include <toml++/toml.h>

namespace stc::motion {

// The [[name]] tables of dir/project.toml, parsed into `holder`; null when there are none or
// the file does not parse (the compiler's project loader reports that).  `file` gets the path.
inline const toml::array* projectTables(const std::string& dir, const char* name, toml::table& holder, std::string& file) {
  file = dir + "/project.toml";
  try {
    holder = toml::parse_file(file);
  } catch (const toml::parse_error&) {
    return nullptr;
  }
  return holder[name].as_array();
}

// "file:line:col: " of a node, for messages.
inline std::string tomlWhere(const std::string& file, const toml::node& n) {
  return file + ":" + std::to_string(n.source().begin.line) + ":" + std::to_string(n.source().begin.column) + ": ";
}

}  // namespace stc::motion
