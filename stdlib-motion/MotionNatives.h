// The controller side of the motion library: the native library that the
// stc tool hands to the controller (the vendor faces' natives, the
// project.toml tables it reads) and the per-controller session (the kernel,
// the axes bound to their ST variables, the simulated devices).  See docs/motion.md.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "stdlib-motion/core/Commands.h"
#include "stdlib-motion/core/Coupling.h"
#include "stdlib-motion/core/Kernel.h"
#include "vm/Native.h"

namespace stc::motion {

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

// A cam table defined in project.toml ([[cam]], docs/motion-cam.md), put into
// the cam variable `var` at start.
struct CamConfig {
  std::string var;
  std::shared_ptr<const Cam> cam;
};

// A G-code program compiled into the project ([[cnc_program]], docs/cnc.md, "Programs in
// the project"): its text is held by the controller and an SMC_CNC_REF points to it.
struct CncProgramConfig {
  std::string var;                              // the SMC_CNC_REF variable
  std::string name;                             // the file as written (diagnostics)
  std::shared_ptr<const std::string> text;
  double defaultVel = 0, defaultAccel = 0, defaultDecel = 0;
  double defaultVelFF = 0, defaultAccelFF = 0, defaultDecelFF = 0;
};

// An axis group configured in project.toml ([[group]], docs/motion-groups.md): its
// AXIS_GROUP_REF_SM3 variable and its member axes' variables, in order.
struct GroupConfig {
  std::string name;
  std::vector<std::string> axes;
  std::string where;               // "project.toml:line:col: " of the table
};

// How a face binds a configured group to its group variable (e.g. AXIS_GROUP_REF_SM3).
struct GroupFace {
  std::string typeName;
  void (*bound)(void* var, uint32_t groupIndex) = nullptr;
};

// What a run's motion needs from project.toml and the command line.
struct MotionConfig {
  std::vector<AxisConfig> axes;    // [[axis]]
  std::vector<std::string> axisUnits;   // [[axis]] unit, by index of `axes` ("" when not given)
  std::vector<GroupConfig> groups; // [[group]]
  std::vector<IoDevice> io;        // [[io]]
  std::vector<CamConfig> cams;     // [[cam]]
  std::vector<CncProgramConfig> cncPrograms;   // [[cnc_program]]
  VendorProfile profile;           // [project] motion_profile, else by the libraries used
  // The data directory: where the files a program opens live (SMC_ReadCAM, SMC_WriteCAM,
  // SMC_AxisDiagnosticLog.WriteToFile; they never leave it, vm/FileSandbox.h).  A project's
  // [project] data_dir (default <project>/data), `stc run --data-dir`, or for loose files
  // the directory of the first one.
  std::string filesDir;
  // "project.toml:line:col: " of the [[axis]] tables, by axis (for the checks at start
  // that need the tasks, e.g. kv against the cycle time).
  std::vector<std::string> axisWhere;
};

// How a face binds a configured axis to an axis variable of its type (e.g.
// AXIS_REF_SM3) and mirrors the kernel's axis into that variable.
struct AxisFace {
  std::string typeName;
  void (*mirror)(const Axis& ax, void* var) = nullptr;
  void (*bound)(void* var, const Axis& ax) = nullptr;   // writes the binding into the variable
};

// How a face fills a cam variable of its type (e.g. MC_CAM_REF) with a cam the
// controller holds under `id`.
struct CamFace {
  std::string typeName;
  void (*bound)(void* var, const Cam& cam, uint64_t id) = nullptr;
};

// How a face fills a program variable of its type (SMC_CNC_REF) with a held program.
struct CncProgramFace {
  std::string typeName;
  void (*bound)(void* var, const CncProgramConfig& program) = nullptr;
};

// The motion library as the controller sees it: the natives of every face
// (codesys_sm3, leadshine) and, per controller, a MotionSession.
class MotionLibrary : public vm::NativeLibrary {
public:
  explicit MotionLibrary(MotionConfig cfg = {});
  std::string_view name() const override { return "motion"; }
  const std::vector<vm::NativeEntry>& natives() const override { return natives_; }
  const void* sessionKey() const override;
  std::unique_ptr<vm::NativeSession> newSession() const override;

  MotionConfig& config() { return cfg_; }
  // Adds the [[axis]] and [[io]] tables and the vendor profile of the project
  // directory `dir` (libraries: those of the command line).  False with
  // `error` (file:line:col: message).
  bool readProject(const std::string& dir, const std::vector<std::string>& libraries, std::string& error);

