// `stc plot`: a trace CSV (the file `stc run --trace-out x.csv` writes) drawn
// as a self-contained SVG.  Numbers become line plots grouped into panels by
// kind (positions, velocities, ...), BOOLs digital lanes, enums and strings
// labelled state bands, all on one time axis.  With --xy: the paths of
// pairs of variables (Y over X) in one square panel; with --gcode the
// commanded tool path of a G-code program under them (or alone, without a
// trace: docs/cnc.md, "Seeing a program").  Long traces are reduced to
// min/max per pixel column, so steps and extremes survive and the file stays
// small.  See docs/projects.md ("Traces and plots").
#pragma once

#include <optional>
#include <utility>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace stc::plot {

struct PlotOptions {
  std::vector<std::string> vars;   // columns to draw, in this order (empty: all)
  std::string title;               // empty: the trace file's name
  std::optional<double> from, to;  // seconds
  // --xy X,Y: instead of the time plot, one square panel (equal scale) with
  // the path of each pair, Y over X.
  std::vector<std::pair<std::string, std::string>> xy;
  // --gcode FILE: a G-code program whose commanded path (feed moves solid,
  // G0 dashed) is drawn under the --xy paths, or alone when there is no trace.
  std::string gcode;
  char gcodeH = 'X', gcodeV = 'Y';   // --gcode-axes H,V: the program's axes drawn across / up
  std::vector<std::pair<std::string, double>> gcodeVars;   // --gcode-var NAME=VALUE: $NAME$ in the program
  // --rapid COL: a trace column that is TRUE (non-zero) while a G0 move runs;
  // those parts of the --xy paths are dashed.
  std::string rapid;
};

// A trace as read from CSV: the time column in seconds, the other columns as text.
struct TraceTable {
  std::vector<std::string> names;
  std::vector<std::string> units;   // per column: its axis unit from a `#units` line ("" none)
  std::vector<double> time;
  std::vector<std::vector<std::string>> columns;   // columns[c][row]
};

// Reads a trace CSV.  False with `error` set if the file cannot be read
// (`missing` true) or is not a trace (no `time` column, bad rows).  Lines
// before the header that start with '#' are comments; `#units,U1,U2,...`
// gives the columns' units.
bool readTraceCsv(const std::string& path, TraceTable& out, std::string& error, bool& missing);

// The SVG document for `trace` (options.vars and options.xy must name existing columns).
std::string renderSvg(const TraceTable& trace, const PlotOptions& options);

// Reads `csvPath`, writes the SVG to `svgPath`.  0 ok; 1 the trace is not
// readable or empty, or the SVG cannot be written; 2 a bad request (missing
// trace file, unknown --vars or --xy name, a non-numeric --xy column, --from
// after --to).  `error` is the message.
int plotTraceFile(const std::string& csvPath, const std::string& svgPath, const PlotOptions& options,
                  std::string& error);

// plotTraceFile with options.gcode: `csvPath` may be empty (the program
// alone).  A program that does not decode is exit 1 with its diagnostics
// (file:line:col, as `stc check` prints them) in `diagnostics`; a missing
// program file, an unknown --rapid column is exit 2.  `diagnostics` may also
// hold warnings when the result is 0.
int plotFiles(const std::string& csvPath, const std::string& svgPath, const PlotOptions& options, std::string& error,
              std::string& diagnostics);

// --compare: the expected and the actual trace of the same variables drawn
// over each other (expected dashed), one panel, pair of lanes or pair of bands
// per variable (matched by name, case-insensitive; one only in one trace is
// drawn alone and listed), on the merged sample times (a sample holds until
// the next one).  Where they differ by more than `tolerance` (numbers:
// |actual - expected| <= tolerance * max(1, |expected|) is equal, as stc
// test; anything else: the text) the time span is shaded; the title says how
// many variables differ.  options.vars picks variables; options.xy/gcode are
// not used.
std::string renderCompareSvg(const TraceTable& expected, const TraceTable& actual, const PlotOptions& options, double tolerance,
                             const std::string& expectedName, const std::string& actualName);

// Reads both traces, writes the comparison to `svgPath`.  0 ok; 1 a trace is
// not readable or has no samples, or the SVG cannot be written; 2 a bad
// request (a missing trace file, a --vars name in neither trace, a tolerance
// that is not a finite number >= 0, --from after --to).
int compareTraceFiles(const std::string& expectedCsv, const std::string& actualCsv, const std::string& svgPath, const PlotOptions& options,
                      double tolerance, std::string& error);

// Seconds from the command line: a duration (1.5s, 250ms, T#2s) or a plain number of seconds.
bool parseSeconds(const std::string& text, double& out);

// The `stc plot` subcommand: registered on `app`; run() executes it once parsed.
// The --xy "X,Y" arguments into options.xy; false with `error` for a malformed pair.
bool parseXyPairs(const std::vector<std::string>& pairs, PlotOptions& options, std::string& error);

struct PlotCommand {
  std::string trace;
  std::string output;
  std::vector<std::string> vars;
  std::vector<std::string> xy;   // "X,Y" per --xy
  std::string title;
  std::string from, to;
  std::string gcode, gcodeAxes, rapid;
  std::vector<std::string> gcodeVars;   // "NAME=VALUE" per --gcode-var
  std::vector<std::string> compare;     // --compare EXPECTED ACTUAL
  std::string tolerance;                // --tolerance (with --compare)
  CLI::App* cmd = nullptr;
  void add(CLI::App& app);
  int run() const;

private:
  int runCompare() const;
  bool parseWindow(PlotOptions& o, std::string& error) const;   // --from/--to into o
};

}  // namespace stc::plot
