#include "basic/SourceManager.h"
#include "config/ConfigSchema.h"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace stc {

SourceManager::SourceManager() = default;
SourceManager::~SourceManager() = default;

bool isValidUtf8(std::string_view s) {
  size_t i = 0, n = s.size();
  while (i < n) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) { ++i; continue; }
    unsigned len;
    uint32_t cp;
    if ((c & 0xE0) == 0xC0) { len = 2; cp = c & 0x1F; }
    else if ((c & 0xF0) == 0xE0) { len = 3; cp = c & 0x0F; }
    else if ((c & 0xF8) == 0xF0) { len = 4; cp = c & 0x07; }
    else return false;
    if (i + len > n) return false;
    for (unsigned k = 1; k < len; ++k) {
      unsigned char cc = static_cast<unsigned char>(s[i + k]);
      if ((cc & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (cc & 0x3F);
    }
    if ((len == 2 && cp < 0x80) || (len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000) ||
        cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
      return false;
    i += len;
  }
  return true;
}

std::string latin1ToUtf8(std::string_view s) {
  std::string out;
  out.reserve(s.size() + s.size() / 8);
  for (char ch : s) {
    unsigned char c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out.push_back(ch);
    } else {
      out.push_back(static_cast<char>(0xC0 | (c >> 6)));
      out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
    }
  }
  return out;
}

uint32_t SourceManager::addBuffer(std::string path, std::string bytes) {
  auto f = std::make_unique<SourceFile>();
  f->id = static_cast<uint32_t>(files_.size() + 1);
  f->path = std::move(path);
  // Strip a UTF-8 byte order mark; offsets then start at the first real byte.
  if (bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xEF &&
      static_cast<unsigned char>(bytes[1]) == 0xBB && static_cast<unsigned char>(bytes[2]) == 0xBF)
    bytes.erase(0, 3);
  if (!isValidUtf8(bytes)) {
    f->text = latin1ToUtf8(bytes);
    f->convertedFromLatin1 = true;
  } else {
    f->text = std::move(bytes);
  }
  files_.push_back(std::move(f));
  return files_.back()->id;
}

uint32_t SourceManager::addGenerated(std::string path, std::string text, std::vector<SourceSegment> segments) {
  auto f = std::make_unique<SourceFile>();
  f->id = static_cast<uint32_t>(files_.size() + 1);
  f->path = std::move(path);
  f->text = std::move(text);
  if (segments.empty() || segments.front().genBegin != 0) segments.insert(segments.begin(), SourceSegment{0, 0, 0, false});
  f->segments = std::move(segments);
  files_.push_back(std::move(f));
  return files_.back()->id;
}

const SourceSegment* SourceManager::segmentOf(SourceLoc loc) const {
  if (!loc.valid() || loc.file > files_.size()) return nullptr;
  const auto& segs = files_[loc.file - 1]->segments;
  if (segs.empty()) return nullptr;
  auto it = std::upper_bound(segs.begin(), segs.end(), loc.offset,
                             [](uint32_t off, const SourceSegment& s) { return off < s.genBegin; });
  return &*(it - 1);
}

SourceLoc SourceManager::originalLoc(SourceLoc loc) const {
  const SourceSegment* s = segmentOf(loc);
  if (!s) return loc;
  if (!s->file) return SourceLoc{};
  return SourceLoc{s->file, s->verbatim ? s->offset + (loc.offset - s->genBegin) : s->offset};
}

SourceRange SourceManager::originalRange(SourceRange r) const {
  if (!r.valid() || !segmentOf(r.begin)) return r;
  SourceRange out(originalLoc(r.begin));
  // The end is exclusive: map the last byte, so a range ending where a
  // piece ends does not jump to the start of the next piece.
  if (r.end.offset > r.begin.offset && r.end.file == r.begin.file) {
    SourceLoc last = originalLoc(SourceLoc{r.end.file, r.end.offset - 1});
    if (last.file == out.begin.file && last.offset >= out.begin.offset) out.end = SourceLoc{last.file, last.offset + 1};
  }
  return out;
}

bool SourceManager::isVerbatim(SourceLoc loc) const {
  const SourceSegment* s = segmentOf(loc);
  return !s || s->verbatim;
}

uint32_t SourceManager::loadFile(const std::string& path, std::string& error) {
  // Regular files only: a FIFO would block, a directory or link loop has no text.
  // Offsets are 32-bit: at most 2 GB.
  std::string text, why;
  if (!config::readRegularFile(path, text, why, uint64_t(1) << 31)) {
    error = "cannot open file: " + (why == "does not exist" ? std::string("no such file") : why);
    return 0;
  }
  return addBuffer(path, std::move(text));
}

void SourceManager::computeLines(SourceFile& f) const {
  if (!f.lineStarts.empty()) return;
  f.lineStarts.push_back(0);
  const std::string& t = f.text;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] == '\n') {
      f.lineStarts.push_back(static_cast<uint32_t>(i + 1));
    } else if (t[i] == '\r') {
      if (i + 1 < t.size() && t[i + 1] == '\n') ++i;  // CRLF
      f.lineStarts.push_back(static_cast<uint32_t>(i + 1));
    }
  }
}

LineCol SourceManager::lineCol(SourceLoc loc) const {
  loc = originalLoc(loc);
  if (!loc.valid() || loc.file > files_.size()) return {};
  SourceFile& f = *files_[loc.file - 1];
  computeLines(f);
  auto it = std::upper_bound(f.lineStarts.begin(), f.lineStarts.end(), loc.offset);
  unsigned line = static_cast<unsigned>(it - f.lineStarts.begin());
  uint32_t begin = f.lineStarts[line - 1];
  if (!f.convertedFromLatin1) return {line, loc.offset - begin + 1};
  // Latin-1 input: one byte per character in the file as written, so count
  // the characters (UTF-8 lead bytes) of the converted text.
  unsigned col = 1;
  uint32_t end = std::min<uint32_t>(loc.offset, static_cast<uint32_t>(f.text.size()));
  for (uint32_t i = begin; i < end; ++i)
    if ((static_cast<unsigned char>(f.text[i]) & 0xC0) != 0x80) ++col;
  if (loc.offset > end) col += loc.offset - end;
  return {line, col};
}

uint32_t SourceManager::lineStart(uint32_t file, unsigned line) const {
  SourceFile& f = *files_[file - 1];
  computeLines(f);
  if (line == 0) return 0;
  if (line > f.lineStarts.size()) return static_cast<uint32_t>(f.text.size());
  return f.lineStarts[line - 1];
}

unsigned SourceManager::lineCount(uint32_t file) const {
  SourceFile& f = *files_[file - 1];
  computeLines(f);
  return static_cast<unsigned>(f.lineStarts.size());
}

std::string_view SourceManager::lineText(SourceLoc loc) const {
  loc = originalLoc(loc);
  if (!loc.valid()) return {};
  LineCol lc = lineCol(loc);
  const SourceFile& f = *files_[loc.file - 1];
  const std::string& t = f.original.empty() ? f.text : f.original;
  uint32_t b = f.lineStarts[lc.line - 1];
  uint32_t e = b;
  while (e < t.size() && t[e] != '\n' && t[e] != '\r') ++e;
  return std::string_view(t).substr(b, e - b);
}

}  // namespace stc
