// compiler/config: the duration grammar and the schema's messages.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "config/ConfigSchema.h"
#include "config/Duration.h"

using namespace stc::config;

namespace {

int64_t ns(std::string_view text) {
  int64_t v = -42;
  std::string why;
  EXPECT_TRUE(parseDuration(text, v, &why)) << text << ": " << why;
  return v;
}

std::string bad(std::string_view text) {
  int64_t v = 0;
  std::string why;
  EXPECT_FALSE(parseDuration(text, v, &why)) << text << " parsed as " << v;
  return why;
}

std::string schemaError(const char* toml, const Schema& s) {
  std::string error;
  toml::table t = toml::parse(toml);
  EXPECT_FALSE(validate(t, s, "f.toml", error)) << toml;
  return error;
}

}  // namespace

TEST(Duration, Grammar) {
  EXPECT_EQ(ns("10ms"), 10'000'000);
  EXPECT_EQ(ns("1.5s"), 1'500'000'000);
  EXPECT_EQ(ns("1h30m"), 5'400'000'000'000);
  EXPECT_EQ(ns("T#10ms"), 10'000'000);
  EXPECT_EQ(ns("t#1h_30m"), 5'400'000'000'000);
  EXPECT_EQ(ns("LTIME#-5us"), -5'000);
  EXPECT_EQ(ns("TIME#1d2h3m4s5ms6us7ns"), 93'784'005'006'007);
  EXPECT_EQ(ns("1_000ms"), 1'000'000'000);
  EXPECT_EQ(ns("0.0000000019s"), 1);                     // truncated to whole ns
  EXPECT_EQ(ns("106751d23h47m16s854ms775us807ns"), std::numeric_limits<int64_t>::max());
  EXPECT_EQ(ns("-106751d23h47m16s854ms775us808ns"), std::numeric_limits<int64_t>::min());
  EXPECT_EQ(ns("9223372036854775807ns"), std::numeric_limits<int64_t>::max());
}

TEST(Duration, Refused) {
  EXPECT_EQ(bad(""), "an empty duration");
  EXPECT_NE(bad(".s").find("a digit is expected before '.'"), std::string::npos);
  EXPECT_NE(bad("1.2.3s").find("one decimal point at most"), std::string::npos);
  EXPECT_NE(bad("99999999999999h").find("out of range"), std::string::npos);
  EXPECT_NE(bad("9223372036854775808ns").find("out of range"), std::string::npos);
  EXPECT_NE(bad(std::string(5000, '9') + "ms").find("out of range"), std::string::npos);
  EXPECT_NE(bad("106751d23h47m16s854ms775us808ns").find("out of range"), std::string::npos);
  EXPECT_NE(bad("5").find("no unit"), std::string::npos);
  EXPECT_NE(bad("1s2h").find("from days down"), std::string::npos);
  EXPECT_NE(bad("1s1s").find("at most once"), std::string::npos);
  EXPECT_NE(bad("1.5s3ms").find("only the last component"), std::string::npos);
  EXPECT_NE(bad("10 ms").find("unexpected ' '"), std::string::npos);
  EXPECT_NE(bad("10parsecs").find("unknown unit 'parsecs'"), std::string::npos);
  EXPECT_NE(bad("1e3ms").find("unknown unit 'e'"), std::string::npos);
  EXPECT_NE(bad("T#").find("no number"), std::string::npos);
  EXPECT_NE(bad("1__0ms").find("'_' only goes between digits"), std::string::npos);
  int64_t v = 0;
  std::string why;
  EXPECT_FALSE(parseDuration("-1ms", DurationSign::NonNegative, v, &why));
  EXPECT_NE(why.find("negative"), std::string::npos);
  EXPECT_FALSE(parseDuration("0s", DurationSign::Positive, v, &why));
  EXPECT_NE(why.find("not positive"), std::string::npos);
  EXPECT_EQ(formatDuration(5'400'000'000'000), "T#1h30m");
  EXPECT_EQ(formatDuration(-1), "T#-1ns");
  EXPECT_EQ(formatDuration(0), "T#0s");
}

TEST(ConfigSchema, Messages) {
  EXPECT_EQ(schemaError("[[axis]]\nname = \"A\"\nmax_velocty = 5.0\n", projectSchema()),
            "f.toml:3:1: error: unknown key 'max_velocty' in [[axis]]; did you mean 'max_velocity'?");
  EXPECT_EQ(schemaError("[[axis]]\nname = \"A\"\nkv = -100\n", projectSchema()),
            "f.toml:3:6: error: [[axis]] kv = -100: out of range (must be > 0 and <= 10000)");
  EXPECT_EQ(schemaError("[[axis]]\nname = \"A\"\nperiod = nan\n", projectSchema()),
            "f.toml:3:10: error: [[axis]] period = nan: the number must be finite");
  EXPECT_EQ(schemaError("duration = \"1s\"\n[[check]]\nvar = \"x\"\nmin = nan\n", scenarioSchema()),
            "f.toml:4:7: error: [[check]] min = nan: the number must be finite");
  EXPECT_EQ(schemaError("cycles = 1\nduration = \"1s\"\n", scenarioSchema()),
            "f.toml:1:1: error: the scenario needs exactly one of duration or cycles");
  // [[axis]] unit: 1 to 16 characters (UTF-8), none of them blank, control or a delimiter.
  for (const char* good : {"\"mm\"", "\"\u00b0\"", "\"m/min\"", "\"sixteen_chars_xx\""}) {
    std::string error;
    toml::table t = toml::parse(std::string("[[axis]]\nname = \"A\"\nunit = ") + good + "\n");
    EXPECT_TRUE(validate(t, projectSchema(), "f.toml", error)) << good << ": " << error;
  }
  for (const char* bad : {"\"\"", "\"m m\"", "\"a,b\"", "\"x#\"", "\"tab\\t\"", "\"seventeen_chars_x\""}) {
    std::string toml = std::string("[[axis]]\nname = \"A\"\nunit = ") + bad + "\n";
    std::string e = schemaError(toml.c_str(), projectSchema());
    EXPECT_NE(e.find("f.toml:3:8: error: [[axis]] unit = "), std::string::npos) << bad << ": " << e;
    EXPECT_NE(e.find("a unit of measure is expected"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_EQ(closest("trapezoid", {"trapez", "quadratic"}), "trapez");
  EXPECT_EQ(closest("zzz", {"trapez", "quadratic"}), "");
}
