// Simulated I/O devices from the [[io]] tables of project.toml: sensors on
// the mechanics of an axis (a photo eye or cam switch closed while the
// axis's actual position is inside a window) and actuators with feedback (a
// BOOL that follows another one after a delay, e.g. a cylinder's end switch
// following its valve output).  They are evaluated after each task slot, so
// the programs see them in their next cycle, as inputs read at cycle start.
#include <algorithm>
#include <cmath>
#include <deque>

#include "stdlib-motion/MotionNatives.h"
#include "stdlib-motion/ProjectToml.h"
#include "vm/Native.h"
#include "vm/Time.h"

namespace stc::motion {

namespace {

struct Bound {
  IoDevice dev;
  vm::StartCtx::BoolTarget out, source;
  Axis* axis = nullptr;
  std::deque<std::pair<int64_t, bool>> changes;   // Delay: the source's changes, oldest first
  bool last = false;
};

bool boolVar(const vm::StartCtx& sc, const std::string& path, const char* what, vm::StartCtx::BoolTarget& out, std::string& error) {
  if (sc.lookupBool(path, out)) return true;
  error = std::string("project.toml: [[io]] ") + what + " '" + path + "' is no BOOL variable of the program";
  return false;
}

bool get(const vm::StartCtx::BoolTarget& t) { return t.bit < 0 ? *t.byte != 0 : ((*t.byte >> t.bit) & 1) != 0; }
void put(const vm::StartCtx::BoolTarget& t, bool v) {
  if (t.bit < 0) *t.byte = v;
  else *t.byte = static_cast<uint8_t>((*t.byte & ~(1u << t.bit)) | (static_cast<unsigned>(v) << t.bit));
}

}  // namespace

struct IoRuntime {
  std::vector<Bound> bound;
};

std::shared_ptr<IoRuntime> startIo(const vm::StartCtx& sc, const std::vector<IoDevice>& devices, Kernel& k, std::string& error) {
  auto s = std::make_shared<IoRuntime>();
  for (const IoDevice& d : devices) {
    Bound b;
    b.dev = d;
    if (!boolVar(sc, d.var, "var", b.out, error)) return nullptr;
    if (d.kind == IoDevice::Kind::AxisWindow) {
      for (size_t i = 0; i < k.axisCount() && !b.axis; ++i)
        if (Axis* a = k.axis(static_cast<uint32_t>(i)); a->config().name == d.axis) b.axis = a;
      if (!b.axis) {
        error = "project.toml: [[io]] '" + d.var + "': no [[axis]] named '" + d.axis + "'";
        return nullptr;
      }
    } else if (!boolVar(sc, d.source, "source", b.source, error)) {
      return nullptr;
    }
    s->bound.push_back(std::move(b));
  }
  return s;
}

void cycleIo(IoRuntime& io, int64_t nowNs) {
  for (Bound& b : io.bound) {
    if (b.axis) {
      // The window is on the mechanics: coordinate shifts (homing, MC_SetPosition) do not move it.
      const double x = b.axis->actPosition() - b.axis->drive().coordinateShift();
      put(b.out, x >= b.dev.low && x <= b.dev.high);
      continue;
    }
    const bool v = get(b.source);
    if (b.changes.empty() ? v != b.last : v != b.changes.back().second) b.changes.emplace_back(nowNs, v);
    while (!b.changes.empty() && b.changes.front().first + b.dev.delayNs <= nowNs) {
      b.last = b.changes.front().second;
      b.changes.pop_front();
    }
    put(b.out, b.last);
  }
}

bool loadProjectIo(const std::string& dir, std::vector<IoDevice>& out, std::string& error) {
  std::string file;
  toml::table tbl;
  const toml::array* arr = projectTables(dir, "io", tbl, file);
  if (!arr) return true;
  for (const toml::node& n : *arr) {
    const toml::table* t = n.as_table();
    const std::string here = tomlWhere(file, n);
    auto str = [&](const char* k) { return t ? (*t)[k].value<std::string>() : std::nullopt; };
    IoDevice d;
    auto var = str("var"), kind = str("kind");
    if (!var || !kind) {
      error = here + "an [[io]] needs var = \"NAME\" (a BOOL) and kind = \"axis_window\" or \"delay\"";
      return false;
    }
    d.var = *var;
    if (*kind == "axis_window") {
      auto axis = str("axis");
      const toml::array* w = (*t)["window"].as_array();
      if (!axis || !w || w->size() != 2 || !w->get(0)->value<double>() || !w->get(1)->value<double>() ||
          *w->get(0)->value<double>() > *w->get(1)->value<double>()) {
        error = here + "an axis_window [[io]] needs axis = \"NAME\" and window = [low, high] (low <= high)";
        return false;
      }
      d.kind = IoDevice::Kind::AxisWindow;
      d.axis = *axis;
      d.low = *w->get(0)->value<double>();
      d.high = *w->get(1)->value<double>();
    } else if (*kind == "delay") {
      auto source = str("source"), delay = str("delay");
      if (!source || !delay || !vm::parseIecDuration(*delay, d.delayNs) || d.delayNs < 0) {
        error = here + "a delay [[io]] needs source = \"NAME\" (a BOOL) and delay = \"<duration>\"";
        return false;
      }
      d.kind = IoDevice::Kind::Delay;
      d.source = *source;
    } else {
      error = here + "[[io]] kind must be \"axis_window\" or \"delay\", not \"" + *kind + "\"";
      return false;
    }
    out.push_back(std::move(d));
  }
  return true;
}

}  // namespace stc::motion
