#include "rockfit/io/atomic_file.hpp"

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "scratch_dir.hpp"
#include "special_files.hpp"

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

TEST(AtomicFile, DeviceFifoOrSocketTargetIsRefusedAndLeftInPlace) {
  const testing::ScratchDir dir("atomic_special");
  if (!testing::MakeCharacterDevice(dir / "null", testing::kNullDeviceMajor, testing::kNullDeviceMinor) ||
      !testing::MakeCharacterDevice(dir / "full", testing::kFullDeviceMajor, testing::kFullDeviceMinor)) {
    GTEST_SKIP() << "mknod needs root";
  }
  ASSERT_TRUE(testing::MakeFifo(dir / "fifo"));
  ASSERT_TRUE(testing::MakeSocketFile(dir / "socket"));
  for (const char* name : {"null", "full", "fifo", "socket"}) {
    const mode_t type = testing::FileTypeOf(dir / name);
    try {
      WriteFileAtomically(dir / name, [](std::ostream& out) { out << "data\n"; });
      ADD_FAILURE() << name << " was written";
    } catch (const OutputError& e) {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
    EXPECT_EQ(testing::FileTypeOf(dir / name), type) << name << " was replaced";
  }
  EXPECT_EQ(EntriesIn(dir.path()), 4u);  // no temporary left
}

TEST(AtomicFile, SymlinkIsFollowedTheFileItNamesIsReplacedAndTheLinkStays) {
  const testing::ScratchDir dir("atomic_link");
  WriteFileAtomically(dir / "real.csv", [](std::ostream& out) { out << "old\n"; });
  std::filesystem::create_symlink("real.csv", dir / "link.csv");
  WriteFileAtomically(dir / "link.csv", [](std::ostream& out) { out << "new\n"; });
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.csv"));
  EXPECT_EQ(Read(dir / "real.csv"), "new\n");
  // A link to a missing file: the file is created where the link points.
  std::filesystem::create_symlink("sub/later.csv", dir / "dangling.csv");
  std::filesystem::create_directory(dir / "sub");
  WriteFileAtomically(dir / "dangling.csv", [](std::ostream& out) { out << "later\n"; });
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "dangling.csv"));
  EXPECT_EQ(Read(dir / "sub" / "later.csv"), "later\n");
  // A link to a device is refused like the device.
  if (testing::MakeCharacterDevice(dir / "null", testing::kNullDeviceMajor, testing::kNullDeviceMinor)) {
    std::filesystem::create_symlink("null", dir / "to-null");
    EXPECT_THROW(WriteFileAtomically(dir / "to-null", [](std::ostream& out) { out << "x"; }), OutputError);
    EXPECT_EQ(testing::FileTypeOf(dir / "null"), static_cast<mode_t>(S_IFCHR));
  }
  std::filesystem::create_symlink("loop", dir / "loop");
  EXPECT_THROW(WriteFileAtomically(dir / "loop", [](std::ostream& out) { out << "x"; }), OutputError);
}

TEST(AtomicReplacement, TargetIsUntouchedUntilCommitAndTheTemporaryLivesBesideIt) {
  const testing::ScratchDir dir("atomic");
  WriteFileAtomically(dir / "fig.png", [](std::ostream& out) { out << "old"; });
  AtomicReplacement replacement(dir / "fig.png");
  EXPECT_EQ(replacement.temporary().parent_path(), dir.path());
  EXPECT_EQ(replacement.temporary().filename().string().rfind(std::string(".fig.png") + kTemporaryMarker, 0), 0u)
      << replacement.temporary();
  {
    // The way an external program (gnuplot) fills it: by the temporary's name.
    std::ofstream out(replacement.temporary());
    out << "new";
  }
  EXPECT_EQ(Read(dir / "fig.png"), "old");
  replacement.Commit();
  EXPECT_EQ(Read(dir / "fig.png"), "new");
  EXPECT_EQ(EntriesIn(dir.path()), 1u);
}

TEST(AtomicReplacement, AnUncommittedReplacementRemovesItsTemporary) {
  const testing::ScratchDir dir("atomic");
  WriteFileAtomically(dir / "a.csv", [](std::ostream& out) { out << "old\n"; });
  {
    AtomicReplacement replacement(dir / "a.csv");
    replacement.Write([](std::ostream& out) { out << "new\n"; });
    EXPECT_EQ(EntriesIn(dir.path()), 2u);
  }
  EXPECT_EQ(Read(dir / "a.csv"), "old\n");
  EXPECT_EQ(EntriesIn(dir.path()), 1u);
}

TEST(AtomicReplacement, ADirectoryOrAnEmptyNameIsNotATarget) {
  const testing::ScratchDir dir("atomic");
  EXPECT_THROW(AtomicReplacement replacement(dir.path()), OutputError);
  EXPECT_THROW(AtomicReplacement replacement(dir / ""), OutputError);
}

TEST(AtomicFile, TemporaryNameCarriesTargetProcessAndSerial) {
  EXPECT_EQ(TemporaryPathFor("/data/run/out.h5", 1234, 5), std::filesystem::path("/data/run/.out.h5.rockfit-tmp-1234-5"));
  EXPECT_EQ(TemporaryPathFor("out.h5", 7, 0), std::filesystem::path(".out.h5.rockfit-tmp-7-0"));
}

TEST(AtomicFiles, ASetIsReplacedWholeOrNotAtAll) {
  const testing::ScratchDir dir("atomic");
  WriteFilesAtomically({{dir / "t_A.csv", "a1"}, {dir / "t_B.csv", "b1"}});
  EXPECT_EQ(Read(dir / "t_A.csv"), "a1");
  EXPECT_EQ(Read(dir / "t_B.csv"), "b1");
  // The second file cannot be written: the first, although written in full, is not renamed over its target.
  EXPECT_THROW(WriteFilesAtomically({{dir / "t_A.csv", "a2"}, {dir / "missing/t_B.csv", "b2"}}), OutputError);
  EXPECT_EQ(Read(dir / "t_A.csv"), "a1");
  EXPECT_EQ(EntriesIn(dir.path()), 2u);
  WriteFilesAtomically({{dir / "t_A.csv", "a3"}, {dir / "t_B.csv", "b3"}});
  EXPECT_EQ(Read(dir / "t_A.csv"), "a3");
  EXPECT_EQ(Read(dir / "t_B.csv"), "b3");
  EXPECT_EQ(EntriesIn(dir.path()), 2u);
}

}  // namespace
}  // namespace rockfit::io
