// TwinCAT 3 PLC objects: the declarations and bodies are ST in CDATA, so the
// generated buffer is mostly verbatim copies; only the END_xxx keywords and
// the accessor/action headers are synthesized (at their elements).
#include "import/ImportInternal.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace fs = std::filesystem;

namespace stc::import {

namespace {

class TwinCatImporter {
public:
  TwinCatImporter(XmlFile& xml, ImportResult& out) : xml_(xml), w_(xml), out_(out) {}

  bool run() {
    pugi::xml_node root = xml_.root();
    if (localName(root) != "TcPlcObject") {
      error(root, "not a TwinCAT object file: the root element is <" + std::string(root.name()) + ">, not <TcPlcObject>", "import");
      return false;
    }
    for (pugi::xml_node n : root.children()) {
      if (n.type() != pugi::node_element) continue;
      std::string_view k = localName(n);
      if (k == "POU") pou(n);
      else if (k == "Itf") itf(n);
      else if (k == "DUT") dut(n);
      else if (k == "GVL") gvl(n);
      else if (k == "Task") task(n);
      else unsupported(n);
    }
    if (w_.size()) out_.file = w_.finish(xml_.sources(), xml_.path());
    return !xml_.hadErrors();
  }

private:
  void error(const pugi::xml_node& n, std::string msg, std::string code) { xml_.error(n, std::move(msg), std::move(code)); }
  void unsupported(const pugi::xml_node& n) {
    xml_.diags().warning(xml_.at(n), "<" + std::string(n.name()) + "> is not supported; it is ignored", "import-ignored");
  }
  std::string name(const pugi::xml_node& n) { return n.attribute("Name").value(); }

  // The <Declaration> of `n`; returns its first keyword.
  std::string declaration(const pugi::xml_node& n, bool required) {
    pugi::xml_node d = child(n, "Declaration");
    size_t start = w_.size();
    if (d) w_.text(d);
    std::string kw = firstKeyword(std::string_view(w_.str()).substr(start));
    if (required && kw.empty())
      error(d ? d : n, "'" + name(n) + "' has an empty declaration", "import");
    w_.synth("\n", d ? d : n);
    return kw;
  }

  // The <Implementation> of `n`: ST, or an error naming the language.
  void implementation(const pugi::xml_node& n, const std::string& what) {
    pugi::xml_node impl = child(n, "Implementation");
    if (!impl) return;
    for (pugi::xml_node b : impl.children()) {
      if (b.type() != pugi::node_element) continue;
      std::string_view lang = localName(b);
      if (lang == "ST") {
        w_.text(b);
        w_.synth("\n", b);
      } else {
        std::string shown = lang == "NWL" ? "LD/FBD/IL networks" : std::string(lang);
        error(b, what + " is written in " + shown + "; only ST bodies are supported", "unsupported-language");
      }
    }
  }

  void members(const pugi::xml_node& n, const std::string& owner, bool prototypes) {
    for (pugi::xml_node m : n.children()) {
      if (m.type() != pugi::node_element) continue;
      std::string_view k = localName(m);
      if (k == "Method") {
        declaration(m, true);
        if (!prototypes) implementation(m, "method '" + owner + "." + name(m) + "'");
        w_.synth("END_METHOD\n", m);
      } else if (k == "Property") {
        declaration(m, true);
        for (const char* acc : {"Get", "Set"}) {
          pugi::xml_node a = child(m, acc);
          if (!a) continue;
          w_.synth(std::string(acc == std::string("Get") ? "GET" : "SET") + "\n", a);
          declaration(a, false);
          if (!prototypes) implementation(a, "property '" + owner + "." + name(m) + "'");
          w_.synth(std::string(acc == std::string("Get") ? "END_GET" : "END_SET") + "\n", a);
        }
        w_.synth("END_PROPERTY\n", m);
      } else if (k == "Action" && !prototypes) {
        w_.synth("ACTION ", m);
        w_.attr(m, "Name");
        w_.synth(":\n", m);
        implementation(m, "action '" + owner + "." + name(m) + "'");
        w_.synth("END_ACTION\n", m);
      } else if (k == "Transition") {
        error(m, "transition '" + name(m) + "' of '" + owner + "' belongs to SFC, which is not supported", "unsupported-language");
      } else if (k == "Declaration" || k == "Implementation" || k == "LineIds" || k == "Folder" || k == "ObjectProperties") {
        // Handled above, or editor data (line maps, folders).
      } else {
        unsupported(m);
      }
    }
  }

