// PLCopen TC6 XML v2.00/v2.01: data types, POUs with ST bodies, global
// variable lists and configurations become ST.  Declarations given as XML are
// written out as ST with each piece pointing at its element or attribute; ST
// text (bodies, CODESYS InterfaceAsPlainText) is copied verbatim.
#include "import/ImportInternal.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>

namespace stc::import {

namespace {

constexpr std::string_view kCodesys = "http://www.3s-software.com/plcopenxml/";

// The TC6 elementary type elements (also accepted: any other element name is
// written as a type name, so sema judges it).
bool isStringTag(std::string_view t) { return t == "string" || t == "wstring"; }

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

// ISO 8601 durations (PT0.01S, as CODESYS writes task intervals) and IEC
// literals (T#10ms, as Beremiz writes them), as an IEC literal.
std::string iecDuration(std::string_view s) {
  if (s.size() > 2 && (s[0] == 'T' || s[0] == 't') && s[1] == '#') return "T#" + std::string(s.substr(2));
  if (s.size() > 5 && (s.substr(0, 5) == "TIME#" || s.substr(0, 5) == "time#")) return "T#" + std::string(s.substr(5));
  if (s.empty() || s[0] != 'P') return "";
  double seconds = 0;
  bool inTime = false;
  size_t i = 1;
  while (i < s.size()) {
    if (s[i] == 'T') { inTime = true; ++i; continue; }
    size_t b = i;
    while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.')) ++i;
    if (b == i || i >= s.size()) return "";
    double v = std::strtod(std::string(s.substr(b, i - b)).c_str(), nullptr);
    char u = s[i++];
    if (u == 'D' && !inTime) seconds += v * 86400;
    else if (u == 'H' && inTime) seconds += v * 3600;
    else if (u == 'M' && inTime) seconds += v * 60;
    else if (u == 'S' && inTime) seconds += v;
    else return "";
  }
  auto us = static_cast<long long>(std::llround(seconds * 1e6));
  if (us % 1000 == 0) return "T#" + std::to_string(us / 1000) + "ms";
  return "T#" + std::to_string(us) + "us";
}

class PlcOpenImporter {
public:
  PlcOpenImporter(XmlFile& xml, ImportResult& out) : xml_(xml), w_(xml), out_(out) {}

  bool run() {
    pugi::xml_node root = xml_.root();
    if (!checkRoot(root)) return false;
    pugi::xml_node types = child(root, "types");
    if (pugi::xml_node dts = child(types, "dataTypes"))
      for (pugi::xml_node d : dts.children())
        if (d.type() == pugi::node_element && localName(d) == "dataType") dataType(d);
    // CODESYS keeps interfaces and global variable lists in <addData>, at
    // project level or below the resource they belong to.
    std::function<void(pugi::xml_node)> walk = [&](pugi::xml_node n) {
      for (pugi::xml_node c : n.children()) {
        if (c.type() != pugi::node_element) continue;
        std::string_view k = localName(c);
        if (k == "pou" || k == "dataType") continue;
        if (k == "data") {
          std::string_view dn = c.attribute("name").value();
          if (dn == std::string(kCodesys) + "interface") {
            for (pugi::xml_node i : c.children())
              if (i.type() == pugi::node_element && localName(i) == "Interface") interfaceDecl(i);
            continue;
          }
          if (dn == std::string(kCodesys) + "globalvars") {
            for (pugi::xml_node g : c.children())
              if (g.type() == pugi::node_element && localName(g) == "globalVars") globalList(g);
            continue;
          }
        }
        walk(c);
      }
    };
    walk(root);
    if (pugi::xml_node pous = child(types, "pous"))
      for (pugi::xml_node p : pous.children())
        if (p.type() == pugi::node_element && localName(p) == "pou") pou(p);
    if (pugi::xml_node cfgs = child(child(root, "instances"), "configurations"))
      for (pugi::xml_node c : cfgs.children())
        if (c.type() == pugi::node_element && localName(c) == "configuration") configuration(c);
    if (w_.size()) out_.file = w_.finish(xml_.sources(), xml_.path());
    return !xml_.hadErrors();
  }

private:
  void error(const pugi::xml_node& n, std::string msg, std::string code) { xml_.error(n, std::move(msg), std::move(code)); }

