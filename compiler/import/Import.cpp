// What the importers share: loading XML with offsets, the ST writer with its
// segment map, and the dispatch on the file kind.
#include "import/ImportInternal.h"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace stc::import {

namespace {

std::string lowerExtension(const std::string& path) {
  size_t slash = path.find_last_of("/\\");
  size_t dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '-' || c == '.' ||
         static_cast<unsigned char>(c) >= 0x80;
}

// Decodes one entity at s[i] == '&'; returns its length (0 if malformed).
size_t decodeEntity(std::string_view s, size_t i, std::string& out) {
  size_t semi = s.find(';', i);
  if (semi == std::string_view::npos || semi - i > 12) return 0;
  std::string_view e = s.substr(i + 1, semi - i - 1);
  if (e == "lt") out.append(1, '<');
  else if (e == "gt") out.append(1, '>');
  else if (e == "amp") out.append(1, '&');
  else if (e == "quot") out.append(1, '"');
  else if (e == "apos") out.append(1, '\'');
  else if (!e.empty() && e[0] == '#') {
    unsigned long cp = 0;
    bool hex = e.size() > 1 && (e[1] == 'x' || e[1] == 'X');
    std::string digits(e.substr(hex ? 2 : 1));
    if (digits.empty()) return 0;
    char* end = nullptr;
    cp = std::strtoul(digits.c_str(), &end, hex ? 16 : 10);
    if (*end || cp > 0x10FFFF) return 0;
    char buf[4];
    size_t n;
    if (cp < 0x80) { buf[0] = static_cast<char>(cp); n = 1; }
    else if (cp < 0x800) { buf[0] = static_cast<char>(0xC0 | (cp >> 6)); buf[1] = static_cast<char>(0x80 | (cp & 0x3F)); n = 2; }
    else if (cp < 0x10000) {
      buf[0] = static_cast<char>(0xE0 | (cp >> 12)); buf[1] = static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      buf[2] = static_cast<char>(0x80 | (cp & 0x3F)); n = 3;
    } else {
      buf[0] = static_cast<char>(0xF0 | (cp >> 18)); buf[1] = static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      buf[2] = static_cast<char>(0x80 | ((cp >> 6) & 0x3F)); buf[3] = static_cast<char>(0x80 | (cp & 0x3F)); n = 4;
    }
    out.append(buf, n);
  } else {
    return 0;
  }
  return semi - i + 1;
}

}  // namespace

FileKind kindOf(const std::string& path) {
  std::string ext = lowerExtension(path);
  if (ext == ".xml") return FileKind::PlcOpen;
  if (ext == ".tcpou" || ext == ".tcgvl" || ext == ".tcdut" || ext == ".tcio" || ext == ".tctto") return FileKind::TwinCat;
  if (ext == ".plcproj") return FileKind::TwinCatProject;
  return FileKind::None;
}

std::string_view localName(const pugi::xml_node& n) {
  std::string_view s = n.name();
  size_t colon = s.find(':');
  return colon == std::string_view::npos ? s : s.substr(colon + 1);
}

pugi::xml_node child(const pugi::xml_node& n, std::string_view name) {
  for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling())
    if (c.type() == pugi::node_element && localName(c) == name) return c;
  return {};
}

bool equalsNoCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

bool XmlFile::load(const std::string& path) {
  std::string error;
  file_ = sm_.loadFile(path, error);
  if (!file_) {
    diags_.error(SourceLoc{}, path + ": " + error, "input");
    return false;
  }
  const std::string& t = sm_.file(file_).text;
  // No end-of-line normalisation: CDATA must keep the file's bytes so that
  // offsets into it are offsets into the file.  The SourceManager has already
  // dropped a BOM and converted Latin-1, so pugixml sees what offsets count.
  unsigned flags = (pugi::parse_full & ~pugi::parse_eol & ~pugi::parse_wconv_attribute);
  pugi::xml_parse_result r = doc_.load_buffer(t.data(), t.size(), flags, pugi::encoding_utf8);
  if (!r) {
    uint32_t at = static_cast<uint32_t>(std::clamp<ptrdiff_t>(r.offset, 0, static_cast<ptrdiff_t>(t.size())));
    std::string what = r.status == pugi::status_no_document_element ? "no root element" : r.description();
    for (char& c : what) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    diags_.error(SourceLoc{file_, at}, "malformed XML: " + what, "xml");
    return false;
  }
  return true;
}

SourceLoc XmlFile::at(const pugi::xml_node& n) const {
  ptrdiff_t o = n.offset_debug();
  if (o < 0) return SourceLoc{file_, 0};
  // Elements report the offset of their name: point at the '<'.
  if (n.type() == pugi::node_element && o > 0) --o;
  return SourceLoc{file_, static_cast<uint32_t>(o)};
}

uint32_t XmlFile::attrOffset(const pugi::xml_node& n, std::string_view attr) const {
  ptrdiff_t o = n.offset_debug();
  const std::string& t = text();
  if (o < 0) return 0;
  size_t i = static_cast<size_t>(o);
  while (i < t.size() && isNameChar(t[i])) ++i;   // the element's name
  while (i < t.size()) {
    while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
    if (i >= t.size() || t[i] == '>' || t[i] == '/') break;
    size_t nb = i;
    while (i < t.size() && isNameChar(t[i])) ++i;
    std::string_view name(t.data() + nb, i - nb);
    while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
    if (i >= t.size() || t[i] != '=') break;
    ++i;
    while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
    if (i >= t.size() || (t[i] != '"' && t[i] != '\'')) break;
    char q = t[i++];
    if (name == attr) return static_cast<uint32_t>(i);
    size_t close = t.find(q, i);
    if (close == std::string::npos) break;
    i = close + 1;
  }
  return static_cast<uint32_t>(n.offset_debug() > 0 ? n.offset_debug() - 1 : 0);
}

