#include "vm/Trace.h"

#include <algorithm>
#include <cerrno>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string_view>


namespace stc::vm {
namespace {

// Buffered output to a FILE*; errors are collected and reported by close().
class Output {
public:
  ~Output() {
    if (file_) std::fclose(file_);
  }
  bool open(const std::string& path, std::string& error) {
    file_ = std::fopen(path.c_str(), "wb");
    if (!file_) {
      error = "cannot open '" + path + "': " + std::strerror(errno);
      return false;
    }
    path_ = path;
    return true;
  }
  std::string& buffer() { return buf_; }
  void flushIfBig() {
    if (buf_.size() >= 1 << 16) flush();
  }
  bool close(std::string& error) {
    if (!file_) return true;
    flush();
    bool ok = !failed_;
    if (std::fclose(file_) != 0) ok = false;
    file_ = nullptr;
    if (!ok) error = "cannot write '" + path_ + "': " + std::strerror(errno ? errno : EIO);
    return ok;
  }

private:
  void flush() {
    if (!buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), file_) != buf_.size()) failed_ = true;
    buf_.clear();
  }
  std::FILE* file_ = nullptr;
  std::string path_;
  std::string buf_;
  bool failed_ = false;
};

// RFC 4180 quoting, also for spaces so that naive splitters agree.
void appendCsvField(std::string& out, std::string_view s) {
  if (s.find_first_of(",\" \r\n") == std::string_view::npos) {
    out.append(s);
    return;
  }
  out.push_back('"');
  for (char c : s) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  out.push_back('"');
}

class CsvWriter final : public TraceWriter {
public:
  CsvWriter(std::unique_ptr<Output> out, std::vector<TraceColumn> columns, const CsvTraceOptions& opts)
      : out_(std::move(out)), columns_(std::move(columns)), opts_(opts) {
    std::string& b = out_->buffer();
    // The axes' units, when a column has one: `#units,,mm,...` lines up with the header.
    if (std::any_of(columns_.begin(), columns_.end(), [](const TraceColumn& c) { return !c.unit.empty(); })) {
      b += "#units";
      for (const TraceColumn& c : columns_) {
        b += ',';
        appendCsvField(b, c.unit);
      }
      b += '\n';
    }
    b += "time";
    for (const TraceColumn& c : columns_) {
      b += ',';
      appendCsvField(b, c.name);
    }
    b += '\n';
  }
  void sample(Time t, const std::vector<TraceValue>& values) override {
    if (opts_.every > 0 && t % opts_.every != 0) return;
    row_.clear();
    for (size_t i = 0; i < values.size(); ++i) {
      row_ += ',';
      const TraceValue& v = values[i];
      if (opts_.tolerance && i < columns_.size() && columns_[i].kind == TraceColumn::Real)
        appendCsvField(row_, formatTraceReal(v.real, columns_[i].bits == 32, *opts_.tolerance));
      else
        appendCsvField(row_, v.literal);
    }
    if (opts_.onChange) {
      if (written_ && row_ == last_) {
        // Unchanged: held back, written by finish() if it is the last sample.
        pending_ = true;
        pendingTime_ = t;
        return;
      }
      last_ = row_;
      written_ = true;
      pending_ = false;
    }
    write(t, row_);
  }
  bool finish(Time, std::string& error) override {
    if (pending_) write(pendingTime_, last_);
    pending_ = false;
    return out_->close(error);
  }

private:
  void write(Time t, const std::string& values) {
    std::string& b = out_->buffer();
    b += formatSeconds(t);
    b += values;
    b += '\n';
    out_->flushIfBig();
  }
  std::unique_ptr<Output> out_;
  std::vector<TraceColumn> columns_;
  CsvTraceOptions opts_;
  std::string row_, last_;   // ",v1,v2..." of this sample / of the last row written
  bool written_ = false, pending_ = false;
  Time pendingTime_ = 0;
};