  bool checkRoot(const pugi::xml_node& root) {
    std::string ns;
    for (pugi::xml_attribute a : root.attributes()) {
      std::string_view an = a.name();
      if (an == "xmlns" || (an.rfind("xmlns:", 0) == 0 && an.substr(6) == std::string_view(root.name()).substr(0, an.size() - 6)))
        ns = a.value();
    }
    if (localName(root) != "project") {
      error(root, "not a PLCopen XML file: the root element is <" + std::string(root.name()) + ">, not <project>", "import");
      return false;
    }
    if (ns != "http://www.plcopen.org/xml/tc6_0201" && ns != "http://www.plcopen.org/xml/tc6_0200") {
      error(root, ns.empty() ? "not a PLCopen XML file: <project> has no namespace (http://www.plcopen.org/xml/tc6_0201)"
                             : "PLCopen XML namespace '" + ns + "' is not supported (tc6_0200 and tc6_0201 are)", "import");
      return false;
    }
    return true;
  }

  // The <data name=".../NAME"> below `n`'s <addData>.
  pugi::xml_node data(const pugi::xml_node& n, std::string_view name) {
    std::string full = std::string(kCodesys) + std::string(name);
    for (pugi::xml_node ad : n.children())
      if (ad.type() == pugi::node_element && localName(ad) == "addData")
        for (pugi::xml_node d : ad.children())
          if (d.type() == pugi::node_element && localName(d) == "data" && full == d.attribute("name").value()) return d;
    return {};
  }

  // CODESYS' declaration as plain ST text, in <addData> of the element or
  // of its <interface>.
  pugi::xml_node plainText(const pugi::xml_node& n) {
    for (pugi::xml_node at : {n, child(n, "interface")}) {
      pugi::xml_node d = data(at, "interfaceasplaintext");
      if (pugi::xml_node t = child(d, "InterfaceAsPlainText")) return t;
    }
    return {};
  }

  // ---------------------------------------------------------------- types
  void type(const pugi::xml_node& holder) {
    pugi::xml_node t;
    for (pugi::xml_node c : holder.children())
      if (c.type() == pugi::node_element && localName(c) != "documentation" && localName(c) != "addData") { t = c; break; }
    if (!t) {
      error(holder, "<" + std::string(holder.name()) + "> names no type", "import");
      w_.synth("INT", holder);
      return;
    }
    std::string_view k = localName(t);
    if (isStringTag(k)) {
      w_.synth(upper(k), t);
      if (t.attribute("length")) {
        w_.synth("(", t);
        w_.attr(t, "length");
        w_.synth(")", t);
      }
    } else if (k == "derived") {
      w_.attr(t, "name");
    } else if (k == "array") {
      w_.synth("ARRAY[", t);
      bool first = true;
      for (pugi::xml_node d : t.children()) {
        if (d.type() != pugi::node_element || localName(d) != "dimension") continue;
        if (!first) w_.synth(", ", d);
        first = false;
        w_.attr(d, "lower");
        w_.synth("..", d);
        w_.attr(d, "upper");
      }
      if (first) error(t, "<array> without <dimension>", "import");
      w_.synth("] OF ", t);
      type(child(t, "baseType"));
    } else if (k == "pointer") {
      w_.synth("POINTER TO ", t);
      type(child(t, "baseType"));
    } else if (k == "subrangeSigned" || k == "subrangeUnsigned") {
      type(child(t, "baseType"));
      pugi::xml_node r = child(t, "range");
      w_.synth("(", r);
      w_.attr(r, "lower");
      w_.synth("..", r);
      w_.attr(r, "upper");
      w_.synth(")", r);
    } else if (k == "enum") {
      w_.synth("(", t);
      bool first = true;
      for (pugi::xml_node v : child(t, "values").children()) {
        if (v.type() != pugi::node_element || localName(v) != "value") continue;
        if (!first) w_.synth(", ", v);
        first = false;
        w_.attr(v, "name");
        if (v.attribute("value")) {
          w_.synth(" := ", v);
          w_.attr(v, "value");
        }
      }
      w_.synth(")", t);
      if (pugi::xml_node b = child(t, "baseType")) {
        w_.synth(" ", b);
        type(b);
      }
    } else if (k == "struct") {
      w_.synth("STRUCT\n", t);
      variables(t);
      w_.synth("END_STRUCT", t);
    } else {
      // Elementary types (<INT/>, <LREAL/>, <TIME/> ...); a name sema does
      // not know is reported there as an unknown type.
      w_.synth(upper(k), t);
    }
  }

