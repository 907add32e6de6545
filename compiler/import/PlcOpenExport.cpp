// PLCopen TC6 XML v2.01 in the form CODESYS writes: interfaces as XML plus
// InterfaceAsPlainText (the exact ST declaration, which CODESYS and stc's
// importer prefer), bodies as CDATA, methods/properties/interfaces/GVLs in
// CODESYS' <addData>.  Texts are slices of the sources, so comments and
// spelling survive the round trip.
#include "import/Import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <ctime>
#include <map>
#include <set>

#include "ast/AST.h"
#include "basic/Text.h"

namespace stc::import {

namespace {

using namespace ast;

constexpr const char* kCodesys = "http://www.3s-software.com/plcopenxml/";

std::string xmlEscape(std::string_view s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string cdata(std::string_view s) {
  std::string o = "<![CDATA[";
  for (size_t i = 0; i < s.size(); ++i) {
    if (s.compare(i, 3, "]]>") == 0) { o += "]]]]><![CDATA[>"; i += 2; continue; }
    o += s[i];
  }
  return o + "]]>";
}

bool isElementary(const std::string& upper) {
  static const std::set<std::string> k = {"BOOL", "BYTE", "WORD", "DWORD", "LWORD", "SINT", "INT", "DINT", "LINT", "USINT",
                                          "UINT", "UDINT", "ULINT", "REAL", "LREAL", "TIME", "DATE", "DT", "TOD", "LTIME",
                                          "DATE_AND_TIME", "TIME_OF_DAY", "CHAR", "WCHAR"};
  return k.count(upper) != 0;
}

// T#1s500ms -> PT1.5S (CODESYS writes task intervals as ISO 8601).
std::string isoDuration(std::string_view lit) {
  std::string s(lit);
  size_t hash = s.find('#');
  if (hash == std::string::npos) return "";
  s = asciiLower(s.substr(hash + 1));
  s.erase(std::remove(s.begin(), s.end(), '_'), s.end());
  double seconds = 0;
  size_t i = 0;
  bool any = false;
  while (i < s.size()) {
    size_t b = i;
    while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.')) ++i;
    if (b == i) return "";
    double v = std::strtod(s.substr(b, i - b).c_str(), nullptr);
    size_t u = i;
    while (i < s.size() && std::isalpha(static_cast<unsigned char>(s[i]))) ++i;
    std::string unit = s.substr(u, i - u);
    static const std::map<std::string, double> f = {{"d", 86400}, {"h", 3600}, {"m", 60}, {"s", 1}, {"ms", 1e-3}, {"us", 1e-6}, {"ns", 1e-9}};
    auto it = f.find(unit);
    if (it == f.end()) return "";
    seconds += v * it->second;
    any = true;
  }
  if (!any) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "PT%.9gS", seconds);
  return buf;
}

class Exporter {
public:
  Exporter(const SourceManager& sm, DiagnosticsEngine& diags) : sm_(sm), diags_(diags) {}

  std::string_view src(uint32_t file, uint32_t b, uint32_t e) const {
    const std::string& t = sm_.file(file).text;
    b = std::min<uint32_t>(b, static_cast<uint32_t>(t.size()));
    e = std::min<uint32_t>(std::max(e, b), static_cast<uint32_t>(t.size()));
    return std::string_view(t).substr(b, e - b);
  }
  std::string_view src(const SourceRange& r) const {
    if (!r.valid()) return {};
    return src(r.begin.file, r.begin.offset, r.end.valid() ? r.end.offset : r.begin.offset);
  }
  void unsupported(SourceRange r, const std::string& what) {
    diags_.error(r.begin, what + " cannot be written as PLCopen XML", "export");
    ok_ = false;
  }

