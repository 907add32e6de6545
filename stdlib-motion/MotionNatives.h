// The controller side of the motion library: registers the kernel's cycle
// hook and start hook and the vendor faces' natives; holds the axes that
// project.toml configures.  See docs/motion.md.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "stdlib-motion/core/Kernel.h"

namespace stc::motion {

// Registers everything (idempotent).  Called by the controller at load.
void registerMotionNatives();

// The axes of the project being run ([[axis]] tables of project.toml).
void setProjectAxes(std::vector<AxisConfig> axes);
// Reads the [[axis]] tables of `dir`/project.toml.  False with `error`
// (file:line:col: message) on a bad table; no file or no table is fine.
bool loadProjectAxes(const std::string& dir, std::vector<AxisConfig>& out, std::string& error);

// The vendor profile of the run (docs/motion.md, "Vendor profiles").  From project.toml:
// [project] motion_profile = "amc1600c" | "leadshine_pmc600"; without it, leadshine_pmc600
// when the project uses the leadshine library, else amc1600c.  `libraries` are those of the
// command line (added to the project's).
bool loadProjectVendorProfile(const std::string& dir, const std::vector<std::string>& libraries, VendorProfile& out,
                              std::string& error);
VendorProfile defaultVendorProfile(const std::vector<std::string>& libraries);
void setVendorProfile(const VendorProfile& p);

// Simulated I/O devices ([[io]] tables of project.toml, docs/projects.md).
struct IoDevice {
  enum class Kind : uint8_t { AxisWindow, Delay };
  Kind kind = Kind::AxisWindow;
  std::string var;                 // the BOOL variable the device writes
  std::string axis;                // AxisWindow: TRUE while the axis's actual position is in [low, high]
  double low = 0, high = 0;
  std::string source;              // Delay: var follows this BOOL variable `delayNs` later
  int64_t delayNs = 0;
};
bool loadProjectIo(const std::string& dir, std::vector<IoDevice>& out, std::string& error);
void setProjectIo(std::vector<IoDevice> devices);
void registerProjectIo();

// Fault kinds by their project.toml / scenario names (drive_error ...); false when unknown.
bool faultKindNamed(std::string_view name, FaultKind& out);
// "drive_error, communication_lost, ... or limits_released", for messages.
const char* faultKindNames();

// The task, cycle and time of the FB call in progress.
CallCtx callContext();

// For the faces: mirror an axis into its ST variable after each step; bind a
// configured axis to the ST variable of the given type; forget bindings at a new run.
void addAxisMirror(std::function<void(Axis&)> fn);
void addAxisBinder(std::string typeName, std::function<void(void* ref, Axis& ax)> fn);
void addResetHook(std::function<void()> fn);

void registerSm3Natives();

}  // namespace stc::motion
