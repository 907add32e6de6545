// stc check of a whole project (docs/projects.md, "stc check"): besides the sources and the
// G-code programs, the names that project.toml tables and scenarios give must be variables
// the sources declare, and every scenario must pass the schema `stc test` applies.  Errors
// point into the TOML file that has the mistake, with a "did you mean" from the right names
// (variables for variables, [[axis]] names for axes).
#include <algorithm>
#include <filesystem>
#include <toml++/toml.h>

#include "basic/Diagnostics.h"
#include "basic/Text.h"
#include "config/ConfigSchema.h"
#include "driver/DeclaredNames.h"
#include "driver/Driver.h"

namespace fs = std::filesystem;

namespace stc {

namespace {

class NameChecker {
public:
  NameChecker(const DeclaredNames& names, std::string shown, std::vector<std::string>& errors)
      : names_(names), shown_(std::move(shown)), errors_(errors) {}

  // A variable path (`GVL.x`, `MAIN.fb.q`, `arr[2]`).
  void variable(const toml::node* n, const std::string& what) {
    auto s = n ? n->value<std::string>() : std::nullopt;
    if (!s || names_.known(*s)) return;
    const std::string hint = names_.closest(*s);
    errors_.push_back(config::where(shown_, *n) + ": error: " + what + " '" + *s + "' is not a variable of the program" +
                      (hint.empty() ? std::string() : "; did you mean '" + hint + "'?"));
  }
  // The name of an [[axis]] of project.toml.
  void axis(const toml::node* n, const std::vector<std::string>& axes, const std::string& what) {
    auto s = n ? n->value<std::string>() : std::nullopt;
    if (!s) return;
    for (const std::string& a : axes)
      if (asciiLower(a) == asciiLower(*s)) return;
    const std::string hint = closestMatch(*s, axes);
    errors_.push_back(config::where(shown_, *n) + ": error: " + what + " '" + *s + "' is not an [[axis]] of project.toml" +
                      (hint.empty() ? std::string() : "; did you mean '" + hint + "'?"));
  }

private:
  const DeclaredNames& names_;
  std::string shown_;
  std::vector<std::string>& errors_;
};

template <class F>
void eachTable(const toml::table& t, const char* key, F&& f) {
  if (const toml::array* a = t[key].as_array())
    for (const toml::node& n : *a)
      if (const toml::table* tt = n.as_table()) f(*tt);
}

}  // namespace

void Compilation::checkProjectFiles() {
  const DeclaredNames names(*ast_);
  for (const std::string& dir : projectDirs_) {
    std::vector<std::string> errors;
    toml::table project;
    std::string error;
    if (!config::loadProjectToml(dir, project, error)) continue;   // reported when the project was loaded
    const std::string manifest = (fs::path(dir) / "project.toml").string();
    NameChecker in(names, manifest, errors);
    std::vector<std::string> axes;
    eachTable(project, "axis", [&](const toml::table& t) {
      in.variable(t["name"].node(), "[[axis]] name");
      if (auto s = t["name"].value<std::string>()) axes.push_back(*s);
    });
    eachTable(project, "group", [&](const toml::table& t) {
      in.variable(t["name"].node(), "[[group]] name");
      if (const toml::array* a = t["axes"].as_array())
        for (const toml::node& n : *a) in.axis(&n, axes, "[[group]] axes:");
    });
    eachTable(project, "io", [&](const toml::table& t) {
      in.variable(t["var"].node(), "[[io]] var");
      in.variable(t["source"].node(), "[[io]] source");
      in.axis(t["axis"].node(), axes, "[[io]] axis");
    });
    eachTable(project, "cam", [&](const toml::table& t) { in.variable(t["var"].node(), "[[cam]] var"); });
    eachTable(project, "cnc_program", [&](const toml::table& t) { in.variable(t["var"].node(), "[[cnc_program]] var"); });
    eachTable(project, "task", [&](const toml::table& t) { in.variable(t["event"].node(), "[[task]] event"); });

    // The scenarios, with the schema stc test applies and the same names.
    std::vector<fs::path> scenarios;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(fs::path(dir) / "scenarios", ec))
      if (e.path().extension() == ".toml") scenarios.push_back(e.path());
    std::sort(scenarios.begin(), scenarios.end());
    for (const fs::path& f : scenarios) {
      toml::table sc;
      if (!config::loadToml(f.string(), f.string(), config::scenarioSchema(), sc, error)) {
        errors.push_back(error);
        continue;
      }
      NameChecker s(names, f.string(), errors);
      if (const toml::array* tr = sc["trace"].as_array())
        for (const toml::node& n : *tr) s.variable(&n, "trace");
      eachTable(sc, "set", [&](const toml::table& t) { s.variable(t["var"].node(), "[[set]] var"); });
      eachTable(sc, "check", [&](const toml::table& t) { s.variable(t["var"].node(), "[[check]] var"); });
      eachTable(sc, "fault", [&](const toml::table& t) { s.axis(t["axis"].node(), axes, "[[fault]] axis"); });
    }
    for (const std::string& e : errors) projectError(e);
  }
}

}  // namespace stc