  // ---------------------------------------------------------------- types
  void type(std::string& o, const TypeRef* t, bool strict) {
    if (!t) { o += "<INT/>"; return; }
    std::string name = asciiUpper(t->name.str());
    switch (t->kind) {
      case TypeRef::Named:
        if (t->fbInitArgs) break;
        if (isElementary(name)) { o += "<" + name + "/>"; return; }
        if (name == "STRING" || name == "WSTRING") { o += "<" + asciiLower(name) + "/>"; return; }
        o += "<derived name=\"" + xmlEscape(t->name.str()) + "\"/>";
        return;
      case TypeRef::Sized:
        if (name == "STRING" || name == "WSTRING") {
          o += "<" + asciiLower(name) + " length=\"" + xmlEscape(src(t->size->range)) + "\"/>";
          return;
        }
        break;
      case TypeRef::Array: {
        bool star = false;
        for (const auto& d : t->dims) star = star || d.star;
        if (star) break;
        o += "<array>";
        for (const auto& d : t->dims)
          o += "<dimension lower=\"" + xmlEscape(src(d.lo->range)) + "\" upper=\"" + xmlEscape(src(d.hi->range)) + "\"/>";
        o += "<baseType>";
        type(o, t->element, strict);
        o += "</baseType></array>";
        return;
      }
      case TypeRef::Pointer:
        o += "<pointer><baseType>";
        type(o, t->element, strict);
        o += "</baseType></pointer>";
        return;
      case TypeRef::Subrange: {
        bool unsignedBase = !name.empty() && (name[0] == 'U' || name == "BYTE" || name == "WORD" || name == "DWORD" || name == "LWORD");
        const char* tag = unsignedBase ? "subrangeUnsigned" : "subrangeSigned";
        o += std::string("<") + tag + "><range lower=\"" + xmlEscape(src(t->lo->range)) + "\" upper=\"" + xmlEscape(src(t->hi->range)) +
             "\"/><baseType><" + name + "/></baseType></" + tag + ">";
        return;
      }
      case TypeRef::Enum:
        o += "<enum><values>";
        for (const EnumValueDecl& v : t->enumValues) {
          o += "<value name=\"" + xmlEscape(v.name.name) + "\"";
          if (v.value) o += " value=\"" + xmlEscape(src(v.value->range)) + "\"";
          o += "/>";
        }
        o += "</values>";
        if (!t->name.parts.empty()) {
          o += "<baseType>";
          TypeRef base(TypeRef::Named);
          base.name = t->name;
          type(o, &base, strict);
          o += "</baseType>";
        }
        o += "</enum>";
        return;
      case TypeRef::Struct:
        if (!t->structBase.parts.empty()) break;
        o += "<struct>";
        for (const VarDecl* m : t->members) variable(o, m);
        o += "</struct>";
        return;
      default:
        break;
    }
    // REFERENCE TO, unions, FB_INIT arguments, ARRAY[*]: no TC6 element.
    if (strict) {
      std::string shown(src(t->range));
      size_t nl = shown.find_first_of("\r\n");
      if (nl != std::string::npos) shown = shown.substr(0, nl) + " ...";
      unsupported(t->range, "the type '" + shown + "'");
    }
    o += "<derived name=\"" + xmlEscape(src(t->range)) + "\"/>";
  }

  void variable(std::string& o, const VarDecl* v) {
    o += "<variable name=\"" + xmlEscape(v->name.name) + "\"";
    if (!v->address.empty()) o += " address=\"" + xmlEscape(v->address) + "\"";
    o += "><type>";
    type(o, v->type, false);
    o += "</type>";
    if (v->init) o += "<initialValue><simpleValue value=\"" + xmlEscape(src(v->init->range)) + "\"/></initialValue>";
    if (!v->attributes.empty()) {
      o += "<addData><data name=\"" + std::string(kCodesys) + "attributes\" handleUnknown=\"implementation\"><Attributes>";
      for (const Pragma& p : v->attributes) o += "<Attribute Name=\"" + xmlEscape(p.name) + "\" Value=\"" + xmlEscape(p.value) + "\"/>";
      o += "</Attributes></data></addData>";
    }
    o += "</variable>\n";
  }