// The date of a VCD: SOURCE_DATE_EPOCH when set (reproducible files), else now.
std::string vcdDate() {
  std::time_t t = std::time(nullptr);
  if (const char* e = std::getenv("SOURCE_DATE_EPOCH")) {
    long long v = 0;
    auto r = std::from_chars(e, e + std::strlen(e), v);
    if (r.ec == std::errc() && *r.ptr == '\0' && v >= 0 && v <= 253402300799)   // up to 9999-12-31
      t = static_cast<std::time_t>(v);
  }
  std::tm tm{};
  char buf[64];
  if (!gmtime_r(&t, &tm) || !std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", &tm)) return "unknown";
  return buf;
}

// Whitespace would end a reference or a value in the VCD grammar.
std::string vcdToken(std::string_view s) {
  std::string out;
  for (char ch : s) out += (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r') ? '_' : ch;
  return out;
}

// A variable path split at the dots outside [...]: GVL.a[1].b -> GVL, a[1], b.
std::vector<std::string> pathParts(const std::string& name) {
  std::vector<std::string> parts(1);
  int depth = 0;
  for (char c : name) {
    if (c == '[') ++depth;
    if (c == ']' && depth > 0) --depth;
    if (c == '.' && depth == 0) parts.emplace_back();
    else parts.back() += c;
  }
  return parts;
}

// One sample per base tick as value changes: BOOL 1-bit wires, integers and
// times n-bit wires, REALs real, enums (their value names) and strings (their
// literals, whitespace as $hh) GTKWave's string variables.  Each dotted part
// of a name but the last is a module scope (a program, GVL, axis, instance).
class VcdWriter final : public TraceWriter {
public:
  VcdWriter(std::unique_ptr<Output> out, std::vector<TraceColumn> columns)
      : out_(std::move(out)), columns_(std::move(columns)) {
    std::string& b = out_->buffer();
    b += "$date " + vcdDate() + " $end\n";
    b += "$version stc " STC_VERSION " $end\n";
    b += "$timescale 1ns $end\n";
    for (size_t i = 0; i < columns_.size(); ++i) {
      TraceColumn& c = columns_[i];
      if (c.kind == TraceColumn::Bool) c.bits = 1;
      if (c.kind == TraceColumn::Int && (c.bits == 0 || c.bits > 64)) c.bits = 64;
      ids_.push_back(identifier(i));
    }
    // The scope tree, first seen first (names case-insensitive, as in ST).
    Scope root;
    for (size_t i = 0; i < columns_.size(); ++i) {
      std::vector<std::string> parts = pathParts(columns_[i].name);
      Scope* s = &root;
      for (size_t p = 0; p + 1 < parts.size(); ++p) {
        std::string key = lower(parts[p]);
        auto it = std::find_if(s->children.begin(), s->children.end(), [&](const Scope& c) { return lower(c.name) == key; });
        if (it == s->children.end()) {
          s->children.push_back(Scope{parts[p], {}, {}});
          it = s->children.end() - 1;
        }
        s = &*it;
      }
      s->vars.emplace_back(i, parts.back());
    }
    writeScope(b, root);
    b += "$enddefinitions $end\n";
    last_.resize(columns_.size());
    lastText_.resize(columns_.size());
  }

  void sample(Time t, const std::vector<TraceValue>& values) override {
    std::string& b = out_->buffer();
    if (first_) {
      stamp(b, t);
      b += "$dumpvars\n";
      for (size_t i = 0; i < columns_.size(); ++i) {
        remember(i, values[i]);
        appendValue(b, i, values[i]);
      }
      b += "$end\n";
      first_ = false;
    } else {
      bool stamped = false;
      for (size_t i = 0; i < columns_.size(); ++i) {
        if (!remember(i, values[i])) continue;
        if (!stamped) {
          stamp(b, t);
          stamped = true;
        }
        appendValue(b, i, values[i]);
      }
    }
    out_->flushIfBig();
  }

  bool finish(Time end, std::string& error) override {
    // The file ends at the end of the run, not at the last change.
    if (!stamped_ || end > lastStamp_) stamp(out_->buffer(), end);
    return out_->close(error);
  }

private:
  struct Scope {
    std::string name;
    std::vector<Scope> children;
    std::vector<std::pair<size_t, std::string>> vars;   // column, the last part of its name
  };

  static std::string lower(std::string s) {
    for (char& c : s)
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return s;
  }

  void writeScope(std::string& b, const Scope& s) const {
    for (const auto& [i, leaf] : s.vars) {
      const TraceColumn& c = columns_[i];
      b += "$var ";
      if (c.kind == TraceColumn::Real) b += "real 64 ";
      else if (isText(i)) b += "string 1 ";
      else b += "wire " + std::to_string(c.bits) + ' ';
      b += ids_[i];
      b += ' ';
      b += vcdToken(leaf);
      b += " $end\n";
    }
    for (const Scope& child : s.children) {
      b += "$scope module " + vcdToken(child.name) + " $end\n";
      writeScope(b, child);
      b += "$upscope $end\n";
    }
  }

  void stamp(std::string& b, Time t) {
    b += '#';
    b += std::to_string(t);
    b += '\n';
    stamped_ = true;
    lastStamp_ = t;
  }

  bool isText(size_t i) const { return columns_[i].kind == TraceColumn::Text || columns_[i].kind == TraceColumn::Enum; }

  // Base-94 over the printable characters '!'..'~'.
  static std::string identifier(size_t i) {
    std::string id;
    do {
      id.push_back(static_cast<char>(33 + i % 94));
      i /= 94;
    } while (i-- > 0);
    return id;
  }

  uint64_t mask(size_t i) const {
    unsigned bits = columns_[i].bits;
    return bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
  }

  // Records the value of column i; true if it changed.  What decides "changed":
  // the text, the masked bits, or the double's bit pattern (so a NaN equals
  // itself and -0.0 differs from 0.0).
  bool remember(size_t i, const TraceValue& v) {
    if (isText(i)) {
      std::string t = textValue(i, v);
      if (!first_ && t == lastText_[i]) return false;
      lastText_[i] = std::move(t);
      return true;
    }
    uint64_t k = v.bits & mask(i);
    if (columns_[i].kind == TraceColumn::Real) std::memcpy(&k, &v.real, sizeof k);
    if (!first_ && k == last_[i]) return false;
    last_[i] = k;
    return true;
  }

  // A string value: an enum's value name (after `Type#`), else the literal
  // with whitespace as IEC $hh escapes (so it stays one token).
  std::string textValue(size_t i, const TraceValue& v) const {
    std::string_view lit = v.literal;
    if (columns_[i].kind == TraceColumn::Enum) {
      size_t hash = lit.find('#');
      if (hash != std::string_view::npos) lit.remove_prefix(hash + 1);
    }
    std::string out;
    for (char ch : lit) {
      if (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r' || ch == '\v' || ch == '\f') {
        char buf[4];
        std::snprintf(buf, sizeof buf, "$%02X", static_cast<unsigned char>(ch));
        out += buf;
      } else {
        out += ch;
      }
    }
    return out;
  }

  void appendValue(std::string& b, size_t i, const TraceValue& v) const {
    const TraceColumn& c = columns_[i];
    if (isText(i)) {
      b += 's';
      b += lastText_[i];
      b += ' ';
    } else if (c.kind == TraceColumn::Bool) {
      b += (v.bits & 1) ? '1' : '0';
    } else if (c.kind == TraceColumn::Real) {
      char buf[32];
      auto r = std::to_chars(buf, buf + sizeof buf, v.real, std::chars_format::general, 17);
      b += 'r';
      b.append(buf, r.ptr);
      b += ' ';
    } else {
      uint64_t x = v.bits & mask(i);
      b += 'b';
      int top = x ? 63 - __builtin_clzll(x) : 0;
      for (int bit = top; bit >= 0; --bit) b += ((x >> bit) & 1) ? '1' : '0';
      b += ' ';
    }
    b += ids_[i];
    b += '\n';
  }

  std::unique_ptr<Output> out_;
  std::vector<TraceColumn> columns_;
  std::vector<std::string> ids_;
  std::vector<uint64_t> last_;
  std::vector<std::string> lastText_;
  bool first_ = true;
  bool stamped_ = false;
  Time lastStamp_ = 0;
};

bool endsWithIgnoreCase(const std::string& s, std::string_view suffix) {
  if (s.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i) {
    char c = s[s.size() - suffix.size() + i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != suffix[i]) return false;
  }
  return true;
}

}  // namespace

std::string formatReal(double v, bool single) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  char buf[64];
  std::to_chars_result r = single ? std::to_chars(buf, buf + sizeof buf, static_cast<float>(v)) : std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  // The shortest round-trip form, but as an ST literal: plain digits for
  // magnitudes a reader takes in at a glance (100000.0, not 1E+05), and a
  // mantissa with a fraction in exponent form (1.0E+19).
  const double mag = std::fabs(v);
  if (s.find('e') != std::string::npos && mag >= 1e-5 && mag < 1e16) {
    r = single ? std::to_chars(buf, buf + sizeof buf, static_cast<float>(v), std::chars_format::fixed)
               : std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
    s.assign(buf, r.ptr);
  }
  for (char& c : s)
    if (c == 'e') c = 'E';
  const size_t e = s.find('E');
  if (s.find('.') == std::string::npos) s.insert(e == std::string::npos ? s.size() : e, ".0");
  return s;
}

