// The tick algorithm of `stc plot` (tools/stc/Ticks.h).
#include "tools/stc/Ticks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

using namespace stc::plot;

namespace {

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

// What every axis must be: 3..10 ticks inside the range drawn, which holds
// the data; distinct labels; the ticks spread over at least half the data.
void expectGoodAxis(double lo, double hi, const TickRequest& r) {
  SCOPED_TRACE(testing::Message() << "data [" << lo << ", " << hi << "]" << (r.integer ? " integer" : ""));
  TickAxis a = niceAxis(lo, hi, r);
  EXPECT_GE(a.ticks.size(), 3u) << joined(a.labels);
  EXPECT_LE(a.ticks.size(), 10u) << joined(a.labels);
  EXPECT_EQ(a.labels.size(), a.ticks.size());
  EXPECT_EQ(std::set<std::string>(a.labels.begin(), a.labels.end()).size(), a.labels.size()) << joined(a.labels);
  EXPECT_LE(a.lo, lo);
  EXPECT_GE(a.hi, hi);
  EXPECT_LT(a.lo, a.hi);
  for (double t : a.ticks) {
    EXPECT_GE(t, a.lo - a.step * 1e-6);
    EXPECT_LE(t, a.hi + a.step * 1e-6);
    if (r.integer) {
      EXPECT_EQ(t, std::floor(t)) << joined(a.labels);
    }
  }
  if (hi > lo && a.ticks.size() >= 2) {
    EXPECT_GE(a.ticks.back() - a.ticks.front(), 0.5 * (hi - lo)) << joined(a.labels);
  }
}

TEST(PlotTicks, SymmetricRange) {
  TickAxis a = niceAxis(-406, 406, {});
  EXPECT_EQ(joined(a.labels), "-400 -200 0 200 400");
  expectGoodAxis(-406, 406, {});
  expectGoodAxis(-1, 1, {});
  expectGoodAxis(-0.003, 0.003, {});
}

TEST(PlotTicks, NegativeOnly) {
  expectGoodAxis(-950, -12, {});
  expectGoodAxis(-1e-3, -9e-4, {});
  TickAxis a = niceAxis(-100, -50, {});
  for (const std::string& l : a.labels) EXPECT_EQ(l[0], '-') << joined(a.labels);
}

TEST(PlotTicks, IntegerCounterNeverHalves) {
  TickRequest r;
  r.integer = true;
  TickAxis a = niceAxis(0, 1, r);
  EXPECT_EQ(joined(a.labels), "0 1 2");
  expectGoodAxis(0, 1, r);
  expectGoodAxis(0, 2, r);
  expectGoodAxis(0, 3, r);
  expectGoodAxis(-1, 0, r);
  expectGoodAxis(0, 7, r);
  expectGoodAxis(-3, 1000, r);
  expectGoodAxis(0, 4'000'000'000.0, r);
  for (double lo : {0.0, 1.0, -5.0})
    for (double hi : {lo, lo + 1, lo + 2, lo + 3, lo + 4, lo + 5}) expectGoodAxis(lo, hi, r);
}

TEST(PlotTicks, ConstantSignal) {
  TickAxis a = niceAxis(0, 0, {});
  EXPECT_LT(a.lo, 0);
  EXPECT_GT(a.hi, 0);
  expectGoodAxis(0, 0, {});
  expectGoodAxis(3.7, 3.7, {});
  expectGoodAxis(-250, -250, {});
  expectGoodAxis(1e-7, 1e-7, {});
  expectGoodAxis(1e9, 1e9, {});
  TickRequest r;
  r.integer = true;
  a = niceAxis(5, 5, r);
  EXPECT_EQ(joined(a.labels), "4 5 6");
  expectGoodAxis(5, 5, r);
}

TEST(PlotTicks, TinyRanges) {
  expectGoodAxis(0, 1e-7, {});
  expectGoodAxis(1.0, 1.0 + 1e-7, {});
  expectGoodAxis(1000, 1000 + 3e-8, {});
  expectGoodAxis(-2e-300, 2e-300, {});
  TickAxis a = niceAxis(0, 1e-7, {});
  EXPECT_EQ(a.labels.front(), "0");
  EXPECT_NE(a.labels.back().find("e-"), std::string::npos) << joined(a.labels);
}

TEST(PlotTicks, HugeRanges) {
  expectGoodAxis(0, 1e9, {});
  expectGoodAxis(-1e9, 1e9, {});
  expectGoodAxis(1e9, 1e9 + 1000, {});
  expectGoodAxis(-1e300, 1e300, {});
  // Beyond 1e300 the axis stops at 1e300 (the spans stay finite).
  TickAxis a = niceAxis(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), {});
  EXPECT_EQ(joined(a.labels), "-1e300 0 1e300");
  a = niceAxis(0, 1e9, {});
  EXPECT_EQ(a.labels.back(), "1e9") << joined(a.labels);
}

TEST(PlotTicks, NoData) {
  TickAxis a = niceAxis(std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), {});
  EXPECT_GE(a.ticks.size(), 3u);
  a = niceAxis(std::nan(""), std::nan(""), {});
  EXPECT_GE(a.ticks.size(), 3u);
}

TEST(PlotTicks, ManySpansAndHeights) {
  for (double height : {120.0, 170.0, 300.0, 600.0})
    for (double span : {1e-9, 3e-6, 0.7, 1.0, 4.2, 13.0, 99.0, 406.0, 12345.0, 7e7, 3e12}) {
      TickRequest r;
      r.pixels = height;
      expectGoodAxis(-span / 3, span, r);
      expectGoodAxis(span, 2 * span, r);
      r.integer = true;
      if (span >= 1) expectGoodAxis(0, std::round(span), r);
    }
}

TEST(PlotTicks, HorizontalLabelsFit) {
  TickRequest r;
  r.pixels = 836;
  r.minGap = 14;
  r.horizontal = true;
  r.pad = false;
  TickAxis a = niceAxis(0, 10, r);
  EXPECT_EQ(joined(a.labels), "0 2 4 6 8 10");   // 11 ticks would be too many
  a = niceAxis(0, 4.2, r);
  for (size_t i = 1; i < a.ticks.size(); ++i) {
    double px = (a.ticks[i] - a.ticks[i - 1]) / (a.hi - a.lo) * r.pixels;
    EXPECT_GE(px, textWidth(a.labels[i]) + r.minGap);
  }
}

TEST(PlotTicks, Labels) {
  EXPECT_EQ(joined(tickLabels({0, 0.25, 0.5, 0.75}, 0.25)), "0 0.25 0.50 0.75");
  EXPECT_EQ(joined(tickLabels({-0.0, 1, 2}, 1)), "0 1 2");
  EXPECT_EQ(joined(tickLabels({1e9, 1.000000002e9, 1.000000004e9}, 2)), "1e9 1.000000002e9 1.000000004e9");
}

TEST(PlotTicks, Seconds) {
  EXPECT_EQ(formatSeconds(4.2), "4.2");
  EXPECT_EQ(formatSeconds(4.199999999, 1e-6), "4.2");
  EXPECT_EQ(formatSeconds(4.199999999), "4.199999999");
  EXPECT_EQ(formatSeconds(0), "0");
  EXPECT_EQ(formatSeconds(-0.0), "0");
  EXPECT_EQ(formatSeconds(10), "10");
  EXPECT_EQ(formatSeconds(0.001), "0.001");
  EXPECT_EQ(formatSeconds(1e-9), "0.000000001");
  EXPECT_EQ(formatSeconds(std::nan("")), "NaN");
}

}  // namespace