  void varBlock(std::string& o, const VarBlock& b, const char* tag) {
    o += std::string("<") + tag;
    if (b.isConstant) o += " constant=\"true\"";
    if (b.isRetain) o += " retain=\"true\"";
    if (b.isNonRetain) o += " nonretain=\"true\"";
    if (b.isPersistent) o += " persistent=\"true\"";
    o += ">\n";
    for (const VarDecl* v : b.vars) variable(o, v);
    o += std::string("</") + tag + ">\n";
  }

  static const char* blockTag(VarSection s) {
    switch (s) {
      case VarSection::Input: return "inputVars";
      case VarSection::Output: return "outputVars";
      case VarSection::InOut: return "inOutVars";
      case VarSection::Temp: return "tempVars";
      case VarSection::External: return "externalVars";
      case VarSection::Global: return "globalVars";
      case VarSection::Access: return "accessVars";
      default: return "localVars";   // VAR, VAR_STAT, VAR_INST (exact in the plain text)
    }
  }

  // ---------------------------------------------------------------- POUs
  // Where the declaration part (header and variable blocks) ends.
  uint32_t declEnd(const PouDecl* p) const {
    uint32_t e = p->name.range.end.offset;
    if (p->returnType) e = std::max(e, p->returnType->range.end.offset);
    e = std::max(e, p->extends.range.end.offset);
    for (const QualifiedName& q : p->implements) e = std::max(e, q.range.end.offset);
    for (const VarBlock& b : p->varBlocks) e = std::max(e, b.range.end.offset);
    return e;
  }

  std::string pragmas(const PouDecl* p) const {
    std::string s;
    for (const Pragma& a : p->attributes)
      s += "{attribute '" + a.name + "'" + (a.value.empty() ? std::string() : " := '" + a.value + "'") + "}\n";
    return s;
  }

  std::string plainText(const PouDecl* p) const {
    return pragmas(p) + std::string(src(p->range.begin.file, p->range.begin.offset, declEnd(p)));
  }

  // The body: between the declaration (and members before the statements)
  // and the members after it / the END keyword.
  std::string bodyText(const PouDecl* p, uint32_t end) const {
    uint32_t b = declEnd(p);
    std::vector<const PouDecl*> members;
    for (auto* v : {&p->methods, &p->properties, &p->actions}) members.insert(members.end(), v->begin(), v->end());
    uint32_t firstStmt = p->body.empty() ? end : p->body.front()->range.begin.offset;
    for (const PouDecl* m : members) {
      if (m->range.begin.offset < b) continue;
      if (m->range.end.offset <= firstStmt) b = std::max(b, m->range.end.offset);
      else end = std::min(end, m->range.begin.offset);
    }
    std::string_view s = src(p->range.begin.file, b, end);
    if (p->pouKind == PouKind::Action) {
      size_t i = s.find_first_not_of(" \t\r\n");
      if (i != std::string_view::npos && s[i] == ':') s.remove_prefix(i + 1);
    }
    // Drop the line end after the declaration and the indentation before END_xxx.
    if (!s.empty() && s.front() == '\r') s.remove_prefix(1);
    if (!s.empty() && s.front() == '\n') s.remove_prefix(1);
    size_t last = s.find_last_of('\n');
    if (last != std::string_view::npos && s.find_first_not_of(" \t\r\n", last) == std::string_view::npos) s = s.substr(0, last + 1);
    return std::string(s);
  }

  // `more`: other <data> elements of the same <addData>.
  void plainTextData(std::string& o, const std::string& text, const std::string& more = {}) {
    o += "<addData><data name=\"" + std::string(kCodesys) +
         "interfaceasplaintext\" handleUnknown=\"implementation\"><InterfaceAsPlainText><xhtml xmlns=\"http://www.w3.org/1999/xhtml\">" +
         xmlEscape(text) + "</xhtml></InterfaceAsPlainText></data>\n" + more + "</addData>\n";
  }

  void interfaceXml(std::string& o, const PouDecl* p, const std::string& plain) {
    o += "<interface>\n";
    if (p->returnType) {
      o += "<returnType>";
      type(o, p->returnType, false);
      o += "</returnType>\n";
    }
    for (const VarBlock& b : p->varBlocks) varBlock(o, b, blockTag(b.section));
    if (!plain.empty()) plainTextData(o, plain);
    o += "</interface>\n";
  }

