#include "vm/Time.h"

#include <gtest/gtest.h>

#include <climits>

using namespace stc::vm;

namespace {

TEST(Time, FormatIecTime) {
  EXPECT_EQ(formatIecTime(0), "T#0s");
  EXPECT_EQ(formatIecTime(1'500 * kMillisecond), "T#1s500ms");
  EXPECT_EQ(formatIecTime(-250 * kMillisecond), "T#-250ms");
  EXPECT_EQ(formatIecTime(1), "T#1ns");
  EXPECT_EQ(formatIecTime(kSecond), "T#1s");
  EXPECT_EQ(formatIecTime(60 * kSecond), "T#1m");
  EXPECT_EQ(formatIecTime(3600 * kSecond + 1), "T#1h1ns");
  EXPECT_EQ(formatIecTime(86'400 * kSecond + 2 * 3600 * kSecond + 3 * 60 * kSecond + 4 * kSecond +
                          5 * kMillisecond + 6 * kMicrosecond + 7),
            "T#1d2h3m4s5ms6us7ns");
  EXPECT_EQ(formatIecTime(1'001 * kMicrosecond), "T#1ms1us");
  EXPECT_EQ(formatIecTime(25 * 86'400 * kSecond), "T#25d");
  EXPECT_EQ(formatIecTime(kSecond, "LTIME#"), "LTIME#1s");
  EXPECT_EQ(formatIecTime(INT64_MAX), "T#106751d23h47m16s854ms775us807ns");
  EXPECT_EQ(formatIecTime(INT64_MIN), "T#-106751d23h47m16s854ms775us808ns");
}

TEST(Time, FormatSeconds) {
  EXPECT_EQ(formatSeconds(0), "0");
  EXPECT_EQ(formatSeconds(kMillisecond), "0.001");
  EXPECT_EQ(formatSeconds(1'500 * kMillisecond), "1.5");
  EXPECT_EQ(formatSeconds(10 * kSecond), "10");
  EXPECT_EQ(formatSeconds(1), "0.000000001");
  EXPECT_EQ(formatSeconds(123 * kSecond + 456'789'012), "123.456789012");
  EXPECT_EQ(formatSeconds(-2 * kSecond - 1), "-2.000000001");
}

}  // namespace
