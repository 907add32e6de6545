#include "vm/Trace.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

using namespace stc::vm;
namespace fs = std::filesystem;

namespace {

class TraceTest : public ::testing::Test {
protected:
  void SetUp() override {
    ::setenv("SOURCE_DATE_EPOCH", "1000000000", 1);   // a fixed VCD $date
    dir_ = fs::temp_directory_path() /
           ("stc-trace-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const char* name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  fs::path dir_;
};

TraceValue boolean(bool b) { return {b, 0, b ? "TRUE" : "FALSE"}; }
TraceValue integer(int64_t v, unsigned bits) {
  uint64_t mask = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
  return {static_cast<uint64_t>(v) & mask, 0, std::to_string(v)};
}
TraceValue real(double d, std::string lit) { return {0, d, std::move(lit)}; }
TraceValue text(std::string lit) { return {0, 0, std::move(lit)}; }

TEST_F(TraceTest, CsvGolden) {
  std::string error;
  auto w = TraceWriter::create(path("t.csv"),
                               {{"MAIN.run", TraceColumn::Bool},
                                {"GVL.n", TraceColumn::Int, 16, true},
                                {"x", TraceColumn::Real},
                                {"msg", TraceColumn::Text}},
                               error);
  ASSERT_TRUE(w) << error;
  w->sample(0, {boolean(false), integer(0, 16), real(0, "0.0"), text("''")});
  w->sample(1'000'000, {boolean(true), integer(-3, 16), real(1.5, "1.5"), text("'a,b'")});
  w->sample(1'500'000'000, {boolean(true), integer(7, 16), real(1e-7, "1.0E-07"), text("'say \"hi\"'")});
  w->sample(10'000'000'001, {boolean(false), integer(7, 16), real(2, "2.0"), text("'two words'")});
  ASSERT_TRUE(w->finish(10'001'000'001, error)) << error;
  EXPECT_EQ(read(path("t.csv")),
            "time,MAIN.run,GVL.n,x,msg\n"
            "0,FALSE,0,0.0,''\n"
            "0.001,TRUE,-3,1.5,\"'a,b'\"\n"
            "1.5,TRUE,7,1.0E-07,\"'say \"\"hi\"\"'\"\n"
            "10.000000001,FALSE,7,2.0,\"'two words'\"\n");
}

TEST_F(TraceTest, VcdGolden) {
  std::string error;
  auto w = TraceWriter::create(path("t.vcd"),
                               {{"MAIN.run", TraceColumn::Bool},
                                {"GVL.n", TraceColumn::Int, 16, true},
                                {"x", TraceColumn::Real},
                                {"t", TraceColumn::Int, 64}},
                               error);
  ASSERT_TRUE(w) << error;
  w->sample(0, {boolean(false), integer(10, 16), real(0.1, "0.1"), integer(0, 64)});
  w->sample(1'000'000, {boolean(false), integer(10, 16), real(0.1, "0.1"), integer(0, 64)});  // no change
  w->sample(2'000'000, {boolean(true), integer(-1, 16), real(0.1, "0.1"), integer(5, 64)});
  w->sample(3'000'000, {boolean(true), integer(0, 16), real(-2.5, "-2.5"), integer(5, 64)});
  ASSERT_TRUE(w->finish(4'000'000, error)) << error;
  EXPECT_EQ(read(path("t.vcd")),
            "$date 2001-09-09 01:46:40 UTC $end\n"
            "$version stc " STC_VERSION " $end\n"
            "$timescale 1ns $end\n"
            "$var real 64 # x $end\n"
            "$var wire 64 $ t $end\n"
            "$scope module MAIN $end\n"
            "$var wire 1 ! run $end\n"
            "$upscope $end\n"
            "$scope module GVL $end\n"
            "$var wire 16 \" n $end\n"
            "$upscope $end\n"
            "$enddefinitions $end\n"
            "#0\n"
            "$dumpvars\n"
            "0!\n"
            "b1010 \"\n"
            "r0.10000000000000001 #\n"
            "b0 $\n"
            "$end\n"
            "#2000000\n"
            "1!\n"
            "b1111111111111111 \"\n"
            "b101 $\n"
            "#3000000\n"
            "b0 \"\n"
            "r-2.5 #\n"
            "#4000000\n");
}

TEST_F(TraceTest, VcdScopesEnumsAndStrings) {
  std::string error;
  auto w = TraceWriter::create(path("s.vcd"),
                               {{"MAIN.fb.state", TraceColumn::Enum},
                                {"MAIN.fb.msg", TraceColumn::Text},
                                {"main.x", TraceColumn::Bool},
                                {"GVL.arr[1, 2].v", TraceColumn::Int, 8}},
                               error);
  ASSERT_TRUE(w) << error;
  w->sample(0, {text("E_State#Idle"), text("'two words'"), boolean(false), integer(1, 8)});
  w->sample(1'000'000, {text("E_State#Idle"), text("'two words'"), boolean(false), integer(1, 8)});
  w->sample(2'000'000, {text("E_State#Run"), text("''"), boolean(false), integer(1, 8)});
  // The run ends at the last sample: no second stamp.
  ASSERT_TRUE(w->finish(2'000'000, error)) << error;
  std::string vcd = read(path("s.vcd"));
  std::string defs = vcd.substr(vcd.find("$timescale"));
  EXPECT_EQ(defs,
            "$timescale 1ns $end\n"
            "$scope module MAIN $end\n"
            "$var wire 1 # x $end\n"
            "$scope module fb $end\n"
            "$var string 1 ! state $end\n"
            "$var string 1 \" msg $end\n"
            "$upscope $end\n"
            "$upscope $end\n"
            "$scope module GVL $end\n"
            "$scope module arr[1,_2] $end\n"
            "$var wire 8 $ v $end\n"
            "$upscope $end\n"
            "$upscope $end\n"
            "$enddefinitions $end\n"
            "#0\n"
            "$dumpvars\n"
            "sIdle !\n"
            "s'two$20words' \"\n"
            "0#\n"
            "b1 $\n"
            "$end\n"
            "#2000000\n"
            "sRun !\n"
            "s'' \"\n");
}

TEST_F(TraceTest, CsvUnitsLine) {
  std::string error;
  TraceColumn pos{"AxisX.fSetPosition", TraceColumn::Real};
  pos.unit = "mm";
  auto w = TraceWriter::create(path("u.csv"), {pos, {"GVL.n", TraceColumn::Int, 16, true}}, error);
  ASSERT_TRUE(w) << error;
  w->sample(0, {real(1.5, "1.5"), integer(2, 16)});
  ASSERT_TRUE(w->finish(1'000'000, error)) << error;
  EXPECT_EQ(read(path("u.csv")), "#units,mm,\ntime,AxisX.fSetPosition,GVL.n\n0,1.5,2\n");
}

TEST_F(TraceTest, VcdIdentifiersStayUniqueBeyond94Columns) {
  std::vector<TraceColumn> cols;
  std::vector<TraceValue> vals;
  for (int i = 0; i < 200; ++i) {
    cols.push_back({"v" + std::to_string(i), TraceColumn::Bool});
    vals.push_back(boolean(false));
  }
  std::string error;
  auto w = TraceWriter::create(path("many.vcd"), cols, error);
  ASSERT_TRUE(w) << error;
  w->sample(0, vals);
  ASSERT_TRUE(w->finish(1, error));
  std::istringstream in(read(path("many.vcd")));
  std::set<std::string> ids;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("$var", 0) != 0) continue;
    std::istringstream ls(line);
    std::string var, type, width, id;
    ls >> var >> type >> width >> id;
    for (char c : id) EXPECT_TRUE(c >= 33 && c <= 126);
    ids.insert(id);
  }
  EXPECT_EQ(ids.size(), 200u);
}

TEST_F(TraceTest, IdenticalInputGivesIdenticalBytes) {
  auto write = [&](const char* name) {
    std::string error;
    auto w = TraceWriter::create(path(name), {{"a", TraceColumn::Int, 32}, {"r", TraceColumn::Real}}, error);
    for (int i = 0; i < 1000; ++i)
      w->sample(i * 1'000'000, {integer(i / 7, 32), real(std::sin(i * 0.01), "x")});
    EXPECT_TRUE(w->finish(1'000'000'000, error));
    return read(path(name));
  };
  std::string a = write("a.vcd"), b = write("b.vcd");
  EXPECT_EQ(a, b);
  EXPECT_GT(a.size(), 10'000u);
}

TEST_F(TraceTest, Errors) {
  std::string error;
  EXPECT_FALSE(TraceWriter::create(path("t.txt"), {{"a", TraceColumn::Bool}}, error));
  EXPECT_EQ(error, "trace file '" + path("t.txt") + "' must end in .csv or .vcd");
  error.clear();
  EXPECT_FALSE(TraceWriter::create(path("no/such/dir/t.csv"), {{"a", TraceColumn::Bool}}, error));
  EXPECT_NE(error.find("cannot open"), std::string::npos);
  EXPECT_TRUE(TraceWriter::create(path("UPPER.CSV"), {{"a", TraceColumn::Bool}}, error));
}

}  // namespace
