#include "stdlib-motion/MotionNatives.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <toml++/toml.h>
#include <unistd.h>

#include "stdlib-motion/ProjectToml.h"

#include "vm/Native.h"
#include "vm/Scheduler.h"
#include "vm/Time.h"

namespace stc::motion {

namespace {
std::string shortNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

MotionLibrary::MotionLibrary(MotionConfig cfg) : cfg_(std::move(cfg)) {
  registerSm3Natives(*this);
  registerMotionTestNatives(*this);
}

const void* MotionLibrary::sessionKey() const { return &kMotionSessionKey; }
std::unique_ptr<vm::NativeSession> MotionLibrary::newSession() const { return std::make_unique<MotionSession>(*this, cfg_); }

bool MotionLibrary::readProject(const std::string& dir, const std::vector<std::string>& libraries, std::string& error) {
  return checkProjectToml(dir, error) && loadProjectDataDir(dir, cfg_.filesDir, error) && loadProjectAxes(dir, cfg_.axes, error, &cfg_.axisWhere, &cfg_.axisUnits) &&
         loadProjectIo(dir, cfg_.io, error) && loadProjectCams(dir, cfg_.cams, error) && loadProjectCncPrograms(dir, cfg_.cncPrograms, error) &&
         loadProjectGroups(dir, cfg_.groups, error) &&
         loadProjectVendorProfile(dir, libraries, cfg_.profile, error);
}

MotionSession::MotionSession(const MotionLibrary& lib, const MotionConfig& cfg) : lib_(lib), cfg_(cfg) {
  kernel.profile = cfg_.profile;
  // Each controller its own copy of the held programs: ST may write through pText.
  for (CncProgramConfig& c : cfg_.cncPrograms) c.text = std::make_shared<const std::string>(*c.text);
}

MotionSession::~MotionSession() {
  for (OpenFile& f : files)   // what the program left open ends with the run
    if (f.fd >= 0) ::close(f.fd);
}

void MotionSession::noSession() {
  throw std::logic_error("a motion native was called outside a controller with the motion library");
}

void MotionSession::bindVar(Axis& ax, void* var, void (*mirrorFn)(const Axis&, void*)) {
  if (axisVars.size() <= ax.index()) axisVars.resize(ax.index() + 1);
  axisVars[ax.index()] = AxisVar{var, mirrorFn, &ax, ax.task};
}

// Binds every configured axis to its AXIS_REF variable and task.
bool MotionSession::start(const vm::StartCtx& sc, std::string& error) {
  Kernel& k = kernel;
  mirrorsRead = sc.mirroredRead;
  imageBegin_ = sc.image;
  imageEnd_ = sc.image + sc.imageSize;
  lookupVariable_ = sc.lookupVariable;
  // The cams of project.toml into their variables.
  for (const CamConfig& cc : cfg_.cams) {
    std::string type;
    void* var = sc.lookup(cc.var, type);
    const auto& cf = lib_.camFaces();
    auto f = std::find_if(cf.begin(), cf.end(), [&](const CamFace& p) { return p.typeName == type; });
    if (!var || f == cf.end()) {
      error = "project.toml: cam '" + cc.var + "' has no cam variable of that name in the program (declare it, e.g. '" + cc.var +
              " : MC_CAM_REF;' in a VAR_GLOBAL)";
      return false;
    }
    const uint64_t id = cams.nextId++;
    cams.held[id] = cc.cam;
    f->bound(var, *cc.cam, id);
  }
  // The programs of project.toml into their SMC_CNC_REF variables.
  for (const CncProgramConfig& pc : cfg_.cncPrograms) {
    std::string type;
    void* var = sc.lookup(pc.var, type);
    const auto& pf = lib_.cncProgramFaces();
    auto f = std::find_if(pf.begin(), pf.end(), [&](const CncProgramFace& p) { return p.typeName == type; });
    if (!var) {
      error = "project.toml: cnc_program '" + pc.var + "' has no variable of that name in the program (declare it, e.g. '" + pc.var +
              " : SMC_CNC_REF;' in a VAR_GLOBAL, with the library codesys_sm3 or leadshine)";
      return false;
    }
    if (f == pf.end()) {
      error = "project.toml: cnc_program '" + pc.var + "' is " + (type.empty() ? std::string("not a variable") : "of type " + type) +
              ", not SMC_CNC_REF";
      return false;
    }
    f->bound(var, pc);
  }
  for (const AxisConfig& cfg : cfg_.axes) {
    std::string type;
    void* ref = sc.lookup(cfg.name, type);
    if (!ref) {
      // The place of the [[axis]] table and the lookup's "did you mean".
      const size_t i = static_cast<size_t>(&cfg - cfg_.axes.data());
      std::string why;
      vm::StartCtx::Variable v;
      if (sc.lookupVariable) sc.lookupVariable(cfg.name, v, why);
      const size_t hint = why.find("; did you mean");
      error = (i < cfg_.axisWhere.size() ? cfg_.axisWhere[i] : std::string("project.toml: ")) + "[[axis]] '" + cfg.name +
              "' has no variable of that name in the program" + (hint == std::string::npos ? std::string() : why.substr(hint)) +
              " (declare it, e.g. '" + cfg.name + " : AXIS_REF_SM3;' in a VAR_GLOBAL, or add the library that declares the axis type)";
      return false;
    }
    const auto& faces = lib_.axisFaces();
    auto f = std::find_if(faces.begin(), faces.end(), [&](const AxisFace& p) { return p.typeName == type; });
    if (f == faces.end()) {
      error = "project.toml: axis '" + cfg.name + "' is a " + type + ", not an axis type of a motion library";
      return false;
    }
    Axis& ax = k.addAxis(cfg);
    // The owning task: the one named, else the first (highest-priority) task.
    uint32_t task = UINT32_MAX;
    for (uint32_t i = 0; i < sc.scheduler.taskCount(); ++i) {
      const std::string& n = sc.scheduler.task(i).name;
      bool same = n.size() == cfg.task.size() && std::equal(n.begin(), n.end(), cfg.task.begin(), [](char a, char c) { return std::tolower(a) == std::tolower(c); });
      if (cfg.task.empty() ? (task == UINT32_MAX || sc.scheduler.task(i).priority < sc.scheduler.task(task).priority) : same) task = i;
    }
    if (!cfg.task.empty() && task == UINT32_MAX) {
      error = "project.toml: axis '" + cfg.name + "': there is no task named '" + cfg.task + "'";
      return false;
    }
    ax.task = task;
    // The position loop samples once per cycle: with kv x cycle time >= 1 it overshoots
    // more every cycle and the actual position runs away while the axis is "standing".
    if (task != UINT32_MAX && cfg.drive.model == DriveModel::Lag) {
      const vm::TaskConfig& tc = sc.scheduler.task(task);
      const double cycle = static_cast<double>(tc.kind == vm::TaskKind::Cyclic ? tc.interval : sc.scheduler.baseTick()) * 1e-9;
      if (cycle > 0 && cfg.drive.kv * cycle >= 1) {
        const size_t i = static_cast<size_t>(&cfg - cfg_.axes.data());
        error = (i < cfg_.axisWhere.size() ? cfg_.axisWhere[i] : std::string("project.toml: ")) + "[[axis]] '" + cfg.name +
                "': kv = " + shortNumber(cfg.drive.kv) + " with the " + vm::formatIecTime(static_cast<int64_t>(cycle * 1e9)) +
                " cycle of task '" + tc.name + "' makes the position loop unstable (kv x cycle time must be < 1: kv < " +
                shortNumber(1 / cycle) + ")";
        return false;
      }
    }
    bindVar(ax, ref, f->mirror);
    f->bound(ref, ax);
    mirror(ax);
  }
  // The configured groups: bound to their variables, members added in order, owned by the
  // members' task (all members must share it).
  for (const GroupConfig& gc : cfg_.groups) {
    std::string type;
    void* var = sc.lookup(gc.name, type);
    const auto& gf = lib_.groupFaces();
    auto f = std::find_if(gf.begin(), gf.end(), [&](const GroupFace& p) { return p.typeName == type; });
    if (!var || f == gf.end()) {
      error = gc.where + "[[group]] '" + gc.name + "' has no axis group variable of that name in the program (declare it, e.g. '" +
              gc.name + " : AXIS_GROUP_REF_SM3;' in a VAR_GLOBAL)";
      return false;
    }
    AxisGroup& g = k.addGroup();
    for (const std::string& an : gc.axes) {
      std::string axType;
      void* axVar = sc.lookup(an, axType);
      auto bound = std::find_if(axisVars.begin(), axisVars.end(), [&](const AxisVar& v) { return v.var && v.var == axVar; });
      if (!axVar || bound == axisVars.end()) {
        error = gc.where + "[[group]] '" + gc.name + "': '" + an + "' is not an [[axis]] of project.toml";
        return false;
      }
      if (g.identOf(*bound->axis) >= 0 || g.axes().size() >= kMaxGroupAxes) {
        error = gc.where + "[[group]] '" + gc.name + "': " + (g.identOf(*bound->axis) >= 0 ? "'" + an + "' is listed twice" : "more than 9 axes");
        return false;
      }
      if (g.task != UINT32_MAX && g.task != bound->axis->task) {
        error = gc.where + "[[group]] '" + gc.name + "': its axes belong to different tasks ('" + an + "')";
        return false;
      }
      g.task = bound->axis->task;
      g.addAxis(*bound->axis);
    }
    if (groupVars.size() <= g.index()) groupVars.resize(g.index() + 1);
    groupVars[g.index()] = var;
    f->bound(var, g.index());
  }
  io_ = startIo(sc, cfg_.io, k, error);
  return io_ != nullptr;
}

bool loadProjectGroups(const std::string& dir, std::vector<GroupConfig>& out, std::string& error) {
  toml::table holder;
  std::string file;
  const toml::array* tables = projectTables(dir, "group", holder, file);
  if (!tables) return true;   // none (or an invalid file: the project loader reports it)
  for (const toml::node& n : *tables) {
    const toml::table& t = *n.as_table();
    GroupConfig gc;
    gc.name = *t["name"].value<std::string>();
    gc.where = tomlWhere(file, n);
    for (const toml::node& a : *t["axes"].as_array()) gc.axes.push_back(*a.value<std::string>());
    if (gc.axes.size() > kMaxGroupAxes) {
      error = gc.where + "[[group]] '" + gc.name + "': at most 9 axes";
      return false;
    }
    out.push_back(std::move(gc));
  }
  (void)error;
  return true;
}

std::vector<std::pair<std::string, std::string>> MotionSession::units() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (size_t i = 0; i < cfg_.axes.size() && i < cfg_.axisUnits.size(); ++i)
    if (!cfg_.axisUnits[i].empty()) out.emplace_back(cfg_.axes[i].name, cfg_.axisUnits[i]);
  return out;
}

void MotionSession::cycle(const vm::HookCtx& c) {
  kernel.cycle(c.task, c.now, c.interval, c.cycle);
  if (mirrorsRead)
    for (const AxisVar& v : axisVars)
      if (v.axis && v.task == c.task && v.mirror) v.mirror(*v.axis, v.var);
  // The devices read the axes stepped above; the programs see them in their next cycle.
  cycleIo(*io_, c.now);
}

VendorProfile defaultVendorProfile(const std::vector<std::string>& libraries) {
  VendorProfile p;
  VendorProfile::named(std::find(libraries.begin(), libraries.end(), "leadshine") != libraries.end() ? "leadshine_pmc600" : "amc1600c", p);
  return p;
}

CallCtx callContext() {
  CallCtx c;
  if (auto* s = vm::Scheduler::current(); s && s->currentTask() != UINT32_MAX) {
    c.task = s->currentTask();
    c.cycle = s->currentCycle();
    c.nowNs = s->now();
    const vm::TaskConfig& t = s->task(c.task);
    c.intervalNs = t.kind == vm::TaskKind::Cyclic ? t.interval : s->baseTick();
  }
  return c;
}

// ---------------------------------------------------------------- project.toml

namespace {

std::string where(const std::string& file, const toml::node& n) { return tomlWhere(file, n); }

}  // namespace

namespace {
const std::pair<const char*, FaultKind> kFaultKinds[] = {
    {"drive_error", FaultKind::DriveError}, {"communication_lost", FaultKind::CommunicationLost},
    {"communication_restored", FaultKind::CommunicationRestored}, {"limit_positive", FaultKind::LimitPositive},
    {"limit_negative", FaultKind::LimitNegative}, {"limits_released", FaultKind::LimitsReleased}};
}  // namespace

bool faultKindNamed(std::string_view name, FaultKind& out) {
  for (const auto& [n, k] : kFaultKinds)
    if (name == n) {
      out = k;
      return true;
    }
  return false;
}

const char* faultKindNames() {
  return "drive_error, communication_lost, communication_restored, limit_positive, limit_negative or limits_released";
}

bool loadProjectDataDir(const std::string& dir, std::string& out, std::string& error) {
  std::string file;
  toml::table tbl;
  projectTables(dir, "project", tbl, file);
  out = (std::filesystem::path(dir) / "data").string();
  if (const toml::node* n = tbl["project"]["data_dir"].node()) {
    auto d = n->value<std::string>();
    if (!d || d->empty()) return error = where(file, *n) + "[project] data_dir must be a directory name (e.g. \"data\")", false;
    // Relative to the project directory; an absolute directory is the project author's choice.
    out = std::filesystem::path(*d).is_absolute() ? *d : (std::filesystem::path(dir) / *d).string();
  }
  return true;
}

bool loadProjectVendorProfile(const std::string& dir, const std::vector<std::string>& libraries, VendorProfile& out,
                              std::string& error) {
  std::vector<std::string> libs = libraries;
  std::string file;
  toml::table tbl;
  projectTables(dir, "project", tbl, file);
  if (const toml::array* a = tbl["project"]["libraries"].as_array())
    for (const toml::node& n : *a)
      if (auto s = n.value<std::string>()) libs.push_back(*s);
  out = defaultVendorProfile(libs);
  if (const toml::node* n = tbl["project"]["motion_profile"].node()) {
    auto name = n->value<std::string>();
    if (!name || !VendorProfile::named(*name, out)) {
      error = where(file, *n) + "[project] motion_profile must be \"amc1600c\" or \"leadshine_pmc600\"";
      return false;
    }
  }
  return true;
}

bool loadProjectAxes(const std::string& dir, std::vector<AxisConfig>& out, std::string& error, std::vector<std::string>* whereOut,
                     std::vector<std::string>* unitsOut) {
  std::string file;
  toml::table tbl;
  const toml::array* axes = projectTables(dir, "axis", tbl, file);
  if (!axes) return true;
  for (const toml::node& node : *axes) {
    const toml::table* t = node.as_table();
    if (!t) {
      error = where(file, node) + "[[axis]] must be a table";
      return false;
    }
    AxisConfig c;
    auto num = [&](const char* key, double& v) -> bool {
      const toml::node* n = t->get(key);
      if (!n) return true;
      if (auto d = n->value<double>()) {
        v = *d;
        return true;
      }
      error = where(file, *n) + "axis key '" + key + "' must be a number";
      return false;
    };
    auto str = [&](const char* key, std::string& v) -> bool {
      const toml::node* n = t->get(key);
      if (!n) return true;
      if (auto s = n->value<std::string>()) {
        v = *s;
        return true;
      }
      error = where(file, *n) + "axis key '" + key + "' must be a string";
      return false;
    };
    std::string kind = "virtual", drive = "ideal", ramp = "trapez", unit;
    double swPos = NAN, swNeg = NAN, limPos = NAN, limNeg = NAN, channel = -1;
    if (!str("name", c.name) || !str("task", c.task) || !str("type", kind) || !str("drive", drive) || !str("ramp", ramp) || !str("unit", unit) ||
        !num("period", c.period) || !num("increments_per_unit", c.drive.incrementsPerUnit) || !num("max_velocity", c.maxVelocity) ||
        !num("max_acceleration", c.maxAcceleration) || !num("max_deceleration", c.maxDeceleration) || !num("max_jerk", c.maxJerk) ||
        !num("error_deceleration", c.errorDeceleration) || !num("sw_limit_positive", swPos) || !num("sw_limit_negative", swNeg) ||
        !num("lag_time", c.drive.lagTime) || !num("kv", c.drive.kv) || !num("following_error_limit", c.drive.followingErrorLimit) ||
        !num("inertia", c.drive.inertia) || !num("encoder_velocity", c.drive.encoderVelocity) ||
        !num("limit_switch_positive", limPos) || !num("limit_switch_negative", limNeg) || !num("index_period", c.drive.indexPeriod) ||
        !num("index_offset", c.drive.indexOffset) || !num("encoder_channel", channel))
      return false;
    if (channel != -1 && (channel != std::floor(channel) || channel < 0 || channel > 2)) {
      error = where(file, node) + "axis '" + c.name + "': encoder_channel must be 0, 1 or 2";
      return false;
    }
    c.encoderChannel = static_cast<int>(channel);
    if (c.name.empty()) {
      error = where(file, node) + "[[axis]] needs a name (the AXIS_REF variable it drives)";
      return false;
    }
    static const std::pair<const char*, AxisKind> kinds[] = {
        {"servo", AxisKind::Servo}, {"virtual", AxisKind::Virtual}, {"encoder", AxisKind::Encoder}, {"pulse", AxisKind::Pulse}};
    auto k = std::find_if(std::begin(kinds), std::end(kinds), [&](auto& p) { return kind == p.first; });
    if (k == std::end(kinds)) {
      error = where(file, node) + "axis '" + c.name + "': type must be servo, virtual, encoder or pulse, not '" + kind + "'";
      return false;
    }
    c.drive.kind = k->second;
    if (drive == "ideal") c.drive.model = DriveModel::Ideal;
    else if (drive == "lag") c.drive.model = DriveModel::Lag;
    else {
      error = where(file, node) + "axis '" + c.name + "': drive must be ideal or lag, not '" + drive + "'";
      return false;
    }
    if (ramp == "trapez") c.ramp = RampType::Trapez;
    else if (ramp == "quadratic" || ramp == "quadratic_ramp") c.ramp = RampType::Quadratic;
    else {
      error = where(file, node) + "axis '" + c.name + "': ramp must be trapez or quadratic, not '" + ramp + "'";
      return false;
    }
    if (!std::isnan(swPos) || !std::isnan(swNeg)) {
      c.swLimitEnable = true;
      c.swLimitPositive = std::isnan(swPos) ? 1e300 : swPos;
      c.swLimitNegative = std::isnan(swNeg) ? -1e300 : swNeg;
    }
    if (!std::isnan(limPos)) c.drive.hasLimitPositive = true, c.drive.limitPositive = limPos;
    if (!std::isnan(limNeg)) c.drive.hasLimitNegative = true, c.drive.limitNegative = limNeg;
    // Scaling from the mechanics: increments per motor revolution, gear ratio
    // [motor revolutions, output revolutions], technical units per output revolution.
    double resolution = NAN, unitsPerRev = NAN;
    if (!num("encoder_resolution", resolution) || !num("units_per_revolution", unitsPerRev)) return false;
    const toml::array* gear = t->get_as<toml::array>("gear_ratio");
    if (!std::isnan(resolution) || !std::isnan(unitsPerRev) || gear) {
      double motorRevs = 1, outputRevs = 1;
      if (gear && (gear->size() != 2 || !gear->get(0)->value<double>() || !gear->get(1)->value<double>() ||
                   !(*gear->get(0)->value<double>() > 0) || !(*gear->get(1)->value<double>() > 0))) {
        error = where(file, *gear) + "axis '" + c.name + "': gear_ratio must be [motor_revolutions, output_revolutions], both > 0";
        return false;
      }
      if (gear) {
        motorRevs = *gear->get(0)->value<double>();
        outputRevs = *gear->get(1)->value<double>();
      }
      if (t->get("increments_per_unit") || !(resolution > 0) || !(unitsPerRev > 0)) {
        error = where(file, node) + "axis '" + c.name +
                "': give either increments_per_unit, or encoder_resolution and units_per_revolution (> 0, with an optional gear_ratio)";
        return false;
      }
      c.drive.incrementsPerUnit = resolution * motorRevs / outputRevs / unitsPerRev;
    }
    if (const toml::array* hs = t->get_as<toml::array>("home_switch")) {
      if (hs->size() != 2 || !hs->get(0)->value<double>() || !hs->get(1)->value<double>()) {
        error = where(file, *hs) + "axis '" + c.name + "': home_switch must be [low, high]";
        return false;
      }
      c.drive.hasHomeSwitch = true;
      c.drive.homeSwitchLow = *hs->get(0)->value<double>();
      c.drive.homeSwitchHigh = *hs->get(1)->value<double>();
    }
    if (const toml::array* faults = t->get_as<toml::array>("fault")) {
      for (const toml::node& fn : *faults) {
        const toml::table* f = fn.as_table();
        std::string at = f ? f->get("at") ? f->get("at")->value_or(std::string()) : std::string() : std::string();
        std::string fk = f ? f->get("kind") ? f->get("kind")->value_or(std::string()) : std::string() : std::string();
        FaultEvent ev;
        if (!f || !vm::parseIecDuration(at, ev.atNs) || !faultKindNamed(fk, ev.kind)) {
          error = where(file, fn) + "axis '" + c.name + "': a fault needs at = \"<duration>\" and kind = " + faultKindNames();
          return false;
        }
        c.drive.faults.push_back(ev);
      }
    }
    out.push_back(std::move(c));
    if (whereOut) whereOut->push_back(where(file, t->get("kv") ? *t->get("kv") : node));
    if (unitsOut) unitsOut->push_back(unit);
  }
  return true;
}

}  // namespace stc::motion
