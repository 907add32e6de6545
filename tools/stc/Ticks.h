// Axis ticks and number labels for `stc plot` (tools/stc/Plot.h): steps of
// 1, 2, 2.5 (not on horizontal axes) or 5 times a power of ten, 3 to 10 ticks over any range
// (symmetric, negative, tiny, huge, constant), integer data ticked at integers
// only, labels with just the digits that tell them apart.  Tests:
// tests/unit/PlotTicksTest.cpp.
#pragma once

#include <string>
#include <vector>

namespace stc::plot {

struct TickRequest {
  double pixels = 170;       // the length of the axis
  double minGap = 22;        // vertical: pixels between ticks at least; horizontal: between labels
  bool horizontal = false;   // labels side by side: their widths count
  bool integer = false;      // integer data: ticks at integers only, never 0.5
  bool pad = true;           // a 5 % margin around the data (a time axis: none)
};

// A value axis: the range drawn and its ticks.
struct TickAxis {
  double lo = 0, hi = 1;             // the range drawn (contains the data)
  double step = 1;                   // between ticks
  std::vector<double> ticks;         // the multiples of step in [lo, hi], 3 to 10 of them
  std::vector<std::string> labels;   // one per tick, all different
};

// The axis for data in [lo, hi] (finite; lo > hi: no data).  A constant
// signal gets a band around its value; integer data at least three integers.
TickAxis niceAxis(double lo, double hi, const TickRequest& request);

// The tick step for the range [lo, hi] as drawn (lo < hi, finite).
double chooseStep(double lo, double hi, const TickRequest& request);

// The multiples of `step` in [lo, hi] (at most 200).
std::vector<double> tickValues(double lo, double hi, double step);

// Labels for ticks `step` apart: fixed or exponent notation with the digits
// that tell the ticks apart ("0", "-200", "0.25", "1.5e-7", "1.000000002e9").
std::vector<std::string> tickLabels(const std::vector<double>& ticks, double step);

// Seconds with the fewest decimals (at most 9) that give `v` within
// `tolerance`: 4.199999999 within 1e-6 is "4.2".
std::string formatSeconds(double v, double tolerance = 5e-10);

// The width of `s` in 11 px sans-serif, estimated.
double textWidth(const std::string& s, double perChar = 6.6);

}  // namespace stc::plot
