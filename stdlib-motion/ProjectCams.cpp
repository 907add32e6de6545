// [[cam]] tables of project.toml and the file names programs give
// (SMC_ReadCAM / SMC_WriteCAM).  docs/motion-cam.md.
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "stdlib-motion/MotionNatives.h"
#include "stdlib-motion/ProjectToml.h"
#include "vm/FileSandbox.h"

namespace stc::motion {

namespace {

std::optional<double> number(const toml::node* n) {
  if (!n) return std::nullopt;
  if (auto d = n->value<double>()) return d;
  return std::nullopt;
}

// [a, b] of numbers into out; false when the node is not such an array.
bool numbers(const toml::node* n, size_t count, double* out) {
  const toml::array* a = n ? n->as_array() : nullptr;
  if (!a || a->size() != count) return false;
  for (size_t i = 0; i < count; ++i) {
    auto v = number(a->get(i));
    if (!v) return false;
    out[i] = *v;
  }
  return true;
}

bool readTappets(const toml::table& t, const std::string& here, std::vector<Tappet>& out, std::string& error) {
  const toml::array* arr = t["tappets"].as_array();
  if (!arr) return true;
  for (const toml::node& n : *arr) {
    const toml::table* tt = n.as_table();
    Tappet tp;
    auto x = tt ? number(tt->get("x")) : std::nullopt;
    auto g = tt ? (*tt)["group"].value<int64_t>() : std::nullopt;
    const std::string pos = tt ? (*tt)["positive"].value_or<std::string>("none") : "", neg = tt ? (*tt)["negative"].value_or<std::string>("none") : "";
    if (!x || !g || *g < 1 || *g > kMaxTappetGroups || !tappetActionNamed(pos, tp.positive) || !tappetActionNamed(neg, tp.negative)) {
      error = here + "a tappet is { x = <master position>, group = 1..512, positive = \"on|off|invert|none\", negative = ... }";
      return false;
    }
    tp.x = *x;
    tp.group = static_cast<int>(*g);
    out.push_back(tp);
  }
  return true;
}

// One [[cam]]: exactly one of file, xyva, table1d, table2d, segments.
bool readCam(const toml::table& t, const std::string& dir, const std::string& here, Cam& cam, std::string& error) {
  std::vector<Tappet> tappets;
  if (!readTappets(t, here, tappets, error)) return false;
  std::string why;
  bool ok = false;
  const int given = !!t.get("file") + !!t.get("xyva") + !!t.get("table1d") + !!t.get("table2d") + !!t.get("segments");
  if (given != 1) {
    error = here + "a [[cam]] needs exactly one of file, xyva, table1d, table2d or segments";
    return false;
  }
  if (auto file = t["file"].value<std::string>()) {
    // Project files: relative to the project directory, never leaving it (vm/FileSandbox.h).
    const int fd = vm::openInside(dir, *file, vm::FileAccess::Read, why);
    if (fd < 0) return error = here + "cam file '" + *file + "': " + why, false;
    std::string text;
    switch (vm::readAndClose(fd, kMaxProjectFileBytes, text)) {
    case vm::ReadResult::Ok: break;
    case vm::ReadResult::Failed: return error = here + "cannot read cam file '" + *file + "'", false;
    case vm::ReadResult::TooBig: return error = here + "cam file '" + *file + "' is larger than 64 MB", false;
    }
    std::string name, detail;
    if (readCamText(text, cam, name, detail) != CamFileError::None) return error = here + *file + ": " + detail, false;
    if (!tappets.empty()) return error = here + "the tappets of a cam file are in the file", false;
    return true;
  }
  if (const toml::array* a = t["xyva"].as_array()) {
    std::vector<CamXYVA> pts;
    for (const toml::node& n : *a) {
      double v[4];
      if (!numbers(&n, 4, v)) return error = here + "xyva = [[x, y, v, a], ...]", false;
      pts.push_back(CamXYVA{v[0], v[1], v[2], v[3]});
    }
    ok = Cam::xyva(std::move(pts), std::move(tappets), cam, why);
  } else if (const toml::array* a2 = t["table2d"].as_array()) {
    std::vector<std::array<double, 2>> pts;
    for (const toml::node& n : *a2) {
      double v[2];
      if (!numbers(&n, 2, v)) return error = here + "table2d = [[x, y], ...]", false;
      pts.push_back({v[0], v[1]});
    }
    ok = Cam::table2D(std::move(pts), std::move(tappets), cam, why);
  } else if (const toml::table* t1 = t["table1d"].as_table()) {
    double range[2];
    const toml::array* vals = (*t1)["values"].as_array();
    if (!numbers(t1->get("master"), 2, range) || !vals) return error = here + "table1d = { master = [xStart, xEnd], values = [...] }", false;
    std::vector<double> ys;
    for (const toml::node& n : *vals) {
      auto v = number(&n);
      if (!v) return error = here + "table1d values must be numbers", false;
      ys.push_back(*v);
    }
    ok = Cam::table1D(range[0], range[1], std::move(ys), std::move(tappets), cam, why);
  } else {
    // segments = [{ law = "cycloid", to = [x, y], base_slope = 0 }, ...] from start = [x, y].
    double start[2] = {0, 0};
    if (t.get("start") && !numbers(t.get("start"), 2, start)) return error = here + "start = [x, y]", false;
    std::vector<CamXYVA> pts;
    double x = start[0], y = start[1];
    const toml::array* segs = t["segments"].as_array();
    if (!segs || segs->empty()) return error = here + "segments = [{ law = \"cycloid\", to = [x, y] }, ...]", false;
    for (const toml::node& n : *segs) {
      const toml::table* s = n.as_table();
      double to[2];
      MotionLaw law;
      auto lawName = s ? (*s)["law"].value<std::string>() : std::nullopt;
      if (!s || !lawName || !motionLawNamed(*lawName, law) || !numbers(s->get("to"), 2, to) || !(to[0] > x))
        return error = here + "a segment is { law = \"linear|harmonic|cycloid|modified_sine|modified_trapezoid|poly345\", to = [x, y], "
                              "base_slope = <slope> } with x increasing",
               false;
      const double base = (*s)["base_slope"].value_or(0.0);
      if (!std::isfinite(base) || std::fabs(base) > 1e6) return error = here + "base_slope must be a finite slope", false;
      appendMotionLaw(law, x, to[0], y, to[1], pts, base);
      x = to[0];
      y = to[1];
    }
    ok = Cam::xyva(std::move(pts), std::move(tappets), cam, why);
  }
  if (!ok) error = here + why;
  return ok;
}

}  // namespace

bool loadProjectCams(const std::string& dir, std::vector<CamConfig>& out, std::string& error) {
  std::string file;
  toml::table tbl;
  const toml::array* arr = projectTables(dir, "cam", tbl, file);
  if (!arr) return true;
  for (const toml::node& n : *arr) {
    const toml::table* t = n.as_table();
    const std::string here = tomlWhere(file, n);
    auto var = t ? (*t)["var"].value<std::string>() : std::nullopt;
    if (!var) return error = here + "a [[cam]] needs var = \"NAME\" (an MC_CAM_REF variable)", false;
    Cam cam;
    if (!readCam(*t, dir, here, cam, error)) return false;
    out.push_back(CamConfig{*var, std::make_shared<const Cam>(std::move(cam))});
  }
  return true;
}

}  // namespace stc::motion
