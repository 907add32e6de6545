#include "vm/Retain.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

using namespace stc::vm;
namespace fs = std::filesystem;

namespace {

RetainLoad loadRetainFile(const std::string& file, std::vector<RetainEntry>& out, std::string& error) {
  uint32_t version = 0;
  return stc::vm::loadRetainFile(file, out, version, error);
}

class RetainTest : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("stc-retain-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    file_ = (dir_ / "plc.ret").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<uint8_t> bytes() const {
    std::ifstream in(file_, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  void writeBytes(const std::vector<uint8_t>& b) const {
    std::ofstream out(file_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
  }
  fs::path dir_;
  std::string file_;
};

std::vector<RetainEntry> sample() {
  return {{"GVL.a", "UDINT", {1, 2, 3, 4}},
          {"MAIN.fb", "FB:TON{IN:BOOL,PT:TIME}", std::vector<uint8_t>(300, 0xAB)},
          {"GVL.empty", "", {}}};
}

TEST(Crc32, KnownVector) {
  const char* s = "123456789";
  EXPECT_EQ(crc32(reinterpret_cast<const uint8_t*>(s), 9), 0xCBF43926u);
  EXPECT_EQ(crc32(nullptr, 0), 0u);
}

TEST_F(RetainTest, RoundTrip) {
  std::string error;
  ASSERT_TRUE(saveRetainFile(file_, sample(), error)) << error;
  EXPECT_FALSE(fs::exists(file_ + ".tmp"));
  std::vector<RetainEntry> got;
  ASSERT_EQ(loadRetainFile(file_, got, error), RetainLoad::Ok) << error;
  auto want = sample();
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].path, want[i].path);
    EXPECT_EQ(got[i].signature, want[i].signature);
    EXPECT_EQ(got[i].bytes, want[i].bytes);
  }
}

TEST_F(RetainTest, ExactLayout) {
  std::string error;
  ASSERT_TRUE(saveRetainFile(file_, {{"a", "BOOL", {1}}}, error)) << error;
  std::vector<uint8_t> want = {'S', 'T', 'C', 'R', 'E', 'T', '0', '1', 2, 0, 0, 0, 1, 0, 0, 0,
                               1,   0,   0,   0,   'a', 4,   0,   0,   0, 'B', 'O', 'O', 'L',
                               1,   0,   0,   0,   1};
  uint32_t crc = crc32(want.data(), want.size());
  for (int i = 0; i < 4; ++i) want.push_back(static_cast<uint8_t>(crc >> (8 * i)));
  EXPECT_EQ(bytes(), want);
}

TEST_F(RetainTest, SaveReplacesTheOldFile) {
  std::string error;
  ASSERT_TRUE(saveRetainFile(file_, sample(), error));
  ASSERT_TRUE(saveRetainFile(file_, {{"x", "INT", {9, 9}}}, error));
  std::vector<RetainEntry> got;
  ASSERT_EQ(loadRetainFile(file_, got, error), RetainLoad::Ok);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].path, "x");
}

TEST_F(RetainTest, Missing) {
  std::string error;
  std::vector<RetainEntry> got;
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Missing);
  EXPECT_TRUE(got.empty());
}

TEST_F(RetainTest, BadCrcIsDamaged) {
  std::string error;
  ASSERT_TRUE(saveRetainFile(file_, sample(), error));
  auto b = bytes();
  b[30] ^= 0x01;  // inside the first entry
  writeBytes(b);
  std::vector<RetainEntry> got;
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Damaged);
  EXPECT_EQ(error, "'" + file_ + "' is damaged (bad checksum)");
  EXPECT_TRUE(got.empty());
}

TEST_F(RetainTest, TruncatedFilesAreDamagedForeignFilesForeign) {
  std::string error;
  ASSERT_TRUE(saveRetainFile(file_, sample(), error));
  auto b = bytes();
  std::vector<RetainEntry> got;
  writeBytes({b.begin(), b.begin() + 20});
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Damaged);
  writeBytes({'h', 'e', 'l', 'l', 'o'});
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Foreign);
  EXPECT_EQ(error, "'" + file_ + "' is not a retain file (it does not start with STCRET)");
  writeBytes({});
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Missing);   // nothing to keep

  // A valid CRC over a malformed body: an entry size beyond the end.
  std::vector<uint8_t> bad = {'S', 'T', 'C', 'R', 'E', 'T', '0', '1', 1, 0, 0, 0, 1, 0, 0, 0, 200, 0, 0, 0};
  uint32_t crc = crc32(bad.data(), bad.size());
  for (int i = 0; i < 4; ++i) bad.push_back(static_cast<uint8_t>(crc >> (8 * i)));
  writeBytes(bad);
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Damaged);
  EXPECT_EQ(error, "'" + file_ + "' is damaged (truncated entry 0)");
  EXPECT_TRUE(got.empty());
}

