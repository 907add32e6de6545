// Shared helpers of the G-code decoder tests: decode a program text and keep
// its diagnostics, rendered as the command line shows them.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/cnc/Geometry.h"

namespace stc::cnc::test {

// $name$ variables from a map (names are case-sensitive as written).
class MapVars : public VariableAccess {
public:
  std::map<std::string, double, std::less<>> values;
  bool read(std::string_view name, double& v) override {
    auto it = values.find(name);
    if (it == values.end()) return false;
    v = it->second;
    return true;
  }
  bool write(std::string_view name, double v) override {
    auto it = values.find(name);
    if (it == values.end()) return false;
    it->second = v;
    return true;
  }
};

// One decode of `text` (file "prog.cnc") with every element and diagnostic.
struct Decoded {
  SourceManager sm;
  std::unique_ptr<DiagnosticsEngine> diags;
  uint32_t file = 0;
  std::vector<Element> els;

  explicit Decoded(const std::string& text, const DecoderOptions& opts = {}, VariableAccess* vars = nullptr) {
    diags = std::make_unique<DiagnosticsEngine>(sm);
    diags->opts.errorLimit = 0;
    file = sm.addBuffer("prog.cnc", text);
    els = decodeAll(sm, file, *diags, opts, vars);
  }
  unsigned errors() const { return diags->errorCount(); }
  unsigned warnings() const { return diags->warningCount(); }
  // First lines of every diagnostic ("prog.cnc:2:7: error: ... [code]").
  std::vector<std::string> heads() const {
    std::vector<std::string> out;
    for (const Diagnostic& d : diags->diagnostics()) {
      std::string t = renderText(sm, d);
      out.push_back(t.substr(0, t.find('\n')));
    }
    return out;
  }
  std::string all() const {
    std::string s;
    for (const Diagnostic& d : diags->diagnostics()) s += renderText(sm, d);
    return s;
  }
  // Elements of one type, in order.
  std::vector<Element> of(MoveType t) const {
    std::vector<Element> out;
    for (const Element& e : els)
      if (e.type == t) out.push_back(e);
    return out;
  }
};

constexpr double kTol = 1e-9;
constexpr double kPi = 3.14159265358979323846;

inline void expectPos(const Pos& p, std::initializer_list<double> xyz, double tol = kTol) {
  int i = 0;
  for (double v : xyz) {
    EXPECT_NEAR(p[i], v, tol) << "axis " << axisLetter(static_cast<Axis>(i));
    ++i;
  }
}
inline void expectVec(const Vec3& p, Vec3 q, double tol = kTol) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(p[i], q[i], tol) << "component " << i;
}

// The junction rule of SMC_CheckVelocities (simplified for the tests): 0 at the end, before
// and after non-motion elements and at corners; else the smaller velocity.
inline void checkVelocities(std::vector<Element>& els) {
  for (size_t i = 0; i < els.size(); ++i) {
    Element& e = els[i];
    e.marks |= MarkVelChecked;
    e.velEnd = 0;
    if (!isMotion(e.type) || i + 1 >= els.size()) continue;
    const Element& n = els[i + 1];
    if (!isToolPath(e.type) || !isToolPath(n.type)) continue;
    const Vec3 a = endTangent(e), b = startTangent(n);
    if (dot(a, b) > std::cos(0.001 * kPi / 180)) e.velEnd = std::min(e.vel, n.vel);
  }
}

// Distance of p from the element's geometry (sampled finely, refined by golden section).
inline double distanceToElement(const Element& e, const Pos& p) {
  auto d2 = [&](double u) {
    const Pos q = point(e, u);
    double s = 0;
    for (int i = 0; i < 3; ++i) s += (q[i] - p[i]) * (q[i] - p[i]);
    return s;
  };
  int best = 0;
  const int n = 200;
  for (int i = 1; i <= n; ++i)
    if (d2(double(i) / n) < d2(double(best) / n)) best = i;
  double lo = std::max(0.0, (best - 1.0) / n), hi = std::min(1.0, (best + 1.0) / n);
  for (int it = 0; it < 70; ++it) {
    const double m1 = lo + (hi - lo) * 0.381966, m2 = hi - (hi - lo) * 0.381966;
    if (d2(m1) < d2(m2)) hi = m2;
    else lo = m1;
  }
  return std::sqrt(d2(0.5 * (lo + hi)));
}

}  // namespace stc::cnc::test
