// Trace files: one sample of the traced variables per base tick, as CSV or
// VCD (chosen by the file extension).  The output depends only on the
// samples, so identical runs give byte-identical files (a VCD's $date is the
// time it was written: SOURCE_DATE_EPOCH fixes it).  The formats:
// docs/projects.md, "Traces and plots".
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
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

// How a CSV trace writes its rows (the golden traces of stc test; docs/projects.md,
// "Trace files").  The defaults are what stc run writes: every sample, exact values.
struct CsvTraceOptions {
  // REAL/LREAL columns in the shortest form within this tolerance (formatTraceReal);
  // unset: the exact IEC literal (the shortest text that reads back bit for bit).
  std::optional<double> tolerance;
  Time every = 0;          // > 0: only the samples at multiples of this time
  bool onChange = false;   // only the rows whose values (as written) differ from the row
                           // written before, and the first and the last sample
};

// A REAL (`single`) or LREAL value as an ST literal: the shortest text that reads back
// bit for bit, plain digits for 1E-5 <= |v| < 1E16 (100000.0), else with an exponent
// (1.0E+19); NaN, Inf, -Inf.  (Also declared in vm/Image.h.)
std::string formatReal(double v, bool single);

// A REAL (`single`) or LREAL value for a trace compared within `tolerance` (as stc
// test compares: |actual - expected| <= tolerance * max(1, |expected|)): NaN, Inf,
// -Inf; 0.0 when |v| < tolerance; else the fewest significant digits whose value is
// within tolerance * max(1, |v|) / 2 of v (never longer than the exact literal), so
// the written value compared with v again is within the tolerance.  Written as an
// IEC literal: 450.0, -0.25, 1.5E-07.  Tolerance 0 (or negative): the exact literal.
std::string formatTraceReal(double v, bool single, double tolerance);

class TraceWriter {
public:
  virtual ~TraceWriter() = default;
  // `.csv` or `.vcd` (case-insensitive).  Null with `error` set if the
  // extension is unknown or the file cannot be opened.  `csv` applies to CSV files
  // (a VCD records every change exactly).
  static std::unique_ptr<TraceWriter> create(const std::string& path, std::vector<TraceColumn> columns,
                                             std::string& error, const CsvTraceOptions& csv = {});
  // One value per column, in column order; times must not decrease.
  virtual void sample(Time t, const std::vector<TraceValue>& values) = 0;
  // Flushes and closes; `end` is the end of the run (VCD: the final
  // timestamp, when after the last sample).  False with `error` set on a
  // write error.
  virtual bool finish(Time end, std::string& error) = 0;
};

}  // namespace stc::vm