  void body(std::string& o, const std::string& text) {
    o += "<body><ST><xhtml:p>" + cdata(text) + "</xhtml:p></ST></body>\n";
  }

  uint32_t endOf(const PouDecl* p, size_t keywordLength) const {
    if (p->endRange.valid()) return p->endRange.begin.offset;
    return p->range.end.offset >= keywordLength ? p->range.end.offset - static_cast<uint32_t>(keywordLength) : p->range.end.offset;
  }

  void method(std::string& o, const PouDecl* m, bool prototype) {
    o += "<Method name=\"" + xmlEscape(m->name.parts.back().name) + "\">\n";
    interfaceXml(o, m, plainText(m));
    if (!prototype) body(o, bodyText(m, endOf(m, 10)));
    o += "<addData/></Method>\n";
  }

  void property(std::string& o, const PouDecl* p, bool prototype) {
    o += "<Property name=\"" + xmlEscape(p->name.parts.back().name) + "\">\n";
    interfaceXml(o, p, plainText(p));
    for (const PouDecl* a : {p->getter, p->setter}) {
      if (!a) continue;
      const char* tag = a == p->getter ? "GetAccessor" : "SetAccessor";
      o += std::string("<") + tag + ">\n<interface>\n";
      for (const VarBlock& b : a->varBlocks) varBlock(o, b, blockTag(b.section));
      if (!a->varBlocks.empty())
        plainTextData(o, std::string(src(a->range.begin.file, a->varBlocks.front().range.begin.offset, a->varBlocks.back().range.end.offset)));
      o += "</interface>\n";
      if (!prototype) body(o, bodyText(a, endOf(a, 7)));
      o += std::string("</") + tag + ">\n";
    }
    o += "<addData/></Property>\n";
  }

  void members(std::string& o, const std::vector<const PouDecl*>& ms, bool prototypes, bool wrap = true) {
    std::string m, p;
    for (const PouDecl* d : ms) {
      if (d->pouKind == PouKind::Method) method(m, d, prototypes);
      else if (d->pouKind == PouKind::Property) property(p, d, prototypes);
    }
    if (m.empty() && p.empty()) return;
    if (wrap) o += "<addData>\n";
    if (!m.empty()) o += "<data name=\"" + std::string(kCodesys) + "method\" handleUnknown=\"implementation\">\n" + m + "</data>\n";
    if (!p.empty()) o += "<data name=\"" + std::string(kCodesys) + "property\" handleUnknown=\"implementation\">\n" + p + "</data>\n";
    if (wrap) o += "</addData>\n";
  }

  void pou(const PouDecl* p, const std::vector<const PouDecl*>& outside) {
    const char* kind = p->pouKind == PouKind::Program ? "program" : p->pouKind == PouKind::Function ? "function" : "functionBlock";
    pous_ += "<pou name=\"" + xmlEscape(p->name.str()) + "\" pouType=\"" + kind + "\">\n";
    interfaceXml(pous_, p, plainText(p));
    std::vector<const PouDecl*> ms(p->methods.begin(), p->methods.end());
    ms.insert(ms.end(), p->properties.begin(), p->properties.end());
    std::vector<const PouDecl*> actions(p->actions.begin(), p->actions.end());
    for (const PouDecl* d : outside) (d->pouKind == PouKind::Action ? actions : ms).push_back(d);
    if (!actions.empty()) {
      pous_ += "<actions>\n";
      for (const PouDecl* a : actions) {
        pous_ += "<action name=\"" + xmlEscape(a->name.parts.back().name) + "\">";
        body(pous_, bodyText(a, endOf(a, 10)));
        pous_ += "</action>\n";
      }
      pous_ += "</actions>\n";
    }
    body(pous_, bodyText(p, endOf(p, 0)));
    members(pous_, ms, false);
    pous_ += "</pou>\n";
  }

