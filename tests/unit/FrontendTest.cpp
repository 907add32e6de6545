// Front-end behaviour seen through the driver API.
#include <gtest/gtest.h>

#include "driver/Driver.h"

using namespace stc;

namespace {

struct Result {
  bool ok;
  std::vector<std::string> messages;
};

Result check(const std::string& src, sema::Dialect d = sema::Dialect::IEC) {
  Compilation c;
  c.addBuffer("t.st", src);
  CompileOptions o;
  o.dialect = d;
  bool ok = false;
  runWithLargeStack([&] { ok = c.check(o); });
  Result r{ok, {}};
  for (const Diagnostic& x : c.diags().diagnostics()) r.messages.push_back(x.message);
  return r;
}

}  // namespace

TEST(Frontend, EmptyFileIsClean) {
  EXPECT_TRUE(check("").ok);
}

TEST(Frontend, ManyErrorsInOneRun) {
  Result r = check("PROGRAM P\nVAR x : INT; END_VAR\nx := a;\nx := b;\nx := c;\nEND_PROGRAM\n");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.messages.size(), 3u);
}

TEST(Frontend, ArbitraryBytesNeverCrash) {
  std::string junk;
  for (int i = 0; i < 2000; ++i) junk += static_cast<char>((i * 7919) % 256);
  Result r = check(junk);
  EXPECT_FALSE(r.ok);
}

TEST(Frontend, DeepNestingIsReportedNotOverflowed) {
  std::string s = "PROGRAM P VAR x : INT; END_VAR x := ";
  for (int i = 0; i < 5000; ++i) s += "(";
  s += "1";
  for (int i = 0; i < 5000; ++i) s += ")";
  s += "; END_PROGRAM";
  Result r = check(s);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.messages.empty());
  EXPECT_NE(r.messages[0].find("nested"), std::string::npos);
}

TEST(Frontend, LongExpressionChainsWork) {
  std::string s = "PROGRAM P VAR x : DINT; END_VAR x := 0";
  for (int i = 0; i < 20000; ++i) s += " + 1";
  s += "; END_PROGRAM";
  EXPECT_TRUE(check(s).ok);
}