  void pou(const pugi::xml_node& n) {
    std::string kw = declaration(n, true);
    const char* end = kw == "PROGRAM" ? "END_PROGRAM" : kw == "FUNCTION_BLOCK" ? "END_FUNCTION_BLOCK" : kw == "FUNCTION" ? "END_FUNCTION" : nullptr;
    if (!end) {
      if (!kw.empty()) error(child(n, "Declaration"), "the declaration of POU '" + name(n) + "' does not start with PROGRAM, FUNCTION_BLOCK or FUNCTION", "import");
      return;
    }
    implementation(n, "POU '" + name(n) + "'");
    members(n, name(n), false);
    w_.synth(std::string(end) + "\n", n);
  }

  void itf(const pugi::xml_node& n) {
    declaration(n, true);
    members(n, name(n), true);
    w_.synth("END_INTERFACE\n", n);
  }

  void dut(const pugi::xml_node& n) { declaration(n, true); }

  void gvl(const pugi::xml_node& n) {
    uint32_t begin = static_cast<uint32_t>(w_.size());
    declaration(n, false);
    out_.globals.push_back({begin, static_cast<uint32_t>(w_.size()), name(n)});
  }

  // An IEC identifier; `dotted`: also Namespace.Name.
  static bool isName(const std::string& s, bool dotted) {
    bool start = true;
    for (char c : s) {
      bool letter = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
      if (start && !letter) return false;
      if (!start && c == '.' && dotted) { start = true; continue; }
      if (!start && !letter && !(c >= '0' && c <= '9')) return false;
      start = false;
    }
    return !s.empty() && !start;
  }

  void task(const pugi::xml_node& n) {
    TwinCatTask t;
    t.name = name(n);
    t.loc = xml_.at(n);
    // <CycleTime> is in microseconds, <Priority> as in TwinCAT (lower runs first).
    std::string cycle = child(n, "CycleTime").text().as_string();
    t.cycleMicros = child(n, "CycleTime").text().as_ullong(0);
    t.priority = child(n, "Priority").text().as_int(0);
    if (t.name.empty() || t.cycleMicros == 0) {
      error(n, "task '" + t.name + "' needs a Name and a <CycleTime> in microseconds", "import");
      return;
    }
    // The values become a CONFIGURATION: names must be names (never ST text), numbers in range.
    if (!isName(t.name, false)) {
      error(n, "task name '" + t.name + "' is not an identifier", "import");
      return;
    }
    if (t.cycleMicros > 3'600'000'000ull || t.priority < 0 || t.priority > 255) {
      error(n, "task '" + t.name + "': <CycleTime> must be 1..3600000000 us and <Priority> 0..255", "import");
      return;
    }
    for (pugi::xml_node c : n.children())
      if (c.type() == pugi::node_element && localName(c) == "PouCall") {
        std::string prog = child(c, "Name").text().as_string();
        if (prog.empty()) continue;
        if (!isName(prog, true)) {
          error(c, "program name '" + prog + "' of task '" + t.name + "' is not an identifier", "import");
          return;
        }
        t.programs.push_back(prog);
      }
    out_.tasks.push_back(std::move(t));
  }