  void interfaceDecl(const PouDecl* p) {
    addData_ += "<data name=\"" + std::string(kCodesys) + "interface\" handleUnknown=\"implementation\">\n<Interface name=\"" +
                xmlEscape(p->name.str()) + "\">\n";
    std::string plain = pragmas(p) + std::string(src(p->range.begin.file, p->range.begin.offset, declEnd(p)));
    std::vector<const PouDecl*> ms(p->methods.begin(), p->methods.end());
    ms.insert(ms.end(), p->properties.begin(), p->properties.end());
    std::string more;
    members(more, ms, true, false);
    plainTextData(addData_, plain, more);
    addData_ += "</Interface>\n</data>\n";
  }

  void dataType(const TypeDecl* t) {
    types_ += "<dataType name=\"" + xmlEscape(t->name.name) + "\"><baseType>";
    type(types_, t->def, true);
    types_ += "</baseType>";
    if (t->init) types_ += "<initialValue><simpleValue value=\"" + xmlEscape(src(t->init->range)) + "\"/></initialValue>";
    types_ += "</dataType>\n";
  }

  void globals(const GlobalVarDecl* g, unsigned& unnamed) {
    std::string name = g->listName.name.empty() ? "GVL" + (unnamed++ ? std::to_string(unnamed) : std::string()) : g->listName.name;
    addData_ += "<data name=\"" + std::string(kCodesys) + "globalvars\" handleUnknown=\"implementation\">\n<globalVars name=\"" + xmlEscape(name) + "\"";
    const VarBlock& b = g->block;
    if (b.isConstant) addData_ += " constant=\"true\"";
    if (b.isRetain) addData_ += " retain=\"true\"";
    if (b.isNonRetain) addData_ += " nonretain=\"true\"";
    if (b.isPersistent) addData_ += " persistent=\"true\"";
    addData_ += ">\n";
    for (const VarDecl* v : b.vars) variable(addData_, v);
    if (!g->attributes.empty()) {
      addData_ += "<addData><data name=\"" + std::string(kCodesys) + "attributes\" handleUnknown=\"implementation\"><Attributes>";
      for (const Pragma& p : g->attributes) addData_ += "<Attribute Name=\"" + xmlEscape(p.name) + "\" Value=\"" + xmlEscape(p.value) + "\"/>";
      addData_ += "</Attributes></data></addData>\n";
    }
    addData_ += "</globalVars>\n</data>\n";
  }

  void configuration(const ConfigurationDecl* c) {
    if (!c->configVars.empty()) unsupported(c->configVars.front().range, "VAR_CONFIG");
    configs_ += "<configuration name=\"" + xmlEscape(c->name.name) + "\">\n";
    for (const ResourceDecl& r : c->resources) {
      configs_ += "<resource name=\"" + xmlEscape(r.name.name.empty() ? "Application" : r.name.name) + "\">\n";
      for (const TaskDecl& t : r.tasks) {
        configs_ += "<task name=\"" + xmlEscape(t.name.name) + "\"";
        std::string priority = "0";
        for (const TaskDecl::Init& i : t.inits) {
          std::string k = asciiUpper(i.name.name);
          std::string v(src(i.value->range));
          if (k == "INTERVAL") {
            std::string iso = isoDuration(v);
            configs_ += " interval=\"" + xmlEscape(iso.empty() ? v : iso) + "\"";
          } else if (k == "SINGLE") {
            configs_ += " single=\"" + xmlEscape(v) + "\"";
          } else if (k == "PRIORITY") {
            priority = v;
          }
        }
        configs_ += " priority=\"" + xmlEscape(priority) + "\">\n";
        for (const ProgramConfig& p : r.programs)
          if (equalsIgnoreCase(p.task.name, t.name.name)) pouInstance(p);
        configs_ += "</task>\n";
      }
      for (const ProgramConfig& p : r.programs)
        if (p.task.name.empty()) pouInstance(p);
      for (const VarBlock& b : r.globals) varBlock(configs_, b, "globalVars");
      configs_ += "</resource>\n";
    }
    for (const VarBlock& b : c->globals) varBlock(configs_, b, "globalVars");
    configs_ += "</configuration>\n";
  }