  void value(const pugi::xml_node& holder) {
    pugi::xml_node v;
    for (pugi::xml_node c : holder.children())
      if (c.type() == pugi::node_element && localName(c) != "documentation" && localName(c) != "addData") { v = c; break; }
    std::string_view k = v ? localName(v) : "";
    if (k == "simpleValue") {
      w_.attr(v, "value");
    } else if (k == "arrayValue") {
      w_.synth("[", v);
      bool first = true;
      for (pugi::xml_node e : v.children()) {
        if (e.type() != pugi::node_element || localName(e) != "value") continue;
        if (!first) w_.synth(", ", e);
        first = false;
        if (e.attribute("repetitionValue")) {
          w_.attr(e, "repetitionValue");
          w_.synth("(", e);
          value(e);
          w_.synth(")", e);
        } else {
          value(e);
        }
      }
      w_.synth("]", v);
    } else if (k == "structValue") {
      w_.synth("(", v);
      bool first = true;
      for (pugi::xml_node e : v.children()) {
        if (e.type() != pugi::node_element || localName(e) != "value") continue;
        if (!first) w_.synth(", ", e);
        first = false;
        w_.attr(e, "member");
        w_.synth(" := ", e);
        value(e);
      }
      w_.synth(")", v);
    } else {
      error(v ? v : holder, "<" + std::string(holder.name()) + "> holds no simpleValue, arrayValue or structValue", "import");
      w_.synth("0", holder);
    }
  }

  // {attribute ...} pragmas from CODESYS' <Attributes> in <addData>.
  void attributes(const pugi::xml_node& n) {
    pugi::xml_node as = child(data(n, "attributes"), "Attributes");
    for (pugi::xml_node a : as.children()) {
      if (a.type() != pugi::node_element || localName(a) != "Attribute") continue;
      w_.synth("{attribute '", a);
      w_.attr(a, "Name");
      std::string_view v = a.attribute("Value").value();
      if (!v.empty()) {
        w_.synth("' := '", a);
        w_.attr(a, "Value");
      }
      w_.synth("'}\n", a);
    }
  }

  void variable(const pugi::xml_node& v) {
    attributes(v);
    w_.attr(v, "name");
    if (v.attribute("address")) {
      w_.synth(" AT ", v);
      w_.attr(v, "address");
    }
    w_.synth(" : ", v);
    type(child(v, "type"));
    if (pugi::xml_node iv = child(v, "initialValue")) {
      w_.synth(" := ", iv);
      value(iv);
    }
    w_.synth(";\n", v);
  }

  void variables(const pugi::xml_node& holder) {
    for (pugi::xml_node v : holder.children())
      if (v.type() == pugi::node_element && localName(v) == "variable") variable(v);
  }

  void varBlock(const pugi::xml_node& b, const char* kw) {
    w_.synth(kw, b);
    if (b.attribute("constant").as_bool()) w_.synth(" CONSTANT", b);
    if (b.attribute("retain").as_bool()) w_.synth(" RETAIN", b);
    if (b.attribute("nonretain").as_bool()) w_.synth(" NON_RETAIN", b);
    if (b.attribute("persistent").as_bool()) w_.synth(" PERSISTENT", b);
    w_.synth("\n", b);
    variables(b);
    w_.synth("END_VAR\n", b);
  }

  // The variable blocks of an <interface>, in document order.
  void interfaceBlocks(const pugi::xml_node& itf) {
    static const std::pair<const char*, const char*> kBlocks[] = {
        {"inputVars", "VAR_INPUT"}, {"outputVars", "VAR_OUTPUT"}, {"inOutVars", "VAR_IN_OUT"},
        {"localVars", "VAR"},       {"tempVars", "VAR_TEMP"},     {"externalVars", "VAR_EXTERNAL"},
        {"globalVars", "VAR_GLOBAL"}, {"accessVars", "VAR_ACCESS"}};
    for (pugi::xml_node b : itf.children()) {
      if (b.type() != pugi::node_element) continue;
      std::string_view k = localName(b);
      bool known = false;
      for (const auto& [tag, kw] : kBlocks)
        if (k == tag) { varBlock(b, kw); known = true; }
      if (!known && k != "returnType" && k != "documentation" && k != "addData")
        xml_.diags().warning(xml_.at(b), "<" + std::string(b.name()) + "> is not supported; it is ignored", "import-ignored");
    }
  }

  // A declaration head: CODESYS' plain text when present, else `head` and
  // the interface written from XML.
  void declaration(const pugi::xml_node& n, const std::string& kw, bool returns) {
    if (pugi::xml_node t = plainText(n)) {
      w_.text(t);
      w_.synth("\n", t);
      return;
    }
    pugi::xml_node itf = child(n, "interface");
    attributes(n);
    w_.synth(kw + " ", n);
    w_.attr(n, "name");
    if (returns) {
      if (pugi::xml_node rt = child(itf, "returnType")) {
        w_.synth(" : ", rt);
        type(rt);
      } else if (kw == "FUNCTION" || kw == "PROPERTY") {
        error(itf ? itf : n, "'" + std::string(n.attribute("name").value()) + "' has no <returnType>", "import");
      }
    }
    w_.synth("\n", n);
    interfaceBlocks(itf);
  }

