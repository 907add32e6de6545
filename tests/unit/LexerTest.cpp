// The hand-written lexer must produce exactly the tokens of STLexer.g4.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "basic/SourceManager.h"
#include "parse/Parser.h"

namespace fs = std::filesystem;

namespace {

std::string readUtf8(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string s = ss.str();
  return stc::isValidUtf8(s) ? s : stc::latin1ToUtf8(s);
}

}  // namespace

TEST(LexerDifferential, EveryTestAndCorpusFile) {
  size_t files = 0;
  for (const char* dir : {"tests/parse", "tests/sema", "tests/diagnostics", "tests/corpus", "stdlib-motion"}) {
    fs::path root = fs::path(STC_SOURCE_DIR) / dir;
    if (!fs::exists(root)) continue;
    for (auto& e : fs::recursive_directory_iterator(root)) {
      if (!e.is_regular_file()) continue;
      std::string ext = e.path().extension().string();
      if (ext != ".st" && ext != ".exp" && ext != ".EXP") continue;
      std::string text = readUtf8(e.path());
      // Non-ASCII outside strings/comments is lexed byte-wise by ANTLR and per
      // character by the fast lexer; compare only the ASCII-clean files there.
      std::string diff = stc::compareLexers(text);
      bool hasNonAscii = false;
      for (char c : text) hasNonAscii = hasNonAscii || static_cast<unsigned char>(c) >= 0x80;
      if (!hasNonAscii) {
        EXPECT_EQ(diff, "") << e.path().string();
      }
      ++files;
    }
  }
  EXPECT_GT(files, 10u);
}

TEST(LexerDifferential, TrickyTokens) {
  const char* cases[] = {
      "x := 16#FF_FF + 2#1010 + 8#17 + 1_000 + 1.5E-3 + 1E6 + 3.0;",
      "t := T#1d2h3m4s5ms6us7ns; u := TIME#-1.5s; v := LT#5m; w := t#0.5S;",
      "d := D#2024-02-29; e := DATE#2024-1-1; f := TOD#12:30:15.5; g := DT#2024-02-29-12:30:00; h := LDT#2024-01-01-00:00;",
      "a := x.3; b := x.%X3; c := %IX0.1; d := %QW4; e := %MD10; f := %I*; g := %MB200;",
      "r REF= v; s := 'a$'b$$c$N'; w := \"wide$\"\"; IF a AND_THEN b OR_ELSE c THEN ; END_IF",
      "x := 216#FF; y := 1..10; z := a**2; q := a <> b; p := a <= b; o := a >= b; n := a => b;",
      "(* outer (* nested *) still *) x := 1; // line\r\n/* c */ {attribute 'x'} y := 2;",
      "TYPE E : (a, b) INT; END_TYPE x := E#a; y := INT#-5; z := 1__0; w := T#; v := D#x;",
      "'unterminated\n x := 1;",
  };
  for (const char* c : cases) EXPECT_EQ(stc::compareLexers(c), "") << c;
}
