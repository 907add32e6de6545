// [[cnc_program]] tables of project.toml: G-code programs compiled into the project
// (docs/cnc.md, "Programs in the project").  The schema (compiler/config/ConfigSchema.cpp)
// has checked the keys, types and ranges; here the files are read.
#include "stdlib-motion/MotionNatives.h"
#include "stdlib-motion/ProjectToml.h"
#include "vm/FileSandbox.h"

namespace stc::motion {

bool loadProjectCncPrograms(const std::string& dir, std::vector<CncProgramConfig>& out, std::string& error) {
  std::string file;
  toml::table tbl;
  const toml::array* arr = projectTables(dir, "cnc_program", tbl, file);
  if (!arr) return true;
  // The controller holds every program for the run: their sum is bounded like one file.
  constexpr uint64_t kMaxHeldBytes = 256ull << 20;
  uint64_t held = 0;
  for (const toml::node& n : *arr) {
    const toml::table* t = n.as_table();
    const std::string here = tomlWhere(file, n);
    auto var = t ? (*t)["var"].value<std::string>() : std::nullopt;
    auto name = t ? (*t)["file"].value<std::string>() : std::nullopt;
    if (!var || !name) return error = here + "a [[cnc_program]] needs var = \"NAME\" (an SMC_CNC_REF) and file = \"nc/part.cnc\"", false;
    // Project files: relative to the project directory, never leaving it (vm/FileSandbox.h).
    std::string why;
    const int fd = vm::openInside(dir, *name, vm::FileAccess::Read, why);
    if (fd < 0) return error = here + "cnc_program file '" + *name + "': " + why, false;
    auto text = std::make_shared<std::string>();
    switch (vm::readAndClose(fd, 64ull << 20, *text)) {
    case vm::ReadResult::Ok: break;
    case vm::ReadResult::Failed: return error = here + "cannot read cnc_program file '" + *name + "'", false;
    case vm::ReadResult::TooBig: return error = here + "cnc_program file '" + *name + "' is larger than 64 MiB", false;
    }
    held += text->size();
    if (held > kMaxHeldBytes) return error = here + "the [[cnc_program]] files are larger than 256 MiB together", false;
    CncProgramConfig c;
    c.var = *var;
    c.name = *name;
    c.text = std::move(text);
    c.defaultVel = (*t)["default_vel"].value_or(0.0);
    c.defaultAccel = (*t)["default_accel"].value_or(0.0);
    c.defaultDecel = (*t)["default_decel"].value_or(0.0);
    c.defaultVelFF = (*t)["default_vel_ff"].value_or(0.0);
    c.defaultAccelFF = (*t)["default_accel_ff"].value_or(0.0);
    c.defaultDecelFF = (*t)["default_decel_ff"].value_or(0.0);
    out.push_back(std::move(c));
  }
  return true;
}

}  // namespace stc::motion
