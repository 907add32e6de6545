#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <toml++/toml.h>

#include "config/ConfigSchema.h"
#include "config/Duration.h"
#include "driver/Driver.h"
#include "import/Import.h"
#include "parse/Parser.h"

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
  // Read and validated against the schema (compiler/config/ConfigSchema.cpp):
  // below, every value has its type and range.
  toml::table tbl;
  if (!config::loadProjectToml(dir, tbl, error)) return false;
  auto at = [&](const toml::node& n) { return config::where(manifest.string(), n) + ": error: "; };
  out.name = tbl["project"]["name"].value_or(root.filename().string());
  if (auto d = tbl["build"]["dialect"].value<std::string>()) out.dialect = *d == "iec" ? sema::Dialect::IEC : sema::Dialect::Codesys;
  if (const toml::node* am = tbl["build"]["address_model"].node()) {
    std::optional<int64_t> bits = am->value<int64_t>();
    if (!bits || (*bits != 32 && *bits != 64)) {
      error = at(*am) + "[build] address_model must be 32 or 64";
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
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        std::string hint = name ? config::closest(*name, known) : std::string();
        error = at(n) + "[project] libraries: unknown library" + (name ? " '" + *name + "'" : "") + " (known: " + list + ")" +
                (hint.empty() ? "" : "; did you mean '" + hint + "'?");
        return false;
      }
      out.libraries.push_back(*name);
    }
  }
  // [[task]] tables: a CONFIGURATION written for the user (one RESOURCE, each
  // program instance named like its PROGRAM type).  Only validated values
  // reach the text: names are ST identifiers, the event a variable path, the
  // interval is re-written from its nanoseconds and the priority from its
  // integer, so no value can add text of its own.
  if (const toml::array* tasks = tbl["task"].as_array(); tasks && !tasks->empty()) {
    out.tasksWhere = config::where(manifest.string(), *tasks->get(0));
    out.manifest = manifest.string();
    // Byte offsets of nodes in project.toml, for the segments of the generated text.
    std::string toml;
    {
      std::ifstream in(manifest, std::ios::binary);
      toml.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    std::vector<uint32_t> lineStart{0};
    for (uint32_t i = 0; i < toml.size(); ++i)
      if (toml[i] == '\n') lineStart.push_back(i + 1);
    auto offsetOf = [&](const toml::node& n) -> uint32_t {
      const auto& b = n.source().begin;
      if (b.line == 0 || b.line > lineStart.size()) return 0;
      return std::min<uint32_t>(lineStart[b.line - 1] + (b.column ? b.column - 1 : 0), static_cast<uint32_t>(toml.size()));
    };
    std::string text = "CONFIGURATION __project\n  RESOURCE __cpu ON PLC\n";
    std::string programs;
    std::vector<SourceSegment> progSegs;
    out.tasksSegments.push_back({0, 0, offsetOf(*tasks->get(0)), false});
    // A name written into the generated text maps byte for byte onto the string in
    // project.toml (after its opening quote); what follows maps to `rest`.
    auto name = [](std::string& into, std::vector<SourceSegment>& segs, const std::string& s, uint32_t quote, uint32_t base, uint32_t rest) {
      segs.push_back({base + static_cast<uint32_t>(into.size()), 0, quote + 1, true});
      into += s;
      segs.push_back({base + static_cast<uint32_t>(into.size()), 0, rest, false});
    };
    // A keyword is an ST name to the schema but not to the parser: refused here,
    // at its place in project.toml, instead of as a syntax error in the generated text.
    auto reserved = [&](const toml::node& v, const char* what) {
      const std::string s = *v.value<std::string>();
      if (!isReservedWord(s)) return false;
      error = at(v) + "[[task]] " + what + " = \"" + s + "\": '" + s + "' is an ST keyword and cannot name a " +
              (std::string(what) == "name" ? "task" : "program");
      return true;
    };
    for (const toml::node& n : *tasks) {
      const toml::table& t = *n.as_table();
      const std::string taskName = *t["name"].value<std::string>();
      if (reserved(*t["name"].node(), "name")) return false;
      for (const toml::node& p : *t["programs"].as_array())
        if (reserved(p, "programs")) return false;
      std::string kind;
      if (auto iv = t["interval"].value<std::string>()) {
        int64_t ns = 0;
        config::parseDuration(*iv, ns);
        kind = "INTERVAL := " + config::formatDuration(ns);
      } else {
        kind = "SINGLE := " + *t["event"].value<std::string>();
      }
      const uint32_t table = offsetOf(n), nameAt = offsetOf(*t["name"].node());
      text += "    TASK ";
      name(text, out.tasksSegments, taskName, nameAt, 0, table);
      text += "(" + kind + ", PRIORITY := " + std::to_string(t["priority"].value_or<int64_t>(0)) + ");\n";
      for (const toml::node& p : *t["programs"].as_array()) {
        const std::string prog = *p.value<std::string>();
        const uint32_t at = offsetOf(p);
        programs += "    PROGRAM ";
        name(programs, progSegs, prog, at, 0, at);
        programs += " WITH ";
        name(programs, progSegs, taskName, nameAt, 0, at);
        programs += " : ";
        name(programs, progSegs, prog, at, 0, at);
        programs += ";\n";
      }
    }
    // The program lines follow the task lines: their segments move by the task text's length.
    for (SourceSegment s : progSegs) {
      s.genBegin += static_cast<uint32_t>(text.size());
      out.tasksSegments.push_back(s);
    }
    out.tasksSegments.push_back({static_cast<uint32_t>(text.size() + programs.size()), 0, offsetOf(*tasks->get(0)), false});
    out.tasksSource = text + programs + "  END_RESOURCE\nEND_CONFIGURATION\n";
  }
  // [[cnc_program]] files that stay inside the project (the run refuses the others, with why).
  if (const toml::array* progs = tbl["cnc_program"].as_array())
    for (const toml::node& n : *progs)
      if (auto f = n.as_table() ? (*n.as_table())["file"].value<std::string>() : std::nullopt) {
        const fs::path rel = fs::path(*f).lexically_normal();
        if (rel.is_absolute() || rel.empty() || *rel.begin() == "..") continue;
        const toml::table& t = *n.as_table();
        out.cncPrograms.push_back({(root / rel).string(), t["default_vel"].value_or(0.0), t["default_accel"].value_or(0.0),
                                   t["default_decel"].value_or(0.0), t["default_vel_ff"].value_or(0.0),
                                   t["default_accel_ff"].value_or(0.0), t["default_decel_ff"].value_or(0.0)});
      }
  fs::path src = root / "src";
  std::error_code ec;
  if (fs::is_directory(src, ec)) {
    for (auto it = fs::recursive_directory_iterator(src, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      // Error codes everywhere: a symbolic-link loop must not throw.  A source name on
      // something that is not a file (a FIFO would block, a loop has no text) is an error.
      std::error_code sec;
      if (it->is_directory(sec) || !isSourceFile(it->path())) continue;
      std::string why;
      if (!config::checkRegularFile(it->path().string(), why)) {
        error = it->path().string() + ": error: " + why;
        return false;
      }
      out.sources.push_back(it->path().string());
    }
    if (ec) {
      error = src.string() + ": error: cannot list the sources: " + ec.message();
      return false;
    }
  }
  std::sort(out.sources.begin(), out.sources.end());
  if (out.sources.empty()) {
    error = (root / "src").string() + ": the project has no sources (src/*.st)";
    return false;
  }
  return true;
}

}  // namespace stc