SourceLoc XmlFile::attrAt(const pugi::xml_node& n, std::string_view attr) const {
  return SourceLoc{file_, attrOffset(n, attr)};
}

void StWriter::synth(std::string_view s, SourceLoc anchor) {
  if (s.empty()) return;
  uint32_t here = static_cast<uint32_t>(out_.size());
  const SourceSegment* last = segs_.empty() ? nullptr : &segs_.back();
  if (!(last && !last->verbatim && last->file == anchor.file && last->offset == anchor.offset))
    segs_.push_back(SourceSegment{here, anchor.file, anchor.offset, false});
  out_.append(s);
}

void StWriter::verbatim(std::string_view s, uint32_t offset) {
  if (s.empty()) return;
  uint32_t here = static_cast<uint32_t>(out_.size());
  const SourceSegment* last = segs_.empty() ? nullptr : &segs_.back();
  // Adjacent copies of adjacent bytes stay one piece.
  if (!(last && last->verbatim && last->file == xml_.file() && last->offset + (here - last->genBegin) == offset))
    segs_.push_back(SourceSegment{here, xml_.file(), offset, true});
  out_.append(s);
}

void StWriter::attr(const pugi::xml_node& n, std::string_view name) {
  std::string_view value = n.attribute(std::string(name).c_str()).value();
  uint32_t off = xml_.attrOffset(n, name);
  const std::string& t = xml_.text();
  if (t.compare(off, value.size(), value) == 0) verbatim(value, off);
  else synth(value, SourceLoc{xml_.file(), off});
}

bool StWriter::text(const pugi::xml_node& n) {
  bool any = false;
  const std::string& t = xml_.text();
  for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling()) {
    if (c.type() == pugi::node_cdata) {
      std::string_view v = c.value();
      ptrdiff_t o = c.offset_debug();
      if (o >= 0 && t.compare(static_cast<size_t>(o), v.size(), v) == 0) verbatim(v, static_cast<uint32_t>(o));
      else synth(v, xml_.at(c));
      any = any || v.find_first_not_of(" \t\r\n") != std::string_view::npos;
    } else if (c.type() == pugi::node_pcdata) {
      // Decode from the file's bytes so that each run between entities is a
      // verbatim piece.
      ptrdiff_t o = c.offset_debug();
      std::string_view v = c.value();
      any = any || v.find_first_not_of(" \t\r\n") != std::string_view::npos;
      if (o < 0) { synth(v, xml_.at(n)); continue; }
      size_t i = static_cast<size_t>(o), run = i;
      while (i < t.size() && t[i] != '<') {
        if (t[i] != '&') { ++i; continue; }
        verbatim(std::string_view(t).substr(run, i - run), static_cast<uint32_t>(run));
        std::string decoded;
        size_t len = decodeEntity(t, i, decoded);
        if (!len) {
          decoded.assign(1, '&');   // a stray '&' (pugixml keeps it as is)
          len = 1;
        }
        synth(decoded, SourceLoc{xml_.file(), static_cast<uint32_t>(i)});
        i += len;
        run = i;
      }
      verbatim(std::string_view(t).substr(run, i - run), static_cast<uint32_t>(run));
    } else if (c.type() == pugi::node_element) {
      // <xhtml:p>, <xhtml>, <br/>: formatting of the text, not separate text.
      if (localName(c) == "br") synth("\n", xml_.at(c));
      else any = text(c) || any;
    }
  }
  return any;
}

bool StWriter::endsWith(char c) const {
  size_t i = out_.find_last_not_of(" \t\r\n");
  return i != std::string::npos && out_[i] == c;
}

uint32_t StWriter::finish(SourceManager& sm, const std::string& path) {
  return sm.addGenerated(path, std::move(out_), std::move(segs_));
}

bool hasContent(const pugi::xml_node& n) {
  for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling()) {
    if (c.type() == pugi::node_element) return true;
    if ((c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) &&
        std::string_view(c.value()).find_first_not_of(" \t\r\n") != std::string_view::npos)
      return true;
  }
  return false;
}

std::string firstKeyword(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    char c = s[i];
    if (std::isspace(static_cast<unsigned char>(c))) { ++i; continue; }
    if (s.compare(i, 2, "//") == 0) { i = s.find('\n', i); if (i == std::string_view::npos) return ""; continue; }
    if (s.compare(i, 2, "(*") == 0) {
      // Comments nest in CODESYS.
      int depth = 0;
      while (i < s.size()) {
        if (s.compare(i, 2, "(*") == 0) { ++depth; i += 2; }
        else if (s.compare(i, 2, "*)") == 0) { i += 2; if (--depth == 0) break; }
        else ++i;
      }
      continue;
    }
    if (s.compare(i, 2, "/*") == 0) { i = s.find("*/", i + 2); if (i == std::string_view::npos) return ""; i += 2; continue; }
    if (c == '{') { i = s.find('}', i); if (i == std::string_view::npos) return ""; ++i; continue; }
    size_t b = i;
    while (i < s.size() && (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_')) ++i;
    std::string w(s.substr(b, i - b));
    for (char& ch : w) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    return w;
  }
  return "";
}

bool importFile(SourceManager& sm, DiagnosticsEngine& diags, const std::string& path, ImportResult& out) {
  XmlFile xml(sm, diags);
  if (!xml.load(path)) return false;
  switch (kindOf(path)) {
    case FileKind::PlcOpen: return importPlcOpen(xml, out);
    case FileKind::TwinCat: return importTwinCat(xml, out);
    default:
      diags.error(SourceLoc{xml.file(), 0}, "not a file stc can import", "input");
      return false;
  }
}

}  // namespace stc::import
