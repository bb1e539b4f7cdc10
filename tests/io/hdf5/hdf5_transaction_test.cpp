#include "rockfit/io/hdf5_transaction.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io::hdf5 {
namespace {

using testing::ScratchDir;

std::string Bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A file as `rockfit summary` and later `rockfit fit` would leave it.
void WriteInitial(const std::filesystem::path& path) {
  Transaction tx(path);
  tx.Root().SetInt("rockfit_schema_version", 1);
  tx.Root().CreateGroup("summary").WriteDoubles("opmf", {0.1, 0.2}, "1");
  tx.Root().CreateGroup("trials/T1").WriteDoubles("time_s", {0, 1}, "s");
  tx.Root().CreateGroup("trials/T2").WriteDoubles("time_s", {0, 2}, "s");
  const Group fit = tx.Root().CreateGroup("fits/T1");
  fit.SetDouble("epsilon_rad_s", 0.012);
  fit.WriteDoubles("lambda", {0.7}, "1");
  tx.Commit();
}

std::vector<std::filesystem::path> Temporaries(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().filename().string().find(".rockfit-tmp-") != std::string::npos) out.push_back(entry.path());
  }
  return out;
}

TEST(Hdf5Transaction, CommitCreatesTheFileAndLeavesNoTemporary) {
  const ScratchDir dir("hdf5_tx");
  WriteInitial(dir / "out.h5");
  EXPECT_TRUE(File::IsHdf5(dir / "out.h5"));
  EXPECT_TRUE(Temporaries(dir.path()).empty());
}

TEST(Hdf5Transaction, RewritingKeepsEverythingThatIsNotReplaced) {
  const ScratchDir dir("hdf5_tx");
  const auto path = dir / "out.h5";
  WriteInitial(path);
  {
    Transaction tx(path, {"/summary", "/trials/T1"});
    EXPECT_FALSE(tx.Root().Exists("summary"));
    EXPECT_FALSE(tx.Root().Exists("trials/T1"));
    tx.Root().CreateGroup("summary").WriteDoubles("opmf", {0.3}, "1");
    tx.Root().CreateGroup("trials/T1").WriteDoubles("time_s", {0, 5}, "s");
    tx.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.Root();
  EXPECT_EQ(root.GetInt("rockfit_schema_version"), 1);                        // root attributes carried over
  EXPECT_EQ(root.OpenGroup("summary").ReadDoubles("opmf"), (std::vector<double>{0.3}));
  EXPECT_EQ(root.OpenGroup("trials/T1").ReadDoubles("time_s"), (std::vector<double>{0, 5}));
  EXPECT_EQ(root.OpenGroup("trials/T2").ReadDoubles("time_s"), (std::vector<double>{0, 2}));  // untouched sibling
  EXPECT_EQ(root.OpenGroup("fits/T1").GetDouble("epsilon_rad_s"), 0.012);      // another writer's group
  EXPECT_EQ(root.OpenGroup("fits/T1").ReadDoubles("lambda"), (std::vector<double>{0.7}));
  EXPECT_EQ(root.OpenGroup("summary").GetString("units", "opmf"), "1");
}

TEST(Hdf5Transaction, WithoutCommitTheTargetIsUntouchedAndTheTemporaryRemoved) {
  const ScratchDir dir("hdf5_tx");
  const auto path = dir / "out.h5";
  WriteInitial(path);
  const std::string before = Bytes(path);
  try {
    Transaction tx(path, {"/summary"});
    tx.Root().CreateGroup("summary");
    throw std::runtime_error("a computation failed half way");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(Bytes(path), before);
  EXPECT_TRUE(Temporaries(dir.path()).empty());
}

TEST(Hdf5Transaction, RefusesToReplaceAFileThatIsNotHdf5) {
  const ScratchDir dir("hdf5_tx");
  const auto path = dir / "notes.h5";
  std::ofstream(path) << "my notes\n";
  try {
    Transaction tx(path);
    FAIL();
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("exists and is not an HDF5 file"), std::string::npos);
  }
  EXPECT_EQ(Bytes(path), "my notes\n");
}

TEST(Hdf5Transaction, UnwritableDirectoryIsAnOutputError) {
  EXPECT_THROW(Transaction("/nonexistent-dir/out.h5"), OutputError);
}

TEST(Hdf5Transaction, KillingTheWriterMidWriteLeavesThePreviousFileIntact) {
  const ScratchDir dir("hdf5_tx");
  const auto path = dir / "campaign.h5";
  WriteInitial(path);
  const std::string before = Bytes(path);

  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // The writer: replaces /trials/T1 with a large trial, dataset after dataset, and says when it has begun.
    ::close(ready[0]);
    try {
      Transaction tx(path, {"/trials/T1", "/summary"});
      const Group big = tx.Root().CreateGroup("trials/T1");
      const std::vector<double> block(20000, 1.0);
      for (int i = 0; i < 100000; ++i) {
        big.WriteDoubles("part_" + std::to_string(i), block, "1");
        tx.Root().OpenGroup("trials/T1");  // keep the library busy inside the file
        if (i == 3) {
          const char byte = 'w';
          if (::write(ready[1], &byte, 1) != 1) ::_exit(3);
        }
      }
      tx.Commit();
    } catch (...) {
      ::_exit(2);
    }
    ::_exit(0);
  }
  ::close(ready[1]);
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1) << "the writer did not start";
  ::close(ready[0]);
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the writer finished before it was killed";

  // The previous file: byte for byte what it was, and readable with its content.
  EXPECT_EQ(Bytes(path), before);
  const File file = File::Open(path);
  EXPECT_EQ(file.Root().OpenGroup("trials/T1").ReadDoubles("time_s"), (std::vector<double>{0, 1}));
  EXPECT_EQ(file.Root().OpenGroup("fits/T1").GetDouble("epsilon_rad_s"), 0.012);
  // Nothing half-written is on disk: the new version lives in memory until Commit() (File::CreateInMemory).
  EXPECT_TRUE(Temporaries(dir.path()).empty());
  {
    Transaction next(path, {"/summary"});
    next.Root().CreateGroup("summary");
    next.Commit();
  }
  EXPECT_TRUE(Temporaries(dir.path()).empty());
}

TEST(Hdf5Transaction, TemporaryLivesBesideTheTarget) {
  const ScratchDir dir("hdf5_tx");
  const Transaction tx(dir / "out.h5");
  EXPECT_EQ(tx.temporary_path().parent_path(), dir.path());
  EXPECT_EQ(tx.temporary_path().filename().string().rfind(std::string(".out.h5") + kTemporaryMarker, 0), 0u)
      << tx.temporary_path();
}

}  // namespace
}  // namespace rockfit::io::hdf5
