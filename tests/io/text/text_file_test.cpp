// Reading whole input files (text/text_file.hpp): regular files only, refused at once otherwise (a FIFO must not
// block), and never more than the caller's limit.
#include "text/text_file.hpp"

#include <unistd.h>

#include <chrono>
#include <string>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "scratch_dir.hpp"
#include "special_files.hpp"

namespace rockfit::io {
namespace {

std::string ErrorOf(const std::filesystem::path& path, std::uint64_t max_bytes = 1000) {
  try {
    ReadRegularFile(path, "a test file", max_bytes);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "no error";
}

TEST(TextFile, ReadsARegularFileAndFollowsASymlink) {
  const testing::ScratchDir dir("text_file");
  dir.Write("a.txt", std::string("one\0two\n", 8));
  std::filesystem::create_symlink("a.txt", dir / "link");
  EXPECT_EQ(ReadRegularFile(dir / "a.txt", "a test file", 8), std::string("one\0two\n", 8));
  EXPECT_EQ(ReadRegularFile(dir / "link", "a test file", 8).size(), 8u);
}

TEST(TextFile, DirectoryFifoSocketAndDeviceAreRefusedAtOnceNamingWhatTheyAre) {
  const testing::ScratchDir dir("text_file_special");
  std::filesystem::create_directory(dir / "d");
  ASSERT_TRUE(testing::MakeFifo(dir / "fifo"));
  ASSERT_TRUE(testing::MakeSocketFile(dir / "socket"));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NE(ErrorOf(dir / "d").find("found a directory, expected a test file"), std::string::npos) << ErrorOf(dir / "d");
  EXPECT_NE(ErrorOf(dir / "fifo").find("found a FIFO (named pipe)"), std::string::npos) << ErrorOf(dir / "fifo");
  EXPECT_NE(ErrorOf(dir / "socket").find("found a socket"), std::string::npos) << ErrorOf(dir / "socket");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));  // nothing waited for a writer
  if (testing::MakeCharacterDevice(dir / "zero", 1, 5)) {  // the numbers of /dev/zero: never ends
    EXPECT_NE(ErrorOf(dir / "zero").find("found a character device"), std::string::npos) << ErrorOf(dir / "zero");
  }
}

TEST(TextFile, FileAboveTheLimitIsRefusedBeforeReadingNamingTheLimit) {
  const testing::ScratchDir dir("text_file_large");
  const std::filesystem::path big = dir / "big.txt";
  dir.Write("big.txt", "");
  std::filesystem::resize_file(big, 1001);  // sparse: no disk space, and never read
  const std::string message = ErrorOf(big, 1000);
  EXPECT_NE(message.find("a file of 1001 bytes"), std::string::npos) << message;
  EXPECT_NE(message.find("up to 0 MB (1000 bytes"), std::string::npos) << message;
  EXPECT_EQ(ReadRegularFile(big, "a test file", 1001).size(), 1001u);
}

TEST(TextFile, MissingFileOrNulInThePathIsBadInput) {
  const testing::ScratchDir dir("text_file_missing");
  EXPECT_NE(ErrorOf(dir / "none").find("No such file"), std::string::npos) << ErrorOf(dir / "none");
  const std::string nul = ErrorOf(std::string("a\0b.csv", 7));
  EXPECT_NE(nul.find("a\\0b.csv: path: found a NUL byte"), std::string::npos) << nul;
}

}  // namespace
}  // namespace rockfit::io