  // For the faces' registration functions.
  void add(vm::NativeEntry e) { natives_.push_back(std::move(e)); }
  void addAxisFace(AxisFace f) { faces_.push_back(std::move(f)); }
  const std::vector<AxisFace>& axisFaces() const { return faces_; }
  void addCamFace(CamFace f) { camFaces_.push_back(std::move(f)); }
  void addGroupFace(GroupFace f) { groupFaces_.push_back(std::move(f)); }
  const std::vector<GroupFace>& groupFaces() const { return groupFaces_; }
  const std::vector<CamFace>& camFaces() const { return camFaces_; }
  void addCncProgramFace(CncProgramFace f) { cncProgramFaces_.push_back(std::move(f)); }
  const std::vector<CncProgramFace>& cncProgramFaces() const { return cncProgramFaces_; }

private:
  MotionConfig cfg_;
  std::vector<vm::NativeEntry> natives_;
  std::vector<AxisFace> faces_;
  std::vector<CamFace> camFaces_;
  std::vector<CncProgramFace> cncProgramFaces_;
  std::vector<GroupFace> groupFaces_;
};

struct IoRuntime;   // ProjectIo.cpp

// The key of the motion library's sessions (an inline variable: one address program-wide).
inline constexpr char kMotionSessionKey = 0;

// One controller's motion: the kernel, its axes and the ST variables they are bound to.
class MotionSession : public vm::NativeSession {
public:
  MotionSession(const MotionLibrary& lib, const MotionConfig& cfg);
  bool start(const vm::StartCtx& sc, std::string& error) override;
  void cycle(const vm::HookCtx& c) override;
  // Each configured axis with a `unit`: (axis name, unit).
  std::vector<std::pair<std::string, std::string>> units() const override;

  // The session of the controller whose code is running (natives only).
  static MotionSession& current() {
    if (auto* s = static_cast<MotionSession*>(vm::currentSession(key()))) return *s;
    noSession();
  }
  static const void* key() { return &kMotionSessionKey; }

  Kernel kernel;
  CommandTable commands;   // function-style commands (motion_test, Hollysys)
  // The axis variable each kernel axis is bound to, by axis index.
  struct AxisVar {
    void* var = nullptr;
    void (*mirror)(const Axis& ax, void* var) = nullptr;
    // A copy of the axis and its owning task, so the per-call binding check reads
    // this small array instead of the (large) Axis object.
    Axis* axis = nullptr;
    uint32_t task = UINT32_MAX;
  };
  std::vector<AxisVar> axisVars;
  // The axis group variable each kernel group is bound to, by group index.
  std::vector<const void*> groupVars;
  void bindVar(Axis& ax, void* var, void (*mirror)(const Axis&, void*));
  // The axis bound to `var` under the binding `index` when the calling task owns it, else null.
  Axis* boundAxis(uint64_t index, const void* var, uint32_t task) const {
    if (index >= axisVars.size()) return nullptr;
    const AxisVar& v = axisVars[index];
    return v.var == var && v.task == task ? v.axis : nullptr;
  }
  // Whether anyone reads the axis variables' fields (vm::StartCtx::mirroredRead):
  // without a reader they are bound but not refreshed (docs/motion.md, "Mirrors").
  bool mirrorsRead = true;
  void mirror(const Axis& ax) {
    if (!mirrorsRead) return;
    if (ax.index() < axisVars.size() && axisVars[ax.index()].mirror) axisVars[ax.index()].mirror(ax, axisVars[ax.index()].var);
  }

  // Cams the controller holds (project.toml, SMC_ReadCAM) and the selections of
  // MC_CamTableSelect, by id (ids are never reused, so a stale id finds nothing).
  struct CamStore {
    std::unordered_map<uint64_t, std::shared_ptr<const Cam>> held;
    std::unordered_map<uint64_t, CamSelection> selections;
    std::unordered_map<const void*, int> registerUsers;   // enabled SMC_CamRegister per cam variable
    uint64_t nextId = 1;
  } cams;
  // Cam data that ST points to must lie in the controller's static memory (never a stack frame).
  bool inImage(const void* p, uint64_t bytes) const {
    const auto* b = static_cast<const uint8_t*>(p);
    return b && b >= imageBegin_ && b <= imageEnd_ && bytes <= static_cast<uint64_t>(imageEnd_ - b);
  }
  const std::string& filesDir() const { return cfg_.filesDir; }
  // Whether [p, p + bytes) lies in the text of a program the controller holds ([[cnc_program]]).
  bool inHeldProgram(const void* p, uint64_t bytes) const {
    const auto* b = static_cast<const char*>(p);
    for (const CncProgramConfig& c : cfg_.cncPrograms) {
      const char* t = c.text->data();
      if (b >= t && b <= t + c.text->size() && bytes <= static_cast<uint64_t>(t + c.text->size() - b)) return true;
    }
    return false;
  }
  // A variable of the program by name (`x`, `GVL.x`, `arr[2]`, `MAIN.fb.q`), for G-code
  // $name$ while the run goes (vm::StartCtx::lookupVariable).  False with `error` if none.
  bool findVariable(const std::string& path, vm::StartCtx::Variable& out, std::string& error) const {
    if (!lookupVariable_) {
      error = "no program variables in this controller";
      return false;
    }
    return lookupVariable_(path, out, error);
  }

