// Source buffers and positions.  A SourceLoc is a (file, byte offset) pair;
// line and column are computed on demand, so AST nodes stay small.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace stc {

struct SourceLoc {
  uint32_t file = 0;      // 0 = no location
  uint32_t offset = 0;    // byte offset in the (normalised) buffer
  bool valid() const { return file != 0; }
};

struct SourceRange {
  SourceLoc begin, end;   // end is exclusive
  SourceRange() = default;
  SourceRange(SourceLoc b, SourceLoc e) : begin(b), end(e) {}
  explicit SourceRange(SourceLoc b) : begin(b), end(b) {}
  bool valid() const { return begin.valid(); }
};

// Generated buffers (files imported from XML): a piece of the generated text
// starting at `genBegin` comes from `file` at `offset`.  A verbatim piece is a
// byte-for-byte copy (ST text inside CDATA), so offsets map one to one; a
// synthesized piece (keywords, declarations built from XML elements) maps
// every offset to `offset`, the element or attribute it was built from.
struct SourceSegment {
  uint32_t genBegin = 0;
  uint32_t file = 0;
  uint32_t offset = 0;
  bool verbatim = false;
};

struct LineCol {
  unsigned line = 0;      // 1-based
  unsigned col = 0;       // 1-based, in bytes (as clang); in characters for Latin-1 files
};

// One loaded file.  `text` is UTF-8 with the original line ends; Latin-1
// input is converted on load.  Full-width punctuation is rewritten in place
// by the lexer driver with byte-preserving padding, so offsets never move.
struct SourceFile {
  uint32_t id = 0;
  std::string path;
  std::string text;
  std::string original;      // the text before full-width rewriting, if any (shown in diagnostics)
  bool convertedFromLatin1 = false;
  bool library = false;      // a library built into stc (standard FBs, motion): its types keep 8-byte pointers
  std::vector<uint32_t> lineStarts;  // filled lazily
  // Non-empty for generated buffers: sorted by genBegin, the first at 0.
  std::vector<SourceSegment> segments;
};

class SourceManager {
public:
  SourceManager();
  ~SourceManager();

  // Reads a file; returns 0 and sets `error` if it cannot be read.
  uint32_t loadFile(const std::string& path, std::string& error);
  // Adds an in-memory buffer (tests, fuzzing, generated code).
  uint32_t addBuffer(std::string path, std::string bytes);
  // Adds generated ST text whose locations are reported in other files
  // (imported XML) through `segments`.  The text is taken as is (UTF-8).
  uint32_t addGenerated(std::string path, std::string text, std::vector<SourceSegment> segments);

  // Where a location of a generated buffer comes from; other locations are
  // returned unchanged.  Everything that shows a location goes through this.
  SourceLoc originalLoc(SourceLoc loc) const;
  // A range mapped so that it stays inside one original piece when it can.
  SourceRange originalRange(SourceRange r) const;
  // Whether `loc` lies in a verbatim piece (a fix-it there can be applied to
  // the original file).
  bool isVerbatim(SourceLoc loc) const;
  bool isGenerated(uint32_t file) const { return !files_[file - 1]->segments.empty(); }

  const SourceFile& file(uint32_t id) const { return *files_[id - 1]; }
  SourceFile& file(uint32_t id) { return *files_[id - 1]; }
  size_t fileCount() const { return files_.size(); }

  // Line and column in the original file (generated buffers are mapped).
  LineCol lineCol(SourceLoc loc) const;
  // The text of the line holding `loc` (mapped), without its line end.
  std::string_view lineText(SourceLoc loc) const;
  // Byte offset where line `line` (1-based) of `file` starts.
  uint32_t lineStart(uint32_t file, unsigned line) const;
  unsigned lineCount(uint32_t file) const;

private:
  void computeLines(SourceFile& f) const;
  const SourceSegment* segmentOf(SourceLoc loc) const;
  std::vector<std::unique_ptr<SourceFile>> files_;
};

// True if `bytes` is well-formed UTF-8 (no overlongs or surrogates).
bool isValidUtf8(std::string_view bytes);
std::string latin1ToUtf8(std::string_view bytes);

}  // namespace stc
