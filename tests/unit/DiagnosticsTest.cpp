#include <gtest/gtest.h>

#include "basic/Diagnostics.h"

using namespace stc;

TEST(SourceManager, LineAndColumnWithCrlf) {
  SourceManager sm;
  uint32_t f = sm.addBuffer("a.st", "ab\r\ncd\ref\n");
  EXPECT_EQ(sm.lineCol({f, 0}).line, 1u);
  EXPECT_EQ(sm.lineCol({f, 4}).line, 2u);
  EXPECT_EQ(sm.lineCol({f, 5}).col, 2u);
  EXPECT_EQ(sm.lineCol({f, 7}).line, 3u);
  EXPECT_EQ(sm.lineText({f, 4}), "cd");
}

TEST(SourceManager, Latin1IsConvertedToUtf8) {
  SourceManager sm;
  uint32_t f = sm.addBuffer("a.exp", std::string("x\xE4y"));
  EXPECT_TRUE(sm.file(f).convertedFromLatin1);
  EXPECT_EQ(sm.file(f).text, "x\xC3\xA4y");
}

TEST(SourceManager, Utf8IsKept) {
  SourceManager sm;
  uint32_t f = sm.addBuffer("a.st", "'\xE4\xB8\xAD'");
  EXPECT_FALSE(sm.file(f).convertedFromLatin1);
}

TEST(Diagnostics, RendersClangStyleWithCaretAndRange) {
  SourceManager sm;
  uint32_t f = sm.addBuffer("m.st", "x := foo + 1;\n");
  DiagnosticsEngine de(sm);
  de.error({f, 5}, "use of undeclared identifier 'foo'", "undeclared-name").range({{f, 5}, {f, 8}});
  ASSERT_EQ(de.diagnostics().size(), 1u);
  std::string text = renderText(sm, de.diagnostics()[0]);
  EXPECT_EQ(text, "m.st:1:6: error: use of undeclared identifier 'foo' [undeclared-name]\n  x := foo + 1;\n       ^~~\n");
}

TEST(Diagnostics, WarningsCanBeDisabledOrPromoted) {
  SourceManager sm;
  uint32_t f = sm.addBuffer("m.st", "x\n");
  DiagnosticsEngine de(sm);
  de.opts.disabledWarnings.insert("unused-variable");
  de.warning({f, 0}, "unused", "unused-variable");
  EXPECT_EQ(de.warningCount(), 0u);
  de.opts.warningsAsErrors = true;
  de.warning({f, 0}, "other", "narrowing");
  EXPECT_EQ(de.errorCount(), 1u);
}

TEST(Diagnostics, ErrorLimitStopsCounting) {
  SourceManager sm;
  uint32_t f = sm.addBuffer("m.st", "x\n");
  DiagnosticsEngine de(sm);
  de.opts.errorLimit = 2;
  for (int i = 0; i < 5; ++i) de.error({f, 0}, "e");
  EXPECT_EQ(de.errorCount(), 2u);
}

TEST(Diagnostics, JsonHasLocationsAndFixits) {
  SourceManager sm;
  uint32_t f = sm.addBuffer("m.st", "IF x THEN\n");
  DiagnosticsEngine de(sm);
  de.error({f, 3}, "msg", "code").fixit({{f, 3}, {f, 4}}, "y");
  std::string j = renderJson(sm, de.diagnostics());
  EXPECT_NE(j.find("\"line\": 1"), std::string::npos);
  EXPECT_NE(j.find("\"column\": 4"), std::string::npos);
  EXPECT_NE(j.find("\"replacement\": \"y\""), std::string::npos);
}

TEST(EditDistance, FindsCloseNames) {
  EXPECT_EQ(editDistance("ELSEIF", "ELSIF"), 1u);
  EXPECT_EQ(closestMatch("counter", {"Counter1", "timer", "countr"}), "Counter1");
  EXPECT_EQ(closestMatch("abc", {"xyz"}), "");
}