  void pouInstance(const ProgramConfig& p) {
    if (!p.args.empty() || p.retain || p.nonRetain) unsupported(p.range, "a program configuration with arguments or RETAIN");
    configs_ += "<pouInstance name=\"" + xmlEscape(p.name.name) + "\" typeName=\"" + xmlEscape(p.type.str()) + "\"/>\n";
  }

  bool run(const ASTContext& ast, const std::vector<uint32_t>& files, const ExportOptions& opts, std::string& xml) {
    std::set<uint32_t> wanted(files.begin(), files.end());
    std::vector<const Decl*> decls;
    for (const SourceUnit& u : const_cast<ASTContext&>(ast).units())
      if (wanted.count(u.file)) decls.insert(decls.end(), u.decls.begin(), u.decls.end());
    // METHOD FB.M / ACTION FB.A written outside their POU.
    std::map<std::string, std::vector<const PouDecl*>> outside;
    for (const Decl* d : decls)
      if (auto* p = dyn_cast<PouDecl>(d))
        if ((p->pouKind == PouKind::Method || p->pouKind == PouKind::Action || p->pouKind == PouKind::Property) && p->name.parts.size() >= 2)
          outside[asciiUpper(p->name.parts.front().name)].push_back(p);
    unsigned unnamed = 0;
    for (const Decl* d : decls) {
      if (auto* t = dyn_cast<TypeDecl>(d)) dataType(t);
      else if (auto* g = dyn_cast<GlobalVarDecl>(d)) globals(g, unnamed);
      else if (auto* c = dyn_cast<ConfigurationDecl>(d)) configuration(c);
      else if (auto* n = dyn_cast<NamespaceDecl>(d)) unsupported(n->range, "NAMESPACE");
      else if (auto* p = dyn_cast<PouDecl>(d)) {
        if (p->pouKind == PouKind::Interface) interfaceDecl(p);
        else if (p->pouKind == PouKind::Program || p->pouKind == PouKind::Function || p->pouKind == PouKind::FunctionBlock)
          pou(p, outside[asciiUpper(p->name.str())]);
      }
    }
    char when[32];
    std::time_t now = std::time(nullptr);
    std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%S", std::gmtime(&now));
    xml = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
          "<project xmlns=\"http://www.plcopen.org/xml/tc6_0201\" xmlns:xhtml=\"http://www.w3.org/1999/xhtml\">\n"
          "<fileHeader companyName=\"\" productName=\"stc\" productVersion=\"" + xmlEscape(opts.productVersion) + "\" creationDateTime=\"" + std::string(when) + "\"/>\n"
          "<contentHeader name=\"" + xmlEscape(opts.projectName) + "\" modificationDateTime=\"" + when + "\">\n"
          "<coordinateInfo><fbd><scaling x=\"1\" y=\"1\"/></fbd><ld><scaling x=\"1\" y=\"1\"/></ld><sfc><scaling x=\"1\" y=\"1\"/></sfc></coordinateInfo>\n"
          "</contentHeader>\n"
          "<types>\n<dataTypes>\n" + types_ + "</dataTypes>\n<pous>\n" + pous_ + "</pous>\n</types>\n"
          "<instances>\n<configurations>\n" + configs_ + "</configurations>\n</instances>\n";
    if (!addData_.empty()) xml += "<addData>\n" + addData_ + "</addData>\n";
    xml += "</project>\n";
    return ok_;
  }

private:
  const SourceManager& sm_;
  DiagnosticsEngine& diags_;
  std::string types_, pous_, configs_, addData_;
  bool ok_ = true;
};

}  // namespace

bool exportPlcOpen(const SourceManager& sm, const ast::ASTContext& ast, const std::vector<uint32_t>& files, DiagnosticsEngine& diags,
                   const ExportOptions& opts, std::string& xml) {
  return Exporter(sm, diags).run(ast, files, opts, xml);
}

}  // namespace stc::import
