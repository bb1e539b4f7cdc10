#include "rockfit/io/atomic_file.hpp"

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

std::string Read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::size_t EntriesIn(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WritesAndReplaces) {
  const testing::ScratchDir dir("atomic");
  WriteFileAtomically(dir / "a.csv", [](std::ostream& out) { out << "one\n"; });
  WriteFileAtomically(dir / "a.csv", [](std::ostream& out) { out << "two\n"; });
  EXPECT_EQ(Read(dir / "a.csv"), "two\n");
  EXPECT_EQ(EntriesIn(dir.path()), 1u);
}

TEST(AtomicFile, AFailureWhileWritingLeavesThePreviousFileAndNoTemporary) {
  const testing::ScratchDir dir("atomic");
  WriteFileAtomically(dir / "a.csv", [](std::ostream& out) { out << "previous\n"; });
  EXPECT_THROW(WriteFileAtomically(dir / "a.csv",
                                   [](std::ostream& out) {
                                     out << "half";
                                     throw NumericalFailure("stopped");
                                   }),
               NumericalFailure);
  EXPECT_EQ(Read(dir / "a.csv"), "previous\n");
  EXPECT_EQ(EntriesIn(dir.path()), 1u);
}

TEST(AtomicFile, MissingDirectoryOrDirectoryTargetIsAnOutputError) {
  const testing::ScratchDir dir("atomic");
  EXPECT_THROW(WriteFileAtomically(dir / "no/such/dir/a.csv", [](std::ostream&) {}), OutputError);
  try {
    WriteFileAtomically(dir / "no/such/dir/a.csv", [](std::ostream&) {});
  } catch (const OutputError& e) {
    // The message names the file the user asked for, not only the directory of the temporary file.
    EXPECT_NE(std::string(e.what()).find((dir / "no/such/dir/a.csv").string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(WriteFileAtomically(dir.path(), [](std::ostream&) {}), OutputError);
}

}  // namespace
}  // namespace rockfit::io
