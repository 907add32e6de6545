#include <algorithm>
#include <cctype>
#include <filesystem>
#include <toml++/toml.h>

#include "driver/Driver.h"
#include "import/Import.h"

namespace fs = std::filesystem;

namespace stc {

static bool isSourceFile(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".st" || ext == ".exp" || ext == ".txt" || import::kindOf(p.string()) == import::FileKind::PlcOpen ||
         import::kindOf(p.string()) == import::FileKind::TwinCat;
}

bool loadProject(const std::string& dir, ProjectConfig& out, std::string& error) {
  fs::path root(dir);
  fs::path manifest = root / "project.toml";
  out.root = root.string();
  toml::table tbl;
  try {
    tbl = toml::parse_file(manifest.string());
  } catch (const toml::parse_error& e) {
    const auto& src = e.source();
    error = manifest.string() + ":" + std::to_string(src.begin.line) + ":" + std::to_string(src.begin.column) + ": " +
            std::string(e.description());
    return false;
  }
  out.name = tbl["project"]["name"].value_or(root.filename().string());
  if (auto d = tbl["build"]["dialect"].value<std::string>()) {
    if (*d == "iec") out.dialect = sema::Dialect::IEC;
    else if (*d == "codesys") out.dialect = sema::Dialect::Codesys;
    else {
      error = manifest.string() + ": [build] dialect must be \"iec\" or \"codesys\", not \"" + *d + "\"";
      return false;
    }
  }
  if (const toml::node* am = tbl["build"]["address_model"].node()) {
    std::optional<int64_t> bits = am->value<int64_t>();
    if (!bits || (*bits != 32 && *bits != 64)) {
      auto src = am->source();
      error = manifest.string() + ":" + std::to_string(src.begin.line) + ":" + std::to_string(src.begin.column) +
              ": [build] address_model must be 32 or 64";
      return false;
    }
    out.addressBits = static_cast<unsigned>(*bits);
  }
  if (auto* defs = tbl["build"]["defines"].as_array())
    for (auto& d : *defs)
      if (auto s = d.value<std::string>()) out.defines.push_back(*s);
  if (const toml::array* libs = tbl["project"]["libraries"].as_array()) {
    const std::vector<std::string> known = availableLibraries();
    for (const toml::node& n : *libs) {
      auto name = n.value<std::string>();
      if (!name || std::find(known.begin(), known.end(), *name) == known.end()) {
        const auto& src = n.source();
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        error = manifest.string() + ":" + std::to_string(src.begin.line) + ":" + std::to_string(src.begin.column) +
                ": [project] libraries: unknown library" + (name ? " '" + *name + "'" : "") + " (known: " + list + ")";
        return false;
      }
      out.libraries.push_back(*name);
    }
  }
  // [[task]] tables: a CONFIGURATION written for the user (one RESOURCE, each
  // program instance named like its PROGRAM type).
  if (const toml::array* tasks = tbl["task"].as_array()) {
    auto at = [&](const toml::node& n) {
      return manifest.string() + ":" + std::to_string(n.source().begin.line) + ":" + std::to_string(n.source().begin.column) + ": ";
    };
    auto ident = [](const std::string& x) {
      return !x.empty() && (std::isalpha(static_cast<unsigned char>(x[0])) || x[0] == '_') &&
             std::all_of(x.begin(), x.end(), [](unsigned char c) { return std::isalnum(c) || c == '_'; });
    };
    std::string text = "CONFIGURATION __project\n  RESOURCE __cpu ON PLC\n";
    std::string programs;
    for (const toml::node& n : *tasks) {
      const toml::table* t = n.as_table();
      auto name = t ? (*t)["name"].value<std::string>() : std::nullopt;
      auto interval = t ? (*t)["interval"].value<std::string>() : std::nullopt;
      auto event = t ? (*t)["event"].value<std::string>() : std::nullopt;
      auto priority = t ? (*t)["priority"].value<int64_t>() : std::nullopt;
      const toml::array* progs = t ? (*t)["programs"].as_array() : nullptr;
      if (!name || !ident(*name) || (!interval == !event) || !progs || progs->empty()) {
        error = at(n) + "a [[task]] needs name = \"IDENT\", interval = \"10ms\" (cyclic) or event = \"VAR\" (on its rising edge), "
                        "and programs = [\"PROGRAM\", ...]; optional priority = N";
        return false;
      }
      std::string iv = interval ? *interval : "";
      if (interval && !(iv.size() > 2 && (iv.compare(0, 2, "T#") == 0 || iv.compare(0, 2, "t#") == 0))) iv = "T#" + iv;
      text += "    TASK " + *name + "(" + (interval ? "INTERVAL := " + iv : "SINGLE := " + *event) +
              ", PRIORITY := " + std::to_string(priority.value_or(0)) + ");\n";
      for (const toml::node& p : *progs) {
        auto prog = p.value<std::string>();
        if (!prog || !ident(*prog)) {
          error = at(p) + "[[task]] programs: a PROGRAM name";
          return false;
        }
        programs += "    PROGRAM " + *prog + " WITH " + *name + " : " + *prog + ";\n";
      }
    }
    out.tasksSource = text + programs + "  END_RESOURCE\nEND_CONFIGURATION\n";
  }
  fs::path src = root / "src";
  std::error_code ec;
  if (fs::is_directory(src, ec)) {
    for (auto it = fs::recursive_directory_iterator(src, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
      if (it->is_regular_file() && isSourceFile(it->path())) out.sources.push_back(it->path().string());
  }
  std::sort(out.sources.begin(), out.sources.end());
  if (out.sources.empty()) {
    error = (root / "src").string() + ": the project has no sources (src/*.st)";
    return false;
  }
  return true;
}

}  // namespace stc