namespace {
// The significant digits of a literal: 450.0 and 4.5E+02 have 2, 0.0012 has 2.
size_t significantDigits(const std::string& literal) {
  std::string d;
  for (char c : literal.substr(0, literal.find('E')))
    if (c >= '0' && c <= '9') d += c;
  const size_t first = d.find_first_not_of('0');
  return first == std::string::npos ? 0 : d.find_last_not_of('0') + 1 - first;
}
}  // namespace

std::string formatTraceReal(double v, bool single, double tolerance) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  if (v == 0 || std::fabs(v) < tolerance) return "0.0";   // also -0.0
  if (!(tolerance > 0)) return formatReal(v, single);
  const double bound = tolerance * std::max(1.0, std::fabs(v)) / 2;
  auto close = [&](const char* b, const char* e) {
    double x = 0;
    return std::from_chars(b, e, x).ec == std::errc() && std::fabs(x - v) <= bound ? std::optional<double>(x) : std::nullopt;
  };
  // The value's own literal (a REAL's is shorter) when it is close enough read as an LREAL.
  const std::string exact = formatReal(v, single);
  const bool exactClose = close(exact.data(), exact.data() + exact.size()).has_value();
  char buf[64];
  // The fewest significant digits whose correctly rounded value is close enough.
  for (int digits = 1; digits < 17; ++digits) {
    const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific, digits - 1);
    const std::optional<double> x = close(buf, r.ptr);
    if (!x) continue;
    // x's shortest round-trip digits (at most `digits`), as a REAL literal: plain for
    // 1E-5 <= |x| < 1E16, else in exponent form (to_chars may choose 377491411941500032).
    const double mag = std::fabs(*x);
    const std::to_chars_result q = mag >= 1e-5 && mag < 1e16 ? std::to_chars(buf, buf + sizeof buf, *x, std::chars_format::fixed)
                                                             : std::to_chars(buf, buf + sizeof buf, *x, std::chars_format::scientific);
    std::string s(buf, q.ptr);
    for (char& c : s)
      if (c == 'e') c = 'E';
    if (s.find('.') == std::string::npos) s.insert(std::min(s.find('E'), s.size()), ".0");
    return exactClose && significantDigits(exact) <= static_cast<size_t>(digits) ? exact : s;
  }
  return exactClose ? exact : formatReal(v, false);
}

std::unique_ptr<TraceWriter> TraceWriter::create(const std::string& path, std::vector<TraceColumn> columns,
                                                 std::string& error, const CsvTraceOptions& csvOptions) {
  bool csv = endsWithIgnoreCase(path, ".csv");
  bool vcd = endsWithIgnoreCase(path, ".vcd");
  if (!csv && !vcd) {
    error = "trace file '" + path + "' must end in .csv or .vcd";
    return nullptr;
  }
  auto out = std::make_unique<Output>();
  if (!out->open(path, error)) return nullptr;
  if (csv) return std::make_unique<CsvWriter>(std::move(out), std::move(columns), csvOptions);
  return std::make_unique<VcdWriter>(std::move(out), std::move(columns));
}

}  // namespace stc::vm