  // A <body>: ST, or an error naming the language.
  void body(const pugi::xml_node& holder, const std::string& what) {
    pugi::xml_node b = child(holder, "body");
    for (pugi::xml_node l : b.children()) {
      if (l.type() != pugi::node_element) continue;
      std::string_view lang = localName(l);
      if (lang == "documentation" || lang == "addData") continue;
      if (lang == "ST") {
        w_.text(l);
        w_.synth("\n", l);
      } else {
        error(l, what + " is written in " + std::string(lang) + "; only ST bodies are supported", "unsupported-language");
      }
      return;
    }
  }

  bool isSfc(const pugi::xml_node& holder) { return bool(child(child(holder, "body"), "SFC")); }

  void method(const pugi::xml_node& m, const std::string& owner, bool prototype) {
    declaration(m, "METHOD", true);
    if (!prototype) body(m, "method '" + owner + "." + m.attribute("name").value() + "'");
    w_.synth("END_METHOD\n", m);
  }

  void property(const pugi::xml_node& p, const std::string& owner, bool prototype) {
    declaration(p, "PROPERTY", true);
    for (const char* acc : {"GetAccessor", "SetAccessor"}) {
      pugi::xml_node a = child(p, acc);
      if (!a) continue;
      bool get = acc == std::string("GetAccessor");
      w_.synth(get ? "GET\n" : "SET\n", a);
      // An accessor's plain text may repeat the PROPERTY line: then its
      // variables come from the XML interface.
      pugi::xml_node t = plainText(a);
      std::string head = t ? firstKeyword(t.child_value()) : "";
      if (t && head != "PROPERTY" && head != "") {
        w_.text(t);
        w_.synth("\n", t);
      } else {
        interfaceBlocks(child(a, "interface"));
      }
      if (!prototype) body(a, "property '" + owner + "." + p.attribute("name").value() + "'");
      w_.synth(get ? "END_GET\n" : "END_SET\n", a);
    }
    w_.synth("END_PROPERTY\n", p);
  }

  void action(const pugi::xml_node& a, const std::string& owner) {
    w_.synth("ACTION ", a);
    w_.attr(a, "name");
    w_.synth(":\n", a);
    body(a, "action '" + owner + "." + a.attribute("name").value() + "'");
    w_.synth("END_ACTION\n", a);
  }

  // CODESYS methods, properties and actions (and interface members).
  void codesysMembers(const pugi::xml_node& n, const std::string& owner, bool prototypes) {
    for (pugi::xml_node ad : n.children())
    for (pugi::xml_node d : ad.children()) {
      if (localName(ad) != "addData" || d.type() != pugi::node_element || localName(d) != "data") continue;
      std::string_view dn = d.attribute("name").value();
      if (dn.rfind(kCodesys, 0) != 0) continue;
      dn.remove_prefix(kCodesys.size());
      for (pugi::xml_node m : d.children()) {
        if (m.type() != pugi::node_element) continue;
        if (dn == "method" && localName(m) == "Method") method(m, owner, prototypes);
        else if (dn == "property" && localName(m) == "Property") property(m, owner, prototypes);
        else if (dn == "action" && localName(m) == "Action" && !prototypes) action(m, owner);
      }
    }
  }

  void pou(const pugi::xml_node& n) {
    std::string name = n.attribute("name").value();
    std::string_view kind = n.attribute("pouType").value();
    const char* kw = kind == "program" ? "PROGRAM" : kind == "functionBlock" ? "FUNCTION_BLOCK" : kind == "function" ? "FUNCTION" : nullptr;
    if (!kw) {
      error(n, "POU '" + name + "' has pouType '" + std::string(kind) + "'; expected program, functionBlock or function", "import");
      return;
    }
    declaration(n, kw, kind == "function");
    // A body in another language is reported; the interface stays declared,
    // so the POUs that use it are still checked.
    body(n, "POU '" + name + "'");
    for (pugi::xml_node a : child(n, "actions").children())
      if (a.type() == pugi::node_element && localName(a) == "action") action(a, name);
    if (!isSfc(n))
      for (pugi::xml_node t : child(n, "transitions").children())
        if (t.type() == pugi::node_element && localName(t) == "transition")
          error(t, "transition '" + std::string(t.attribute("name").value()) + "' of '" + name + "' belongs to SFC, which is not supported",
                "unsupported-language");
    codesysMembers(n, name, false);
    w_.synth(std::string("END_") + kw + "\n", n);
  }

