#include "vm/Trace.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
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

// The golden traces' REAL form (stc test): the fewest digits within half the tolerance.
TEST(TraceRealTest, ShortestWithinTolerance) {
  EXPECT_EQ(formatTraceReal(-7.105427357601197E-13, false, 1e-9), "0.0");   // noise around a zero
  EXPECT_EQ(formatTraceReal(9.9e-10, false, 1e-9), "0.0");
  EXPECT_EQ(formatTraceReal(-0.0, false, 0), "0.0");
  EXPECT_EQ(formatTraceReal(0.0, false, 1e-9), "0.0");
  EXPECT_EQ(formatTraceReal(450.0, false, 1e-9), "450.0");
  EXPECT_EQ(formatTraceReal(449.99999999999994, false, 1e-9), "450.0");
  EXPECT_EQ(formatTraceReal(0.1 + 0.2, false, 1e-9), "0.3");
  EXPECT_EQ(formatTraceReal(-123.456789012345, false, 1e-9), "-123.456789");
  EXPECT_EQ(formatTraceReal(-123.456789012345, false, 1e-3), "-123.5");
  EXPECT_EQ(formatTraceReal(1.2345678901234567e20, false, 1e-9), "1.23456789E+20");
  EXPECT_EQ(formatTraceReal(-2.5e-7, false, 1e-9), "-2.5E-07");
  EXPECT_EQ(formatTraceReal(1.0 / 3, false, 1e-9), "0.333333333");
  // Tolerance 0: the exact literal, as stc run writes it.
  EXPECT_EQ(formatTraceReal(1.0 / 3, false, 0), "0.3333333333333333");
  EXPECT_EQ(formatTraceReal(1e-12, false, 0), "1.0E-12");
  // A REAL: its own literal when that is close enough read as an LREAL, else more digits.
  EXPECT_EQ(formatTraceReal(static_cast<float>(0.1), true, 0), "0.1");
  EXPECT_EQ(formatTraceReal(static_cast<float>(0.1), true, 1e-6), "0.1");
  EXPECT_EQ(formatTraceReal(static_cast<float>(0.1), true, 1e-9), "0.100000001");
  EXPECT_EQ(formatTraceReal(static_cast<float>(1.5), true, 1e-9), "1.5");
  // Not numbers.
  EXPECT_EQ(formatTraceReal(std::nan(""), false, 1e-9), "NaN");
  EXPECT_EQ(formatTraceReal(HUGE_VAL, false, 1e-9), "Inf");
  EXPECT_EQ(formatTraceReal(-HUGE_VAL, true, 1e-9), "-Inf");
  EXPECT_EQ(formatTraceReal(1e300, false, 1e-9), "1.0E+300");
  EXPECT_EQ(formatTraceReal(-1.7976931348623157e308, false, 0), "-1.7976931348623157E+308");
}

// Every value, written and read back, compares equal to itself again under stc test's
// rule |actual - expected| <= tolerance * max(1, |expected|), and no shorter form would
// be within half the tolerance.
TEST(TraceRealTest, RoundTripWithinTolerance) {
  uint64_t seed = 12345;
  auto next = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return seed >> 11;
  };
  for (double tol : {1e-12, 1e-9, 1e-6, 1e-3, 0.5}) {
    for (int i = 0; i < 20000; ++i) {
      const double mant = static_cast<double>(next()) / static_cast<double>(1ull << 53) * 2 - 1;
      const int exp10 = static_cast<int>(next() % 60) - 30;
      const double v = mant * std::pow(10.0, exp10);
      const std::string s = formatTraceReal(v, false, tol);
      const double x = std::strtod(s.c_str(), nullptr);
      if (std::fabs(v) < tol) {
        EXPECT_EQ(s, "0.0") << v;
        continue;
      }
      ASSERT_LE(std::fabs(x - v), tol * std::max(1.0, std::fabs(v)) / 2) << v << " " << tol << " " << s;
      ASSERT_LE(std::fabs(v - x), tol * std::max(1.0, std::fabs(x))) << v << " " << tol << " " << s;
      // Minimal: one significant digit fewer is not close enough.
      std::string written = s.substr(0, s.find('E'));
      std::string sig;
      for (char c : written)
        if (c >= '0' && c <= '9') sig += c;
      sig.erase(0, sig.find_first_not_of('0'));
      sig.erase(sig.find_last_not_of('0') + 1);
      const size_t significant = sig.size();
      if (significant > 1) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.*e", static_cast<int>(significant) - 2, v);
        ASSERT_GT(std::fabs(std::strtod(buf, nullptr) - v), tol * std::max(1.0, std::fabs(v)) / 2) << v << " " << s << " " << buf;
      }
    }
  }
}

TEST_F(TraceTest, CsvSampledEvery) {
  std::string error;
  CsvTraceOptions o;
  o.tolerance = 1e-9;
  o.every = 10'000'000;   // 10 ms
  auto w = TraceWriter::create(path("s.csv"), {{"n", TraceColumn::Int, 32}, {"x", TraceColumn::Real, 64}}, error, o);
  ASSERT_TRUE(w) << error;
  for (int i = 0; i <= 25; ++i) w->sample(i * 1'000'000, {integer(i, 32), real(i * 0.1 + (i == 10 ? -7.105427357601197E-15 : 0.0), "x")});
  ASSERT_TRUE(w->finish(26 * 1'000'000, error)) << error;
  EXPECT_EQ(read(path("s.csv")), "time,n,x\n0,0,0.0\n0.01,10,1.0\n0.02,20,2.0\n");
}

TEST_F(TraceTest, CsvSampledOnChange) {
  std::string error;
  CsvTraceOptions o;
  o.tolerance = 1e-9;
  o.onChange = true;
  auto w = TraceWriter::create(path("c.csv"), {{"b", TraceColumn::Bool}, {"x", TraceColumn::Real, 64}}, error, o);
  ASSERT_TRUE(w) << error;
  // x changes below the tolerance at 2 ms (the same as written: no row), b at 3 ms.
  const double xs[] = {1.5, 1.5, 1.5 + 1e-12, 1.5, 1.5, 2.0, 2.0};
  const bool bs[] = {false, false, false, true, true, true, true};
  for (int i = 0; i < 7; ++i) w->sample(i * 1'000'000, {boolean(bs[i]), real(xs[i], "x")});
  ASSERT_TRUE(w->finish(7'000'000, error)) << error;
  // The first row, the changes, and the last sample (unchanged, but it ends the trace).
  EXPECT_EQ(read(path("c.csv")), "time,b,x\n0,FALSE,1.5\n0.003,TRUE,1.5\n0.005,TRUE,2.0\n0.006,TRUE,2.0\n");
  // The last sample is not repeated when it was a change.
  auto w2 = TraceWriter::create(path("d.csv"), {{"b", TraceColumn::Bool}}, error, o);
  w2->sample(0, {boolean(false)});
  w2->sample(1'000'000, {boolean(true)});
  ASSERT_TRUE(w2->finish(2'000'000, error)) << error;
  EXPECT_EQ(read(path("d.csv")), "time,b\n0,FALSE\n0.001,TRUE\n");
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