TEST_F(RetainTest, LeftoverTmpIsRemoved) {
  std::string error;
  ASSERT_TRUE(saveRetainFile(file_, sample(), error));
  { std::ofstream(file_ + ".tmp") << "STCRET01half-written"; }
  std::vector<RetainEntry> got;
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Ok);
  EXPECT_EQ(got.size(), 3u);
  EXPECT_FALSE(fs::exists(file_ + ".tmp"));

  // Also when FILE itself is missing.
  fs::remove(file_);
  { std::ofstream(file_ + ".tmp"); }   // killed before the first write
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Missing);
  EXPECT_FALSE(fs::exists(file_ + ".tmp"));
}

TEST_F(RetainTest, SaveIntoMissingDirectoryFails) {
  std::string error;
  EXPECT_FALSE(saveRetainFile((dir_ / "nope" / "x.ret").string(), sample(), error));
  EXPECT_NE(error.find("cannot create"), std::string::npos);
}

}  // namespace

namespace {
std::vector<uint8_t> withCrc(std::vector<uint8_t> b) {
  uint32_t crc = crc32(b.data(), b.size());
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<uint8_t>(crc >> (8 * i)));
  return b;
}
}  // namespace

TEST_F(RetainTest, NewerFormatsAreNewer) {
  std::vector<RetainEntry> got;
  std::string error;
  writeBytes(withCrc({'S', 'T', 'C', 'R', 'E', 'T', '0', '1', 3, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Newer);
  EXPECT_NE(error.find("format version 3, newer than this stc reads (1 to 2)"), std::string::npos) << error;
  writeBytes({'S', 'T', 'C', 'R', 'E', 'T', '0', '2', 1, 2, 3});
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Newer);
  // Version 1 files (whole variables) are still read.
  writeBytes(withCrc({'S', 'T', 'C', 'R', 'E', 'T', '0', '1', 1, 0, 0, 0, 0, 0, 0, 0}));
  uint32_t version = 0;
  EXPECT_EQ(stc::vm::loadRetainFile(file_, got, version, error), RetainLoad::Ok);
  EXPECT_EQ(version, 1u);
}

TEST_F(RetainTest, UnreadableIsNotMissing) {
  std::vector<RetainEntry> got;
  std::string error;
  fs::create_directories(file_);   // a directory where the file should be
  EXPECT_EQ(loadRetainFile(file_, got, error), RetainLoad::Unreadable);
  EXPECT_FALSE(retainWritable(file_, error));
}

TEST_F(RetainTest, SavesThroughSymbolicLinksAndKeepsTheMode) {
  fs::create_directories(dir_ / "real");
  const std::string target = (dir_ / "real" / "plc.ret").string();
  fs::create_symlink("real/plc.ret", file_);   // dangling: the first save creates the target
  std::string error;
  ASSERT_TRUE(saveRetainFile(file_, sample(), error)) << error;
  EXPECT_TRUE(fs::is_symlink(file_));
  EXPECT_TRUE(fs::is_regular_file(target));
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write);
  ASSERT_TRUE(saveRetainFile(file_, {{"x", "INT", {9, 9}}}, error)) << error;
  EXPECT_TRUE(fs::is_symlink(file_));
  EXPECT_EQ(fs::status(target).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_FALSE(fs::exists(target + ".tmp"));
  std::vector<RetainEntry> got;
  ASSERT_EQ(loadRetainFile(file_, got, error), RetainLoad::Ok) << error;
  ASSERT_EQ(got.size(), 1u);
  std::string t;
  EXPECT_TRUE(retainTarget(file_, t, error));
  EXPECT_EQ(t, dir_.string() + "/real/plc.ret");
  // A link loop is an error, not a hang.
  fs::create_symlink("loop2", dir_ / "loop1");
  fs::create_symlink("loop1", dir_ / "loop2");
  EXPECT_FALSE(saveRetainFile((dir_ / "loop1").string(), sample(), error));
}

TEST_F(RetainTest, AForeignTmpIsNeverOverwritten) {
  { std::ofstream(file_ + ".tmp") << "someone else's notes"; }
  std::string error;
  EXPECT_FALSE(saveRetainFile(file_, sample(), error));
  EXPECT_NE(error.find("is in the way"), std::string::npos) << error;
  std::ifstream in(file_ + ".tmp");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "someone else's notes");
}