  void interfaceDecl(const pugi::xml_node& n) {
    if (pugi::xml_node t = plainText(n)) {
      w_.text(t);
      w_.synth("\n", t);
    } else {
      w_.synth("INTERFACE ", n);
      w_.attr(n, "name");
      w_.synth("\n", n);
    }
    codesysMembers(n, n.attribute("name").value(), true);
    w_.synth("END_INTERFACE\n", n);
  }

  void dataType(const pugi::xml_node& n) {
    pugi::xml_node base = child(n, "baseType");
    w_.synth("TYPE ", n);
    w_.attr(n, "name");
    w_.synth(" : ", n);
    type(base);
    if (pugi::xml_node iv = child(n, "initialValue")) {
      w_.synth(" := ", iv);
      value(iv);
    }
    w_.synth(";\nEND_TYPE\n", n);
  }

  // A named global variable list (GVL.x).
  void globalList(const pugi::xml_node& g) {
    uint32_t begin = static_cast<uint32_t>(w_.size());
    attributes(g);
    varBlock(g, "VAR_GLOBAL");
    out_.globals.push_back({begin, static_cast<uint32_t>(w_.size()), g.attribute("name").value()});
  }

  void task(const pugi::xml_node& t) {
    w_.synth("TASK ", t);
    w_.attr(t, "name");
    w_.synth("(", t);
    std::string sep;
    if (pugi::xml_attribute iv = t.attribute("interval")) {
      std::string lit = iecDuration(iv.value());
      if (lit.empty()) error(t, "task interval '" + std::string(iv.value()) + "' is neither T#... nor an ISO 8601 duration", "import");
      w_.synth("INTERVAL := " + (lit.empty() ? std::string("T#0ms") : lit), xml_.attrAt(t, "interval"));
      sep = ", ";
    }
    if (t.attribute("single")) {
      w_.synth(sep + "SINGLE := ", t);
      w_.attr(t, "single");
      sep = ", ";
    }
    w_.synth(sep + "PRIORITY := ", t);
    if (t.attribute("priority")) w_.attr(t, "priority");
    else w_.synth("0", t);
    w_.synth(");\n", t);
  }

  void pouInstance(const pugi::xml_node& p, const pugi::xml_node* task) {
    w_.synth("PROGRAM ", p);
    w_.attr(p, "name");
    if (task) {
      w_.synth(" WITH ", p);
      w_.attr(*task, "name");
    }
    w_.synth(" : ", p);
    // CODESYS leaves typeName empty: the instance is named like its program.
    w_.attr(p, std::string_view(p.attribute("typeName").value()).empty() ? "name" : "typeName");
    w_.synth(";\n", p);
  }

  void globalBlocks(const pugi::xml_node& n) {
    for (pugi::xml_node g : n.children())
      if (g.type() == pugi::node_element && localName(g) == "globalVars") varBlock(g, "VAR_GLOBAL");
  }

  void configuration(const pugi::xml_node& c) {
    w_.synth("CONFIGURATION ", c);
    w_.attr(c, "name");
    w_.synth("\n", c);
    globalBlocks(c);
    bool any = false;
    for (pugi::xml_node r : c.children()) {
      if (r.type() != pugi::node_element || localName(r) != "resource") continue;
      any = true;
      w_.synth("RESOURCE ", r);
      w_.attr(r, "name");
      w_.synth(" ON PLC\n", r);
      globalBlocks(r);
      for (pugi::xml_node t : r.children())
        if (t.type() == pugi::node_element && localName(t) == "task") task(t);
      for (pugi::xml_node t : r.children())
        if (t.type() == pugi::node_element && localName(t) == "task")
          for (pugi::xml_node p : t.children())
            if (p.type() == pugi::node_element && localName(p) == "pouInstance") pouInstance(p, &t);
      for (pugi::xml_node p : r.children())
        if (p.type() == pugi::node_element && localName(p) == "pouInstance") pouInstance(p, nullptr);
      w_.synth("END_RESOURCE\n", r);
    }
    if (!any) error(c, "configuration '" + std::string(c.attribute("name").value()) + "' has no <resource>", "import");
    w_.synth("END_CONFIGURATION\n", c);
  }

  XmlFile& xml_;
  StWriter w_;
  ImportResult& out_;
};

}  // namespace

bool importPlcOpen(XmlFile& xml, ImportResult& out) { return PlcOpenImporter(xml, out).run(); }

}  // namespace stc::import