  // FILE.* (CAA File, codesys_sm3/Sm3File.cpp): the files the program has open; a handle
  // is slot + 1 with the slot's generation above, so a stale handle finds nothing.
  struct OpenFile {
    int fd = -1;
    uint32_t generation = 0;
    bool read = false, write = false, exclusive = false;
    std::string path;   // resolved, for xExclusive
  };
  std::vector<OpenFile> files;

  // Per-instance C++ state of face blocks that need more than their ST variables (the
  // G-code decoder of SMC_NCDecoder): by an id the instance keeps in an internal ULINT.
  // Each state records the instance it belongs to, so a copied or stale id finds nothing.
  struct InstanceState {
    virtual ~InstanceState() = default;
    const void* owner = nullptr;
  };
  std::unordered_map<uint64_t, std::unique_ptr<InstanceState>> instanceStates;
  uint64_t nextInstanceState = 1;
  // The state of `owner` under `id` if it is of type T, else null.
  template <class T>
  T* instanceState(uint64_t id, const void* owner) {
    auto it = instanceStates.find(id);
    if (it == instanceStates.end() || it->second->owner != owner) return nullptr;
    return dynamic_cast<T*>(it->second.get());
  }
  ~MotionSession() override;

private:
  [[noreturn]] static void noSession();
  const MotionLibrary& lib_;
  MotionConfig cfg_;
  std::shared_ptr<IoRuntime> io_;
  const uint8_t* imageBegin_ = nullptr;
  const uint8_t* imageEnd_ = nullptr;
  std::function<bool(const std::string&, vm::StartCtx::Variable&, std::string&)> lookupVariable_;
};

// The kernel of the calling controller.
inline Kernel& kernel() { return MotionSession::current().kernel; }

// The axes of the project ([[axis]] tables of `dir`/project.toml).  False with
// `error` (file:line:col: message) on a bad table; no file or no table is fine.
// `where` (optional) gets "file:line:col: " of each axis's kv (else of its table), in order;
// `units` (optional) each axis's `unit` ("" when not given), in order.
bool loadProjectAxes(const std::string& dir, std::vector<AxisConfig>& out, std::string& error, std::vector<std::string>* where = nullptr,
                     std::vector<std::string>* units = nullptr);

// The vendor profile of the run (docs/motion.md, "Vendor profiles").  From project.toml:
// [project] motion_profile = "amc1600c" | "leadshine_pmc600"; without it, leadshine_pmc600
// when the project uses the leadshine library, else amc1600c.  `libraries` are those of the
// command line (added to the project's).
bool loadProjectVendorProfile(const std::string& dir, const std::vector<std::string>& libraries, VendorProfile& out,
                              std::string& error);
VendorProfile defaultVendorProfile(const std::vector<std::string>& libraries);

// [project] data_dir of dir/project.toml (relative to dir; default dir/data).
bool loadProjectDataDir(const std::string& dir, std::string& out, std::string& error);
bool loadProjectIo(const std::string& dir, std::vector<IoDevice>& out, std::string& error);
// The [[group]] tables of dir/project.toml.
bool loadProjectGroups(const std::string& dir, std::vector<GroupConfig>& out, std::string& error);
// The [[cam]] tables of dir/project.toml (ProjectCams.cpp).
bool loadProjectCams(const std::string& dir, std::vector<CamConfig>& out, std::string& error);
// The [[cnc_program]] tables (ProjectCnc.cpp): each file read (inside the project, at most 64 MiB).
bool loadProjectCncPrograms(const std::string& dir, std::vector<CncProgramConfig>& out, std::string& error);
// The largest file a program or project.toml may have read (cam files).
inline constexpr uint64_t kMaxProjectFileBytes = 64ull * 1024 * 1024;
// ProjectIo.cpp: binds the devices at start; evaluates them after each task slot.
std::shared_ptr<IoRuntime> startIo(const vm::StartCtx& sc, const std::vector<IoDevice>& devices, Kernel& k, std::string& error);
void cycleIo(IoRuntime& io, int64_t nowNs);

// Fault kinds by their project.toml / scenario names (drive_error ...); false when unknown.
bool faultKindNamed(std::string_view name, FaultKind& out);
// "drive_error, communication_lost, ... or limits_released", for messages.
const char* faultKindNames();

// The task, cycle and time of the FB call in progress.
CallCtx callContext();

// The faces' registration (codesys_sm3/Sm3Natives.cpp and the family files).
void registerSm3Natives(MotionLibrary& lib);
void registerMotionTestNatives(MotionLibrary& lib);   // motion_test/MotionTestFace.cpp

}  // namespace stc::motion
