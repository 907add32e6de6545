// vm/FileSandbox: the one place that decides which files a program may open (docs/security.md).
#include "vm/FileSandbox.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

using namespace stc::vm;
namespace fs = std::filesystem;

namespace {

class FileSandboxTest : public ::testing::Test {
protected:
  void SetUp() override {
    top_ = fs::temp_directory_path() /
           ("stc-sandbox-" + std::to_string(::getpid()) + "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(top_ / "data" / "sub");
    root_ = (top_ / "data").string();
    std::ofstream(top_ / "secret.txt") << "secret";
    std::ofstream(top_ / "data" / "in.txt") << "inside";
  }
  void TearDown() override { fs::remove_all(top_); }
  int open(const std::string& name, FileAccess a) {
    why_.clear();
    return openInside(root_, name, a, why_);
  }
  std::string text(const fs::path& p) {
    std::ifstream in(p);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  fs::path top_;
  std::string root_, why_;
};

TEST_F(FileSandboxTest, ReadsAndWritesInside) {
  int fd = open("in.txt", FileAccess::Read);
  ASSERT_GE(fd, 0) << why_;
  std::string t;
  EXPECT_EQ(readAndClose(fd, 100, t), ReadResult::Ok);
  EXPECT_EQ(t, "inside");
  fd = open("sub/../new.txt", FileAccess::Write);   // '..' that stays inside
  ASSERT_GE(fd, 0) << why_;
  ASSERT_EQ(::write(fd, "x", 1), 1);
  ::close(fd);
  EXPECT_EQ(text(top_ / "data" / "new.txt"), "x");
  fd = open("in.txt", FileAccess::Read);
  EXPECT_EQ(readAndClose(fd, 3, t), ReadResult::TooBig);
}

TEST_F(FileSandboxTest, RefusesAbsoluteAndDotDot) {
  EXPECT_LT(open((top_ / "secret.txt").string(), FileAccess::Read), 0);
  EXPECT_NE(why_.find("an absolute path"), std::string::npos) << why_;
  EXPECT_LT(open("../secret.txt", FileAccess::Write), 0);
  EXPECT_NE(why_.find("'..' leads outside"), std::string::npos) << why_;
  EXPECT_LT(open("sub/../../secret.txt", FileAccess::Read), 0);
  EXPECT_LT(open("", FileAccess::Read), 0);
  EXPECT_EQ(text(top_ / "secret.txt"), "secret");
}

TEST_F(FileSandboxTest, RefusesLinksOutButFollowsLinksInside) {
  fs::create_symlink("../secret.txt", top_ / "data" / "out.txt");
  fs::create_directory_symlink(top_, top_ / "data" / "updir");
  fs::create_symlink("in.txt", top_ / "data" / "alias.txt");
  fs::create_symlink("nowhere.txt", top_ / "data" / "dangling.txt");
  EXPECT_LT(open("out.txt", FileAccess::Read), 0);
  EXPECT_NE(why_.find("through a symbolic link"), std::string::npos) << why_;
  EXPECT_LT(open("out.txt", FileAccess::Write), 0);
  EXPECT_LT(open("updir/secret.txt", FileAccess::Write), 0);
  EXPECT_LT(open("updir/brand_new.txt", FileAccess::Write), 0);
  EXPECT_LT(open("dangling.txt", FileAccess::Write), 0);   // not followed to create its target
  EXPECT_FALSE(fs::exists(top_ / "data" / "nowhere.txt"));
  EXPECT_FALSE(fs::exists(top_ / "brand_new.txt"));
  EXPECT_EQ(text(top_ / "secret.txt"), "secret");
  int fd = open("alias.txt", FileAccess::Read);
  ASSERT_GE(fd, 0) << why_;
  ::close(fd);
  std::string resolved;
  EXPECT_TRUE(resolveInside(root_, "alias.txt", resolved, why_)) << why_;
  EXPECT_EQ(fs::path(resolved).filename(), "in.txt");
}

TEST_F(FileSandboxTest, OnlyRegularFilesAndNoHardLinksForWrites) {
  ASSERT_EQ(::mkfifo((top_ / "data" / "fifo").c_str(), 0600), 0);
  EXPECT_LT(open("fifo", FileAccess::Read), 0);    // no hang
  EXPECT_LT(open("fifo", FileAccess::Write), 0);
  EXPECT_LT(open("sub", FileAccess::Read), 0);
  fs::create_hard_link(top_ / "secret.txt", top_ / "data" / "hard.txt");
  EXPECT_LT(open("hard.txt", FileAccess::Write), 0);
  EXPECT_NE(why_.find("hard links"), std::string::npos) << why_;
  EXPECT_EQ(text(top_ / "secret.txt"), "secret");   // not truncated
}

TEST_F(FileSandboxTest, CreatesTheRootAndOnlyWithMakeDirsSubdirectories) {
  root_ = (top_ / "fresh").string();
  EXPECT_LT(open("x.txt", FileAccess::Read), 0);
  EXPECT_FALSE(fs::exists(top_ / "fresh"));
  int fd = open("x.txt", FileAccess::Write);
  ASSERT_GE(fd, 0) << why_;
  ::close(fd);
  EXPECT_LT(open("a/b.txt", FileAccess::Write), 0);
  fd = open("a/b.txt", FileAccess::WriteMakeDirs);
  ASSERT_GE(fd, 0) << why_;
  ::close(fd);
  EXPECT_TRUE(fs::is_regular_file(top_ / "fresh" / "a" / "b.txt"));
  root_ = (top_ / "no" / "parent").string();
  EXPECT_LT(open("x.txt", FileAccess::Write), 0);
}

}  // namespace
