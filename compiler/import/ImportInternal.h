// Shared by the importers: the XML document with byte offsets into the file
// as loaded by the SourceManager, and the writer of generated ST text with
// its segment map.
#pragma once

#include <pugixml.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "import/Import.h"

namespace stc::import {

// The local part of an element name ("xhtml:p" -> "p").
std::string_view localName(const pugi::xml_node& n);
// The first child element with local name `name` (case-sensitive, as XML).
pugi::xml_node child(const pugi::xml_node& n, std::string_view name);
// Case-insensitive ASCII comparison.
bool equalsNoCase(std::string_view a, std::string_view b);

// One XML file, parsed with offsets kept (no end-of-line normalisation, so
// offsets into CDATA are offsets into the file).
class XmlFile {
public:
  XmlFile(SourceManager& sm, DiagnosticsEngine& diags) : sm_(sm), diags_(diags) {}
  // Loads and parses `path`; reports unreadable or malformed files.
  bool load(const std::string& path);

  uint32_t file() const { return file_; }
  const std::string& text() const { return sm_.file(file_).text; }
  const std::string& path() const { return sm_.file(file_).path; }
  pugi::xml_node root() const { return doc_.document_element(); }

  // The location of an element's '<', and of an attribute's value.
  SourceLoc at(const pugi::xml_node& n) const;
  SourceLoc attrAt(const pugi::xml_node& n, std::string_view attr) const;
  uint32_t attrOffset(const pugi::xml_node& n, std::string_view attr) const;

  DiagnosticsEngine& diags() { return diags_; }
  SourceManager& sources() { return sm_; }
  // An error at element `n`; the import then reports failure (hadErrors).
  void error(const pugi::xml_node& n, std::string msg, std::string code) {
    diags_.error(at(n), std::move(msg), std::move(code));
    errors_ = true;
  }
  bool hadErrors() const { return errors_; }

private:
  SourceManager& sm_;
  DiagnosticsEngine& diags_;
  bool errors_ = false;
  pugi::xml_document doc_;
  uint32_t file_ = 0;
};

// Generated ST text and where each piece of it comes from.
class StWriter {
public:
  explicit StWriter(const XmlFile& xml) : xml_(xml) {}

  // Text built by the importer, reported at `anchor` (an element/attribute).
  void synth(std::string_view s, SourceLoc anchor);
  void synth(std::string_view s, const pugi::xml_node& n) { synth(s, xml_.at(n)); }
  // A copy of the file's bytes [offset, offset + s.size()).
  void verbatim(std::string_view s, uint32_t offset);
  // An attribute value: verbatim when written without entities.
  void attr(const pugi::xml_node& n, std::string_view name);
  // The character data below `n` (CDATA sections, text with entities decoded,
  // nested elements such as <xhtml:p>), in document order.  Returns false
  // when there is none but whitespace.
  bool text(const pugi::xml_node& n);

  size_t size() const { return out_.size(); }
  const std::string& str() const { return out_; }
  // Whether the last non-blank character written is `c`.
  bool endsWith(char c) const;
  uint32_t finish(SourceManager& sm, const std::string& path);

private:
  const XmlFile& xml_;
  std::string out_;
  std::vector<SourceSegment> segs_;
};

// Whether `n` holds anything but whitespace text.
bool hasContent(const pugi::xml_node& n);
// The first word of ST text after comments, pragmas and blanks ("" if none).
std::string firstKeyword(std::string_view st);

bool importPlcOpen(XmlFile& xml, ImportResult& out);
bool importTwinCat(XmlFile& xml, ImportResult& out);

}  // namespace stc::import
