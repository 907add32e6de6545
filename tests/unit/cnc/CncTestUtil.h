// Shared helpers of the G-code decoder tests: decode a program text and keep
// its diagnostics, rendered as the command line shows them.
#pragma once

#include <gtest/gtest.h>

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

}  // namespace stc::cnc::test