  XmlFile& xml_;
  StWriter w_;
  ImportResult& out_;
};

bool isAbsoluteWindowsOrPosix(const std::string& p) {
  return (!p.empty() && (p[0] == '/' || p[0] == '\\')) ||
         (p.size() >= 2 && std::isalpha(static_cast<unsigned char>(p[0])) && p[1] == ':');
}

// TwinCAT projects come from Windows: names in the project file may differ
// in case from the files on disk.
fs::path resolveNoCase(const fs::path& root, const fs::path& rel) {
  fs::path cur = root;
  std::error_code ec;
  for (const fs::path& part : rel) {
    fs::path next = cur / part;
    if (!fs::exists(next, ec) && fs::is_directory(cur, ec)) {
      for (const fs::directory_entry& e : fs::directory_iterator(cur, ec))
        if (equalsNoCase(e.path().filename().string(), part.string())) { next = e.path(); break; }
    }
    cur = next;
  }
  return cur;
}

}  // namespace

bool importTwinCat(XmlFile& xml, ImportResult& out) { return TwinCatImporter(xml, out).run(); }

bool loadPlcProject(SourceManager& sm, DiagnosticsEngine& diags, const std::string& path, std::vector<std::string>& files) {
  XmlFile xml(sm, diags);
  if (!xml.load(path)) return false;
  if (localName(xml.root()) != "Project") {
    diags.error(xml.at(xml.root()), "not a TwinCAT PLC project: the root element is <" + std::string(xml.root().name()) + ">, not <Project>", "import");
    return false;
  }
  fs::path root = fs::path(path).parent_path();
  if (root.empty()) root = ".";
  std::error_code ec;
  fs::path canonicalRoot = fs::weakly_canonical(root, ec);
  bool ok = true;
  for (pugi::xml_node group : xml.root().children()) {
    if (localName(group) != "ItemGroup") continue;
    for (pugi::xml_node item : group.children()) {
      if (item.type() != pugi::node_element || localName(item) != "Compile") continue;
      std::string inc = item.attribute("Include").value();
      SourceLoc at = xml.attrAt(item, "Include");
      std::string rel = inc;
      std::replace(rel.begin(), rel.end(), '\\', '/');
      fs::path norm = fs::path(rel).lexically_normal();
      if (inc.empty() || isAbsoluteWindowsOrPosix(inc) || norm.empty() || *norm.begin() == "..") {
        diags.error(at, "'" + inc + "' is outside the project directory; only files below it are compiled", "project");
        ok = false;
        continue;
      }
      fs::path file = resolveNoCase(root, norm);
      // A symbolic link may still lead out of the project.
      fs::path real = fs::weakly_canonical(file, ec);
      auto [r, f] = std::mismatch(canonicalRoot.begin(), canonicalRoot.end(), real.begin(), real.end());
      if (r != canonicalRoot.end()) {
        diags.error(at, "'" + inc + "' is outside the project directory; only files below it are compiled", "project");
        ok = false;
        continue;
      }
      if (kindOf(file.string()) != FileKind::TwinCat) {
        diags.warning(at, "'" + inc + "' is not compiled: only .TcPOU, .TcGVL, .TcDUT, .TcIO and .TcTTO files are imported", "import-ignored");
        continue;
      }
      if (!fs::is_regular_file(file, ec)) {
        diags.error(at, "'" + inc + "' does not exist", "project");
        ok = false;
        continue;
      }
      files.push_back(file.string());
    }
  }
  if (files.empty() && ok) {
    diags.error(xml.at(xml.root()), "the project compiles no PLC objects (<Compile Include=\"...TcPOU\"/>)", "project");
    ok = false;
  }
  return ok;
}

uint32_t twinCatConfiguration(SourceManager& sm, const std::vector<TwinCatTask>& tasks) {
  if (tasks.empty()) return 0;
  std::string text;
  std::vector<SourceSegment> segs;
  auto put = [&](const std::string& s, SourceLoc at) {
    segs.push_back(SourceSegment{static_cast<uint32_t>(text.size()), at.file, at.offset, false});
    text += s;
  };
  put("CONFIGURATION __twincat\nRESOURCE __plc ON PLC\n", tasks.front().loc);
  for (const TwinCatTask& t : tasks) {
    uint64_t us = t.cycleMicros;
    std::string iv = us % 1000 == 0 ? std::to_string(us / 1000) + "ms" : std::to_string(us) + "us";
    put("TASK " + t.name + "(INTERVAL := T#" + iv + ", PRIORITY := " + std::to_string(t.priority) + ");\n", t.loc);
  }
  // Each program runs as an instance named like it, as in TwinCAT (MAIN.x).
  for (const TwinCatTask& t : tasks)
    for (const std::string& p : t.programs) put("PROGRAM " + p + " WITH " + t.name + " : " + p + ";\n", t.loc);
  put("END_RESOURCE\nEND_CONFIGURATION\n", tasks.front().loc);
  std::string path = sm.file(tasks.front().loc.file).path;
  return sm.addGenerated(path, std::move(text), std::move(segs));
}

}  // namespace stc::import
