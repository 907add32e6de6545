// Trace files: one sample of the traced variables per base tick, as CSV or
// VCD (chosen by the file extension).  The output depends only on the
// samples, so identical runs give byte-identical files (a VCD's $date is the
// time it was written: SOURCE_DATE_EPOCH fixes it).  The formats:
// docs/projects.md, "Traces and plots".
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vm/Time.h"

namespace stc::vm {

struct TraceColumn {
  std::string name;
  // Enum: TraceValue::literal is `Type#Name`; Text: strings, arrays, structures.
  enum Kind { Bool, Int, Real, Text, Enum } kind;
  unsigned bits = 0;        // Int: the width (1..64; 0 means 64)
  bool isSigned = false;
  // The unit of measure of the axis the variable belongs to (project.toml
  // [[axis]] unit); empty: none configured.  CSV: a `#units` line before the
  // header when a column has one (docs/projects.md, "Traces and plots").
  std::string unit = {};
};

struct TraceValue {
  uint64_t bits = 0;        // Bool/Int: two's complement, only the low `bits` count
  double real = 0;          // Real
  std::string literal;      // the IEC literal text (CSV uses it for every kind)
};

class TraceWriter {
public:
  virtual ~TraceWriter() = default;
  // `.csv` or `.vcd` (case-insensitive).  Null with `error` set if the
  // extension is unknown or the file cannot be opened.
  static std::unique_ptr<TraceWriter> create(const std::string& path, std::vector<TraceColumn> columns,
                                             std::string& error);
  // One value per column, in column order; times must not decrease.
  virtual void sample(Time t, const std::vector<TraceValue>& values) = 0;
  // Flushes and closes; `end` is the end of the run (VCD: the final
  // timestamp, when after the last sample).  False with `error` set on a
  // write error.
  virtual bool finish(Time end, std::string& error) = 0;
};

}  // namespace stc::vm
